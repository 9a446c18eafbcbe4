"""Tests of eotrack.imaging.extraction."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.imaging import render_gaussian_spots
from eotrack.imaging.extraction import (
    ExtractionConfig,
    dynamic_range,
    extract_stars,
    grey_quantiles,
    image_confidence,
)


def _frame(rng, bg=20.0, gradient=0.0):
    xy = np.array([[30.3, 40.7], [90.6, 80.2], [60.1, 20.9]])
    flux = np.array([3000.0, 1500.0, 800.0])
    img = render_gaussian_spots((128, 128), xy, flux, 1.0)
    _, xx = np.mgrid[0:128, 0:128]
    img += bg + gradient * xx / 128
    img += rng.normal(0, 2.0, img.shape)
    return np.clip(np.rint(img), 0, 255).astype(np.uint8), xy


@pytest.mark.parametrize("method", ["adaptive", "global"])
def test_centroids_brightest_first(method):
    img, xy = _frame(np.random.default_rng(0))
    out = extract_stars(img, method=method)
    xs, flux = out
    assert len(xs) >= 3
    assert np.all(np.diff(flux) <= 0)
    for i, p in enumerate(xy):
        assert np.min(np.hypot(*(xs - p).T)) < 0.25, i  # thresholded CoG: pixel locking


def test_centroid_grow_reduces_bias():
    img, xy = _frame(np.random.default_rng(0))
    err = []
    for grow in (0, 2):
        out = extract_stars(img, config=ExtractionConfig(centroid_grow=grow))
        err.append(max(np.min(np.hypot(*(out.xy - p).T)) for p in xy))
    assert err[1] < err[0] and err[1] < 0.08


def test_adaptive_survives_gradient_global_does_not():
    img, xy = _frame(np.random.default_rng(1), bg=60, gradient=150)
    a = extract_stars(img)
    assert np.min(np.hypot(*(a.xy - xy[2]).T)) < 0.3
    g = extract_stars(img, method="global")
    assert len(g.xy) == 0 or np.min(np.hypot(*(g.xy - xy[2]).T)) > 0.3


def test_quantiles_and_dynamic_range():
    img = np.repeat(np.arange(256, dtype=np.uint8)[None], 10, axis=0)
    g5, g95 = grey_quantiles(img)
    assert (g5, g95) == (12, 243)
    assert dynamic_range(img) == pytest.approx((243 - 12) / 255)


def test_low_dynamic_range_uses_roi():
    img, _ = _frame(np.random.default_rng(2), bg=200)
    r = extract_stars(img, return_info=True, config=ExtractionConfig(r_min=0.5))
    assert r.dynamic_range < 0.5 and r.roi_fraction < 0.5 and len(r) >= 2


def test_image_confidence_range():
    c = image_confidence(np.array([0.0, 8.0, 100.0, 100.0]), np.array([1.0, 1.0, 1.0, 10.0]),
                         1.0)
    assert c[0] == 0 and 0 < c[1] < c[2] <= 1 and c[3] < c[2]


def test_bad_images():
    with pytest.raises(ValueError, match="image is empty"):
        extract_stars(np.zeros((0, 5)))
    with pytest.raises(ValueError, match="constant"):
        extract_stars(np.full((20, 20), 7))
    with pytest.raises(ValueError, match="NaN"):
        extract_stars(np.full((20, 20), np.nan))
    with pytest.raises(ValueError, match="2-D"):
        extract_stars(np.zeros((4, 20, 20)))
    with pytest.raises(TypeError, match="image"):
        extract_stars("image.png")
    img, _ = _frame(np.random.default_rng(0))
    with pytest.raises(ValueError, match="method"):
        extract_stars(img, method="otsu")
    with pytest.raises(ValueError, match="k_b"):
        ExtractionConfig(k_b=-1)
    with pytest.raises(ValueError, match="constant"):
        dynamic_range(np.ones((5, 5)))
    with pytest.raises(ValueError, match="q must be"):
        grey_quantiles(img, (0.9, 0.1))
    with pytest.raises(ValueError, match="flux_ref"):
        image_confidence([1.0], [1.0], 0.0)
