"""The lint's rules fire on the defects they name and stay quiet on a clean figure; the house
style's helpers reject bad input with errors that name the argument."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest
from eotrack.plotting import (
    BOOK_WIDTH_IN,
    MIN_FONT_PT,
    known_methods,
    label_axes,
    legend_outside,
    lint_figure,
    log_axis,
    method_style,
    paper_values,
    plain_number,
    series_styles,
)


def _rules(fig):
    return sorted({p.rule for p in lint_figure(fig)})


def _clean():
    fig, ax = plt.subplots()
    x = np.linspace(1, 10, 30)
    ax.plot(x, x, label="LSQ", **method_style("lsq").line())
    ax.plot(x, 2 * x, label="RANSAC", **method_style("ransac").line())
    label_axes(ax, x="time $t$", xunit="s", y="error", yunit="″", title="A clean figure")
    legend_outside(ax)
    return fig, ax


def test_clean_figure_passes():
    fig, _ = _clean()
    assert lint_figure(fig) == []


def test_missing_title_and_labels():
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    assert _rules(fig) == ["axis-label", "title"]


def test_untitled_panel_in_multi_panel_figure():
    fig, (a, b) = plt.subplots(1, 2)
    for ax in (a, b):
        label_axes(ax, x="x", y="y")
    a.set_title("left")
    assert "title" in _rules(fig)
    b.set_title("right")
    assert "title" not in _rules(fig)


def test_overlapping_tick_labels():
    fig, ax = plt.subplots()
    ax.set_xticks(range(8), ["a long object name"] * 8)
    label_axes(ax, x="object", y="y", title="t")
    assert "overlapping-text" in _rules(fig)
    ax.set_xticks(range(8), ["a long object name"] * 8, rotation=60, ha="right")
    assert "overlapping-text" not in _rules(fig)  # rotated boxes, not their bounding boxes


def test_legend_covering_lines_bars_and_images():
    fig, ax = plt.subplots()
    ax.plot(np.arange(10), np.full(10, 5.0), label="flat")
    ax.bar([4.5], [5.0], label="bar")
    label_axes(ax, x="x", y="y", title="t")
    ax.legend(loc="center")
    assert "legend-covers-data" in _rules(fig)
    fig, ax = plt.subplots()
    ax.imshow(np.zeros((8, 8)))
    ax.plot([1], [1], "o", label="star")
    label_axes(ax, x="x", xunit="px", y="y", yunit="px", title="image")
    ax.legend(loc="upper right")
    assert "legend-covers-data" in _rules(fig)
    legend_outside(ax, where="below")
    assert "legend-covers-data" not in _rules(fig)


def test_small_text_at_book_width():
    fig, ax = _clean()
    ax.text(2, 5, "tiny note", fontsize=MIN_FONT_PT - 1)
    assert "small-text" in _rules(fig)
    fig, ax = _clean()
    fig.set_size_inches(2 * BOOK_WIDTH_IN, 4)  # shrunk by half in the book
    assert {"small-text", "too-wide"} <= set(_rules(fig))


def test_width_as_saved_includes_the_tight_box_padding():
    """savefig(bbox_inches="tight") pads 0.1 in on each side: a figure whose drawn box is just
    under the limit is saved just over it (wransac's orbit-fit figure: 903 px in the book)."""
    import matplotlib as mpl
    from eotrack.plotting.lint import MIN_BOOK_SCALE, saved_width_in
    from eotrack.plotting.style import BOOK_COLUMN_PX

    fig, _ = _clean()
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    tight = fig.get_tightbbox(renderer).width
    assert saved_width_in(fig, renderer) == pytest.approx(
        tight + 2 * mpl.rcParams["savefig.pad_inches"])
    limit_in = BOOK_COLUMN_PX / MIN_BOOK_SCALE / mpl.rcParams["savefig.dpi"]
    # widen the figure until its drawn box is 0.05–0.15 in under the limit: saved, it is over
    for _ in range(20):
        fig.canvas.draw()
        tight = fig.get_tightbbox(fig.canvas.get_renderer()).width
        if limit_in - 0.15 < tight < limit_in - 0.05:
            break
        fig.set_size_inches(fig.get_figwidth() + (limit_in - 0.1 - tight), fig.get_figheight())
    assert limit_in - 0.15 < tight < limit_in - 0.05
    assert "too-wide" in _rules(fig)


def test_same_colour_and_style():
    fig, ax = _clean()
    ax.plot([1, 2], [3, 3], label="another LSQ", **method_style("lsq").line())
    assert "same-style" in _rules(fig)


def test_log_axis_labels():
    fig, ax = _clean()
    ax.set_yscale("log")
    ax.set_ylim(2, 9)
    assert "log-labels" in _rules(fig)
    log_axis(ax, "y")
    assert "log-labels" not in _rules(fig)


def test_method_styles_distinct_without_colour():
    # every pair of known methods differs in line style or marker, not only colour
    seen = {}
    for m in known_methods():
        s = method_style(m)
        key = (s.linestyle, s.marker)
        assert key not in seen, f"{s.name} and {seen[key]} differ only in colour"
        seen[key] = s.name
    pairs = [("logic 3/4", "angle logic 3/4"), ("modified Hough 3/4 (paper)",
                                                "modified Hough 3/4 (ours)"),
             ("Baseline", "BEAK-ST-GT"), ("lsq", "ransac"), ("wransac_refit", "wransac")]
    for a, b in pairs:
        sa, sb = method_style(a), method_style(b)
        assert (sa.linestyle, sa.marker) != (sb.linestyle, sb.marker), (a, b)


def test_method_style_matches_spellings():
    assert method_style("wransac_refit") == method_style("WRANSAC (refit weights, 1 step)")
    assert method_style("Sage–Husa").name == method_style("sage-husa").name == "Sage–Husa"
    assert method_style("logic 3/4").name != method_style("angle logic 3/4").name


def test_bad_inputs():
    with pytest.raises(TypeError, match="name"):
        method_style(3)
    with pytest.raises(KeyError, match="no house style for method 'frobnicate'"):
        method_style("frobnicate")
    with pytest.raises(ValueError, match="n must be"):
        series_styles(0)
    fig, ax = plt.subplots()
    with pytest.raises(ValueError, match="where"):
        legend_outside(ax, where="inside")
    with pytest.raises(TypeError, match="target"):
        legend_outside("ax")
    with pytest.raises(TypeError, match="ax must be"):
        label_axes(None, x="x")
    with pytest.raises(TypeError, match="z is given"):
        label_axes(ax, z="height")
    with pytest.raises(ValueError, match="which"):
        log_axis(ax, "z")
    with pytest.raises(ValueError, match="kind"):
        paper_values(ax, [1], [1], kind="pie")
    with pytest.raises(ValueError, match="same non-empty shape"):
        paper_values(ax, [1, 2], [1])
    with pytest.raises(TypeError, match="fig must be"):
        lint_figure("figure")
    with pytest.raises(ValueError, match="unknown rules"):
        lint_figure(fig, rules=("pretty",))


def test_plain_numbers():
    assert [plain_number(v) for v in (0.01, 1.0, 20.0, 1000.0)] == ["0.01", "1", "20", "1000"]
    assert plain_number(1e6) == "$10^{6}$"


def test_series_styles_distinct():
    st = series_styles(16)
    assert len({(s.color, s.linestyle, s.marker) for s in st}) == 16


def test_colour_coded_data_needs_a_key():
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1], color="tab:green")
    ax.plot([0, 1], [1, 0], color="tab:red")
    label_axes(ax, x="x", y="y", title="pairs")
    assert "unkeyed-colours" in _rules(fig)
    ax.plot([], [], color="tab:green", label="correct pair")
    ax.plot([], [], color="tab:red", ls="--", label="false pair")
    legend_outside(ax)
    assert "unkeyed-colours" not in _rules(fig)


