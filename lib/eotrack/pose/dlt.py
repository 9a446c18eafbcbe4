"""Linear (DLT) pose from ≥ 6 point correspondences, Hartley-normalised, batched.

The paper's RANSAC (§2.2, step 1) estimates the pose from 6 random points with a linear solution.
Image points are first mapped to normalised camera coordinates ``x̂ = K⁻¹ u`` so the unknown is
``[R | t]`` up to scale:

* general 3-D points: ``x̂ ~ M X̃`` with ``M = λ [R | t]`` (3×4, 11 dof, ≥ 6 points); ``R`` is the
  nearest rotation to ``M[:, :3]`` (SVD) and ``λ`` the mean singular value;
* coplanar points (the paper's simulation puts every feature on one plane, where the 3×4 DLT is
  rank-deficient): in plane coordinates ``(a, b)``, ``x̂ ~ H (a, b, 1)`` with
  ``H = λ [R e₁, R e₂, R c + t]`` (8 dof, ≥ 4 points; 6 in the paper's sample).

Both systems are solved by SVD after Hartley normalisation (centroid at 0, mean distance √2 or
√3), for a whole batch of samples at once. Collinear samples are degenerate.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from eotrack.validation import as_points, check_same_length

from .projection import _check_K

__all__ = ["dlt_pose", "dlt_pose_batch", "is_planar", "plane_frame"]


def _svd_spread(X: np.ndarray) -> np.ndarray:
    """Singular values of the centred point cloud(s), (..., 3)."""
    Xc = X - X.mean(axis=-2, keepdims=True)
    return np.linalg.svd(Xc, compute_uv=False)


def is_planar(points: Any, *, rtol: float = 1e-6) -> bool:
    """Whether the (n, 3) points lie on one plane (smallest spread ≤ ``rtol`` × largest)."""
    X = as_points(points, "points", dim=3)
    s = _svd_spread(X)
    return bool(s[2] <= rtol * s[0])


def plane_frame(points: Any) -> tuple[np.ndarray, np.ndarray]:
    """Centroid ``c`` and orthonormal basis ``B = [e₁ e₂ n]`` (columns) of the best-fit plane."""
    X = as_points(points, "points", dim=3)
    c = X.mean(axis=0)
    _, _, Vt = np.linalg.svd(X - c, full_matrices=False)
    B = Vt.T.copy()
    if np.linalg.det(B) < 0:
        B[:, 2] *= -1
    return c, B


def _normalise(P: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Hartley normalisation of (B, n, d) points; returns normalised points and (B, d+1, d+1) T."""
    d = P.shape[-1]
    c = P.mean(axis=1, keepdims=True)
    dist = np.linalg.norm(P - c, axis=-1).mean(axis=1)
    s = np.sqrt(d) / np.maximum(dist, 1e-300)
    T = np.zeros((P.shape[0], d + 1, d + 1))
    T[:, np.arange(d), np.arange(d)] = s[:, None]
    T[:, :d, d] = -s[:, None] * c[:, 0, :]
    T[:, d, d] = 1.0
    return (P - c) * s[:, None, None], T


