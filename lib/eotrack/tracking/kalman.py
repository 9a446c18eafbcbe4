"""Kalman filters for star-spot tracking: standard, Singer, Sage–Husa adaptive, confidence-gated.

The state of a star spot on the image is ``X = [x, y, v_x, v_y, a_x, a_y]`` (pixels, pixels per
second, pixels per second squared; Sheng 2026, eq. 30) and the measurement is its centroid
``Z = [x, y]`` (eq. 36). Everything here is plain linear algebra on numpy arrays:

* :func:`kalman_filter` — the standard filter over a measurement sequence (a NaN row means "no
  measurement": predict only);
* :func:`kalman_filter_batch` — the same filter run on many independent sequences at once
  (vectorised over the batch axis, for Monte Carlo work);
* :func:`singer_process_noise` — eqs. (33)–(35), the Singer acceleration variance
  ``q_a = σ_w²/(2α)(1 − e^{−2αΔT})`` put on the acceleration states;
* :func:`sage_husa_weight` and :func:`sage_husa_update` — eq. (41) with ``d_k = (1−b)/(1−b^{k+1})``
  and a safeguard that keeps ``R`` and ``Q`` positive definite;
* :class:`ConfidenceKalmanFilter` — eqs. (42)–(46): a confidence ``C_k`` from image quality and
  motion consistency selects one of three modes (update / update with inflated ``R`` / predict
  only with a growing ``Q``);
* :func:`track_nearest` — a nearest-neighbour driver that feeds per-frame detections to a filter;
* :func:`nees` and :func:`nis` — consistency statistics.

Conventions: every filter step is *predict, then update* (as FilterPy's ``batch_filter``), so
``x0, P0`` describe the state one frame period before the first measurement. Updates use the
Joseph form ``P = (I−KH)P(I−KH)ᵀ + KRKᵀ`` and covariances are re-symmetrised after each step.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from enum import IntEnum
from typing import Any

import numpy as np

from eotrack.validation import (
    as_finite_array,
    check_int,
    check_positive,
    check_probability,
)

__all__ = [
    "ConfidenceConfig",
    "ConfidenceKalmanFilter",
    "FilterMode",
    "KalmanFilter",
    "TrackResult",
    "constant_acceleration_model",
    "constant_velocity_model",
    "is_positive_definite",
    "kalman_filter",
    "kalman_filter_batch",
    "nees",
    "nis",
    "sage_husa_update",
    "sage_husa_weight",
    "singer_acceleration_variance",
    "singer_process_noise",
    "track_nearest",
    "white_acceleration_noise",
]


# --------------------------------------------------------------------------------------------
# validation helpers
# --------------------------------------------------------------------------------------------

def _square(value: Any, name: str, n: int | None = None, *, symmetric: bool = False,
            psd: bool = False, pd: bool = False) -> np.ndarray:
    arr = as_finite_array(value, name, ndim=2)
    if arr.shape[0] != arr.shape[1]:
        raise ValueError(f"{name} must be a square matrix, got shape {arr.shape}")
    if n is not None and arr.shape[0] != n:
        raise ValueError(f"{name} must have shape ({n}, {n}) to match the state/measurement "
                         f"dimension, got {arr.shape}")
    if symmetric or psd or pd:
        scale = max(1.0, float(np.max(np.abs(arr))))
        if not np.allclose(arr, arr.T, rtol=1e-9, atol=1e-12 * scale):
            raise ValueError(f"{name} must be symmetric")
    if pd and not is_positive_definite(arr):
        raise ValueError(f"{name} must be positive definite")
    if psd and not pd and np.min(np.linalg.eigvalsh(arr)) < -1e-10 * max(1.0, scale):
        raise ValueError(f"{name} must be positive semi-definite")
    return arr


def is_positive_definite(a: np.ndarray) -> bool:
    """Whether a symmetric matrix is positive definite (Cholesky succeeds).

    Parameters
    ----------
    a
        Square matrix (or a stack ``(..., n, n)``; all must be positive definite).
    """
    try:
        np.linalg.cholesky(np.asarray(a, dtype=float))
    except np.linalg.LinAlgError:
        return False
    return True


def _model(F: Any, H: Any, Q: Any, R: Any, x0: Any, P0: Any
           ) -> tuple[np.ndarray, ...]:
    F_ = as_finite_array(F, "F", ndim=2)
    if F_.shape[0] != F_.shape[1]:
        raise ValueError(f"F must be a square matrix, got shape {F_.shape}")
    n = F_.shape[0]
    H_ = as_finite_array(H, "H", ndim=2)
    if H_.shape[1] != n:
        raise ValueError(f"H must have {n} columns to match F {F_.shape}, got shape {H_.shape}")
    m = H_.shape[0]
    Q_ = _square(Q, "Q", n, psd=True)
    R_ = _square(R, "R", m, pd=True)
    x0_ = as_finite_array(x0, "x0", ndim=1)
    if x0_.shape != (n,):
        raise ValueError(f"x0 must have shape ({n},), got {x0_.shape}")
    P0_ = _square(P0, "P0", n, pd=True)
    return F_, H_, Q_, R_, x0_, P0_


# --------------------------------------------------------------------------------------------
# motion models
# --------------------------------------------------------------------------------------------

def constant_acceleration_model(dt: float, dim: int = 2) -> tuple[np.ndarray, np.ndarray]:
    """Transition and measurement matrices of the constant-acceleration model (eq. 30).

    Parameters
    ----------
    dt
        Frame period ΔT (s, > 0).
    dim
        Number of position coordinates (2 for an image).

    Returns
    -------
    F : numpy.ndarray
        ``(3 dim, 3 dim)`` transition for ``[p, v, a]`` (positions first, then velocities,
        then accelerations, as in eq. 30).
    H : numpy.ndarray
        ``(dim, 3 dim)`` measurement matrix selecting the positions.
    """
    t = check_positive(dt, "dt")
    d = check_int(dim, "dim", min_value=1)
    eye = np.eye(d)
    F = np.block([[eye, t * eye, 0.5 * t * t * eye],
                  [0 * eye, eye, t * eye],
                  [0 * eye, 0 * eye, eye]])
    H = np.hstack([eye, np.zeros((d, 2 * d))])
    return F, H


def constant_velocity_model(dt: float, dim: int = 2) -> tuple[np.ndarray, np.ndarray]:
    """Transition and measurement matrices of the constant-velocity model, state ``[p, v]``."""
    t = check_positive(dt, "dt")
    d = check_int(dim, "dim", min_value=1)
    eye = np.eye(d)
    F = np.block([[eye, t * eye], [0 * eye, eye]])
    H = np.hstack([eye, np.zeros((d, d))])
    return F, H


def white_acceleration_noise(dt: float, q: float, dim: int = 2) -> np.ndarray:
    """Process noise of the constant-velocity model driven by white acceleration of density ``q``.

    ``Q = q [[ΔT³/3, ΔT²/2], [ΔT²/2, ΔT]] ⊗ I`` (pixels² per s³ for ``q``).
    """
    t = check_positive(dt, "dt")
    qq = check_positive(q, "q", allow_zero=True)
    d = check_int(dim, "dim", min_value=1)
    return qq * np.kron(np.array([[t**3 / 3, t**2 / 2], [t**2 / 2, t]]), np.eye(d))


def singer_acceleration_variance(dt: float, alpha: float, sigma_w: float) -> float:
    """Eq. (34): ``q_a = σ_w² / (2α) · (1 − exp(−2 α ΔT))``.

    Parameters
    ----------
    dt
        Frame period ΔT (s).
    alpha
        Inverse manoeuvre (sway) time constant α (1/s, > 0).
    sigma_w
        Standard deviation density of the driving white noise ``w(t)`` of ``ȧ = −α a + w``
        (pixels/s^2.5).

    Returns
    -------
    float
        The discrete acceleration variance (pixels²/s⁴): the variance added to ``a`` over one
        frame by the Ornstein–Uhlenbeck process of eq. (33).
    """
    t = check_positive(dt, "dt")
    a = check_positive(alpha, "alpha")
    s = check_positive(sigma_w, "sigma_w", allow_zero=True)
    return float(s * s / (2 * a) * -np.expm1(-2 * a * t))


def singer_process_noise(dt: float, alpha: float, sigma_w: float, dim: int = 2) -> np.ndarray:
    """Eq. (35): ``Q = diag(0, …, 0, q_a, …, q_a)`` with ``q_a`` of eq. (34) on the accelerations.

    Returns the ``(3 dim, 3 dim)`` matrix for the state of :func:`constant_acceleration_model`.
    """
    d = check_int(dim, "dim", min_value=1)
    qa = singer_acceleration_variance(dt, alpha, sigma_w)
    return np.diag(np.r_[np.zeros(2 * d), np.full(d, qa)])


# --------------------------------------------------------------------------------------------
# the standard filter
# --------------------------------------------------------------------------------------------

def _check_zs(zs: Any, m: int, H: np.ndarray) -> np.ndarray:
    z = as_finite_array(zs, "zs", ndim=(1, 2), allow_nan=True)
    if z.ndim == 1:
        if m != 1:
            raise ValueError(f"zs must have shape (n, {m}) to match H, got {z.shape}")
        z = z[:, None]
    if z.shape[1] != m:
        raise ValueError(f"zs must have shape (n, {m}) to match H {H.shape}, got {z.shape}")
    return z


def _inv_stack(S: np.ndarray) -> np.ndarray:
    """Inverse of a stack of small matrices (closed form for 1×1 and 2×2)."""
    m = S.shape[-1]
    if m == 1:
        return 1.0 / S
    if m == 2:
        a, b, c, d = S[..., 0, 0], S[..., 0, 1], S[..., 1, 0], S[..., 1, 1]
        idet = 1.0 / (a * d - b * c)
        out = np.empty_like(S)
        out[..., 0, 0] = d * idet
        out[..., 0, 1] = -b * idet
        out[..., 1, 0] = -c * idet
        out[..., 1, 1] = a * idet
        return out
    return np.linalg.inv(S)


def kalman_filter(zs: Any, F: Any, H: Any, Q: Any, R: Any, x0: Any, P0: Any
                  ) -> tuple[np.ndarray, np.ndarray]:
    """Run the standard Kalman filter (eqs. 31–32, 36–40) over a measurement sequence.

    Each step predicts ``x⁻ = F x``, ``P⁻ = F P Fᵀ + Q`` and, if the measurement row is finite,
    updates with the gain ``K = P⁻Hᵀ(HP⁻Hᵀ + R)⁻¹``, ``x = x⁻ + K(z − Hx⁻)``,
    ``P = P⁻ − K H P⁻``. A row that contains NaN means no measurement: prediction only.

    Parameters
    ----------
    zs
        Measurements ``(n, m)`` (NaN rows allowed; ``(n,)`` when ``m = 1``).
    F, H, Q, R
        Transition ``(d, d)``, measurement ``(m, d)``, process noise ``(d, d)`` (symmetric
        positive semi-definite) and measurement noise ``(m, m)`` (symmetric positive definite).
    x0, P0
        State ``(d,)`` and covariance ``(d, d)`` one frame before the first measurement.

    Returns
    -------
    xs : numpy.ndarray
        Filtered states ``(n, d)``.
    Ps : numpy.ndarray
        Filtered covariances ``(n, d, d)`` (symmetrised).

    Notes
    -----
    The predict-then-update order is that of FilterPy's ``KalmanFilter.batch_filter``; both give
    the same estimates on the same data (to rounding; FilterPy uses the Joseph form for ``P``,
    algebraically equal for the optimal gain). The loop carries ``[P | x]`` as one ``(d, d+1)``
    array so that one matrix product predicts both and one rank-``m`` product updates both.
    The covariance recursion does not depend on the measured values: once the updated ``P``
    stops changing (relative change ≤ 1e-15, the steady state of an uninterrupted run of
    measurements) the converged gain is reused and only the state is propagated, until the
    next missing measurement restarts the full recursion.
    """
    F_, H_, Q_, R_, x, P = _model(F, H, Q, R, x0, P0)
    m = H_.shape[0]
    z = _check_zs(zs, m, H_)
    n, d = len(z), F_.shape[0]
    FT = np.ascontiguousarray(F_.T)
    M = np.empty((d, d + 1))
    M[:, :d] = P
    M[:, d] = x
    out = np.empty((n, d, d + 1))
    have = np.all(np.isfinite(z), axis=1).tolist()
    Zr = np.zeros((n, m, d + 1))
    Zr[:, :, d] = np.where(np.isfinite(z), z, 0.0)
    selector = np.array_equal(H_, np.hstack([np.eye(m), np.zeros((m, d - m))]))
    if selector and m == 2:
        r00, r01, r10, r11 = R_.ravel().tolist()
        zl = np.where(np.isfinite(z), z, 0.0)
        xs_steady = np.full(n, -1)           # frames served by the steady-state gain
        steady = False
        K_ss = P_ss = None
        x = M[:, d].copy()
        prev_post = None
        run = 0                              # consecutive measured frames
        for k in range(n):
            if steady:
                if have[k]:
                    x = F_ @ x
                    x += K_ss @ (zl[k] - x[:2])
                    out[k, :, d] = x
                    xs_steady[k] = 1
                    continue
                steady = False                 # a gap: back to the full recursion
                M[:, :d] = P_ss
                M[:, d] = x
            M = F_ @ M
            P = M[:, :d] @ FT
            P += Q_
            M[:, :d] = P
            if have[k]:
                a, b, c, e = P[:2, :2].ravel().tolist()
                a += r00
                b += r01
                c += r10
                e += r11
                idet = 1.0 / (a * e - b * c)
                K = P[:, :2] @ np.array(((e * idet, -b * idet), (-c * idet, a * idet)))
                M -= K @ (M[:2] - Zr[k])
                run += 1
                if run % 8 == 0:  # symmetrise, and test for the steady state (same P twice)
                    P = M[:, :d]
                    M[:, :d] = 0.5 * (P + P.T)
                    post = M[:, :d]
                    if prev_post is not None and \
                            np.abs(post - prev_post).max() <= 1e-15 * np.abs(post).max():
                        steady, K_ss, P_ss = True, K, post.copy()
                        x = M[:, d].copy()
                    prev_post = None
                elif run % 8 == 7:
                    P = M[:, :d]
                    M[:, :d] = 0.5 * (P + P.T)
                    prev_post = M[:, :d].copy()
            else:
                run = 0
                prev_post = None
            out[k] = M
        # covariances of the steady-state frames: the converged one just before each run
        flag = np.r_[False, xs_steady > 0, False]
        starts = np.flatnonzero(~flag[:-1] & flag[1:])
        ends = np.flatnonzero(flag[:-1] & ~flag[1:])
        for st, en in zip(starts, ends):
            out[st:en, :, :d] = out[st - 1, :, :d]
    else:
        HT = np.ascontiguousarray(H_.T)
        for k in range(n):
            M = F_ @ M
            P = M[:, :d] @ FT
            P += Q_
            M[:, :d] = P
            if have[k]:
                PHT = P @ HT
                K = PHT @ _inv_stack(H_ @ PHT + R_)
                G = H_ @ M
                G[:, d] -= Zr[k, :, d]
                M -= K @ G
                P = M[:, :d]
                M[:, :d] = 0.5 * (P + P.T)
            out[k] = M
    Ps = out[:, :, :d]
    return out[:, :, d].copy(), 0.5 * (Ps + np.swapaxes(Ps, 1, 2))


def _left_product(F: np.ndarray, P: np.ndarray, nz: list[np.ndarray] | None = None
                  ) -> np.ndarray:
    """``F @ P`` contracted over the first axis of ``P`` (``(d, ...)``), as a sum of scaled
    slabs over the non-zeros of ``F`` (a transition matrix is sparse). Element-wise passes over
    contiguous slabs; no BLAS call, so no thread start-up per step on small matrices.
    ``nz[i]`` may hold the column indices of row ``i``'s non-zeros (precomputed)."""
    out = np.empty((F.shape[0], *P.shape[1:]), dtype=np.result_type(F, P))
    for i in range(F.shape[0]):
        cols = np.flatnonzero(F[i]) if nz is None else nz[i]
        if cols.size == 0:
            out[i] = 0.0
            continue
        acc = out[i]
        f0 = F[i, cols[0]]
        if f0 == 1.0:
            acc[...] = P[cols[0]]
        else:
            np.multiply(P[cols[0]], f0, out=acc)
        for k in cols[1:]:
            f = F[i, k]
            if f == 1.0:
                acc += P[k]
            else:
                acc += f * P[k]
    return out


