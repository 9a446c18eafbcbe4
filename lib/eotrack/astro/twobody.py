"""Two-body (Keplerian) orbits: classical elements → state, propagation, GEO placement, Earth
blocking of a line of sight.

Enough for a scenario defined at one instant by its orbital elements (no perturbations). Frame:
whatever inertial frame the elements refer to (J2000/GCRS in this project); km, km/s, degrees.
"""

from __future__ import annotations

import numpy as np

from eotrack.validation import as_finite_array, check_positive

__all__ = [
    "EARTH_RADIUS_KM",
    "GEO_RADIUS_KM",
    "MU_EARTH_KM3_S2",
    "elements_to_state",
    "geo_positions",
    "line_of_sight_clear",
    "place_on_shell",
    "propagate_elements",
    "solve_kepler",
]

MU_EARTH_KM3_S2 = 398600.4418
EARTH_RADIUS_KM = 6378.137
GEO_RADIUS_KM = 42164.17


def _broadcast(*arrays: np.ndarray) -> list[np.ndarray]:
    try:
        return list(np.broadcast_arrays(*arrays))
    except ValueError as exc:
        raise ValueError(f"orbital elements must broadcast to one shape: {exc}") from None


def solve_kepler(mean_anomaly_rad: np.ndarray | float, e: np.ndarray | float, *,
                 tol: float = 1e-13, max_iter: int = 50) -> np.ndarray:
    """Eccentric anomaly ``E`` from ``M = E − e sin E`` (Newton, vectorised; 0 ≤ e < 1)."""
    m = as_finite_array(mean_anomaly_rad, "mean_anomaly_rad")
    ecc = as_finite_array(e, "e")
    if np.any((ecc < 0) | (ecc >= 1)):
        raise ValueError("e must lie in [0, 1) (elliptic orbits only)")
    m, ecc = _broadcast(m, ecc)
    big = np.where(ecc > 0.8, np.pi, m)
    ea = np.array(big, dtype=float)
    for _ in range(max_iter):
        f = ea - ecc * np.sin(ea) - m
        step = f / (1.0 - ecc * np.cos(ea))
        ea = ea - step
        if np.all(np.abs(step) < tol):
            break
    return ea


def elements_to_state(a_km, e, i_deg, raan_deg, argp_deg, nu_deg, *,
                      mu: float = MU_EARTH_KM3_S2) -> tuple[np.ndarray, np.ndarray]:
    """Position and velocity from classical orbital elements (vectorised).

    Parameters
    ----------
    a_km
        Semi-major axis (km, > 0).
    e
        Eccentricity, 0 ≤ e < 1 (dimensionless).
    i_deg, raan_deg, argp_deg, nu_deg
        Inclination, right ascension of the ascending node, argument of perigee, true anomaly
        (degrees).
    mu
        Gravitational parameter (km³/s²).

    Returns
    -------
    r_km, v_km_s : numpy.ndarray
        Shape ``(..., 3)`` in the elements' inertial frame.
    """
    a = as_finite_array(a_km, "a_km")
    ecc = as_finite_array(e, "e")
    if np.any(a <= 0):
        raise ValueError("a_km must be > 0")
    if np.any((ecc < 0) | (ecc >= 1)):
        raise ValueError("e must lie in [0, 1) (elliptic orbits only)")
    inc, raan, argp, nu = (np.radians(as_finite_array(x, n)) for x, n in
                           ((i_deg, "i_deg"), (raan_deg, "raan_deg"), (argp_deg, "argp_deg"),
                            (nu_deg, "nu_deg")))
    check_positive(mu, "mu")
    a, ecc, inc, raan, argp, nu = _broadcast(a, ecc, inc, raan, argp, nu)
    p = a * (1 - ecc**2)
    r = p / (1 + ecc * np.cos(nu))
    r_pf = np.stack([r * np.cos(nu), r * np.sin(nu), np.zeros_like(r)], -1)
    v_pf = np.sqrt(mu / p)[..., None] * np.stack([-np.sin(nu), ecc + np.cos(nu),
                                                  np.zeros_like(r)], -1)
    cO, sO, ci, si, cw, sw = (np.cos(raan), np.sin(raan), np.cos(inc), np.sin(inc),
                              np.cos(argp), np.sin(argp))
    q = np.stack([
        np.stack([cO * cw - sO * sw * ci, -cO * sw - sO * cw * ci, sO * si], -1),
        np.stack([sO * cw + cO * sw * ci, -sO * sw + cO * cw * ci, -cO * si], -1),
        np.stack([sw * si, cw * si, ci], -1),
    ], -2)  # perifocal -> inertial, (..., 3, 3)
    return np.einsum("...ij,...j->...i", q, r_pf), np.einsum("...ij,...j->...i", q, v_pf)


