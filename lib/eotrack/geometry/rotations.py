"""Elementary rotations and the 3-2-1 (yaw, pitch, roll) attitude matrix.

All matrices here are *passive* (frame rotations), as Huang et al. write them (eq. 4): the
matrix ``r`` maps the coordinates of a fixed vector in the reference frame to its coordinates in
the rotated (camera) frame, ``x_cam = r @ x_ref``. ``rot_z(a)`` is the frame turned by ``+a``
about z, i.e. ``[[cos a, sin a, 0], [−sin a, cos a, 0], [0, 0, 1]]``.
"""

from __future__ import annotations

import numpy as np

from eotrack.validation import as_finite_array

__all__ = [
    "check_rotation",
    "dcm_321",
    "euler_321_from_matrix",
    "look_at",
    "rot_x",
    "rot_y",
    "rot_z",
    "rotation_321",
]


def _angles(a, name: str) -> np.ndarray:
    return as_finite_array(a, name)


def rot_x(angle_rad) -> np.ndarray:
    """Passive rotation about x: ``[[1, 0, 0], [0, c, s], [0, −s, c]]`` (shape ``(..., 3, 3)``)."""
    a = _angles(angle_rad, "angle_rad")
    c, s, o, z = np.cos(a), np.sin(a), np.ones_like(a), np.zeros_like(a)
    return np.stack([np.stack([o, z, z], -1), np.stack([z, c, s], -1),
                     np.stack([z, -s, c], -1)], -2)


def rot_y(angle_rad) -> np.ndarray:
    """Passive rotation about y: ``[[c, 0, −s], [0, 1, 0], [s, 0, c]]`` (shape ``(..., 3, 3)``)."""
    a = _angles(angle_rad, "angle_rad")
    c, s, o, z = np.cos(a), np.sin(a), np.ones_like(a), np.zeros_like(a)
    return np.stack([np.stack([c, z, -s], -1), np.stack([z, o, z], -1),
                     np.stack([s, z, c], -1)], -2)


def rot_z(angle_rad) -> np.ndarray:
    """Passive rotation about z: ``[[c, s, 0], [−s, c, 0], [0, 0, 1]]`` (shape ``(..., 3, 3)``)."""
    a = _angles(angle_rad, "angle_rad")
    c, s, o, z = np.cos(a), np.sin(a), np.ones_like(a), np.zeros_like(a)
    return np.stack([np.stack([c, s, z], -1), np.stack([-s, c, z], -1),
                     np.stack([z, z, o], -1)], -2)


def rotation_321(yaw_rad, pitch_rad, roll_rad) -> np.ndarray:
    """Reference → camera matrix of a 3-2-1 rotation, eq. (4) of Huang et al.

    ``r = Rz(Y) · Ry(P) · Rx(R)`` with the passive elementary matrices :func:`rot_z`,
    :func:`rot_y`, :func:`rot_x` — exactly the product printed in the paper. Applied to a
    vector (``x_cam = r x_ref``) this turns the frame first about x by R, then about y by P,
    then about z by Y: as printed, eq. (4) is a 1-2-3 frame sequence, although the paper calls
    it 3-2-1. We keep its product so the code matches eq. (4); the conventional aerospace
    3-2-1 matrix is :func:`dcm_321`. :func:`euler_321_from_matrix` inverts this one.

    Parameters
    ----------
    yaw_rad, pitch_rad, roll_rad
        Angles in radians (scalars or broadcastable arrays).

    Returns
    -------
    numpy.ndarray
        ``(..., 3, 3)`` proper orthonormal matrices.
    """
    y = _angles(yaw_rad, "yaw_rad")
    p = _angles(pitch_rad, "pitch_rad")
    r = _angles(roll_rad, "roll_rad")
    return rot_z(y) @ rot_y(p) @ rot_x(r)


