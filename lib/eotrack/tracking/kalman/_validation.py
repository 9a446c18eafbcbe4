"""Validation and small linear-algebra helpers shared by the Kalman modules (private)."""

from __future__ import annotations

from typing import Any

import numpy as np

from eotrack.validation import as_finite_array

__all__ = ["is_positive_definite"]


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

