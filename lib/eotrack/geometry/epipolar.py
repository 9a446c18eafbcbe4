"""Epipolar geometry from known camera poses (Huang et al., eqs. 1–5 and 8).

``F = M₂^{-T} R₁₂ S₁₂ M₁^{-1}`` with ``R₁₂ = r₂ r₁^{-1}`` and ``S₁₂ = [t]ₓ``, ``t`` the centre of
camera 2 in camera-1 coordinates. A point with camera-1 coordinates ``P₁`` has camera-2
coordinates ``R₁₂ (P₁ − t)``, and ``(P₁ − t)ᵀ [t]ₓ P₁ = 0`` — so ``p₂ᵀ F p₁ = 0`` for the two
images of any world point.
"""

from __future__ import annotations

import math

import numpy as np

from eotrack.validation import as_finite_array, as_points

from .camera import check_intrinsics
from .rotations import check_rotation

__all__ = [
    "cross_matrix",
    "epipolar_distances",
    "epipolar_lines",
    "epipoles",
    "fundamental_from_poses",
    "relative_pose",
    "sampson_distances",
]


def cross_matrix(t) -> np.ndarray:
    """Eq. (5): the skew matrix ``[t]ₓ`` with ``[t]ₓ v = t × v``."""
    tx, ty, tz = as_finite_array(t, "t", shape=(3,))
    return np.array([[0.0, -tz, ty], [tz, 0.0, -tx], [-ty, tx, 0.0]])


def relative_pose(R1, c1, R2, c2) -> tuple[np.ndarray, np.ndarray]:
    """Eq. (3) and the translation of eq. (5): ``R₁₂ = R₂ R₁ᵀ`` and ``t = R₁ (c₂ − c₁)``.

    Raises
    ------
    ValueError
        For non-rotations or coincident centres (zero baseline: no epipolar geometry).
    """
    r1 = check_rotation(R1, "R1")
    r2 = check_rotation(R2, "R2")
    a = as_finite_array(c1, "c1", shape=(3,))
    b = as_finite_array(c2, "c2", shape=(3,))
    base = b - a
    scale = max(np.linalg.norm(a), np.linalg.norm(b), 1.0)
    if np.linalg.norm(base) <= 1e-12 * scale:
        raise ValueError("c1 and c2 coincide (zero baseline): the fundamental matrix is "
                         "undefined; two distinct camera centres are needed")
    return r2 @ r1.T, r1 @ base


def fundamental_from_poses(K1, R1, c1, K2, R2, c2) -> np.ndarray:
    """Fundamental matrix of two calibrated cameras at known poses (eq. 2).

    Parameters
    ----------
    K1, K2
        Intrinsic matrices (3×3, non-singular).
    R1, R2
        World → camera rotations (proper orthonormal).
    c1, c2
        Camera centres in world coordinates (distinct).

    Returns
    -------
    numpy.ndarray
        ``F`` (3×3, rank 2, Frobenius norm 1) with ``p₂ᵀ F p₁ = 0`` for homogeneous pixel
        coordinates ``p = (u, v, 1)`` of the same world point.
    """
    k1 = check_intrinsics(K1, "K1")
    k2 = check_intrinsics(K2, "K2")
    r12, t = relative_pose(R1, c1, R2, c2)
    f = np.linalg.inv(k2).T @ r12 @ cross_matrix(t) @ np.linalg.inv(k1)
    return f / np.linalg.norm(f)


_F8 = np.dtype(np.float64)


def _check_F(F) -> np.ndarray:
    if type(F) is np.ndarray and F.shape == (3, 3) and F.dtype == np.float64 and \
            np.isfinite(F).all() and F.any():
        return F
    f = as_finite_array(F, "F")
    if f.shape != (3, 3):
        raise ValueError(f"F must be a 3x3 fundamental matrix, got shape {f.shape}")
    if not np.any(f):
        raise ValueError("F must not be the zero matrix")
    return f


def epipolar_lines(F, pts1) -> np.ndarray:
    """Lines ``l = F p₁ = (a, b, c)`` in image 2, one row per point of image 1, normalised so
    that ``a² + b² = 1`` (then ``l · (u, v, 1)`` is a signed pixel distance)."""
    return _lines(_check_F(F), as_points(pts1, "pts1"))


#: relative size of (a, b) = (F p)₁,₂ (against max|F|·max|p|) below which a point counts as AT the epipole: there the
#: line is round-off (|(a, b)| ~ ε‖F‖‖p‖) and any distance would be arbitrary. 1e-12 is ~4500
#: ulp; it flags only points within ~1e-9 px of the epipole.
EPIPOLE_RTOL = 1e-12


def _epipole_limit(f: np.ndarray, p: np.ndarray) -> float:
    return EPIPOLE_RTOL * float(np.abs(f).max()) * (float(np.abs(p).max()) + 1.0)


def _lines(f: np.ndarray, p: np.ndarray) -> np.ndarray:
    lines = p @ f[:, :2].T + f[:, 2]
    n = np.hypot(lines[:, 0], lines[:, 1])
    lim = _epipole_limit(f, p) if len(n) else np.nan
    if math.isfinite(lim) and n.min() <= lim:
        raise ValueError("pts1 contains the epipole of image 1: its epipolar line is undefined")
    return lines / n[:, None]


