"""The standard Kalman filter over whole measurement sequences: one sequence
(:func:`kalman_filter`, optionally with per-step ``F``/``Q`` for irregular time steps) and many
independent sequences at once (:func:`kalman_filter_batch`)."""

from __future__ import annotations

from typing import Any

import numpy as np

from eotrack.validation import as_finite_array

from ._validation import _check_zs, _inv_stack, _model

__all__ = ["kalman_filter", "kalman_filter_batch"]


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
        For irregular time steps ``F`` and/or ``Q`` may be stacks ``(n, d, d)``, one per
        step (step ``k`` predicts with ``F[k]``, ``Q[k]``; e.g. built from the ``dt_k``).
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
    if np.ndim(F) == 3 or np.ndim(Q) == 3:
        return _kalman_filter_steps(zs, F, H, Q, R, x0, P0)
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


def _kalman_filter_steps(zs: Any, F: Any, H: Any, Q: Any, R: Any, x0: Any, P0: Any
                         ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`kalman_filter` with per-step ``F`` and/or ``Q`` stacks (irregular time steps)."""
    from .filters import KalmanFilter

    Fs = as_finite_array(F, "F", ndim=(2, 3))
    Qs = as_finite_array(Q, "Q", ndim=(2, 3))
    F0 = Fs[0] if Fs.ndim == 3 else Fs
    Q0 = Qs[0] if Qs.ndim == 3 else Qs
    kf = KalmanFilter(F0, H, Q0, R, x0, P0)
    z = _check_zs(zs, kf.H.shape[0], kf.H)
    n, d = len(z), kf.F.shape[0]
    for name, a in (("F", Fs), ("Q", Qs)):
        if a.ndim == 3 and a.shape != (n, d, d):
            raise ValueError(f"{name} as a per-step stack must have shape ({n}, {d}, {d}) "
                             f"(one per measurement row), got {a.shape}")
    xs = np.empty((n, d))
    Ps = np.empty((n, d, d))
    for k in range(n):
        kf.predict(F=Fs[k] if Fs.ndim == 3 else None, Q=Qs[k] if Qs.ndim == 3 else None)
        kf.update(z[k])
        xs[k], Ps[k] = kf.x, kf.P
    return xs, Ps


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

