"""Figures of the Xu & Wang reproduction: the paper's Figs. 2–3, the (ρ, θ) voting drawn from
code, the method comparison, the chance rates, the planted scenes and the Explore panel."""

from __future__ import annotations

import math
from functools import cache
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from eotrack.plotting import get_ax, legend_outside, log_axis
from eotrack.tracking.initiation.base import Track, validate_frames
from eotrack.tracking.initiation.modified_hough import ModifiedHoughInitiator, pair_parameters
from eotrack.tracking.initiation.pairs import gated_pairs
from eotrack.validation import check_positive

from .chance import chi2_chance_tracks
from .scenario import PlantedConfig, Scene, XuConfig, planted_scene, score_tracks, xu_config

__all__ = [
    "EXPLORE_CLUTTER",
    "EXPLORE_SCENES",
    "explore_results",
    "plot_angle_constraint",
    "plot_chance_check",
    "plot_comparison",
    "plot_comparison_grid",
    "plot_explore",
    "plot_fig3",
    "plot_fig3_pair",
    "plot_logic_false_tracks",
    "plot_planted_summary",
    "plot_rho_theta_votes",
    "plot_scene_tracks",
    "plot_xu_frames",
]


def plot_xu_frames(scene: Scene, ax: plt.Axes | None = None) -> plt.Axes:
    """All candidates of the four frames in one image (like the paper's Fig. 2)."""
    ax = get_ax(ax, figsize=(5.2, 5.2))
    ax.plot(*scene.stars_px.T, "o", mfc="none", mec="0.75", ms=9, label="catalogue stars")
    cols = plt.cm.viridis(np.linspace(0, 0.9, len(scene.frames)))
    for k, ((_, xy), c) in enumerate(zip(scene.frames, cols)):
        ax.plot(*xy.T, "+", color=c, ms=7, label=f"frame {k + 1} candidates")
    _image_axes(ax, scene)
    ax.set_title("Candidates after star removal (4 frames)")
    legend_outside(ax, where="below", ncol=3)
    return ax


def _image_axes(ax: plt.Axes, scene: Scene, width: float = 512) -> None:
    ax.set_xlim(0, width)
    ax.set_ylim(width, 0)
    ax.set_aspect("equal")
    ax.set_xlabel("x (px)")
    ax.set_ylabel("y (px)")


def plot_fig3(scene: Scene, tracks: list[Track], ax: plt.Axes | None = None) -> plt.Axes:
    """Fig. 3: the extracted tracks (lines through their detections) over the candidates."""
    ax = get_ax(ax, figsize=(5.2, 5.2))
    allxy = np.concatenate([xy for _, xy in scene.frames])
    ax.plot(*allxy.T, ".", color="0.7", ms=4, label="candidates")
    fr = validate_frames(scene.frames)
    for i, tr in enumerate(tracks):
        p = tr.positions(fr)
        ids = {int(scene.labels[f][d]) for f, d in tr.hits}
        name = (f"track {next(iter(ids)) + 1}" if len(ids) == 1 and min(ids) >= 0
                else f"false track {i + 1}")
        line = ax.plot(*p.T, "-o", ms=4, label=f"{name}: frames "
                       f"{','.join(str(f + 1) for f in tr.frame_indices)}; conf. {tr.confirmed_at + 1}")
        ax.annotate(name.replace("track ", "T"), p[-1], xytext=(4, 4),
                    textcoords="offset points", color=line[0].get_color(), fontsize=9)
    _image_axes(ax, scene)
    ax.set_title(f"Fig. 3 — extracted tracks ({len(tracks)})")
    legend_outside(ax, where="below", ncol=1)
    return ax


