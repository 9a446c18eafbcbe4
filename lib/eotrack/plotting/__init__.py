"""The collection's one house style for figures, and the figure lint's rules.

Notebooks and ``make repro`` draw with the same settings, so a figure looks the same in a
notebook, in a REPORT and in the book.

Using it
--------
* **Turn it on.** Notebooks call :func:`eotrack.notebook.setup_notebook` (which calls
  :func:`use_house_style`); ``python -m eotrack.repro`` calls :func:`use_house_style` once.
  In a test or a script: ``with house_style(): fig = plot_something(...)``.
* **One look per method.** ``ax.plot(x, y, label="RANSAC", **method_style("ransac").line())``;
  bars: ``**method_style(m).bar()`` (colour and hatch), scatter: ``.scatter()``. The colour is
  from the Okabe–Ito palette and every pair of methods also differs in line style or marker,
  so no pair relies on colour alone (deuteranopia, greyscale print). Names are matched
  case-insensitively (``"wransac_refit"`` and ``"WRANSAC (refit weights, 1 step)"`` are the
  same method). Series that are not methods (objects, stations): ``series_styles(n)``.
  Overlays on dark star-field images: the colours in :data:`ON_IMAGE`.
* **Axes.** ``label_axes(ax, x="time $t$", xunit="s", y=r"$P_\\mathrm{FA}$", title=...)``:
  every axis labelled with its unit, symbols in mathtext; every panel titled (the title says
  what is shown). Log axes: ``log_axis(ax, "y")`` labels decades as plain numbers.
* **Legends off the data.** ``legend_outside(ax)`` beside one axes, ``legend_outside(fig,
  where="below")`` one shared legend for all panels; or ``ax.legend(loc=...)`` in a corner the
  lint confirms is free.
* **Paper values beside ours.** ``paper_values(ax, x, y)`` (hollow black diamonds),
  ``kind="bar"`` (hollow hatched bars, offset ``x`` to stand beside ours), ``kind="hline"`` /
  ``kind="band"``, wherever the paper gives numbers.
* **Size.** Default figure :data:`FIG_WIDTH_IN` × :data:`FIG_HEIGHT_IN` in; the book's column is
  :data:`BOOK_WIDTH_IN` in (:data:`BOOK_COLUMN_PX` px). A figure wider than the column is
  shrunk by the browser; at the column width no text may be under :data:`MIN_FONT_PT` pt (the
  house fonts are 9–11 pt: do not pass ``fontsize`` below 9 to a figure of default width).

The lint
--------
:func:`lint_figure` draws a figure and returns its problems: overlapping text (each line of
every text drawn — multi-line labels and outlined text included — as the renderer lays it out,
rotated labels as rotated boxes), text cut off by its axes or the figure's edge, a legend
covering data (lines, markers, bars, filled bands, error bars, patches, images), an axis
without a label, text under 8 pt at the book's width, a figure or panel without a title, two
series with the same colour and style or with the same style in colours a deuteranope cannot
tell apart (red vs green), colour-coded data without any key (lines, per-point scatter colours,
bands, bars), tick labels like ``2×10⁰`` or ``1e−03`` (on colour bars too), a figure so wide
that the book shows it below 80 % of its size; and texts that touch (less than 1 px apart), a
symbol's subscript written as plain text (``P_D``, ``t_i`` outside ``$…$``), a reference line
(``axhline``/``axvline``, a dashed constant) with no legend entry and no text beside it, a text
drawn over data markers, a series hidden under another one drawn later, a colour-mapped scatter
without a colour bar. ``tests/figures/`` runs it on every public figure function of the library,
on every REPORT figure (re-linted from the pickled figure ``make repro`` stores beside its PNG)
and on every figure the notebooks store (the kernel's verdict, which must be of the current
lint version).
"""

from __future__ import annotations

from typing import Any

from . import helpers as _helpers
from . import lint as _lint
from . import style as _style_module
from .helpers import *  # noqa: F403  (the names are each submodule's __all__)
from .helpers import register_figure_descriptions
from .lint import *  # noqa: F403
from .style import *  # noqa: F403
from .style import HOUSE_RC, use_house_style

#: The package's names: each submodule's ``__all__`` (listed once, there) and the two old names.
__all__ = sorted({*_helpers.__all__, *_lint.__all__, *_style_module.__all__, "STYLE", "style"})

#: The house rc settings (the name used before :data:`HOUSE_RC`; the same dict).
STYLE: dict[str, Any] = HOUSE_RC


def style() -> None:
    """Apply the house style globally (the name used before :func:`use_house_style`); in a
    notebook kernel also :func:`register_figure_descriptions` (alt text for the book).
    :func:`eotrack.notebook.setup_notebook` calls it."""
    use_house_style()
    register_figure_descriptions()
