"""The figure lint: what a program can check of a figure's readability, from the drawn artists.

:func:`lint_figure` draws the figure once with the Agg renderer, records every text actually
drawn, and checks the rules listed in the package docstring. Each problem is a
:class:`FigureProblem` with a rule name, so a test can report counts per rule.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import PathCollection
from matplotlib.colors import to_rgba
from matplotlib.container import BarContainer
from matplotlib.figure import Figure
from matplotlib.image import AxesImage
from matplotlib.legend import Legend
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.text import Text

from .style import BOOK_WIDTH_IN, MIN_FONT_PT

__all__ = ["RULES", "FigureProblem", "effective_font_scale", "lint_figure"]

#: The lint's rules, in the order they are checked.
RULES = ("overlapping-text", "legend-covers-data", "axis-label", "small-text", "title",
         "same-style", "unkeyed-colours", "log-labels", "too-wide")

#: A figure is shown at no less than this share of its size in the book (the browser shrinks a
#: wider one to the column).
MIN_BOOK_SCALE = 0.8


@dataclass(frozen=True)
class FigureProblem:
    """One problem the lint found: ``rule`` (one of :data:`RULES`) and what, where."""

    rule: str
    message: str

    def __str__(self) -> str:
        return f"[{self.rule}] {self.message}"


def _is_colorbar(ax: Any) -> bool:
    return getattr(ax, "_colorbar", None) is not None or ax.get_label() == "<colorbar>"


def _data_axes(fig: Figure) -> list[Any]:
    return [a for a in fig.axes if a.get_visible() and not _is_colorbar(a)]


def effective_font_scale(fig: Figure, renderer: Any = None) -> float:
    """The factor from a font's nominal size to its size in the book: ``min(1, column /
    width)`` with the figure's width taken from its tight bounding box (as it is saved)."""
    if renderer is None:
        canvas = FigureCanvasAgg(fig) if fig.canvas is None else fig.canvas
        renderer = canvas.get_renderer() if hasattr(canvas, "get_renderer") else None
    width_in = saved_width_in(fig, renderer)
    return float(min(1.0, BOOK_WIDTH_IN / max(width_in, 1e-9)))


def saved_width_in(fig: Figure, renderer: Any) -> float:
    """The figure's width as saved (inches): its tight bounding box plus the padding
    ``savefig`` adds on both sides (``savefig.pad_inches``) when ``savefig.bbox`` is tight."""
    import matplotlib as mpl

    w = fig.get_tightbbox(renderer).width  # tight bbox is in inches
    if mpl.rcParams["savefig.bbox"] == "tight":
        pad = mpl.rcParams["savefig.pad_inches"]
        w += 2 * (float(pad) if pad != "layout" else 0.0)
    return float(w)


def _draw_recording(fig: Figure) -> tuple[Any, list[Text]]:
    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    renderer = canvas.get_renderer()
    drawn: dict[int, Text] = {}
    original = renderer.draw_text

    def record(gc, x, y, s, prop, angle, ismath=False, mtext=None):
        if mtext is not None and s.strip():
            drawn.setdefault(id(mtext), mtext)
        return original(gc, x, y, s, prop, angle, ismath=ismath, mtext=mtext)

    renderer.draw_text = record
    try:
        fig.draw(renderer)
    finally:
        del renderer.draw_text
    return renderer, list(drawn.values())


def _describe(t: Text) -> str:
    s = t.get_text().replace("\n", " ")
    return repr(s if len(s) <= 40 else s[:37] + "…")


