"""Figures of the WRANSAC notebook and report: one function per figure, ``ax=None`` → new axes."""

from __future__ import annotations

import itertools

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.patches import FancyArrowPatch, FancyBboxPatch
from matplotlib.ticker import FuncFormatter, NullLocator

from eotrack.plotting import (
    get_ax,
    label_axes,
    legend_outside,
    log_axis,
    method_style,
    paper_marker,
    series_styles,
)
from eotrack.robust import (
    min_samples_real,
    msac_loss,
    sinusoidal_loss,
    sinusoidal_loss_as_printed,
    zero_one_loss,
)
from eotrack.validation import check_choice

from .scenario import COORDS, Scenario
from .trials import PredictionResults

__all__ = [
    "METHOD_LABELS",
    "plot_budget",
    "plot_eclipse_season",
    "plot_error_distribution",
    "plot_flowchart",
    "plot_generalisation",
    "plot_inlier_histograms",
    "plot_leverage",
    "plot_losses",
    "plot_min_samples",
    "plot_prediction",
    "plot_pull",
    "plot_ratio_table",
    "plot_threshold_sensitivity",
]

METHOD_LABELS = {
    "sin": "sin (free-ω sinusoid)", "lsq": "LSQ", "ransac": "RANSAC",
    "wransac": "WRANSAC", "wransac_hypothesis": "WRANSAC (hypothesis weights)",
    "wransac_refit": "WRANSAC (refit weights, 1 step)",
    "wransac_iterated": "WRANSAC (iterated weights)", "ideal": "ideal: OLS on true inliers",
    "msac": "MSAC", "huber": "Huber from LSQ", "soft_l1": "soft-L1 from LSQ",
    "huber_ransac": "Huber from RANSAC", "cauchy_ransac": "Cauchy from RANSAC",
    "orbit": "orbit fit (Gauss IOD + Cauchy LSQ)",
}
#: shorter names where a legend must fit the book's column (the long ones in the text)
_SHORT_LABELS = {"orbit": "orbit fit (IOD + Cauchy)", "wransac_refit": "WRANSAC (refit, 1 step)"}


def _styles(names: list[str]) -> list:
    """House style per method name; names without one get distinct series styles."""
    spare = iter(series_styles(len(names) + 8)[8:])
    out = []
    for n in names:
        try:
            out.append(method_style(n))
        except KeyError:
            out.append(next(spare))
    return out


def plot_min_samples(confidence: float = 0.99, sample_sizes=(4, 7, 8), *, paper: dict | None = None,
                     ax: plt.Axes | None = None) -> plt.Axes:
    """Fig. 1: U versus outlier ratio ε (eq. 2), log scale."""
    ax = get_ax(ax)
    eps = np.linspace(0.0, 0.6, 121)
    for m in sample_sizes:
        ax.plot(eps, [min_samples_real(confidence, e, m) for e in eps], label=f"m = {m}")
    if paper is not None:
        paper_marker(ax, paper["check_outlier_ratios"], paper["check_values_m4"],
                     label="paper check values (m = 4)")
    ax.set_yscale("log")
    ax.set(xlabel="outlier ratio ε", ylabel="minimum number of samples U",
           title=f"Fig. 1 — U versus ε (P = {confidence})")
    ax.legend()
    return ax


def plot_losses(t: float = 1.0, *, ax: plt.Axes | None = None) -> plt.Axes:
    """Fig. 2: L_R, L_M (linear and squared), L_s corrected and as printed."""
    ax = get_ax(ax)
    e = np.linspace(-1.5 * t, 1.5 * t, 601)
    ax.plot(e, zero_one_loss(e, t), label="$L_R$ (0-1), eq. 4")
    ax.plot(e, msac_loss(e, t), label="$L_M$ = |e|/t, eq. 5")
    ax.plot(e, msac_loss(e, t, "squared"), ls=":", label="usual MSAC e²/t²")
    ax.plot(e, sinusoidal_loss(e, t), lw=2.2, label="$L_s$ corrected: ½ − ½cos(πe/t)")
    ax.plot(e, sinusoidal_loss_as_printed(e, t), ls="--", label="$L_s$ as printed (erratum)")
    label_axes(ax, x="error $e/t$", y="loss $L(e)$", title="Fig. 2 — loss functions")
    legend_outside(ax, where="below", ncol=2)
    return ax