def plot_comparison(df: pd.DataFrame, sweep: str, metric: str,
                    ax: plt.Axes | None = None, *, legend: bool = True) -> plt.Axes:
    """One metric (``p_correct`` / ``false_per_frame``) versus the sweep variable, per method
    (``legend=False``: no legend, for a grid with one shared legend)."""
    ax = get_ax(ax)
    sub = df[df["sweep"] == sweep]
    x = "clutter" if sweep == "clutter" else "p_detect"
    groups = dict(tuple(sub.groupby("method", sort=False)))
    same = ("logic 3/4" in groups and "angle logic 3/4" in groups
            and np.allclose(groups["logic 3/4"][metric].to_numpy(),
                            groups["angle logic 3/4"][metric].to_numpy()))
    for name, g in groups.items():
        # the angle-constrained logic often coincides with logic 3/4: draw it dashed on top
        style = "--s" if name.startswith("angle") else "-o"
        label = {"modified Hough 3/4": "modified Hough 3/4 (paper)"}.get(name, name)
        if name == "logic 3/4" and same:
            label = "logic 3/4 (= angle logic here)"
        ax.plot(g[x], g[metric], style, ms=4, mfc="none" if name.startswith("angle") else None,
                label=label)
    ax.set_xlabel("false alarms per frame" if x == "clutter" else r"detection probability $P_\mathrm{D}$")
    ax.set_ylabel({"p_correct": "P(correct initiation)",
                   "false_per_frame": "false tracks per frame"}[metric])
    if metric == "false_per_frame":
        ax.set_yscale("symlog", linthresh=0.01)
    ax.set_title({"p_correct": "correct initiations",
                  "false_per_frame": "false tracks"}[metric]
                 + (" vs clutter" if x == "clutter" else r" vs $P_\mathrm{D}$"))
    ax.xaxis.set_major_locator(plt.MaxNLocator(4))
    if legend:
        legend_outside(ax, where="right")
    return ax


def plot_comparison_grid(df: pd.DataFrame) -> Figure:
    """The method comparison as a 2 × 2 grid (P(correct) and false tracks versus clutter and
    P_D) with one shared legend below."""
    fig, axes = plt.subplots(2, 2, figsize=(7.5, 7.0))
    for i, sweep in enumerate(("clutter", "p_detect")):
        for j, metric in enumerate(("p_correct", "false_per_frame")):
            plot_comparison(df, sweep, metric, ax=axes[j, i], legend=False)
    fig.tight_layout()
    legend_outside(fig, where="below", ncol=2)
    return fig


def plot_fig3_pair(scene: Scene, left: list[Track], right: list[Track], *,
                   titles: tuple[str, str] = ("left", "right"), suptitle: str = "") -> Figure:
    """Two Fig. 3 panels side by side (e.g. the paper's procedure and a variant)."""
    fig, axes = plt.subplots(1, 2, figsize=(7.5, 6.4))
    for ax, tracks, title in zip(axes, (left, right), titles):
        plot_fig3(scene, tracks, ax=ax)
        ax.set_title(f"{title} ({len(tracks)} tracks)")
    if suptitle:
        fig.suptitle(suptitle)
    fig.tight_layout()
    return fig


def plot_logic_false_tracks(df: pd.DataFrame, ax: plt.Axes | None = None) -> plt.Axes:
    """Measured (markers) and analytic (lines) false tracks per frame of the logic rules."""
    ax = get_ax(ax)
    for name, g in df.groupby("method", sort=False):
        line = ax.plot(g["clutter"], g["analytic"], "-", label=f"{name} analytic")
        ax.plot(g["clutter"], g["measured"], "o", color=line[0].get_color(),
                label=f"{name} measured")
    log_axis(ax, "both")
    ax.set_xlabel("false alarms per frame")
    ax.set_ylabel("false tracks per frame")
    ax.set_title("Logic rules in clutter only: measured and analytic")
    legend_outside(ax, where="below", ncol=2)
    return ax




# --------------------------------------------------------------------------- (ρ, θ) voting
def _object_pairs(scene: Scene, cfg: XuConfig):
    """Velocity-gated pairs (frame k − 1 or k − 2 → frame k) of every frame: arrays of the
    two positions, Δt and the object label of the pair (−1 unless both are one object)."""
    pa, pb, dts, lab = [], [], [], []
    for k in range(1, len(scene.frames)):
        tk, xk = scene.frames[k]
        for j in (k - 1, k - 2):
            if j < 0:
                continue
            tj, xj = scene.frames[j]
            ia, ib, _, _ = gated_pairs(xj, xk, tk - tj, *cfg.v_gate_px_s)
            la, lb = scene.labels[j][ia], scene.labels[k][ib]
            pa.append(xj[ia])
            pb.append(xk[ib])
            dts.append(np.full(len(ia), tk - tj))
            lab.append(np.where((la == lb) & (la >= 0), la, -1))
    return np.concatenate(pa), np.concatenate(pb), np.concatenate(dts), np.concatenate(lab)