def _rect(t: Text, renderer: Any) -> np.ndarray:
    """The text's rotated rectangle (4×2 display coordinates)."""
    bb = t.get_window_extent(renderer)
    angle = t.get_rotation() % 180
    c = np.array([(bb.x0 + bb.x1) / 2, (bb.y0 + bb.y1) / 2])
    if min(angle, 180 - angle) < 1 or abs(angle - 90) < 1:
        hw, hh = bb.width / 2, bb.height / 2
        return c + np.array([[-hw, -hh], [hw, -hh], [hw, hh], [-hw, hh]])
    rot = t.get_rotation()
    t.set_rotation(0)
    try:
        b0 = t.get_window_extent(renderer)
    finally:
        t.set_rotation(rot)
    th = np.radians(rot)
    R = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    hw, hh = b0.width / 2, b0.height / 2
    corners = np.array([[-hw, -hh], [hw, -hh], [hw, hh], [-hw, hh]])
    return c + corners @ R.T


def _overlap(p: np.ndarray, q: np.ndarray, tol: float = 1.0) -> bool:
    """Separating-axis test of two convex quadrilaterals, overlapping by more than ``tol`` px."""
    for poly in (p, q):
        for i in range(4):
            edge = poly[(i + 1) % 4] - poly[i]
            n = np.array([-edge[1], edge[0]])
            norm = np.hypot(*n)
            if norm == 0:
                continue
            n = n / norm
            a, b = p @ n, q @ n
            if min(a.max(), b.max()) - max(a.min(), b.min()) <= tol:
                return False
    return True


def _check_overlaps(texts: list[Text], renderer: Any) -> list[FigureProblem]:
    rects = [(t, _rect(t, renderer)) for t in texts]
    out = []
    for i, (t, p) in enumerate(rects):
        for u, q in rects[i + 1:]:
            if _overlap(p, q):
                out.append(FigureProblem("overlapping-text",
                                         f"{_describe(t)} overlaps {_describe(u)}"))
    return out


def _check_small(texts: list[Text], scale: float) -> list[FigureProblem]:
    out = []
    for t in texts:
        pt = t.get_fontsize() * scale
        if pt < MIN_FONT_PT - 1e-6:
            out.append(FigureProblem(
                "small-text", f"{_describe(t)} is {pt:.1f} pt at the book's width "
                f"({t.get_fontsize():g} pt nominal, figure scaled by {scale:.2f}); "
                f"minimum {MIN_FONT_PT:g} pt"))
    return out


def _title_of(ax: Any) -> str:
    return " ".join(ax.get_title(loc=loc) for loc in ("left", "center", "right")).strip()


def _check_titles(fig: Figure) -> list[FigureProblem]:
    axes = _data_axes(fig)
    sup = fig._suptitle.get_text().strip() if fig._suptitle is not None else ""
    titled = [bool(_title_of(a)) for a in axes]
    if not axes:
        return [] if sup else [FigureProblem("title", "the figure has no title")]
    if len(axes) == 1:
        return [] if (titled[0] or sup) else [FigureProblem("title", "the figure has no title")]
    out = []
    if not sup and not any(titled):
        out.append(FigureProblem("title", "the figure has no title (no suptitle, no panel title)"))
    untitled = [i for i, ok in enumerate(titled) if not ok]
    if untitled and (any(titled) or sup):  # (none titled and no suptitle: reported above)
        out.append(FigureProblem("title", f"panels {[i + 1 for i in untitled]} of {len(axes)} "
                                 f"have no title"))
    return out


def _axis_has_ticklabels(axis: Any) -> bool:
    return any(t.get_visible() and t.get_text().strip()
               for t in axis.get_ticklabels(minor=False)) and axis.get_visible()


def _check_labels(fig: Figure) -> list[FigureProblem]:
    out = []
    for i, ax in enumerate(fig.axes):
        if not ax.get_visible() or not ax.axison:
            continue
        name = f"panel {i + 1}" if not _title_of(ax) else repr(_title_of(ax)[:40])
        if _is_colorbar(ax):
            long = ax.yaxis if ax.get_position().height >= ax.get_position().width else ax.xaxis
            if _axis_has_ticklabels(long) and not long.get_label().get_text().strip():
                out.append(FigureProblem("axis-label", f"a colour bar has no label (near {name})"))
            continue
        axes = [("x", ax.xaxis), ("y", ax.yaxis)]
        if hasattr(ax, "zaxis"):
            axes.append(("z", ax.zaxis))
        for nm, axis in axes:
            if _axis_has_ticklabels(axis) and not axis.get_label().get_text().strip():
                out.append(FigureProblem("axis-label", f"{name}: the {nm} axis has no label"))
    return out


