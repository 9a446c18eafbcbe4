"""Two-body states from classical elements, propagation, GEO placement, Earth blocking."""

import numpy as np
import pytest
from eotrack.astro.twobody import (
    GEO_RADIUS_KM,
    MU_EARTH_KM3_S2,
    elements_to_state,
    geo_positions,
    line_of_sight_clear,
    place_on_shell,
    propagate_elements,
    solve_kepler,
)
from hypothesis import given, settings
from hypothesis import strategies as st


def test_circular_equatorial():
    r, v = elements_to_state(7000.0, 0.0, 0.0, 0.0, 0.0, 90.0)
    assert np.allclose(r, [0, 7000, 0])
    assert np.allclose(v, [-np.sqrt(MU_EARTH_KM3_S2 / 7000), 0, 0])


@settings(max_examples=30, deadline=None)
@given(st.floats(6600, 45000), st.floats(0, 0.7), st.floats(0, 180), st.floats(0, 360),
       st.floats(0, 360), st.floats(0, 360))
def test_energy_and_angular_momentum(a, e, i, raan, w, nu):
    r, v = elements_to_state(a, e, i, raan, w, nu)
    eps = v @ v / 2 - MU_EARTH_KM3_S2 / np.linalg.norm(r)
    assert eps == pytest.approx(-MU_EARTH_KM3_S2 / (2 * a), rel=1e-9)
    h = np.cross(r, v)
    assert np.degrees(np.arccos(h[2] / np.linalg.norm(h))) == pytest.approx(i, abs=1e-6)


def test_propagation_full_period_and_vectorised():
    a = 7470.86
    T = 2 * np.pi * np.sqrt(a**3 / MU_EARTH_KM3_S2)
    r0, _v0 = elements_to_state(a, 0.02, 63.36, 328.65, 7.22, 144.69)
    r, _v = propagate_elements(a, 0.02, 63.36, 328.65, 7.22, 144.69, np.array([0.0, T]))
    assert r.shape == (2, 3)
    assert np.allclose(r[0], r0) and np.allclose(r[1], r0, atol=1e-6)
    E = solve_kepler(np.array([0.5, 2.0]), 0.9)
    assert np.allclose(E - 0.9 * np.sin(E), [0.5, 2.0])


def test_geo_and_line_of_sight():
    g = geo_positions([0.0, 90.0], [0.0, 0.0])
    assert np.allclose(np.linalg.norm(g, axis=1), GEO_RADIUS_KM)
    obs = np.array([[7000.0, 0, 0], [-7000.0, 0, 0]])
    clear = line_of_sight_clear(obs, g[0])
    assert clear.tolist() == [True, False]  # the second looks through the Earth


def test_place_on_shell():
    o = np.array([7000.0, 0, 0])
    X = place_on_shell(o, [[1.0, 0, 0], [-1.0, 0, 0], [0, 3.0, 0]])
    assert np.allclose(np.linalg.norm(X, axis=1), GEO_RADIUS_KM)
    assert np.allclose(X[0], [GEO_RADIUS_KM, 0, 0]) and np.allclose(X[1], [-GEO_RADIUS_KM, 0, 0])
    with pytest.raises(ValueError, match="origin_km must lie inside"):
        place_on_shell([5e4, 0, 0], [[1.0, 0, 0]])
    with pytest.raises(ValueError, match="directions must have shape"):
        place_on_shell(o, [[1.0, 0]])


def test_bad_input():
    with pytest.raises(ValueError, match="e must lie in"):
        elements_to_state(7000, 1.2, 0, 0, 0, 0)
    with pytest.raises(ValueError, match="a_km must be > 0"):
        elements_to_state(-7000, 0.1, 0, 0, 0, 0)
    with pytest.raises(ValueError, match="i_deg"):
        elements_to_state(7000, 0.1, np.nan, 0, 0, 0)
    with pytest.raises(ValueError, match="dec_deg"):
        geo_positions(0, 95)
    with pytest.raises(ValueError, match="observer_km and target_km must end"):
        line_of_sight_clear([0, 0], [1, 2, 3])
    with pytest.raises(ValueError, match="coincide"):
        line_of_sight_clear([8000.0, 0, 0], [8000.0, 0, 0])
    with pytest.raises(ValueError, match="dt_s"):
        propagate_elements(7000, 0, 0, 0, 0, 0, np.inf)
