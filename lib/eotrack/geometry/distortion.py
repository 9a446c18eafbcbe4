"""Lens distortion in OpenCV's model (radial k1, k2; tangential p1, p2).

Huang et al. (Table 2) give "radial distortion p1, p2" and "tangential distortion q1, q2"; in
OpenCV's order ``(k1, k2, p1, p2)`` these are ``(p1, p2, q1, q2)`` of the paper —
:func:`opencv_coefficients` makes the mapping explicit. The model acts on normalised image
coordinates ``x = X/Z, y = Y/Z`` (r² = x² + y²)::

    x_d = x (1 + k1 r² + k2 r⁴) + 2 p1 x y + p2 (r² + 2 x²)
    y_d = y (1 + k1 r² + k2 r⁴) + p1 (r² + 2 y²) + 2 p2 x y

The paper does not say in which units its coefficients apply; in normalised coordinates of a
2° sensor (r ≤ 0.025) they move a point by far less than 0.01 px.
"""

from __future__ import annotations

import cv2
import numpy as np

from eotrack.validation import as_finite_array, as_points

__all__ = ["distort_normalized", "opencv_coefficients", "undistort_pixels"]


def opencv_coefficients(radial=(0.0, 0.0), tangential=(0.0, 0.0)) -> np.ndarray:
    """OpenCV ``distCoeffs = (k1, k2, p1, p2)`` from the paper's radial and tangential pairs."""
    rad = as_finite_array(radial, "radial", shape=(2,))
    tan = as_finite_array(tangential, "tangential", shape=(2,))
    return np.array([rad[0], rad[1], tan[0], tan[1]], dtype=float)


def _check_dist(dist) -> np.ndarray:
    d = as_finite_array(dist, "dist", ndim=1)
    if d.shape[0] not in (4, 5):
        raise ValueError(f"dist must hold 4 or 5 OpenCV coefficients (k1, k2, p1, p2[, k3]), "
                         f"got {d.shape[0]}")
    return np.pad(d, (0, 5 - d.shape[0]))


def distort_normalized(xy, dist) -> np.ndarray:
    """Apply OpenCV's distortion to normalised coordinates ``(n, 2)`` (vectorised).

    Parameters
    ----------
    xy
        Undistorted normalised coordinates ``(n, 2)``.
    dist
        ``(k1, k2, p1, p2[, k3])``.
    """
    p = as_points(xy, "xy")
    k1, k2, p1, p2, k3 = _check_dist(dist)
    x, y = p[:, 0], p[:, 1]
    r2 = x * x + y * y
    radial = 1 + k1 * r2 + k2 * r2**2 + k3 * r2**3
    xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)
    yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y
    return np.stack([xd, yd], 1)


def undistort_pixels(pts, K, dist) -> np.ndarray:
    """Remove distortion from pixel coordinates (``cv2.undistortPoints``, back to pixels).

    Parameters
    ----------
    pts
        Distorted pixel coordinates ``(n, 2)``.
    K
        Intrinsic matrix ``(3, 3)``.
    dist
        ``(k1, k2, p1, p2[, k3])``.
    """
    from .camera import check_intrinsics

    p = as_points(pts, "pts")
    k = check_intrinsics(K)
    d = _check_dist(dist)
    if len(p) == 0:
        return p
    und = cv2.undistortPoints(p.reshape(-1, 1, 2), k, d, P=k,
                              criteria=(cv2.TERM_CRITERIA_COUNT | cv2.TERM_CRITERIA_EPS, 50, 1e-12))
    return und.reshape(-1, 2)