def epipolar_distances(F, pts1, pts2) -> np.ndarray:
    """Eq. (8): distance (px) of every ``pts2`` point from the epipolar line of every ``pts1`` point.

    ``d[i, j] = |p₂ⱼᵀ F p₁ᵢ| / sqrt(a_i² + b_i²)`` with ``F p₁ᵢ = (a_i, b_i, c_i)``; vectorised,
    invariant to the scale of ``F``. A ``pts1`` point at the epipole (``|(a, b)|`` at
    round-off level, :data:`EPIPOLE_RTOL`) has no epipolar line: ValueError, not arbitrary
    numbers.

    Parameters
    ----------
    F
        Fundamental matrix (3×3) with ``p₂ᵀ F p₁ = 0``.
    pts1, pts2
        Pixel coordinates ``(n1, 2)`` and ``(n2, 2)`` (either may be empty).

    Returns
    -------
    numpy.ndarray
        ``(n1, n2)`` distances.
    """
    if not (type(F) is np.ndarray and type(pts1) is np.ndarray and type(pts2) is np.ndarray
            and F.dtype is _F8 and pts1.dtype is _F8 and pts2.dtype is _F8
            and F.shape == (3, 3) and pts1.ndim == 2 == pts2.ndim
            and pts1.shape[1] == 2 == pts2.shape[1] and len(pts1) and len(pts2)):
        # slow path: full validation with the error messages, then the same kernel
        F = _check_F(F)
        pts1 = as_points(pts1, "pts1")
        pts2 = as_points(pts2, "pts2")
        if len(pts1) == 0 or len(pts2) == 0:
            return np.zeros((len(pts1), len(pts2)))
        _lines(F, pts1)  # raises for a point at the epipole
    # The kernel. Both point sets go into one homogeneous buffer H = [[p1ᵀ, p2ᵀ], [1, 1]]; ONE
    # product F H gives the lines of image-1 points (contiguous rows a, b, c; normalised in
    # place by hypot(a, b)) and, as a by-product, F p2 — so a single dot product checks every
    # input (F, pts1, pts2) and every line norm for NaN/inf. The distance matrix is a second
    # product linesᵀ H2, taken in absolute value in place: no (n1, n2) temporaries. float64
    # throughout: float32 cannot keep 1e-6 px agreement at 512-px coordinates (~3e-5 px).
    n1 = len(pts1)
    h = np.empty((3, n1 + len(pts2)))
    h[:2, :n1] = pts1.T
    h[:2, n1:] = pts2.T
    h[2] = 1.0
    both = F @ h
    lines = both[:, :n1]
    nrm = np.hypot(lines[0], lines[1])
    lim = _epipole_limit(F, pts1)  # NaN/inf inputs: not finite, left to the check below
    if math.isfinite(lim) and nrm.min() <= lim:  # at the epipole: no line (exact/round-off)
        raise ValueError("pts1 contains the epipole of image 1: its epipolar line is undefined")
    lines /= nrm
    flat = both.ravel()
    if not math.isfinite(flat @ flat):  # re-validate: raises with the right message
        _check_F(F)
        as_points(pts1, "pts1")
        as_points(pts2, "pts2")
        _lines(F, pts1)  # (valid inputs reach here only if the check overflowed: carry on)
    out = lines.T @ h[:, n1:]
    return np.abs(out, out=out)


def sampson_distances(F, pts1, pts2) -> np.ndarray:
    """First-order geometric (Sampson) distance for every pair, ``(n1, n2)``, in pixels.

    ``d = |p₂ᵀFp₁| / sqrt((Fp₁)₁² + (Fp₁)₂² + (Fᵀp₂)₁² + (Fᵀp₂)₂²)`` — errors in both images
    are accounted for (the one-sided distance of eq. 8 blames image 2 only). Returned as a
    distance (square root of the usual Sampson error).
    """
    f = _check_F(F)
    p1 = as_points(pts1, "pts1")
    p2 = as_points(pts2, "pts2")
    if len(p1) == 0 or len(p2) == 0:
        return np.zeros((len(p1), len(p2)))
    l2 = p1 @ f[:, :2].T + f[:, 2]  # F p1, (n1, 3)
    l1 = p2 @ f[:2, :] + f[2, :]  # Fᵀ p2 as rows, (n2, 3)
    alg = l2[:, :2] @ p2.T + l2[:, 2:]  # p2ᵀ F p1, (n1, n2)
    den = (l2[:, 0] ** 2 + l2[:, 1] ** 2)[:, None] + (l1[:, 0] ** 2 + l1[:, 1] ** 2)[None, :]
    return np.abs(alg) / np.sqrt(den)


def epipoles(F) -> tuple[np.ndarray, np.ndarray]:
    """Homogeneous epipoles ``(e1, e2)`` with ``F e1 = 0`` and ``Fᵀ e2 = 0`` (unit norm)."""
    f = _check_F(F)
    _, _, vt = np.linalg.svd(f)
    _, _, vt2 = np.linalg.svd(f.T)
    return vt[-1], vt2[-1]
