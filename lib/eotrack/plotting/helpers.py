"""Shared figure helpers of the house style: axes, labels, legends, log axes, paper values."""

from __future__ import annotations

import importlib
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from .style import method_style

__all__ = [
    "LINT_MIMETYPE",
    "describe_figure",
    "figure_lint_record",
    "get_ax",
    "label_axes",
    "legend_outside",
    "log_axis",
    "paper_marker",
    "paper_values",
    "plain_number",
    "register_figure_descriptions",
    "savefig",
]


def get_ax(ax: plt.Axes | None = None, **fig_kw: Any) -> plt.Axes:
    """Return ``ax`` or a new axes in a new figure (``fig_kw`` go to ``plt.subplots``)."""
    if ax is not None:
        return ax
    _, ax = plt.subplots(**fig_kw)
    return ax


def _with_unit(text: str | None, unit: str | None) -> str | None:
    if text is None:
        return None
    return f"{text} ({unit})" if unit else text


def label_axes(ax: plt.Axes, x: str | None = None, y: str | None = None, *,
               xunit: str | None = None, yunit: str | None = None, title: str | None = None,
               z: str | None = None, zunit: str | None = None) -> plt.Axes:
    """Label the axes as ``"quantity (unit)"`` and set the title; ``None`` leaves a part alone.

    Symbols go in mathtext: ``label_axes(ax, x=r"time $t_i$", xunit="s", y=r"$P_\\mathrm{FA}$")``.
    A dimensionless quantity takes no unit (a count, a probability, a ratio).

    Raises
    ------
    TypeError
        If ``ax`` is not a matplotlib Axes or a given label is not a string.
    """
    if not isinstance(ax, plt.Axes):
        raise TypeError(f"ax must be a matplotlib Axes, got {type(ax).__name__}")
    for nm, v in (("x", x), ("y", y), ("z", z), ("xunit", xunit), ("yunit", yunit),
                  ("zunit", zunit), ("title", title)):
        if v is not None and not isinstance(v, str):
            raise TypeError(f"{nm} must be a string or None, got {type(v).__name__}")
    if x is not None:
        ax.set_xlabel(_with_unit(x, xunit))
    if y is not None:
        ax.set_ylabel(_with_unit(y, yunit))
    if z is not None:
        if not hasattr(ax, "set_zlabel"):
            raise TypeError("z is given but ax is not a 3-D axes")
        ax.set_zlabel(_with_unit(z, zunit))
    if title is not None:
        ax.set_title(title)
    return ax


_WHERE = {
    # where → (loc of the legend box, anchor point in axes/figure fraction)
    "right": ("upper left", (1.02, 1.0)),
    "below": ("upper center", (0.5, -0.16)),
    "above": ("lower center", (0.5, 1.02)),
}


def legend_outside(target: plt.Axes | plt.Figure, *, where: str = "right",
                   ncol: int | None = None, handles: Sequence[Any] | None = None,
                   labels: Sequence[str] | None = None, **kw: Any) -> Any:
    """A legend off the data: beside or below an axes, or one shared legend for a figure.

    For a figure, the handles of all its axes are gathered (one entry per label), so a
    multi-panel figure gets a single legend instead of one per panel.

    Parameters
    ----------
    target : Axes or Figure
        Where the legend belongs.
    where : {"right", "below", "above"}
        Side of the axes (or figure) it goes on.
    ncol : int, optional
        Columns; default 1 on the right, up to 4 below/above.
    handles, labels : optional
        Explicit entries (default: every labelled artist).
    **kw
        Passed on to ``legend``.

    Returns
    -------
    matplotlib.legend.Legend or None
        ``None`` when there is nothing to put in a legend.

    Raises
    ------
    ValueError
        If ``where`` is not one of the allowed sides.
    TypeError
        If ``target`` is neither an Axes nor a Figure.
    """
    if where not in _WHERE:
        raise ValueError(f"where must be one of {sorted(_WHERE)}, got {where!r}")
    if isinstance(target, plt.Axes):
        axes = [target]
    elif isinstance(target, plt.Figure):
        axes = target.axes
    else:
        raise TypeError(f"target must be a matplotlib Axes or Figure, got {type(target).__name__}")
    if handles is None:
        seen: dict[str, Any] = {}
        for a in axes:
            for h, lab in zip(*a.get_legend_handles_labels(), strict=True):
                seen.setdefault(lab, h)
        labels = list(seen)
        handles = list(seen.values())
    elif labels is None:
        labels = [h.get_label() for h in handles]
    if not handles:
        return None
    loc, anchor = _WHERE[where]
    if ncol is None:
        ncol = 1 if where == "right" else min(4, len(handles))
    if isinstance(target, plt.Figure):
        for a in axes:
            if a.get_legend() is not None:
                a.get_legend().remove()
        fig_anchor = {"right": (1.0, 0.95), "below": (0.5, 0.0), "above": (0.5, 1.0)}[where]
        fig_loc = {"right": "upper left", "below": "upper center", "above": "lower center"}[where]
        return target.legend(handles, labels, loc=fig_loc, bbox_to_anchor=fig_anchor,
                             ncol=ncol, **kw)
    return target.legend(handles, labels, loc=loc, bbox_to_anchor=anchor, ncol=ncol,
                         borderaxespad=0.0, **kw)


