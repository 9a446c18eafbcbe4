"""Lint cases of the capstone's figures (notebook 07; no REPORT): FIG owns this file.

The data are a short real night (two objects, 3.5 h; computed once and cached) for the plan,
the frame, the budget, the triangulation and a one-level sweep. The prediction figure needs an
umbra passage, which only the full night has (too slow for the lint): its case reads the
prediction table that notebook 07 stored from its last full run.
"""

from __future__ import annotations

import json
from typing import Any

import pandas as pd

from .cache import ROOT, cached

DEPENDS = ("experiments/capstone",)


def _short() -> dict[str, Any]:
    from eotrack.experiments import capstone as C

    cfg = C.with_changes(night_start_utc="2006-03-25T03:00:00", night_hours=3.5,
                         visit_interval_s=1800.0, norad_ids=(28626, 25954))
    plan = C.make_plan(cfg)
    night = C.run_night(cfg, strict=False)
    sweep = C.noise_sweep(cfg, (cfg.sky_e,), known={cfg.sky_e: night})
    return {"plan": plan, "night": night, "sweep": sweep}


def short() -> dict[str, Any]:
    return cached("capstone-short", DEPENDS, _short)


def stored_prediction() -> pd.DataFrame:
    """The prediction table of notebook 07's stored output (its last full-night run), long form
    ``station, object, method, rms_arcsec`` as ``NightResult.prediction``."""
    nb = json.loads((ROOT / "notebooks" / "07_capstone_geo_surveillance.ipynb").read_text())
    for cell in nb["cells"]:
        if "night.prediction.pivot_table" in "".join(cell["source"]) and cell.get("outputs"):
            text = "".join(cell["outputs"][0]["data"]["text/plain"]).splitlines()
            methods = text[0].split()[1:]
            at = text[1].index("object")  # fixed-width columns: station | object | values
            rows, station = [], ""
            for line in text[2:]:
                station = line[:at].strip() or station
                obj, *vals = line[at:].split()
                for m, v in zip(methods, vals, strict=True):
                    rows.append({"station": station, "object": obj, "method": m,
                                 "rms_arcsec": float(v)})
            return pd.DataFrame(rows)
    raise LookupError("notebook 07 stores no prediction table")


def _sweep_explorer():
    from eotrack.experiments import capstone as C

    sw = short()["sweep"]
    return C.sweep_explorer(sw)(float(sw.columns[0]))


CASES = {
    "plot_pipeline": lambda: _c().plot_pipeline(),
    "plot_night": lambda: _c().plot_night(short()["plan"]),
    "plot_frame": lambda: _c().plot_frame(_c().frame_example(short()["plan"], 0, seed=1)),
    "plot_budget": lambda: _c().plot_budget(short()["night"]),
    "plot_triangulation": lambda: _c().plot_triangulation(short()["night"]),
    "plot_prediction": lambda: _c().plot_prediction(stored_prediction()),
    "plot_sweep": lambda: _c().plot_sweep(short()["sweep"], float(short()["sweep"].columns[0])),
    "sweep_explorer": _sweep_explorer,
}


def _c():
    from eotrack.experiments import capstone as C

    return C
