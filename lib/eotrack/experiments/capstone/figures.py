"""Figures of the capstone: the pipeline, the night, a frame, the error budget, the sweep."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from matplotlib.patches import FancyArrowPatch, FancyBboxPatch

from eotrack.geometry import project_directions
from eotrack.imaging import BackgroundConfig, SkyConfig, extract_stars

from .pipeline import (
    PREDICTORS,
    NightResult,
    _stars_for_burst,
    render_frame,
    separate_targets,
)
from .scenario import NightPlan, camera_matrix

__all__ = ["frame_example", "plot_budget", "plot_frame", "plot_night", "plot_pipeline",
           "plot_prediction", "plot_sweep", "plot_triangulation", "sweep_explorer"]

_FRACTIONS = [
    ("extraction · target completeness (sunlit frames)", "extraction\ncompleteness"),
    ("separation · target kept as candidate", "kept as\ncandidate"),
    ("initiation · recall (bursts with ≥ 3 sunlit frames)", "initiation\nrecall"),
    ("association · correct pairs", "association\ncorrect"),
]


def _ax(ax, figsize=(7, 4)):
    if ax is None:
        _, ax = plt.subplots(figsize=figsize)
    return ax


def plot_pipeline(*, ax: plt.Axes | None = None) -> plt.Axes:
    """Block diagram of the chain: two stations' per-frame stages merging into the 3-D ones."""
    ax = _ax(ax, (11, 4.2))
    ax.set_xlim(0, 11.2)
    ax.set_ylim(0, 4.2)
    ax.axis("off")
    per_station = [("frames\nPSF · noise · sky", "imaging"), ("extraction\nsky extractor", "nb 05"),
                   ("star / target\ncatalogue + drift", "Gaia"), ("initiation\nmodified Hough",
                                                                  "nb 04")]
    joint = [("association\nepipolar", "nb 02"), ("triangulation\nranges", "nb 02"),
             ("prediction\nthrough eclipse", "nb 01")]
    w, h = 1.45, 0.9

    def box(x, y, text, note, colour):
        ax.add_patch(FancyBboxPatch((x, y), w, h, boxstyle="round,pad=0.05", fc=colour,
                                    ec="0.3", lw=1))
        ax.text(x + w / 2, y + h / 2 + 0.08, text, ha="center", va="center", fontsize=8)
        ax.text(x + w / 2, y + 0.1, note, ha="center", va="bottom", fontsize=7, color="0.35")

    def arrow(x0, y0, x1, y1):
        ax.add_patch(FancyArrowPatch((x0, y0), (x1, y1), arrowstyle="-|>", mutation_scale=10,
                                     color="0.3", lw=1))

    ax.add_patch(FancyBboxPatch((0.05, 1.55), 0.9, 1.1, boxstyle="round,pad=0.05", fc="#fde7c4",
                                ec="0.3"))
    ax.text(0.5, 2.1, "sky\nSGP4 · Gaia\nshadow", ha="center", va="center", fontsize=8)
    for row, (y, name) in enumerate(((3.0, "station A"), (0.3, "station B"))):
        ax.text(1.2, y + h + 0.12, name, fontsize=8, style="italic")
        arrow(0.95, 2.1, 1.2, y + h / 2)
        for i, (t, n) in enumerate(per_station):
            x = 1.2 + i * 1.75
            box(x, y, t, n, "#dbe9f6")
            if i:
                arrow(x - 0.3, y + h / 2, x, y + h / 2)
        arrow(1.2 + 3 * 1.75 + w, y + h / 2, 8.3, 1.65 + h / 2 + (0.2 if row == 0 else -0.2))
    box(8.3, 1.65, joint[0][0], joint[0][1], "#d9f0d3")
    box(9.55, 2.85, joint[1][0], joint[1][1], "#d9f0d3")
    box(9.55, 0.45, joint[2][0], joint[2][1], "#d9f0d3")
    arrow(8.3 + w / 2, 1.65 + h, 9.55, 2.85 + h / 2)
    arrow(8.3 + w / 2, 1.65, 9.55, 0.45 + h / 2)
    ax.set_title("The chain: per-station stages (blue) feed the two-station stages (green)")
    return ax


