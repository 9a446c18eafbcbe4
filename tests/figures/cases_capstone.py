"""Lint cases of the capstone's figures (notebook 07; no REPORT): FIG owns this file.

The data are a short real night (two objects, 3.5 h, about 10 s) for the plan, the frame and the
sweep, and the full default night (about 60 s, cached) for the budget, triangulation and
prediction figures, which need an umbra passage.
"""

from __future__ import annotations

from typing import Any

from .cache import cached

DEPENDS = ("experiments/capstone",)


def _short() -> dict[str, Any]:
    from eotrack.experiments import capstone as C

    cfg = C.with_changes(night_start_utc="2006-03-25T03:00:00", night_hours=3.5,
                         visit_interval_s=1800.0, norad_ids=(28626, 25954))
    plan = C.make_plan(cfg)
    night = C.run_night(cfg, strict=False)
    sweep = C.noise_sweep(cfg, (cfg.sky_e, 4 * cfg.sky_e), known={cfg.sky_e: night})
    return {"plan": plan, "sweep": sweep}


def _full() -> Any:
    from eotrack.experiments import capstone as C

    return C.run_night(C.CapstoneConfig())


def short() -> dict[str, Any]:
    return cached("capstone-short", DEPENDS, _short)


def full() -> Any:
    return cached("capstone-full", DEPENDS, _full)


def _sweep_explorer():
    from eotrack.experiments import capstone as C

    sw = short()["sweep"]
    return C.sweep_explorer(sw)(float(sw.columns[-1]))


CASES = {
    "plot_pipeline": lambda: _c().plot_pipeline(),
    "plot_night": lambda: _c().plot_night(short()["plan"]),
    "plot_frame": lambda: _c().plot_frame(_c().frame_example(short()["plan"], 0, seed=1)),
    "plot_budget": lambda: _c().plot_budget(full()),
    "plot_triangulation": lambda: _c().plot_triangulation(full()),
    "plot_prediction": lambda: _c().plot_prediction(full().prediction),
    "plot_sweep": lambda: _c().plot_sweep(short()["sweep"], float(short()["sweep"].columns[0])),
    "sweep_explorer": _sweep_explorer,
}


def _c():
    from eotrack.experiments import capstone as C

    return C