def _axis_blocks(F: np.ndarray, H: np.ndarray, Q: np.ndarray, R: np.ndarray, P0: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray, float, np.ndarray] | None:
    """If the model is the same ``o``-state model on each of the ``m`` measured axes, with the
    state laid out ``[p_1..p_m, v_1..v_m, …]`` (as :func:`constant_acceleration_model`), no
    coupling between axes and ``R = r I``, return the per-axis ``(F_a, Q_a, r, P0_a)``.
    Every axis then has the same covariance whenever the measurements of a sequence are missing
    for all axes at once, so one ``o × o`` covariance per sequence suffices."""
    m, d = H.shape
    if d % m or not np.array_equal(H, np.hstack([np.eye(m), np.zeros((m, d - m))])):
        return None
    if not (np.allclose(R, R[0, 0] * np.eye(m), rtol=0, atol=0)):
        return None
    o = d // m
    idx = [a + m * np.arange(o) for a in range(m)]
    blocks = []
    for M in (F, Q, P0):
        b0 = M[np.ix_(idx[0], idx[0])]
        for a in range(m):
            for b in range(m):
                blk = M[np.ix_(idx[a], idx[b])]
                if (a == b and not np.array_equal(blk, b0)) or (a != b and np.any(blk != 0)):
                    return None
        blocks.append(b0.copy())
    return blocks[0], blocks[1], float(R[0, 0]), blocks[2]


