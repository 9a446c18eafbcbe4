"""Bounded loss functions for robust model scoring (eqs. 4–6 of Yan et al. 2019).

All losses take residuals ``e`` (any shape) and the inlier threshold ``t > 0`` and return an
array of the same shape with values in [0, 1], equal to 1 for ``|e| > t``.

- ``zero_one_loss`` — classic RANSAC, eq. (4): 0 inside the threshold, 1 outside.
- ``msac_loss`` — eq. (5) as the paper prints it (``|e|/t``, ``form="linear"``) or the usual
  MSAC truncated quadratic (``e²/t²``, ``form="squared"``).
- ``sinusoidal_loss`` — the corrected eq. (6): ``½ − ½ cos(π e / t)``; 0 at 0, 1 at ``t``, zero
  slope at both ends, below the linear MSAC loss for ``|e| < t/2`` and above it beyond.
- ``sinusoidal_loss_as_printed`` — eq. (6) exactly as printed, ``½ cos(e/(2t)) + ½``, kept to
  show why it cannot be what was meant (it is largest at ``e = 0`` and jumps at ``t``).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from eotrack.validation import as_finite_array, check_choice, check_positive

__all__ = [
    "LOSSES",
    "get_loss",
    "loss_weights",
    "msac_loss",
    "sinusoidal_loss",
    "sinusoidal_loss_as_printed",
    "zero_one_loss",
]


def _prep(e: np.ndarray, t: float) -> tuple[np.ndarray, float]:
    return np.abs(as_finite_array(e, "e")), check_positive(t, "t")


def zero_one_loss(e: np.ndarray, t: float) -> np.ndarray:
    """Eq. (4): ``0`` if ``|e| ≤ t`` else ``1``."""
    a, t = _prep(e, t)
    return (a > t).astype(float)


def msac_loss(e: np.ndarray, t: float, form: str = "linear") -> np.ndarray:
    """Eq. (5): ``|e|/t`` (paper, ``form="linear"``) or ``e²/t²`` (``"squared"``), 1 beyond ``t``."""
    a, t = _prep(e, t)
    check_choice(form, "form", ("linear", "squared"))
    r = a / t if form == "linear" else (a / t) ** 2
    return np.where(a <= t, r, 1.0)


def sinusoidal_loss(e: np.ndarray, t: float) -> np.ndarray:
    """Corrected eq. (6): ``½ − ½ cos(π e / t)`` for ``|e| ≤ t``, 1 beyond."""
    a, t = _prep(e, t)
    return np.where(a <= t, 0.5 - 0.5 * np.cos(np.pi * a / t), 1.0)


def sinusoidal_loss_as_printed(e: np.ndarray, t: float) -> np.ndarray:
    """Eq. (6) as printed: ``½ cos(e/(2t)) + ½`` for ``|e| ≤ t``, 1 beyond (an erratum)."""
    a, t = _prep(e, t)
    return np.where(a <= t, 0.5 * np.cos(a / (2 * t)) + 0.5, 1.0)


def _msac_squared(e: np.ndarray, t: float) -> np.ndarray:
    return msac_loss(e, t, form="squared")


#: Loss name → function ``(e, t) -> loss``.
LOSSES: dict[str, Callable[[np.ndarray, float], np.ndarray]] = {
    "zero_one": zero_one_loss,
    "msac": msac_loss,
    "msac_squared": _msac_squared,
    "sinusoidal": sinusoidal_loss,
    "sinusoidal_as_printed": sinusoidal_loss_as_printed,
}


def get_loss(name: str) -> Callable[[np.ndarray, float], np.ndarray]:
    """Look up a loss by name (keys of :data:`LOSSES`)."""
    return LOSSES[check_choice(name, "loss", tuple(LOSSES))]


def loss_weights(e: np.ndarray, t: float, loss: str = "sinusoidal") -> np.ndarray:
    """Refit weights ``w = 1 − L(e)`` (1 for a perfect fit, 0 at and beyond the threshold).

    The paper defines the WRANSAC weights "from the loss value" without a formula; this is the
    project's reading (see the wransac digest).
    """
    return 1.0 - get_loss(loss)(e, t)
