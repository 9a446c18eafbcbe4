"""The house style: one colour, line style and marker per method; the rc settings; book width.

See the package docstring (:mod:`eotrack.plotting`) for how to use it.
"""

from __future__ import annotations

import contextlib
import difflib
import re
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import matplotlib as mpl
from cycler import cycler

__all__ = [
    "BOOK_COLUMN_PX",
    "BOOK_WIDTH_IN",
    "FIG_HEIGHT_IN",
    "FIG_WIDTH_IN",
    "HOUSE_RC",
    "MIN_FONT_PT",
    "OKABE_ITO",
    "ON_IMAGE",
    "MethodStyle",
    "house_style",
    "known_methods",
    "method_style",
    "series_styles",
    "use_house_style",
]

#: Width of the book's text column in CSS pixels (sphinx-book-theme at a 1400 px wide window,
#: both sidebars shown). A figure wider than this is shrunk by the browser.
BOOK_COLUMN_PX = 720
#: The column in inches at the CSS 96 px/in: a figure up to this wide (after ``bbox_inches=
#: "tight"``) shows its fonts at their nominal size or larger in the book.
BOOK_WIDTH_IN = BOOK_COLUMN_PX / 96
#: Default figure size of the house style (inches): fits the column with room for a legend.
FIG_WIDTH_IN = 6.4
FIG_HEIGHT_IN = 3.9
#: No text may show smaller than this (pt) at the book's column width (the figure lint's rule).
MIN_FONT_PT = 8.0

#: Okabe & Ito (2008) colour-blind-safe palette, by name.
OKABE_ITO: dict[str, str] = {
    "black": "#000000",
    "orange": "#E69F00",
    "sky blue": "#56B4E9",
    "bluish green": "#009E73",
    "yellow": "#F0E442",
    "blue": "#0072B2",
    "vermillion": "#D55E00",
    "reddish purple": "#CC79A7",
    "grey": "#7F7F7F",
}
_C = OKABE_ITO

#: Colours that stay visible on a dark image (star fields): use them for overlays on images.
ON_IMAGE: dict[str, str] = {
    "target": _C["yellow"], "truth": "#FFFFFF", "star": _C["sky blue"],
    "candidate": _C["orange"], "false": _C["vermillion"], "track": _C["bluish green"],
}

_CYCLE_COLOURS = [_C[k] for k in ("blue", "orange", "bluish green", "vermillion",
                                  "reddish purple", "sky blue", "black", "grey")]
_CYCLE_LS = ["-", "--", "-.", ":", "-", "--", "-.", ":"]
_CYCLE_MARKERS = ["o", "s", "^", "D", "v", "P", "X", "*"]

#: The rc settings of the house style (used by :func:`use_house_style` and :func:`house_style`).
HOUSE_RC: dict[str, Any] = {
    "figure.figsize": (FIG_WIDTH_IN, FIG_HEIGHT_IN),
    "figure.dpi": 100,
    "savefig.dpi": 110,
    "savefig.bbox": "tight",
    "figure.facecolor": "white",
    "font.size": 10,
    "axes.titlesize": 10.5,
    "axes.titlelocation": "left",
    "axes.titleweight": "bold",
    "axes.labelsize": 10,
    "xtick.labelsize": 9,
    "ytick.labelsize": 9,
    "legend.fontsize": 9,
    "legend.title_fontsize": 9,
    "figure.titlesize": 11,
    "figure.titleweight": "bold",
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "axes.prop_cycle": cycler(color=_CYCLE_COLOURS, linestyle=_CYCLE_LS),
    "axes.formatter.use_mathtext": True,
    "legend.frameon": True,
    "legend.framealpha": 0.92,
    "legend.edgecolor": "0.8",
    "legend.facecolor": "white",
    "lines.linewidth": 1.6,
    "lines.markersize": 5.5,
    "image.cmap": "gray",
    "mathtext.fontset": "dejavusans",
    "hatch.linewidth": 0.8,
}


def use_house_style() -> None:
    """Apply the house style to matplotlib's global rc settings (notebooks call it in Setup,
    through :func:`eotrack.notebook.setup_notebook`; ``make repro`` calls it once)."""
    mpl.rcParams.update(HOUSE_RC)


@contextlib.contextmanager
def house_style() -> Iterator[None]:
    """Context manager: the house style inside the block, the previous rc settings after it.

    Examples
    --------
    >>> from eotrack.plotting import house_style
    >>> with house_style():
    ...     pass  # draw here
    """
    with mpl.rc_context(HOUSE_RC):
        yield


