"""eotrack.notebook: display settings and tidy widget panels (in a plain Python process)."""

from __future__ import annotations

import math
from decimal import Decimal

import matplotlib as mpl
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import pytest
from eotrack.notebook import (
    dropdown,
    float_slider,
    format_sig,
    int_slider,
    panel,
    readout_format,
    setup_notebook,
    toggle,
    versions,
)
from hypothesis import given
from hypothesis import strategies as st

pytest.importorskip("ipywidgets")


# -- readout_format ----------------------------------------------------------------------------
@pytest.mark.parametrize(("step", "fmt"), [(1, ".0f"), (0.5, ".1f"), (0.25, ".2f"),
                                           (0.005, ".3f"), (10, ".0f"), (1e-7, ".7f"),
                                           (np.float64(0.05), ".2f")])
def test_readout_format_known(step, fmt):
    assert readout_format(step) == fmt


@pytest.mark.parametrize("step", [0, -0.1, math.inf, math.nan, "0.1", None, True])
def test_readout_format_bad_input(step):
    with pytest.raises(ValueError, match="step"):
        readout_format(step)


@given(k=st.integers(1, 9999), d=st.integers(0, 8))
def test_readout_format_shows_step_exactly_and_minimally(k, d):
    step = float(Decimal(k).scaleb(-d))
    fmt = readout_format(step)
    decimals = int(fmt[1:-1])
    assert float(format(step, fmt)) == step  # the readout shows the step exactly
    if decimals > 0:  # and with no needless digit
        assert float(format(step, f".{decimals - 1}f")) != step


# -- controls ----------------------------------------------------------------------------------
def test_float_slider_settings():
    s = float_slider("σ (″)", 0.5, 10.0, 0.005, 3.0)
    assert s.readout_format == ".3f"
    assert s.continuous_update is False
    assert s.description == "σ (″)"
    assert s.style.description_width == "initial"


@pytest.mark.parametrize(("args", "exc"), [
    (("", 0.0, 1.0, 0.1, 0.5), ValueError),
    ((None, 0.0, 1.0, 0.1, 0.5), ValueError),
    (("x (m)", 1.0, 1.0, 0.1, 1.0), ValueError),
    (("x (m)", 0.0, 1.0, 0.0, 0.5), ValueError),
    (("x (m)", 0.0, 1.0, 0.1, 2.0), ValueError),
    (("x (m)", 0.0, math.nan, 0.1, 0.5), ValueError),
    (("x (m)", "0", 1.0, 0.1, 0.5), TypeError),
    (("x (m)", 0.0, 1.0, 0.1, True), TypeError),
])
def test_float_slider_bad_input(args, exc):
    with pytest.raises(exc):
        float_slider(*args)


def test_int_slider_settings_and_bad_input():
    s = int_slider("window (frames)", 2, 20, 2, 8)
    assert (s.value, s.step, s.continuous_update) == (8, 2, False)
    assert int_slider("n", 1, 5).value == 1
    with pytest.raises(TypeError, match="min"):
        int_slider("n", 0.5, 5)
    with pytest.raises(ValueError, match="outside"):
        int_slider("n", 1, 5, 1, 9)
    with pytest.raises(ValueError, match="description"):
        int_slider("  ", 1, 5)


def test_toggle_and_bad_input():
    t = toggle("weighted refit", True)
    assert t.value is True and t.description == "weighted refit"
    with pytest.raises(TypeError, match="bool"):
        toggle("weighted refit", 1)
    with pytest.raises(ValueError, match="description"):
        toggle("", True)


def test_dropdown_and_bad_input():
    d = dropdown("loss", ["0-1", "MSAC"])
    assert d.value == "0-1"
    d = dropdown("loss", {"zero-one": "01", "MSAC": "msac"}, value="msac")
    assert d.value == "msac"
    with pytest.raises(ValueError, match="empty"):
        dropdown("loss", [])
    with pytest.raises(ValueError, match="not one of"):
        dropdown("loss", ["a", "b"], value="c")
    with pytest.raises(TypeError, match="list or a dict"):
        dropdown("loss", "ab")
    with pytest.raises(ValueError, match="description"):
        dropdown("", ["a"])