def test_describe_figure():
    from eotrack.plotting import describe_figure

    fig, (a, b) = plt.subplots(1, 2)
    a.set_title("left")
    b.set_title("right")
    fig.suptitle("Both")
    assert describe_figure(fig) == "Figure: Both — left; right"
    with pytest.raises(TypeError, match="fig must be"):
        describe_figure(a)


# --- blind spots of the first lint (review of issue 23): each test fails on the old rules ---

def test_multi_line_text_overlaps_line_by_line():
    """A text with a line break is measured line by line (the renderer draws it line by line,
    and the first lint saw none of it): 'target' over the second line of 'long\\ngate'."""
    fig, ax = _clean()
    ax.text(5, 10, "target", ha="center", va="bottom", fontsize=10)
    ax.text(5, 10.3, "long\ngate", ha="center", va="top", fontsize=10)
    msgs = [p.message for p in lint_figure(fig) if p.rule == "overlapping-text"]
    assert msgs and "a line of 'long gate'" in msgs[0]


def test_multi_line_text_with_a_short_line_is_not_its_bounding_box():
    """Per-line rectangles: a label beside the short second line of a text does not overlap
    it, although it lies inside the text's bounding box."""
    fig, ax = _clean()
    ax.text(1, 15, "a long first line here\nshort", ha="left", va="top", fontsize=10)
    t = ax.text(1, 15, "short", ha="left", va="top", fontsize=10)
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    bb = t.get_window_extent(r)
    ax.text(ax.transData.inverted().transform((bb.x1 + 40, 0))[0],
            ax.transData.inverted().transform((0, bb.y0 - bb.height * 1.3))[1], "beside",
            ha="left", va="bottom", fontsize=10)
    t.remove()
    assert "overlapping-text" not in _rules(fig)


