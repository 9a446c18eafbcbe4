"""The figure lint: what a program can check of a figure's readability, from the drawn artists.

:func:`lint_figure` draws the figure once with the Agg renderer, records every text actually
drawn, and checks the rules listed in the package docstring. Each problem is a
:class:`FigureProblem` with a rule name, so a test can report counts per rule.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import Collection, PathCollection
from matplotlib.colors import to_rgba
from matplotlib.container import BarContainer
from matplotlib.figure import Figure
from matplotlib.image import AxesImage
from matplotlib.legend import Legend
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.text import Annotation, Text

from .style import BOOK_WIDTH_IN, MIN_FONT_PT

__all__ = ["LINT_VERSION", "RULES", "FigureProblem", "effective_font_scale", "lint_figure"]

def _lint_version() -> str:
    """SHA-256 (12 hex digits) of this module's code — its syntax tree with the docstrings left
    out, so an edit of a comment or a docstring keeps the version: a stored verdict names the
    rules that wrote it, so a verdict of older rules can be told from a current one."""
    import ast
    import hashlib
    from pathlib import Path

    tree = ast.parse(Path(__file__).read_text(encoding="utf-8"))
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if (isinstance(body, list) and body and isinstance(body[0], ast.Expr)
                and isinstance(body[0].value, ast.Constant) and isinstance(body[0].value.value, str)):
            node.body = body[1:] or [ast.Pass()]
    return hashlib.sha256(ast.dump(tree).encode()).hexdigest()[:12]


#: The version of the lint's rules (hash of ``lint.py``'s code, comments and docstrings left
#: out), stored with every verdict.
LINT_VERSION = _lint_version()

#: The lint's rules, in the order they are checked.
RULES = ("overlapping-text", "touching-text", "clipped-text", "legend-covers-data", "axis-label",
         "small-text", "title", "same-style", "unkeyed-colours", "log-labels", "colorbar-labels",
         "no-colorbar", "raw-symbol", "unlabelled-reference", "text-over-markers",
         "hidden-series", "too-wide")

#: Texts closer than this (display px, at the figure's dpi) touch: they read as one string.
TOUCH_PX = 1.0

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


@dataclass(frozen=True)
class _Line:
    """One drawn line of a text: the artist, the line's string and its rotated rectangle
    (4×2 display coordinates), measured from the renderer's layout of that very draw."""

    text: Text
    line: str
    rect: np.ndarray


def _line_rects(t: Text, renderer: Any) -> list[_Line]:
    """Per-line rectangles of ``t`` as :meth:`Text.draw` places them (a multi-line label is
    several lines, each as wide as its own string; rotation kept)."""
    _, info, _ = t._get_layout(renderer)
    x, y = t.get_unitless_position()
    posx, posy = t.get_transform().transform((x, y))
    if not (np.isfinite(posx) and np.isfinite(posy)):
        return []
    th = np.radians(t.get_rotation())
    rot = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    out = []
    for line, (w, a, d), (lx, ly) in info:
        if not line.strip() or w <= 0:
            continue
        box = np.array([[0.0, -d], [w, -d], [w, a], [0.0, a]])
        out.append(_Line(t, line, box @ rot.T + np.array([lx + posx, ly + posy])))
    return out


def _draw_recording(fig: Figure) -> tuple[Any, list[Text], list[_Line]]:
    """Draw ``fig`` once with Agg and record every text actually drawn, with its lines.

    Recorded at :meth:`Text.draw` (not at the renderer's ``draw_text``, which sees no artist
    for a multi-line text and is bypassed by path effects such as an outline)."""
    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    renderer = canvas.get_renderer()
    drawn: dict[int, Text] = {}
    lines: dict[int, list[_Line]] = {}
    original = Text.draw

    def record(self, rend, *args, **kw):
        if (self.get_visible() and self.get_text().strip() and id(self) not in drawn
                and to_rgba(self.get_color(), self.get_alpha())[3] > 0):
            try:
                ls = _line_rects(self, rend)
            except Exception:  # a text the layout cannot measure is not checked
                ls = []
            if ls:
                drawn[id(self)] = self
                lines[id(self)] = ls
        return original(self, rend, *args, **kw)

    Text.draw = record
    try:
        fig.draw(renderer)
    finally:
        Text.draw = original
    texts = list(drawn.values())
    return renderer, texts, [ln for t in texts for ln in lines[id(t)]]


def _describe(t: Text) -> str:
    s = t.get_text().replace("\n", " ")
    return repr(s if len(s) <= 40 else s[:37] + "…")


def _describe_line(ln: _Line) -> str:
    whole = ln.text.get_text()
    s = ln.line if "\n" in whole else whole
    s = repr(s if len(s) <= 40 else s[:37] + "…")
    return s + (f" (a line of {_describe(ln.text)})" if "\n" in whole else "")


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