# -- panel -------------------------------------------------------------------------------------
def _draw_factory(calls):
    def draw(sigma, weighted):
        calls.append((sigma, weighted))
        fig, ax = plt.subplots()
        ax.plot([0, 1], [0, sigma if weighted else -sigma])
        return fig
    return draw


def test_panel_builds_redraws_and_does_not_leak(capsys):
    plt.close("all")
    calls = []
    p = panel(_draw_factory(calls), sigma=float_slider("σ (″)", 0.5, 10.0, 0.5, 3.0),
              weighted=toggle("weighted refit", True))
    assert "eotrack-panel" in p._dom_classes
    assert calls == [(3.0, True)]
    assert p.last_draw_s >= 0
    assert plt.get_fignums() == []  # the figure was shown and closed
    sigma, weighted = p.children[0].children
    p.last_draw_s = None
    sigma.value = 3.5
    weighted.value = False
    assert calls == [(3.0, True), (3.5, True), (3.5, False)]
    assert isinstance(p.last_draw_s, float) and p.last_draw_s >= 0
    assert plt.get_fignums() == []
    capsys.readouterr()


def test_panel_accepts_none_and_axes_and_closes_extra_figures():
    plt.close("all")

    def draw_none(n):
        plt.figure()
        plt.plot(range(n))

    def draw_axes(n):
        plt.figure()  # a stray extra figure: closed too
        _, ax = plt.subplots()
        ax.plot(range(n))
        return ax

    for draw in (draw_none, draw_axes):
        p = panel(draw, n=int_slider("n (points)", 2, 9, 1, 3))
        p.children[0].children[0].value = 5
        assert plt.get_fignums() == []


@pytest.mark.parametrize(("kwargs", "exc"), [
    ({"draw": 3, "n": None}, TypeError),
    ({"draw": lambda n: None}, ValueError),
    ({"draw": lambda n: None, "columns": 0, "n": None}, ValueError),
    ({"draw": lambda n: None, "n": 5}, TypeError),
])
def test_panel_bad_input(kwargs, exc):
    kwargs = dict(kwargs)
    if kwargs.get("n", 0) is None:
        kwargs["n"] = int_slider("n", 1, 3)
    draw = kwargs.pop("draw")
    with pytest.raises(exc):
        panel(draw, **kwargs)


def test_panel_draw_errors_raise_and_leak_nothing():
    plt.close("all")

    def wrong_type(n):
        plt.figure()
        return "a figure"

    with pytest.raises(TypeError, match="Figure"):
        panel(wrong_type, n=int_slider("n", 1, 3))
    with pytest.raises(TypeError, match="drew no new figure"):
        panel(lambda n: None, n=int_slider("n", 1, 3))

    def fails_at_2(n):
        plt.figure()
        if n == 2:
            raise RuntimeError("boom")
        return plt.gcf()

    p = panel(fails_at_2, n=int_slider("n", 1, 3))
    with pytest.raises(RuntimeError, match="boom"):  # outside a kernel the error propagates
        p.children[0].children[0].value = 2
    assert plt.get_fignums() == []


# -- display -----------------------------------------------------------------------------------
def test_format_sig_and_bad_input():
    assert format_sig(32.98134) == "32.98"
    assert format_sig(2.8e-17, 2) == "2.8e-17"
    with pytest.raises(ValueError, match="digits"):
        format_sig(1.0, 0)
    with pytest.raises(ValueError, match="digits"):
        format_sig(1.0, True)
    with pytest.raises(TypeError, match="real number"):
        format_sig("1.0")


def test_versions_and_bad_input():
    v = versions(("numpy", "no-such-distribution-eotrack"))
    assert v["numpy"] == np.__version__
    assert v["no-such-distribution-eotrack"] == "not installed"
    with pytest.raises(TypeError, match="sequence"):
        versions("numpy")


