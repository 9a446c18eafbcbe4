"""Figures of Li et al. (2008): one function per paper figure, plus the Explore panel's figure.

Each takes ``ax=None`` (or ``fig=None`` for multi-panel figures) and returns the axes or figure;
none calls ``plt.show()``.
"""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle
from matplotlib.ticker import MaxNLocator, NullLocator

from eotrack.plotting import get_ax
from eotrack.tracking import hypothesis as hyp
from eotrack.tracking.initiation.base import Frame

from .scenario import HIGH_PDA, LOW_PFA
from .trials import Fig1Result, Fig2Result

__all__ = [
    "explore_figure",
    "plot_fig1",
    "plot_fig2",
    "plot_fig3",
    "plot_fig4",
    "plot_fig5",
    "plot_fig6",
    "plot_fig7",
    "plot_initiator_vs_formulas",
    "plot_measured_vs_formula",
    "plot_schematic",
    "plot_snr_sweep",
]


def plot_schematic(*, p_f: float = 0.2, window: int = 5, target_pixels: int = 4, s: int = 7,
                   gate: int = 3, frames: int = 7, seed: int = 3,
                   fig: plt.Figure | None = None) -> plt.Figure:
    """The two tests drawn: a clustering window with its count ``D`` and a gate over ``T`` frames.

    Left: one ``window × window`` box of a binary image — the target's pixels (hatched) and
    random false alarms; the title gives ``D`` against ``S``. Right: a candidate followed
    through ``T`` frames; in each frame the ``gate × gate`` association region (grey) around
    the prediction holds a point (hit) or not (miss).
    """
    rng = np.random.default_rng(seed)
    fig = fig or plt.figure(figsize=(7.5, 3.3))
    a1, a2 = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1, 2.2]})
    n = window
    fa = rng.random((n, n)) < p_f
    tgt = np.zeros((n, n), dtype=bool)
    c = n // 2
    k = int(np.ceil(np.sqrt(target_pixels)))
    idx = [(c + i - k // 2, c + j - k // 2) for i in range(k) for j in range(k)][:target_pixels]
    for i, j in idx:
        tgt[i, j] = True
    det = tgt & (rng.random((n, n)) < 0.8)
    g = det | fa
    for i in range(n):
        for j in range(n):
            a1.add_patch(Rectangle((j, i), 1, 1, fc="k" if g[i, j] else "w", ec="0.6",
                                   hatch="///" if tgt[i, j] else None))
    a1.set_xlim(0, n)
    a1.set_ylim(n, 0)
    a1.set_aspect("equal")
    a1.set_xticks([])
    a1.set_yticks([])
    d = int(g.sum())
    a1.set_title(f"window {n}×{n}: D = {d} {'≥' if d >= s else '<'} S = {s}", fontsize=9)
    a1.set_xlabel(f"$W_S$ = {n * n} pixels; black: suspicious,\nhatched: target", fontsize=9)
    # temporal test: a target drifting right, detected in most frames
    hits = rng.random(frames) < 0.75
    hits[0] = True
    x = np.arange(frames) * (gate + 0.8)  # gates apart, each drawn pixel by pixel (M pixels)
    for f in range(frames):
        for i in range(gate):
            for j in range(gate):
                a2.add_patch(Rectangle((x[f] - gate / 2 + j, -gate / 2 + i), 1, 1, fc="0.88",
                                       ec="0.5", lw=0.6))
        if hits[f]:
            a2.plot(x[f] + rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), "ko", ms=6)
        a2.text(x[f], -gate / 2 - 0.5, f"k={f + 1}", ha="center", fontsize=9)
    nh = int(hits.sum())
    a2.set_xlim(-gate, x[-1] + gate)
    a2.set_ylim(-gate, gate)
    a2.set_aspect("equal")
    a2.axis("off")
    a2.set_title(f"gate {gate}×{gate} (M = {gate * gate}) over T = {frames} frames:\n"
                 f"{nh} hits — a target track if ≥ $T_h$", fontsize=9)
    fig.tight_layout()
    return fig


def plot_fig1(res: Fig1Result, *, s_max: int = 12, ax: plt.Axes | None = None) -> plt.Axes:
    """Fig. 1: P_FA and P_DA versus S (lines: formulas; markers: Monte Carlo)."""
    ax = get_ax(ax, figsize=(5.0, 4.2))
    sel = res.s <= s_max
    s = res.s[sel]
    ax.semilogy(s, res.pfa[sel], "k-", lw=2, label="$P_{FA}$ eq. (4)")
    ok = res.mc_pfa[sel] > 0
    ax.plot(s[ok], res.mc_pfa[sel][ok], "kx", ms=7, label="$P_{FA}$ Monte Carlo")
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for j, snr in enumerate(res.snr):
        c = colors[j % len(colors)]
        ax.semilogy(s, res.pda_paper[j, sel], "-", color=c,
                    label=f"$P_{{DA}}$ eq. (7), SNR {snr:g}")
        ax.semilogy(s, res.pda_exact[j, sel], "--", color=c, label=f"exact count, SNR {snr:g}")
        ok = res.mc_pda[j, sel] > 0
        ax.plot(s[ok], res.mc_pda[j, sel][ok], "o", mfc="none", color=c, ms=5)
    ax.plot([], [], "o", mfc="none", color="gray", label="Monte Carlo (pixels)")
    # the li_fig1 decision: P_FA <= LOW_PFA from the smallest admissible S on, P_DA >= HIGH_PDA
    ok_s = res.pfa <= LOW_PFA
    if ok_s.any():
        ax.axvline(float(res.s[ok_s][0]), color="0.4", lw=0.8, ls="-.",
                   label=f"smallest S with $P_{{FA}}$ ≤ {LOW_PFA:g}")
    ax.axhline(LOW_PFA, color="k", lw=0.8, ls=":", label=f"$P_{{FA}}$ = {LOW_PFA:g}")
    ax.axhline(HIGH_PDA, color="0.4", lw=0.8, ls=":", label=f"$P_{{DA}}$ = {HIGH_PDA:g}")
    ax.set_ylim(1e-9, 2)
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))  # S is an integer
    ax.set_xlabel("clustering threshold S")
    ax.set_ylabel("probability")
    w = res.settings
    ax.set_title(f"Fig. 1 — $W_S$ = {w['window'] ** 2}, $T_S$ = {w['target_pixels']}, "
                 f"$P_F$ = {w['p_f']:g}")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))  # off the curves
    ax.figure.tight_layout()
    return ax


