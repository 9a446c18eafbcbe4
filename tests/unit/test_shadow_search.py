"""Fast Sun, shadow intervals and the WRANSAC scenario's shadow search."""

import astropy.units as u
import numpy as np
import pytest
from astropy.time import Time
from eotrack import astro as A
from eotrack.experiments import wransac as W


def test_sun_approx_agrees_with_astropy_up_to_precession():
    t = Time("2006-03-20T19:00:00") + np.arange(0, 360, 30) * u.day
    a = A.sun_position_approx(t.utc.jd)
    b = A.sun_position_gcrs(t)
    ang = np.degrees(np.arccos(np.sum(a * b, 1) / np.linalg.norm(a, axis=1)
                               / np.linalg.norm(b, axis=1)))
    # of date vs J2000: ≈ 50″/yr × 6 yr of precession, plus ≈ 0.01° of formula error
    assert np.all(ang < 0.12)
    np.testing.assert_allclose(np.linalg.norm(a, axis=1), np.linalg.norm(b, axis=1), rtol=2e-4)


def test_shadow_intervals():
    s = np.array([0, 1, 2, 2, 0, 0, 2, 1])
    np.testing.assert_array_equal(A.shadow_intervals(s), [[1, 4], [6, 8]])
    np.testing.assert_array_equal(A.shadow_intervals(s, A.UMBRA), [[2, 4], [6, 7]])
    assert A.shadow_intervals(np.zeros(5, int)).shape == (0, 2)
    with pytest.raises(ValueError, match="states must be 1-D"):
        A.shadow_intervals(np.zeros((2, 2)))
    with pytest.raises(ValueError, match="min_state must be"):
        A.shadow_intervals(s, 0)


def test_eclipse_season_finds_the_72_min_pass():
    entry, minutes, durations, start, end = W.eclipse_season(26900, 45)
    assert minutes == pytest.approx(72, abs=2)
    assert start < entry < end and len(durations) > 30


def test_no_shadow_pass_is_a_clear_error():
    cfg = W.with_changes(norad_id=28626, station=(32.78, -105.82))
    with pytest.raises(ValueError, match=r"NORAD 28626 has no Earth-shadow pass between "
                                         r"2006-05-\d\d .* and 2006-06-25"):
        W.make_scenario(cfg)
    # the documented fallback: a fixed window
    sc = W.make_scenario(W.with_changes(cfg, window_end_utc="2006-06-20T06:00:00"))
    assert np.isnan(sc.eclipse_min) and sc.truth_obs.shape == (2, 80)


def test_scenario_below_horizon_and_bad_window():
    with pytest.raises(ValueError, match="below the horizon"):
        W.make_scenario(W.with_changes(station=(39.6, -60.0)))
    with pytest.raises(ValueError, match="window_end_utc must be an ISO UTC time"):
        W.make_scenario(W.with_changes(window_end_utc="tomorrow"))
