"""Real orbits from two-line elements, offline.

The ``sgp4`` package ships Vallado's verification TLEs (``sgp4/SGP4-VER.TLE``): real satellites
from the public catalogue, among them geostationary ones (24208 ITALSAT 2, 25954 AMC-4,
26900 INTELSAT 902, 28626 XM-3). Lines in that file carry verification time ranges after
column 69; they are cut off here.
"""

from __future__ import annotations

from functools import lru_cache
from importlib import resources
from itertools import pairwise

import numpy as np
from astropy.time import Time
from sgp4.api import Satrec

from eotrack.validation import check_int

__all__ = ["GEO_NORAD_IDS", "propagate_teme", "satellite", "tle_epoch", "verification_tles"]

#: Geostationary objects among the verification TLEs.
GEO_NORAD_IDS: tuple[int, ...] = (24208, 25954, 26900, 28626)


@lru_cache(maxsize=1)
def verification_tles() -> dict[int, tuple[str, str]]:
    """All TLEs shipped with ``sgp4``: NORAD id → (line 1, line 2), each cut to 69 characters."""
    text = resources.files("sgp4").joinpath("SGP4-VER.TLE").read_text()
    lines = [ln.rstrip() for ln in text.splitlines()]
    out: dict[int, tuple[str, str]] = {}
    for a, b in pairwise(lines):
        if a.startswith("1 ") and b.startswith("2 ") and a[2:7] == b[2:7]:
            out[int(a[2:7])] = (a[:69], b[:69])
    return out


def satellite(norad_id: int) -> Satrec:
    """The SGP4 satellite record of a verification TLE.

    Raises
    ------
    ValueError
        If ``norad_id`` is not among the shipped TLEs.
    """
    nid = check_int(norad_id, "norad_id", min_value=1)
    tles = verification_tles()
    if nid not in tles:
        raise ValueError(f"norad_id {nid} is not among the TLEs shipped with sgp4; known "
                         f"geostationary ids: {list(GEO_NORAD_IDS)}; all: {sorted(tles)}")
    return Satrec.twoline2rv(*tles[nid])


def tle_epoch(sat: Satrec) -> Time:
    """Epoch of a TLE as an astropy ``Time`` (UTC)."""
    return Time(sat.jdsatepoch, sat.jdsatepochF, format="jd", scale="utc")


def propagate_teme(sat: Satrec, times: Time) -> tuple[np.ndarray, np.ndarray]:
    """Propagate with SGP4.

    Parameters
    ----------
    sat
        Satellite record.
    times
        Times (astropy ``Time``, any scale; UTC is used as SGP4 expects).

    Returns
    -------
    r_km, v_km_s
        TEME position (km) and velocity (km/s), each ``(n, 3)``.
    """
    if not isinstance(sat, Satrec):
        raise TypeError(f"sat must be an sgp4 Satrec, got {type(sat).__name__}")
    if not isinstance(times, Time):
        raise TypeError(f"times must be an astropy Time, got {type(times).__name__}")
    tu = times.utc
    jd1 = np.atleast_1d(tu.jd1)
    jd2 = np.atleast_1d(tu.jd2)
    err, r, v = sat.sgp4_array(jd1.astype(float), jd2.astype(float))
    if np.any(err):
        raise ValueError(f"SGP4 failed (error codes {sorted(set(err[err != 0].tolist()))}) — "
                         "times too far from the TLE epoch?")
    return np.asarray(r), np.asarray(v)