def dcm_321(yaw_rad, pitch_rad, roll_rad) -> np.ndarray:
    """Conventional aerospace 3-2-1 reference → body matrix ``Rx(roll) · Ry(pitch) · Rz(yaw)``.

    The frame is turned first by yaw about z, then by pitch about the new y, then by roll about
    the new x (passive matrices). Note the order differs from the paper's eq. (4), see
    :func:`rotation_321`; the two coincide only when at most one angle is non-zero.
    """
    y = _angles(yaw_rad, "yaw_rad")
    p = _angles(pitch_rad, "pitch_rad")
    r = _angles(roll_rad, "roll_rad")
    return rot_x(r) @ rot_y(p) @ rot_z(y)


def euler_321_from_matrix(r) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Angles ``(yaw, pitch, roll)`` (radians) with ``rotation_321(yaw, pitch, roll) == r``.

    With ``r = Rz(Y) Ry(P) Rx(R)`` the first column is ``(cY cP, −sY cP, sP)`` and the last row is
    ``(sP, −cP sR, cP cR)`` (derived in notebook 02), so
    ``Y = atan2(−r₁₀, r₀₀)``, ``P = asin r₂₀``, ``R = atan2(−r₂₁, r₂₂)``; pitch in [−π/2, π/2].

    Parameters
    ----------
    r
        Rotation matrix ``(3, 3)`` or stack ``(..., 3, 3)``.
    """
    m = check_rotation(r, "r", batch=True)
    yaw = np.arctan2(-m[..., 1, 0], m[..., 0, 0])
    pitch = np.arctan2(m[..., 2, 0], np.hypot(m[..., 0, 0], m[..., 1, 0]))
    roll = np.arctan2(-m[..., 2, 1], m[..., 2, 2])
    return yaw, pitch, roll


def check_rotation(r, name: str = "R", *, atol: float = 1e-6, batch: bool = False) -> np.ndarray:
    """Return ``r`` as a float array after checking it is a proper rotation (RᵀR = I, det = +1).

    Raises
    ------
    ValueError
        If the shape is not ``(3, 3)`` (or ``(..., 3, 3)`` with ``batch``), or the matrix is not
        orthonormal with determinant +1 within ``atol``.
    """
    m = as_finite_array(r, name)
    if m.shape[-2:] != (3, 3) or (not batch and m.ndim != 2):
        raise ValueError(f"{name} must be a 3x3 rotation matrix, got shape {m.shape}")
    err = np.abs(np.swapaxes(m, -1, -2) @ m - np.eye(3)).max() if m.size else 0.0
    if err > atol:
        raise ValueError(f"{name} is not orthonormal (max |RᵀR − I| = {err:.2e} > {atol:g})")
    if m.size and np.any(np.linalg.det(m) < 0):
        raise ValueError(f"{name} has determinant −1 (a reflection), need a proper rotation")
    return m


def look_at(boresight, up=(0.0, 0.0, 1.0)) -> np.ndarray:
    """World → camera rotation of a camera looking along ``boresight``.

    Camera axes (computer-vision convention, used by OpenCV and by the pixel coordinates here):
    z along the boresight, x to the right (increasing column u), y down (increasing row v). The
    image's "up" (−y) is the projection of ``up`` onto the image plane.

    Parameters
    ----------
    boresight
        Viewing direction ``(3,)`` in world coordinates (any length > 0).
    up
        World direction that should appear up in the image; must not be parallel to boresight.
    """
    z = as_finite_array(boresight, "boresight", shape=(3,))
    u = as_finite_array(up, "up", shape=(3,))
    nz = np.linalg.norm(z)
    if nz == 0:
        raise ValueError("boresight must be a non-zero vector")
    z = z / nz
    x = np.cross(z, u)  # right = boresight × up  (then y = z × x points down)
    nx = np.linalg.norm(x)
    if nx < 1e-9 * max(np.linalg.norm(u), 1e-300):
        raise ValueError("up must not be parallel to boresight")
    x = x / nx
    y = np.cross(z, x)
    return np.stack([x, y, z])
