"""Fisher information and Cramér–Rao lower bound of a pose from N image points (§2.3).

Measurement model: each of the N points gives an image position ``u_i = π(K (R X_i + t)) + e_i``
with ``e_i ~ N(0, σ_i² I₂)`` independent. For Gaussian noise the Fisher information of any pose
parametrisation ``θ`` is

    J(θ) = Σ_i G_iᵀ G_i / σ_i²,      G_i = ∂u_i/∂θ  (2 × dim θ),

so information is *additive over points*: ``J(S ∪ {i}) = J(S) + J_i`` with ``J_i ⪰ 0``.

Two parametrisations:

* minimal (6): ``(δt, δθ)`` with ``t ← t + δt`` and the rotation perturbed on the left,
  ``R ← expm([δθ]ₓ) R``; then ``∂x_c/∂δt = I`` and ``∂x_c/∂δθ = −[R X]ₓ``;
* the paper's (7): ``θ = (t1, t2, t3, q0, q1, q2, q3)`` (eq. 5). With ``R = R(q/|q|)`` the
  information is singular along ``q`` (scaling ``q`` changes nothing); the unit-norm constraint is
  handled by the constrained CRLB (Stoica & Ng 1998) ``U (Uᵀ J U)⁻¹ Uᵀ``, ``U`` an orthonormal
  basis of the tangent space ``{δq : qᵀδq = 0}``, which equals the minimal-form bound mapped
  through ``δq = ½ (0, δθ) ⊗ q``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from eotrack.validation import as_finite_array, as_points

from .projection import _check_K, check_rotation, check_translation, matrix_from_quaternion, skew

__all__ = [
    "constrained_crlb",
    "finite_difference_jacobian",
    "minimal_to_quaternion_jacobian",
    "pose_crlb",
    "pose_fisher_information",
    "pose_fisher_information_quaternion",
    "projection_jacobian",
    "projection_jacobian_quaternion",
    "quaternion_crlb",
]


def _sigma(sigma_px: Any, n: int) -> np.ndarray:
    s = as_finite_array(sigma_px, "sigma_px", ndim=(0, 1))
    if s.ndim == 1 and s.shape[0] != n:
        raise ValueError(f"sigma_px must be a scalar or have shape ({n},), got {s.shape}")
    if np.any(s <= 0):
        raise ValueError("sigma_px must be > 0 (noise standard deviation in image units), got "
                         f"min {float(np.min(s))!r}")
    return np.broadcast_to(s, (n,)).astype(float)


def _camera(points: Any, R: Any, t: Any, K: Any, min_points: int = 1):
    X = as_points(points, "points", dim=3)
    if X.shape[0] < min_points:
        raise ValueError(f"points needs at least {min_points} points, got {X.shape[0]}")
    R = check_rotation(R)
    t = check_translation(t)
    K = _check_K(K)
    RX = X @ R.T
    xc = RX + t
    if np.any(xc[:, 2] <= 0):
        raise ValueError(f"points: {int(np.sum(xc[:, 2] <= 0))} point(s) lie behind the camera")
    return X, R, t, K, RX, xc


def _du_dxc(xc: np.ndarray, K: np.ndarray) -> np.ndarray:
    """∂u/∂x_c, shape (n, 2, 3): ``(K[:2] − u e₃ᵀ) / z_c``."""
    p = xc @ K.T
    z = p[:, 2]
    u = p[:, :2] / z[:, None]
    D = np.broadcast_to(K[:2], (len(xc), 2, 3)).copy()
    D[:, :, 2] -= u
    return D / z[:, None, None]


def projection_jacobian(points: Any, R: Any, t: Any, K: Any) -> np.ndarray:
    """Analytic Jacobians ``G_i = ∂u_i/∂(δt, δθ)`` of the projections, shape (n, 2, 6).

    ``t ← t + δt`` and ``R ← expm([δθ]ₓ) R``; with ``x_c = R X + t``:
    ``∂u/∂δt = ∂u/∂x_c`` and ``∂u/∂δθ = −∂u/∂x_c [R X]ₓ``.
    """
    _, _, _, K, RX, xc = _camera(points, R, t, K)
    D = _du_dxc(xc, K)
    G = np.empty((len(xc), 2, 6))
    G[:, :, :3] = D
    G[:, :, 3:] = -D @ skew(RX)
    return G


def _dRX_dq(q: np.ndarray, X: np.ndarray) -> np.ndarray:
    """∂(R(q/|q|) X)/∂q at a unit ``q`` (scalar first), shape (n, 3, 4).

    For a unit quaternion ``R X = (w² − vᵀv) X + 2 (vᵀX) v + 2 w (v × X)``; its derivative is
    taken with respect to the un-normalised ``q`` and multiplied by ``(I − q qᵀ)``, the
    Jacobian of ``q / |q|`` at ``|q| = 1``.
    """
    w, v = q[0], q[1:]
    n = len(X)
    D = np.empty((n, 3, 4))
    D[:, :, 0] = 2.0 * w * X + 2.0 * np.cross(v, X)
    vX = X @ v
    D[:, :, 1:] = (-2.0 * X[:, :, None] * v[None, None, :]
                   + 2.0 * v[None, :, None] * X[:, None, :]
                   + 2.0 * vX[:, None, None] * np.eye(3)
                   - 2.0 * w * skew(X))
    return D @ (np.eye(4) - np.outer(q, q))


def _unit_quaternion(q: Any) -> np.ndarray:
    q = as_finite_array(q, "q", shape=(4,))
    nq = np.linalg.norm(q)
    if abs(nq - 1.0) > 1e-6:
        raise ValueError(f"q must be a unit quaternion (|q| = 1), got |q| = {nq:.6g}")
    return q / nq


def projection_jacobian_quaternion(points: Any, q: Any, t: Any, K: Any) -> np.ndarray:
    """Analytic Jacobians ``∂u_i/∂(t1, t2, t3, q0, q1, q2, q3)`` (the paper's θ), shape (n, 2, 7).

    ``R = R(q/|q|)``, so every row is orthogonal to ``(0, 0, 0, q)``.
    """
    q = _unit_quaternion(q)
    R = matrix_from_quaternion(q)
    X, _, _, K, _, xc = _camera(points, R, t, K)
    D = _du_dxc(xc, K)
    G = np.empty((len(xc), 2, 7))
    G[:, :, :3] = D
    G[:, :, 3:] = D @ _dRX_dq(q, X)
    return G


def _info(G: np.ndarray, sigma: np.ndarray) -> np.ndarray:
    Gw = G / sigma[:, None, None]
    return np.einsum("nki,nkj->ij", Gw, Gw)


def pose_fisher_information(points: Any, R: Any, t: Any, K: Any, sigma_px: Any) -> np.ndarray:
    """Fisher information of the pose for (δt (3), δθ (3)), a 6×6 matrix.

    Parameters
    ----------
    points
        (n, 3) target-frame points.
    R, t
        Pose, ``x_c = R X + t``; ``R`` must be a rotation matrix.
    K
        Intrinsic matrix, ``u = K x_c / z_c``.
    sigma_px
        Standard deviation of each image coordinate (image units), scalar or (n,), > 0.

    Returns
    -------
    numpy.ndarray
        ``J = Σ G_iᵀ G_i / σ_i²`` with ``G_i`` from :func:`projection_jacobian`; the rotation is
        perturbed on the left, ``R ← expm([δθ]ₓ) R``, and ``t ← t + δt``.
    """
    G = projection_jacobian(points, R, t, K)
    return _info(G, _sigma(sigma_px, len(G)))


def pose_fisher_information_quaternion(points: Any, q: Any, t: Any, K: Any,
                                       sigma_px: Any) -> np.ndarray:
    """Fisher information for the paper's θ = (t, q) (7×7, singular along ``(0, q)``)."""
    G = projection_jacobian_quaternion(points, q, t, K)
    return _info(G, _sigma(sigma_px, len(G)))


def pose_crlb(points: Any, R: Any, t: Any, K: Any, sigma_px: Any, *,
              rcond: float = 1e-12) -> np.ndarray:
    """CRLB of (δt, δθ): the inverse of :func:`pose_fisher_information` (6×6).

    Raises
    ------
    ValueError
        If fewer than 3 points are given or the information is singular (degenerate geometry,
        e.g. collinear points).
    """
    X = as_points(points, "points", dim=3)
    if X.shape[0] < 3:
        raise ValueError(f"points needs at least 3 points for a pose CRLB, got {X.shape[0]}")
    J = pose_fisher_information(X, R, t, K, sigma_px)
    s = np.linalg.svd(J, compute_uv=False)
    if s[-1] <= rcond * s[0]:
        raise ValueError("points give a singular Fisher information (degenerate geometry, e.g. "
                         f"collinear points); condition number {s[0] / max(s[-1], 1e-300):.2e}")
    return np.linalg.inv(J)


def constrained_crlb(J: Any, q: Any) -> np.ndarray:
    """Constrained CRLB of θ = (t, q) under ``|q| = 1`` (Stoica & Ng 1998), 7×7.

    ``C = U (Uᵀ J U)⁻¹ Uᵀ`` with ``U`` (7×6) an orthonormal basis of the null space of the
    constraint gradient ``(0, 0, 0, 2 q)``.
    """
    J = as_finite_array(J, "J", shape=(7, 7))
    q = _unit_quaternion(q)
    F = np.concatenate([np.zeros(3), q])[None, :]
    U = np.linalg.svd(F)[2][1:].T  # 7×6, orthonormal, ⟂ F
    return U @ np.linalg.inv(U.T @ J @ U) @ U.T


def minimal_to_quaternion_jacobian(q: Any) -> np.ndarray:
    """Jacobian ``∂(t, q)/∂(δt, δθ)`` (7×6) of the left perturbation ``q ← exp(δθ/2) ⊗ q``.

    ``δq = ½ (0, δθ) ⊗ q``, i.e. ``∂q/∂δθ = ½ [[−vᵀ], [w I − [v]ₓ]]`` for ``q = (w, v)``.
    """
    q = _unit_quaternion(q)
    w, v = q[0], q[1:]
    E = np.zeros((7, 6))
    E[:3, :3] = np.eye(3)
    E[3, 3:] = -0.5 * v
    E[4:, 3:] = 0.5 * (w * np.eye(3) - skew(v))
    return E


def quaternion_crlb(points: Any, R: Any, t: Any, K: Any, sigma_px: Any) -> np.ndarray:
    """CRLB of the paper's 7 parameters (t, q) from the minimal form, ``E C₆ Eᵀ`` (7×7)."""
    from .projection import quaternion_from_matrix

    C6 = pose_crlb(points, R, t, K, sigma_px)
    E = minimal_to_quaternion_jacobian(quaternion_from_matrix(R))
    return E @ C6 @ E.T


def finite_difference_jacobian(points: Any, R: Any, t: Any, K: Any, *,
                               step: float = 1e-6) -> np.ndarray:
    """Central finite-difference version of :func:`projection_jacobian` (n, 2, 6), for checks."""
    from scipy.spatial.transform import Rotation

    from .projection import project_points

    X = as_points(points, "points", dim=3)
    R = check_rotation(R)
    t = check_translation(t)
    out = np.empty((len(X), 2, 6))
    for k in range(6):
        d = np.zeros(6)
        d[k] = step
        ups = []
        for s in (1.0, -1.0):
            Rk = Rotation.from_rotvec(s * d[3:]).as_matrix() @ R
            ups.append(project_points(X, Rk, t + s * d[:3], K))
        out[:, :, k] = (ups[0] - ups[1]) / (2 * step)
    return out