@dataclass(frozen=True)
class MethodStyle:
    """The fixed look of one method: colour, line style, marker, and a hatch for bars."""

    name: str
    color: str
    linestyle: str
    marker: str
    hatch: str = ""
    mfc: str | None = None  # marker face colour; ``"none"`` for hollow markers

    def line(self, **override: Any) -> dict[str, Any]:
        """Keyword arguments for ``ax.plot`` (colour, line style, marker); ``override`` wins
        (``ls=``/``c=`` are accepted for ``linestyle=``/``color=``)."""
        kw: dict[str, Any] = {"color": self.color, "linestyle": self.linestyle,
                              "marker": self.marker}
        if self.mfc is not None:
            kw["mfc"] = self.mfc
        return {**kw, **_canonical(override)}

    def bar(self, **override: Any) -> dict[str, Any]:
        """Keyword arguments for ``ax.bar``/``ax.barh``/``ax.hist`` (colour and hatch)."""
        kw = {"color": self.color, "hatch": self.hatch, "edgecolor": "black", "linewidth": 0.6}
        return {**kw, **_canonical(override)}

    def scatter(self, **override: Any) -> dict[str, Any]:
        """Keyword arguments for ``ax.scatter`` (colour and marker)."""
        return {"color": self.color, "marker": self.marker, **_canonical(override)}


_ALIASES = {"ls": "linestyle", "c": "color", "lw": "linewidth", "ec": "edgecolor"}


def _canonical(kw: dict[str, Any]) -> dict[str, Any]:
    return {_ALIASES.get(k, k): v for k, v in kw.items()}


# (canonical name, pattern on the normalised name, colour, line style, marker, hatch, mfc)
# First match wins: the more specific patterns come first.
_REGISTRY: list[tuple[str, str, str, str, str, str, str | None]] = [
    # paper values and references
    ("paper", r"^paper\b|paper value", _C["black"], "none", "D", "", "none"),
    ("GT", r"^gt$|ground.?truth|^truth\b|^true\b", _C["black"], "-", "+", "", None),
    ("ideal", r"\bideal\b", _C["black"], ":", "*", "..", None),
    # robust estimation (01, 06, 07)
    ("WRANSAC (hypothesis weights)", r"wransac.*hypothesis", _C["bluish green"], "--", "^",
     "//", None),
    ("WRANSAC (refit weights)", r"wransac.*refit", _C["bluish green"], "-.", "<", "\\\\", None),
    ("WRANSAC (iterated weights)", r"wransac.*iterat", _C["bluish green"], ":", ">", "xx", None),
    ("WRANSAC", r"\bwransac\b|weighted ransac", _C["bluish green"], "-", "^", "//", None),
    ("Huber from RANSAC", r"huber.*ransac", _C["vermillion"], "-", "P", "++", None),
    ("Cauchy from RANSAC", r"cauchy", _C["reddish purple"], "-.", "X", "oo", None),
    ("soft-L1 from LSQ", r"soft.?l1", _C["vermillion"], ":", "h", "--", None),
    ("Huber from LSQ", r"huber", _C["vermillion"], "--", "P", "..", None),
    ("M-estimator", r"m.?estimator", _C["vermillion"], "--", "p", "..", None),
    ("MSAC", r"\bmsac\b", _C["yellow"], "-.", "D", "||", None),
    ("RANSAC", r"ransac", _C["orange"], "-", "o", "\\\\", None),
    ("LSQ", r"^lsq\b|least.?squares|\bols\b", _C["sky blue"], "--", "s", "", None),
    ("sinusoid (free ω)", r"^sin\b|sinusoid", _C["reddish purple"], ":", "v", "..", None),
    ("ML", r"^ml\b|maximum.?likelihood", _C["black"], "--", "*", "", None),
    ("D-optimal", r"d.?optimal", _C["blue"], "-", "h", "", None),
    ("A-optimal", r"a.?optimal", _C["vermillion"], "--", "d", "//", None),
    ("random", r"^random\b", _C["grey"], ":", "s", "..", None),
    # track initiation (03, 04)
    ("angle logic 3/4", r"angle.?(constrained|logic)|logic.*angle", _C["reddish purple"], "-.",
     "d", "xx", None),
    ("logic 2/3", r"logic 2/3", _C["sky blue"], "--", "v", "..", None),
    ("logic 3/4", r"logic", _C["blue"], "-", "s", "", None),
    ("verified modified Hough", r"verified|modified hough.*\bours\b", _C["bluish green"], "-",
     "p", "//", None),
    ("modified Hough (26-nbhd)", r"modified hough.*26", _C["vermillion"], ":", "d", "++", None),
    ("modified Hough", r"modified hough", _C["vermillion"], "-", "v", "\\\\", None),
    ("classic Hough", r"hough", _C["orange"], "--", "o", "||", None),
    ("hypothesis test", r"hypothesis|sprt", _C["blue"], "-", "*", "", None),
    ("Stone Soup", r"stone.?soup", _C["bluish green"], ":", "^", "--", None),
    # Kalman variants (05)
    ("BEAK-ST-GT", r"beak.?st.?gt", _C["orange"], ":", "x", "xx", None),
    ("BEAK-ST-SKF", r"beak.?st.?skf", _C["bluish green"], "-.", "^", "//", None),
    ("BEAK-ST", r"beak|confidence|\bakf\b|adaptive kf", _C["blue"], "-", "H", "", None),
    ("Sage–Husa", r"sage", _C["reddish purple"], "--", "D", "..", None),
    ("CV KF", r"\bcv\b.*kf|constant.?velocity", _C["sky blue"], "--", "<", "++", None),
    ("SKF", r"\bskf\b|standard k(alman|f)", _C["bluish green"], "-.", ">", "//", None),
    ("Baseline", r"baseline", _C["grey"], "--", "H", "..", None),
    # peers and our library (benchmarks, beyond sections)
    ("SEP", r"\bsep\b", _C["orange"], "--", "X", "//", None),
    ("OpenCV", r"opencv|\bcv2\b", _C["reddish purple"], "-.", "h", "\\\\", None),
    ("FilterPy", r"filterpy", _C["sky blue"], ":", "o", "..", None),
    ("photutils", r"photutils", _C["vermillion"], ":", "P", "++", None),
    ("eotrack", r"eotrack|\bours\b", _C["blue"], "-", "8", "", None),
]
_COMPILED = [(name, re.compile(pat), *rest) for name, pat, *rest in _REGISTRY]


