"""Robust estimation: minimal-sample counts, bounded losses, a vectorised RANSAC engine, models."""

from __future__ import annotations

from .losses import (
    LOSSES,
    get_loss,
    loss_weights,
    msac_loss,
    sinusoidal_loss,
    sinusoidal_loss_as_printed,
    zero_one_loss,
)
from .mestimators import M_ESTIMATORS, irls_linear, m_weights
from .models import (
    SIDEREAL_RATE_RAD_S,
    FreeSinusoid,
    LinearModel,
    Polynomial,
    SinusoidDrift,
    fit_free_sinusoid,
    fit_linear,
    predict_linear,
)
from .ransac import (
    REFITS,
    WEIGHTED_REFITS,
    RansacResult,
    draw_samples,
    ransac,
    ransac_linear,
    wransac_linear,
)
from .sampling import min_samples, min_samples_real, success_probability

__all__ = [
    "LOSSES",
    "M_ESTIMATORS",
    "REFITS",
    "SIDEREAL_RATE_RAD_S",
    "WEIGHTED_REFITS",
    "FreeSinusoid",
    "LinearModel",
    "Polynomial",
    "RansacResult",
    "SinusoidDrift",
    "draw_samples",
    "fit_free_sinusoid",
    "fit_linear",
    "get_loss",
    "irls_linear",
    "loss_weights",
    "m_weights",
    "min_samples",
    "min_samples_real",
    "msac_loss",
    "predict_linear",
    "ransac",
    "ransac_linear",
    "sinusoidal_loss",
    "sinusoidal_loss_as_printed",
    "success_probability",
    "wransac_linear",
    "zero_one_loss",
]