def plot_rho_theta_votes(scene: Scene, cfg: XuConfig | None = None, *, target: int = 0,
                         axes=None):
    """Where the pairs vote in (ρ, θ): all pairs of the scene (left), then one object's pairs
    over the δρ × δθ cell grid with ρ measured from the image corner (middle, the paper's
    unstated choice) and from the image centre (right).

    A pair's θ error σ_θ ≈ √2 σ / (v Δt) moves its ρ by up to |r| σ_θ, with r the distance of
    the detections from the ρ origin: far from the origin one object's pairs straddle cells.
    """
    cfg = cfg or xu_config()
    if axes is None:
        fig = plt.figure(figsize=(7.5, 7.6))
        gs = fig.add_gridspec(2, 2)
        axes = [fig.add_subplot(gs[0, :]), fig.add_subplot(gs[1, 0]), fig.add_subplot(gs[1, 1])]
    else:
        fig = axes[0].figure
    pa, pb, dt, lab = _object_pairs(scene, cfg)
    rho, th, _, _ = pair_parameters(pa, pb, dt)
    ax = axes[0]
    clut = lab < 0
    ax.plot(np.degrees(th[clut]), rho[clut], ".", color="0.75", ms=2, label="other pairs")
    for i in np.unique(lab[lab >= 0]):
        s = lab == i
        ax.plot(np.degrees(th[s]), rho[s], "o", ms=5, mfc="none", label=f"object {i + 1}")
    ax.set_xlabel("θ (°)")
    ax.set_ylabel("ρ from the image corner (px)")
    ax.set_title(f"all velocity-gated pairs ({len(rho)})")
    legend_outside(ax, where="right")
    sel = lab == target
    w = float(cfg.width_px)
    for ax, origin, name in ((axes[1], (0.0, 0.0), "image corner"),
                             (axes[2], (w / 2, w / 2), "image centre")):
        r, t, _, _ = pair_parameters(pa[sel], pb[sel], dt[sel], origin)
        td = np.degrees(t)
        ax.plot(td, r, "o", color="tab:blue", ms=6)
        t0 = math.floor(td.min() / cfg.cell_theta_deg - 1) * cfg.cell_theta_deg
        t1 = math.ceil(td.max() / cfg.cell_theta_deg + 1) * cfg.cell_theta_deg
        r0 = math.floor(r.min() / cfg.cell_rho_px - 1) * cfg.cell_rho_px
        r1 = math.ceil(r.max() / cfg.cell_rho_px + 1) * cfg.cell_rho_px
        for x in np.arange(t0, t1 + 1e-9, cfg.cell_theta_deg):
            ax.axvline(x, color="0.8", lw=0.8)
        for y in np.arange(r0, r1 + 1e-9, cfg.cell_rho_px):
            ax.axhline(y, color="0.8", lw=0.8)
        it = np.floor(td / cfg.cell_theta_deg)
        ir = np.floor(r / cfg.cell_rho_px)
        differ = [lab_ for lab_, v_ in (("θ", it), ("ρ", ir)) if len(np.unique(v_)) > 1]
        verdict = ("one cell" if not differ else
                   f"cells differ in {' and '.join(differ)}"
                   + ("\n(not 6-neighbours)" if len(differ) > 1 else "\n(6-neighbours)"))
        ax.set_xlim(t0, t1)
        ax.set_ylim(r0, r1)
        ax.xaxis.set_major_locator(plt.MaxNLocator(5))
        ax.set_xlabel("θ (°)")
        ax.set_ylabel(f"ρ from the {name} (px)")
        ax.set_title(f"object {target + 1}, ρ from the {name}:\n{verdict}", fontsize=9)
    fig.tight_layout()
    return fig


# --------------------------------------------------------------------------- Monte Carlo plots
def plot_angle_constraint(df: pd.DataFrame, ax: plt.Axes | None = None) -> plt.Axes:
    """False tracks per frame of logic 3/4 with and without the angle constraint versus the
    prediction-gate radius, one pair of lines per clutter level."""
    ax = get_ax(ax)
    for lam, g in df.groupby("clutter"):
        plain = g[g["method"] == "logic 3/4"]
        ang = g[g["method"] == "angle logic 3/4"]
        line = ax.plot(plain["gate_px"], plain["false_per_frame"], "-o", ms=4,
                       label=f"logic 3/4, {lam:g} false alarms/frame")
        ax.plot(ang["gate_px"], ang["false_per_frame"], "--s", ms=4, mfc="none",
                color=line[0].get_color(), label=f"angle-constrained, {lam:g}/frame")
    log_axis(ax, "both")
    ax.set_xlabel("prediction gate radius (px)")
    ax.set_ylabel("false tracks per frame")
    ax.set_title("Angle constraint versus the prediction gate")
    legend_outside(ax, where="below", ncol=2)
    return ax


