"""Unit tests for eotrack.pose.dlt."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.pose import (
    attitude_matrix,
    dlt_pose,
    dlt_pose_batch,
    intrinsic_matrix,
    is_planar,
    plane_frame,
    project_points,
)
from hypothesis import given, settings
from hypothesis import strategies as st

K0 = intrinsic_matrix(10.0)
T0 = np.array([1.0, 1.2, 10.0])


@given(st.integers(0, 10_000), st.booleans(), st.integers(6, 40),
       st.tuples(*[st.floats(-40, 40) for _ in range(3)]))
@settings(max_examples=40, deadline=None)
def test_noise_free_pose_recovered_exactly(seed, planar, n, ang):
    rng = np.random.default_rng(seed)
    X = rng.uniform(-1, 1, (n, 3))
    if planar:
        X[:, 2] = -1.0
    R = attitude_matrix(ang)
    u = project_points(X, R, T0, K0)
    R2, t2 = dlt_pose(X, u, K0)
    np.testing.assert_allclose(R2, R, atol=1e-8)
    np.testing.assert_allclose(t2, T0, atol=1e-7)


def test_batch_flags_degenerate_samples():
    rng = np.random.default_rng(0)
    X = rng.uniform(-1, 1, (3, 6, 3))
    X[1] = np.outer(np.linspace(0, 1, 6), [1.0, 2.0, 0.5])  # collinear
    X[2, :, 2] = 0.3  # coplanar but planar=False forces the 3×4 DLT
    R = attitude_matrix([5, 10, 15])
    u = np.stack([project_points(x, R, T0, K0) for x in X])
    _, _, ok = dlt_pose_batch(X, u, K0, planar=False)
    assert ok.tolist() == [True, False, False]
    Rb, _tb, ok = dlt_pose_batch(X, u, K0)
    assert ok.tolist() == [True, False, True]
    np.testing.assert_allclose(Rb[2], R, atol=1e-8)


def test_planarity_helpers():
    X = np.c_[np.random.default_rng(1).uniform(-1, 1, (10, 2)), np.full(10, 2.0)]
    assert is_planar(X)
    _c, B = plane_frame(X)
    np.testing.assert_allclose(abs(B[:, 2]), [0, 0, 1], atol=1e-12)
    assert np.isclose(np.linalg.det(B), 1)
    assert not is_planar(np.random.default_rng(2).normal(size=(10, 3)))


def test_bad_inputs():
    rng = np.random.default_rng(3)
    X = rng.uniform(-1, 1, (8, 3))
    u = project_points(X, np.eye(3), T0, K0)
    with pytest.raises(ValueError, match="at least 6"):
        dlt_pose(X[:5], u[:5], K0)
    with pytest.raises(ValueError, match="same length"):
        dlt_pose(X, u[:7], K0)
    with pytest.raises(ValueError, match="collinear"):
        line = np.outer(np.linspace(-1, 1, 8), [1.0, 0.5, 0.2])
        dlt_pose(line, u, K0)
    with pytest.raises(ValueError, match="pixels must have shape"):
        dlt_pose(X, X, K0)
    with pytest.raises(ValueError, match="points must be"):
        dlt_pose_batch(X, u, K0)
    with pytest.raises(ValueError, match="points must have shape"):
        is_planar(X[:, :2])
    with pytest.raises(ValueError, match="points must have shape"):
        plane_frame(X[:, :2])


def test_batch_planar_four_points():
    rng = np.random.default_rng(4)
    X = np.c_[rng.uniform(-1, 1, (4, 2)), np.full(4, -1.0)]
    R = attitude_matrix([15, 20, 10])
    u = project_points(X, R, T0, K0)
    Rb, tb, ok = dlt_pose_batch(X[None], u[None], K0)
    assert ok[0]
    np.testing.assert_allclose(Rb[0], R, atol=1e-9)
    np.testing.assert_allclose(tb[0], T0, atol=1e-9)