def plot_fig2(res: Fig2Result, *, t_h: tuple[int, ...] = (3, 4, 5, 6),
              ax: plt.Axes | None = None) -> plt.Axes:
    """Fig. 2: P_DS (solid) and P_DT (dashed) versus P_F for several T_h; markers Monte Carlo."""
    ax = get_ax(ax, figsize=(5.0, 4.2))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for c, th in zip(colors, t_h):
        i = int(th) - 1
        ax.semilogx(res.p_f, res.pds[i], "-", color=c, label=f"$P_{{DS}}$, $T_h$ = {th}")
        ax.semilogx(res.p_f, res.pdt[i], "--", color=c, label=f"$P_{{DT}}$, $T_h$ = {th}")
        ax.plot(res.p_f, res.mc_pds[i], "o", mfc="none", color=c, ms=4)
        ax.plot(res.p_f, res.mc_pdt[i], "s", mfc="none", color=c, ms=4)
    ax.plot([], [], "o", mfc="none", color="gray", label="Monte Carlo")
    st = res.settings
    ax.set_xlabel("single-frame false-alarm probability $P_F$")
    ax.set_ylabel("probability")
    ax.set_title(f"Fig. 2 — SNR {st['snr']:g}, M = {st['gate']}×{st['gate']}, "
                 f"T = {st['frames']}")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))  # off the curves
    ax.figure.tight_layout()
    return ax


def plot_initiator_vs_formulas(df: pd.DataFrame, *, ax: plt.Axes | None = None) -> plt.Axes:
    """The initiator's measured track probabilities beside eqs. (12)–(13)."""
    ax = get_ax(ax, figsize=(6.0, 3.8))
    ax.semilogx(df["P_F"], df["P_DS eq.12"], "C1-", label="$P_{DS}$ eq. (12)")
    ax.semilogx(df["P_F"], df["track containing the target"], "C1o", mfc="none",
                label="initiator: a track contains the target")
    ax.semilogx(df["P_F"], df["P_DT eq.13"], "C2--", label="$P_{DT}$ eq. (13)")
    ax.semilogx(df["P_F"], df["track with >= T_h target points"], "C2s", mfc="none",
                label="initiator: a track holds $\\geq T_h$ target points")
    ax.set_xlabel("single-frame $P_F$")
    ax.set_ylabel("probability")
    ax.set_title("The temporal-test initiator against eqs. (12)-(13)")
    ax.legend(fontsize=8)
    return ax