def _check_overlaps(lines: list[_Line]) -> list[FigureProblem]:
    """Lines of two different texts whose rectangles overlap (``overlapping-text``) or are
    less than :data:`TOUCH_PX` apart (``touching-text``: two panel titles, two tick labels
    that run into one string); each pair of texts once."""
    if len(lines) < 2:
        return []
    rects = np.array([ln.rect for ln in lines])
    lo, hi = rects.min(axis=1), rects.max(axis=1)
    owner = np.array([id(ln.text) for ln in lines])
    out, seen = [], set()
    g = TOUCH_PX
    for i in range(len(lines) - 1):
        cand = np.nonzero((lo[i + 1:, 0] < hi[i, 0] + g) & (hi[i + 1:, 0] > lo[i, 0] - g)
                          & (lo[i + 1:, 1] < hi[i, 1] + g) & (hi[i + 1:, 1] > lo[i, 1] - g)
                          & (owner[i + 1:] != owner[i]))[0] + i + 1
        for j in cand:
            pair = (min(owner[i], owner[j]), max(owner[i], owner[j]))
            if pair in seen:
                continue
            if _overlap(rects[i], rects[j]):
                rule, verb = "overlapping-text", "overlaps"
            elif _overlap(rects[i], rects[j], tol=-g):
                rule, verb = "touching-text", f"touches (gap < {g:g} px)"
            else:
                continue
            seen.add(pair)
            out.append(FigureProblem(rule, f"{_describe_line(lines[i])} {verb} "
                                     f"{_describe_line(lines[j])}"))
    return out


def _shown_area(fig: Figure, renderer: Any) -> Any:
    """The part of the canvas that is saved (display px): the tight box plus its padding when
    ``savefig.bbox`` is tight (as the notebooks and ``savefig`` save), else the whole figure."""
    import matplotlib as mpl
    from matplotlib.transforms import Bbox

    if mpl.rcParams["savefig.bbox"] != "tight":
        return fig.bbox
    bb = fig.get_tightbbox(renderer)
    pad = mpl.rcParams["savefig.pad_inches"]
    pad = float(pad) if pad != "layout" else 0.0
    return Bbox.from_extents(bb.x0 - pad, bb.y0 - pad, bb.x1 + pad, bb.y1 + pad).transformed(
        fig.dpi_scale_trans)


def _check_clipped(fig: Figure, lines: list[_Line], renderer: Any) -> list[FigureProblem]:
    """Text cut off: a line reaching past its clip box (``clip_on`` text near an axes edge)
    or past the saved area of the figure (e.g. a legend placed outside and left out of the
    tight box)."""
    shown = _shown_area(fig, renderer)
    out, seen = [], set()
    for ln in lines:
        if id(ln.text) in seen:
            continue
        x0, y0 = ln.rect.min(axis=0)
        x1, y1 = ln.rect.max(axis=0)
        boxes = [("the figure's edge", shown)]
        clip = ln.text.get_clip_box() if ln.text.get_clip_on() else None
        if clip is not None:
            boxes.append(("its axes (clip_on)", clip))
        for where, bb in boxes:
            cut = max(bb.x0 - x0, x1 - bb.x1, bb.y0 - y0, y1 - bb.y1)
            if cut > 1.5:
                seen.add(id(ln.text))
                out.append(FigureProblem("clipped-text", f"{_describe_line(ln)} is cut off by "
                                         f"{where} ({cut:.0f} px)"))
                break
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


def _c(v: Any) -> tuple | None:
    try:
        return tuple(np.round(to_rgba(v), 2))
    except (ValueError, TypeError):
        return None


def _style_key(h: Any) -> tuple | None:
    """``(kind, colour, the rest of the style…)`` of a legend handle; ``None`` if unknown."""
    c = _c
    if isinstance(h, Line2D):
        ls = h.get_linestyle()
        ls = "none" if ls in ("None", "none", " ", "") else ls
        mk = h.get_marker()
        mk = "none" if mk in (None, "None", "none", " ", "") else str(mk)
        mfc = h.get_markerfacecolor()
        if isinstance(mfc, str) and mfc.lower() == "none":
            mfc = "none"
        else:  # a fill in the series' own colour is part of its colour, not of its style
            mfc = "filled" if c(mfc) == c(h.get_color()) else c(mfc)
        return ("line", c(h.get_color()), ls, mk, mfc if mk != "none" else None)
    if isinstance(h, PathCollection):
        fc = h.get_facecolor()
        ec = h.get_edgecolor()
        path = h.get_paths()[0].vertices.round(2).tobytes() if h.get_paths() else b""
        fcol = c(fc[0]) if len(fc) else None
        ecol = c(ec[0]) if len(ec) else None
        # an edge in the face colour (scatter(color=…)) is part of the colour, not the style
        return ("scatter", fcol, "face" if ecol == fcol else ecol, path)
    if isinstance(h, BarContainer):
        h = h.patches[0] if h.patches else None
        if h is None:
            return None
    if isinstance(h, Patch):
        return ("patch", c(h.get_facecolor()), c(h.get_edgecolor()) if h.get_hatch() else None,
                h.get_hatch() or "")
    if isinstance(h, Collection):  # fill_between, vlines, …
        fc, ec = h.get_facecolor(), h.get_edgecolor()
        filled = len(fc) and to_rgba(fc[0])[3] > 0
        col = c(fc[0]) if filled else (c(ec[0]) if len(ec) else None)
        return ("collection", col, "filled" if filled else "edge", h.get_hatch() or "",
                str(h.get_linestyle()[0] if len(h.get_linestyle()) else ""))
    if hasattr(h, "lines") and h.lines and isinstance(h.lines[0], Line2D):  # errorbar
        return _style_key(h.lines[0])
    return None


