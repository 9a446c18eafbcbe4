"""Frames and the pinhole projection model of a relative-pose problem (Ning et al. 2016, §1).

Conventions used throughout :mod:`eotrack.pose`:

* target (body) frame: origin at the target's centre of mass; a feature point is ``X`` (m);
* camera frame: origin at the projection centre, ``z`` along the optical axis, ``x``/``y``
  parallel to the image axes ``u``/``v`` (right-handed);
* pose ``(R, t)``: ``x_c = R @ X + t`` (``R = C_ct``, target → camera; ``t`` = the target's centre
  of mass in camera coordinates, eq. 1);
* image: ``u = K x_c / z_c`` (eq. 2) with the intrinsic matrix ``K``. Image coordinates are in
  whatever unit ``K`` maps to ("px"); with ``K = diag(f_mm, f_mm, 1)`` they are millimetres on the
  focal plane, which is how the paper states its noise;
* quaternions are scalar-first ``(q0, q1, q2, q3)`` with ``q0 >= 0``; rotations come from
  :class:`scipy.spatial.transform.Rotation`.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from eotrack.validation import as_finite_array, as_points, check_positive

__all__ = [
    "attitude_matrix",
    "camera_points",
    "check_rotation",
    "check_translation",
    "intrinsic_matrix",
    "matrix_from_quaternion",
    "project_points",
    "quaternion_from_matrix",
    "rotation_error_deg",
    "skew",
]


def skew(v: Any) -> np.ndarray:
    """Cross-product matrix ``[v]ₓ`` (``[v]ₓ w = v × w``); works on ``(..., 3)`` stacks."""
    v = as_finite_array(v, "v")
    if v.shape[-1:] != (3,):
        raise ValueError(f"v must have shape (..., 3), got {v.shape}")
    out = np.zeros((*v.shape[:-1], 3, 3))
    out[..., 0, 1], out[..., 0, 2] = -v[..., 2], v[..., 1]
    out[..., 1, 0], out[..., 1, 2] = v[..., 2], -v[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -v[..., 1], v[..., 0]
    return out


def check_rotation(R: Any, name: str = "R", *, atol: float = 1e-6) -> np.ndarray:
    """Return ``R`` as a 3×3 float array after checking ``RᵀR = I`` and ``det R = +1``.

    Raises
    ------
    ValueError
        If ``R`` is not 3×3, not orthonormal within ``atol`` or a reflection.
    """
    R = as_finite_array(R, name, shape=(3, 3))
    err = np.max(np.abs(R.T @ R - np.eye(3)))
    if err > atol:
        raise ValueError(f"{name} must be a rotation matrix (orthonormal); max |RᵀR − I| = "
                         f"{err:.2e} > {atol:g}")
    if np.linalg.det(R) < 0:
        raise ValueError(f"{name} must be a proper rotation (det = +1), got a reflection")
    return R


def check_translation(t: Any, name: str = "t") -> np.ndarray:
    """Return ``t`` as a finite ``(3,)`` float array."""
    return as_finite_array(t, name, shape=(3,))


def intrinsic_matrix(f: float, cx: float = 0.0, cy: float = 0.0, *,
                     pixel_size: float | None = None) -> np.ndarray:
    """Pinhole intrinsic matrix ``K``.

    Parameters
    ----------
    f
        Focal length (m, or any length unit).
    cx, cy
        Principal point in image units.
    pixel_size
        Pixel pitch in the unit of ``f``. ``None``: image coordinates in the unit of ``f``
        (``K = diag(f, f, 1)``); otherwise pixels (``f / pixel_size`` on the diagonal).

    Returns
    -------
    numpy.ndarray
        ``[[fx, 0, cx], [0, fy, cy], [0, 0, 1]]``.
    """
    f = check_positive(f, "f")
    scale = 1.0 if pixel_size is None else 1.0 / check_positive(pixel_size, "pixel_size")
    cx = float(as_finite_array(cx, "cx", ndim=0))
    cy = float(as_finite_array(cy, "cy", ndim=0))
    return np.array([[f * scale, 0.0, cx], [0.0, f * scale, cy], [0.0, 0.0, 1.0]])


def _check_K(K: Any) -> np.ndarray:
    K = as_finite_array(K, "K", shape=(3, 3))
    if not (np.allclose(K[2], [0.0, 0.0, 1.0]) and K[1, 0] == 0.0 and K[0, 0] > 0
            and K[1, 1] > 0):
        raise ValueError("K must be an upper-triangular intrinsic matrix with last row "
                         f"[0, 0, 1] and positive focal lengths, got {K.tolist()}")
    return K


def attitude_matrix(angles_deg: Any, seq: str = "xyz") -> np.ndarray:
    """Rotation matrix target → camera from three attitude angles (degrees).

    The paper gives "relative attitude angles [15°, 20°, 10°]" without the sequence; the default
    adopted here is the extrinsic x-y-z sequence of :meth:`scipy.spatial.transform.Rotation.
    from_euler` (roll about x, then pitch about y, then yaw about z).
    """
    a = as_finite_array(angles_deg, "angles_deg", shape=(3,))
    if not isinstance(seq, str) or len(seq) != 3:
        raise ValueError(f"seq must be a 3-letter axis sequence such as 'xyz', got {seq!r}")
    return Rotation.from_euler(seq, a, degrees=True).as_matrix()


def quaternion_from_matrix(R: Any) -> np.ndarray:
    """Scalar-first unit quaternion ``(q0, q1, q2, q3)``, ``q0 >= 0``, of a rotation matrix."""
    R = check_rotation(R)
    x, y, z, w = Rotation.from_matrix(R).as_quat()
    q = np.array([w, x, y, z])
    return q if q[0] >= 0 else -q


def matrix_from_quaternion(q: Any) -> np.ndarray:
    """Rotation matrix of a scalar-first quaternion (normalised first; ``q`` and ``−q`` agree)."""
    q = as_finite_array(q, "q", shape=(4,))
    n = np.linalg.norm(q)
    if n < 1e-12:
        raise ValueError("q must be a non-zero quaternion")
    w, x, y, z = q / n
    return Rotation.from_quat([x, y, z, w]).as_matrix()


def camera_points(points: Any, R: Any, t: Any) -> np.ndarray:
    """Camera-frame coordinates ``x_c = R X + t`` of target points ``X`` (n, 3)."""
    X = as_points(points, "points", dim=3)
    R = check_rotation(R)
    t = check_translation(t)
    return X @ R.T + t


def project_points(points: Any, R: Any, t: Any, K: Any, *, min_depth: float = 0.0) -> np.ndarray:
    """Pinhole projection (eqs. 1–2): ``u = K (R X + t) / z_c``.

    Parameters
    ----------
    points
        Target-frame points ``X``, shape (n, 3).
    R, t
        Pose (target → camera).
    K
        Intrinsic matrix.
    min_depth
        Points with ``z_c <= min_depth`` are "behind the camera" and raise.

    Returns
    -------
    numpy.ndarray
        Image coordinates, shape (n, 2).

    Raises
    ------
    ValueError
        If a point lies behind (or on the plane of) the camera.
    """
    K = _check_K(K)
    xc = camera_points(points, R, t)
    bad = xc[:, 2] <= min_depth
    if np.any(bad):
        raise ValueError(f"points: {int(bad.sum())} point(s) lie behind the camera "
                         f"(z_c <= {min_depth}), e.g. index {int(np.flatnonzero(bad)[0])}")
    p = xc @ K.T
    return p[:, :2] / p[:, 2:3]


def rotation_error_deg(R_est: Any, R_true: Any) -> float:
    """Angle (degrees) of the rotation ``R_est R_trueᵀ`` — the attitude error."""
    R_est = check_rotation(R_est, "R_est", atol=1e-5)
    R_true = check_rotation(R_true, "R_true", atol=1e-5)
    return float(np.degrees(Rotation.from_matrix(R_est @ R_true.T).magnitude()))