def plot_chance_check(df: pd.DataFrame, ax: plt.Axes | None = None) -> plt.Axes:
    """Chance tracks per clutter-only scene: analytic (line) versus measured (markers, ±1 s.e.)."""
    from matplotlib.ticker import NullFormatter, ScalarFormatter

    ax = get_ax(ax)
    ax.plot(df["clutter"], df["analytic per scene"], "-", label="analytic (χ² 3-of-4 rule)")
    err = np.sqrt(df["measured"].clip(lower=1)) / df["scenes"]
    ax.errorbar(df["clutter"], df["measured per scene"], yerr=err, fmt="o", ms=5,
                label="measured (verified initiator, acceleration search off)")
    ax.set_xscale("log")
    log_axis(ax, "y")
    ax.set_xticks(list(df["clutter"]))
    ax.xaxis.set_major_formatter(ScalarFormatter())
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("clutter points per frame")
    ax.set_ylabel("chance tracks per scene")
    ax.set_title("Chance tracks in clutter-only scenes")
    legend_outside(ax, where="below", ncol=1)
    return ax


def plot_planted_summary(summary: pd.DataFrame, axes=None, *, recall_min: float = 0.95,
                         ratio_max: float = 1.5, chance_factor: float = 1.0):
    """Recall (left) and false tracks per scene against the calibrated chance rate (right) per
    initiator; dashed lines: the criterion. ``chance_factor``: the clutter-only check's pooled
    measured/analytic ratio (:func:`~.claims.calibrated_chance_factor`)."""
    check_positive(chance_factor, "chance_factor")
    if axes is None:
        fig, axes = plt.subplots(1, 2, figsize=(7.5, 4.4))
    else:
        fig = axes[0].figure
    y = np.arange(len(summary))
    axes[0].barh(y, summary["recall"], color="tab:blue")
    axes[0].axvline(recall_min, color="k", ls=":", lw=1.5, label=f"criterion ≥ {recall_min:g}")
    axes[0].set_yticks(y, summary["method"])
    axes[0].set_ylabel("initiator")
    axes[0].set_xlabel("recall")
    axes[0].set_xlim(0, 1)
    axes[0].set_title("recall (initiated / eligible)")
    # markers, not bars: a bar's length means nothing on a log axis
    axes[1].plot(summary["false per scene"], y, "o", color="tab:red", label="measured")
    chance = chance_factor * float(summary["chance per scene"].iloc[0])
    axes[1].axvline(chance, color="k", lw=1, label="calibrated chance rate")
    axes[1].axvline(ratio_max * chance, color="k", ls="--", lw=1,
                    label=f"criterion ≤ {ratio_max:g} × chance rate")
    axes[1].set_yticks(y, [""] * len(y))
    axes[1].set_ylim(-0.5, len(y) - 0.5)
    log_axis(axes[1], "x")
    axes[1].set_xlabel("false tracks per scene")
    axes[1].set_title("false tracks")
    fig.tight_layout()
    legend_outside(fig, where="below", ncol=2)
    return fig


