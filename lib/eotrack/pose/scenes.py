"""Random robust-PnP scenes for testing pose estimators on settings no paper used.

:func:`random_pnp_scene` draws a non-planar point model seen by a pixel camera whose principal
point is off-centre, at a random distance and attitude, with per-point noise levels and a share
of gross mismatches — the kind of scene a user brings, unlike the paper's planar target on a
millimetre focal plane.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from eotrack.validation import check_generator, check_int, check_positive

from .projection import intrinsic_matrix, project_points

__all__ = ["PnPScene", "random_pnp_scene"]


@dataclass(frozen=True)
class PnPScene:
    """One simulated image: model points, image points (px), truth and the gross-error mask."""

    points: np.ndarray
    pixels: np.ndarray
    K: np.ndarray
    R: np.ndarray
    t: np.ndarray
    sigma_px: np.ndarray
    outliers: np.ndarray


def random_pnp_scene(rng: np.random.Generator, *, n_points: int = 60,
                     outlier_fraction: float = 0.3, distance_m: tuple[float, float] = (8.0, 15.0),
                     sigma_px: tuple[float, float] = (0.3, 1.5), size_m: float = 2.0,
                     focal_px: float = 1400.0, principal_point: tuple[float, float] = (590.0, 410.0),
                     image_size: tuple[int, int] = (1280, 960)) -> PnPScene:
    """A random non-planar PnP scene with heteroscedastic noise and gross mismatches.

    Parameters
    ----------
    rng
        Generator.
    n_points
        Number of correspondences (≥ 6).
    outlier_fraction
        Share of gross errors in [0, 1): their image point is replaced by a uniform random
        position in the image.
    distance_m
        Range of the target's distance along the optical axis (m).
    sigma_px
        Range of the per-point noise standard deviation (px), uniform per point.
    size_m
        Side of the cube the model points fill (m), centred on the target.
    focal_px, principal_point, image_size
        Camera: focal length (px), principal point (px; off-centre by default) and image size.

    Returns
    -------
    PnPScene
    """
    rng = check_generator(rng)
    n = check_int(n_points, "n_points", min_value=6)
    if not 0.0 <= float(outlier_fraction) < 1.0:
        raise ValueError(f"outlier_fraction must lie in [0, 1), got {outlier_fraction!r}")
    lo_d, hi_d = (float(v) for v in distance_m)
    if not 0 < lo_d <= hi_d:
        raise ValueError(f"distance_m must be (lo, hi) with 0 < lo <= hi, got {distance_m!r}")
    lo_s, hi_s = (float(v) for v in sigma_px)
    if not 0 <= lo_s <= hi_s:
        raise ValueError(f"sigma_px must be (lo, hi) with 0 <= lo <= hi, got {sigma_px!r}")
    check_positive(size_m, "size_m")
    K = intrinsic_matrix(check_positive(focal_px, "focal_px"), *principal_point)
    w, h = image_size
    R = Rotation.random(random_state=rng).as_matrix()
    z = rng.uniform(lo_d, hi_d)
    # lateral offset keeps the target inside the image
    lat = (np.array([w, h]) * rng.uniform(0.3, 0.7, 2) - np.asarray(principal_point)) * z / focal_px
    t = np.array([lat[0], lat[1], z])
    X = rng.uniform(-size_m / 2, size_m / 2, (n, 3))
    sig = rng.uniform(lo_s, hi_s, n)
    u = project_points(X, R, t, K) + rng.normal(size=(n, 2)) * sig[:, None]
    bad = np.zeros(n, bool)
    bad[rng.permutation(n)[:round(outlier_fraction * n)]] = True
    u[bad] = rng.uniform([0, 0], [w, h], (int(bad.sum()), 2))
    return PnPScene(X, u, K, R, t, sig, bad)
