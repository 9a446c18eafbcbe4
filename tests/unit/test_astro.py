"""Offline astronomy: settings, TLEs, frames, Earth shadow, catalogue."""

import astropy.units as u
import eotrack.astro as A
import numpy as np
import pytest
from astropy.coordinates import AltAz, SkyCoord
from astropy.time import Time


def test_offline_settings_applied_on_import():
    from astropy.utils import iers
    from astropy.utils.data import conf

    assert iers.conf.auto_download is False
    assert iers.conf.auto_max_age is None
    assert conf.allow_internet is False


def test_future_date_works_offline():
    t = Time("2026-11-22T00:00:00") + np.arange(3) * u.h
    st = A.Station(39.6, 121.0)
    assert A.Station.gcrs_km(st, t).shape == (3, 3)


def test_verification_tles_and_geo():
    tles = A.verification_tles()
    assert set(A.GEO_NORAD_IDS) <= set(tles)
    assert all(len(l1) == 69 and len(l2) == 69 for l1, l2 in tles.values())
    sat = A.satellite(26900)
    t = A.tle_epoch(sat) + np.arange(0, 86400, 3600) * u.s
    r, v = A.propagate_teme(sat, t)
    assert np.allclose(np.linalg.norm(r, axis=1), 42164, atol=50)  # geostationary radius
    assert np.allclose(np.linalg.norm(v, axis=1), 3.075, atol=0.01)


def test_unknown_norad_id():
    with pytest.raises(ValueError, match="norad_id 99999 is not among the TLEs"):
        A.satellite(99999)
    with pytest.raises(TypeError, match="norad_id must be an integer"):
        A.satellite("26900")


def test_topocentric_radec_agrees_with_astropy_altaz_direction():
    """Our geometric Az/El and astropy's AltAz of the same topocentric vector agree."""
    sat = A.satellite(26900)
    t = A.tle_epoch(sat) + np.arange(0, 7200, 1800) * u.s
    r, _ = A.propagate_teme(sat, t)
    st = A.Station(39.6, 121.0, 50.0)
    az, el, rng = A.topocentric_azel(r, t, st)
    itrs = A.teme_to_itrs(r, t)
    from astropy.coordinates import ITRS, CartesianRepresentation

    topo = ITRS(CartesianRepresentation((itrs - st.itrs_km()).T * u.km), obstime=t,
                location=st.location)
    aa = topo.transform_to(AltAz(obstime=t, location=st.location))
    np.testing.assert_allclose(az, aa.az.deg, atol=2e-4)
    np.testing.assert_allclose(el, aa.alt.deg, atol=2e-4)
    assert np.all((rng > 35000) & (rng < 42000))


def test_radec_of_known_direction():
    ra, dec = A.radec_from_vector(np.array([[0.0, 1.0, 1.0]]))
    assert ra[0] == pytest.approx(90.0) and dec[0] == pytest.approx(45.0)
    with pytest.raises(ValueError, match="zero-length"):
        A.radec_from_vector(np.zeros((1, 3)))
    with pytest.raises(ValueError, match=r"vec must have shape \(n, 3\)"):
        A.radec_from_vector(np.zeros((2, 2)))


def test_station_and_frame_bad_input():
    with pytest.raises(ValueError, match="lat_deg must lie in"):
        A.Station(95.0, 0.0)
    with pytest.raises(TypeError, match="times must be an astropy Time"):
        A.teme_to_gcrs(np.zeros((1, 3)) + 7000, 0.0)
    with pytest.raises(ValueError, match="times has 2 entries but the positions have 1"):
        A.teme_to_gcrs(np.ones((1, 3)) * 7000, Time(["2020-01-01", "2020-01-02"]))
    with pytest.raises(TypeError, match="station must be a Station"):
        A.topocentric_radec(np.ones((1, 3)) * 7000, Time(["2020-01-01"]), (0, 0))
    with pytest.raises(TypeError, match="sat must be an sgp4 Satrec"):
        A.propagate_teme("ISS", Time("2020-01-01"))


def test_earth_shadow_geometry():
    sun = np.array([1.496e8, 0.0, 0.0])
    behind = np.array([[-42164.0, 0.0, 0.0], [-42164.0, 6378.0 + 60.0, 0.0],
                       [42164.0, 0.0, 0.0], [0.0, 42164.0, 0.0]])
    st = A.earth_shadow(behind, sun)
    assert st.tolist() == [A.UMBRA, A.PENUMBRA, A.SUNLIT, A.SUNLIT]
    with pytest.raises(ValueError, match="inside the Earth"):
        A.earth_shadow(np.array([[1000.0, 0, 0]]), sun)
    with pytest.raises(ValueError, match="lengths differ"):
        A.earth_shadow(behind, np.tile(sun, (2, 1)))


def test_geo_max_eclipse_near_72_min():
    """A geostationary object's longest Earth-shadow pass lasts about 72 min (equinox)."""
    sat = A.satellite(26900)
    t = Time("2006-03-20T19:00:00") + np.arange(0, 2 * 3600, 60) * u.s
    r, _ = A.propagate_teme(sat, t)
    s = A.earth_shadow(A.teme_to_gcrs(r, t), A.sun_position_gcrs(t))
    assert 66 <= np.count_nonzero(s) <= 74


def test_catalogue():
    cat = A.load_catalog()
    assert len(cat) > 400_000
    assert np.all(np.diff(cat.mag) >= 0)
    orion = A.stars_in_field(83.82, -5.39, 1.0, max_mag=6.0)  # around M42
    assert len(orion) >= 5
    sep = SkyCoord(orion.ra_deg * u.deg, orion.dec_deg * u.deg).separation(
        SkyCoord(83.82 * u.deg, -5.39 * u.deg))
    assert np.all(sep.deg <= 1.0)
    moved = orion.at_epoch(2026.0)
    assert np.max(np.abs(moved.dec_deg - orion.dec_deg)) < 0.01
    with pytest.raises(ValueError, match="radius_deg must be finite and > 0"):
        A.stars_in_field(0.0, 0.0, 0.0)
    with pytest.raises(ValueError, match="dec_deg must lie in"):
        A.stars_in_field(0.0, 91.0, 1.0)