#: Deuteranopia (severity 1) in linear RGB, Machado, Oliveira & Fernandes (2009).
_DEUTAN = np.array([[0.367322, 0.860646, -0.227968],
                    [0.280085, 0.672501, 0.047413],
                    [-0.011820, 0.042940, 1.042940]])
#: Two colours closer than this (CIELAB ΔE) look alike (the Okabe–Ito pairs are ≥ 17 apart
#: under deuteranopia; matplotlib's default red and green, 7).
CVD_DELTA_E = 12.0


def _lab(rgb: np.ndarray) -> np.ndarray:
    """sRGB (…×3, 0–1) → CIELAB (D65)."""
    lin = np.where(rgb <= 0.04045, rgb / 12.92, ((rgb + 0.055) / 1.055) ** 2.4)
    m = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]])
    xyz = lin @ m.T / np.array([0.95047, 1.0, 1.08883])
    f = np.where(xyz > (6 / 29) ** 3, np.cbrt(xyz), xyz / (3 * (6 / 29) ** 2) + 4 / 29)
    return np.stack([116 * f[..., 1] - 16, 500 * (f[..., 0] - f[..., 1]),
                     200 * (f[..., 1] - f[..., 2])], axis=-1)


def deuteranopia(rgb: Any) -> np.ndarray:
    """A colour (or …×3 array of sRGB colours) as a deuteranope sees it (sRGB, 0–1)."""
    rgb = np.clip(np.asarray(to_rgba(rgb)[:3] if np.ndim(rgb) == 0 or isinstance(rgb, str)
                             else rgb, dtype=float)[..., :3], 0, 1)
    lin = np.where(rgb <= 0.04045, rgb / 12.92, ((rgb + 0.055) / 1.055) ** 2.4)
    sim = np.clip(lin @ _DEUTAN.T, 0, 1)
    return np.where(sim <= 0.0031308, 12.92 * sim, 1.055 * sim ** (1 / 2.4) - 0.055)


def _look_alike_deutan(c1: tuple, c2: tuple) -> bool:
    """Two different colours a deuteranope cannot tell apart (ΔE < :data:`CVD_DELTA_E`)."""
    if c1 == c2:
        return False
    d = _lab(deuteranopia(np.array([c1[:3], c2[:3]])))
    return float(np.linalg.norm(d[0] - d[1])) < CVD_DELTA_E


def _check_same_style(fig: Figure) -> list[FigureProblem]:
    """Two legend entries with the same colour and style, or whose colours differ only for
    normal colour vision (a deuteranope sees the same colour) and whose style is the same."""
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
            elif key not in seen:
                for k2, lab2 in seen.items():
                    if (k2[0] == key[0] and k2[2:] == key[2:] and lab2 != lab
                            and _look_alike_deutan(k2[1], key[1])):
                        out.append(FigureProblem(
                            "same-style", f"{where}: {lab2!r} and {lab!r} have the same style "
                            f"and colours a deuteranope cannot tell apart (red vs green); give "
                            f"one another line style, marker or hatch"))
                        break
            seen.setdefault(key, lab)
    return out


def _hue_key(rgba: Any) -> tuple | None:
    r, g, b, a = to_rgba(rgba)
    if a == 0 or max(r, g, b) - min(r, g, b) < 0.15:  # transparent, black, grey, white
        return None
    return (round(r, 1), round(g, 1), round(b, 1))


def _collection_colours(col: Collection) -> list:
    """The colours a collection shows: every face colour (a scatter with a list of colours
    has one per point), or the edge colours of an unfilled one."""
    fc = np.asarray(col.get_facecolor())
    if len(fc) and (fc[:, 3] > 0).any():
        return list(fc[fc[:, 3] > 0])
    return list(np.asarray(col.get_edgecolor()))


def _check_unkeyed(fig: Figure, texts: list[Text]) -> list[FigureProblem]:
    """Colour-coded data with no key: two or more colours (lines, scatter points — one
    colour per point counts —, filled areas, bars and other patches), no legend, no colour
    bar, and no text in those colours naming them (direct labels count as a key)."""
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
            if col.get_visible() and col.get_array() is None:
                hues.update(_hue_key(c) for c in np.unique(np.round(
                    np.asarray(_collection_colours(col)).reshape(-1, 4), 3), axis=0))
        for p in ax.patches:
            if p.get_visible():
                fc = p.get_facecolor()
                hues.add(_hue_key(fc if p.get_fill() and to_rgba(fc)[3] > 0
                                  else p.get_edgecolor()))
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


def _grid(bb: Any, n: int = 9, shrink: float = 2.0) -> np.ndarray:
    gx = np.linspace(bb.x0 + shrink, bb.x1 - shrink, n)
    gy = np.linspace(bb.y0 + shrink, bb.y1 - shrink, n)
    return np.stack(np.meshgrid(gx, gy), axis=-1).reshape(-1, 2)


def _path_covered(path: Any, filled: bool, bb: Any, min_share: float = 0.05) -> bool:
    """A display-space path under the box ``bb``: its filled area covers at least
    ``min_share`` of the box, or (unfilled) its outline runs through the box."""
    if not len(path.vertices):
        return False
    if filled and path.contains_points(_grid(bb)).mean() >= min_share:
        return True
    pts = []
    for poly in path.to_polygons(closed_only=False):
        if len(poly) >= 2:
            seg = np.diff(poly, axis=0)
            n = np.clip(np.ceil(np.hypot(*seg.T) / 3.0).astype(int), 1, 400)
            idx = np.repeat(np.arange(len(seg)), n)
            frac = (np.arange(idx.size) - np.repeat(np.cumsum(n) - n, n)) / np.repeat(n, n)
            pts.append(poly[idx] + seg[idx] * frac[:, None])
        pts.append(poly)
    return bool(pts) and _inside(np.vstack(pts), bb) > 0


