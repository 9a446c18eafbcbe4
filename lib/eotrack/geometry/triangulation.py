"""Triangulation of lines of sight (Huang et al., §3) and the combination of pairwise estimates.

Two rays give the target as the midpoint of their common perpendicular; N rays give the
least-squares point (minimum sum of squared perpendicular distances). With N sensors there are
C(N, 2) pairwise estimates; the paper rejects any estimate with a coordinate more than 3
standard deviations from the mean and averages the rest — a rule that can never reject among
n ≤ 10 estimates, because the largest possible z-score of n samples (sample standard deviation)
is (n − 1)/√n. :func:`combine_estimates` offers that rule and two that can reject.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from eotrack.validation import as_finite_array, check_choice, check_positive

__all__ = [
    "CombinedEstimate",
    "closest_points_two_rays",
    "combine_estimates",
    "max_z_score",
    "triangulate_rays",
    "triangulate_two_rays",
]


def _unit(d: np.ndarray, name: str) -> np.ndarray:
    n = np.linalg.norm(d, axis=-1, keepdims=True)
    if np.any(n == 0):
        raise ValueError(f"{name} contains a zero direction vector")
    return d / n


def closest_points_two_rays(o1, d1, o2, d2) -> tuple[np.ndarray, np.ndarray]:
    """The two ends of the common perpendicular of two rays (vectorised).

    Parameters
    ----------
    o1, o2
        Ray origins ``(..., 3)``.
    d1, d2
        Directions ``(..., 3)`` (any length > 0).

    Returns
    -------
    (q1, q2) : numpy.ndarray
        ``q1`` on ray 1 and ``q2`` on ray 2, each ``(..., 3)``; ``|q2 − q1|`` is the miss
        distance and their midpoint the two-ray triangulation. The rays are treated as full
        lines: for diverging rays (a false pair) the closest points lie *behind* an origin,
        ``(q1 − o1)·d1 < 0`` — check that sign (or the depth in the cameras, as
        :func:`eotrack.geometry.three_view_check` does) before trusting the point.

    Raises
    ------
    ValueError
        Parallel rays (no unique closest points), bad shapes or zero directions.
    """
    a1 = as_finite_array(o1, "o1")
    a2 = as_finite_array(o2, "o2")
    u = _unit(as_finite_array(d1, "d1"), "d1")
    w = _unit(as_finite_array(d2, "d2"), "d2")
    for name, arr in (("o1", a1), ("o2", a2), ("d1", u), ("d2", w)):
        if arr.shape[-1:] != (3,):
            raise ValueError(f"{name} must end in 3 coordinates, got shape {arr.shape}")
    b = np.einsum("...i,...i->...", u, w)
    den = 1.0 - b * b
    if np.any(den < 1e-14):
        raise ValueError("the two rays are parallel: no unique closest point")
    r = a2 - a1
    e = np.einsum("...i,...i->...", u, r)
    f = np.einsum("...i,...i->...", w, r)
    s = (e - b * f) / den
    t = (b * e - f) / den
    return a1 + s[..., None] * u, a2 + t[..., None] * w


def triangulate_two_rays(o1, d1, o2, d2, *, return_gap: bool = False):
    """Closest point of two rays: midpoint of their common perpendicular (vectorised).

    Parameters
    ----------
    o1, o2
        Ray origins ``(..., 3)`` (sensor positions).
    d1, d2
        Directions ``(..., 3)`` (any length > 0).
    return_gap
        Also return the length of the common perpendicular (miss distance).

    Returns
    -------
    numpy.ndarray
        Points ``(..., 3)`` (and gaps ``(...)``). As in :func:`closest_points_two_rays`, the
        rays are full lines: diverging rays give a point behind the origins, with a small gap.

    Raises
    ------
    ValueError
        Parallel rays (no unique closest point).
    """
    p1, p2 = closest_points_two_rays(o1, d1, o2, d2)
    mid = 0.5 * (p1 + p2)
    if return_gap:
        return mid, np.linalg.norm(p1 - p2, axis=-1)
    return mid


def triangulate_rays(origins, directions) -> np.ndarray:
    """Least-squares intersection of N ≥ 2 rays: ``argmin Σ |(I − dᵢdᵢᵀ)(x − oᵢ)|²``.

    Parameters
    ----------
    origins, directions
        ``(n, 3)`` each.

    Raises
    ------
    ValueError
        Fewer than 2 rays or all rays parallel.
    """
    o = as_finite_array(origins, "origins", ndim=2)
    d = as_finite_array(directions, "directions", ndim=2)
    if o.shape != d.shape or o.shape[1:] != (3,):
        raise ValueError(f"origins and directions must both have shape (n, 3), got {o.shape} "
                         f"and {d.shape}")
    if len(o) < 2:
        raise ValueError(f"origins needs at least 2 rays, got {len(o)}")
    d = _unit(d, "directions")
    proj = np.eye(3) - d[:, :, None] * d[:, None, :]
    a = proj.sum(0)
    b = np.einsum("nij,nj->i", proj, o)
    if np.linalg.cond(a) > 1e12:
        raise ValueError("the rays are (nearly) parallel: no unique least-squares point")
    return np.linalg.solve(a, b)


def max_z_score(n: int) -> float:
    """Largest possible |x − mean| / s among n samples (s with ddof = 1): (n − 1)/√n."""
    if n < 2:
        raise ValueError(f"n must be >= 2, got {n}")
    return (n - 1) / np.sqrt(n)


@dataclass(frozen=True)
class CombinedEstimate:
    """Result of :func:`combine_estimates`: the kept mean and which estimates were kept."""

    position: np.ndarray
    kept: np.ndarray


def combine_estimates(estimates, *, rule: str = "paper", k: float = 3.0,
                      gate_km: float | None = None, scale_floor_km: float = 0.5
                      ) -> CombinedEstimate:
    """Average pairwise position estimates after rejecting outliers.

    Parameters
    ----------
    estimates
        ``(n, 3)`` positions (km), n ≥ 1.
    rule
        ``"paper"``: reject an estimate if any coordinate is more than ``k`` sample standard
        deviations from the mean (cannot reject anything for n ≤ 10 when k = 3);
        ``"mad"``: reject if any coordinate is more than ``k`` robust standard deviations
        (1.4826 · MAD, at least ``scale_floor_km``) from the coordinate-wise median;
        ``"gate"``: reject if the distance to the coordinate-wise median exceeds ``gate_km``
        (a bound from the error budget).
        Both robust rules need n ≥ 3 to reject *one* estimate: ``"mad"`` keeps everything for
        n < 3, and for n = 2 the median is the midpoint, so ``"gate"`` keeps both or rejects
        both.
    k
        Multiplier (> 0).
    gate_km
        Distance gate for ``rule="gate"`` (> 0).
    scale_floor_km
        Smallest robust scale used by ``"mad"`` (> 0).

    Raises
    ------
    ValueError
        Bad input, or no estimate survives the rule (e.g. two estimates farther apart than
        ``2 · gate_km``): there is then no position to return.
    """
    est = as_finite_array(estimates, "estimates", ndim=2)
    if est.shape[1:] != (3,) or len(est) == 0:
        raise ValueError(f"estimates must have shape (n, 3) with n >= 1, got {est.shape}")
    check_choice(rule, "rule", ("paper", "mad", "gate"))
    kk = check_positive(k, "k")
    n = len(est)
    keep = np.ones(n, bool)
    if rule == "paper" and n >= 2:
        sd = est.std(0, ddof=1)
        z = np.abs(est - est.mean(0)) / np.where(sd > 0, sd, np.inf)
        keep = ~np.any(z > kk, axis=1)
    elif rule == "mad" and n >= 3:
        med = np.median(est, 0)
        scale = np.maximum(1.4826 * np.median(np.abs(est - med), 0),
                           check_positive(scale_floor_km, "scale_floor_km"))
        keep = ~np.any(np.abs(est - med) > kk * scale, axis=1)
    elif rule == "gate":
        if gate_km is None:
            raise ValueError("gate_km is required for rule='gate'")
        g = check_positive(gate_km, "gate_km")
        keep = np.linalg.norm(est - np.median(est, 0), axis=1) <= g
    if not keep.any():
        raise ValueError(f"no estimate survives rule={rule!r} (all {n} rejected)"
                         + (f"; gate_km={gate_km!r} is smaller than their spread"
                            if rule == "gate" else ""))
    return CombinedEstimate(est[keep].mean(0), keep)
