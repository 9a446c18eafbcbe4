"""Dim-target image-sequence simulator."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.imaging.dim_targets import (
    DimSequenceConfig,
    DimTarget,
    curved_path,
    fwhm_to_sigma,
    m13_star_field,
    peak_snr_for_pixel_pd,
    simulate_dim_sequence,
    straight_path,
)
from scipy.stats import norm


def test_paths():
    p = straight_path((1, 2), (0.5, -1), 4)
    np.testing.assert_allclose(p[-1], [2.5, -1])
    c = curved_path((0, 0), 10, 0.0, np.pi / 2, 3)
    np.testing.assert_allclose(c, [[10, 0], [0, 10], [-10, 0]], atol=1e-12)


def test_target_peak_and_noise_statistics():
    tg = DimTarget(straight_path((20, 30), (0, 0), 4), snr=5.0, sigma_px=1.0)
    cfg = DimSequenceConfig(shape=(64, 64), n_frames=4, clutter_sigma=0.0, noise_sigma=2.0,
                            level=10.0, targets=(tg,))
    seq = simulate_dim_sequence(cfg, np.random.default_rng(0))
    assert seq.images.shape == (4, 64, 64) and seq.images.dtype == np.float32
    peak = seq.images[:, 30, 20].mean() - 10
    assert peak == pytest.approx(5 * 2.0, abs=3 * 2.0 / 2)
    far = seq.images[:, :10, :10]
    assert far.std() == pytest.approx(2.0, rel=0.1)
    np.testing.assert_allclose(seq.truth_xy[0], np.tile([20, 30], (4, 1)))
    np.testing.assert_allclose(seq.times_s, 0.04 * np.arange(4))


def test_clutter_and_late_target_and_seed():
    tg = DimTarget(straight_path((10, 10), (1, 0), 3), snr=3.0, first_frame=2)
    cfg = DimSequenceConfig(shape=(48, 48), n_frames=5, targets=(tg,), jitter_px=0.1)
    a = simulate_dim_sequence(cfg, np.random.default_rng(5))
    b = simulate_dim_sequence(cfg, np.random.default_rng(5))
    np.testing.assert_array_equal(a.images, b.images)
    assert np.isnan(a.truth_xy[0, :2]).all() and np.isfinite(a.truth_xy[0, 2:]).all()
    # clutter: frame-to-frame smooth background with std ~ sqrt(noise^2 + clutter^2)
    assert a.images.std() > 20


def test_m13_star_field():
    s = m13_star_field((256, 256))
    assert s.shape == (256, 256) and np.median(s) == pytest.approx(0, abs=5)
    assert s.max() > 1000  # real stars
    assert m13_star_field((320, 310)).shape == (320, 310)
    cfg = DimSequenceConfig(shape=(64, 64), n_frames=2, stars=m13_star_field((64, 64)))
    assert simulate_dim_sequence(cfg, np.random.default_rng(0)).images.shape == (2, 64, 64)


def test_peak_snr_for_pixel_pd():
    sig = fwhm_to_sigma(3.0)
    assert sig == pytest.approx(1.274, abs=1e-3)
    a = peak_snr_for_pixel_pd(0.98, 0.03, sig)
    k = np.array([-1, 0, 1])
    g = np.exp(-0.5 * np.add.outer(k ** 2, k ** 2) / sig ** 2)
    assert norm.sf(norm.isf(0.03) - a * g).mean() == pytest.approx(0.98, abs=1e-6)


def test_bad_input():
    with pytest.raises(ValueError, match="n_frames"):
        straight_path((0, 0), (1, 1), 0)
    with pytest.raises(ValueError, match="start_xy"):
        straight_path((0, 0, 0), (1, 1), 3)
    with pytest.raises(ValueError, match="radius_px"):
        curved_path((0, 0), -1, 0, 0.1, 3)
    with pytest.raises(ValueError, match="snr"):
        DimTarget(np.zeros((3, 2)), snr=-1)
    with pytest.raises(ValueError, match="path_xy"):
        DimTarget(np.zeros((3, 3)), snr=1)
    with pytest.raises(ValueError, match="clutter_memory"):
        DimSequenceConfig(clutter_memory=1.0)
    with pytest.raises(ValueError, match="stars"):
        DimSequenceConfig(shape=(32, 32), stars=np.zeros((16, 16)))
    with pytest.raises(TypeError, match="targets"):
        DimSequenceConfig(targets=("x",))
    with pytest.raises(TypeError, match="rng"):
        simulate_dim_sequence(DimSequenceConfig(shape=(16, 16), n_frames=1), 3)
    with pytest.raises(TypeError, match="config"):
        simulate_dim_sequence({}, np.random.default_rng(0))
    with pytest.raises(ValueError, match="shape"):
        m13_star_field((10,))
    with pytest.raises(ValueError, match="p_d"):
        peak_snr_for_pixel_pd(0.01, 0.03, 1.0)
    with pytest.raises(ValueError, match="size"):
        peak_snr_for_pixel_pd(0.9, 0.03, 1.0, size=2)
    with pytest.raises(ValueError, match="fwhm_px"):
        fwhm_to_sigma(0.0)


def test_held_out_peak_snr_other_size_and_pf():
    """A 5x5 core of a FWHM-5 spot at P_F 0.003 (neither is the paper's): the solved peak SNR
    gives the wanted mean detection rate in simulated white noise."""
    sig = fwhm_to_sigma(5.0)
    a = peak_snr_for_pixel_pd(0.9, 0.003, sig, 5)
    k = np.arange(-2, 3)
    g = np.exp(-0.5 * np.add.outer(k ** 2, k ** 2) / sig ** 2)
    rng = np.random.default_rng(3)
    x = rng.standard_normal((40_000, 5, 5)) + a * g
    assert (x > norm.isf(0.003)).mean() == pytest.approx(0.9, abs=0.005)