def _truth_circles(ax: plt.Axes, truth: np.ndarray, frame: int) -> None:
    for i in range(truth.shape[0]):
        if np.isfinite(truth[i, frame, 0]):
            ax.add_patch(plt.Circle(truth[i, frame], 7, fill=False, ec="w"))


def _image_axes(ax: plt.Axes) -> None:
    ax.set_xticks([])
    ax.set_yticks([])


def plot_fig3(run: dict[str, Any], frame: int, *, ax: plt.Axes | None = None) -> plt.Axes:
    """Fig. 3: one raw frame of the simulated sequence, the targets circled."""
    ax = get_ax(ax, figsize=(5.2, 5.2))
    seq = run["seq"]
    im = seq.images[frame]
    lo, hi = np.percentile(im, [1, 99.5])
    ax.imshow(im, vmin=lo, vmax=hi, cmap="gray")
    _truth_circles(ax, seq.truth_xy, frame)
    ax.set_title(f"Fig. 3 — frame {frame}, fluctuating background (targets circled)",
                 fontsize=9)
    _image_axes(ax)
    return ax


def plot_fig4(run: dict[str, Any], frame: int, *, p_f: float, ax: plt.Axes | None = None
              ) -> plt.Axes:
    """Fig. 4: the CFAR-segmented frame ``G`` (white: above the threshold)."""
    ax = get_ax(ax, figsize=(5.2, 5.2))
    g = run["binary"][frame]
    ax.imshow(g, interpolation="nearest", cmap="gray")
    _truth_circles(ax, run["seq"].truth_xy, frame)
    ax.set_title(f"Fig. 4 — CFAR segmentation at $P_F$ = {p_f:g}: {int(g.sum())} pixels set",
                 fontsize=9)
    _image_axes(ax)
    return ax


def plot_fig5(run: dict[str, Any], frame: int, *, window: int, s: int,
              ax: plt.Axes | None = None) -> plt.Axes:
    """Fig. 5: the frame after spatial clustering (``D ≥ S`` in a ``window²`` box)."""
    ax = get_ax(ax, figsize=(5.2, 5.2))
    c = run["clustered"][frame]
    ax.imshow(c, interpolation="nearest", cmap="gray")
    yy, xx = np.nonzero(c)  # 1-px pixels vanish when the image is shrunk: mark each one
    ax.plot(xx, yy, "s", ms=7, mfc="none", mec="C1", mew=1.2, label="pixel left (marked)")
    _truth_circles(ax, run["seq"].truth_xy, frame)
    ax.plot([], [], "o", ms=9, mfc="none", mec="w", label="true target")
    ax.set_title(f"Fig. 5 — clustered, $W_S$ = {window}×{window}, S = {s}: "
                 f"{int(c.sum())} pixels left", fontsize=9)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.01), ncol=2,
              facecolor="0.3", labelcolor="w", frameon=True)  # below the image
    _image_axes(ax)
    return ax


def _tracks(ax: plt.Axes, run: dict[str, Any], *, false_color: str = "r") -> None:
    fr_objs = [Frame(t, xy) for t, xy in run["frames"]]
    for tr, o in zip(run["tracks"], run["owner"]):
        p = tr.positions(fr_objs)
        ax.plot(p[:, 0], p[:, 1], ".-", ms=3, lw=1.2,
                color=f"C{int(o) % 10}" if o >= 0 else false_color)


def plot_fig6(run: dict[str, Any], *, gate: int, frames: int, min_hits: int,
              ax: plt.Axes | None = None) -> plt.Axes:
    """Fig. 6: the candidate points of all frames and the tracks the temporal test confirms."""
    ax = get_ax(ax, figsize=(5.6, 5.6))
    acc = run["clustered"].max(axis=0)
    ax.imshow(acc, interpolation="nearest", cmap="gray_r", vmin=0, vmax=3)
    _tracks(ax, run)
    owner = run["owner"]
    n_fr = run["binary"].shape[0]
    ax.set_xlim(0, acc.shape[1])
    ax.set_ylim(acc.shape[0], 0)
    ax.set_title(f"Fig. 6 — {n_fr} frames, M = {gate}×{gate}, T = {frames}, $T_h$ = {min_hits}:"
                 f"\n{int(np.sum(owner >= 0))} target track(s), {int(np.sum(owner < 0))} false "
                 "(red); grey: clustered pixels of all frames", fontsize=9)
    _track_legend(ax, run)
    ax.set_xlabel("x (px)")
    ax.set_ylabel("y (px)")
    ax.grid(False)
    return ax