def _nearest_rotation(A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Nearest rotations (B, 3, 3) to matrices A and their mean singular values."""
    U, S, Vt = np.linalg.svd(A)
    D = np.ones((A.shape[0], 3))
    D[:, 2] = np.sign(np.linalg.det(U @ Vt))
    return (U * D[:, None, :]) @ Vt, S.mean(axis=1)


def _homography_pose(ab: np.ndarray, xn: np.ndarray, c: np.ndarray, B: np.ndarray):
    n_b = ab.shape[0]
    a_n, Ta = _normalise(ab)
    x_n, Tx = _normalise(xn)
    m = ab.shape[1]
    A = np.zeros((n_b, 2 * m, 9))
    ones = np.ones((n_b, m, 1))
    ah = np.concatenate([a_n, ones], axis=-1)
    A[:, 0::2, 0:3] = ah
    A[:, 0::2, 6:9] = -x_n[:, :, 0:1] * ah
    A[:, 1::2, 3:6] = ah
    A[:, 1::2, 6:9] = -x_n[:, :, 1:2] * ah
    Hn = np.linalg.svd(A, full_matrices=A.shape[1] < 9)[2][:, -1].reshape(n_b, 3, 3)
    H = np.linalg.inv(Tx) @ Hn @ Ta
    h1, h2, h3 = H[:, :, 0], H[:, :, 1], H[:, :, 2]
    lam = 2.0 / (np.linalg.norm(h1, axis=1) + np.linalg.norm(h2, axis=1))
    sgn = np.where(h3[:, 2] * lam < 0, -1.0, 1.0)  # centroid in front of the camera
    lam = lam * sgn
    r1, r2 = lam[:, None] * h1, lam[:, None] * h2
    Rp = np.stack([r1, r2, np.cross(r1, r2)], axis=-1)  # = R B
    R, _ = _nearest_rotation(Rp @ np.swapaxes(B, 1, 2))
    t = lam[:, None] * h3 - np.einsum("bij,bj->bi", R, c)
    return R, t


def _general_pose(X: np.ndarray, xn: np.ndarray):
    n_b, m, _ = X.shape
    X_n, TX = _normalise(X)
    x_n, Tx = _normalise(xn)
    Xh = np.concatenate([X_n, np.ones((n_b, m, 1))], axis=-1)
    A = np.zeros((n_b, 2 * m, 12))
    A[:, 0::2, 0:4] = Xh
    A[:, 0::2, 8:12] = -x_n[:, :, 0:1] * Xh
    A[:, 1::2, 4:8] = Xh
    A[:, 1::2, 8:12] = -x_n[:, :, 1:2] * Xh
    Mn = np.linalg.svd(A, full_matrices=False)[2][:, -1].reshape(n_b, 3, 4)
    M = np.linalg.inv(Tx) @ Mn @ TX
    M = M * np.sign(np.linalg.det(M[:, :, :3]))[:, None, None]
    R, lam = _nearest_rotation(M[:, :, :3])
    t = M[:, :, 3] / lam[:, None]
    # depth of the centroid must be positive; otherwise the sign of M was wrong
    return R, t


def dlt_pose_batch(points: np.ndarray, pixels: np.ndarray, K: Any, *,
                   planar: bool | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """DLT poses of a batch of samples.

    Parameters
    ----------
    points
        (B, m, 3) target-frame points of each sample (m ≥ 6 for general points, ≥ 4 planar).
    pixels
        (B, m, 2) image coordinates.
    K
        Intrinsic matrix.
    planar
        Use the plane-homography form (``True``), the 3×4 DLT (``False``) or decide per sample
        (``None``).

    Returns
    -------
    R, t, ok
        (B, 3, 3), (B, 3) and a boolean (B,) mask; ``ok`` is False for degenerate (collinear or,
        with ``planar=False``, coplanar) samples, whose ``R, t`` are meaningless.
    """
    K = _check_K(K)
    X = np.asarray(points, float)
    u = np.asarray(pixels, float)
    if X.ndim != 3 or X.shape[-1] != 3 or u.shape != (*X.shape[:2], 2):
        raise ValueError(f"points must be (B, m, 3) and pixels (B, m, 2), got {X.shape} and "
                         f"{u.shape}")
    n_b, m, _ = X.shape
    xn = (u - K[:2, 2]) @ np.linalg.inv(K[:2, :2]).T
    s = _svd_spread(X)
    collinear = s[:, 1] <= 1e-9 * s[:, 0]
    flat = s[:, 2] <= 1e-6 * s[:, 0]
    use_plane = flat if planar is None else np.full(n_b, bool(planar))
    R = np.tile(np.eye(3), (n_b, 1, 1))
    t = np.zeros((n_b, 3))
    ok = ~collinear & (m >= np.where(use_plane, 4, 6))
    ok &= ~(flat & ~use_plane)
    sel_p = np.flatnonzero(ok & use_plane)
    if sel_p.size:
        c = X[sel_p].mean(axis=1)
        _, _, Vt = np.linalg.svd(X[sel_p] - c[:, None, :], full_matrices=False)
        Bm = np.swapaxes(Vt, 1, 2).copy()
        Bm[:, :, 2] *= np.sign(np.linalg.det(Bm))[:, None]
        ab = np.einsum("bmk,bkj->bmj", X[sel_p] - c[:, None, :], Bm[:, :, :2])
        R[sel_p], t[sel_p] = _homography_pose(ab, xn[sel_p], c, Bm)
    sel_g = np.flatnonzero(ok & ~use_plane)
    if sel_g.size:
        R[sel_g], t[sel_g] = _general_pose(X[sel_g], xn[sel_g])
    ok &= np.all(np.isfinite(t), axis=1) & np.all(np.isfinite(R), axis=(1, 2))
    return R, t, ok


def dlt_pose(points: Any, pixels: Any, K: Any) -> tuple[np.ndarray, np.ndarray]:
    """Linear pose ``(R, t)`` from n ≥ 6 correspondences (plane homography if coplanar).

    Parameters
    ----------
    points
        (n, 3) target-frame points, n ≥ 6.
    pixels
        (n, 2) image coordinates.
    K
        Intrinsic matrix.

    Returns
    -------
    R, t
        Rotation (target → camera) and translation.

    Raises
    ------
    ValueError
        Fewer than 6 points, mismatched lengths, or collinear points.
    """
    X = as_points(points, "points", dim=3)
    u = as_points(pixels, "pixels", dim=2)
    check_same_length("points", X, "pixels", u)
    if X.shape[0] < 6:
        raise ValueError(f"points needs at least 6 correspondences for the DLT pose, got "
                         f"{X.shape[0]}")
    s = _svd_spread(X)
    if s[1] <= 1e-9 * s[0]:
        raise ValueError("points are collinear (degenerate): the pose is not determined")
    R, t, ok = dlt_pose_batch(X[None], u[None], K)
    if not ok[0]:
        raise ValueError("points are degenerate for the DLT pose")
    return R[0], t[0]