def plot_flowchart(*, ax: plt.Axes | None = None) -> plt.Axes:
    """Fig. 3: the WRANSAC flowchart, drawn from the steps of :func:`eotrack.robust.ransac`."""
    ax = get_ax(ax, figsize=(6.5, 7.2))
    steps = [
        ("start", r"observations $(t_i, y_i)$, threshold $t = 3\sigma$, budget $U$ (eq. 2)"),
        ("box", r"draw a minimal sample of $m = 4$ points"),
        ("box", r"solve $y = a\,\sin\omega t + b\,\cos\omega t + c + d\,t$ exactly"),
        ("box", r"cost $J = \Sigma_i\, L_s(e_i)$ over ALL data (eq. 3, eq. 6 corrected)"),
        ("diamond", r"$J <$ best $J$ so far?"),
        ("box", r"keep: best inlier set $\{|e_i| \leq t\}$, its residuals"),
        ("diamond", r"$U$ samples drawn?"),
        ("box", r"weights $w_i = 1 - L_s(e_i)$ on the best inlier set"),
        ("box", r"weighted refit: $\theta = \arg\min\, \Sigma_i\, w_i (y_i - a_i^\top\theta)^2$"),
        ("start", r"predict $y(t)$ for 15 / 30 / 72 min"),
    ]
    ys = np.linspace(0.95, 0.05, len(steps))
    half, pad, x0, x1 = 0.025, 0.012, 0.14, 0.86  # box half-height, padding, left/right edge
    top, bottom, left, right = half + pad, -(half + pad), x0 - pad, x1 + pad
    for (kind, text), y in zip(steps, ys, strict=True):
        style = {"start": f"round,pad={pad}", "box": f"square,pad={pad}",
                 "diamond": f"round4,pad={pad}"}[kind]
        color = {"start": "#dbe9f6", "box": "#f2f2f2", "diamond": "#fde9c9"}[kind]
        ax.add_patch(FancyBboxPatch((x0, y - half), x1 - x0, 2 * half, boxstyle=style, fc=color,
                                    ec="k", lw=0.8, transform=ax.transAxes))
        ax.text(0.5, y, text, ha="center", va="center", fontsize=9, transform=ax.transAxes)
    arrow = {"arrowstyle": "-|>", "mutation_scale": 10, "transform": ax.transAxes, "color": "k",
             "shrinkA": 0, "shrinkB": 0}
    for y0, y1 in itertools.pairwise(ys):
        ax.add_patch(FancyArrowPatch((0.5, y0 + bottom), (0.5, y1 + top), **arrow))
    # "no" branches, edge to edge: J not better → skip the update (to the U test); not all U
    # drawn → back to sampling
    ax.add_patch(FancyArrowPatch((right, ys[4]), (right, ys[6]),
                                 connectionstyle="bar,fraction=-0.3", **arrow))
    ax.text(right + 0.01, ys[4] + 0.012, "no", fontsize=9, ha="left", va="bottom",
            transform=ax.transAxes)
    ax.add_patch(FancyArrowPatch((left, ys[6]), (left, ys[1]),
                                 connectionstyle="bar,fraction=-0.18", **arrow))
    ax.text(left - 0.01, ys[6] - 0.012, "no: next sample", fontsize=9, ha="right", va="top",
            transform=ax.transAxes)
    for k in (4, 6):
        ax.text(0.52, (ys[k] + ys[k + 1]) / 2, "yes", fontsize=9, va="center",
                transform=ax.transAxes)
    ax.set_axis_off()
    ax.set_title("Fig. 3 — WRANSAC flowchart (steps of eotrack.robust.ransac)")
    return ax


def plot_inlier_histograms(res: PredictionResults, *, axes=None):
    """Figs. 4–5: histograms of the WRANSAC inliers' loss values and weights (all runs)."""
    if axes is None:
        _, axes = plt.subplots(1, 2, figsize=(9, 3.4))
    loss = np.concatenate(res.inlier_loss)
    w = np.concatenate(res.inlier_weight)
    bins = np.linspace(0, 1, 21)
    axes[0].hist(loss, bins=bins, color="C1", edgecolor="k")
    axes[0].set(xlabel="$L_s(e)$ of inliers", ylabel="count",
                title="Fig. 4 — inlier cost values")
    axes[1].hist(w, bins=bins, color="C2", edgecolor="k")
    axes[1].set(xlabel="weight w = 1 − $L_s$", ylabel="count", title="Fig. 5 — inlier weights")
    return axes


