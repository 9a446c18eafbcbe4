"""Figures of the RANSAC + CRLB notebook: each function takes ``ax=None`` and returns it."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.ticker import MaxNLocator

from eotrack.plotting import (
    FIG_WIDTH_IN,
    get_ax,
    legend_outside,
    log_axis,
    method_style,
    series_styles,
)
from eotrack.validation import check_choice

from .scenario import READINGS

__all__ = [
    "draw_scene_3d",
    "figure_errors",
    "method_line",
    "plot_budget",
    "plot_crlb_ellipsoid",
    "plot_efficiency",
    "plot_error_distribution",
    "plot_error_ecdf",
    "plot_monotonicity",
    "plot_paired_ratio_ecdf",
    "plot_selected_fraction",
]

_QTY = {"pos": ("position error |t̂ − t| (m)", "Fig. 4", "position"),
        "att": ("attitude error, angle of R̂Rᵀ (deg)", "Fig. 5", "attitude")}


def _reading_styles() -> dict:
    """One fixed style per reading (colour, line style, marker), none like RANSAC's or ML's."""
    taken = {method_style("ransac").color, method_style("ml").color}
    pool = [st for st in series_styles(10) if st.color not in taken]
    return dict(zip(READINGS, pool))


def method_line(m: str) -> dict:
    """``ax.plot`` keywords of a method: RANSAC and ML from the house registry, each reading
    of the §2.4 rule its own colour + line style + marker (the same in every figure)."""
    if m == "ransac":
        return method_style("ransac").line()
    if m == "ml":
        return method_style("ml").line()
    return _reading_styles()[m].line()


def _label(m: str) -> str:
    return {"ransac": "RANSAC\nonly", "ml": "ML\n(weighted,\nreference)"}.get(
        m, "+ CRLB\n" + m.replace(" (", "\n("))


def plot_error_distribution(df: pd.DataFrame, quantity: str = "att",
                            methods: tuple[str, ...] = ("ransac", "pooled"), ax=None,
                            paper_note: str = "paper's curves lost"):
    """Figs. 4/5 as distributions: a box per method, each run a faint line across the boxes.

    The faint lines join the same run's errors, so a reader sees both the spread over runs and
    the paired change that the Wilcoxon test uses.
    """
    check_choice(quantity, "quantity", list(_QTY))
    ax = get_ax(ax, figsize=(FIG_WIDTH_IN, 4.2))
    ok = df[df["success"]]
    data = [ok[f"{quantity}_{m}"].to_numpy() for m in methods]
    x = np.arange(1, len(methods) + 1)
    Y = np.column_stack(data)
    ax.plot(x, Y.T, color="0.5", lw=0.3, alpha=0.25, zorder=1)
    ax.boxplot(data, positions=x, widths=0.45, showmeans=True, zorder=3,
               meanprops={"marker": "D", "markerfacecolor": "w", "markeredgecolor": "k"},
               medianprops={"color": "k"}, flierprops={"markersize": 2})
    ax.set_xticks(x, [_label(m) for m in methods])
    log_axis(ax, "y")
    ylab, fig_no, word = _QTY[quantity]
    ax.set_ylabel(ylab)
    ax.set_xlabel("method (a faint line joins one run's errors)")
    ax.set_title(f"{fig_no} — {word} error, {len(ok)} runs (◇ mean; {paper_note})")
    return ax


def plot_error_ecdf(df: pd.DataFrame, quantity: str = "att",
                    methods: tuple[str, ...] = ("ransac", "pooled"), ax=None):
    """Empirical CDF of the per-run error for each method (log x)."""
    check_choice(quantity, "quantity", list(_QTY))
    ax = get_ax(ax, figsize=(FIG_WIDTH_IN, 4.2))
    ok = df[df["success"]]
    for m in methods:
        v = np.sort(ok[f"{quantity}_{m}"].to_numpy())
        ax.step(v, np.arange(1, len(v) + 1) / len(v), where="post", lw=1.3,
                markevery=max(1, len(v) // 8), ms=5, label=_label(m).replace("\n", " "),
                **method_line(m))
    log_axis(ax, "x")
    ax.set_xlabel(_QTY[quantity][0])
    ax.set_ylabel("fraction of runs ≤ x")
    ax.set_title("ECDF of the same runs (left/up = more accurate)")
    legend_outside(ax, where="below", ncol=3)
    return ax


def plot_paired_ratio_ecdf(df: pd.DataFrame, quantity: str = "att",
                           methods: tuple[str, ...] = ("ransac", "pooled"), ax=None):
    """ECDF of the per-run paired ratio (method's error / RANSAC's error), log x.

    This is what the paired tests compare: a curve left of 1 for most runs = better than
    RANSAC on the same image. The ECDFs of the errors themselves overlap when the paired
    differences are a few per cent.
    """
    check_choice(quantity, "quantity", list(_QTY))
    ax = get_ax(ax, figsize=(FIG_WIDTH_IN, 4.2))
    ok = df[df["success"]]
    base = ok[f"{quantity}_ransac"].to_numpy()
    for m in methods:
        if m == "ransac":
            continue
        v = np.sort(ok[f"{quantity}_{m}"].to_numpy() / base)
        ax.step(v, np.arange(1, len(v) + 1) / len(v), where="post", lw=1.3,
                markevery=max(1, len(v) // 8), ms=5, label=_label(m).replace("\n", " "),
                **method_line(m))
    ax.axvline(1.0, color="k", lw=0.8, ls="--", label="no change (ratio 1)")
    log_axis(ax, "x")
    ax.set_xlabel(f"paired ratio per run: {_QTY[quantity][2]} error / RANSAC's (–)")
    ax.set_ylabel("fraction of runs ≤ x")
    ax.set_title("Paired ratio to RANSAC alone, same runs (left of 1 = better)")
    legend_outside(ax, where="below", ncol=3)
    return ax


def figure_errors(df: pd.DataFrame, quantity: str = "att",
                  methods: tuple[str, ...] = ("ransac", "pooled")):
    """Box plot with per-run lines (top) and the ECDF of the paired ratio to RANSAC (bottom)
    for Fig. 4 or Fig. 5."""
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(FIG_WIDTH_IN, 8.2), height_ratios=[1.15, 1],
                                 layout="constrained")
    plot_error_distribution(df, quantity, methods, ax=a1)
    plot_paired_ratio_ecdf(df, quantity, methods, ax=a2)
    return fig


def plot_selected_fraction(df: pd.DataFrame, readings: tuple[str, ...] = ("pooled",),
                           paper_fraction: float = 2 / 3,
                           fraction_range: tuple[float, float] = (0.55, 0.8), ax=None):
    """Fig. 6 as a distribution: selected / inliers per run for each reading, paper's value."""
    ax = get_ax(ax, figsize=(FIG_WIDTH_IN, 4.2))
    ok = df[df["success"]]
    data = [(ok[f"n_{r}"] / ok["n_inliers"]).to_numpy() for r in readings]
    x = np.arange(1, len(readings) + 1)
    ax.axhspan(*fraction_range, color="C2", alpha=0.12, label="our tolerance (claims.toml)")
    ax.axhline(paper_fraction, color="k", ls="--", lw=1,
               label=f"paper: ≈ {paper_fraction:.2f} of the inliers")
    ax.violinplot(data, positions=x, widths=0.7, showmedians=True)
    jit = np.random.default_rng(0).uniform(-0.12, 0.12, len(ok))
    for xi, d in zip(x, data):
        ax.plot(xi + jit, d, ".", ms=3, color="0.3", alpha=0.5)
    ax.set_xticks(x, [r.replace(" (", "\n(") for r in readings])
    ax.set_xlabel("reading of the §2.4 rule")
    ax.set_ylabel("selected points / RANSAC inliers")
    ax.set_ylim(0, 1.05)
    ax.set_title(f"Fig. 6 — share of inliers kept, {len(ok)} runs (one dot per run)")
    legend_outside(ax, where="below")
    return ax


