"""How many random minimal samples RANSAC needs (eqs. 1–2 of Yan et al. 2019).

With a fraction ``ε`` of outliers, a minimal sample of ``m`` points is outlier-free with
probability ``(1 − ε)^m``; ``U`` independent samples contain at least one clean sample with
probability ``P = 1 − (1 − (1 − ε)^m)^U`` (eq. 1), so

    U = log(1 − P) / log(1 − (1 − ε)^m)        (eq. 2, rounded up).
"""

from __future__ import annotations

import math

import numpy as np

from eotrack.validation import check_int, check_probability

__all__ = ["min_samples", "min_samples_real", "success_probability"]


def _check(confidence: float, outlier_ratio: float, sample_size: int) -> tuple[float, float, int]:
    p = check_probability(confidence, "confidence", open_low=True, open_high=True)
    e = check_probability(outlier_ratio, "outlier_ratio", open_high=True)
    m = check_int(sample_size, "sample_size", min_value=1)
    return p, e, m


def min_samples_real(confidence: float, outlier_ratio: float, sample_size: int) -> float:
    """Unrounded ``U`` of eq. (2).

    Parameters
    ----------
    confidence
        Required probability ``P`` in (0, 1) of drawing at least one outlier-free sample.
    outlier_ratio
        Outlier fraction ``ε`` in [0, 1).
    sample_size
        Minimal sample size ``m`` (≥ 1).

    Returns
    -------
    float
        ``log(1 − P) / log(1 − (1 − ε)^m)``; 1.0 for ``ε = 0`` (any single sample is clean).
    """
    p, e, m = _check(confidence, outlier_ratio, sample_size)
    clean = (1.0 - e) ** m
    if clean >= 1.0:
        return 1.0
    return math.log1p(-p) / math.log1p(-clean)


def min_samples(confidence: float, outlier_ratio: float, sample_size: int) -> int:
    """Minimum number of random minimal samples, eq. (2) rounded up (at least 1).

    Examples
    --------
    >>> min_samples(0.995, 0.03, 4)   # the paper's setting
    3
    """
    return max(1, math.ceil(min_samples_real(confidence, outlier_ratio, sample_size) - 1e-12))


def success_probability(n_samples: int | np.ndarray, outlier_ratio: float,
                        sample_size: int) -> float | np.ndarray:
    """Probability that ``n_samples`` minimal samples include a clean one (eq. 1)."""
    e = check_probability(outlier_ratio, "outlier_ratio", open_high=True)
    m = check_int(sample_size, "sample_size", min_value=1)
    u = np.asarray(n_samples)
    if np.any(u < 0):
        raise ValueError("n_samples must be >= 0")
    return 1.0 - (1.0 - (1.0 - e) ** m) ** u
