"""Offline astronomy: time and frames, TLE propagation, Earth shadow, the star catalogue.

Importing this package switches astropy to offline operation (no IERS or other downloads).
"""

from __future__ import annotations

from .offline import configure_offline

configure_offline()

from .catalog import StarCatalog, load_catalog, stars_in_field  # noqa: E402
from .frames import (  # noqa: E402
    Station,
    azel_from_enu,
    radec_from_vector,
    teme_to_gcrs,
    teme_to_itrs,
    topocentric_azel,
    topocentric_radec,
)
from .orbit_fit import OrbitFit, fit_orbit, gauss_iod, propagate_state  # noqa: E402
from .shadow import (  # noqa: E402
    PENUMBRA,
    SUNLIT,
    UMBRA,
    earth_shadow,
    shadow_intervals,
    sun_position_approx,
    sun_position_gcrs,
)
from .tle import GEO_NORAD_IDS, propagate_teme, satellite, tle_epoch, verification_tles  # noqa: E402

__all__ = [
    "GEO_NORAD_IDS",
    "PENUMBRA",
    "SUNLIT",
    "UMBRA",
    "OrbitFit",
    "StarCatalog",
    "Station",
    "azel_from_enu",
    "configure_offline",
    "earth_shadow",
    "fit_orbit",
    "gauss_iod",
    "load_catalog",
    "propagate_state",
    "propagate_teme",
    "radec_from_vector",
    "satellite",
    "shadow_intervals",
    "stars_in_field",
    "sun_position_approx",
    "sun_position_gcrs",
    "teme_to_gcrs",
    "teme_to_itrs",
    "tle_epoch",
    "topocentric_azel",
    "topocentric_radec",
    "verification_tles",
]