def _collection_covered(col: Collection, bb: Any) -> bool:
    fc = np.asarray(col.get_facecolor())
    filled = bool(len(fc) and (fc[:, 3] > 0).any())
    tr = col.get_transform()
    return any(_path_covered(tr.transform_path(p), filled, bb) for p in col.get_paths())


def _patch_covered(p: Patch, bb: Any) -> bool:
    filled = p.get_fill() and to_rgba(p.get_facecolor())[3] > 0
    return _path_covered(p.get_transform().transform_path(p.get_path()), filled, bb)


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
                if not col.get_visible():
                    continue
                if isinstance(col, PathCollection):
                    offs = col.get_offset_transform().transform(col.get_offsets())
                    if _inside(np.asarray(offs), bb):
                        hits.append(col.get_label())
                elif _collection_covered(col, bb):  # fill_between, error bars, vlines
                    hits.append(col.get_label())
            in_bars = {id(p) for cont in ax.containers if isinstance(cont, BarContainer)
                       for p in cont.patches}
            for p in ax.patches:  # histograms (step), polygons, rectangles not in a bar chart
                if p.get_visible() and id(p) not in in_bars and _patch_covered(p, bb):
                    hits.append(p.get_label())
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


#: A tick label in computer notation (``1e−03``, ``2.5e+04``): a reader expects ``10⁻³``.
_E_NOTATION = re.compile(r"\d[eE][+\-\u2212]?\d")


def _check_log_labels(fig: Figure) -> list[FigureProblem]:
    """Log-axis labels like ``2×10⁰`` or ``1e−03``, and ``1e−03`` on any axis (a tick label
    or the axis' offset text): decades read as plain numbers or ``10⁻³``."""
    out = []
    for i, ax in enumerate(_data_axes(fig)):
        for nm, axis in (("x", ax.xaxis), ("y", ax.yaxis)):
            if axis.get_scale() != "log":
                continue
            texts = [t.get_text() for t in axis.get_ticklabels(minor=True)
                     + axis.get_ticklabels(minor=False) if t.get_visible()]
            bad = [s for s in texts if "times" in s or "×" in s or _E_NOTATION.search(s)]
            if bad:
                out.append(FigureProblem("log-labels", f"panel {i + 1}: {nm} tick labels like "
                                         f"{bad[0]!r}; use eotrack.plotting.log_axis"))
        for nm, axis in (("x", ax.xaxis), ("y", ax.yaxis)):
            if axis.get_scale() == "log":
                continue
            texts = [t.get_text() for t in axis.get_ticklabels(minor=False) if t.get_visible()]
            off = axis.get_offset_text()
            texts += [off.get_text()] if off.get_visible() else []
            bad = [s for s in texts if _E_NOTATION.search(s)]
            if bad:
                out.append(FigureProblem("log-labels", f"panel {i + 1}: {nm} tick labels like "
                                         f"{bad[0]!r} (computer notation); write 10^k "
                                         f"(eotrack.plotting.plain_number)"))
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


# --- rules of the second review (issue 23): raw symbols, reference lines, text over markers,
# hidden series, colour bars ---

_GREEK = ("alpha|beta|gamma|delta|epsilon|zeta|eta|theta|iota|kappa|lambda|mu|nu|xi|pi|rho|"
          "sigma|tau|upsilon|phi|chi|psi|omega")
#: A symbol with an underscore subscript written as plain text (``P_D``, ``t_i``, ``x_c``,
#: ``sigma_px``): matplotlib prints the underscore; in mathtext it is a subscript.
_RAW_SUBSCRIPT = re.compile(rf"(?<![A-Za-z0-9_\\\u0391-\u03c9])(?:[A-Za-z\u0391-\u03c9]{{1,3}}|(?i:{_GREEK}))_"
                            rf"(?:\{{[^}}]*\}}|[A-Za-z0-9]+)")
#: … or a superscript written as plain text (``sigma^2``, ``x^2``; ``10^3`` is left alone).
_RAW_SUPERSCRIPT = re.compile(rf"(?<![A-Za-z0-9_\\\u0391-\u03c9])(?:[A-Za-z\u0391-\u03c9]{{1,3}}|"
                              rf"(?i:{_GREEK}))\^(?:\{{[^}}]*\}}|[A-Za-z0-9]+)")
_DOLLAR = re.compile(r"(?<!\\)\$")


def _plain_parts(s: str) -> list[str]:
    """The parts of a text that matplotlib prints literally: all of it unless it holds an even
    number (≥ 2) of unescaped ``$``, else the parts outside ``$…$``."""
    parts = _DOLLAR.split(s)
    if len(parts) < 3 or len(parts) % 2 == 0:
        return [s]
    return parts[0::2]


