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