def test_outlined_text_is_seen():
    """Text with an outline (path effects) bypasses the renderer's draw_text: still linted."""
    import matplotlib.patheffects as pe

    fig, ax = _clean()
    ax.text(2, 5, "outlined", fontsize=MIN_FONT_PT - 1,
            path_effects=[pe.withStroke(linewidth=3, foreground="white")])
    assert "small-text" in _rules(fig)
    ax.text(2.05, 5.05, "over it", fontsize=10,
            path_effects=[pe.withStroke(linewidth=3, foreground="white")])
    assert "overlapping-text" in _rules(fig)


def test_small_multi_line_bar_labels():
    """Bar labels with a line break at 7 pt (01's budget bars) are small text."""
    fig, ax = plt.subplots()
    bars = ax.bar([0, 1], [3, 4], **method_style("lsq").bar())
    ax.bar_label(bars, labels=["LSQ\n62 %", "RANSAC\n25 %"], fontsize=7)
    label_axes(ax, x="method", y="share", yunit="%", title="budget")
    assert "small-text" in _rules(fig)


def test_clipped_text():
    """A clip_on text running past its axes is cut off in the saved figure."""
    fig, ax = _clean()
    ax.text(9.5, 5, "a label that runs past the edge", clip_on=True, fontsize=10)
    assert "clipped-text" in _rules(fig)
    fig, ax = _clean()
    ax.text(9.5, 5, "a label that runs past the edge", fontsize=10)  # not clipped: shown
    assert "clipped-text" not in _rules(fig)