def plot_night(plan: NightPlan, *, axes=None):
    """Elevation of each object from each station over the night; dark time and umbra shaded."""
    cfg = plan.config
    if axes is None:
        _, axes = plt.subplots(1, len(cfg.stations), figsize=(11, 3.6), sharey=True)
    h = plan.visit_s / 3600 + (plan.t0.datetime.hour + plan.t0.datetime.minute / 60)
    hg = plan.grid_s / 3600 + (plan.t0.datetime.hour + plan.t0.datetime.minute / 60)
    for s, ax in enumerate(np.atleast_1d(axes)):
        for o, name in enumerate(plan.names):
            line, = ax.plot(h, plan.elevation_deg[s, o], label=name)
            umb = plan.grid_shadow[o] == 2
            if umb.any():
                ax.axvspan(hg[umb].min(), hg[umb].max(), color=line.get_color(), alpha=0.25)
        dk = plan.dark[s]
        ax.fill_between(h, 0, 90, where=~dk, color="0.85", step="mid", zorder=0)
        ax.axhline(cfg.min_elevation_deg, color="0.4", ls=":", lw=1)
        ax.set_xlabel("UTC (h) on " + plan.t0.datetime.strftime("%Y-%m-%d"))
        ax.set_title(cfg.stations[s].name)
        ax.set_ylim(0, 90)
    np.atleast_1d(axes)[0].set_ylabel("elevation (°)")
    np.atleast_1d(axes)[0].legend(fontsize=7, title="NORAD id (umbra shaded)")
    return axes


def frame_example(plan: NightPlan, index: int, seed: int = 0) -> dict:
    """Render and analyse the first frames of burst ``index`` (for figures).

    Returns a dict with the first frame ``image``, its detections ``xy``, masks ``catalogue`` and
    ``candidate``, the catalogue stars' predicted ``star_xy`` and the true ``target_xy``.
    """
    cfg = plan.config
    b = plan.bursts[index]
    rng = np.random.default_rng(seed)
    K = camera_matrix(cfg)
    dirs, mag, cat = _stars_for_burst(rng, plan, b)
    sky = SkyConfig(psf_sigma=cfg.psf_sigma_px, thresh=cfg.detect_sigma,
                    background=BackgroundConfig(mesh=32, filter_size=1))
    imgs, det, sxy = [], [], []
    for k in range(2):
        imgs.append(render_frame(rng, plan, b, k, dirs, mag))
        det.append(np.asarray(extract_stars(imgs[-1], config=sky).xy).reshape(-1, 2))
        sxy.append(project_directions(dirs[cat], K, b.R[k]))
    c = np.array([[(cfg.size_px - 1) / 2] * 2])
    from eotrack.geometry import pixel_rays

    ray = pixel_rays(c, K, b.R[0])
    drift = project_directions(ray, K, b.R[1]) - c
    is_cat, is_cand = separate_targets(det, sxy, drift, cfg.size_px)
    return {"image": imgs[0], "xy": det[0], "catalogue": is_cat[0], "candidate": is_cand[0],
            "star_xy": sxy[0], "target_xy": b.target_xy[0], "drift": drift[0], "burst": b}