def propagate_elements(a_km, e, i_deg, raan_deg, argp_deg, nu_deg, dt_s, *,
                       mu: float = MU_EARTH_KM3_S2) -> tuple[np.ndarray, np.ndarray]:
    """State ``dt_s`` seconds after the epoch of the elements (two-body, vectorised over dt).

    Returns
    -------
    r_km, v_km_s : numpy.ndarray
        Shape ``broadcast(elements, dt_s) + (3,)``.
    """
    a = as_finite_array(a_km, "a_km")
    ecc = as_finite_array(e, "e")
    if np.any(a <= 0):
        raise ValueError("a_km must be > 0")
    if np.any((ecc < 0) | (ecc >= 1)):
        raise ValueError("e must lie in [0, 1) (elliptic orbits only)")
    dt = as_finite_array(dt_s, "dt_s")
    nu0 = np.radians(as_finite_array(nu_deg, "nu_deg"))
    ea0 = 2 * np.arctan2(np.sqrt(1 - ecc) * np.sin(nu0 / 2), np.sqrt(1 + ecc) * np.cos(nu0 / 2))
    m0 = ea0 - ecc * np.sin(ea0)
    n = np.sqrt(check_positive(mu, "mu") / a**3)
    ea = solve_kepler(m0 + n * dt, ecc)
    nu = 2 * np.arctan2(np.sqrt(1 + ecc) * np.sin(ea / 2), np.sqrt(1 - ecc) * np.cos(ea / 2))
    return elements_to_state(a, ecc, i_deg, raan_deg, argp_deg, np.degrees(nu), mu=mu)


def geo_positions(ra_deg, dec_deg, radius_km: float = GEO_RADIUS_KM) -> np.ndarray:
    """Geocentric positions at ``radius_km`` in the direction (RA, Dec), shape ``(..., 3)`` km.

    A geostationary object seen from the geocentre; a small declination is an inclined GEO
    object near its node crossing.
    """
    ra = np.radians(as_finite_array(ra_deg, "ra_deg"))
    dec = as_finite_array(dec_deg, "dec_deg")
    if np.any(np.abs(dec) > 90):
        raise ValueError("dec_deg must lie in [-90, 90]")
    dec = np.radians(dec)
    rad = check_positive(radius_km, "radius_km")
    ra, dec = _broadcast(ra, dec)
    return rad * np.stack([np.cos(dec) * np.cos(ra), np.cos(dec) * np.sin(ra), np.sin(dec)], -1)


def place_on_shell(origin_km, directions, radius_km: float = GEO_RADIUS_KM) -> np.ndarray:
    """Where lines of sight from ``origin_km`` leave a geocentric sphere of ``radius_km``.

    GEO object placement from a sensor's lines of sight: the far intersection of each ray
    ``origin + s·d`` (s > 0) with the sphere. The origin must lie inside the sphere.

    Parameters
    ----------
    origin_km
        Sensor position ``(3,)`` (km, geocentric).
    directions
        Directions ``(n, 3)`` (any length > 0).
    radius_km
        Shell radius (default: the geostationary radius).

    Returns
    -------
    numpy.ndarray
        ``(n, 3)`` positions on the shell.
    """
    o = as_finite_array(origin_km, "origin_km", shape=(3,))
    d = as_finite_array(directions, "directions", ndim=2)
    if d.shape[1] != 3:
        raise ValueError(f"directions must have shape (n, 3), got {d.shape}")
    n = np.linalg.norm(d, axis=1, keepdims=True)
    if np.any(n == 0):
        raise ValueError("directions contains a zero vector")
    d = d / n
    rad = check_positive(radius_km, "radius_km")
    c = o @ o - rad**2
    if c >= 0:
        raise ValueError(f"origin_km must lie inside the shell of radius {rad} km")
    b = d @ o
    return o + (-b + np.sqrt(b * b - c))[:, None] * d


def line_of_sight_clear(observer_km, target_km, *, body_radius_km: float = EARTH_RADIUS_KM,
                        margin_km: float = 100.0) -> np.ndarray:
    """Whether the segment observer → target misses a sphere of radius body + margin.

    Parameters
    ----------
    observer_km, target_km
        Positions ``(..., 3)`` (broadcast against each other), geocentric km.
    body_radius_km
        Sphere radius (Earth's equatorial radius by default).
    margin_km
        Extra height (atmosphere, grazing rays), ≥ 0.

    Returns
    -------
    numpy.ndarray of bool
        ``True`` where the line of sight is clear.
    """
    o = as_finite_array(observer_km, "observer_km")
    t = as_finite_array(target_km, "target_km")
    if o.shape[-1:] != (3,) or t.shape[-1:] != (3,):
        raise ValueError(f"observer_km and target_km must end in 3 coordinates, got {o.shape} "
                         f"and {t.shape}")
    rad = check_positive(body_radius_km, "body_radius_km") + check_positive(
        margin_km, "margin_km", allow_zero=True)
    d = t - o
    dd = np.einsum("...i,...i->...", d, d)
    if np.any(dd == 0):
        raise ValueError("observer_km and target_km coincide somewhere: no line of sight")
    s = np.clip(-np.einsum("...i,...i->...", o, d) / dd, 0.0, 1.0)
    closest = o + s[..., None] * d
    return np.linalg.norm(closest, axis=-1) > rad
