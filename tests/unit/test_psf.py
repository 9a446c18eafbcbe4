"""Gaussian spot rendering."""

import numpy as np
import pytest
from eotrack.imaging import render_gaussian_spots
from hypothesis import given, settings
from hypothesis import strategies as st


@settings(max_examples=30, deadline=None)
@given(x=st.floats(16, 48), y=st.floats(16, 48), sigma=st.floats(1.0, 3.0),
       flux=st.floats(1, 1e4))
def test_flux_and_centroid_conserved(x, y, sigma, flux):
    """Flux is conserved; the centroid too for PSFs that are not undersampled (σ ≥ 1 px: below
    that, pixel integration biases the centroid — 'pixel locking' — by up to a few 0.01 px)."""
    img = render_gaussian_spots((64, 64), [[x, y]], flux, sigma)
    assert img.sum() == pytest.approx(flux, rel=1e-4)
    rows, cols = np.indices(img.shape)
    assert (img * cols).sum() / img.sum() == pytest.approx(x, abs=1e-3)
    assert (img * rows).sum() / img.sum() == pytest.approx(y, abs=1e-3)


def test_edges_clipped_and_add_into_out():
    out = np.ones((16, 16))
    img = render_gaussian_spots((16, 16), [[-0.2, 8.0], [100.0, 100.0]], [100.0, 5.0], 1.0,
                                out=out)
    assert img is out
    assert 40 < img.sum() - 256 < 70
    assert render_gaussian_spots((8, 8), np.zeros((0, 2)), [], 1.0).sum() == 0


def test_sampled_psf_peak():
    img = render_gaussian_spots((21, 21), [[10, 10]], 1.0, 2.0, integrate=False)
    assert img.max() == pytest.approx(1 / (2 * np.pi * 4), rel=1e-12)


@pytest.mark.parametrize(("kw", "exc", "match"), [
    ({"shape": (0, 5)}, ValueError, r"shape\[0\] must be >= 1"),
    ({"shape": (5,)}, ValueError, "shape must be"),
    ({"xy": [[1, 2, 3]]}, ValueError, r"xy must have shape \(n, 2\)"),
    ({"flux": -1.0}, ValueError, "flux must be >= 0"),
    ({"sigma_px": 0.0}, ValueError, "sigma_px must be"),
    ({"out": np.zeros((3, 3))}, ValueError, "out must be a float array"),
])
def test_bad_input(kw, exc, match):
    args = {"shape": (8, 8), "xy": [[3.0, 3.0]], "flux": 1.0, "sigma_px": 1.0}
    args.update(kw)
    with pytest.raises(exc, match=match):
        render_gaussian_spots(**args)