def test_unkeyed_bars_scatter_lists_and_bands():
    """Colour-coded bars, a scatter with one colour per point and filled bands need a key."""
    fig, ax = plt.subplots()
    ax.bar([0, 1], [1, 2], color=["#E69F00", "#0072B2"])
    label_axes(ax, x="x", y="y", title="bars")
    assert "unkeyed-colours" in _rules(fig)
    fig, ax = plt.subplots()
    ax.scatter([0, 1, 2, 3], [0, 1, 0, 1], c=["#009E73", "#D55E00"] * 2)
    label_axes(ax, x="x", y="y", title="pairs")
    assert "unkeyed-colours" in _rules(fig)
    fig, ax = plt.subplots()
    ax.fill_between([0, 1], 0, 1, color="#56B4E9")
    ax.fill_between([0, 1], 1, 2, color="#CC79A7")
    label_axes(ax, x="x", y="y", title="bands")
    assert "unkeyed-colours" in _rules(fig)
    ax.fill_between([], [], [], color="#56B4E9", label="inner")
    ax.fill_between([], [], [], color="#CC79A7", label="outer")
    legend_outside(ax)
    assert "unkeyed-colours" not in _rules(fig)


def test_legend_over_bands_and_error_bars():
    """A legend over a filled band (fill_between) or over error bars covers data."""
    for draw in (lambda ax: ax.fill_between(np.arange(10), 0, 10, label="band", alpha=0.3),
                 lambda ax: ax.errorbar(np.arange(10), np.full(10, 5.0), yerr=1, fmt="none",
                                        label="error bars")):
        fig, ax = plt.subplots()
        draw(ax)
        label_axes(ax, x="x", y="y", title="t")
        ax.legend(loc="center")
        assert "legend-covers-data" in _rules(fig)
        legend_outside(ax)
        assert "legend-covers-data" not in _rules(fig)


def test_red_green_pairs_in_the_same_style():
    """Red vs green in the same style is one colour to a deuteranope (02's Fig. 4)."""
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1], color="tab:green", ls="-", marker="", label="correct pair")
    ax.plot([0, 1], [1, 0], color="tab:red", ls="-", marker="", label="false pair")
    label_axes(ax, x="x", y="y", title="pairs")
    legend_outside(ax)
    assert "same-style" in _rules(fig)
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1], color="tab:green", ls="-", marker="", label="correct pair")
    ax.plot([0, 1], [1, 0], color="tab:red", ls="--", marker="", label="false pair")
    label_axes(ax, x="x", y="y", title="pairs")
    legend_outside(ax)
    assert "same-style" not in _rules(fig)
    fig, ax = plt.subplots()  # bands in the same hatch
    ax.fill_between([0, 1], 0, 1, color="tab:green", label="correct")
    ax.fill_between([0, 1], 1, 2, color="tab:red", label="false")
    label_axes(ax, x="x", y="y", title="bands")
    legend_outside(ax)
    assert "same-style" in _rules(fig)


def test_okabe_ito_pairs_pass_the_deuteranopia_check():
    from eotrack.plotting.lint import _look_alike_deutan
    from matplotlib.colors import to_rgba

    oi = ["#000000", "#E69F00", "#56B4E9", "#009E73", "#F0E442", "#0072B2", "#D55E00",
          "#CC79A7"]
    assert not any(_look_alike_deutan(to_rgba(a), to_rgba(b)) for a in oi for b in oi if a != b)
    assert _look_alike_deutan(to_rgba("tab:red"), to_rgba("tab:green"))


def test_computer_notation_tick_labels():
    """'1e−03' is not how a decade reads (log or linear axis, tick label or offset text)."""
    from matplotlib.ticker import FuncFormatter

    fig, ax = _clean()
    ax.set_yscale("log")
    ax.set_ylim(1e-3, 10)
    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:.0e}".replace("-", "−")))
    assert "log-labels" in _rules(fig)
    log_axis(ax, "y")
    assert "log-labels" not in _rules(fig)
    fig, ax = plt.subplots()
    ax.plot([0, 1], [1e-3, 2e-3])
    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:.1e}"))
    label_axes(ax, x="x", y="y", title="linear")
    assert "log-labels" in _rules(fig)  # '1.0e-03' on a linear axis too


