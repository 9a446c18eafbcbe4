"""Does a Monte Carlo agree with a closed form? Binomial confidence intervals, vectorised.

A Monte Carlo estimate of a probability is a count: ``k`` successes in ``n`` independent
trials. It *agrees* with a closed-form value ``p`` when ``p`` lies inside a confidence interval
for the binomial proportion ``k / n``. Two intervals are offered:

* ``"wilson"`` — the Wilson score interval (Wilson 1927): closed form, never outside [0, 1],
  close to nominal coverage even for ``k = 0`` or ``k = n``;
* ``"clopper-pearson"`` — the exact interval from beta quantiles (Clopper & Pearson 1934):
  coverage at least nominal for every ``p``, a little wider.

Both agree with :meth:`scipy.stats.binomtest(...).proportion_ci` (methods ``"wilson"`` and
``"exact"``) but take arrays, so a whole figure's worth of points is checked in one call.

**Many points at once.** Checking ``m`` points, each at confidence ``c``, a correct formula
still falls outside some interval with probability up to ``m (1 − c)`` (the Bonferroni bound;
it needs no independence between the points, so it holds for curves estimated from the same
samples). :func:`mc_agreement` reports that bound (``familywise_bound``) and, with
``familywise=True``, widens each interval to confidence ``1 − (1 − c)/m`` so that *all* points
are covered with probability at least ``c``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.stats import beta, norm

__all__ = ["Agreement", "binomial_interval", "mc_agreement"]

_METHODS = ("wilson", "clopper-pearson")


def _confidence(confidence: Any) -> float:
    if isinstance(confidence, bool) or not isinstance(confidence, int | float | np.floating):
        raise TypeError(f"confidence must be a real number in (0, 1), got "
                        f"{type(confidence).__name__}")
    c = float(confidence)
    if not 0.0 < c < 1.0:
        raise ValueError(f"confidence must lie strictly between 0 and 1 (e.g. 0.999), got {c!r}")
    return c


def _method(method: Any) -> str:
    if not isinstance(method, str) or method.lower() not in _METHODS:
        raise ValueError(f"method must be one of {_METHODS}, got {method!r}")
    return method.lower()


def _counts(k: Any, n: Any) -> tuple[np.ndarray, np.ndarray]:
    """Validated, broadcast success counts ``k`` and trial counts ``n`` (as floats)."""
    out = []
    for name, v in (("k", k), ("n", n)):
        if isinstance(v, bool) or (isinstance(v, np.ndarray) and v.dtype == bool):
            raise TypeError(f"{name} must be an integer count (or array of them), got bool")
        try:
            a = np.asarray(v, dtype=float)
        except (TypeError, ValueError):
            raise TypeError(f"{name} must be an integer count (or array of them), got "
                            f"{type(v).__name__}") from None
        if not np.all(np.isfinite(a)):
            raise ValueError(f"{name} must be finite, got {v!r}")
        if np.any(a != np.round(a)):
            raise ValueError(f"{name} must hold whole numbers (counts), got {v!r}; "
                             "for an estimated proportion p pass k = round(p * n)")
        out.append(a)
    ka, na = np.broadcast_arrays(*out)
    if np.any(na < 1):
        raise ValueError(f"n must be >= 1 trial, got {na[na < 1].ravel()[0]:g}")
    if np.any(ka < 0) or np.any(ka > na):
        raise ValueError("k must satisfy 0 <= k <= n (successes among n trials)")
    return ka, na


def binomial_interval(k: Any, n: Any, *, confidence: float = 0.999,
                      method: str = "wilson") -> tuple[np.ndarray, np.ndarray]:
    """Two-sided confidence interval of a binomial proportion ``k / n`` (vectorised).

    Parameters
    ----------
    k
        Successes (non-negative whole numbers, ``k ≤ n``; scalar or array).
    n
        Trials (≥ 1; broadcast against ``k``).
    confidence
        Two-sided confidence level in (0, 1), e.g. 0.999.
    method
        ``"wilson"`` (score interval) or ``"clopper-pearson"`` (exact, from beta quantiles).

    Returns
    -------
    lo, hi : numpy.ndarray
        Interval bounds in [0, 1], shape of ``k`` and ``n`` broadcast.

    Raises
    ------
    ValueError
        ``k`` outside ``[0, n]``, non-integer counts, ``n < 1``, ``confidence`` outside (0, 1),
        an unknown ``method``.
    TypeError
        Non-numeric or boolean counts or confidence.

    Examples
    --------
    >>> lo, hi = binomial_interval(0, 1_000_000, confidence=0.999)
    >>> float(lo), round(float(hi), 8)
    (0.0, 1.083e-05)
    """
    c = _confidence(confidence)
    m = _method(method)
    ka, na = _counts(k, n)
    alpha = 1.0 - c
    if m == "wilson":
        z = float(norm.isf(alpha / 2))
        p = ka / na
        den = 1.0 + z * z / na
        centre = (p + z * z / (2 * na)) / den
        half = z * np.sqrt(p * (1 - p) / na + z * z / (4 * na * na)) / den
        lo, hi = np.clip(centre - half, 0.0, 1.0), np.clip(centre + half, 0.0, 1.0)
        # exact ends: the score interval touches 0 (1) exactly when k = 0 (k = n)
        lo = np.where(ka == 0, 0.0, lo)
        hi = np.where(ka == na, 1.0, hi)
    else:
        with np.errstate(invalid="ignore"):
            lo = np.where(ka == 0, 0.0, beta.ppf(alpha / 2, np.maximum(ka, 1), na - ka + 1))
            hi = np.where(ka == na, 1.0, beta.ppf(1 - alpha / 2, ka + 1, np.maximum(na - ka, 1)))
    return np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)


@dataclass(frozen=True)
class Agreement:
    """Outcome of :func:`mc_agreement`; truthy when every formula value is inside its interval.

    Attributes
    ----------
    inside
        Boolean array: the formula value lies in the interval of its estimate.
    lo, hi
        The intervals (per-point confidence ``point_confidence``).
    confidence
        The confidence asked for.
    point_confidence
        The confidence of each interval (``confidence``, or ``1 − (1 − confidence)/m`` with
        ``familywise=True``).
    familywise_bound
        Bonferroni bound on the chance that a *correct* formula lands outside at least one of
        the ``m`` intervals: ``min(1, m (1 − point_confidence))``.
    method
        The interval used.
    """

    inside: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    confidence: float
    point_confidence: float
    familywise_bound: float
    method: str

    @property
    def all_inside(self) -> bool:
        """Every formula value lies inside its interval."""
        return bool(np.all(self.inside))

    @property
    def fraction_inside(self) -> float:
        """Fraction of the points whose formula value lies inside the interval."""
        return float(np.mean(self.inside)) if self.inside.size else 1.0

    @property
    def n_points(self) -> int:
        """Number of points checked (``m``)."""
        return int(self.inside.size)

    @property
    def n_outside(self) -> int:
        """Number of points whose formula value lies outside its interval."""
        return int(self.inside.size - np.count_nonzero(self.inside))

    def __bool__(self) -> bool:
        return self.all_inside

    def summary(self) -> str:
        """One line, e.g. ``'36/36 points inside their 99.9 % Wilson intervals (...)'``."""
        name = "Wilson" if self.method == "wilson" else "Clopper–Pearson"
        return (f"{self.n_points - self.n_outside}/{self.n_points} points inside their "
                f"{100 * self.point_confidence:.4g} % {name} intervals (chance that a correct "
                f"formula leaves at least one: <= {self.familywise_bound:.2g})")


def mc_agreement(k: Any, n: Any, expected: Any, *, confidence: float = 0.999,
                 method: str = "wilson", familywise: bool = False) -> Agreement:
    """Check closed-form probabilities against Monte Carlo counts, point by point.

    Parameters
    ----------
    k
        Monte Carlo successes per point (whole numbers; for a stored proportion ``p̂`` pass
        ``numpy.rint(p̂ * n)``).
    n
        Trials per point (≥ 1; broadcast against ``k``).
    expected
        The closed-form probabilities in [0, 1] (broadcast against ``k``).
    confidence
        Confidence of each interval, or of the whole family with ``familywise=True``.
    method
        ``"wilson"`` or ``"clopper-pearson"`` (see :func:`binomial_interval`).
    familywise
        Bonferroni-correct: each of the ``m`` intervals at ``1 − (1 − confidence)/m``, so that a
        correct formula lies inside *all* of them with probability at least ``confidence``.

    Returns
    -------
    Agreement
        Truthy when every point agrees; see its ``summary()``.

    Raises
    ------
    ValueError, TypeError
        Bad counts, confidence or method (as :func:`binomial_interval`); ``expected`` not in
        [0, 1] or not broadcastable to ``k``.
    """
    c = _confidence(confidence)
    if not isinstance(familywise, bool):
        raise TypeError(f"familywise must be a bool, got {type(familywise).__name__}")
    ka, na = _counts(k, n)
    if isinstance(expected, bool):
        raise TypeError("expected must be probabilities in [0, 1], got bool")
    try:
        p = np.asarray(expected, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"expected must be probabilities in [0, 1], got "
                        f"{type(expected).__name__}") from None
    if not np.all(np.isfinite(p)) or np.any((p < 0) | (p > 1)):
        raise ValueError("expected must hold probabilities in [0, 1]")
    try:
        ka, na, p = np.broadcast_arrays(ka, na, p)
    except ValueError:
        raise ValueError(f"expected (shape {np.shape(expected)}) does not broadcast against k "
                         f"(shape {np.shape(k)})") from None
    m = max(1, ka.size)
    pc = 1.0 - (1.0 - c) / m if familywise else c
    lo, hi = binomial_interval(ka, na, confidence=pc, method=method)
    tol = 1e-12  # round-off of the closed forms
    inside = (p >= lo - tol) & (p <= hi + tol)
    return Agreement(inside=inside, lo=lo, hi=hi, confidence=c, point_confidence=pc,
                     familywise_bound=float(min(1.0, m * (1.0 - pc))), method=_method(method))
