"""Trajectory models for one angular coordinate as a function of time.

Linear-in-parameters models (used inside RANSAC, where a minimal sample is solved exactly):

- :class:`SinusoidDrift` — ``y = a sin(ω τ) + b cos(ω τ) + c + d τ/τ_s`` with known ``ω`` (the
  sidereal rate by default), ``τ = t − t_ref``. Four parameters, so ``m = 4`` (the project's
  reading of the paper's unstated model; see the wransac digest).
- :class:`Polynomial` — ``y = Σ c_k (τ/τ_s)^k``.

Nonlinear model (fitted to all data by least squares, the paper's "standard sine"):

- :func:`fit_free_sinusoid` — ``y = A sin(ω' τ + φ) + c`` with free ``ω'``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np
from scipy.optimize import least_squares

from eotrack.validation import as_finite_array, check_int, check_positive, check_same_length

__all__ = [
    "SIDEREAL_RATE_RAD_S",
    "FreeSinusoid",
    "LinearModel",
    "Polynomial",
    "SinusoidDrift",
    "fit_free_sinusoid",
    "fit_linear",
    "predict_linear",
]

#: Earth's sidereal rotation rate (rad/s), IERS conventional value.
SIDEREAL_RATE_RAD_S = 7.2921150e-5


@runtime_checkable
class LinearModel(Protocol):
    """A model ``y = A(x) θ`` linear in its parameters ``θ``."""

    @property
    def n_params(self) -> int:
        """Number of parameters (= minimal sample size)."""
        ...

    def design(self, x: np.ndarray) -> np.ndarray:
        """Design matrix ``A(x)``, shape ``x.shape + (n_params,)``."""
        ...


@dataclass(frozen=True)
class SinusoidDrift:
    """``y = a sin(ωτ) + b cos(ωτ) + c + d·τ/τ_s``, ``τ = t − t_ref``.

    Parameters
    ----------
    omega_rad_s
        Known angular frequency ``ω`` (default: Earth's sidereal rate).
    t_ref_s
        Time origin (centre the data window for a well-conditioned design).
    time_scale_s
        Scale ``τ_s`` of the drift column (conditioning only; predictions do not depend on it).
    """

    omega_rad_s: float = SIDEREAL_RATE_RAD_S
    t_ref_s: float = 0.0
    time_scale_s: float = 3600.0

    def __post_init__(self) -> None:
        check_positive(self.omega_rad_s, "omega_rad_s")
        check_positive(self.time_scale_s, "time_scale_s")
        if not np.isfinite(self.t_ref_s):
            raise ValueError(f"t_ref_s must be finite, got {self.t_ref_s}")

    @property
    def n_params(self) -> int:
        """4."""
        return 4

    def design(self, x: np.ndarray) -> np.ndarray:
        """Columns ``sin ωτ, cos ωτ, 1, τ/τ_s``."""
        tau = np.asarray(x, dtype=float) - self.t_ref_s
        wt = self.omega_rad_s * tau
        return np.stack([np.sin(wt), np.cos(wt), np.ones_like(tau), tau / self.time_scale_s], -1)


@dataclass(frozen=True)
class Polynomial:
    """``y = Σ_k c_k (τ/τ_s)^k`` for ``k = 0..degree``, ``τ = t − t_ref``."""

    degree: int = 3
    t_ref_s: float = 0.0
    time_scale_s: float = 3600.0

    def __post_init__(self) -> None:
        check_int(self.degree, "degree", min_value=0, max_value=12)
        check_positive(self.time_scale_s, "time_scale_s")

    @property
    def n_params(self) -> int:
        """``degree + 1``."""
        return self.degree + 1

    def design(self, x: np.ndarray) -> np.ndarray:
        """Columns ``1, s, s², …`` with ``s = τ/τ_s``."""
        s = (np.asarray(x, dtype=float) - self.t_ref_s) / self.time_scale_s
        return s[..., None] ** np.arange(self.degree + 1)


def _check_model(model: LinearModel) -> LinearModel:
    # duck typing (a runtime Protocol isinstance check costs ~0.3 ms per call)
    if not (callable(getattr(model, "design", None)) and hasattr(model, "n_params")):
        raise TypeError("model must be a linear model with n_params and design(x) "
                        f"(e.g. SinusoidDrift, Polynomial), got {type(model).__name__}")
    return model


def fit_linear(model: LinearModel, x: np.ndarray, y: np.ndarray,
               weights: np.ndarray | None = None) -> np.ndarray:
    """(Weighted) least-squares parameters of a linear model.

    Parameters
    ----------
    model
        A :class:`LinearModel`.
    x, y
        Data, shape ``(n,)`` each, ``n ≥ model.n_params``.
    weights
        Non-negative weights ``(n,)``; minimises ``Σ w_i (y_i − A_i θ)²``.

    Returns
    -------
    numpy.ndarray
        Parameters ``(n_params,)``.
    """
    _check_model(model)
    xx = as_finite_array(x, "x", ndim=1)
    yy = as_finite_array(y, "y", ndim=1)
    check_same_length("x", xx, "y", yy)
    a = model.design(xx)
    if weights is not None:
        w = as_finite_array(weights, "weights", ndim=1)
        check_same_length("x", xx, "weights", w)
        if np.any(w < 0):
            raise ValueError("weights must be >= 0")
        sw = np.sqrt(w)
        a, yy = a * sw[:, None], yy * sw
        n_eff = int(np.count_nonzero(w))
    else:
        n_eff = len(xx)
    if n_eff < model.n_params:
        raise ValueError(f"need at least {model.n_params} points with non-zero weight to fit, "
                         f"got {n_eff}")
    theta, *_ = np.linalg.lstsq(a, yy, rcond=None)
    return theta


def _wls(a: np.ndarray, y: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Weighted least squares on a prepared design (no validation; hot loops only)."""
    sw = np.sqrt(w)
    theta, *_ = np.linalg.lstsq(a * sw[:, None], y * sw, rcond=None)
    return theta


def predict_linear(model: LinearModel, theta: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Model values ``A(x) θ``; ``theta`` may be a batch ``(k, n_params)`` → ``(k, n)``."""
    _check_model(model)
    th = as_finite_array(theta, "theta", ndim=(1, 2))
    if th.shape[-1] != model.n_params:
        raise ValueError(f"theta must have {model.n_params} parameters, got {th.shape}")
    a = model.design(as_finite_array(x, "x", ndim=1))
    return th @ a.T


@dataclass(frozen=True)
class FreeSinusoid:
    """Fitted ``y = A sin(ω' τ + φ) + c`` (``τ = t − t_ref``)."""

    amplitude: float
    omega_rad_s: float
    phase_rad: float
    offset: float
    t_ref_s: float

    def __call__(self, t: np.ndarray) -> np.ndarray:
        """Evaluate at times ``t`` (s)."""
        tau = np.asarray(t, dtype=float) - self.t_ref_s
        return self.amplitude * np.sin(self.omega_rad_s * tau + self.phase_rad) + self.offset


def fit_free_sinusoid(t: np.ndarray, y: np.ndarray, *,
                      omega0_rad_s: float = SIDEREAL_RATE_RAD_S) -> FreeSinusoid:
    """Nonlinear least-squares fit of ``A sin(ω' τ + φ) + c`` with free ``ω'`` to all data.

    The start values come from the linear fit with ``ω' = ω0``. No outlier handling: this is the
    paper's "standard sine function" baseline.
    """
    tt = as_finite_array(t, "t", ndim=1)
    yy = as_finite_array(y, "y", ndim=1)
    check_same_length("t", tt, "y", yy)
    if len(tt) < 4:
        raise ValueError(f"need at least 4 points to fit a free sinusoid, got {len(tt)}")
    w0 = check_positive(omega0_rad_s, "omega0_rad_s")
    t_ref = float(np.mean(tt))
    tau = tt - t_ref
    a0 = np.stack([np.sin(w0 * tau), np.cos(w0 * tau), np.ones_like(tau)], 1)
    (s, c, off), *_ = np.linalg.lstsq(a0, yy, rcond=None)
    amp0 = float(np.hypot(s, c)) or float(np.std(yy)) or 1.0
    p0 = np.array([amp0, 1.0, np.arctan2(c, s), off])  # omega as a multiple of w0

    def resid(p: np.ndarray) -> np.ndarray:
        return p[0] * np.sin(p[1] * w0 * tau + p[2]) + p[3] - yy

    def jac(p: np.ndarray) -> np.ndarray:
        arg = p[1] * w0 * tau + p[2]
        c = p[0] * np.cos(arg)
        return np.stack([np.sin(arg), c * w0 * tau, c, np.ones_like(tau)], axis=1)

    sol = least_squares(resid, p0, jac=jac, method="lm", x_scale="jac")
    amp, k, ph, c0 = sol.x
    return FreeSinusoid(float(amp), float(k * w0), float(ph), float(c0), t_ref)
