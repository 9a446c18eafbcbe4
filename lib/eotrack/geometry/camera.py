"""Pinhole cameras: intrinsics (eqs. 6–7 of Huang et al.), projection, back-projection.

Conventions: ``R`` maps world coordinates to camera coordinates (``X_cam = R (X − c)``), ``c`` is
the camera centre in world coordinates, camera z is the boresight, x → increasing column u,
y → increasing row v. Pixel coordinates are ``(u, v)`` = (x = column, y = row), as in
:mod:`eotrack.imaging.psf`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from eotrack.validation import as_finite_array, as_points, check_int, check_positive

from .distortion import _check_dist, distort_normalized, undistort_pixels
from .rotations import check_rotation

__all__ = [
    "PinholeCamera",
    "check_intrinsics",
    "intrinsics_from_focal",
    "intrinsics_from_fov",
    "pixel_rays",
    "project_directions",
    "project_points",
]


def intrinsics_from_focal(f_mm: float, dx_mm: float, dy_mm: float, u0: float, v0: float
                          ) -> np.ndarray:
    """Eq. (6): ``M = [[f/dx, 0, u0], [0, f/dy, v0], [0, 0, 1]]``.

    Parameters
    ----------
    f_mm
        Focal length (any length unit, > 0).
    dx_mm, dy_mm
        Pixel width and height in the same unit (> 0).
    u0, v0
        Principal point (px).
    """
    f = check_positive(f_mm, "f_mm")
    dx = check_positive(dx_mm, "dx_mm")
    dy = check_positive(dy_mm, "dy_mm")
    u, v = as_finite_array([u0, v0], "u0, v0")
    return np.array([[f / dx, 0.0, u], [0.0, f / dy, v], [0.0, 0.0, 1.0]])


def intrinsics_from_fov(fov_x_deg: float, fov_y_deg: float, nx: int, ny: int,
                        u0: float | None = None, v0: float | None = None) -> np.ndarray:
    """Eq. (7): focal lengths in pixels ``N / (2 tan(fov/2))`` from field of view and resolution.

    Parameters
    ----------
    fov_x_deg, fov_y_deg
        Full fields of view (degrees, in (0, 180)).
    nx, ny
        Image width and height (px).
    u0, v0
        Principal point; the geometric centre ``((nx − 1)/2, (ny − 1)/2)`` if omitted.
    """
    fx_deg = check_positive(fov_x_deg, "fov_x_deg")
    fy_deg = check_positive(fov_y_deg, "fov_y_deg")
    if fx_deg >= 180 or fy_deg >= 180:
        raise ValueError("fov_x_deg and fov_y_deg must be < 180 for a pinhole camera")
    w = check_int(nx, "nx", min_value=1)
    h = check_int(ny, "ny", min_value=1)
    u = (w - 1) / 2 if u0 is None else float(as_finite_array(u0, "u0", ndim=0))
    v = (h - 1) / 2 if v0 is None else float(as_finite_array(v0, "v0", ndim=0))
    fx = w / (2 * np.tan(np.radians(fx_deg) / 2))
    fy = h / (2 * np.tan(np.radians(fy_deg) / 2))
    return np.array([[fx, 0.0, u], [0.0, fy, v], [0.0, 0.0, 1.0]])


def check_intrinsics(K, name: str = "K") -> np.ndarray:
    """Return ``K`` as a 3×3 float array after checking it is a usable intrinsic matrix.

    Raises
    ------
    ValueError
        Wrong shape, last row not ``(0, 0, 1)``, or singular (a zero focal length).
    """
    k = as_finite_array(K, name)
    if k.shape != (3, 3):
        raise ValueError(f"{name} must be a 3x3 intrinsic matrix, got shape {k.shape}")
    if k[2, 0] != 0.0 or k[2, 1] != 0.0 or abs(k[2, 2] - 1.0) > 1e-12:
        raise ValueError(f"{name} must have last row (0, 0, 1), got {k[2].tolist()}")
    if abs(k[0, 0] * k[1, 1]) < 1e-12:
        raise ValueError(f"{name} is singular (focal lengths {k[0, 0]}, {k[1, 1]}); need "
                         "non-zero f/dx and f/dy")
    return k


def project_points(X_world, K, R, c, dist=None, *, return_depth: bool = False):
    """Project world points through a pinhole camera (optionally with OpenCV distortion).

    Parameters
    ----------
    X_world
        Points ``(n, 3)`` in world coordinates.
    K, R, c
        Intrinsics, world → camera rotation, camera centre (world).
    dist
        OpenCV ``(k1, k2, p1, p2[, k3])`` or ``None`` for an ideal lens.
    return_depth
        Also return the camera-z depth of each point (negative = behind the camera).

    Returns
    -------
    numpy.ndarray
        Pixel coordinates ``(n, 2)`` (and depths ``(n,)``).
    """
    X = as_points(X_world, "X_world", dim=3)
    k = check_intrinsics(K)
    r = check_rotation(R, "R")
    cc = as_finite_array(c, "c", shape=(3,))
    Xc = (X - cc) @ r.T
    z = Xc[:, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        xy = Xc[:, :2] / z[:, None]
    if dist is not None and len(X):
        xy = distort_normalized(np.where(np.isfinite(xy), xy, 0.0), _check_dist(dist))
    uv = xy @ k[:2, :2].T + k[:2, 2]
    return (uv, z) if return_depth else uv


def project_directions(dirs_world, K, R, dist=None, *, return_depth: bool = False):
    """Project directions (points at infinity, e.g. stars) ``(n, 3)`` to pixels.

    Same as :func:`project_points` with the camera at the origin and the points far away.
    """
    d = as_points(dirs_world, "dirs_world", dim=3)
    return project_points(d, K, R, np.zeros(3), dist, return_depth=return_depth)


def pixel_rays(pts, K, R, dist=None) -> np.ndarray:
    """Unit world directions of the lines of sight through pixels ``(n, 2)``.

    Distortion, if given, is removed first with ``cv2.undistortPoints``.
    """
    p = as_points(pts, "pts")
    k = check_intrinsics(K)
    r = check_rotation(R, "R")
    if dist is not None and len(p):
        p = undistort_pixels(p, k, dist)
    h = np.column_stack([p, np.ones(len(p))])
    d = np.linalg.solve(k, h.T).T @ r  # camera dir -> world: Rᵀ d  (row form d @ R)
    return d / np.linalg.norm(d, axis=1, keepdims=True)


@dataclass(frozen=True)
class PinholeCamera:
    """A calibrated camera at a pose.

    Parameters
    ----------
    K
        Intrinsics (3×3).
    R
        World → camera rotation.
    c
        Camera centre in world coordinates.
    size
        Image ``(width, height)`` in px.
    dist
        OpenCV distortion coefficients or ``None``.
    """

    K: np.ndarray
    R: np.ndarray
    c: np.ndarray
    size: tuple[int, int] = (512, 512)
    dist: np.ndarray | None = field(default=None)

    def __post_init__(self) -> None:
        object.__setattr__(self, "K", check_intrinsics(self.K))
        object.__setattr__(self, "R", check_rotation(self.R, "R"))
        object.__setattr__(self, "c", as_finite_array(self.c, "c", shape=(3,)))
        if self.dist is not None:
            object.__setattr__(self, "dist", _check_dist(self.dist))
        w, h = self.size
        object.__setattr__(self, "size", (check_int(w, "size[0]", min_value=1),
                                          check_int(h, "size[1]", min_value=1)))

    def project(self, X_world, *, return_depth: bool = False):
        """Pixel coordinates of world points (see :func:`project_points`)."""
        return project_points(X_world, self.K, self.R, self.c, self.dist,
                              return_depth=return_depth)

    def project_directions(self, dirs_world, *, return_depth: bool = False):
        """Pixel coordinates of directions at infinity (stars)."""
        return project_directions(dirs_world, self.K, self.R, self.dist,
                                  return_depth=return_depth)

    def rays(self, pts) -> np.ndarray:
        """Unit world directions through pixels (see :func:`pixel_rays`)."""
        return pixel_rays(pts, self.K, self.R, self.dist)

    def sees(self, X_world, *, margin_px: float = 0.0) -> np.ndarray:
        """Boolean mask: in front of the camera and inside the image (minus a margin)."""
        uv, z = self.project(X_world, return_depth=True)
        w, h = self.size
        m = float(margin_px)
        return (z > 0) & (uv[:, 0] >= -0.5 + m) & (uv[:, 0] <= w - 0.5 - m) & \
            (uv[:, 1] >= -0.5 + m) & (uv[:, 1] <= h - 0.5 - m)