def _track_legend(ax: plt.Axes, run: dict[str, Any], *, truth: bool = False,
                  below: float = -0.12) -> None:
    """Legend of the track colours (one per target, red false) and the grey true paths."""
    n_t = run["seq"].truth_xy.shape[0]
    names = ["main target", "curved target"] if n_t == 2 else [f"target {i}" for i in range(n_t)]
    for i in range(n_t):
        ax.plot([], [], ".-", color=f"C{i % 10}", label=f"confirmed track: {names[i]}")
    ax.plot([], [], ".-", color="r", label="false track")
    if truth:
        ax.plot([], [], ":", color="0.5", lw=1.5, label="true path (grey)")
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, below), ncol=2)  # below


def plot_fig7(runs: dict[float, dict[str, Any]], sweep: pd.DataFrame | None = None, *,
              paper_snr: float = 2.0, fig: plt.Figure | None = None) -> plt.Figure:
    """Fig. 7: confirmed tracks against the true paths, one panel per curved-target SNR.

    ``runs`` maps an SNR to a kept run (:func:`~.sequences.sweep_example`: a member of the sweep
    at that SNR, its index in the title); ``sweep`` (:func:`~.sequences.snr_sweep`)
    adds that SNR's recovery share over all runs to the title. The SNR ``paper_snr`` is the
    paper's; any other is labelled exploratory.
    """
    fig = fig or plt.figure(figsize=(min(7.5, 3.9 * len(runs)), 5.4))
    axs = np.atleast_1d(fig.subplots(1, len(runs)))
    for ax, (snr, run) in zip(axs, runs.items()):
        truth = run["seq"].truth_xy
        for i in range(truth.shape[0]):
            # dotted, over the tracks: a path tracked all along stays visible
            ax.plot(truth[i, :, 0], truth[i, :, 1], ":", color="0.5", lw=1.5, zorder=3)
        _tracks(ax, run)
        cov = run["coverage"]
        h, w = run["binary"].shape[1:]
        ax.set_xlim(0, w)
        ax.set_ylim(h, 0)
        ax.set_aspect("equal")
        ax.set_xlabel("x (px)")
        ax.set_ylabel("y (px)")
        tag = "paper's SNR" if float(snr) == float(paper_snr) else "exploratory"
        line2 = (f"run {run.get('run_index', 0)}: main {cov[0]:.0%}, curved {cov[-1]:.0%} "
                 "of frames tracked")
        line3 = ""
        if sweep is not None:
            row = sweep.loc[np.isclose(sweep["SNR"], float(snr))]
            if len(row):
                r = row.iloc[0]
                line3 = (f"\nall {int(r['runs'])} runs: curved target recovered in "
                         f"{int(r['recovered runs'])}\n(95 % CP [{r['CP low']:.0%}, "
                         f"{r['CP high']:.0%}])")
        ax.set_title(f"Fig. 7 — SNR {snr:g} ({tag})\n{line2}{line3}", fontsize=8)
        _track_legend(ax, run, truth=True, below=-0.16)
    fig.tight_layout()
    return fig


def plot_measured_vs_formula(exp: dict[str, Any], *, ax: plt.Axes | None = None) -> plt.Axes:
    """Measured P_FA(S) and P_FT(T_h) on the sequences beside eqs. (4) and (9)."""
    ax = get_ax(ax, figsize=(6.4, 4.0))
    t = exp["pfa_table"]
    ax.semilogy(t["S"], t["P_FA eq.4 (measured P_F)"], "k-", label="$P_{FA}$ eq. (4) vs S")
    m = t["P_FA measured"] > 0
    ax.semilogy(t["S"][m], t["P_FA measured"][m], "ko", mfc="none", label="measured vs S")
    f = exp["pft_table"]
    ax.semilogy(f["T_h"], f["P_FT eq.9 (measured candidate P_F)"], "C3-",
                label="$P_{FT}$ eq. (9) vs $T_h$")
    m = f["P_FT measured (fixed gate)"] > 0
    ax.semilogy(f["T_h"][m], f["P_FT measured (fixed gate)"][m], "C3s", mfc="none",
                label="measured vs $T_h$")
    ax.set_ylim(1e-12, 1.5)
    ax.set_xlabel("S (clustering) or $T_h$ (temporal)")
    ax.set_ylabel("probability")
    ax.set_title("Sequences: measured false-alarm rates vs formulas")
    ax.legend(fontsize=8)
    return ax