def _check_raw_symbols(texts: list[Text]) -> list[FigureProblem]:
    """Text with a symbol's underscore subscript or caret superscript outside ``$…$``
    (``P_FA`` beside ``$P_\\mathrm{FA}$``, ``sigma^2``): the reader sees the ``_`` or ``^``."""
    out = []
    for t in texts:
        hits = [m.group(0) for part in _plain_parts(t.get_text())
                for rx in (_RAW_SUBSCRIPT, _RAW_SUPERSCRIPT) for m in rx.finditer(part)]
        if hits:
            out.append(FigureProblem("raw-symbol", f"{_describe(t)} writes {hits[0]!r} as plain "
                                     f"text; write it in mathtext (e.g. r'$P_\\mathrm{{D}}$')"))
    return out


def _legend_labels(fig: Figure) -> set[str]:
    legends = [a.get_legend() for a in fig.axes if a.get_legend() is not None] + list(fig.legends)
    return {t.get_text() for lg in legends if lg.get_visible() for t in lg.get_texts()}


def _legend_keys(fig: Figure) -> tuple[set, set]:
    """``(colours, neutral styles)`` of the figure's legend entries that are lines: the
    colours the legends name, and the line styles a grey or black entry names (a style key
    such as "dashed: analytic bound")."""
    legends = [a.get_legend() for a in fig.axes if a.get_legend() is not None] + list(fig.legends)
    colours, styles = set(), set()
    for lg in legends:
        if not lg.get_visible():
            continue
        for h in lg.legend_handles:
            if not isinstance(h, Line2D) or h.get_linestyle() in ("None", "none", "", " "):
                continue
            col = _c(h.get_color())
            colours.add(col)
            if col is not None and _hue_key(h.get_color()) is None:
                styles.add(str(h.get_linestyle()))
    return colours, styles


def _is_solid(ls: Any) -> bool:
    return ls in ("-", "solid")


def _constant_line(line: Line2D) -> tuple[str, float] | None:
    """``("h", y)`` / ``("v", x)`` for a straight horizontal / vertical line (``axhline``,
    ``axvline``, or ``plot`` of a constant), else ``None``."""
    x = np.asarray(line.get_xdata(orig=False), dtype=float)
    y = np.asarray(line.get_ydata(orig=False), dtype=float)
    ok = np.isfinite(x) & np.isfinite(y)
    x, y = x[ok], y[ok]
    if len(x) < 2 or line.get_linestyle() in ("None", "none", "", " ") or line.get_linewidth() <= 0:
        return None
    if np.ptp(y) == 0 and np.ptp(x) > 0:
        return ("h", float(y[0]))
    if np.ptp(x) == 0 and np.ptp(y) > 0:
        return ("v", float(x[0]))
    return None


def _check_reference_lines(fig: Figure, lines: list[_Line], renderer: Any) -> list[FigureProblem]:
    """A reference line nobody named: an ``axhline``/``axvline`` (a solid one at 0, the axis'
    own baseline, excepted) or a dashed/dotted constant line, with no legend entry, no
    annotation arrow at it and no label beside it (a text in the line's colour within 25 px, or
    a text within 1.2 of its height beside one of the line's ends — within 40 px or 12 % of the
    line's length of it). Lines of one look (orientation,
    colour, style, width) count as one: a ±27″ pair is named when one of them is; three or
    more of one look at equal spacing are a grid (cell boundaries), not reference lines. A
    line in a series' colour is named by a grey style key of its line style in a legend
    ("dashed: analytic value", one entry for the dashed line of every series). A look named in
    one panel is named in every panel (one legend shared by the panels)."""
    shown = _legend_labels(fig)
    key_colours, key_styles = _legend_keys(fig)
    panels: list[tuple[int, dict[tuple, list[tuple[float, bool]]]]] = []
    for i, ax in enumerate(_data_axes(fig)):
        if hasattr(ax, "zaxis"):
            continue
        notes = [ln for ln in lines if (ln.text.axes is ax and ln.text in ax.texts)
                 or ln.text in fig.texts]
        abb = ax.get_window_extent(renderer)
        groups: dict[tuple, list[tuple[float, bool]]] = {}
        for line in ax.get_lines():
            if not line.get_visible() or to_rgba(line.get_color(), line.get_alpha())[3] == 0:
                continue
            const = _constant_line(line)
            if const is None:
                continue
            axline = line.get_transform() != ax.transData
            solid = _is_solid(line.get_linestyle())
            if not axline and solid:
                continue  # a flat data series, not a reference line
            if axline and solid and const[1] == 0:
                continue  # the zero baseline
            pts = line.get_transform().transform(np.column_stack(
                [line.get_xdata(orig=False), line.get_ydata(orig=False)]).astype(float))
            pts = pts[np.all(np.isfinite(pts), axis=1)]
            if not len(pts):
                continue
            lo = np.maximum(pts.min(axis=0), [abb.x0, abb.y0])
            hi = np.minimum(pts.max(axis=0), [abb.x1, abb.y1])
            if np.any(hi < lo - 0.5):
                continue  # outside the view
            named = ((not line.get_label().startswith("_") and line.get_label() in shown)
                     or (str(line.get_linestyle()) in key_styles
                         and _c(line.get_color()) in key_colours
                         and _hue_key(line.get_color()) is not None))
            along, across = (0, 1) if const[0] == "h" else (1, 0)
            for ln in [] if named else notes:
                # a label of the line: in its colour within 25 px, or (any colour) beside it —
                # within 1.2 of its own height across — at one of its ends; an unrelated text
                # somewhere along the line does not name it
                r0, r1 = ln.rect.min(axis=0), ln.rect.max(axis=0)
                gap = max(0.0, r0[across] - hi[across], lo[across] - r1[across])
                overlaps = r1[along] >= lo[along] - 25 and r0[along] <= hi[along] + 25
                same_colour = _c(ln.text.get_color()) == _c(line.get_color())
                size = (r1 - r0)[across] if const[0] == "h" else (r1 - r0)[along]
                at_end = min(abs(r0[along] - hi[along]), abs(r1[along] - lo[along]),
                             abs(r1[along] - hi[along]), abs(r0[along] - lo[along])) <= max(
                    40.0, 0.12 * (hi[along] - lo[along]))
                if overlaps and ((same_colour and gap <= 25)
                                 or (gap <= max(4.0, 1.2 * size) and at_end)):
                    named = True
                    break
                if isinstance(ln.text, Annotation) and ln.text.arrow_patch is not None:
                    xy = ln.text._get_xy_display()
                    if (abs(xy[across] - lo[across]) <= 5
                            and lo[along] - 5 <= xy[along] <= hi[along] + 5):
                        named = True
                        break
            key = (const[0], _c(line.get_color()), str(line.get_linestyle()),
                   round(float(line.get_linewidth()), 2))
            groups.setdefault(key, []).append((const[1], named))
        panels.append((i, groups))
    # a look named in one panel names it in every panel (one legend shared by the panels)
    named_looks = {k for _, g in panels for k, m in g.items() if any(n for _, n in m)}
    out = []
    for i, groups in panels:
        for key, members in groups.items():
            if key in named_looks:
                continue
            vals = np.sort([v for v, _ in members])
            if len(vals) >= 3 and np.ptp(np.diff(vals)) <= 1e-6 * max(1.0, np.ptp(vals)):
                continue  # a grid
            where = "y" if key[0] == "h" else "x"
            for v in vals:
                out.append(FigureProblem(
                    "unlabelled-reference", f"panel {i + 1}: the reference line at {where} = "
                    f"{v:.4g} has no legend entry and no text beside it"))
    return out