def plain_number(v: float, _pos: Any = None) -> str:
    """A tick value as a plain number: ``0.01``, ``1``, ``20``, ``1000`` (no ``2×10⁰``)."""
    if not np.isfinite(v):
        return ""
    if v == 0:
        return "0"
    if abs(v) >= 1e5 or abs(v) < 1e-4:
        e = int(np.floor(np.log10(abs(v)) + 1e-9))
        m = v / 10 ** e
        return f"$10^{{{e}}}$" if np.isclose(m, 1) else f"${m:g}\\times10^{{{e}}}$"
    return f"{v:.6g}"


def log_axis(ax: plt.Axes, which: str = "y", *, minor_labels: bool | None = None) -> plt.Axes:
    """Put ``which`` (``"x"``, ``"y"`` or ``"both"``) on a log scale with plain decade labels.

    Decades are labelled ``0.1, 1, 10, 100``; minor ticks are drawn unlabelled, except on an
    axis spanning less than about one decade, where 2 and 5 of each decade are labelled too
    (``minor_labels`` forces either). Call it after the data are drawn.

    Raises
    ------
    ValueError
        If ``which`` is not ``"x"``, ``"y"`` or ``"both"``.
    """
    if which not in ("x", "y", "both"):
        raise ValueError(f"which must be 'x', 'y' or 'both', got {which!r}")
    for name in ("x", "y") if which == "both" else (which,):
        axis = ax.xaxis if name == "x" else ax.yaxis
        (ax.set_xscale if name == "x" else ax.set_yscale)("log")
        axis.set_major_locator(LogLocator(base=10))
        axis.set_major_formatter(FuncFormatter(plain_number))
        lo, hi = (ax.get_xlim() if name == "x" else ax.get_ylim())
        lo, hi = sorted((abs(lo) or 1e-12, abs(hi) or 1e-12))
        short = np.log10(hi / lo) < 1.3 if minor_labels is None else minor_labels
        axis.set_minor_locator(LogLocator(base=10, subs=(2.0, 5.0) if short else
                                          tuple(np.arange(2, 10)), numticks=12))
        axis.set_minor_formatter(FuncFormatter(plain_number) if short else NullFormatter())
    return ax


def paper_values(ax: plt.Axes, x: Any, y: Any, *, kind: str = "marker", label: str = "paper",
                 width: float | None = None, yerr: Any = None, **kw: Any) -> Any:
    """Draw the paper's values beside ours in the one paper style (black, hollow).

    Parameters
    ----------
    ax : Axes
        Where our values are drawn.
    x, y : array-like
        ``kind="marker"``: positions and values (hollow black diamonds, error bars if
        ``yerr``); ``kind="bar"``: bar positions and heights (hollow hatched black bars of
        ``width``, place them beside ours by offsetting ``x``); ``kind="hline"``: ``y`` a value
        or a sequence of values (dashed black horizontal lines; ``x`` ignored, pass ``None``);
        ``kind="band"``: ``y = (low, high)`` a shaded horizontal band.
    kind : {"marker", "bar", "hline", "band"}
    label : str
        Legend entry (``"paper"``, ``"paper, Table 2"``).
    width : float, optional
        Bar width for ``kind="bar"`` (default 0.35).
    yerr : array-like, optional
        Error bars for ``kind="marker"``.
    **kw
        Passed on to the matplotlib call.

    Returns
    -------
    The artist(s) drawn.

    Raises
    ------
    ValueError
        If ``kind`` is unknown or the values have mismatched or empty shapes.
    """
    style = method_style("paper")
    if kind == "hline":
        vals = np.atleast_1d(np.asarray(y, dtype=float))
        if vals.size == 0:
            raise ValueError("y must hold at least one paper value")
        out = []
        for i, v in enumerate(vals):
            out.append(ax.axhline(v, color=style.color, ls="--", lw=1.2,
                                  label=label if i == 0 else "_nolegend_", **kw))
        return out
    if kind == "band":
        lo, hi = np.asarray(y, dtype=float).ravel()[:2] if np.size(y) == 2 else (None, None)
        if lo is None:
            raise ValueError(f"kind='band' needs y=(low, high), got {y!r}")
        return ax.axhspan(lo, hi, color="0.5", alpha=0.18, lw=0, label=label, zorder=0, **kw)
    xa = np.atleast_1d(np.asarray(x))
    ya = np.atleast_1d(np.asarray(y, dtype=float))
    if xa.shape != ya.shape or ya.size == 0:
        raise ValueError(f"x and y must have the same non-empty shape, got {xa.shape} and "
                         f"{ya.shape}")
    if kind == "marker":
        kws = {"marker": style.marker, "mfc": "none", "mec": style.color, "ecolor": style.color,
               "ls": "none", "ms": 7, "mew": 1.4, "zorder": 5, **kw}
        return ax.errorbar(xa, ya, yerr=yerr, label=label, **kws)
    if kind == "bar":
        kws = {"facecolor": "white", "edgecolor": style.color, "hatch": "///", "lw": 1.0, **kw}
        return ax.bar(xa, ya, width if width is not None else 0.35, label=label, **kws)
    raise ValueError(f"kind must be 'marker', 'bar', 'hline' or 'band', got {kind!r}")