def plot_frame(example: dict, *, ax: plt.Axes | None = None) -> plt.Axes:
    """A frame with its detections: catalogue stars, stars found by their drift, candidates."""
    ax = _ax(ax, (6, 6))
    img = example["image"]
    lo, hi = np.percentile(img, [5, 99.5])
    ax.imshow(img, cmap="gray", vmin=lo, vmax=hi, origin="upper")
    xy, cat, cand = example["xy"], example["catalogue"], example["candidate"]
    mov = ~cat & ~cand
    ax.scatter(*xy[cat].T, s=60, facecolors="none", edgecolors="tab:blue",
               label="catalogue star (Gaia)")
    ax.scatter(*xy[mov].T, s=30, facecolors="none", edgecolors="tab:orange",
               label="star by sidereal drift / untestable")
    ax.scatter(*xy[cand].T, s=120, marker="s", facecolors="none", edgecolors="red", lw=1.5,
               label="target candidate")
    t = example["target_xy"]
    ax.plot(*t, "+", color="lime", ms=16, label="true target (SGP4)")
    d = example["drift"]
    ax.annotate("", xy=(30 + d[0], 30 + d[1]), xytext=(30, 30),
                arrowprops={"arrowstyle": "-|>", "color": "yellow"})
    ax.text(30, 45, "star drift / frame", color="yellow", fontsize=7)
    ax.legend(fontsize=7, loc="lower right")
    ax.set_xlabel("x (px)")
    ax.set_ylabel("y (px)")
    return ax


def plot_budget(result: NightResult, *, axes=None):
    """The error budget: stage fractions (left), errors in km and arcsec (right)."""
    if axes is None:
        _, axes = plt.subplots(1, 2, figsize=(11, 3.6), gridspec_kw={"width_ratios": [1.2, 1]})
    b = result.budget
    val = dict(zip(b["stage"] + " · " + b["metric"], b["value"]))
    a0, a1 = axes
    names = [lab for _, lab in _FRACTIONS]
    vals = [val.get(k, np.nan) for k, _ in _FRACTIONS]
    a0.bar(names, vals, color=["#4c78a8", "#72b7b2", "#54a24b", "#eeca3b"])
    for i, v in enumerate(vals):
        a0.text(i, (v if np.isfinite(v) else 0) + 0.02, f"{v:.3f}", ha="center", fontsize=8)
    a0.set_ylim(0, 1.12)
    a0.set_ylabel("fraction")
    a0.set_title("detection → initiation → association")
    tri = result.pairs.dropna(subset=["range_err_km"]) if len(result.pairs) else result.pairs
    a1.hist(tri["range_err_km"] if len(tri) else [], bins=20, color="#4c78a8")
    a1.set_xlabel("triangulated range − SGP4 range (km)")
    a1.set_ylabel("pairs")
    pr = [val.get(f"prediction · {m}: RMS error through the eclipse", np.nan) for m in PREDICTORS]
    a1.set_title("triangulation; prediction RMS through the eclipse: " +
                 ", ".join(f"{m} {v:.1f}″" for m, v in zip(PREDICTORS, pr)), fontsize=8)
    return axes


def plot_triangulation(result: NightResult, *, ax: plt.Axes | None = None) -> plt.Axes:
    """Range error (km) of every associated pair over the night, by object."""
    ax = _ax(ax)
    p = result.pairs.dropna(subset=["range_err_km"]) if len(result.pairs) else result.pairs
    for o, name in enumerate(result.plan.names):
        sel = p[p["obj_a"] == o] if len(p) else p
        if len(sel):
            ax.plot(sel["t_s"] / 3600, sel["range_err_km"], "o", ms=4, label=name)
    ax.axhline(0, color="0.4", lw=1)
    ax.set_xlabel("hours since the night's start")
    ax.set_ylabel("range error (km)")
    ax.legend(fontsize=7, title="NORAD id")
    return ax


def plot_prediction(prediction: pd.DataFrame, *, ax: plt.Axes | None = None) -> plt.Axes:
    """RMS prediction error through the eclipse per station/object and predictor (log scale)."""
    ax = _ax(ax, (8, 3.6))
    if len(prediction) == 0:
        ax.text(0.5, 0.5, "no prediction (stage failed)", ha="center", transform=ax.transAxes)
        return ax
    tab = prediction.pivot_table(index=["station", "object"], columns="method",
                                 values="rms_arcsec")[list(PREDICTORS)]
    x = np.arange(len(tab))
    for i, m in enumerate(PREDICTORS):
        ax.bar(x + (i - 1) * 0.27, tab[m], 0.27, label=m)
    ax.set_xticks(x, [f"{s}\n{o}" for s, o in tab.index], fontsize=7)
    ax.set_yscale("log")
    ax.set_ylabel("RMS error in umbra (″)")
    ax.legend(fontsize=7)
    return ax