def test_red_green_scatter_pairs():
    """Red vs green scatter markers of the same shape (edge in the face colour) look alike."""
    fig, ax = plt.subplots()
    ax.scatter([0, 1], [0, 1], color="tab:green", label="correct")
    ax.scatter([0, 1], [1, 0], color="tab:red", label="false")
    label_axes(ax, x="x", y="y", title="pairs")
    legend_outside(ax)
    assert "same-style" in _rules(fig)


# --- rules of the second review (issue 23): each test fails on a bad figure, passes on a good one ---

def test_raw_symbol_beside_mathtext():
    fig, ax = _clean()
    t = ax.text(2, 15, "P_D at P_FA = 0.01")
    assert "raw-symbol" in _rules(fig)
    t.set_text(r"$P_\mathrm{D}$ at $P_\mathrm{FA} = 0.01$")
    assert "raw-symbol" not in _rules(fig)
    ax.set_xlabel("time t_i (s)")
    assert "raw-symbol" in _rules(fig)
    ax.set_xlabel(r"time $t_i$ (s)")
    ax.set_title("wransac_refit vs ransac")  # an identifier, not a symbol: not this rule
    assert "raw-symbol" not in _rules(fig)


def test_unlabelled_reference_line():
    fig, ax = _clean()
    ref = ax.axhline(12, color="0.4", ls="--")
    assert "unlabelled-reference" in _rules(fig)
    ax.text(9.5, 12.3, "27″ limit", ha="right", va="bottom")
    assert "unlabelled-reference" not in _rules(fig)
    fig, ax = _clean()
    ax.plot([1, 10], [12, 12], color="0.4", ls=":")  # a dashed constant plotted as data
    assert "unlabelled-reference" in _rules(fig)
    fig, ax = _clean()
    ref = ax.axvline(4, color="0.4", ls="--", label="eclipse start")
    legend_outside(ax)
    assert "unlabelled-reference" not in _rules(fig)
    ref.set_label("_nolegend_")
    legend_outside(ax)
    assert "unlabelled-reference" in _rules(fig)
    fig, ax = _clean()
    ax.axhline(0, color="k", lw=0.8)  # the zero baseline needs no name
    assert "unlabelled-reference" not in _rules(fig)


def test_reference_lines_named_once():
    """A ±bound pair is named by one label; a regular grid is not a reference line; one
    grey style key names the dashed line of every series; a shared legend names the same
    line in every panel."""
    fig, ax = _clean()
    ax.axhline(12, color="k", ls="--", lw=0.8, label="paper's ±12″")
    ax.axhline(-12, color="k", ls="--", lw=0.8)
    legend_outside(ax)
    assert "unlabelled-reference" not in _rules(fig)
    fig, ax = _clean()
    for v in (2.0, 4.0, 6.0, 8.0):
        ax.axvline(v, color="0.8", lw=0.8, ls="--")  # cell boundaries
    assert "unlabelled-reference" not in _rules(fig)
    ax.axvline(5.5, color="C3", ls=":")
    assert "unlabelled-reference" in _rules(fig)
    fig, ax = _clean()
    for k, v in enumerate((5.0, 15.0)):
        ax.plot([1, 10], [v + 1, v + 2], color=f"C{k}", label=f"L = {k}")
        ax.axhline(v, color=f"C{k}", ls="--", lw=0.8)
    assert "unlabelled-reference" in _rules(fig)
    ax.plot([], [], color="0.3", ls="--", lw=0.8, label="dashed: analytic, same colour")
    legend_outside(ax)
    assert "unlabelled-reference" not in _rules(fig)
    fig, (a, b) = plt.subplots(1, 2, figsize=(7, 3))
    for k, ax in enumerate((a, b)):
        ax.plot([0, 1], [0, 20], label="elevation" if k == 0 else None)
        ax.axhline(10, color="0.3", ls=":", label="minimum elevation" if k == 0 else None)
        label_axes(ax, x="time", xunit="h", y="elevation", yunit="°", title=f"station {k}")
    legend_outside(fig, where="below")
    assert "unlabelled-reference" not in _rules(fig)


