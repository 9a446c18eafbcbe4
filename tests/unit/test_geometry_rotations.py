"""Rotations: eq. (4) of Huang et al., passive elementary matrices, look-at frames."""

import numpy as np
import pytest
from eotrack.geometry import (
    check_rotation,
    dcm_321,
    euler_321_from_matrix,
    look_at,
    rot_x,
    rot_y,
    rot_z,
    rotation_321,
)
from hypothesis import given, settings
from hypothesis import strategies as st

angle = st.floats(-3.0, 3.0)


def test_elementary_matrices_are_passive_as_printed():
    a = 0.3
    c, s = np.cos(a), np.sin(a)
    assert np.allclose(rot_z(a), [[c, s, 0], [-s, c, 0], [0, 0, 1]])
    assert np.allclose(rot_y(a), [[c, 0, -s], [0, 1, 0], [s, 0, c]])
    assert np.allclose(rot_x(a), [[1, 0, 0], [0, c, s], [0, -s, c]])
    # passive: the x axis expressed in a frame turned by +a about z has a negative y component
    assert rot_z(a)[1] @ [1, 0, 0] < 0


def test_rotation_321_is_product_of_eq4():
    y, p, r = 0.1, -0.2, 0.7
    assert np.allclose(rotation_321(y, p, r), rot_z(y) @ rot_y(p) @ rot_x(r))


@settings(max_examples=50, deadline=None)
@given(angle, st.floats(-1.5, 1.5), angle)
def test_euler_roundtrip(y, p, r):
    R = rotation_321(y, p, r)
    check_rotation(R)
    assert np.allclose(rotation_321(*euler_321_from_matrix(R)), R, atol=1e-9)


def test_paper_order_versus_conventional_321():
    from scipy.spatial.transform import Rotation

    y, p, r = 0.3, -0.4, 1.1
    # eq. (4) as printed = frame turned about x, then y, then z (a 1-2-3 frame sequence)
    assert np.allclose(rotation_321(y, p, r), Rotation.from_euler("XYZ", [r, p, y]).as_matrix().T)
    # the conventional aerospace 3-2-1 reference -> body matrix
    assert np.allclose(dcm_321(y, p, r), Rotation.from_euler("ZYX", [y, p, r]).as_matrix().T)
    assert np.allclose(dcm_321(y, 0, 0), rotation_321(y, 0, 0))


def test_vectorised_shapes():
    R = rotation_321(np.zeros(5), np.ones(5), np.full(5, 0.2))
    assert R.shape == (5, 3, 3)
    _y, p, _r = euler_321_from_matrix(R)
    assert np.allclose(p, 1.0)


def test_look_at_axes():
    R = look_at([0, 1, 0], up=[0, 0, 1])
    assert np.allclose(R[2], [0, 1, 0])
    assert np.allclose(R[1], [0, 0, -1])  # image y (rows) points down = -up
    check_rotation(R)


def test_check_rotation_rejects_bad_input():
    with pytest.raises(ValueError, match="R must be a 3x3"):
        check_rotation(np.eye(2))
    with pytest.raises(ValueError, match="not orthonormal"):
        check_rotation(np.diag([1, 1, 2.0]))
    with pytest.raises(ValueError, match="determinant"):
        check_rotation(np.diag([1, 1, -1.0]))
    with pytest.raises(ValueError, match="angle_rad"):
        rot_x(np.nan)
    with pytest.raises(ValueError, match="yaw_rad"):
        rotation_321(np.inf, 0, 0)
    with pytest.raises(ValueError, match="boresight"):
        look_at([0, 0, 0])
    with pytest.raises(ValueError, match="up must not be parallel"):
        look_at([0, 0, 1], up=[0, 0, 2])
