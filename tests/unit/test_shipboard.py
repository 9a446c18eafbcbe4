"""Tests of eotrack.geometry.shipboard."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.geometry.shipboard import (
    OMEGA_EARTH,
    ShipMotion,
    camera_from_deck,
    camera_from_level,
    deck_from_level,
    diurnal_rates,
    diurnal_rates_paper,
    enu_from_azalt,
    image_rate_projective,
    project_to_image,
    sea_state_motion,
    ship_attitude,
    star_angles_from_image,
)
from hypothesis import given, settings
from hypothesis import strategies as st

ang = st.floats(-0.3, 0.3)


@settings(max_examples=30, deadline=None)
@given(ang, ang, ang)
def test_rotations_orthonormal(h, p, r):
    R = deck_from_level(h, p, r)
    np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-12)
    assert np.linalg.det(R) == pytest.approx(1.0)


def test_camera_points_at_target():
    A, h, psi = np.radians(130.0), np.radians(42.0), np.radians(45.0)
    R = camera_from_level(psi, 0.0, 0.0, A - psi, h)
    np.testing.assert_allclose(R @ enu_from_azalt(A, h), [0, 1, 0], atol=1e-12)
    xy = project_to_image((R @ enu_from_azalt(A, h))[None], 700.0, (63.5, 63.5))
    np.testing.assert_allclose(xy, [[63.5, 63.5]])


def test_small_angle_camera_matrix():
    exact = camera_from_deck(0.01, 0.02)
    approx = camera_from_deck(0.01, 0.02, small_angle=True)
    assert np.abs(exact - approx).max() < 3e-4


@settings(max_examples=30, deadline=None)
@given(st.floats(-200, 200), st.floats(-200, 200))
def test_star_angles_eq6_9(sx, sz):
    f = 700.0
    az, el = star_angles_from_image(sx, sz, f)
    v = np.array([sx, f, sz]) / np.linalg.norm([sx, f, sz])
    assert az == pytest.approx(np.arctan2(v[0], v[1]), abs=1e-12)
    assert el == pytest.approx(np.arcsin(v[2]), abs=1e-12)


def test_projective_rate_finite_difference():
    r = np.array([0.1, -0.2, 1.0])
    rd = np.array([0.01, 0.03, -0.02])
    u, v = image_rate_projective(r, rd, 500.0)
    dt = 1e-6
    r2 = r + rd * dt
    assert u == pytest.approx(500 * (r2[0] / r2[2] - r[0] / r[2]) / dt, rel=1e-5)
    assert v == pytest.approx(500 * (r2[1] / r2[2] - r[1] / r[2]) / dt, rel=1e-5)


def test_diurnal_rates():
    # at the pole the stars circle the zenith: no altitude change, azimuth rate = omega
    dA, dh = diurnal_rates(1.0, 0.5, np.pi / 2)
    assert dh == pytest.approx(0, abs=1e-20) and dA == pytest.approx(OMEGA_EARTH * np.cos(0.5))
    _, ph = diurnal_rates_paper(1.0, 0.5)
    assert ph != 0  # the printed form has no latitude and is wrong there


def test_ship_attitude_rates():
    rng = np.random.default_rng(0)
    t = np.linspace(0, 20, 2001)
    att = ship_attitude(sea_state_motion(3), t, rng)
    num = np.gradient(att["roll"], t)
    np.testing.assert_allclose(num[5:-5], att["roll_rate"][5:-5], atol=1e-5)
    assert np.degrees(np.abs(att["roll"]).max()) < 1.2 * 1.1 + 1e-9


def test_bad_inputs():
    with pytest.raises(ValueError, match="lat"):
        diurnal_rates(0.0, 0.0, 3.0)
    with pytest.raises(ValueError, match="focal"):
        star_angles_from_image(1.0, 1.0, 0.0)
    with pytest.raises(ValueError, match="v_cam"):
        project_to_image(np.zeros((3, 2)), 1.0, (0, 0))
    with pytest.raises(ValueError, match="r and r_dot"):
        image_rate_projective(np.zeros(3), np.zeros(2), 1.0)
    with pytest.raises(ValueError, match="roll_amp_deg"):
        ShipMotion(roll_amp_deg=(1.0,), roll_period_s=(1.0, 2.0))
    with pytest.raises(ValueError, match="sea_state"):
        sea_state_motion(9)
    with pytest.raises(TypeError, match="rng"):
        ship_attitude(sea_state_motion(3), np.zeros(3), 1)
    with pytest.raises(ValueError, match="heading"):
        deck_from_level(np.nan, 0, 0)
    with pytest.raises(ValueError, match="azimuth"):
        camera_from_deck(np.inf, 0.0)
    with pytest.raises(ValueError, match="altitude"):
        enu_from_azalt(0.0, np.nan)
    with pytest.raises(ValueError, match="azimuth"):
        diurnal_rates_paper(np.nan, 0.0)
    with pytest.raises(TypeError, match="motion"):
        ship_attitude("calm", np.zeros(3), np.random.default_rng(0))
    with pytest.raises(ValueError, match="pitch"):
        camera_from_level(0.0, np.nan, 0.0, 0.0, 0.0)