def _titled_pair(gap_px: float):
    """Two panel titles ``gap_px`` apart horizontally (as notebook 04's ρ–θ panels)."""
    fig, (a, b) = plt.subplots(1, 2, figsize=(6, 3))
    for ax in (a, b):
        label_axes(ax, x="x", y="y")
        ax.set_yticks([0.2, 0.5])  # no tick label at the top, next to a title
    ta = a.set_title("accumulator votes (paper)", loc="right")
    tb = b.set_title("votes (ours)", loc="left")
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    right = ta.get_window_extent(r).x1
    left = tb.get_window_extent(r).x0
    x_axes = b.transAxes.inverted().transform((left - (left - right) + gap_px, 0))[0]
    tb.set_position((x_axes, 1.0))
    return fig


def test_touching_texts():
    assert "touching-text" in _rules(_titled_pair(0.3))
    assert "overlapping-text" not in _rules(_titled_pair(0.3))
    assert "touching-text" not in _rules(_titled_pair(6.0))


def test_text_over_markers():
    fig, ax = _clean()
    ax.plot([3, 6, 8], [4, 9, 14], ls="none", label="objects", **method_style("logic").scatter())
    legend_outside(ax)
    t = ax.text(6, 9, "O4", ha="center", va="center")
    assert "text-over-markers" in _rules(fig)
    t.set_position((6.4, 9.0))
    t.set_ha("left")
    t.set_x(6.6)
    assert "text-over-markers" not in _rules(fig)
    fig, ax = _clean()
    ax.scatter([5.0], [5.0], label="target")
    legend_outside(ax)
    ax.annotate("O4", (5.0, 5.0), ha="center", va="center")
    assert "text-over-markers" in _rules(fig)


def test_hidden_series():
    fig, ax = plt.subplots()
    x = np.linspace(0, 10, 50)
    ax.plot(x, np.sin(x), label="RANSAC", color="C1", lw=1.5, ls="-")
    ax.plot(x, np.sin(x), label="ideal", color="k", lw=2.5, ls="-")  # on top: RANSAC gone
    label_axes(ax, x="time", xunit="min", y="Dec", yunit="″", title="prediction")
    legend_outside(ax)
    assert "hidden-series" in _rules(fig)
    fig, ax = plt.subplots()
    ax.plot(x, np.sin(x), label="ideal", color="k", lw=2.5, ls="-")
    ax.plot(x, np.sin(x), label="RANSAC", color="C1", lw=1.5, ls="--")  # on top: both seen
    label_axes(ax, x="time", xunit="min", y="Dec", yunit="″", title="prediction")
    legend_outside(ax)
    assert "hidden-series" not in _rules(fig)
    fig, ax = plt.subplots()  # a visibly different series under a thick line: not hidden
    ax.plot(x, np.sin(x) + 0.3, label="RANSAC", color="C1", lw=1.5, ls="-")
    ax.plot(x, np.sin(x), label="ideal", color="k", lw=2.5, ls="-")
    label_axes(ax, x="time", xunit="min", y="Dec", yunit="″", title="prediction")
    legend_outside(ax)
    assert "hidden-series" not in _rules(fig)


