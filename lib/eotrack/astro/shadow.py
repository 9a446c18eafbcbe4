"""Earth's shadow: is a satellite sunlit, in penumbra or in umbra?

Conical shadow model (Montenbruck & Gill, *Satellite Orbits*, §3.4.2): with the apparent
angular radii of the Sun ``a = asin(R_sun/|s − r|)`` and of the Earth ``b = asin(R_earth/|r|)``
seen from the satellite, and ``c`` the angle between the directions to the Earth's and the Sun's
centres, the satellite is in umbra when ``c < b − a``, in penumbra when ``|a − b| < c < a + b``,
sunlit otherwise.
"""

from __future__ import annotations

import astropy.units as u
import numpy as np
from astropy.coordinates import get_body
from astropy.time import Time

from eotrack.validation import as_finite_array

__all__ = ["PENUMBRA", "R_EARTH_KM", "R_SUN_KM", "SUNLIT", "UMBRA", "earth_shadow",
           "sun_position_gcrs"]

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