def plot_monotonicity(sizes: np.ndarray, scores: np.ndarray, sandwich: np.ndarray | None = None,
                      ax=None):
    """Weighted CRLB sum (and optionally the sandwich score) versus the number of points."""
    ax = get_ax(ax)
    colors = [st.color for st in series_styles(len(scores))]
    for k, s in enumerate(scores):
        ax.semilogy(sizes, s, lw=1.2, ls="-", marker="", color=colors[k],
                    label="exact CRLB (one colour per random order)" if k == 0 else None)
        if sandwich is not None:
            ax.semilogy(sizes, sandwich[k], lw=1.0, ls=":", marker="", color=colors[k],
                        label="unweighted-LS covariance ('sandwich')" if k == 0 else None)
    ax.set_xlabel("number of points in the set (random order)")
    ax.set_ylabel("score: sum of the 7 variances (m² + 1, unit weights)")
    ax.set_title("Exact CRLB never rises when a point is added")
    ax.legend()
    return ax


def _frame(ax, origin, R, length, label, color):
    for k, c in enumerate(("r", "g", "b")):
        d = R[:, k] * length
        ax.quiver(*origin, *d, color=c, lw=1.5, arrow_length_ratio=0.15)
        ax.text(*(origin + 1.15 * d), f"${label}_{'xyz'[k]}$", color=c, fontsize=9)