def test_colorbar_tick_labels():
    fig, ax = plt.subplots()
    im = ax.imshow(np.logspace(-4, -2, 64).reshape(8, 8))
    label_axes(ax, x="x", xunit="px", y="y", yunit="px", title="rate")
    cb = fig.colorbar(im, label="rate")
    cb.ax.yaxis.set_major_formatter(plt.FormatStrFormatter("%.0e"))  # '2e-03', …
    assert "colorbar-labels" in _rules(fig)
    cb.ax.yaxis.set_major_formatter(plt.FuncFormatter(plain_number))
    assert "colorbar-labels" not in _rules(fig)
    from matplotlib.colors import LogNorm

    fig, ax = plt.subplots()
    im = ax.imshow(np.logspace(0, 0.6, 64).reshape(8, 8), norm=LogNorm())
    label_axes(ax, x="x", xunit="px", y="y", yunit="px", title="gain")
    fig.colorbar(im, label="gain")
    assert "colorbar-labels" in _rules(fig)  # 2×10⁰, 3×10⁰ minor labels
    from eotrack.plotting import log_axis as _log

    fig2, ax2 = plt.subplots()
    im = ax2.imshow(np.logspace(0, 0.6, 64).reshape(8, 8), norm=LogNorm())
    label_axes(ax2, x="x", xunit="px", y="y", yunit="px", title="gain")
    cb = fig2.colorbar(im, label="gain")
    _log(cb.ax, "y")
    assert "colorbar-labels" not in _rules(fig2)


def test_colour_mapped_scatter_needs_a_colour_bar():
    fig, ax = plt.subplots()
    sc = ax.scatter([1, 2, 3], [1, 2, 3], c=[0.1, 0.5, 0.9], cmap="viridis")
    label_axes(ax, x="x", xunit="px", y="y", yunit="px", title="detections by SNR")
    assert "no-colorbar" in _rules(fig)
    fig.colorbar(sc, label="SNR")
    assert "no-colorbar" not in _rules(fig)


# --- review of the second round (revfigs, 16:13) ---

def test_red_green_marker_series_in_the_same_style():
    """Two marker series in red and green (02's Fig. 4): the fill in the series' own colour is
    colour, not style, so the deuteranopia check compares them."""
    fig, ax = plt.subplots()
    for col, lab in (("tab:green", "correct pair"), ("tab:red", "false pair")):
        ax.plot([1, 2, 3], np.random.default_rng(0).uniform(0, 1, 3), "o", ls="none",
                color=col, label=lab)
    label_axes(ax, x="x", xunit="px", y="y", yunit="px", title="pairs")
    legend_outside(ax)
    assert "same-style" in _rules(fig)
    ax.lines[1].set_marker("s")
    legend_outside(ax)
    assert "same-style" not in _rules(fig)


def test_an_unrelated_text_does_not_name_a_reference_line():
    fig, ax = _clean()
    ax.axhline(12, color="0.4", ls="--")
    ax.text(5.5, 12.4, "the ramp", ha="center", va="bottom")  # mid-line, another colour
    assert "unlabelled-reference" in _rules(fig)
    ax.text(10, 12.2, "limit", ha="right", va="bottom")  # at the line's end
    assert "unlabelled-reference" not in _rules(fig)
    fig, ax = _clean()
    ax.axhline(12, color="C3", ls="--")
    ax.text(5.5, 12.4, "limit", color="C3", ha="center", va="bottom")  # its own colour
    assert "unlabelled-reference" not in _rules(fig)


def test_raw_superscript():
    fig, ax = _clean()
    ax.text(2, 15, "sigma^2 model, chi2 gate")
    assert "raw-symbol" in _rules(fig)
    ax.texts[-1].set_text(r"$\sigma^2$ model, $\chi^2$ gate; 10^3 px")
    assert "raw-symbol" not in _rules(fig)


def test_lint_bbox_is_how_the_figure_is_saved():
    """The verdict follows the bbox given, not the caller's rcParams: a legend placed outside
    is cut off when the figure is saved without the tight box."""
    import matplotlib as mpl

    fig, _ = _clean()
    with mpl.rc_context({"savefig.bbox": "standard"}):
        loose = {p.rule for p in lint_figure(fig)}
        assert "clipped-text" not in {p.rule for p in lint_figure(fig, bbox="tight")}
    assert "clipped-text" in loose
    with pytest.raises(ValueError, match="bbox"):
        lint_figure(fig, bbox="loose")