def test_setup_notebook_and_bad_input():
    with pytest.raises(ValueError, match="digits"):
        setup_notebook(digits=0)
    opts = ("display.float_format", None, "display.max_colwidth", 50, "display.width", 80,
            "display.max_columns", 20, "display.max_rows", 60)
    with pd.option_context(*opts), np.printoptions(), mpl.rc_context():
        setup_notebook()
        assert pd.get_option("display.float_format")(3.14159265) == "3.142"
        assert pd.get_option("display.max_colwidth") >= 200
        assert np.get_printoptions()["precision"] == 3


def test_panel_untight_renders_once_and_bad_tight():
    plt.close("all")
    calls = []
    p = panel(_draw_factory(calls), tight=False, sigma=float_slider("σ (″)", 0.5, 10.0, 0.5, 3.0),
              weighted=toggle("weighted refit", True))
    p.children[0].children[0].value = 4.0
    assert calls == [(3.0, True), (4.0, True)]
    assert plt.get_fignums() == []
    with pytest.raises(TypeError, match="tight"):
        panel(_draw_factory([]), tight="no", sigma=float_slider("σ (″)", 0.5, 10.0, 0.5, 3.0))


def _png_size(data: bytes) -> tuple[int, int]:
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    return int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")


def test_panel_sends_the_figure_as_png_bytes():
    import ipywidgets

    def draw(n):
        fig, ax = plt.subplots(figsize=(4, 2), dpi=50)
        ax.plot(range(n))
        return fig

    p = panel(draw, tight=False, n=int_slider("n (points)", 2, 9, 1, 3))
    image = next(c for c in p.children if isinstance(c, ipywidgets.Image))
    first = image.value
    assert _png_size(first) == (200, 100)  # tight=False: the figure's own size in pixels
    p.children[0].children[0].value = 7
    assert image.value != first and _png_size(image.value) == (200, 100)
    cropped = panel(draw, n=int_slider("n (points)", 2, 9, 1, 3))  # tight: cropped to content
    w_px, h_px = _png_size(next(c for c in cropped.children
                               if isinstance(c, ipywidgets.Image)).value)
    assert w_px != 200 or h_px != 100


def test_panel_keeps_the_last_good_figure_when_a_redraw_fails():
    import ipywidgets

    plt.close("all")

    def draw(n):
        if n == 2:
            raise RuntimeError("boom")
        fig, ax = plt.subplots(figsize=(2, 2))
        ax.plot(range(n))
        return fig

    p = panel(draw, n=int_slider("n", 1, 3))
    image = next(c for c in p.children if isinstance(c, ipywidgets.Image))
    good = image.value
    with pytest.raises(RuntimeError, match="boom"):  # outside a kernel the error propagates
        p.children[0].children[0].value = 2
    assert image.value == good
    p.children[0].children[0].value = 3
    assert image.value != good
    assert plt.get_fignums() == []


def test_panel_enabled_when_greys_out_a_control():
    def draw(reading, tol):
        fig, ax = plt.subplots(figsize=(2, 2))
        ax.set_title(f"{reading} {tol}")
        return fig

    p = panel(draw, reading=dropdown("reading", ["pooled", "tolerance"]),
              tol=float_slider("tolerance (%)", 0.0, 5.0, 0.5, 1.0),
              enabled_when={"tol": ("reading", ("tolerance",))})
    reading, tol = p.children[0].children
    assert tol.disabled
    reading.value = "tolerance"
    assert not tol.disabled
    reading.value = "pooled"
    assert tol.disabled
    plt.close("all")


@pytest.mark.parametrize("rule", [
    {"nope": ("reading", ["a"])},
    {"tol": ("tol", ["a"])},
    {"tol": ("reading", "tolerance")},
    {"tol": "reading"},
])
def test_panel_enabled_when_bad_input(rule):
    with pytest.raises(ValueError, match="enabled_when"):
        panel(lambda reading, tol: plt.figure(), reading=dropdown("reading", ["a", "b"]),
              tol=float_slider("tolerance (%)", 0.0, 5.0, 0.5, 1.0), enabled_when=rule)
    plt.close("all")
