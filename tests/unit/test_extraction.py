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


@pytest.mark.parametrize("method", ["sky", "adaptive", "global"])
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
        out = extract_stars(img, method="adaptive", config=ExtractionConfig(centroid_grow=grow))
        err.append(max(np.min(np.hypot(*(out.xy - p).T)) for p in xy))
    assert err[1] < err[0] and err[1] < 0.08


def test_adaptive_survives_gradient_global_does_not():
    img, xy = _frame(np.random.default_rng(1), bg=60, gradient=150)
    for method in ("sky", "adaptive"):
        a = extract_stars(img, method=method)
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
    r = extract_stars(img, method="adaptive", return_info=True, config=ExtractionConfig(r_min=0.5))
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


def test_default_is_accurate_and_uncapped():
    rng = np.random.default_rng(4)
    xy = rng.uniform(8, 248, (120, 2))
    img = render_gaussian_spots((256, 256), xy, 3000.0, 1.2) + 20 + rng.normal(0, 2.0, (256, 256))
    for method in ("sky", "adaptive"):
        r = extract_stars(img, method=method)
        assert len(r.xy) > 100                          # no silent cap of 50
        d = np.min(np.hypot(*(r.xy[None] - xy[:, None]).transpose(2, 0, 1)), axis=1)
        assert np.median(d[d < 1.5]) < 0.05, method


def test_dynamic_range_scaled_to_data():
    rng = np.random.default_rng(5)
    xy = rng.uniform(8, 120, (30, 2))
    img = render_gaussian_spots((128, 128), xy, 20000.0, 1.0) + 200 + rng.normal(0, 20, (128, 128))
    R0 = dynamic_range(img)
    assert 0 < R0 < 1
    assert dynamic_range(img + 1000) == pytest.approx(R0, rel=1e-6)    # an offset changes nothing
    assert dynamic_range(img, full_scale=65535) < R0
    with pytest.raises(ValueError, match="full_scale"):
        dynamic_range(img, full_scale=0)
    # 16-bit data are no longer clipped at 255: the paper's method finds the stars
    r = extract_stars((img + 1000).astype(np.uint16), method="adaptive")
    d = np.min(np.hypot(*(r.xy[None] - xy[:, None]).transpose(2, 0, 1)), axis=1)
    assert np.mean(d < 1) > 0.9


def test_sky_deblends_touching_pair_and_saturated_star():
    rng = np.random.default_rng(6)
    xy = np.array([[40.0, 40.0], [44.2, 41.5], [90.3, 70.6]])     # pair 3.4 σ apart
    img = render_gaussian_spots((128, 128), xy, np.array([8e4, 4e4, 2e6]), 1.3)
    img = np.clip(img + 100 + rng.normal(0, 5, img.shape), 0, 20000)
    r = extract_stars(img)
    for p in xy:
        assert np.min(np.hypot(*(r.xy - p).T)) < 0.6
    assert len(r.xy) <= 6


def test_sky_config_and_cap():
    from eotrack.imaging import SkyConfig

    img, _ = _frame(np.random.default_rng(0))
    r = extract_stars(img, config=SkyConfig(max_sources=2))
    full = extract_stars(img)
    assert len(r.xy) == 2 and np.allclose(r.flux, full.flux[:2])
    with pytest.raises(TypeError, match="SkyConfig"):
        extract_stars(img, config=ExtractionConfig())
    with pytest.raises(TypeError, match="ExtractionConfig"):
        extract_stars(img, method="adaptive", config=SkyConfig())
    with pytest.raises(ValueError, match="thresh"):
        SkyConfig(thresh=0)
    with pytest.raises(ValueError, match="max_sources"):
        SkyConfig(max_sources=0)
    with pytest.raises(ValueError, match="max_stars"):
        ExtractionConfig(max_stars=0)


def test_paper_method_on_a_real_crowded_frame():
    from eotrack.imaging import real_sky_images

    m13 = real_sky_images()["m13"]
    robust = extract_stars(m13, method="adaptive", return_info=True)
    printed = extract_stars(m13, method="adaptive", return_info=True,
                            config=ExtractionConfig(robust_roi=False))
    # the printed eq. (21) lets the crowded core's light raise T_f: the ROI shrinks
    assert robust.roi_fraction > 2 * printed.roi_fraction
    assert len(robust) > 2 * len(printed)
