"""Consistency statistics (Bar-Shalom, Li & Kirubarajan 2001, §5.4): NEES and NIS."""

from __future__ import annotations

from typing import Any

import numpy as np

from eotrack.validation import as_finite_array

__all__ = ["nees", "nis"]


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