def _marker_points(line: Line2D) -> np.ndarray:
    mk = line.get_marker()
    if mk in (None, "None", "none", " ", "") or line.get_markersize() <= 0:
        return np.empty((0, 2))
    xy = np.column_stack([np.asarray(line.get_xdata(orig=False), dtype=float),
                          np.asarray(line.get_ydata(orig=False), dtype=float)])
    pts = line.get_transform().transform(xy) if len(xy) else np.empty((0, 2))
    return pts[np.all(np.isfinite(pts), axis=1)]


def _ink_rect(ln: _Line, renderer: Any) -> np.ndarray:
    """The line's rectangle without its leading and trailing spaces (``"  GEO5"`` beside a
    marker does not cover it)."""
    s = ln.line
    lead, trail = len(s) - len(s.lstrip(" ")), len(s) - len(s.rstrip(" "))
    if not (lead or trail) or not s.strip():
        return ln.rect
    prop = ln.text.get_fontproperties()
    def width(t: str) -> float:
        return renderer.get_text_width_height_descent(t, prop, ismath=False)[0]

    w_sp = max(0.0, width("x x") - width("xx"))  # one space's advance
    u = ln.rect[1] - ln.rect[0]
    n = np.hypot(*u)
    if n == 0:
        return ln.rect
    u = u / n
    a, b = u * min(lead * w_sp, n / 2), u * min(trail * w_sp, n / 2)
    return np.array([ln.rect[0] + a, ln.rect[1] - b, ln.rect[2] - b, ln.rect[3] + a])


def _check_text_over_markers(fig: Figure, lines: list[_Line], renderer: Any) -> list[FigureProblem]:
    """A text (label, annotation) drawn over data markers: a marker of a line or a scatter
    whose centre lies inside the text's rectangle (spaces at its ends left out) widened by half
    the marker's radius — the text hides at least half of it. 3-D axes too: their markers and
    texts are compared as projected in the draw."""
    px = fig.dpi / 72.0
    out = []
    for i, ax in enumerate(_data_axes(fig)):
        notes = [ln for ln in lines if ln.text in ax.texts]
        if not notes:
            continue
        abb = ax.get_window_extent(renderer)
        sets: list[tuple[str, np.ndarray, np.ndarray]] = []
        for line in ax.get_lines():
            if line.get_visible():
                pts = _marker_points(line)
                sets.append((line.get_label(), pts,
                             np.full(len(pts), line.get_markersize() * px / 2)))
        for col in ax.collections:
            if col.get_visible() and isinstance(col, PathCollection) and len(col.get_offsets()):
                pts = np.asarray(col.get_offset_transform().transform(col.get_offsets()),
                                 dtype=float)
                sz = np.asarray(col.get_sizes(), dtype=float)
                r = np.sqrt(np.resize(sz if len(sz) else [36.0], len(pts))) / 2 * px
                sets.append((col.get_label(), pts, r))
        rects = [(ln, _ink_rect(ln, renderer)) for ln in notes]
        for name, pts, r in sets:
            if not len(pts):
                continue
            keep = ((pts[:, 0] >= abb.x0) & (pts[:, 0] <= abb.x1)
                    & (pts[:, 1] >= abb.y0) & (pts[:, 1] <= abb.y1))
            pts, r = pts[keep], r[keep]
            for ln, rect in rects:
                r0, r1 = rect.min(axis=0), rect.max(axis=0)
                grow = (r / 2 - 1.0)[:, None]
                inside = np.all((pts >= r0 - grow) & (pts <= r1 + grow), axis=1)
                if inside.any():
                    nm = "unlabelled" if name.startswith("_") else repr(name)
                    out.append(FigureProblem(
                        "text-over-markers", f"panel {i + 1}: {_describe_line(ln)} is drawn "
                        f"over {int(inside.sum())} marker(s) of {nm}"))
                    break
    return out


