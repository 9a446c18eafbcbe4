"""Tests of eotrack.imaging.deblend and eotrack.imaging.detection_eval."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.imaging import (
    aperture_flux,
    clean_isolated,
    completeness_at,
    completeness_curve,
    crowded_field,
    deblend_peaks,
    estimate_psf_sigma,
    find_peaks,
    inject_stars,
    match_positions,
    real_sky_images,
    render_gaussian_spots,
    windowed_centroids,
)
from hypothesis import given, settings
from hypothesis import strategies as st


@settings(max_examples=25, deadline=None)
@given(st.floats(20.0, 100.0), st.floats(20.0, 100.0), st.floats(0.8, 2.5))
def test_windowed_centroid_is_unbiased(x, y, sigma):
    img = render_gaussian_spots((128, 128), np.array([[x, y]]), 1e4, sigma)
    s_eff = np.sqrt(sigma ** 2 + 1 / 12)                     # pixel integration widens the PSF
    xy = windowed_centroids(img, np.array([[round(x), round(y)]], float), s_eff, iterations=8)
    assert np.hypot(*(xy[0] - [x, y])) < 0.01


def test_plateau_gives_one_peak_and_pair_is_deblended():
    img = np.zeros((40, 40), np.float32)
    img[10:13, 10:13] = 5.0                                  # a flat (saturated) top
    pair = render_gaussian_spots((40, 40), np.array([[25.0, 25.0], [28.5, 25.0]]),
                                 np.array([1000.0, 600.0]), 1.0)
    img += pair.astype(np.float32)
    p = find_peaks(img, img > 0.5)
    keep = deblend_peaks(img, p, 0.05)
    kept = p[keep]
    assert np.sum(np.all(np.abs(kept - [11, 11]) <= 1, axis=1)) == 1
    assert np.sum(np.hypot(*(kept - [25, 25]).T) < 1) == 1
    assert np.sum(np.hypot(*(kept - [28.5, 25]).T) < 1) == 1


def test_aperture_flux_and_psf_sigma():
    xy = np.array([[30.2, 30.7], [70.5, 60.1]])
    img = render_gaussian_spots((100, 100), xy, np.array([1000.0, 500.0]), 1.5)
    f = aperture_flux(img, xy, 6.0)
    assert np.allclose(f, [1000, 500], rtol=1e-3)
    assert estimate_psf_sigma(img, xy) == pytest.approx(1.5, rel=0.05)


def test_matching_and_completeness_curve():
    truth = np.array([[10.0, 10.0], [20.0, 20.0]])
    hit, real, err = match_positions(np.array([[10.5, 10.0], [50.0, 50.0]]), truth)
    assert hit.tolist() == [True, False] and real.tolist() == [True, False]
    assert err[0] == pytest.approx(0.5)
    curve = completeness_curve(lambda img, t: truth[: int(t)], None, truth,
                               np.array([True, True]), [0, 1, 2])
    assert curve.completeness.tolist() == [0, 0.5, 1.0]
    assert completeness_at(curve, [0]).item() == pytest.approx(1.0)


def test_crowded_field_and_injection():
    cf = crowded_field(np.random.default_rng(0), 128)
    assert cf.image.shape == (128, 128) and cf.image.max() <= 40000
    assert cf.blended.any() and len(cf.xy) == len(cf.flux) == len(cf.peak_snr)
    _, xy, peak = inject_stars(cf.image, np.random.default_rng(1), 10, 1.3, (100, 1000))
    assert len(xy) == 10 and np.all((peak >= 100) & (peak <= 1000))
    idx = clean_isolated(cf.xy, cf.flux, np.zeros(len(cf.xy)), (128, 128), n=5)
    assert len(idx) <= 5


def test_real_images_load_offline():
    imgs = real_sky_images()
    assert imgs["m13"].shape == (300, 300) and imgs["hubble_deep_field"].ndim == 2


def test_bad_input():
    with pytest.raises(ValueError, match="mask"):
        find_peaks(np.zeros((5, 5)), np.zeros((4, 4), bool))
    with pytest.raises(ValueError, match="nsigma"):
        deblend_peaks(np.zeros((5, 5)), np.zeros((0, 2)), 1.0, nsigma=-1)
    with pytest.raises(ValueError, match="sigma"):
        windowed_centroids(np.zeros((5, 5)), np.zeros((1, 2)), 0.0)
    with pytest.raises(ValueError, match="xy0"):
        windowed_centroids(np.zeros((5, 5)), np.zeros((3,)), 1.0)
    with pytest.raises(ValueError, match="radius"):
        aperture_flux(np.zeros((5, 5)), np.zeros((1, 2)), -1.0)
    with pytest.raises(ValueError, match="found"):
        match_positions(np.zeros((3,)), np.zeros((1, 2)))
    with pytest.raises(ValueError, match="size"):
        crowded_field(np.random.default_rng(0), 8)
    with pytest.raises(ValueError, match="peak_range"):
        inject_stars(np.zeros((50, 50)), np.random.default_rng(0), 3, 1.0, (0, 1))
