"""Frames: TEME → GCRS / ITRS, and topocentric RA/Dec and Az/El of a satellite from a station.

Topocentric directions are computed geometrically: (satellite − station) in the same geocentric
frame, then turned into angles. Passing the station through astropy's GCRS ``obsgeoloc`` instead
would add an aberration artefact of about 2″ for a geostationary object — too much at the 3″
noise level of the papers reproduced here.
"""

from __future__ import annotations

from dataclasses import dataclass

import astropy.units as u
import numpy as np
from astropy.coordinates import GCRS, ITRS, TEME, CartesianRepresentation, EarthLocation
from astropy.time import Time

from eotrack.validation import as_finite_array

__all__ = [
    "Station",
    "azel_from_enu",
    "radec_from_vector",
    "teme_to_gcrs",
    "teme_to_itrs",
    "topocentric_azel",
    "topocentric_radec",
]


@dataclass(frozen=True)
class Station:
    """A ground station (geodetic WGS84).

    Parameters
    ----------
    lat_deg, lon_deg
        Geodetic latitude (−90…90) and east longitude (degrees).
    height_m
        Height above the ellipsoid.
    name
        Label.
    """

    lat_deg: float
    lon_deg: float
    height_m: float = 0.0
    name: str = ""

    def __post_init__(self) -> None:
        if not -90.0 <= float(self.lat_deg) <= 90.0:
            raise ValueError(f"lat_deg must lie in [-90, 90], got {self.lat_deg}")
        if not np.isfinite(self.lon_deg):
            raise ValueError(f"lon_deg must be finite, got {self.lon_deg}")
        if not np.isfinite(self.height_m):
            raise ValueError(f"height_m must be finite, got {self.height_m}")

    @property
    def location(self) -> EarthLocation:
        """The astropy ``EarthLocation``."""
        return EarthLocation.from_geodetic(self.lon_deg * u.deg, self.lat_deg * u.deg,
                                           self.height_m * u.m)

    def gcrs_km(self, times: Time) -> np.ndarray:
        """Geocentric GCRS position of the station (km), ``(n, 3)``."""
        pos, _ = self.location.get_gcrs_posvel(times)
        return np.atleast_2d(pos.xyz.to_value(u.km).T)

    def itrs_km(self) -> np.ndarray:
        """Earth-fixed position (km), ``(3,)``."""
        return np.array(self.location.to_value(u.km).tolist(), dtype=float)


def _check_times(times: Time, n: int, name: str = "times") -> Time:
    if not isinstance(times, Time):
        raise TypeError(f"{name} must be an astropy Time, got {type(times).__name__}")
    t = times if times.ndim else times.reshape((1,))
    if len(t) != n:
        raise ValueError(f"{name} has {len(t)} entries but the positions have {n}")
    return t


def teme_to_gcrs(r_teme_km: np.ndarray, times: Time) -> np.ndarray:
    """Rotate TEME positions (km, ``(n, 3)``) to geocentric GCRS (km)."""
    r = as_finite_array(r_teme_km, "r_teme_km", ndim=2, shape=(None, 3))
    t = _check_times(times, len(r))
    teme = TEME(CartesianRepresentation(r.T * u.km), obstime=t)
    return teme.transform_to(GCRS(obstime=t)).cartesian.xyz.to_value(u.km).T


def teme_to_itrs(r_teme_km: np.ndarray, times: Time) -> np.ndarray:
    """Rotate TEME positions (km, ``(n, 3)``) to Earth-fixed ITRS (km)."""
    r = as_finite_array(r_teme_km, "r_teme_km", ndim=2, shape=(None, 3))
    t = _check_times(times, len(r))
    teme = TEME(CartesianRepresentation(r.T * u.km), obstime=t)
    return teme.transform_to(ITRS(obstime=t)).cartesian.xyz.to_value(u.km).T


def radec_from_vector(vec: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Right ascension in [0, 360) and declination (degrees) of direction vectors ``(n, 3)``."""
    v = as_finite_array(vec, "vec", ndim=2, shape=(None, 3))
    norm = np.linalg.norm(v, axis=1)
    if np.any(norm == 0):
        raise ValueError("vec contains zero-length vectors (no direction)")
    ra = np.degrees(np.arctan2(v[:, 1], v[:, 0])) % 360.0
    dec = np.degrees(np.arcsin(np.clip(v[:, 2] / norm, -1.0, 1.0)))
    return ra, dec


def topocentric_radec(r_teme_km: np.ndarray, times: Time, station: Station
                      ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Topocentric (geometric) RA/Dec of a satellite seen from ``station``.

    Returns
    -------
    ra_deg, dec_deg, range_km
    """
    if not isinstance(station, Station):
        raise TypeError(f"station must be a Station, got {type(station).__name__}")
    sat = teme_to_gcrs(r_teme_km, times)
    rho = sat - station.gcrs_km(times)
    ra, dec = radec_from_vector(rho)
    return ra, dec, np.linalg.norm(rho, axis=1)


def azel_from_enu(enu: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Azimuth (from north through east, [0, 360)) and elevation (degrees) of ENU vectors."""
    v = as_finite_array(enu, "enu", ndim=2, shape=(None, 3))
    az = np.degrees(np.arctan2(v[:, 0], v[:, 1])) % 360.0
    el = np.degrees(np.arctan2(v[:, 2], np.hypot(v[:, 0], v[:, 1])))
    return az, el


def topocentric_azel(r_teme_km: np.ndarray, times: Time, station: Station
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Geometric azimuth/elevation (no refraction) of a satellite from ``station``.

    Returns
    -------
    az_deg, el_deg, range_km
    """
    if not isinstance(station, Station):
        raise TypeError(f"station must be a Station, got {type(station).__name__}")
    rho = teme_to_itrs(r_teme_km, times) - station.itrs_km()
    lat, lon = np.radians(station.lat_deg), np.radians(station.lon_deg)
    east = np.array([-np.sin(lon), np.cos(lon), 0.0])
    north = np.array([-np.sin(lat) * np.cos(lon), -np.sin(lat) * np.sin(lon), np.cos(lat)])
    up = np.array([np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon), np.sin(lat)])
    enu = rho @ np.stack([east, north, up], axis=1)
    az, el = azel_from_enu(enu)
    return az, el, np.linalg.norm(rho, axis=1)