def _style_key(h: Any) -> tuple | None:
    def c(v):
        try:
            return tuple(np.round(to_rgba(v), 2))
        except (ValueError, TypeError):
            return None
    if isinstance(h, Line2D):
        ls = h.get_linestyle()
        ls = "none" if ls in ("None", "none", " ", "") else ls
        mk = h.get_marker()
        mk = "none" if mk in (None, "None", "none", " ", "") else str(mk)
        mfc = h.get_markerfacecolor()
        mfc = "none" if isinstance(mfc, str) and mfc.lower() == "none" else c(mfc)
        return ("line", c(h.get_color()), ls, mk, mfc if mk != "none" else None)
    if isinstance(h, PathCollection):
        fc = h.get_facecolor()
        ec = h.get_edgecolor()
        path = h.get_paths()[0].vertices.round(2).tobytes() if h.get_paths() else b""
        return ("scatter", c(fc[0]) if len(fc) else None, c(ec[0]) if len(ec) else None, path)
    if isinstance(h, BarContainer):
        h = h.patches[0] if h.patches else None
        if h is None:
            return None
    if isinstance(h, Patch):
        return ("patch", c(h.get_facecolor()), c(h.get_edgecolor()) if h.get_hatch() else None,
                h.get_hatch() or "")
    if hasattr(h, "lines") and h.lines and isinstance(h.lines[0], Line2D):  # errorbar
        return _style_key(h.lines[0])
    return None


def _check_same_style(fig: Figure) -> list[FigureProblem]:
    out = []
    groups: list[tuple[str, list, list]] = []
    for i, ax in enumerate(_data_axes(fig)):
        hs, ls = ax.get_legend_handles_labels()
        groups.append((f"panel {i + 1}", hs, ls))
    for j, lg in enumerate(fig.legends):
        groups.append((f"figure legend {j + 1}", lg.legend_handles,
                       [t.get_text() for t in lg.get_texts()]))
    for where, hs, ls in groups:
        seen: dict[tuple, str] = {}
        for h, lab in zip(hs, ls, strict=False):
            key = _style_key(h)
            if key is None or None in key[1:2]:
                continue
            if key in seen and seen[key] != lab:
                out.append(FigureProblem("same-style", f"{where}: {seen[key]!r} and {lab!r} "
                                         f"have the same colour and style"))
            seen.setdefault(key, lab)
    return out


def _hue_key(rgba: Any) -> tuple | None:
    r, g, b, a = to_rgba(rgba)
    if a == 0 or max(r, g, b) - min(r, g, b) < 0.15:  # transparent, black, grey, white
        return None
    return (round(r, 1), round(g, 1), round(b, 1))


def _check_unkeyed(fig: Figure, texts: list[Text]) -> list[FigureProblem]:
    """Colour-coded data with no key: two or more colours, no legend, no colour bar, and no
    text in those colours naming them (direct labels count as a key)."""
    if fig.legends or any(_is_colorbar(a) for a in fig.axes):
        return []
    text_hues = {_hue_key(t.get_color()) for t in texts}
    out = []
    for i, ax in enumerate(_data_axes(fig)):
        if ax.get_legend() is not None or not ax.axison:
            continue
        hues = set()
        for ln in ax.get_lines():
            if ln.get_visible() and len(np.atleast_1d(ln.get_xdata())) >= 1:
                hues.add(_hue_key(ln.get_color()))
        for col in ax.collections:
            if col.get_visible() and len(col.get_facecolor()) and col.get_array() is None:
                fc = col.get_facecolor()[0] if to_rgba(col.get_facecolor()[0])[3] > 0 else \
                    (col.get_edgecolor()[0] if len(col.get_edgecolor()) else (0, 0, 0, 0))
                hues.add(_hue_key(fc))
        hues.discard(None)
        unkeyed = hues - text_hues
        if len(hues) >= 2 and unkeyed:
            out.append(FigureProblem("unkeyed-colours", f"panel {i + 1}: {len(hues)} colours "
                                     f"code the data but there is no legend or label for them"))
    return out