def draw_scene_3d(scene: Any, ax=None, *, frustum_depth: float = 2.0):
    """3-D schematic: camera frame and field of view, target frame, feature points (§1, §3).

    The camera sits at the origin with ``z`` along the optical axis; the target frame is at
    ``t`` with axes ``R e_k``; feature points (gross errors in red) are ``R X + t``.
    """
    if ax is None:
        fig = plt.figure(figsize=(6.5, 5.5))
        ax = fig.add_subplot(projection="3d")
    P = scene.points @ scene.R.T + scene.t
    ax.scatter(*P[~scene.gross].T, s=4, c="C0", label="feature points (matched)")
    ax.scatter(*P[scene.gross].T, s=8, c="C3", marker="x", label="gross errors")
    _frame(ax, np.zeros(3), np.eye(3), 1.5, "c", "k")
    _frame(ax, scene.t, scene.R, 1.0, "t", "k")
    ax.plot(*np.column_stack([np.zeros(3), scene.t]), "k:", lw=0.8)
    # field of view through the extreme image points
    half = np.abs(P[:, :2] / P[:, 2:]).max(axis=0) * 1.1
    corners = np.array([[sx * half[0], sy * half[1], 1.0] for sx, sy in
                        ((1, 1), (-1, 1), (-1, -1), (1, -1), (1, 1))]) * P[:, 2].max()
    for c in corners[:4]:
        ax.plot(*np.column_stack([np.zeros(3), c]), color="0.6", lw=0.6)
    ax.plot(*corners.T, color="0.6", lw=0.6)
    ax.set_xlabel("$x_c$ (m)")
    ax.set_ylabel("$y_c$ (m)")
    ax.set_zlabel("$z_c$ (m, optical axis)")
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_locator(MaxNLocator(4))
    ax.set_box_aspect((1, 1, 2.5))
    ax.view_init(elev=20, azim=-60)
    ax.legend(loc="upper left")
    ax.set_title("Camera frame c, target frame t, feature plane (§1, §3)")
    return ax