def plot_snr_sweep(df: pd.DataFrame, *, ax: plt.Axes | None = None) -> plt.Axes:
    """Recovery of the curved target versus SNR."""
    ax = get_ax(ax, figsize=(6.0, 4.6))
    y = df["recovered share"].to_numpy()
    err = np.vstack([y - df["CP low"].to_numpy(), df["CP high"].to_numpy() - y])
    ax.errorbar(df["SNR"], y, yerr=err, fmt="o-", capsize=3,
                label=f"share of runs recovered (95 % CP, {int(df['runs'].iloc[0])} runs)")
    ax.plot(df["SNR"], df["P_DA measured"], "s--", label="per-frame $P_{DA}$")
    ax.axhline(0.5, color="0.5", lw=0.8, ls=":", label="criterion: half the runs")
    ax.set_xlabel("peak SNR of the curved 3×3 target")
    ax.set_ylabel("fraction")
    ax.set_ylim(-0.03, 1.03)
    snr = df["SNR"].to_numpy(dtype=float)
    ax.set_xticks(snr)  # the sweep's integer SNR grid
    ax.set_xticklabels([f"{v:g}" for v in snr])
    ax.set_xlim(snr.min() - 0.4, snr.max() + 0.4)  # no point on the frame
    ax.set_title("Fig. 7 target: recovery versus SNR (same scene, same noise)")
    # below the axes: the curves rise from bottom-left to top-right and fill the frame
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.18), ncol=1,
              frameon=False)
    ax.figure.tight_layout()
    return ax


def _plain_sci(v: float) -> str:
    """``3.2e-05`` as ``3.2×10⁻⁵`` (Unicode superscripts, no mathtext), ``0.012`` as is."""
    if v == 0 or 1e-3 <= abs(v) < 1e4:
        return f"{v:.2g}"
    m, e = f"{v:.1e}".split("e")
    sup = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")
    return f"{m}×10{str(int(e)).translate(sup)}"


#: The Explore panel's figure, built once and updated in place (see :func:`explore_figure`).
_EXPLORE: dict[str, Any] = {}


def _explore_legend(ax: Any, handles: list[Any]) -> None:
    """The Explore panel's legend, below its axes (outside the data area)."""
    ax.legend(handles=handles, fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.2),
              ncol=2, frameon=False)


def _explore_artists() -> dict[str, Any]:
    """Build the Explore figure once: two log axes, their lines and markers (no pyplot state)."""
    if _EXPLORE:
        return _EXPLORE
    fig = Figure(figsize=(7.2, 3.9), dpi=90)  # within the book's width (7.5 in, with savefig padding); fewer pixels
    a1, a2 = fig.subplots(1, 2)
    x = np.arange(1, 3)
    # symbols in mathtext; the labels are fixed, so each is parsed once (matplotlib caches it)
    art = {
        "fig": fig, "a1": a1, "a2": a2,
        "pfa": a1.semilogy(x, x, "k-", label=r"$P_\mathrm{FA}$ eq. (4)")[0],
        "exact": a1.semilogy(x, x, "C0-", lw=2, label=r"$P_\mathrm{DA}$ exact count")[0],
        "eq7": a1.semilogy(x, x, "C3--", label=r"$P_\mathrm{DA}$ eq. (7)")[0],
        "s": a1.axvline(1, color="0.5", lw=0.8, label="chosen $S$"),
        "pds": a2.semilogy(x, x, "C1-o", label=r"$P_\mathrm{DS}$ eq. (12)")[0],
        "pdt": a2.semilogy(x, x, "C2--s", label=r"$P_\mathrm{DT}$ eq. (13)")[0],
        "pft": a2.semilogy(x, x, "k:", label=r"$P_\mathrm{FT}$ eq. (9)")[0],
        "th": a2.axvline(1, color="0.5", lw=0.8, label="chosen $T_h$"),
    }
    for a in (a1, a2):
        a.set_ylim(1e-12, 2)
        # fixed decades as plain text (10⁻¹², …): no mathtext to re-parse on a redraw
        a.set_yticks(10.0 ** np.arange(-12, 1, 3), ["10⁻¹²", "10⁻⁹", "10⁻⁶", "0.001", "1"])
        a.yaxis.set_minor_locator(NullLocator())
    a1.set(xlabel="clustering threshold $S$", ylabel="probability")
    a2.set(xlabel="hits needed $T_h$", ylabel="probability")
    # legends below the panels: no setting of the controls can put a curve under them
    _explore_legend(a1, [art["pfa"], art["exact"], art["eq7"]])
    _explore_legend(a2, [art["pds"], art["pdt"], art["pft"], art["th"]])
    a1.set_title("placeholder\nplaceholder", fontsize=9)
    a2.set_title("placeholder\nplaceholder", fontsize=9)
    fig.tight_layout()
    _EXPLORE.update(art)
    return _EXPLORE


