"""Motion models and process noise: constant velocity / acceleration, white acceleration,
Singer (Sheng 2026, eqs. 30, 33–35)."""

from __future__ import annotations

import numpy as np

from eotrack.validation import check_int, check_positive

__all__ = ["constant_acceleration_model", "constant_velocity_model",
           "singer_acceleration_variance", "singer_process_noise", "white_acceleration_noise"]


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