def _sample_path(pts: np.ndarray, step: float = 1.0, cap: int = 40_000) -> np.ndarray:
    """Points every ``step`` px along a polyline (NaN vertices break it)."""
    if len(pts) < 2:
        return pts[np.all(np.isfinite(pts), axis=1)]
    a, b = pts[:-1], pts[1:]
    ok = np.all(np.isfinite(a), axis=1) & np.all(np.isfinite(b), axis=1)
    a, b = a[ok], b[ok]
    if not len(a):
        return np.empty((0, 2))
    n = np.clip(np.ceil(np.hypot(*(b - a).T) / step).astype(int), 1, 2000)
    if n.sum() > cap:
        n = np.maximum(1, (n * cap / n.sum()).astype(int))
    idx = np.repeat(np.arange(len(a)), n)
    frac = (np.arange(idx.size) - np.repeat(np.cumsum(n) - n, n)) / np.repeat(n, n)
    return np.vstack([a[idx] + (b - a)[idx] * frac[:, None], b[-1:]])


def _check_hidden_series(fig: Figure, renderer: Any) -> list[FigureProblem]:
    """A line or marker series drawn entirely under another one (a result equal to the ideal
    curve, drawn first): every drawn point of it lies under the later series' solid line or
    filled markers, so the reader cannot see it."""
    from scipy.spatial import cKDTree

    px = fig.dpi / 72.0
    out = []
    for i, ax in enumerate(_data_axes(fig)):
        if hasattr(ax, "zaxis"):
            continue
        abb = ax.get_window_extent(renderer)
        order = sorted(enumerate(ax.get_lines()), key=lambda t: (t[1].get_zorder(), t[0]))
        info = []
        for _, line in order:
            if not line.get_visible() or to_rgba(line.get_color(), line.get_alpha())[3] == 0:
                info.append(None)
                continue
            tp = line.get_transform().transform_path(line.get_path()).vertices
            has_line = (line.get_linestyle() not in ("None", "none", "", " ")
                        and line.get_linewidth() > 0)
            mk = _marker_points(line)
            path = _sample_path(tp) if has_line else np.empty((0, 2))
            own = np.vstack([path, mk]) if len(mk) else path
            own = own[(own[:, 0] >= abb.x0 - 1) & (own[:, 0] <= abb.x1 + 1)
                      & (own[:, 1] >= abb.y0 - 1) & (own[:, 1] <= abb.y1 + 1)]
            reach = max(line.get_linewidth() * px / 2 if has_line else 0.0,
                        line.get_markersize() * px / 2 if len(mk) else 0.0)
            alpha = to_rgba(line.get_color(), line.get_alpha())[3]
            opaque = alpha >= 0.9
            cover_line = (line.get_linewidth() * px / 2
                          if has_line and _is_solid(line.get_linestyle()) and opaque else None)
            mfc = line.get_markerfacecolor()
            filled = not (isinstance(mfc, str) and mfc.lower() == "none") and \
                to_rgba(mfc)[3] >= 0.9 and opaque
            cover_mk = line.get_markersize() * px / 2 if len(mk) and filled else None
            cover = max(cover_line or 0.0, cover_mk or 0.0)
            box = (np.vstack([path, mk]) if len(mk) else path)
            box = (box.min(axis=0) - cover, box.max(axis=0) + cover) if len(box) else None
            info.append({"line": line, "own": own, "reach": reach, "path": path, "mk": mk,
                         "cover_line": cover_line, "cover_mk": cover_mk, "box": box})
        trees: dict[int, tuple] = {}
        for a in range(len(info)):
            lo = info[a]
            if lo is None or not len(lo["own"]):
                continue
            for b in range(a + 1, len(info)):
                up = info[b]
                if up is None or (up["cover_line"] is None and up["cover_mk"] is None):
                    continue
                if up["box"] is None or np.any(lo["own"].min(axis=0) < up["box"][0] - 0.5) \
                        or np.any(lo["own"].max(axis=0) > up["box"][1] + 0.5):
                    continue  # not inside the later series' reach: cannot be covered
                if b not in trees:
                    trees[b] = (cKDTree(up["path"]) if up["cover_line"] is not None
                                and len(up["path"]) else None,
                                cKDTree(up["mk"]) if up["cover_mk"] is not None
                                and len(up["mk"]) else None)
                slack = np.full(len(lo["own"]), np.inf)
                tl, tm = trees[b]
                if tl is not None:
                    slack = np.minimum(slack, tl.query(lo["own"])[0] - up["cover_line"])
                if tm is not None:
                    slack = np.minimum(slack, tm.query(lo["own"])[0] - up["cover_mk"])
                if np.all(slack + lo["reach"] <= 0.5):
                    n1, n2 = lo["line"].get_label(), up["line"].get_label()
                    n1 = "an unlabelled series" if n1.startswith("_") else repr(n1)
                    n2 = "an unlabelled series" if n2.startswith("_") else repr(n2)
                    out.append(FigureProblem(
                        "hidden-series", f"panel {i + 1}: {n1} is hidden under {n2} (drawn "
                        f"later); draw it on top dashed, offset it, or say so in its label"))
                    break
    return out