def _line_points(line: Line2D, ax: Any, step_px: float = 3.0, cap: int = 200_000) -> np.ndarray:
    xy = np.column_stack([np.asarray(line.get_xdata(orig=False), dtype=float),
                          np.asarray(line.get_ydata(orig=False), dtype=float)])
    if not len(xy):
        return np.empty((0, 2))
    tr = line.get_transform()
    pts = tr.transform(xy)
    pts = pts[np.all(np.isfinite(pts), axis=1)]
    if line.get_linestyle() in ("None", "none", "", " ") or len(pts) < 2:
        return pts
    seg = np.diff(pts, axis=0)
    n = np.clip(np.ceil(np.hypot(*seg.T) / step_px).astype(int), 1, 400)
    if n.sum() > cap:
        n = np.maximum(1, (n * cap / n.sum()).astype(int))
    idx = np.repeat(np.arange(len(seg)), n)
    frac = np.concatenate([np.arange(k) / k for k in n]) if len(n) < 5000 else \
        (np.arange(idx.size) - np.repeat(np.cumsum(n) - n, n)) / np.repeat(n, n)
    return np.vstack([pts[idx] + seg[idx] * frac[:, None], pts[-1:]])


def _inside(pts: np.ndarray, bb: Any, shrink: float = 2.0) -> int:
    if not len(pts):
        return 0
    m = ((pts[:, 0] > bb.x0 + shrink) & (pts[:, 0] < bb.x1 - shrink)
         & (pts[:, 1] > bb.y0 + shrink) & (pts[:, 1] < bb.y1 - shrink))
    return int(m.sum())


def _check_legends(fig: Figure, renderer: Any) -> list[FigureProblem]:
    out = []
    legends: list[Legend] = [a.get_legend() for a in fig.axes if a.get_legend() is not None]
    legends += list(fig.legends)
    for lg in legends:
        if not lg.get_visible():
            continue
        bb = lg.get_window_extent(renderer)
        for i, ax in enumerate(_data_axes(fig)):
            if hasattr(ax, "zaxis"):
                continue  # 3-D projections: not checked
            abb = ax.get_window_extent(renderer)
            if not bb.overlaps(abb):
                continue
            hits = []
            for line in ax.get_lines():
                if line.get_visible() and _inside(_line_points(line, ax), bb):
                    hits.append(line.get_label())
            for col in ax.collections:
                if isinstance(col, PathCollection) and col.get_visible():
                    offs = col.get_offset_transform().transform(col.get_offsets())
                    if _inside(np.asarray(offs), bb):
                        hits.append(col.get_label())
            for cont in ax.containers:
                if isinstance(cont, BarContainer):
                    for p in cont.patches:
                        pb = p.get_window_extent(renderer)
                        ix = min(pb.x1, bb.x1) - max(pb.x0, bb.x0)
                        iy = min(pb.y1, bb.y1) - max(pb.y0, bb.y0)
                        if ix > 2 and iy > 2:
                            hits.append(cont.get_label())
                            break
            for im in ax.images:
                if isinstance(im, AxesImage) and im.get_visible():
                    ib = im.get_window_extent(renderer)
                    if min(ib.x1, bb.x1) - max(ib.x0, bb.x0) > 2 and \
                            min(ib.y1, bb.y1) - max(ib.y0, bb.y0) > 2:
                        hits.append("image")
            if hits:
                names = sorted({h if not h.startswith("_") else "unlabelled" for h in hits})
                out.append(FigureProblem("legend-covers-data",
                                         f"a legend covers data in panel {i + 1}: "
                                         f"{', '.join(names[:5])}"))
    return out