def plot_scene_tracks(scene: Scene, tracks: list[Track], ax: plt.Axes | None = None, *,
                      title: str = "", width: float = 512.0) -> plt.Axes:
    """One scene: all detections (grey), the objects' true paths (dotted), correct tracks
    (green) and false tracks (red)."""
    ax = get_ax(ax, figsize=(5, 5))
    fr = validate_frames(scene.frames)
    allxy = np.concatenate([xy for _, xy in scene.frames])
    ax.plot(*allxy.T, ".", color="0.7", ms=3)
    truth = np.array(scene.truth_xy)
    for i in range(scene.n_targets):
        ax.plot(*truth[:, i].T, ":", color="k", lw=1, zorder=3)  # dotted, over the tracks
    sc = score_tracks(tracks, scene)
    seen: set[bool] = set()
    for tr in tracks:
        ids = {int(scene.labels[f][d]) for f, d in tr.hits if f <= tr.confirmed_at}
        good = len(ids) == 1 and min(ids) >= 0
        ax.plot(*tr.positions(fr).T, "-o" if good else "-x", ms=3,
                color="tab:green" if good else "tab:red",
                label=None if good in seen else ("correct track" if good else "false track"))
        seen.add(good)
    if scene.n_targets:
        ax.lines[1].set_label("true path")
    legend_outside(ax, where="below", ncol=3)
    ax.set_xlim(0, width)
    ax.set_ylim(width, 0)
    ax.set_aspect("equal")
    ax.set_xlabel("x (px)")
    ax.set_ylabel("y (px)")
    ax.set_title(f"{title}{sc['correct']}/{sc['eligible']} objects, {sc['false']} false",
                 fontsize=9)
    return ax


# --------------------------------------------------------------------------- explore
EXPLORE_CLUTTER = (5.0, 20.0, 50.0)
EXPLORE_SCENES = 4


def _explore_initiator(neighbourhood: int, centred: bool, verified: bool,
                       cfg: PlantedConfig) -> ModifiedHoughInitiator:
    xu = xu_config()
    vmin, vmax = cfg.v_gate_px_s
    if verified:
        return ModifiedHoughInitiator(v_min=vmin, v_max=vmax, sigma_px=cfg.sigma_px,
                                      alpha=cfg.alpha)
    origin = (cfg.width_px / 2, cfg.width_px / 2) if centred else (0.0, 0.0)
    return ModifiedHoughInitiator(d_rho=xu.cell_rho_px, d_theta_deg=xu.cell_theta_deg,
                                  d_v=xu.cell_v_px_s, v_min=vmin, v_max=vmax,
                                  neighbourhood=neighbourhood, origin_px=origin, literal=True)


@cache
def _explore_scenes(clutter: float) -> tuple:
    cfg = PlantedConfig()
    rng = np.random.default_rng(int(1000 + clutter))
    return tuple(planted_scene(rng, cfg, clutter_per_frame=clutter)
                 for _ in range(EXPLORE_SCENES))


@cache
def explore_results(clutter: float, neighbourhood: int = 6, centred: bool = False,
                    verified: bool = False) -> dict:
    """Cached results of one modified-Hough variant on the Explore panel's scenes.

    ``EXPLORE_SCENES`` seeded planted scenes at the given clutter level; ``neighbourhood`` and
    ``centred`` (ρ from the image centre) act on the paper's literal procedure, ``verified``
    selects our initiator. Returns per-scene arrays ``correct``, ``eligible``, ``false`` and
    ``chance``, and what the panel draws of the first scene: ``detections`` ``(n, 2)``,
    ``truth`` ``(frames, objects, 2)`` and ``tracks`` (a list of ``(positions, correct)``).
    """
    cfg = PlantedConfig()
    ini = _explore_initiator(int(neighbourhood), bool(centred), bool(verified), cfg)
    out = {"correct": [], "eligible": [], "false": [], "chance": []}
    for i, scene in enumerate(_explore_scenes(float(clutter))):
        tracks = ini.initiate(scene.frames)
        sc = score_tracks(tracks, scene)
        out["correct"].append(sc["correct"])
        out["eligible"].append(sc["eligible"])
        out["false"].append(sc["false"])
        out["chance"].append(chi2_chance_tracks(
            scene, v_min=cfg.v_gate_px_s[0], v_max=cfg.v_gate_px_s[1], sigma_px=cfg.sigma_px,
            alpha=cfg.alpha, width=cfg.width_px))
        if i == 0:
            fr = validate_frames(scene.frames)
            out["detections"] = np.concatenate([xy for _, xy in scene.frames])
            out["truth"] = np.array(scene.truth_xy)
            out["tracks"] = []
            for tr in tracks:
                ids = {int(scene.labels[f][d]) for f, d in tr.hits if f <= tr.confirmed_at}
                out["tracks"].append((tr.positions(fr), len(ids) == 1 and min(ids) >= 0))
    for k in ("correct", "eligible", "false", "chance"):
        out[k] = np.asarray(out[k], dtype=float)
    return out


#: The Explore panel's figure, built once and updated in place (see :func:`plot_explore`).
_EXPLORE: dict[str, Any] = {}


