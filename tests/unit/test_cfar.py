"""CFAR segmentation with a robust tile background."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.imaging.cfar import CfarResult, cfar_segment, cfar_threshold, tile_background_noise


def test_false_alarm_rate_on_white_noise():
    rng = np.random.default_rng(0)
    img = 100 + 5 * rng.standard_normal((256, 256))
    g = cfar_segment(img, 0.03)
    assert g.dtype == np.uint8 and set(np.unique(g)) <= {0, 1}
    assert abs(g.mean() - 0.03) < 0.004


def test_ramp_background_is_removed():
    rng = np.random.default_rng(1)
    yy, xx = np.mgrid[0:128, 0:160]
    img = 50 + 0.5 * xx + 0.3 * yy + rng.standard_normal((128, 160))
    bg, sig = tile_background_noise(img, 16)
    inner = (slice(16, -16), slice(16, -16))
    assert np.abs(bg - (50 + 0.5 * xx + 0.3 * yy))[inner].max() < 0.6
    assert np.median(sig) == pytest.approx(1.0, rel=0.1)
    g = cfar_segment(img, 0.01)
    assert abs(g[inner].mean() - 0.01) < 0.004


def test_bright_spot_detected_and_full_result():
    rng = np.random.default_rng(2)
    img = rng.standard_normal((64, 64))
    img[30:33, 30:33] += 10
    res = cfar_segment(img, 0.001, full=True)
    assert isinstance(res, CfarResult)
    assert res.binary[30:33, 30:33].all()
    np.testing.assert_allclose(cfar_threshold(img, 0.001), res.threshold)


def test_global_tile_and_uneven_tiles():
    rng = np.random.default_rng(3)
    img = rng.standard_normal((50, 70))
    bg, sig = tile_background_noise(img, None)
    assert np.ptp(bg) == 0 and np.ptp(sig) == 0
    bg, sig = tile_background_noise(img, 16)  # 50 and 70 are not multiples of 16
    assert bg.shape == img.shape and np.all(sig > 0)


def test_bad_input():
    img = np.zeros((16, 16))
    with pytest.raises(ValueError, match="p_f"):
        cfar_segment(img, 1.5)
    with pytest.raises(ValueError, match="p_f"):
        cfar_threshold(img, 0.0)
    with pytest.raises(ValueError, match="image"):
        cfar_segment(np.zeros((3, 16, 16)), 0.03)
    with pytest.raises(ValueError, match="image"):
        tile_background_noise(np.zeros(16))
    with pytest.raises(ValueError, match="tile"):
        tile_background_noise(img, 2)
    with pytest.raises(ValueError, match="image"):
        cfar_segment(np.full((8, 8), np.nan), 0.03)


# ---------------------------------------------------------------- held-out scenes
def _measured_pf(shape, clutter, scale, p_f, *, tile=16, seed=7):
    from eotrack.imaging.dim_targets import DimSequenceConfig, simulate_dim_sequence

    cfg = DimSequenceConfig(shape=shape, n_frames=6, clutter_sigma=float(clutter),
                            clutter_scale_px=float(scale), targets=())
    seq = simulate_dim_sequence(cfg, np.random.default_rng(seed))
    g = np.stack([cfar_segment(im, p_f, tile=tile) for im in seq.images])
    return float(g[:, 8:-8, 8:-8].mean())


@pytest.mark.parametrize("shape", [(200, 150), (96, 320)])  # not multiples of the 16-px tile
@pytest.mark.parametrize("p_f", [0.01, 0.03, 0.1])
def test_held_out_pf_within_range_for_smooth_clutter(shape, p_f):
    """Operating range: clutter sigma <= noise sigma, scale >= 2 tiles -> P_F within 15 %."""
    assert _measured_pf(shape, 10, 40, p_f) / p_f == pytest.approx(1.0, abs=0.15)


def test_held_out_pf_outside_range_for_rough_clutter():
    """Clutter finer than a tile (8 px < 16 px) or 6x the noise: the rate is too high."""
    assert _measured_pf((200, 150), 30, 8, 0.03) / 0.03 > 1.1
    assert _measured_pf((200, 150), 60, 24, 0.003) / 0.003 > 1.5


# ------------------------------------------------ held-out: outside the Gaussian noise model
def test_held_out_poisson_dark_sky_warns_and_poisson_model_is_conservative():
    """Photon-limited counts (mean 0.5): MAD = 0 is detected, the Gaussian rate is off, and
    ``noise="poisson"`` keeps the rate at or below p_f."""
    from eotrack.imaging.cfar import CfarWarning

    img = np.random.default_rng(11).poisson(0.5, (128, 128)).astype(float)
    with pytest.warns(CfarWarning, match="MAD is 0"):
        g = cfar_segment(img, 0.03)
    assert g.mean() / 0.03 > 2.0  # documented: the discrete levels cannot give 0.03
    for p_f in (0.03, 0.003):
        rate = cfar_segment(img, p_f, noise="poisson").mean()
        assert 0.2 * p_f < rate <= 1.1 * p_f  # conservative, not degenerate


def test_held_out_poisson_bright_sky_rate_close_and_target_found():
    rng = np.random.default_rng(12)
    img = rng.poisson(20.0, (128, 128)).astype(float)
    img[60:63, 60:63] += 40
    res = cfar_segment(img, 0.01, noise="poisson", full=True)
    assert res.binary[60:63, 60:63].all()
    core = res.binary.copy()
    core[55:68, 55:68] = 0
    assert 0.4 * 0.01 < core.mean() <= 1.1 * 0.01
    assert np.median(res.background) == pytest.approx(20.0, rel=0.05)


def test_quantised_gaussian_warns():
    from eotrack.imaging.cfar import CfarWarning

    img = np.round(0.4 * np.random.default_rng(13).standard_normal((64, 64)))
    with pytest.warns(CfarWarning):
        cfar_threshold(img, 0.03)


def test_continuous_gaussian_does_not_warn():
    import warnings

    img = 100 + 5 * np.random.default_rng(14).standard_normal((64, 64))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        cfar_segment(img, 0.03)
        cfar_segment(np.round(img), 0.03)  # integer DN, but 5 DN of noise: no warning


def test_poisson_bad_input():
    with pytest.raises(ValueError, match="noise"):
        cfar_segment(np.zeros((16, 16)), 0.03, noise="laplace")
    with pytest.raises(ValueError, match="counts"):
        cfar_segment(np.full((16, 16), 0.5), 0.03, noise="poisson")
    with pytest.raises(ValueError, match="counts"):
        cfar_threshold(np.full((16, 16), -1.0), 0.03, noise="poisson")
