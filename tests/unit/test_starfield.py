"""Star-sensor image rendering: catalogue + synthetic stars, star-count slope, noise."""

import numpy as np
import pytest
from eotrack.geometry import PinholeCamera, intrinsics_from_fov, look_at
from eotrack.imaging import (
    StarFieldConfig,
    catalogue_stars_in_view,
    render_star_image,
    star_count_slope,
    synthetic_faint_stars,
)


def test_slope_recovers_power_law():
    rng = np.random.default_rng(0)
    xy, mag = synthetic_faint_stars(rng, -1.0, 0.4, 5.0, 12.0, (512, 512))
    _a, b = star_count_slope(mag, 8.0, 12.0)
    assert b == pytest.approx(0.4, abs=0.03)
    assert xy.shape == (len(mag), 2) and np.all(mag > 5) and np.all(mag <= 12)


def test_catalogue_view_and_render():
    K = intrinsics_from_fov(2, 2, 512, 512)
    ra, dec = np.radians(160.0), np.radians(-5.0)
    d = [np.cos(dec) * np.cos(ra), np.cos(dec) * np.sin(ra), np.sin(dec)]
    cam = PinholeCamera(K, look_at(d), np.zeros(3))
    rng = np.random.default_rng(1)
    sf = catalogue_stars_in_view(cam, rng)
    assert sf.from_catalogue.any() and (~sf.from_catalogue).any()
    assert sf.mag[sf.from_catalogue].max() <= 10.0 and sf.mag.max() <= 13.0
    assert np.all((sf.xy > -0.5) & (sf.xy < 511.5))
    img = render_star_image((512, 512), sf.xy, sf.mag, rng)
    assert img.shape == (512, 512)
    cfg = StarFieldConfig()
    assert abs(np.median(img) - cfg.background_e) < 3


def test_bad_input():
    rng = np.random.default_rng(0)
    with pytest.raises(ValueError, match="m_hi must exceed m_lo"):
        star_count_slope([1, 2, 3], 5, 4)
    with pytest.raises(ValueError, match="too few stars"):
        star_count_slope([1.0], 0, 5)
    with pytest.raises(ValueError, match="m_to must exceed"):
        synthetic_faint_stars(rng, 0, 0.4, 13, 10, (10, 10))
    with pytest.raises(TypeError, match=r"rng must be a numpy\.random\.Generator"):
        synthetic_faint_stars(1, 0, 0.4, 10, 13, (10, 10))
    with pytest.raises(ValueError, match="xy and mag must have the same length"):
        render_star_image((10, 10), [[1, 1]], [1.0, 2.0], rng)