def _explore_artists(n_scenes: int) -> dict[str, Any]:
    """Build the Explore figure once: bars, markers and lines to update (no pyplot state)."""
    if _EXPLORE.get("n") == n_scenes:
        return _EXPLORE
    _EXPLORE.clear()
    fig = Figure(figsize=(7.5, 4.8))
    ax, axr = fig.subplots(1, 2)
    x = np.arange(n_scenes)
    zeros = np.zeros(n_scenes)
    art: dict[str, Any] = {"n": n_scenes, "fig": fig, "ax": ax, "axr": axr}
    # false tracks per scene (bars) against the chance rate; recall is in the title
    art["false"] = ax.bar(x, zeros, 0.6, color="tab:red", label="false tracks")
    art["chance"] = ax.plot(x, zeros, "k_", ms=18, mew=2, label="chance rate (χ² 3-of-4)")[0]
    ax.set_ylabel("false tracks per scene")
    ax.set_xlabel("scene")
    ax.set_xticks(x)
    art["ax2"] = ax
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=1)
    art["title"] = ax.set_title("\n", fontsize=9)
    # the first scene: every polyline of a kind is one line, pieces separated by NaN
    art["detections"] = axr.plot([], [], ".", color="0.7", ms=3)[0]
    art["truth"] = axr.plot([], [], ":", color="k", lw=1)[0]
    art["good"] = axr.plot([], [], "-o", ms=3, color="tab:green", label="correct track")[0]
    art["bad"] = axr.plot([], [], "-x", ms=3, color="tab:red", label="false track")[0]
    art["truth"].set_label("true path")
    axr.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
    w = PlantedConfig().width_px
    axr.set_xlim(0, w)
    axr.set_ylim(w, 0)
    axr.set_aspect("equal")
    axr.set_xlabel("x (px)")
    axr.set_ylabel("y (px)")
    art["title_r"] = axr.set_title("", fontsize=9)
    fig.subplots_adjust(left=0.09, right=0.97, bottom=0.36, top=0.84, wspace=0.55)
    _EXPLORE.update(art)
    return _EXPLORE


def _joined(polylines: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Polylines ``(k_i, 2)`` as one x, y pair with NaN between them (one artist draws all)."""
    if not polylines:
        return np.empty(0), np.empty(0)
    gap = np.full((1, 2), np.nan)
    xy = np.concatenate([p for q in polylines for p in (np.asarray(q, float), gap)])
    return xy[:, 0], xy[:, 1]


def plot_explore(clutter: float = 20.0, neighbourhood: int = 6, centred: bool = False,
                 verified: bool = False):
    """The Explore panel's figure: false tracks per scene over the panel's scenes against the
    chance rate, with the recall in the title (left) and the first scene's tracks (right), for one variant.

    The figure is built once and its bars and lines updated on every call (the same
    ``Figure`` is returned), so a widget redraw costs one render.
    """
    res = explore_results(float(clutter), int(neighbourhood), bool(centred), bool(verified))
    n = len(res["false"])
    art = _explore_artists(n)
    for bar, h in zip(art["false"].patches, res["false"], strict=True):
        bar.set_height(h)
    art["chance"].set_ydata(res["chance"])
    top = max(float(res["false"].max(initial=0)), float(res["chance"].max(initial=0)), 1.0)
    art["ax2"].set_ylim(0, 1.05 * top)
    name = ("ours (verified)" if verified else
            f"paper, {neighbourhood}-nbhd, ρ from the {'centre' if centred else 'corner'}")
    art["title"].set_text(
        f"{name} — {n} scenes only\nrecall "
        f"{res['correct'].sum() / max(res['eligible'].sum(), 1):.2f}, "
        f"{res['false'].mean():.1f} false/scene (chance {res['chance'].mean():.1f})")
    art["detections"].set_data(*res["detections"].T)
    art["truth"].set_data(*_joined([res["truth"][:, i] for i in range(res["truth"].shape[1])]))
    art["good"].set_data(*_joined([pos for pos, good in res["tracks"] if good]))
    art["bad"].set_data(*_joined([pos for pos, good in res["tracks"] if not good]))
    art["title_r"].set_text(f"scene 0: {int(res['correct'][0])}/{int(res['eligible'][0])} "
                            f"objects, {int(res['false'][0])} false")
    return art["fig"]
