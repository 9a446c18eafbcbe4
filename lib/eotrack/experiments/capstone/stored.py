"""The stored nights: the whole night, the same night at 6,400 e⁻/px and the QUICK-night sweep,
written by ``benchmarks/bench_capstone.py`` to ``papers_repro/capstone/stored_nights.json`` and
read by notebook 07 (which would otherwise spend minutes re-running them).

The file holds each night's tables (budget, pairs without their vectors, prediction, eclipse
status, failures, χ² prediction, σ reconciliation, per-ray split), the timings, the
configuration's ``repr`` and a hash of the code that produced it; :func:`read_stored` refuses a
file whose code hash or configuration differs (the notebook then runs the night live and says
so).
"""

from __future__ import annotations

import hashlib
import json
from io import StringIO
from pathlib import Path

import numpy as np
import pandas as pd

from .pipeline import NightResult, ray_error_split
from .scenario import CapstoneConfig, make_plan

__all__ = ["STORED_FILE", "code_hash", "night_from_summary", "night_summary", "read_stored",
           "write_stored"]

#: File name under ``papers_repro/capstone/``.
STORED_FILE = "stored_nights.json"
_PAIR_COLUMNS = ["visit", "frame", "t_s", "obj_a", "obj_b", "cat_a", "cat_b", "correct",
                 "cluster", "epipolar_px", "n_in_gate", "ray_err_a", "ray_err_b", "range_km",
                 "range_err_km", "pos_err_km", "gap_km", "b_perp_km", "inplane_a", "inplane_b"]


def code_hash() -> str:
    """SHA-256 (16 hex digits) of the code written for the capstone: its package (this file
    excepted), the frames pipeline, the astrometry and the orbit fit. Changes elsewhere in the
    library (the extractor, the initiator) do not invalidate the file: re-run the bench after
    them."""
    lib = Path(__file__).resolve().parents[2]
    h = hashlib.sha256()
    for rel in ("experiments/capstone", "pipeline", "astro/astrometry.py",
                "astro/orbit_fit.py"):
        p = lib / rel
        files = sorted(p.rglob("*.py")) if p.is_dir() else [p]
        for f in files:
            if f.name in ("stored.py", "figures.py") and f.parent.name == "capstone":
                continue  # reading/writing and plotting: they do not change a night
            h.update(f.relative_to(lib).as_posix().encode())
            h.update(f.read_bytes())
    return h.hexdigest()[:16]


def _df(d: pd.DataFrame) -> str:
    return d.to_json(orient="split", index=True, double_precision=15)


def _undf(s: str) -> pd.DataFrame:
    return pd.read_json(StringIO(s), orient="split")


def night_summary(night: NightResult, **extra) -> dict:
    """The JSON-able tables of a night (``extra``: timings and the like, stored as given)."""
    pairs = night.pairs[[c for c in _PAIR_COLUMNS if c in night.pairs.columns]] \
        if len(night.pairs) else pd.DataFrame(columns=_PAIR_COLUMNS)
    split = ray_error_split(night).reset_index()
    return {"config": repr(night.plan.config), "budget": _df(night.budget),
            "pairs": _df(pairs), "prediction": _df(night.prediction),
            "eclipse": _df(night.eclipse), "failures": _df(night.failures),
            "false_association": _df(night.false_association),
            "sigma": {k: (None if not np.isfinite(v) else float(v))
                      for k, v in night.sigma.items()},
            "ray_split": _df(split), "wall_s": night.wall_s, "error": night.error, **extra}


def night_from_summary(summary: dict, config: CapstoneConfig) -> NightResult:
    """A :class:`NightResult` from a stored summary (no bursts: the per-burst results are not
    stored); ``summary["ray_split"]`` holds :func:`ray_error_split`'s table."""
    if repr(config) != summary["config"]:
        raise ValueError("config differs from the stored night's configuration")
    sg = {k: (np.nan if v is None else v) for k, v in summary["sigma"].items()}
    return NightResult(make_plan(config), [], _undf(summary["pairs"]),
                       _undf(summary["prediction"]), _undf(summary["budget"]),
                       _undf(summary["eclipse"]), _undf(summary["failures"]),
                       _undf(summary["false_association"]), sg, summary["wall_s"],
                       summary.get("error", ""))


def write_stored(path: str | Path, content: dict) -> Path:
    """Write ``content`` (night summaries, sweep, timings) with the code hash to ``path``."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(json.dumps({"code_hash": code_hash(), **content}, indent=1,
                            allow_nan=False, default=_jsonable))
    return p


def _jsonable(v):
    if isinstance(v, (np.floating, np.integer)):
        return v.item()
    if isinstance(v, np.bool_):
        return bool(v)
    raise TypeError(f"not JSON-able: {type(v).__name__}")


def read_stored(path: str | Path) -> tuple[dict | None, str]:
    """The stored content and ``""``, or ``None`` and why it cannot be used (missing file,
    written by other code)."""
    p = Path(path)
    if not p.is_file():
        return None, f"{p} does not exist (run `python benchmarks/bench_capstone.py`)"
    content = json.loads(p.read_text())
    if content.get("code_hash") != code_hash():
        return None, (f"{p} was written by other code (hash {content.get('code_hash')}, now "
                      f"{code_hash()}): run `python benchmarks/bench_capstone.py`")
    return content, ""


def sweep_from(content: dict) -> pd.DataFrame:
    """The stored sweep (columns: sky levels as floats) with its ``attrs``."""
    sw = _undf(content["sweep"])
    sw.columns = [float(c) for c in sw.columns]
    sw.attrs["nights"] = content.get("sweep_nights", "QUICK nights")
    return sw