def _check_colorbar_labels(fig: Figure) -> list[FigureProblem]:
    """Colour-bar tick labels (or offset text) like ``1e−03`` or ``2×10⁰``."""
    out = []
    for ax in fig.axes:
        if not _is_colorbar(ax) or not ax.get_visible():
            continue
        for axis in (ax.xaxis, ax.yaxis):
            texts = [t.get_text() for t in axis.get_ticklabels(minor=True)
                     + axis.get_ticklabels(minor=False) if t.get_visible()]
            off = axis.get_offset_text()
            texts += [off.get_text()] if off.get_visible() else []
            bad = [s for s in texts if _E_NOTATION.search(s) or (
                axis.get_scale() == "log" and ("times" in s or "×" in s))]
            if bad:
                lab = axis.get_label().get_text() or "unlabelled"
                out.append(FigureProblem("colorbar-labels", f"colour bar {lab!r}: tick labels "
                                         f"like {bad[0]!r}; use plain numbers or 10^k "
                                         f"(eotrack.plotting.plain_number)"))
                break
    return out


def _check_colour_mapped(fig: Figure) -> list[FigureProblem]:
    """A colour-mapped scatter or line collection (``c=values``) with no colour bar for its
    colour map and range: the colours cannot be read."""
    from matplotlib.collections import LineCollection

    bars = [a._colorbar.mappable for a in fig.axes
            if _is_colorbar(a) and getattr(a, "_colorbar", None) is not None]
    out = []
    for i, ax in enumerate(_data_axes(fig)):
        for col in ax.collections:
            if not col.get_visible() or not isinstance(col, PathCollection | LineCollection):
                continue
            arr = col.get_array()
            if arr is None or len(np.unique(np.asarray(arr, dtype=float)[
                    np.isfinite(np.asarray(arr, dtype=float))])) < 2:
                continue
            if any(m is col or (m.get_cmap().name == col.get_cmap().name
                                and m.norm.vmin == col.norm.vmin and m.norm.vmax == col.norm.vmax)
                   for m in bars):
                continue
            nm = col.get_label()
            nm = "" if nm.startswith("_") else f" {nm!r}"
            out.append(FigureProblem("no-colorbar", f"panel {i + 1}: a colour-mapped "
                                     f"{'scatter' if isinstance(col, PathCollection) else 'line set'}"
                                     f"{nm} has no colour bar"))
    return out


def lint_figure(fig: Any, *, rules: tuple[str, ...] = RULES,
                bbox: str | None = None) -> list[FigureProblem]:
    """Draw ``fig`` and return its readability problems (empty list: it passes).

    Parameters
    ----------
    fig : Figure, Axes or array of Axes
        What a figure function returned; an Axes (or array of them) stands for its figure.
    rules : tuple of str
        The rules to check (default all of :data:`RULES`).
    bbox : {"tight", "standard"} or None
        How the figure is saved (``savefig``'s ``bbox_inches``: what is shown, how wide it is);
        default the current ``rcParams["savefig.bbox"]``. Pass ``"tight"`` for a figure saved
        with ``bbox_inches="tight"`` (REPORT figures, notebook outputs) whatever the caller's
        rcParams.

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
    if bbox not in (None, "tight", "standard"):
        raise ValueError(f"bbox must be 'tight', 'standard' or None, got {bbox!r}")
    if bbox is not None:
        import matplotlib as mpl

        with mpl.rc_context({"savefig.bbox": bbox if bbox == "tight" else "standard"}):
            return lint_figure(fig, rules=rules)
    fig = _figure_of(fig)
    renderer, texts, lines = _draw_recording(fig)
    scale = effective_font_scale(fig, renderer)
    problems: list[FigureProblem] = []
    text_pairs: list[FigureProblem] = []
    if {"overlapping-text", "touching-text"} & set(rules):
        text_pairs = _check_overlaps(lines)
    checks = {
        "overlapping-text": lambda: [p for p in text_pairs if p.rule == "overlapping-text"],
        "touching-text": lambda: [p for p in text_pairs if p.rule == "touching-text"],
        "clipped-text": lambda: _check_clipped(fig, lines, renderer),
        "legend-covers-data": lambda: _check_legends(fig, renderer),
        "axis-label": lambda: _check_labels(fig),
        "small-text": lambda: _check_small(texts, scale),
        "title": lambda: _check_titles(fig),
        "same-style": lambda: _check_same_style(fig),
        "unkeyed-colours": lambda: _check_unkeyed(fig, texts),
        "log-labels": lambda: _check_log_labels(fig),
        "colorbar-labels": lambda: _check_colorbar_labels(fig),
        "no-colorbar": lambda: _check_colour_mapped(fig),
        "raw-symbol": lambda: _check_raw_symbols(texts),
        "unlabelled-reference": lambda: _check_reference_lines(fig, lines, renderer),
        "text-over-markers": lambda: _check_text_over_markers(fig, lines, renderer),
        "hidden-series": lambda: _check_hidden_series(fig, renderer),
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