def plot_prediction(res: PredictionResults, run: int = 0, coord: str = "dec",
                    methods: tuple[str, ...] = ("sin", "lsq", "ransac", "wransac", "ideal"), *,
                    ax: plt.Axes | None = None) -> plt.Axes:
    """Fig. 6: observations, the true track and each method's 72-min prediction for one run."""
    ax = get_ax(ax, figsize=(7.5, 4))
    ci = COORDS.index(check_choice(coord, "coord", COORDS))
    sc = res.scenario
    tmin = (np.r_[sc.t_obs_s, sc.t_pred_s] - sc.t_obs_s[-1]) / 60.0
    n = len(sc.t_obs_s)
    if run == 0:
        ax.plot(tmin[:n], res.first_obs[ci], ".", color="0.5", ms=4, label="observations (run 0)")
    ax.plot(tmin, np.r_[sc.truth_obs[ci], sc.truth_pred[ci]], "k-", lw=1,
            label="true track (SGP4)")
    for m in methods:
        if m in res.methods:
            ln, = ax.plot(tmin[n:], sc.truth_pred[ci] + res.errors[run, res.methods.index(m), ci],
                          label=METHOD_LABELS.get(m, m))
            if ln.get_linestyle() not in ("-", "solid"):
                ln.set_zorder(2.5)  # dashed over solid: a prediction equal to another shows
    ax.axvspan(0, tmin[-1], color="0.9", zorder=-1)
    lo, hi = np.percentile(np.r_[sc.truth_obs[ci], sc.truth_pred[ci]], [0, 100])
    pad = 0.3 * (hi - lo) + 60
    ax.set_ylim(lo - pad, hi + pad)
    ax.set(xlabel="minutes after the last observation",
           ylabel=f"{'Dec' if coord == 'dec' else 'RA − sidereal'} (arcsec)",
           title=f"Fig. 6 — 72-min prediction (run {run})")
    ax.legend(fontsize=8, ncol=2)
    return ax


def plot_error_distribution(res: PredictionResults, coord: str = "dec", *,
                            bound: float | None = None,
                            methods: tuple[str, ...] = ("ransac", "wransac", "ideal"),
                            ax: plt.Axes | None = None) -> plt.Axes:
    """Fig. 7: prediction error versus time ahead, all runs (median and 5–95 % band)."""
    ax = get_ax(ax, figsize=(7.5, 4))
    ci = COORDS.index(check_choice(coord, "coord", COORDS))
    sc = res.scenario
    tm = (sc.t_pred_s - sc.t_obs_s[-1]) / 60.0
    for k, m in enumerate(m for m in methods if m in res.methods):
        e = res.errors[:, res.methods.index(m), ci]
        lo, med, hi = np.percentile(e, [5, 50, 95], axis=0)
        ax.plot(tm, med, label=METHOD_LABELS.get(m, m), color=f"C{k}")
        ax.fill_between(tm, lo, hi, color=f"C{k}", alpha=0.15)
    if bound is not None:
        ax.axhline(bound, ls="--", c="k", lw=0.8, label=f"paper's ±{bound:g}″")
        ax.axhline(-bound, ls="--", c="k", lw=0.8)
    ax.set(xlabel="minutes ahead", ylabel="prediction error (arcsec)",
           title=f"Fig. 7 — prediction error (median, 5–95 % of {res.n_runs} runs)")
    ax.legend(fontsize=8, ncol=2)
    return ax


def plot_pull(res: PredictionResults, coord: str = "dec", at_min: float = 72.0, *,
              ax: plt.Axes | None = None) -> plt.Axes:
    """The mechanism: WRANSAC − RANSAC against best hypothesis − RANSAC, one dot per run."""
    from .tables import pull_statistics

    ax = get_ax(ax, figsize=(5.5, 4.5))
    ci = COORDS.index(check_choice(coord, "coord", COORDS))
    st = pull_statistics(res, coord, at_min)
    dt = res.scenario.t_pred_s - res.scenario.t_obs_s[-1]
    j = int(np.argmin(np.abs(dt - at_min * 60.0)))
    meth = "wransac_hypothesis" if "wransac_hypothesis" in res.methods else "wransac"
    r = res.errors[:, res.methods.index("ransac"), ci, j]
    x = res.hyp_errors[:, ci, j] - r
    y = res.errors[:, res.methods.index(meth), ci, j] - r
    ax.plot(x, y, ".", alpha=0.6, label="runs")
    xs = np.array([x.min(), x.max()])
    ax.plot(xs, st["slope"] * xs, "C3-", label=f"slope {st['slope']:.2f}, corr {st['corr']:.2f}")
    ax.plot(xs, xs, "k:", lw=0.8, label="all the way to the hypothesis")
    ax.axhline(0, c="0.6", lw=0.6)
    ax.set(xlabel=f"best 4-point hypothesis − RANSAC at +{st['minutes_ahead']:.0f} min (″)",
           ylabel="WRANSAC − RANSAC (″)",
           title="The pull toward the hypothesis (weights from its residuals)")
    ax.legend(fontsize=8)
    return ax


