"""Lint cases of the capstone's figures (notebook 07; no REPORT).

The data are the QUICK night (the cluster's field around XM-3's eclipse: every stage, the
prediction included; computed once and cached) for the plan, the frame, the budget, the
triangulation, the prediction and a two-level sweep (the QUICK night at 400 and 1,600 e⁻/px).
"""

from __future__ import annotations

from typing import Any

from .cache import cached

DEPENDS = ("experiments/capstone", "pipeline", "astro")


def _short() -> dict[str, Any]:
    from eotrack.experiments import capstone as C

    cfg = C.quick_config()
    plan = C.make_plan(cfg)
    night = C.run_night(cfg, strict=False)
    sweep = C.noise_sweep(cfg, (cfg.sky_e, 1600.0), known={cfg.sky_e: night})
    return {"plan": plan, "night": night, "sweep": sweep}


def short() -> dict[str, Any]:
    return cached("capstone-quick", DEPENDS, _short)


def _sweep_explorer():
    from eotrack.experiments import capstone as C

    sw = short()["sweep"]
    return C.sweep_explorer(sw)(float(sw.columns[0]))


def _frame():
    C = _c()
    plan = short()["plan"]
    i = next(i for i, b in enumerate(plan.bursts) if b.target_flux.min() > 0)
    return C.plot_frame(C.frame_example(plan, i, seed=1))


CASES = {
    "plot_pipeline": lambda: _c().plot_pipeline(),
    "plot_night": lambda: _c().plot_night(short()["plan"]),
    "plot_frame": _frame,
    "plot_budget": lambda: _c().plot_budget(short()["night"]),
    "plot_triangulation": lambda: _c().plot_triangulation(short()["night"]),
    "plot_prediction": lambda: _c().plot_prediction(short()["night"].prediction),
    "plot_sweep": lambda: _c().plot_sweep(short()["sweep"], float(short()["sweep"].columns[0])),
    "sweep_explorer": _sweep_explorer,
}


def _c():
    from eotrack.experiments import capstone as C

    return C