def _check_log_labels(fig: Figure) -> list[FigureProblem]:
    out = []
    for i, ax in enumerate(_data_axes(fig)):
        for nm, axis in (("x", ax.xaxis), ("y", ax.yaxis)):
            if axis.get_scale() != "log":
                continue
            texts = [t.get_text() for t in axis.get_ticklabels(minor=True)
                     + axis.get_ticklabels(minor=False) if t.get_visible()]
            bad = [s for s in texts if "times" in s or "×" in s]
            if bad:
                out.append(FigureProblem("log-labels", f"panel {i + 1}: {nm} tick labels like "
                                         f"{bad[0]!r}; use eotrack.plotting.log_axis"))
    return out


def _check_width(fig: Figure, renderer: Any) -> list[FigureProblem]:
    import matplotlib as mpl

    from .style import BOOK_COLUMN_PX

    dpi = mpl.rcParams["savefig.dpi"]
    dpi = fig.dpi if dpi == "figure" else float(dpi)
    w_in = saved_width_in(fig, renderer)
    scale = BOOK_COLUMN_PX / (w_in * dpi)
    if scale < MIN_BOOK_SCALE:
        return [FigureProblem("too-wide", f"{w_in:.1f} in wide at {dpi:g} dpi: the book shows it "
                              f"at {100 * scale:.0f} % (minimum {100 * MIN_BOOK_SCALE:.0f} %); "
                              f"at most {BOOK_COLUMN_PX / MIN_BOOK_SCALE / dpi:.1f} in")]
    return []


def lint_figure(fig: Any, *, rules: tuple[str, ...] = RULES) -> list[FigureProblem]:
    """Draw ``fig`` and return its readability problems (empty list: it passes).

    Parameters
    ----------
    fig : Figure, Axes or array of Axes
        What a figure function returned; an Axes (or array of them) stands for its figure.
    rules : tuple of str
        The rules to check (default all of :data:`RULES`).

    Returns
    -------
    list of FigureProblem

    Raises
    ------
    TypeError
        If ``fig`` is not a figure or axes.
    ValueError
        If a rule name is unknown.
    """
    unknown = set(rules) - set(RULES)
    if unknown:
        raise ValueError(f"unknown rules {sorted(unknown)}; allowed: {RULES}")
    fig = _figure_of(fig)
    renderer, texts = _draw_recording(fig)
    scale = effective_font_scale(fig, renderer)
    problems: list[FigureProblem] = []
    checks = {
        "overlapping-text": lambda: _check_overlaps(texts, renderer),
        "legend-covers-data": lambda: _check_legends(fig, renderer),
        "axis-label": lambda: _check_labels(fig),
        "small-text": lambda: _check_small(texts, scale),
        "title": lambda: _check_titles(fig),
        "same-style": lambda: _check_same_style(fig),
        "unkeyed-colours": lambda: _check_unkeyed(fig, texts),
        "log-labels": lambda: _check_log_labels(fig),
        "too-wide": lambda: _check_width(fig, renderer),
    }
    for r in RULES:
        if r in rules:
            problems += checks[r]()
    return problems


def _figure_of(obj: Any) -> Figure:
    if isinstance(obj, Figure):
        return obj
    if hasattr(obj, "get_figure") and callable(obj.get_figure):
        f = obj.get_figure()
        if isinstance(f, Figure):
            return f.get_figure(root=True) if hasattr(f, "get_figure") else f
    if isinstance(obj, dict):
        for v in obj.values():
            try:
                return _figure_of(v)
            except TypeError:
                continue
    if isinstance(obj, list | tuple | np.ndarray):
        for v in np.ravel(np.asarray(obj, dtype=object)):
            try:
                return _figure_of(v)
            except TypeError:
                continue
    raise TypeError(f"fig must be a matplotlib Figure or Axes (or a collection of them), got "
                    f"{type(obj).__name__}")