def _normalise(name: str) -> str:
    s = name.lower().replace("_", " ").replace("–", "-").replace("—", "-")
    return re.sub(r"\s+", " ", s).strip()


def known_methods() -> tuple[str, ...]:
    """Canonical names of every method the house style knows, in registry order."""
    return tuple(r[0] for r in _REGISTRY)


def method_style(name: str) -> MethodStyle:
    """The fixed style of a method, the same in every figure of the collection.

    The name is matched case-insensitively against the registry (``"wransac_refit"``,
    ``"WRANSAC (refit weights, 1 step)"`` → the same style; ``"logic 3/4"`` and
    ``"angle logic 3/4"`` differ in colour, line style and marker).

    Parameters
    ----------
    name : str
        A method's name as the experiments spell it (``"lsq"``, ``"RANSAC"``,
        ``"modified Hough 3/4 (ours)"``, ``"BEAK-ST"``, ``"Sage-Husa"``, ``"SEP"``, ``"paper"``…).

    Returns
    -------
    MethodStyle
        Use ``ax.plot(x, y, label=..., **method_style(m).line())``, ``.bar()`` for bars,
        ``.scatter()`` for scatter plots.

    Raises
    ------
    TypeError
        If ``name`` is not a string.
    KeyError
        If no method of the registry matches; the message lists the closest known names.
    """
    if not isinstance(name, str):
        raise TypeError(f"name must be a method name (str), got {type(name).__name__}")
    s = _normalise(name)
    for canonical, pat, color, ls, marker, hatch, mfc in _COMPILED:
        if pat.search(s):
            return MethodStyle(canonical, color, ls, marker, hatch, mfc)
    close = difflib.get_close_matches(name, known_methods(), n=4, cutoff=0.3)
    raise KeyError(f"no house style for method {name!r}; known methods include "
                   f"{', '.join(close or known_methods()[:8])} (see eotrack.plotting."
                   f"known_methods()); use series_styles(n) for series that are not methods")


def series_styles(n: int) -> list[MethodStyle]:
    """``n`` distinct styles (colour, line style and marker all differ between neighbours) for
    series that are not methods (objects, stations, thresholds…).

    Raises
    ------
    ValueError
        If ``n`` is not a positive integer or more than 24 (a legend that long is unreadable).
    """
    if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= 24:
        raise ValueError(f"n must be an integer in 1..24, got {n!r}")
    hatches = ["", "//", "\\\\", "..", "xx", "++", "||", "--"]
    out = []
    for i in range(n):
        c = _CYCLE_COLOURS[i % 8]
        ls = _CYCLE_LS[(i + i // 8) % 8]
        mk = _CYCLE_MARKERS[(i + 2 * (i // 8)) % 8]
        out.append(MethodStyle(f"series {i + 1}", c, ls, mk, hatches[(i + i // 8) % 8]))
    return out