def paper_marker(ax: plt.Axes, x: Sequence[float], y: Sequence[float], *,
                 label: str = "paper", **kw: Any) -> Any:
    """Plot the paper's values as hollow black markers on ``ax`` (as ``paper_values``, kept for
    the figures written before it; returns the lines of ``ax.plot``)."""
    style = method_style("paper")
    kw = {"marker": style.marker, "mfc": "none", "mec": style.color, "ls": "none", "ms": 7,
          "mew": 1.4, **kw}
    return ax.plot(np.asarray(x), np.asarray(y), label=label, **kw)


def savefig(fig: plt.Figure, path: str | Path, *, dpi: int = 110) -> Path:
    """Save ``fig`` to ``path`` (parents created) with a tight box and return the path."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(p, dpi=dpi, bbox_inches="tight")
    return p


def describe_figure(fig: Any) -> str:
    """A one-line description of a figure from its titles, for alt text:
    ``"Figure: <suptitle> — <panel title>; <panel title>"`` (``"Figure"`` if untitled).

    Raises
    ------
    TypeError
        If ``fig`` is not a matplotlib Figure.
    """
    from matplotlib.figure import Figure

    if not isinstance(fig, Figure):
        raise TypeError(f"fig must be a matplotlib Figure, got {type(fig).__name__}")
    sup = fig._suptitle.get_text().strip() if fig._suptitle is not None else ""
    panels = []
    for ax in fig.axes:
        t = " ".join(ax.get_title(loc=k) for k in ("left", "center", "right")).strip()
        if t and t not in panels:
            panels.append(t)
    text = " — ".join(p for p in (sup, "; ".join(panels)) if p).replace("\n", " ")
    return f"Figure: {text}" if text else "Figure"


#: The output type under which a notebook stores the figure lint's verdict on each figure it
#: shows (``{"problems": [[rule, message], ...]}``); ``tests/figures`` reads it from the stored
#: notebooks. Viewers that do not know it (JupyterLab, the book) show the PNG as before.
LINT_MIMETYPE = "application/vnd.eotrack.figure-lint+json"


def figure_lint_record(fig: Any) -> dict:
    """The lint's verdict on ``fig`` as stored with a notebook's figure output:
    ``{"problems": [[rule, message], ...], "lint": LINT_VERSION, "png_px": [w, h]}`` (empty
    list: the figure passes; ``lint`` names the rules' version; ``png_px`` the size of the PNG
    the inline backend stores — ``bbox_inches="tight"`` at the figure's dpi — so the test can
    tell that the record belongs to the image beside it). The figure is linted as saved with
    the tight box. A lint that itself fails is recorded as the problem ``"lint-error"``."""
    import matplotlib as mpl

    from .lint import LINT_VERSION, _figure_of, _shown_area, lint_figure

    size = None
    try:
        problems = [[p.rule, p.message] for p in lint_figure(fig, bbox="tight")]
        f = _figure_of(fig)
        with mpl.rc_context({"savefig.bbox": "tight"}):
            area = _shown_area(f, f.canvas.get_renderer())
        size = [round(area.width), round(area.height)]
    except Exception as exc:  # the record must not break the notebook's output
        problems = [["lint-error", f"{type(exc).__name__}: {exc}"]]
    return {"problems": problems, "lint": LINT_VERSION, "png_px": size}


def register_figure_descriptions() -> bool:
    """In an IPython kernel, make a figure's plain-text output its :func:`describe_figure`
    (instead of ``<Figure size 640x480 with 1 Axes>``), so a stored notebook carries each
    figure's titles and the book uses them as the image's alt text; and store with every
    figure shown the figure lint's verdict (:func:`figure_lint_record`, output type
    :data:`LINT_MIMETYPE`), so the lint checks the notebooks' own figures as stored. Returns
    whether a kernel was found (outside IPython nothing happens)."""
    try:
        from IPython import get_ipython
    except ImportError:
        return False
    ip = get_ipython()
    if ip is None:
        return False
    import matplotlib
    from IPython.core.formatters import JSONFormatter
    from matplotlib.figure import Figure

    # load the backend first: loading the inline backend removes every formatter of Figure
    # (matplotlib_inline's select_figure_formats), so ours are registered after it
    backend = matplotlib.get_backend()
    if backend.startswith("module://"):
        importlib.import_module(backend.removeprefix("module://"))

    ip.display_formatter.formatters["text/plain"].for_type(
        Figure, lambda fig, p, cycle: p.text(describe_figure(fig)))
    formatters = ip.display_formatter.formatters
    if LINT_MIMETYPE not in formatters:
        lint_fmt = JSONFormatter(parent=ip.display_formatter)
        lint_fmt.format_type = LINT_MIMETYPE
        formatters[LINT_MIMETYPE] = lint_fmt
    formatters[LINT_MIMETYPE].for_type(Figure, figure_lint_record)
    return True
