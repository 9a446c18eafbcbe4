"""Unit tests for eotrack.pose.projection."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.pose import (
    attitude_matrix,
    camera_points,
    check_rotation,
    intrinsic_matrix,
    matrix_from_quaternion,
    project_points,
    quaternion_from_matrix,
    rotation_error_deg,
    skew,
)
from hypothesis import given, settings
from hypothesis import strategies as st

R0 = attitude_matrix([15, 20, 10])
T0 = np.array([1.0, 1.2, 10.0])
K0 = intrinsic_matrix(10.0)

angles = st.tuples(*[st.floats(-170, 170) for _ in range(3)])


def test_project_points_pinhole():
    X = np.array([[0.0, 0.0, 0.0], [1.0, -1.0, 0.5]])
    u = project_points(X, np.eye(3), [0, 0, 10.0], K0)
    np.testing.assert_allclose(u[0], [0.0, 0.0])
    np.testing.assert_allclose(u[1], [10.0 * 1 / 10.5, -10.0 / 10.5])


def test_camera_points_and_intrinsics():
    xc = camera_points([[1.0, 0, 0]], R0, T0)
    np.testing.assert_allclose(xc[0], R0[:, 0] + T0)
    K = intrinsic_matrix(0.01, 320, 240, pixel_size=1e-5)
    np.testing.assert_allclose(K, [[1000, 0, 320], [0, 1000, 240], [0, 0, 1]])


@given(angles)
@settings(max_examples=40, deadline=None)
def test_quaternion_round_trip(a):
    R = attitude_matrix(a)
    q = quaternion_from_matrix(R)
    assert q[0] >= 0 and np.isclose(np.linalg.norm(q), 1)
    np.testing.assert_allclose(matrix_from_quaternion(q), R, atol=1e-12)
    np.testing.assert_allclose(matrix_from_quaternion(-3 * q), R, atol=1e-12)


@given(st.lists(st.floats(-5, 5), min_size=3, max_size=3), st.lists(st.floats(-5, 5),
                                                                     min_size=3, max_size=3))
@settings(max_examples=30, deadline=None)
def test_skew_is_cross_product(v, w):
    np.testing.assert_allclose(skew(v) @ np.array(w), np.cross(v, w), atol=1e-12)


def test_rotation_error():
    R1 = attitude_matrix([0, 0, 7]) @ R0
    assert rotation_error_deg(R1, R0) == pytest.approx(7.0)
    assert rotation_error_deg(R0, R0) == pytest.approx(0.0, abs=1e-6)


def test_bad_inputs():
    with pytest.raises(ValueError, match="R must be a rotation"):
        check_rotation(np.diag([1.0, 1.0, 1.1]))
    with pytest.raises(ValueError, match="proper rotation"):
        check_rotation(np.diag([1.0, 1.0, -1.0]))
    with pytest.raises(ValueError, match="behind the camera"):
        project_points([[0, 0, -20.0]], np.eye(3), [0, 0, 10.0], K0)
    with pytest.raises(ValueError, match="points must have shape"):
        project_points([[0, 0]], np.eye(3), [0, 0, 10.0], K0)
    with pytest.raises(ValueError, match="K must be"):
        project_points([[0, 0, 0.0]], np.eye(3), [0, 0, 10.0], np.eye(3) * -1)
    with pytest.raises(ValueError, match="t must have shape"):
        camera_points([[0, 0, 0.0]], np.eye(3), [0, 10.0])
    with pytest.raises(ValueError, match="f must be"):
        intrinsic_matrix(-1.0)
    with pytest.raises(ValueError, match="angles_deg"):
        attitude_matrix([1, 2])
    with pytest.raises(ValueError, match="seq"):
        attitude_matrix([1, 2, 3], seq="xy")
    with pytest.raises(ValueError, match="q must be a non-zero"):
        matrix_from_quaternion([0, 0, 0, 0])
    with pytest.raises(ValueError, match="R_est"):
        rotation_error_deg(np.ones((3, 3)), R0)
    with pytest.raises(ValueError, match="v must have shape"):
        skew([1.0, 2.0])
    with pytest.raises(ValueError, match="R must be a rotation"):
        quaternion_from_matrix(2 * np.eye(3))
