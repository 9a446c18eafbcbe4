"""Figures of the capstone: the pipeline, the night, a frame, the error budget, the sweep."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from matplotlib.patches import FancyArrowPatch, FancyBboxPatch

from eotrack.plotting import (
    ON_IMAGE,
    label_axes,
    legend_outside,
    log_axis,
    method_style,
    series_styles,
)

from .pipeline import (
    PREDICTORS,
    NightResult,
    _stars_for_burst,
    paired_orbit_curve,
    render_frame,
)
from .scenario import NightPlan, camera_matrix

__all__ = ["frame_example", "plot_budget", "plot_frame", "plot_night", "plot_pipeline",
           "plot_prediction", "plot_sweep", "plot_triangulation", "sweep_explorer"]

_FRACTIONS = [
    ("extraction · target completeness (sunlit frames)", "extraction\ncompleteness"),
    ("separation · target kept as candidate", "kept as\ncandidate"),
    ("initiation · recall (object-bursts with ≥ 3 sunlit frames)", "initiation\nrecall"),
    ("association · correct pairs, cluster field", "association\ncorrect (cluster)"),
]
#: The predictors drawn: notebook 01's on the catalogue-correlated tracklets, and the orbit.
_PRED = [(m, f"{m} (catalogue)") for m in PREDICTORS] + [
    ("orbit", "orbit (catalogue, both stations)")]
ORBIT_LABEL = "orbit fit (Gauss IOD + Cauchy LSQ)"


def _pred_name(m: str) -> str:
    return ORBIT_LABEL if m == "orbit" else method_style(m).name


def _ax(ax, figsize=(6.4, 3.9)):
    if ax is None:
        _, ax = plt.subplots(figsize=figsize)
    return ax


def plot_pipeline(*, ax: plt.Axes | None = None) -> plt.Axes:
    """Block diagram of the chain: two stations' per-frame stages (rendering, extraction, plate
    solution against the catalogue, star/target separation, initiation) merging into the
    two-station ones (association, triangulation, orbit fit, prediction)."""
    ax = _ax(ax, (7.4, 4.6))
    ax.set_xlim(0, 11.0)
    ax.set_ylim(0, 6.6)
    ax.set_axis_off()
    per_station = [("frames", "PSF, noise"), ("extraction", "nb 05"),
                   ("astrometry", "plate vs Gaia"), ("star/target", "motion"),
                   ("initiation", "Hough, nb 04")]
    joint = [("association", "epipolar, nb 02"), ("triangulation", "nb 02"),
             ("orbit fit", "J2, nb 01"), ("prediction", "eclipse, nb 01")]
    w, h, dx = 1.8, 1.05, 1.9

    def box(x, y, text, note, colour):
        ax.add_patch(FancyBboxPatch((x, y), w, h, boxstyle="round,pad=0.04", fc=colour,
                                    ec="0.3", lw=1))
        ax.text(x + w / 2, y + 0.68, text, ha="center", va="center", fontsize=8.5,
                weight="bold")
        ax.text(x + w / 2, y + 0.28, note, ha="center", va="center", fontsize=8,
                color="0.25")

    def arrow(x0, y0, x1, y1):
        ax.add_patch(FancyArrowPatch((x0, y0), (x1, y1), arrowstyle="-|>", mutation_scale=10,
                                     color="0.3", lw=1.2, shrinkA=0, shrinkB=0))

    ax.add_patch(FancyBboxPatch((0.05, 2.45), 1.0, 1.7, boxstyle="round,pad=0.04",
                                fc="#fde7c4", ec="0.3"))
    ax.text(0.55, 3.3, "sky\nSGP4\nGaia\nshadow", ha="center", va="center", fontsize=8)
    xs = [1.45 + i * dx for i in range(len(per_station))]
    for y, name in ((5.1, "station A"), (0.4, "station B")):
        ax.text(xs[0], y + h + 0.12 if y > 3 else y - 0.38, name, fontsize=9, style="italic")
        arrow(1.05, 3.3 + (0.5 if y > 3 else -0.5), xs[0], y + h / 2)
        for i, (t, n) in enumerate(per_station):
            box(xs[i], y, t, n, "#dbe9f6")
            if i:
                arrow(xs[i - 1] + w, y + h / 2, xs[i], y + h / 2)
    yj = 2.75
    xj = [xs[-1] - i * dx for i in range(len(joint))]
    for (t, n), x in zip(joint, xj, strict=True):
        box(x, yj, t, n, "#d9f0d3")
    arrow(xs[-1] + w / 2, 5.1, xs[-1] + w / 2, yj + h)     # A → association
    arrow(xs[-1] + w / 2, 0.4 + h, xs[-1] + w / 2, yj)     # B → association
    for i in range(1, len(joint)):                         # association → … → prediction
        arrow(xj[i - 1], yj + h / 2, xj[i] + w, yj + h / 2)
    ax.set_title("The chain: per-station stages (blue) feed the two-station stages (green)")
    return ax


def plot_night(plan: NightPlan, *, axes=None):
    """Elevation of each object from each station over the night; dark time and umbra shaded."""
    cfg = plan.config
    if axes is None:
        fig, axes = plt.subplots(1, len(cfg.stations), figsize=(7.4, 3.6), sharey=True,
                                 layout="constrained")
    axes_ = np.atleast_1d(axes)
    h = plan.visit_s / 3600 + (plan.t0.datetime.hour + plan.t0.datetime.minute / 60)
    hg = plan.grid_s / 3600 + (plan.t0.datetime.hour + plan.t0.datetime.minute / 60)
    styles = series_styles(len(plan.names))
    for s, ax in enumerate(axes_):
        for o, name in enumerate(plan.names):
            st = styles[o]
            ln, = ax.plot(h, plan.elevation_deg[s, o], label=f"{name}",
                          **st.line(marker="none"))
            if ln.get_linestyle() not in ("-", "solid"):
                ln.set_zorder(2.5)  # dashed over solid: objects on one path all stay visible
            umb = plan.grid_shadow[o] == 2
            if umb.any():
                ax.axvspan(hg[umb].min(), hg[umb].max(), color=st.color, alpha=0.2, lw=0)
        dk = plan.dark[s]
        ax.fill_between(h, 0, 90, where=~dk, color="0.88", step="mid", zorder=0,
                        label="daylight / twilight" if s == 0 else None)
        ax.axhline(cfg.min_elevation_deg, color="0.3", ls=":", lw=1,
                   label=f"minimum elevation {cfg.min_elevation_deg:g}°" if s == 0 else None)
        label_axes(ax, x="UTC on " + plan.t0.datetime.strftime("%Y-%m-%d"), xunit="h",
                   title=cfg.stations[s].name)
        ax.set_ylim(0, 90)
    label_axes(axes_[0], y="elevation", yunit="°")
    fig = axes_[0].figure
    fig.suptitle("Elevation of each object over the night (umbra passages shaded)")
    legend_outside(fig, where="below", ncol=3, title="NORAD id")
    return axes


def frame_example(plan: NightPlan, index: int, seed: int = 0) -> dict:
    """Render and analyse the first two frames of burst ``index`` (for figures), through the
    chain's own per-frame call (:func:`eotrack.pipeline.measure_frame`).

    Returns a dict with the first frame ``image``, its detections ``xy``, masks ``catalogue``
    (matched by the plate solution) and ``candidate``, the catalogue stars where the BELIEVED
    pointing puts them (``star_xy_believed``) and where the plate solution puts them
    (``star_xy``), the true object positions ``target_xy`` ``(n_objs, 2)``, the star drift per
    frame and the plate ``solution``.
    """
    from eotrack.astro.astrometry import catalog_in_field, wcs_from_camera
    from eotrack.pipeline import Frame, measure_frame, separate_targets, target_border_px

    from .pipeline import MATCH_PX, burst_catalogue, frame_id, pipeline_config, velocity_gate

    cfg = plan.config
    if not 0 <= int(index) < len(plan.bursts):
        raise ValueError(f"index must lie in [0, {len(plan.bursts)}), got {index}")
    b = plan.bursts[int(index)]
    rng = np.random.default_rng(seed)
    K = camera_matrix(cfg)
    n = cfg.size_px
    dirs, mag, cat_f = _stars_for_burst(rng, plan, b)
    catalog = burst_catalogue(plan, b, dirs, mag, cat_f)
    pcfg = pipeline_config(cfg, velocity_gate(cfg))
    from astropy import units as u

    imgs, meas = [], []
    for k in range(2):
        imgs.append(render_frame(rng, plan, b, k, dirs, mag))
        fr = Frame(image=imgs[-1], time=plan.t0 + float(b.times_s[k]) * u.s,
                   exposure_s=cfg.exposure_s, station=cfg.stations[b.station].name,
                   wcs_guess=wcs_from_camera(K, b.R_believed[k], (n, n)),
                   frame_id=frame_id(plan, b, k), sequence=f"v{b.visit}")
        meas.append(measure_frame(fr, catalog, config=pcfg))
    cand = separate_targets(meas, radius_px=MATCH_PX, border_px=target_border_px(meas[0].frame, pcfg))
    m0 = meas[0]
    guess = wcs_from_camera(K, b.R_believed[0], (n, n))
    cat = catalog_in_field(guess, (n, n), max_mag=cfg.astrometry_limit, margin_px=20.0,
                           catalog=catalog)
    sb = np.column_stack(guess.wcs_world2pix(cat.ra_deg, cat.dec_deg, 0))
    ss = m0.solution.radec_to_pixel(cat.ra_deg, cat.dec_deg)
    c = np.array([[(n - 1) / 2] * 2])
    ra_c, de_c = m0.solution.pixel_to_radec(c)
    drift = meas[1].solution.radec_to_pixel(ra_c, de_c)[0] - c[0]
    return {"image": imgs[0], "xy": m0.xy, "catalogue": m0.is_catalogue, "candidate": cand[0],
            "star_xy": ss, "star_xy_believed": sb, "target_xy": b.target_xy[:, 0],
            "drift": drift, "burst": b, "solution": m0.solution,
            "names": [plan.names[o] for o in b.objs], "station": cfg.stations[b.station].name}


def plot_frame(example: dict, *, ax: plt.Axes | None = None) -> plt.Axes:
    """A frame with its detections: catalogue stars, stars found by their drift, candidates."""
    ax = _ax(ax, (6.0, 6.9))
    img = example["image"]
    lo, hi = np.percentile(img, [5, 99.5])
    ax.imshow(img, cmap="gray", vmin=lo, vmax=hi, origin="upper")
    xy, cat, cand = example["xy"], example["catalogue"], example["candidate"]
    mov = ~cat & ~cand
    sol = example.get("solution")
    fitted = f"; {sol.n_matched} of them in the plate fit" if sol is not None else ""
    ax.scatter(*xy[cat].T, s=28, facecolors="none", edgecolors=ON_IMAGE["star"], lw=0.7,
               marker="o", label=f"at a catalogue star of the solved plate ({int(cat.sum())}{fitted})")
    ax.scatter(*xy[mov].T, s=10, color=ON_IMAGE["candidate"], lw=0, marker="o", alpha=0.6,
               label=f"star: fixed on the sky in a neighbouring frame ({int(mov.sum())})")
    ax.scatter(*xy[cand].T, s=160, marker="s", facecolors="none",
               edgecolors=ON_IMAGE["target"], lw=1.8, label=f"target candidate ({int(cand.sum())})")
    sb = example.get("star_xy_believed")
    if sb is not None and len(sb):
        ax.scatter(*sb.T, s=22, marker="x", color=ON_IMAGE["star"], lw=0.9, alpha=0.8,
                   label="catalogue star where the believed pointing puts it")
    t = np.atleast_2d(example["target_xy"])
    ax.plot(*t.T, "+", color=ON_IMAGE["truth"], ms=18, mew=1.6, ls="none",
            label=f"true objects (SGP4, {len(t)})")
    d = example["drift"]
    # the drift arrow (to scale) in the image corner with the fewest markers, named in the
    # legend: a text on a star field this dense would hide markers wherever it went
    h_img, w_img = img.shape[:2]
    marks = [np.asarray(c.get_offsets(), float) for c in ax.collections
             if len(c.get_offsets())] + [np.column_stack(ln.get_data()).astype(float)
                                          for ln in ax.get_lines()]
    marks = np.vstack(marks) if marks else np.empty((0, 2))
    span = max(abs(float(d[0])), abs(float(d[1])), 0.06 * w_img) + 0.03 * w_img
    corners = [(0.05 * w_img, 0.05 * h_img), (0.95 * w_img, 0.05 * h_img),
               (0.05 * w_img, 0.95 * h_img), (0.95 * w_img, 0.95 * h_img)]

    def start(c):  # the arrow's tail, so that the arrow points into the image
        return (c[0] + (span if (c[0] < w_img / 2) == (d[0] < 0) else 0) * np.sign(w_img / 2 - c[0]),
                c[1] + (span if (c[1] < h_img / 2) == (d[1] < 0) else 0) * np.sign(h_img / 2 - c[1]))

    def crowd(c):
        x, y = start(c)
        xs, ys = sorted((x, x + d[0])), sorted((y, y + d[1]))
        return int(np.sum((marks[:, 0] >= xs[0] - 6) & (marks[:, 0] <= xs[1] + 6)
                          & (marks[:, 1] >= ys[0] - 6) & (marks[:, 1] <= ys[1] + 6)))

    x0, y0 = start(min(corners, key=crowd))
    ax.annotate("", xy=(x0 + d[0], y0 + d[1]), xytext=(x0, y0),
                arrowprops={"arrowstyle": "-|>", "color": ON_IMAGE["target"], "lw": 1.5})
    ax.plot([], [], ls="none", marker=r"$\rightarrow$", ms=14, color=ON_IMAGE["target"],
            label="star drift per frame (arrow to scale)")
    ax.grid(False)
    ax.set_xlim(-0.5, img.shape[1] - 0.5)
    ax.set_ylim(img.shape[0] - 0.5, -0.5)
    b = example.get("burst")
    label_axes(ax, x="x", xunit="px", y="y", yunit="px",
               title="First frame of a burst and what the chain makes of its detections"
               + (f"\n({example.get('station', f'station {b.station + 1}')}, field of "
                  f"{example['names'][0] if 'names' in example else b.obj + 1}, visit "
                  f"{b.visit + 1}; plate solution RMS {example['solution'].rms_arcsec:.2f}″)"
                  if b is not None and "solution" in example else ""))
    # a dark legend box: the image's overlay colours are made to show on black
    legend_outside(ax, where="below", ncol=1, facecolor="0.12", labelcolor="white")
    return ax


def plot_budget(result: NightResult, *, axes=None):
    """The error budget: stage fractions (left), errors in km and arcsec (right)."""
    if axes is None:
        _, axes = plt.subplots(1, 2, figsize=(7.4, 3.7), layout="constrained",
                               gridspec_kw={"width_ratios": [1.25, 1]})
    b = result.budget
    val = dict(zip(b["stage"] + " · " + b["metric"], b["value"], strict=False))
    a0, a1 = axes
    names = [lab for _, lab in _FRACTIONS]
    vals = [val.get(k, np.nan) for k, _ in _FRACTIONS]
    st = series_styles(1)[0]  # one colour: the bars are named by their tick labels
    for i, v in enumerate(vals):
        a0.bar(i, v, 0.7, **st.bar())
        a0.text(i, (v if np.isfinite(v) else 0) + 0.02, f"{v:.3f}", ha="center", fontsize=9)
    a0.set_xticks(range(len(names)), names)
    a0.set_ylim(0, 1.15)
    a0.grid(axis="x", visible=False)
    label_axes(a0, x="stage", y="fraction of the stage's inputs",
               title="Detection → initiation → association")
    tri = result.pairs.dropna(subset=["range_err_km"]) if len(result.pairs) else result.pairs
    a1.hist(tri["range_err_km"] if len(tri) else [], bins=20,
            **series_styles(1)[0].bar(hatch=""))
    label_axes(a1, x="triangulated − SGP4 range", xunit="km", y="associated pairs",
               title="Triangulation: range error")
    orb, cur = paired_orbit_curve(result.prediction) if len(result.prediction) else ([], [])

    def rms(x):
        return float(np.sqrt(np.mean(np.square(x)))) if len(x) else np.nan

    a0.figure.suptitle("Error budget of the night\nprediction RMS through the eclipse "
                       f"({len(orb)} cases both predict):\norbit {rms(orb):.1f}″, best curve "
                       f"{rms(cur):.1f}″")
    return axes


def plot_triangulation(result: NightResult, *, ax: plt.Axes | None = None) -> plt.Axes:
    """Range error (km) of every associated pair over the night, by object."""
    ax = _ax(ax)
    p = result.pairs.dropna(subset=["range_err_km"]) if len(result.pairs) else result.pairs
    styles = series_styles(max(1, len(result.plan.names)))
    for o, name in enumerate(result.plan.names):
        sel = p[p["obj_a"] == o] if len(p) else p
        if len(sel):
            ax.plot(sel["t_s"] / 3600, sel["range_err_km"], ms=5, label=name,
                    **styles[o].line(ls="none"))
    ax.axhline(0, color="0.4", lw=1)
    label_axes(ax, x="time since the night's start", xunit="h", y="range error", yunit="km",
               title="Triangulated range − SGP4 range, every associated pair")
    legend_outside(ax, title="NORAD id")
    return ax


def plot_prediction(prediction: pd.DataFrame, *, ax: plt.Axes | None = None) -> plt.Axes:
    """RMS prediction error through the eclipse per station/object: notebook 01's predictors on
    the catalogue-correlated tracklets beside the orbit fit (horizontal bars, one labelled row
    per station and object; linear axis from zero, so bar lengths compare)."""
    ax = _ax(ax, (6.4, 5.6))  # the legend goes below it: the whole stays at the book's width
    title = "Prediction through the eclipse: RMS error per station and object"
    sel = prediction
    if len(prediction) and "series" in prediction.columns:
        keep = ((prediction["series"] == "catalogue") & prediction["method"].isin(PREDICTORS)) \
            | (prediction["method"] == "orbit")
        sel = prediction[keep]
    if len(sel) == 0:
        ax.text(0.5, 0.5, "no prediction (stage failed)", ha="center", transform=ax.transAxes)
        ax.set_axis_off()
        ax.set_title(title)
        return ax
    tab = sel.pivot_table(index=["station", "object"], columns="method", values="rms_arcsec")
    methods = [m for m, _ in _PRED if m in tab.columns]
    # horizontal bars: one row per station and object, its label on one line beside it
    # (ten vertical groups' two-line labels overlapped at the book's width)
    y = np.arange(len(tab))[::-1]
    ht = 0.8 / len(methods)
    for i, m in enumerate(methods):
        st = method_style("cauchy" if m == "orbit" else m)
        ax.barh(y - (i - (len(methods) - 1) / 2) * ht, tab[m].fillna(0.0), ht,
                label=_pred_name(m), **st.bar())
    ax.set_yticks(y, [f"{s.split()[-1]} · {o}" for s, o in tab.index], fontsize=9)
    ax.set_xlim(0, None)
    ax.set_ylim(-0.6, len(tab) - 0.4)
    ax.grid(axis="y", visible=False)
    codes = ", ".join(f"{s.split()[-1]} = {' '.join(s.split()[:-1])}"
                      for s in dict.fromkeys(st for st, _ in tab.index))
    label_axes(ax, y="station · object", x="RMS error in umbra", xunit="″",
               title=f"{title}\n(stations: {codes})")
    legend_outside(ax, where="below", ncol=2)
    return ax


def _sweep_title(sweep: pd.DataFrame, level: float) -> str:
    snr = float(sweep.loc["target peak S/N", level]) if level in sweep.columns else np.nan
    what = sweep.attrs.get("nights", "full nights")
    return (f"sky {level:.0f} e⁻/px: target peak S/N {snr:.1f} "
            f"(precomputed {what} at {len(sweep.columns)} sky levels)")


def _draw_sweep(sweep: pd.DataFrame, level: float, axes) -> tuple[list, Any]:
    """Draw the sweep on three axes; return the level markers and the title (to update)."""
    a0, a1, a2 = axes
    x = np.asarray(sweep.columns, float)
    for (key, lab), st in zip(_FRACTIONS, series_styles(len(_FRACTIONS)), strict=True):
        a0.plot(x, sweep.loc[key], label=lab.replace("\n", " "), **st.line())
    a0.set_ylim(-0.03, 1.05)
    label_axes(a0, y="fraction", title="Stages: fraction kept")
    a1.plot(x, sweep.loc["triangulation · RMS position error"], label="triangulation",
            **series_styles(7)[6].line())
    label_axes(a1, y="RMS position error", yunit="km", title="Triangulation")
    for m, key in _PRED:
        row = f"prediction · {key}: RMS error through the eclipse"
        if row in sweep.index:
            a2.plot(x, sweep.loc[row], label=_pred_name(m),
                    **method_style("cauchy" if m == "orbit" else m).line())
    label_axes(a2, y="RMS error in umbra", yunit="″", title="Prediction through the eclipse")
    marks = []
    for a in axes:
        a.set_xscale("log")
        a.xaxis.set_major_formatter(plt.FuncFormatter(lambda v, _p: f"{v:,.0f}"))
        a.set_xticks(x)
        a.minorticks_off()
        label_axes(a, x="sky background", xunit="e⁻/px")
        marks.append(a.axvline(level, color="k", ls="--", lw=1,
                               label="this sky level" if a is a0 else None))
    for a in (a1, a2):
        vals = np.concatenate([ln.get_ydata() for ln in a.get_lines()[:-1]]).astype(float)
        if np.isfinite(vals).any() and np.nanmin(vals) > 0:
            log_axis(a, "y")
    legend_outside(a0)
    legend_outside(a2)
    title = a0.figure.suptitle(_sweep_title(sweep, level))
    return marks, title


def _sweep_axes(fig: Figure):
    gs = fig.add_gridspec(2, 2, height_ratios=[1, 1])
    return [fig.add_subplot(gs[0, :]), fig.add_subplot(gs[1, 0]), fig.add_subplot(gs[1, 1])]


def plot_sweep(sweep: pd.DataFrame, level: float, *, axes=None):
    """The chain against the sky level: fractions (top), triangulation error in km and
    prediction error in ″ (bottom, each on its own labelled axis); ``level`` marked."""
    if axes is None:
        fig = plt.figure(figsize=(7.4, 6.0), layout="constrained")
        axes = _sweep_axes(fig)
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
            fig = Figure(figsize=(7.4, 6.0), layout="constrained")
            axes = _sweep_axes(fig)
            state["marks"], state["title"] = _draw_sweep(sweep, level, axes)
            fig.draw_without_rendering()
            fig.set_layout_engine("none")  # keep the constrained positions: no re-layout
            state["fig"] = fig
        for m in state["marks"]:
            m.set_xdata([level, level])
        state["title"].set_text(_sweep_title(sweep, level))
        return state["fig"]

    return draw