def _full_from_axis(Pa: np.ndarray, m: int) -> np.ndarray:
    """``(B, d, d)`` covariances from the per-axis ``(o, o, B)`` block."""
    o, _, B = Pa.shape
    out = np.zeros((B, o * m, o * m))
    blk = Pa.transpose(2, 0, 1)
    for a in range(m):
        ia = a + m * np.arange(o)
        out[:, ia[:, None], ia[None, :]] = blk
    return out


def kalman_filter_batch(zs: Any, F: Any, H: Any, Q: Any, R: Any, x0: Any, P0: Any, *,
                        return_covariances: bool = False
                        ) -> tuple[np.ndarray, np.ndarray]:
    """Run :func:`kalman_filter` on ``B`` independent sequences at once (vectorised over ``B``).

    The covariance recursion does not depend on the measured values, only on which frames have
    a measurement: while every sequence has had the same pattern (e.g. all measured, or a
    shared occlusion) one covariance and gain serve the whole batch; once the patterns differ
    each sequence carries its own covariance. The batch is stored on the last axis (``P`` as
    ``(d, d, B)``), so the prediction is a few scaled additions of ``(d, B)`` slabs over the
    non-zeros of ``F`` and the update
    (for a position-selecting ``H`` with two measurements) element-wise closed forms over
    length-``B`` vectors; a missing measurement sets that sequence's gain to zero (masking, no
    branching per sequence). When the model is the same on every measured axis with no
    coupling (e.g. :func:`constant_acceleration_model` with diagonal, axis-symmetric ``Q``,
    ``P0`` and ``R = r I``) and measurements are missing for all axes at once, the axes share
    one ``o × o`` covariance per sequence (``o`` = states per axis), which is what is carried.

    Parameters
    ----------
    zs
        Measurements ``(B, n, m)``; rows with NaN are prediction-only steps of that sequence.
    F, H, Q, R
        The shared model (see :func:`kalman_filter`).
    x0
        Initial states ``(d,)`` (shared) or ``(B, d)``.
    P0
        Initial covariance ``(d, d)``, shared by all sequences.
    return_covariances
        Return all covariances ``(B, n, d, d)`` (memory!) instead of only the final ones.

    Returns
    -------
    xs : numpy.ndarray
        Filtered states ``(B, n, d)``.
    Ps : numpy.ndarray
        Final covariances ``(B, d, d)`` or all of them ``(B, n, d, d)``.
    """
    z = as_finite_array(zs, "zs", ndim=3, allow_nan=True)
    B, n, m = z.shape
    x0a = as_finite_array(x0, "x0", ndim=(1, 2))
    F_, H_, Q_, R_, _, P0_ = _model(F, H, Q, R, x0a if x0a.ndim == 1 else x0a[0], P0)
    d = F_.shape[0]
    if H_.shape[0] != m:
        raise ValueError(f"zs must have last dimension {H_.shape[0]} to match H, got {m}")
    if x0a.ndim == 2 and x0a.shape != (B, d):
        raise ValueError(f"x0 must have shape ({d},) or ({B}, {d}), got {x0a.shape}")
    # structure-of-arrays layout: the batch is the last (contiguous) axis, so every step is a
    # few element-wise passes over length-B vectors
    x = np.array(np.broadcast_to(x0a, (B, d)).T)              # (d, B)
    xs = np.empty((B, n, d))
    Ps = np.empty((B, n, d, d)) if return_covariances else None
    have = np.all(np.isfinite(z), axis=2)
    zt = z.transpose(1, 2, 0)                  # (n, m, B) view; NaN rows zeroed per step
    FT = np.ascontiguousarray(F_.T)
    HT = np.ascontiguousarray(H_.T)
    selector = m == 2 and np.array_equal(H_, np.hstack([np.eye(2), np.zeros((2, d - 2))]))
    P = P0_.copy()            # shared while every sequence has had the same measurement pattern
    shared = True
    Qb = Q_[:, :, None]
    blocks = _axis_blocks(F_, H_, Q_, R_, P0_)
    axis_mode = False
    if blocks is not None:
        Fa, Qa, r_a, _ = blocks
        o = d // m
        idx = [a + m * np.arange(o) for a in range(m)]
        Qab = Qa[:, :, None]
    nzF = [np.flatnonzero(r) for r in F_]
    nzH = [np.flatnonzero(r) for r in H_]
    if blocks is not None:
        nzA = [np.flatnonzero(r) for r in Fa]
    block = 16                                 # states are written to xs in blocks of steps
    buf = np.empty((block, d, B))
    for k in range(n):
        h = have[:, k]
        zk = np.where(h, zt[k], 0.0)                                  # (m, B)
        if shared and not (h.all() or not h.any()):
            shared = False
            if blocks is not None:
                axis_mode = True
                P = np.array(np.broadcast_to(P[np.ix_(idx[0], idx[0])][:, :, None], (o, o, B)))
            else:
                P = np.array(np.broadcast_to(P[:, :, None], (d, d, B)))      # (d, d, B)
        x = _left_product(F_, x, nzF)
        if axis_mode:
            # one o × o covariance per sequence serves every axis; scalar gain per axis
            A = _left_product(Fa, P, nzA)
            P = _left_product(Fa, A.transpose(1, 0, 2), nzA)
            P += Qab
            c0 = P[:, 0].copy()                                   # (o, B)
            g = np.where(h, 1.0 / (c0[0] + r_a), 0.0)
            K = c0 * g
            P -= K[:, None, :] * c0[None, :, :]
            for a in range(m):
                x[idx[a]] += K * (zk[a] - x[a])
            if k % 8 == 0 or k == n - 1:
                P = 0.5 * (P + P.transpose(1, 0, 2))
        elif shared:
            P = F_ @ P @ FT + Q_
            if h[0]:
                PHT = P @ HT
                K = PHT @ _inv_stack(H_ @ PHT + R_)
                P = P - K @ PHT.T
                P = 0.5 * (P + P.T)
                x += _left_product(K, zk - _left_product(H_, x, nzH))
        else:
            # F P Fᵀ for the whole batch: F (F P)ᵀ (P symmetric), each product a sum of
            # scaled (d, B) slabs over the non-zeros of F
            A = _left_product(F_, P, nzF)
            P = _left_product(F_, A.transpose(1, 0, 2), nzF)
            P += Qb
            if selector:
                c0 = P[:, 0].copy()                           # P Hᵀ, column 0   (d, B)
                c1 = P[:, 1].copy()
                a_ = c0[0] + R_[0, 0]
                b_ = c1[0] + R_[0, 1]
                c_ = c0[1] + R_[1, 0]
                e_ = c1[1] + R_[1, 1]
                idet = np.where(h, 1.0 / (a_ * e_ - b_ * c_), 0.0)   # no measurement: K = 0
                K0 = c0 * (e_ * idet) - c1 * (c_ * idet)
                K1 = c1 * (a_ * idet) - c0 * (b_ * idet)
                P -= K0[:, None, :] * c0[None, :, :]
                P -= K1[:, None, :] * c1[None, :, :]
                i0 = zk[0] - x[0]
                i1 = zk[1] - x[1]
                x += K0 * i0 + K1 * i1
            else:
                Pb = P.transpose(2, 0, 1)
                PHT = Pb @ HT
                K = PHT @ _inv_stack(H_ @ PHT + R_)
                K *= h[:, None, None]
                Pb = Pb - K @ np.swapaxes(PHT, 1, 2)
                P = np.ascontiguousarray(Pb.transpose(1, 2, 0))
                x += np.einsum("bdm,bm->db", K, zk.T - (H_ @ x).T)
            if k % 8 == 0 or k == n - 1:
                P = 0.5 * (P + P.transpose(1, 0, 2))
        buf[k % block] = x
        if k % block == block - 1 or k == n - 1:
            k0 = k - k % block
            xs[:, k0:k + 1] = buf[: k + 1 - k0].transpose(2, 0, 1)
        if Ps is not None:
            Ps[:, k] = P if shared else (_full_from_axis(P, m) if axis_mode
                                         else P.transpose(2, 0, 1))
    if shared:
        Pfinal = np.broadcast_to(P, (B, d, d)).copy()
    elif axis_mode:
        Pfinal = _full_from_axis(P, m)
    else:
        Pfinal = np.ascontiguousarray(P.transpose(2, 0, 1))
    return xs, (Ps if Ps is not None else Pfinal)


