"""Earth's shadow: is a satellite sunlit, in penumbra or in umbra?

Conical shadow model (Montenbruck & Gill, *Satellite Orbits*, §3.4.2): with the apparent
angular radii of the Sun ``a = asin(R_sun/|s − r|)`` and of the Earth ``b = asin(R_earth/|r|)``
seen from the satellite, and ``c`` the angle between the directions to the Earth's and the Sun's
centres, the satellite is in umbra when ``c < b − a``, in penumbra when ``|a − b| < c < a + b``,
sunlit otherwise.

For scanning weeks of orbit quickly, :func:`sun_position_approx` gives the Sun from the
low-precision formulae of the Astronomical Almanac (≈ 0.01°, mean equator and equinox of date,
which TEME matches to within nutation), and :func:`shadow_intervals` turns a sequence of shadow
states into the index ranges of the separate shadow passes.
"""

from __future__ import annotations

import astropy.units as u
import numpy as np
from astropy.coordinates import get_body
from astropy.time import Time

from eotrack.validation import as_finite_array

__all__ = ["AU_KM", "PENUMBRA", "R_EARTH_KM", "R_SUN_KM", "SUNLIT", "UMBRA", "earth_shadow",
           "shadow_intervals", "sun_position_approx", "sun_position_gcrs"]

AU_KM = 149_597_870.7

R_EARTH_KM = 6378.137
R_SUN_KM = 695_700.0
SUNLIT, PENUMBRA, UMBRA = 0, 1, 2


def sun_position_gcrs(times: Time) -> np.ndarray:
    """Geocentric GCRS position of the Sun (km), ``(n, 3)``, from astropy's built-in ephemeris."""
    if not isinstance(times, Time):
        raise TypeError(f"times must be an astropy Time, got {type(times).__name__}")
    t = times if times.ndim else times.reshape((1,))
    sun = get_body("sun", t)
    return sun.cartesian.xyz.to_value(u.km).T


def sun_position_approx(jd_ut1: np.ndarray) -> np.ndarray:
    """Geocentric Sun position (km), ``(n, 3)``, low precision (≈ 0.01°), equator of date.

    Astronomical Almanac low-precision formulae (Vallado, *Fundamentals of Astrodynamics*,
    Alg. 29). Fast and vectorised: for scanning long spans for shadow passes; use
    :func:`sun_position_gcrs` where accuracy matters.

    Parameters
    ----------
    jd_ut1
        Julian dates (UT1 ≈ UTC is good enough here), any shape; flattened.
    """
    jd = np.ravel(as_finite_array(jd_ut1, "jd_ut1"))
    tc = (jd - 2451545.0) / 36525.0
    lam_m = np.radians((280.460 + 36000.771 * tc) % 360.0)
    m = np.radians((357.5291092 + 35999.05034 * tc) % 360.0)
    lam = lam_m + np.radians(1.914666471 * np.sin(m) + 0.019994643 * np.sin(2 * m))
    eps = np.radians(23.439291 - 0.0130042 * tc)
    r = (1.000140612 - 0.016708617 * np.cos(m) - 0.000139589 * np.cos(2 * m)) * AU_KM
    return np.stack([r * np.cos(lam), r * np.cos(eps) * np.sin(lam),
                     r * np.sin(eps) * np.sin(lam)], axis=1)


def shadow_intervals(states: np.ndarray, min_state: int = PENUMBRA) -> np.ndarray:
    """Index ranges ``[start, stop)`` of the contiguous runs with ``states >= min_state``.

    Parameters
    ----------
    states
        Shadow states ``(n,)`` from :func:`earth_shadow`.
    min_state
        ``PENUMBRA`` (any shadow, default) or ``UMBRA``.

    Returns
    -------
    numpy.ndarray
        Integer array ``(k, 2)``; ``k = 0`` when the satellite is never in shadow.
    """
    st = np.asarray(states)
    if st.ndim != 1:
        raise ValueError(f"states must be 1-D, got shape {st.shape}")
    if min_state not in (PENUMBRA, UMBRA):
        raise ValueError(f"min_state must be PENUMBRA ({PENUMBRA}) or UMBRA ({UMBRA}), "
                         f"got {min_state!r}")
    on = np.r_[False, st >= min_state, False].astype(np.int8)
    d = np.diff(on)
    return np.stack([np.flatnonzero(d == 1), np.flatnonzero(d == -1)], axis=1)


def earth_shadow(r_sat_km: np.ndarray, r_sun_km: np.ndarray) -> np.ndarray:
    """Shadow state of satellites (``SUNLIT`` 0, ``PENUMBRA`` 1, ``UMBRA`` 2).

    Parameters
    ----------
    r_sat_km, r_sun_km
        Geocentric positions ``(n, 3)`` (or ``(3,)``) of the satellite and the Sun, same frame.

    Returns
    -------
    numpy.ndarray
        Integer states, shape ``(n,)``.
    """
    r = np.atleast_2d(as_finite_array(r_sat_km, "r_sat_km", ndim=(1, 2)))
    s = np.atleast_2d(as_finite_array(r_sun_km, "r_sun_km", ndim=(1, 2)))
    if r.shape[1] != 3 or s.shape[1] != 3:
        raise ValueError(f"positions must have 3 components, got {r.shape} and {s.shape}")
    if len(s) == 1:
        s = np.repeat(s, len(r), axis=0)
    if len(s) != len(r):
        raise ValueError(f"r_sat_km and r_sun_km lengths differ: {len(r)} vs {len(s)}")
    rn = np.linalg.norm(r, axis=1)
    if np.any(rn <= R_EARTH_KM):
        raise ValueError("r_sat_km has positions inside the Earth")
    to_sun = s - r
    dn = np.linalg.norm(to_sun, axis=1)
    a = np.arcsin(R_SUN_KM / dn)
    b = np.arcsin(R_EARTH_KM / rn)
    cosc = np.einsum("ij,ij->i", -r, to_sun) / (rn * dn)
    c = np.arccos(np.clip(cosc, -1.0, 1.0))
    state = np.full(len(r), SUNLIT, dtype=int)
    state[(c < a + b) & (c > np.abs(a - b))] = PENUMBRA
    state[c < b - a] = UMBRA
    return state