def plot_leverage(res: PredictionResults, coord: str = "dec", *,
                  ax: plt.Axes | None = None) -> plt.Axes:
    """Gauss–Markov prediction spread of OLS on the true inliers versus minutes ahead."""
    ax = get_ax(ax, figsize=(6, 3.8))
    ci = COORDS.index(check_choice(coord, "coord", COORDS))
    sc = res.scenario
    tm = (sc.t_pred_s - sc.t_obs_s[-1]) / 60.0
    gm = np.sqrt(np.mean(res.gm_sd[:, ci] ** 2, axis=0))
    ax.plot(tm, gm, "k-", label=r"Gauss–Markov / Cramér–Rao $\sigma_\mathrm{pred}$")
    for k, m in enumerate(x for x in ("ransac", "wransac", "ideal") if x in res.methods):
        ax.plot(tm, res.errors[:, res.methods.index(m), ci].std(axis=0), color=f"C{k}",
                label=f"{METHOD_LABELS.get(m, m)} (measured)")
    ax.set(xlabel="minutes ahead", ylabel="prediction error sd (arcsec)",
           title="Extrapolation leverage: noise amplification with horizon")
    ax.legend(fontsize=8)
    return ax


def plot_ratio_table(table: pd.DataFrame, coord: str = "dec", *,
                     ax: plt.Axes | None = None) -> plt.Axes:
    """Forest plot of the variance ratios to RANSAC with their 95 % intervals."""
    ax = get_ax(ax, figsize=(7, 3.8))
    sub = table.xs(coord, level="coordinate")
    labels = [f"{str(n).split()[0]} · {str(m).replace('WRANSAC, weights from ', '')}"
              for n, m in sub.index]
    y = np.arange(len(sub))[::-1]
    r = sub["var ratio to RANSAC"].to_numpy()
    err = np.stack([r - sub["95 % lo"].to_numpy(), sub["95 % hi"].to_numpy() - r])
    ax.errorbar(r, y, xerr=err, fmt="o", capsize=3)
    ax.axvline(1.0, c="k", lw=0.8, label="ratio 1: as RANSAC")
    ax.set_yticks(y, labels)
    ax.set_xscale("log")
    log_axis(ax, "x")
    label_axes(ax, x="variance ratio to RANSAC (72 min, paired, 95 % bootstrap)",
               y="noise · WRANSAC reading",
               title=f"Which reading × noise gives the paper's ordering? ({coord})")
    legend_outside(ax, where="below")
    return ax


def plot_budget(errors: np.ndarray, budgets: tuple[int, ...], methods: tuple[str, ...],
                budget: int, show: tuple[str, ...], *, bound: float = 27.0,
                ax: plt.Axes | None = None) -> plt.Axes:
    """Worst 72-min Dec error per run for the chosen U and methods (box plot, log scale)."""
    ax = get_ax(ax, figsize=(7.5, 4))
    if budget not in budgets:
        raise ValueError(f"budget must be one of {list(budgets)}, got {budget}")
    bi = list(budgets).index(budget)
    show = [m for m in show if m in methods]
    worst = np.abs(errors[:, bi]).max(axis=-1)  # runs, methods
    data = [worst[:, methods.index(m)] for m in show]
    if data:
        ax.boxplot(data, whis=(5, 95), showfliers=True, flierprops={"ms": 3})
        ax.set_xticks(range(1, len(show) + 1),
                      [f"{METHOD_LABELS.get(m, m)}\n{np.mean(d <= bound):.0%} ≤ {bound:g}″"
                       for m, d in zip(show, data, strict=True)], fontsize=8.5, rotation=20,
                      ha="right", rotation_mode="anchor")
    ax.axhline(bound, ls="--", c="k", lw=0.8)
    ax.annotate(f"bound {bound:g}″", (1.0, bound), xycoords=("axes fraction", "data"),
                xytext=(-3, 3), textcoords="offset points", ha="right", va="bottom",
                fontsize=9)
    ax.set_yscale("log")
    # plain decade labels, no minor ticks, a fixed title place: the Explore panel redraws
    # this figure on every change, and mathtext labels, minor ticks and the automatic title
    # placement were most of its cost
    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.yaxis.set_minor_locator(NullLocator())
    ax.set_ylabel("worst |Dec error| over 72 min (″)")
    ax.set_xlabel("method (share of runs within the bound)")
    ax.set_title(f"U = {budget} hypotheses, {errors.shape[0]} runs per method (fewer than "
                 "the main run: a side study)", y=1.01)
    return ax


