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