def explore_figure(snr: float = 2.0, log10_p_f: float = -2.5, window: int = 5,
                   target_pixels: int = 4, s: int = 4, gate: int = 3, frames: int = 7,
                   min_hits: int = 5, show_eq7: bool = True) -> Figure:
    """The closed forms for one setting: Fig. 1 (left) and Fig. 2 at that ``P_F`` (right).

    Left: ``P_FA`` (eq. 4) and ``P_DA`` (exact count; eq. 7 if ``show_eq7``) versus ``S``, the
    chosen ``S`` marked. Right: ``P_DS``, ``P_DT``, ``P_FT`` (eqs. 12, 13, 9) versus ``T_h``,
    the chosen ``T_h`` marked. Values that the controls make inconsistent are clipped
    (``T_S, S ≤ W_S``; ``T_h ≤ T``). Closed forms only, no Monte Carlo; the figure is built once
    and its lines updated on every call (the same ``Figure`` is returned), so a widget redraw
    costs one render.
    """
    p_f = 10.0 ** log10_p_f
    n = window * window
    target_pixels = min(target_pixels, n)
    s = min(s, n)
    min_hits = min(min_hits, frames)
    p_d = float(hyp.snr_to_pd(snr, p_f))
    art = _explore_artists()
    a1, a2 = art["a1"], art["a2"]
    ss = np.arange(1, n + 1)
    floor = 1e-300  # zeros cannot be drawn on a log axis
    pfa = hyp.area_false_alarm(p_f, window, ss)
    exact = hyp.area_detection_exact(p_d, p_f, window, target_pixels, ss)
    art["pfa"].set_data(ss, np.maximum(pfa, floor))
    art["exact"].set_data(ss, np.maximum(exact, floor))
    art["eq7"].set_data(ss, np.maximum(hyp.area_detection(p_d, p_f, window, target_pixels, ss),
                                       floor))
    art["eq7"].set_visible(bool(show_eq7))
    art["s"].set_xdata([s, s])
    a1.set_xlim(0.5, n + 0.5)
    handles = [art["pfa"], art["exact"]] + ([art["eq7"]] if show_eq7 else []) + [art["s"]]
    _explore_legend(a1, handles)
    # symbols in mathtext (≈ 15 ms more per redraw at load 5 than plain text)
    a1.set_title(f"SNR {snr:g} → $P_\\mathrm{{D}}$ = {p_d:.3f}, window {window}×{window}, "
                 f"$T_S$ = {target_pixels}\nat $S$ = {s}: $P_\\mathrm{{FA}}$ = "
                 f"{_plain_sci(pfa[s - 1])}, exact $P_\\mathrm{{DA}}$ = {exact[s - 1]:.3f}",
                 fontsize=9)
    th = np.arange(1, frames + 1)
    pdt = hyp.track_detection(p_d, frames, th)
    pft = hyp.track_false_alarm(p_f, gate, frames, th)
    art["pds"].set_data(th, np.maximum(hyp.sequence_detection(p_d, p_f, gate, frames, th),
                                       floor))
    art["pdt"].set_data(th, np.maximum(pdt, floor))
    art["pft"].set_data(th, np.maximum(pft, floor))
    art["th"].set_xdata([min_hits, min_hits])
    a2.set_xlim(0.5, frames + 0.5)
    i = min_hits - 1
    a2.set_title(f"$P_\\mathrm{{F}}$ = {p_f:.2g}, gate {gate}×{gate}, $T$ = {frames}\nat "
                 f"$T_h$ = {min_hits}: $P_\\mathrm{{DT}}$ = {pdt[i]:.3f}, $P_\\mathrm{{FT}}$ = "
                 f"{_plain_sci(pft[i])}", fontsize=9)
    return art["fig"]
