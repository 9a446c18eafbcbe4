"""Explore panel of notebook 06: selection reading × noise unit × stopping tolerance.

The expensive part (scenes + RANSAC) depends only on the noise unit and is cached per unit;
a reading/tolerance change re-runs only the selection and the refit on the cached inliers
(cached too), so a change redraws well within 0.5 s.
"""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.ticker import NullLocator

from eotrack.plotting import FIG_WIDTH_IN
from eotrack.pose import ransac_pose_dlt, refine_pose
from eotrack.repro import load_claims
from eotrack.validation import check_choice, check_int, check_positive

from .scenario import READINGS, SLUG, Scenario, Settings, make_scene, pose_errors
from .trials import select_and_refit

__all__ = ["EXPLORE_RUNS", "NOISE_UNITS", "TOLERANCE_PCT", "explore_figure", "explore_runs",
           "explore_selection", "warm_explore_cache"]

#: Runs per setting inside the widget (the reproduction uses 300; said on the figure).
EXPLORE_RUNS = 24
#: Noise-unit choices (mm): as printed, and the pixel reading (10 µm pixel).
NOISE_UNITS = {"1 mm (variances in mm², as printed)": 1.0,
               "0.01 mm (variances in px², 10 µm pixel)": 0.01}

#: The tolerance slider's values (%): min, max, step, default.
TOLERANCE_PCT = (0.0, 5.0, 0.5, 1.0)


@lru_cache(maxsize=8)
def explore_runs(noise_unit_mm: float, n_runs: int = EXPLORE_RUNS, seed: int = 3) -> tuple:
    """Cached scenes and RANSAC results for one noise unit: a tuple of per-run dicts."""
    check_positive(noise_unit_mm, "noise_unit_mm")
    n_runs = check_int(n_runs, "n_runs", min_value=1)
    sc = replace(Scenario(), noise_unit_mm=float(noise_unit_mm))
    st = Settings()
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n_runs):
        scene = make_scene(rng, sc)
        res = ransac_pose_dlt(scene.points, scene.pixels, scene.K, rng, st.ransac_config(sc))
        if not res.success:
            continue
        inl = res.inliers
        X, u, sig = scene.points[inl], scene.pixels[inl], scene.sigma[inl]
        Rm, tm = refine_pose(X, u, scene.K, res.R, res.t, sigma_px=sig)
        out.append({"scene": scene, "X": X, "u": u, "sigma": sig, "R": res.R, "t": res.t,
                    "att_ransac": pose_errors(res.R, res.t, scene)[1],
                    "att_ml": pose_errors(Rm, tm, scene)[1], "seed": int(rng.integers(2**62))})
    return tuple(out)


@lru_cache(maxsize=256)
def explore_selection(noise_unit_mm: float, reading: str, tolerance: float = 0.01
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Attitude error (deg) and kept fraction per cached run for one reading (cached)."""
    check_choice(reading, "reading", list(READINGS))
    st = replace(Settings(), tolerance=float(tolerance))
    att, frac = [], []
    for r in explore_runs(noise_unit_mm):
        rng = np.random.default_rng([r["seed"], list(READINGS).index(reading)])
        s = select_and_refit(reading, r["X"], r["u"], r["scene"].K, r["R"], r["t"],
                             r["sigma"], rng, st)
        att.append(pose_errors(s["R"], s["t"], r["scene"])[1])
        frac.append(s["selected"].mean())
    return np.array(att), np.array(frac)


def warm_explore_cache() -> int:
    """Compute every (noise unit, reading, tolerance) the panel can ask for; return the count.

    After this, every control change only draws (no selection, no RANSAC).
    """
    lo, hi, step, _ = TOLERANCE_PCT
    n = 0
    for unit in NOISE_UNITS.values():
        for name in READINGS:
            explore_selection(unit, name, Settings().tolerance)
            n += 1
        for pct in np.arange(lo, hi + step / 2, step):
            explore_selection(unit, "tolerance", float(pct) / 100)
            n += 1
    return n


def explore_figure(reading: str = "pooled", noise_unit_mm: float = 1.0,
                   tolerance_pct: float = 1.0, show_ml: bool = True):
    """The panel's figure: attitude error per method (paired runs) and the share kept."""
    tol = float(tolerance_pct) / 100 if READINGS[check_choice(reading, "reading",
                                                              list(READINGS))][0] == "tolerance" \
        else Settings().tolerance
    runs = explore_runs(noise_unit_mm)
    att, frac = explore_selection(noise_unit_mm, reading, tol)
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(FIG_WIDTH_IN, 6.6), height_ratios=[1.4, 1])
    if not runs:
        a1.text(0.5, 0.5, "RANSAC failed in every run", ha="center", transform=a1.transAxes)
        return fig
    cols = [np.array([r["att_ransac"] for r in runs]), att]
    labels = ["RANSAC only", f"+ CRLB ({reading})"]
    if show_ml:
        cols.append(np.array([r["att_ml"] for r in runs]))
        labels.append("ML (weighted)")
    x = np.arange(1, len(cols) + 1)
    a1.plot(x, np.column_stack(cols).T, color="0.5", lw=0.4, alpha=0.4)
    a1.boxplot(cols, positions=x, widths=0.45, showmeans=True, medianprops={"color": "k"},
               meanprops={"marker": "D", "markerfacecolor": "w", "markeredgecolor": "k"})
    a1.set_xticks(x, labels)
    a1.set_yscale("log")
    a1.yaxis.set_minor_locator(NullLocator())   # fewer ticks: the inline PNG renders faster
    a1.set_ylabel("attitude error (deg)")
    a1.set_xlabel("method (a faint line joins one run's errors)")
    ratio = att.mean() / cols[0].mean()
    a1.set_title(f"{len(runs)} runs (reduced from 300 for speed); mean ratio vs RANSAC "
                 f"{ratio:.2f}")
    a2.hist(frac, bins=np.linspace(0, 1, 21), color="C1")
    paper = load_claims(SLUG)["ransac_crlb_pose.fig6"].paper["selected_fraction"]
    a2.axvline(paper, color="k", ls="--", lw=1)
    a2.set_xlabel(f"selected / inliers (dashed: paper ≈ {paper:.2f})")
    a2.set_ylabel("runs")
    a2.set_title(f"kept {frac.mean():.2f} of the inliers on average")
    # fixed margins: tight_layout would cost more than half of the redraw time
    fig.subplots_adjust(left=0.12, right=0.97, bottom=0.09, top=0.94, hspace=0.5)
    return fig