class KalmanFilter:
    """Step-wise standard Kalman filter (the same algebra as :func:`kalman_filter`).

    Parameters
    ----------
    F, H, Q, R, x0, P0
        See :func:`kalman_filter`.
    """

    adaptive = False

    def __init__(self, F: Any, H: Any, Q: Any, R: Any, x0: Any, P0: Any) -> None:
        self.F, self.H, self.Q, self.R, self.x, self.P = _model(F, H, Q, R, x0, P0)
        self.x = self.x.copy()
        self.P = self.P.copy()
        self._FT = self.F.T
        self._HT = self.H.T
        self._I = np.eye(self.F.shape[0])
        self.x_prior = self.x.copy()
        self.P_prior = self.P.copy()

    def predict(self) -> np.ndarray:
        """Predict one frame ahead; returns the predicted state ``x⁻``."""
        self.x = self.F @ self.x
        self.P = self.F @ self.P @ self._FT + self.Q
        self.x_prior = self.x
        self.P_prior = self.P
        return self.x

    def innovation_covariance(self) -> np.ndarray:
        """``S = H P⁻ Hᵀ + R`` at the current prediction."""
        return self.H @ self.P_prior @ self._HT + self.R

    def update(self, z: np.ndarray | None, c_img: float = 1.0) -> int:
        """Update with measurement ``z`` (or skip if ``None``); returns the :class:`FilterMode`.

        ``c_img`` is accepted for interface compatibility with :class:`ConfidenceKalmanFilter`
        and ignored.
        """
        if z is None:
            self.P = 0.5 * (self.P + self.P.T)
            return FilterMode.PREDICT
        self._update(np.asarray(z, dtype=float), self.R)
        return FilterMode.UPDATE

    def _update(self, z: np.ndarray, R: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        P = self.P
        PHT = P @ self._HT
        S = self.H @ PHT + R
        K = PHT @ _inv_stack(S)
        e = z - self.H @ self.x
        self.x = self.x + K @ e
        IKH = self._I - K @ self.H
        P = IKH @ P @ IKH.T + K @ R @ K.T
        self.P = 0.5 * (P + P.T)
        return e, K


# --------------------------------------------------------------------------------------------
# Sage–Husa
# --------------------------------------------------------------------------------------------

def sage_husa_weight(k: int, b: float) -> float:
    """Eq. (41) weight ``d_k = (1 − b) / (1 − b^{k+1})`` (``k = 0, 1, …``; ``d_0 = 1``).

    Parameters
    ----------
    k
        Index of the adaptive step (≥ 0).
    b
        Forgetting factor in (0, 1) (the paper uses 0.95–0.99).
    """
    kk = check_int(k, "k", min_value=0)
    bb = check_probability(b, "b", open_low=True, open_high=True)
    return (1.0 - bb) / (1.0 - bb ** (kk + 1))


def _clip_eig(a: np.ndarray, lo: float, hi: float) -> np.ndarray:
    a = 0.5 * (a + a.T)
    if a.shape == (2, 2):  # closed-form eigenvalues: most steps need no change
        tr, det = a[0, 0] + a[1, 1], a[0, 0] * a[1, 1] - a[0, 1] * a[1, 0]
        disc = np.sqrt(max(0.25 * tr * tr - det, 0.0))
        if lo <= 0.5 * tr - disc and 0.5 * tr + disc <= hi:
            return a
    w, v = np.linalg.eigh(a)
    w = np.clip(w, lo, hi)
    return (v * w) @ v.T


def sage_husa_update(R: np.ndarray, Q: np.ndarray, *, e: np.ndarray, K: np.ndarray,
                     H: np.ndarray, F: np.ndarray, P_prior: np.ndarray, P_post: np.ndarray,
                     P_prev: np.ndarray, d: float, safeguard: bool = True,
                     r_bounds: tuple[float, float] = (1e-3, 1e6),
                     q_structure: np.ndarray | None = None,
                     q_bounds: tuple[float, float] = (0.0, np.inf)
                     ) -> tuple[np.ndarray, np.ndarray]:
    """One Sage–Husa step (eq. 41) for ``R`` and ``Q``.

    ``R_k = (1−d) R + d (e eᵀ − H P⁻ Hᵀ)``;
    ``Q_k = (1−d) Q + d (K e eᵀ Kᵀ + P_k − F P_{k−1} Fᵀ)``.

    Parameters
    ----------
    R, Q
        Current estimates.
    e, K, H, F
        Innovation, gain, measurement and transition matrices of this step.
    P_prior, P_post, P_prev
        ``P_{k|k−1}``, ``P_k`` and ``P_{k−1}``.
    d
        Weight ``d_k`` (:func:`sage_husa_weight`).
    safeguard
        Keep the estimates positive definite: ``R`` is symmetrised and its eigenvalues clipped
        to ``r_bounds``; ``Q`` is projected onto ``q_structure`` (a 0/1 diagonal mask, e.g. the
        acceleration states of eq. 35: the mean of the masked diagonal becomes the new ``q_a``,
        clipped to ``q_bounds``) or, without a structure, its eigenvalues are clipped to
        ``q_bounds``. Without the safeguard the raw estimates are returned — they can become
        indefinite (the known weakness of Sage–Husa).
    r_bounds, q_structure, q_bounds
        See ``safeguard``.

    Returns
    -------
    R_new, Q_new : numpy.ndarray
    """
    dd = float(d)
    if not 0.0 < dd <= 1.0:
        raise ValueError(f"d must lie in (0, 1], got {d!r}")
    ee = np.outer(e, e)
    R_new = (1 - dd) * R + dd * (ee - H @ P_prior @ H.T)
    Ke = K @ e
    Q_new = (1 - dd) * Q + dd * (np.outer(Ke, Ke) + P_post - F @ P_prev @ F.T)
    if not safeguard:
        return R_new, Q_new
    R_new = _clip_eig(R_new, *r_bounds)
    if q_structure is not None:
        mask = np.asarray(q_structure, dtype=bool)
        qa = float(np.clip(np.mean(np.diag(Q_new)[mask]), *q_bounds))
        Q_new = np.diag(np.where(mask, qa, 0.0))
    else:
        Q_new = _clip_eig(Q_new, *q_bounds)
    return R_new, Q_new


# --------------------------------------------------------------------------------------------
# the confidence-gated adaptive filter
# --------------------------------------------------------------------------------------------

class FilterMode(IntEnum):
    """What a filter did at one frame (eqs. 44–46)."""

    UPDATE = 0      #: C_k ≥ τ_h: standard update
    INFLATED = 1    #: τ_l ≤ C_k < τ_h: update with R̃ = λ R
    PREDICT = 2     #: C_k < τ_l or no star: prediction only, growing Q


@dataclass(frozen=True)
class ConfidenceConfig:
    """Parameters of the confidence-gated adaptive Kalman filter (eqs. 41–46).

    The paper gives the smoothing constant 0.9, the threshold ratios 0.85 and 0.35 and the
    forgetting-factor range 0.95–0.99; it gives no values for ω, η, γ, λ or the Q growth — ours
    are stated here and varied in the notebook's Explore section.

    Attributes
    ----------
    omega
        ω, weight of the image confidence ``C_img`` in ``C_k`` (eq. 42).
    eta
        η, decay rate of ``C_motion = exp(−η max(0, D_M − γ))`` (eq. 43).
    gamma
        γ, Mahalanobis distance tolerated without penalty.
    lam
        λ ≥ 1, the R inflation of the middle mode.
    smoothing
        ``Ĉ_k = s Ĉ_{k−1} + (1 − s) C_k`` (eq. 44, s = 0.9).
    tau_high, tau_low
        ``τ_h = 0.85 Ĉ_k``, ``τ_l = 0.35 Ĉ_k`` (eqs. 45–46).
    forgetting
        b of the Sage–Husa weight ``d_k`` (eq. 41).
    adaptive_noise
        Run the Sage–Husa estimators of R and Q (eq. 41) on trusted updates.
    safeguard
        Keep the Sage–Husa estimates positive definite (see :func:`sage_husa_update`).
    r_bounds
        Eigenvalue bounds of the adapted R (pixels²).
    q_bounds_ratio
        Bounds of the adapted q_a relative to the initial q_a.
    q_growth
        During prediction-only frames Q is multiplied by ``1 + q_growth · n_missed`` …
    q_growth_max
        … up to this factor.
    """

    omega: float = 0.5
    eta: float = 1.0
    gamma: float = 5.0
    lam: float = 10.0
    smoothing: float = 0.9
    tau_high: float = 0.85
    tau_low: float = 0.35
    forgetting: float = 0.97
    adaptive_noise: bool = True
    safeguard: bool = True
    r_bounds: tuple[float, float] = (0.01, 1.0)
    q_bounds_ratio: tuple[float, float] = (1.0, 16.0)
    q_growth: float = 0.5
    q_growth_max: float = 20.0

    def __post_init__(self) -> None:
        check_probability(self.omega, "omega")
        check_positive(self.eta, "eta", allow_zero=True)
        check_positive(self.gamma, "gamma", allow_zero=True)
        if check_positive(self.lam, "lam") < 1.0:
            raise ValueError(f"lam must be >= 1 (an inflation of R), got {self.lam!r}")
        check_probability(self.smoothing, "smoothing", open_high=True)
        check_probability(self.tau_high, "tau_high")
        check_probability(self.tau_low, "tau_low")
        if self.tau_low > self.tau_high:
            raise ValueError(f"tau_low must be <= tau_high, got {self.tau_low} > {self.tau_high}")
        check_probability(self.forgetting, "forgetting", open_low=True, open_high=True)
        lo, hi = self.r_bounds
        if not 0 < lo <= hi:
            raise ValueError(f"r_bounds must satisfy 0 < lo <= hi, got {self.r_bounds}")
        lo, hi = self.q_bounds_ratio
        if not 0 < lo <= 1 <= hi:
            raise ValueError(f"q_bounds_ratio must satisfy 0 < lo <= 1 <= hi, got "
                             f"{self.q_bounds_ratio}")
        check_positive(self.q_growth, "q_growth", allow_zero=True)
        if check_positive(self.q_growth_max, "q_growth_max") < 1:
            raise ValueError(f"q_growth_max must be >= 1, got {self.q_growth_max}")


class ConfidenceKalmanFilter(KalmanFilter):
    """Confidence-gated adaptive Kalman filter (Sheng 2026, eqs. 41–46).

    At each frame with a candidate measurement ``z``:

    * innovation ``e = z − H x⁻``, ``S = H P⁻ Hᵀ + R``, ``D_M = sqrt(eᵀ S⁻¹ e)``;
    * ``C_motion = exp(−η max(0, D_M − γ))``, ``C_k = ω C_img + (1 − ω) C_motion``;
    * ``Ĉ_k = 0.9 Ĉ_{k−1} + 0.1 C_k`` (``Ĉ_0 = 1``), ``τ_h = 0.85 Ĉ_k``, ``τ_l = 0.35 Ĉ_k``;
    * ``C_k ≥ τ_h``: standard update, then a Sage–Husa step for R and q_a (eq. 41);
      ``τ_l ≤ C_k < τ_h``: update with ``λ R``; ``C_k < τ_l``: prediction only.

    Without a measurement (or with ``C_k < τ_l``) the step is prediction only and the process
    noise of the *next* prediction is multiplied by ``1 + q_growth · n_missed`` (capped), so the
    covariance opens up while the star is hidden. Frames without a measurement leave ``Ĉ``
    unchanged (the paper does not say; updating it with ``C = 0`` would drive the thresholds to
    zero during a long occlusion and accept anything afterwards).

    ``C_img`` is not defined by the paper; the caller supplies it per measurement (our
    definition is in :func:`eotrack.imaging.image_confidence`).

    Parameters
    ----------
    F, H, Q, R, x0, P0
        As for :class:`KalmanFilter`; ``Q`` is the initial (Singer) process noise.
    config
        :class:`ConfidenceConfig`.
    """

    adaptive = True

    def __init__(self, F: Any, H: Any, Q: Any, R: Any, x0: Any, P0: Any,
                 config: ConfidenceConfig | None = None) -> None:
        super().__init__(F, H, Q, R, x0, P0)
        if config is None:
            config = ConfidenceConfig()
        if not isinstance(config, ConfidenceConfig):
            raise TypeError(f"config must be a ConfidenceConfig, got {type(config).__name__}")
        self.config = config
        self.Q_base = self.Q.copy()
        diag = np.diag(self.Q)
        self._q_mask = diag > 0 if np.allclose(self.Q, np.diag(diag)) and np.any(diag > 0) \
            else None
        qa0 = float(np.mean(diag[self._q_mask])) if self._q_mask is not None else 1.0
        lo, hi = config.q_bounds_ratio
        self._q_bounds = (lo * qa0, hi * qa0)
        self.c_smooth = 1.0
        self.n_missed = 0
        self.k_adapt = 0
        self.last_confidence = np.nan
        self.last_mahalanobis = np.nan
        self._P_prev = self.P.copy()

    def predict(self) -> np.ndarray:
        """Predict, with the process noise grown by the number of frames already missed."""
        cfg = self.config
        grow = min(1.0 + cfg.q_growth * self.n_missed, cfg.q_growth_max)
        self._P_prev = self.P
        self.x = self.F @ self.x
        self.P = self.F @ self.P @ self._FT + grow * self.Q_base
        self.x_prior = self.x
        self.P_prior = self.P
        return self.x

    def confidence(self, z: np.ndarray, c_img: float = 1.0) -> tuple[float, float]:
        """``(C_k, D_M)`` of a candidate measurement at the current prediction (eqs. 42–43)."""
        cfg = self.config
        e = np.asarray(z, dtype=float) - self.H @ self.x_prior
        S = self.innovation_covariance()
        d2 = float(e @ _inv_stack(S) @ e)
        dm = float(np.sqrt(max(d2, 0.0))) if np.isfinite(d2) else np.inf
        c_motion = float(np.exp(-cfg.eta * max(0.0, dm - cfg.gamma)))
        return cfg.omega * float(c_img) + (1 - cfg.omega) * c_motion, dm

    def update(self, z: np.ndarray | None, c_img: float = 1.0) -> int:
        """Gate and update with ``z`` (``None``: no star this frame); returns the mode."""
        cfg = self.config
        if z is None:
            self.n_missed += 1
            self.last_confidence = np.nan
            self.P = 0.5 * (self.P + self.P.T)
            return FilterMode.PREDICT
        z = np.asarray(z, dtype=float)
        c, dm = self.confidence(z, c_img)
        self.last_confidence, self.last_mahalanobis = c, dm
        self.c_smooth = cfg.smoothing * self.c_smooth + (1 - cfg.smoothing) * c
        tau_h = cfg.tau_high * self.c_smooth
        tau_l = cfg.tau_low * self.c_smooth
        if c >= tau_h:
            P_prior = self.P
            e, K = self._update(z, self.R)
            if cfg.adaptive_noise:
                d = sage_husa_weight(self.k_adapt, cfg.forgetting)
                self.R, Qn = sage_husa_update(
                    self.R, self.Q_base, e=e, K=K, H=self.H, F=self.F, P_prior=P_prior,
                    P_post=self.P, P_prev=self._P_prev, d=d, safeguard=cfg.safeguard,
                    r_bounds=cfg.r_bounds, q_structure=self._q_mask, q_bounds=self._q_bounds)
                self.Q_base = Qn
                self.k_adapt += 1
            self.n_missed = 0
            return FilterMode.UPDATE
        if c >= tau_l:
            self._update(z, cfg.lam * self.R)
            self.n_missed = 0
            return FilterMode.INFLATED
        self.n_missed += 1
        self.P = 0.5 * (self.P + self.P.T)
        return FilterMode.PREDICT


# --------------------------------------------------------------------------------------------
# nearest-neighbour tracking driver
# --------------------------------------------------------------------------------------------

@dataclass
class TrackResult:
    """Output of :func:`track_nearest`.

    Attributes
    ----------
    xs
        Filtered states ``(n, d)``.
    Ps
        Filtered covariances ``(n, d, d)``.
    modes
        :class:`FilterMode` per frame ``(n,)``.
    z
        The measurement associated at each frame ``(n, 2)`` (NaN where none).
    confidence
        ``C_k`` per frame (NaN where none or for the standard filter).
    innovations, S
        Innovation ``(n, m)`` and its covariance ``(n, m, m)`` at each frame (NaN without a
        measurement).
    """

    xs: np.ndarray
    Ps: np.ndarray
    modes: np.ndarray
    z: np.ndarray
    confidence: np.ndarray
    innovations: np.ndarray
    S: np.ndarray
    extra: dict[str, Any] = field(default_factory=dict)


def track_nearest(filt: KalmanFilter, detections: Sequence[np.ndarray], *,
                  gate_px: float = 10.0, gate_sigma: float | None = 4.0,
                  gate_max_px: float = 30.0, hold_after: int | None = 5,
                  c_img: Sequence[np.ndarray] | None = None) -> TrackResult:
    """Track one star through per-frame detections with nearest-neighbour association.

    At each frame the filter predicts; the detection nearest to the predicted position within
    the gate is handed to ``filt.update`` with its image confidence. The gate radius is
    ``min(gate_max_px, max(gate_px, gate_sigma · sqrt(λ_max(S))))`` (pixels; ``S`` the
    innovation covariance), so it opens while the star is hidden and the prediction becomes
    uncertain, but never so far that a coasting track grabs any spot in the image; no
    detection in the gate means a prediction-only frame. A sequence in which the star is never
    detected is a valid input: the result is pure prediction from ``x0`` (all modes
    ``PREDICT``, covariances growing).

    Parameters
    ----------
    filt
        A :class:`KalmanFilter` or :class:`ConfidenceKalmanFilter` (state; modified in place).
    detections
        One ``(n_i, 2)`` array of centroids (x, y) per frame.
    gate_px
        Smallest association radius (pixels, > 0).
    gate_sigma
        Gate in standard deviations of the innovation (``None``: fixed radius ``gate_px``).
    gate_max_px
        Largest association radius (pixels, ≥ ``gate_px``).
    hold_after
        Track maintenance (not in the paper): after this many consecutive frames without an
        associated measurement the velocity and acceleration states are set to zero, so the
        estimate holds the last position instead of running away along an extrapolated
        parabola; the star is re-acquired when it reappears inside the (grown) gate.
        ``None`` disables it (pure prediction for ever).
    c_img
        One ``(n_i,)`` array of image confidences per frame (default: all 1).

    Returns
    -------
    TrackResult
    """
    if not isinstance(filt, KalmanFilter):
        raise TypeError(f"filt must be a KalmanFilter, got {type(filt).__name__}")
    gate0 = check_positive(gate_px, "gate_px")
    gs = None if gate_sigma is None else check_positive(gate_sigma, "gate_sigma")
    gmax = check_positive(gate_max_px, "gate_max_px")
    hold = None if hold_after is None else check_int(hold_after, "hold_after", min_value=1)
    missed = 0
    if gmax < gate0:
        raise ValueError(f"gate_max_px must be >= gate_px, got {gate_max_px} < {gate_px}")
    n = len(detections)
    if c_img is not None and len(c_img) != n:
        raise ValueError(f"c_img must have one entry per frame ({n}), got {len(c_img)}")
    d = filt.F.shape[0]
    m = filt.H.shape[0]
    xs = np.empty((n, d))
    Ps = np.empty((n, d, d))
    modes = np.empty(n, dtype=np.int8)
    zs = np.full((n, m), np.nan)
    conf = np.full(n, np.nan)
    innov = np.full((n, m), np.nan)
    Ss = np.full((n, m, m), np.nan)
    H = filt.H
    for k in range(n):
        xp = filt.predict()
        det = detections[k]
        z = None
        ci = 1.0
        if len(det):
            pp = H @ xp
            dist2 = np.sum((det - pp) ** 2, axis=1)
            j = int(np.argmin(dist2))
            S = filt.innovation_covariance()
            g2 = gate0 * gate0
            if gs is not None:
                g2 = min(max(g2, gs * gs * float(np.linalg.eigvalsh(S)[-1])), gmax * gmax)
            if dist2[j] <= g2:
                z = det[j]
                ci = float(c_img[k][j]) if c_img is not None else 1.0
                zs[k] = z
                innov[k] = z - pp
                Ss[k] = S
        modes[k] = filt.update(z, ci)
        missed = missed + 1 if modes[k] == FilterMode.PREDICT else 0
        if hold is not None and missed >= hold:
            filt.x = filt.x.copy()
            filt.x[m:] = 0.0
        if filt.adaptive and z is not None:
            conf[k] = filt.last_confidence
        xs[k] = filt.x
        Ps[k] = filt.P
    return TrackResult(xs, Ps, modes, zs, conf, innov, Ss)


# --------------------------------------------------------------------------------------------
# consistency
# --------------------------------------------------------------------------------------------

def nees(errors: Any, P: Any) -> np.ndarray:
    """Normalised estimation error squared ``εᵀ P⁻¹ ε`` per row.

    Parameters
    ----------
    errors
        Estimation errors ``(n, d)`` (NaN rows give NaN).
    P
        Covariances ``(n, d, d)``.
    """
    err = as_finite_array(errors, "errors", ndim=2, allow_nan=True)
    cov = as_finite_array(P, "P", ndim=3, allow_nan=True)
    if cov.shape != (len(err), err.shape[1], err.shape[1]):
        raise ValueError(f"P must have shape ({len(err)}, {err.shape[1]}, {err.shape[1]}) to "
                         f"match errors, got {cov.shape}")
    ok = np.all(np.isfinite(err), axis=1) & np.all(np.isfinite(cov), axis=(1, 2))
    out = np.full(len(err), np.nan)
    if np.any(ok):
        sol = np.linalg.solve(cov[ok], err[ok][..., None])[..., 0]
        out[ok] = np.sum(err[ok] * sol, axis=1)
    return out


def nis(innovations: Any, S: Any) -> np.ndarray:
    """Normalised innovation squared ``eᵀ S⁻¹ e`` per row (NaN rows give NaN)."""
    return nees(innovations, S)