def plot_threshold_sensitivity(df: pd.DataFrame, *, ax: plt.Axes | None = None) -> plt.Axes:
    """RMS 72-min error versus t/σ per loss."""
    ax = get_ax(ax)
    names = {"zero_one": "ransac", "msac": "msac", "msac_squared": "quadratic scoring",
             "sinusoidal": "sinusoidal"}
    keys = ["wransac" if "weighted" in c else names.get(c.split(" +")[0], c) for c in df.columns]
    for c, st in zip(df.columns, _styles(keys), strict=True):
        ax.plot(df.index, df[c], label=c.replace("L_s", "$L_s$"), **st.line())
    ax.set_yscale("log")
    log_axis(ax, "y")
    label_axes(ax, x="threshold $t/\\sigma$", y="median RMS 72-min Dec error", yunit="″",
               title="Threshold sensitivity: scoring loss and refit apart")
    legend_outside(ax, where="below", ncol=2)
    return ax


def plot_eclipse_season(sc: Scenario, *, ax: plt.Axes | None = None) -> plt.Axes:
    """Length of each Earth-shadow pass of the object over the searched span."""
    ax = get_ax(ax)
    d = sc.extra["eclipse_durations_min"]
    ax.bar(np.arange(len(d)), d, color="C0", label="shadow pass (ours)")
    ax.axhline(72, ls="--", c="k", lw=0.8, label="72 min (paper)")
    label_axes(ax, x="shadow pass (chronological index)", y="shadow duration", yunit="min",
               title=f"Earth-shadow passes of NORAD {sc.extra['norad_id']}")
    legend_outside(ax, where="right")
    return ax


#: Extra bar colours for methods whose house colours coincide (bars differ by colour, not by
#: hatch alone, so the figure reads in grey too).
_BAR_SPARE = ("#0072B2", "#882255", "#117733", "#999999", "#44AA99", "#332288", "#DDCC77")


def _bar_styles(names: list[str]) -> list:
    """House styles with a distinct colour per bar series (first user of a colour keeps it)."""
    from dataclasses import replace as _replace

    styles = _styles(names)
    used = set()
    spare = iter(c for c in _BAR_SPARE if c not in {st.color for st in styles})
    out = []
    for st in styles:
        if st.color in used:
            st = _replace(st, color=next(spare))
        used.add(st.color)
        out.append(st)
    return out


def _case_tick(label: str) -> str:
    """Tick label of a case: its NORAD id, starred where the object drifts."""
    words = str(label).replace("NORAD ", "").split()
    return words[0] + ("*" if "drifting" in str(label) else "")


def plot_generalisation(table: pd.DataFrame, *, ax: plt.Axes | None = None,
                        title: str = "Generalisation") -> plt.Axes:
    """Worst 72-min error per method and scenario (log scale); ticks: the case's NORAD id.

    Drifting cases are starred on their tick. With an ``"orbit"`` column, each drifting case
    also gets the orbit criterion's mark: 1/5 of the best sinusoid predictor's worst error
    (the orbit bar must reach below it).
    """
    ax = get_ax(ax, figsize=(8, 4))
    worst = table["worst"]
    x = np.arange(len(worst.index))
    k = len(worst.columns)
    for i, (m, st) in enumerate(zip(worst.columns, _bar_styles(list(worst.columns)), strict=True)):
        ax.bar(x + (i - k / 2 + 0.5) * 0.8 / k, worst[m], width=0.8 / k,
               label=_SHORT_LABELS.get(m, METHOD_LABELS.get(m, m)), **st.bar())
    ax.set_yscale("log")
    log_axis(ax, "y")
    ax.set_xticks(x, [_case_tick(c) for c in worst.index])
    ax.axhline(27, ls="--", c="k", lw=0.8, label="27″ (the paper's bound)")
    if "orbit" in worst.columns:
        sin_cols = [m for m in worst.columns if m not in ("orbit", "ideal")]
        first = True
        for xi, case in zip(x, worst.index, strict=True):
            if "drifting" in str(case) and sin_cols:
                ax.hlines(worst.loc[case, sin_cols].min() / 5.0, xi - 0.45, xi + 0.45,
                          colors="k", linestyles="-", lw=1.6,
                          label="criterion: 1/5 of the best sinusoid" if first else None)
                first = False
    label_axes(ax, x="object (NORAD id; * drifting)", y="worst |error| in 72 min", yunit="″",
               title=title)
    legend_outside(ax, where="below", ncol=3)  # below: the figure keeps the book's width
    return ax