def plot_crlb_ellipsoid(C: np.ndarray, samples: np.ndarray | None = None, *,
                        block: str = "att", ax=None, n_sigma: float = 1.0):
    """1-σ ellipsoid of the position (m) or attitude (deg) block of a 6×6 CRLB, with samples.

    ``samples`` (m, 6) are Monte Carlo estimator errors ``(δt, δθ)`` drawn as dots; for an
    efficient estimator a share ``P(χ²₃ ≤ n_sigma²)`` falls inside (1-σ: 20 %, 2-σ: 74 %).
    """
    check_choice(block, "block", ["pos", "att"])
    C = np.asarray(C, float)
    if C.shape != (6, 6):
        raise ValueError(f"C must be 6×6, got {C.shape}")
    sl = slice(0, 3) if block == "pos" else slice(3, 6)
    scale = 1.0 if block == "pos" else np.degrees(1.0)
    S = C[sl, sl] * scale ** 2
    if ax is None:
        fig = plt.figure(figsize=(5.5, 5))
        ax = fig.add_subplot(projection="3d")
    w, V = np.linalg.eigh(S)
    uu, vv = np.meshgrid(np.linspace(0, 2 * np.pi, 30), np.linspace(0, np.pi, 16))
    sph = np.stack([np.cos(uu) * np.sin(vv), np.sin(uu) * np.sin(vv), np.cos(vv)], -1)
    E = n_sigma * sph @ (V * np.sqrt(w)).T
    ax.plot_wireframe(E[..., 0], E[..., 1], E[..., 2], color="C1", lw=0.5, alpha=0.7)
    if samples is not None:
        s = np.asarray(samples, float)[:, sl] * scale
        ax.scatter(*s.T, s=4, c="C0", alpha=0.6, label=f"ML estimates ({len(s)} draws)")
        ax.legend(loc="upper left")
    unit = "m" if block == "pos" else "deg"
    names = ((r"$\delta t_x$", r"$\delta t_y$", r"$\delta t_z$") if block == "pos" else
             (r"$\delta\theta_x$", r"$\delta\theta_y$", r"$\delta\theta_z$"))
    for setter, nm in zip((ax.set_xlabel, ax.set_ylabel, ax.set_zlabel), names):
        setter(f"{nm} ({unit})")
    from matplotlib.ticker import MaxNLocator

    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):  # 3-D tick labels run into each other
        axis.set_major_locator(MaxNLocator(4))
    ax.set_title(f"{n_sigma:g}-σ CRLB ellipsoid, {'position' if block == 'pos' else 'attitude'}")
    return ax


def plot_efficiency(df: pd.DataFrame, ax=None):
    """RMS error / CRLB for each estimator versus the noise unit."""
    ax = get_ax(ax)
    for j, (name, g) in enumerate(df.groupby("estimator", sort=False)):
        x = g["noise unit (mm)"].to_numpy() * 1.08 ** (j - 1)  # small offsets: no overlap
        line = ax.loglog(x, g["att RMS / CRLB"], "o-", label=f"{name}: attitude")[0]
        ax.loglog(x, g["pos RMS / CRLB"], "s--", color=line.get_color(),
                  label=f"{name}: position")
    ax.axhline(1.0, color="k", lw=0.8, label="ratio 1: at the CRLB")
    log_axis(ax, "both")
    ax.set_xlabel("noise unit (mm): 1 = as printed, 0.01 = 10 µm pixel")
    ax.set_ylabel("RMS error / √CRLB")
    legend_outside(ax, where="below", ncol=2)
    ax.set_title("Estimator efficiency")
    return ax


def plot_budget(df: pd.DataFrame, ax=None):
    """Median attitude error versus k for greedy D/A-optimal and random subsets."""
    ax = get_ax(ax)
    for method, g in df.groupby("method"):
        ax.loglog(g["k"], g["att_median_deg"], "o-", label=method)
    log_axis(ax, "both")
    ax.set_xlabel("number of points k")
    ax.set_ylabel("median attitude error (deg)")
    ax.set_title("Budgeted selection: best k points vs random k (pixel reading)")
    ax.legend()
    return ax
