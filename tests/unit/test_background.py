"""Tests of eotrack.imaging.background."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.imaging import BackgroundConfig, background_map, render_gaussian_spots
from hypothesis import given, settings
from hypothesis import strategies as st


def test_background_follows_gradient_and_ignores_stars():
    rng = np.random.default_rng(0)
    yy, xx = np.mgrid[0:256, 0:256]
    sky = 100 + 0.2 * xx + 0.1 * yy
    stars = render_gaussian_spots((256, 256), rng.uniform(5, 250, (200, 2)), 5e4, 1.3)
    img = sky + stars + rng.normal(0, 5, sky.shape)
    bg = background_map(img, BackgroundConfig(mesh=32))
    assert np.median(np.abs(bg.back - sky)) < 1.5
    assert 4.5 < np.median(bg.rms) < 6.5       # the gradient inside a mesh adds a little
    assert bg.back.shape == img.shape and bg.back.dtype == np.float32


@settings(max_examples=20, deadline=None)
@given(st.integers(10, 150), st.integers(10, 150), st.floats(-1e4, 1e4))
def test_constant_plus_noise_any_shape(h, w, level):
    rng = np.random.default_rng(h * 1000 + w)
    img = level + rng.normal(0, 3.0, (h, w))
    bg = background_map(img, BackgroundConfig(mesh=16))
    assert bg.back.shape == (h, w)
    assert abs(bg.global_back - level) < 2.0
    assert 1.5 < bg.global_rms < 4.5


def test_bad_input():
    with pytest.raises(ValueError, match="2-D"):
        background_map(np.zeros((3, 4, 5)))
    with pytest.raises(TypeError, match="image"):
        background_map("sky.fits")
    with pytest.raises(ValueError, match="NaN"):
        background_map(np.full((10, 10), np.nan))
    with pytest.raises(ValueError, match="filter_size"):
        BackgroundConfig(filter_size=4)
    with pytest.raises(ValueError, match="mesh"):
        BackgroundConfig(mesh=2)
    with pytest.raises(TypeError, match="BackgroundConfig"):
        background_map(np.zeros((10, 10)), config={"mesh": 8})


# --------------------------------------------------------------------------------------------
# quantised frames (issue 28): integer / gain-times-integer values with noise σ of about a step
# --------------------------------------------------------------------------------------------

def _quantised(rng, sigma, frac, gain=1.0, offset=100.0, dtype=np.uint16, shape=(256, 256)):
    k = np.round(frac + sigma * rng.standard_normal(shape))
    return (k * gain + offset).astype(dtype)


def test_quantisation_step():
    from eotrack.imaging import quantisation_step
    rng = np.random.default_rng(1)
    assert quantisation_step(_quantised(rng, 0.3, 0.0)) == 1.0
    assert quantisation_step(_quantised(rng, 2.0, 0.4).astype(np.uint8)) == 1.0
    g = quantisation_step(_quantised(rng, 0.5, 0.2, gain=0.37, offset=12.1, dtype=np.float32))
    assert abs(g - 0.37) < 1e-4
    assert quantisation_step(_quantised(rng, 0.5, 0.0, gain=2.5, offset=-40.0,
                                        dtype=np.float64)) == pytest.approx(2.5)
    # continuous values, and float32 values at a large offset (their own float grid): 0
    assert quantisation_step(rng.normal(0, 1, (256, 256))) == 0.0
    assert quantisation_step(rng.normal(5e4, 30, (256, 256)).astype(np.float32)) == 0.0
    assert quantisation_step(np.full((8, 8), 3.0)) == 0.0
    with pytest.raises(ValueError, match="2-D"):
        quantisation_step(np.zeros(9))
    with pytest.raises(ValueError, match="NaN"):
        quantisation_step(np.full((9, 9), np.inf))
    with pytest.raises(TypeError, match="image"):
        quantisation_step(None)


@pytest.mark.parametrize("sigma", [0.2, 0.3, 0.5, 0.8, 1.5])
def test_quantised_noise_does_not_collapse(sigma):
    """The mesh σ of quantised values is their standard deviation (it was ~10⁻⁴ DN for
    σ = 0.2–0.5 DN on a step: most samples equal the median, the interquartile start is 0),
    and the level is their mean, for any sub-step offset, gain and dtype."""
    rng = np.random.default_rng(int(sigma * 100))
    for frac in (0.0, 0.3, 0.5):
        for gain, off, dt in ((1.0, 100.0, np.uint16), (0.37, 12.1, np.float32),
                              (2.5, -40.0, np.float64)):
            img = _quantised(rng, sigma, frac, gain, off, dt)
            bg = background_map(img)
            assert bg.quantum == pytest.approx(gain, rel=1e-3)
            sd, mu = float(img.std()), float(img.mean())
            assert 0.85 * sd < float(np.median(bg.rms)) < 1.15 * sd, (frac, gain)
            assert float(bg.rms.min()) > 0.7 * sd
            assert abs(float(np.median(bg.back)) - mu) < 0.05 * gain + 0.2 * sd


def test_quantised_collapse_without_the_quantum():
    """The test can fail: treating the same frame as continuous collapses σ (the old estimate)."""
    img = _quantised(np.random.default_rng(2), 0.3, 0.0)
    assert float(np.median(background_map(img, BackgroundConfig(quantum=0)).rms)) < 0.01
    assert float(np.median(background_map(img).rms)) > 0.25


def test_continuous_data_unchanged_by_the_quantum_logic():
    rng = np.random.default_rng(4)
    img = rng.normal(100.0, 3.0, (200, 300))
    a, b = background_map(img), background_map(img, BackgroundConfig(quantum=0))
    assert a.quantum == 0.0
    assert np.array_equal(a.back, b.back) and np.array_equal(a.rms, b.rms)


def test_quantum_config_checked():
    with pytest.raises(ValueError, match="quantum"):
        BackgroundConfig(quantum=-1.0)
    with pytest.raises((TypeError, ValueError), match="quantum"):
        BackgroundConfig(quantum="1")


def test_quantisation_step_survives_patched_pixels_and_large_levels():
    """Cosmetic corrections (review 28 #3) and integer levels far above 2·10⁵ (#4): one
    off-lattice pixel, 100 hot pixels replaced by a float, a bad column interpolated from 3 or 2
    neighbours, and integer frames at 3·10⁵ and 3·10⁶ keep Δ = 1."""
    from eotrack.imaging import quantisation_step
    rng = np.random.default_rng(6)

    def base(level=100.0):
        return np.round(level + 0.3 * rng.standard_normal((512, 512)))

    frames = []
    a = base()
    a[0, 0] = 100.37
    frames.append(a)
    a = base()
    idx = rng.integers(0, 512, (100, 2))
    a[idx[:, 0], idx[:, 1]] = 100.001
    frames.append(a)
    for cols in ((255, 257, 258), (255, 257)):
        a = base()
        a[:, 256] = a[:, list(cols)].mean(axis=1)
        frames.append(a)
    frames += [base(3e5), base(3e6)]
    for i, f in enumerate(frames):
        assert quantisation_step(f) == pytest.approx(1.0), i
        assert float(np.median(background_map(f).rms)) > 0.25, i