def _sweep_title(sweep: pd.DataFrame, level: float) -> str:
    snr = float(sweep.loc["target peak S/N", level]) if level in sweep.columns else np.nan
    return (f"sky {level:.0f} e⁻/px: target peak S/N {snr:.1f} "
            f"(precomputed full nights at {len(sweep.columns)} sky levels)")


def _draw_sweep(sweep: pd.DataFrame, level: float, axes) -> tuple[list, Any]:
    """Draw the sweep on ``axes``; return the level markers and the title (to update)."""
    a0, a1 = axes
    x = np.asarray(sweep.columns, float)
    for key, lab in _FRACTIONS:
        a0.plot(x, sweep.loc[key], "o-", label=lab.replace("\n", " "))
    a0.set_ylim(-0.03, 1.05)
    a0.set_ylabel("fraction")
    a1.plot(x, sweep.loc["triangulation · RMS position error"], "s-", color="k",
            label="triangulation RMS (km)")
    for m in PREDICTORS:
        a1.plot(x, sweep.loc[f"prediction · {m}: RMS error through the eclipse"], "o--",
                label=f"{m} prediction (″)")
    a1.set_yscale("log")
    marks = []
    for a in axes:
        a.set_xscale("log")
        a.set_xlabel("sky background (e⁻/px)")
        marks.append(a.axvline(level, color="k", ls="--", lw=1))
        a.legend(fontsize=7)
        a.minorticks_off()
    title = a0.figure.suptitle(_sweep_title(sweep, level), fontsize=9)
    return marks, title


def plot_sweep(sweep: pd.DataFrame, level: float, *, axes=None):
    """The chain against the sky level: fractions (left) and errors (right); ``level`` marked."""
    if axes is None:
        _, axes = plt.subplots(1, 2, figsize=(10, 3.6), dpi=90, layout="constrained")
    _draw_sweep(sweep, level, axes)
    return axes


def sweep_explorer(sweep: pd.DataFrame) -> Callable[[float], Figure]:
    """The Explore panel's figure for a sweep: ``draw(sky)`` returns the same ``Figure``.

    The figure is built and laid out (constrained layout) on the first call; later calls only
    move the level markers and rewrite the title, so a widget redraw costs one render.

    Parameters
    ----------
    sweep : pandas.DataFrame
        A :func:`~eotrack.experiments.capstone.noise_sweep` result.

    Returns
    -------
    callable
        ``draw(sky) -> Figure``; ``sky`` (e⁻/px) must be one of the sweep's sky levels.

    Raises
    ------
    ValueError
        If ``sweep`` has no sky levels, or ``draw`` gets a level the sweep does not hold.
    """
    if not isinstance(sweep, pd.DataFrame) or sweep.shape[1] == 0:
        raise ValueError("sweep must be a noise_sweep DataFrame with at least one sky level")
    levels = [float(v) for v in sweep.columns]
    state: dict[str, Any] = {}

    def draw(sky: float) -> Figure:
        level = float(sky)
        if level not in levels:
            raise ValueError(f"sky must be one of the sweep's sky levels {levels}, got {sky}")
        if not state:
            fig = Figure(figsize=(10, 3.6), dpi=90, layout="constrained")
            axes = fig.subplots(1, 2)
            state["marks"], state["title"] = _draw_sweep(sweep, level, axes)
            fig.draw_without_rendering()
            fig.set_layout_engine("none")  # keep the constrained positions: no re-layout
            state["fig"] = fig
        for m in state["marks"]:
            m.set_xdata([level, level])
        state["title"].set_text(_sweep_title(sweep, level))
        return state["fig"]

    return draw
