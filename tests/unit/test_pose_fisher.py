"""Unit tests for eotrack.pose.fisher (Fisher information / CRLB of a pose)."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.pose import (
    attitude_matrix,
    constrained_crlb,
    finite_difference_jacobian,
    intrinsic_matrix,
    matrix_from_quaternion,
    minimal_to_quaternion_jacobian,
    pose_crlb,
    pose_fisher_information,
    pose_fisher_information_quaternion,
    project_points,
    projection_jacobian,
    projection_jacobian_quaternion,
    quaternion_crlb,
    quaternion_from_matrix,
)
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

R0 = attitude_matrix([15, 20, 10])
T0 = np.array([1.0, 1.2, 10.0])
K0 = np.array([[800.0, 0.5, 320.0], [0.0, 790.0, 240.0], [0.0, 0.0, 1.0]])


def _points(rng, n=12):
    return rng.uniform(-1, 1, (n, 3))


@given(st.integers(0, 10_000), st.tuples(*[st.floats(-60, 60) for _ in range(3)]))
@settings(max_examples=25, deadline=None)
def test_jacobian_matches_finite_differences(seed, ang):
    rng = np.random.default_rng(seed)
    X = _points(rng)
    R = attitude_matrix(ang)
    G = projection_jacobian(X, R, T0, K0)
    Gf = finite_difference_jacobian(X, R, T0, K0, step=1e-6)
    np.testing.assert_allclose(G, Gf, rtol=1e-6, atol=1e-5 * np.abs(G).max())


def test_fisher_equals_finite_difference_fisher():
    rng = np.random.default_rng(1)
    X = _points(rng, 30)
    sig = rng.uniform(0.5, 2.0, 30)
    J = pose_fisher_information(X, R0, T0, K0, sig)
    Gf = finite_difference_jacobian(X, R0, T0, K0) / sig[:, None, None]
    Jf = np.einsum("nki,nkj->ij", Gf, Gf)
    np.testing.assert_allclose(J, Jf, rtol=1e-6, atol=1e-8 * np.abs(J).max())
    assert J.shape == (6, 6)
    np.testing.assert_allclose(J, J.T)


def test_fisher_scalar_sigma_scaling():
    X = _points(np.random.default_rng(2))
    J1 = pose_fisher_information(X, R0, T0, K0, 1.0)
    J2 = pose_fisher_information(X, R0, T0, K0, 2.0)
    np.testing.assert_allclose(J2, J1 / 4)


@given(st.integers(0, 10_000))
@settings(max_examples=25, deadline=None)
def test_information_is_monotone_under_adding_points(seed):
    rng = np.random.default_rng(seed)
    X = _points(rng, 10)
    sig = rng.uniform(0.1, 3.0, 10)
    J9 = pose_fisher_information(X[:9], R0, T0, K0, sig[:9])
    J10 = pose_fisher_information(X, R0, T0, K0, sig)
    assert np.linalg.eigvalsh(J10 - J9).min() >= -1e-9 * np.abs(J10).max()
    C9, C10 = np.linalg.inv(J9), np.linalg.inv(J10)
    assert np.linalg.eigvalsh(C9 - C10).min() >= -1e-9 * np.abs(C9).max()


def test_quaternion_jacobian_and_constrained_crlb():
    rng = np.random.default_rng(3)
    X = _points(rng, 20)
    q = quaternion_from_matrix(R0)
    G = projection_jacobian_quaternion(X, q, T0, K0)
    h = 1e-6
    th = np.r_[T0, q]
    Gf = np.empty_like(G)
    for k in range(7):
        d = np.zeros(7)
        d[k] = h
        up = project_points(X, matrix_from_quaternion(th[3:] + d[3:]), th[:3] + d[:3], K0)
        um = project_points(X, matrix_from_quaternion(th[3:] - d[3:]), th[:3] - d[:3], K0)
        Gf[:, :, k] = (up - um) / (2 * h)
    np.testing.assert_allclose(G, Gf, atol=1e-4)
    J7 = pose_fisher_information_quaternion(X, q, T0, K0, 1.0)
    # singular along (0, q): scaling q changes nothing
    np.testing.assert_allclose(J7 @ np.r_[0, 0, 0, q], 0, atol=1e-8 * np.abs(J7).max())
    C7 = constrained_crlb(J7, q)
    np.testing.assert_allclose(C7, quaternion_crlb(X, R0, T0, K0, 1.0), rtol=1e-7,
                               atol=1e-12)
    np.testing.assert_allclose(C7 @ np.r_[0, 0, 0, q], 0, atol=1e-12)


def test_minimal_to_quaternion_jacobian_is_derivative():
    q = quaternion_from_matrix(R0)
    E = minimal_to_quaternion_jacobian(q)
    d = 1e-6
    for k in range(3):
        v = np.zeros(3)
        v[k] = d
        x, y, z, w = (Rotation.from_rotvec(v) * Rotation.from_matrix(R0)).as_quat()
        qn = np.array([w, x, y, z])
        qn = qn if qn @ q > 0 else -qn
        np.testing.assert_allclose((qn - q) / d, E[3:, 3 + k], atol=1e-5)


def test_crlb_is_inverse():
    X = _points(np.random.default_rng(4))
    C = pose_crlb(X, R0, T0, K0, 0.5)
    np.testing.assert_allclose(C @ pose_fisher_information(X, R0, T0, K0, 0.5), np.eye(6),
                               atol=1e-8)


def test_bad_inputs():
    X = _points(np.random.default_rng(5))
    with pytest.raises(ValueError, match="sigma_px must be > 0"):
        pose_fisher_information(X, R0, T0, K0, -1.0)
    with pytest.raises(ValueError, match="sigma_px must be a scalar or have shape"):
        pose_fisher_information(X, R0, T0, K0, np.ones(3))
    with pytest.raises(ValueError, match="R must be a rotation"):
        pose_fisher_information(X, 1.01 * R0, T0, K0, 1.0)
    with pytest.raises(ValueError, match="behind the camera"):
        pose_fisher_information(X, R0, [0, 0, -10.0], K0, 1.0)
    with pytest.raises(ValueError, match="collinear"):
        line = np.outer(np.linspace(-1, 1, 8), [1.0, 0.5, 0.2])
        pose_crlb(line, R0, T0, K0, 1.0)
    with pytest.raises(ValueError, match="at least 3"):
        pose_crlb(X[:2], R0, T0, K0, 1.0)
    with pytest.raises(ValueError, match="unit quaternion"):
        projection_jacobian_quaternion(X, [1.0, 0.1, 0, 0], T0, K0)
    with pytest.raises(ValueError, match="J must have shape"):
        constrained_crlb(np.eye(6), [1.0, 0, 0, 0])
    with pytest.raises(ValueError, match="points must have shape"):
        projection_jacobian(X[:, :2], R0, T0, K0)
    with pytest.raises(ValueError, match="unit quaternion"):
        minimal_to_quaternion_jacobian([2.0, 0, 0, 0])
    with pytest.raises(ValueError, match="points must have shape"):
        finite_difference_jacobian(X[:, :2], R0, T0, K0)
    with pytest.raises(ValueError, match="sigma_px"):
        quaternion_crlb(X, R0, T0, K0, 0.0)
    with pytest.raises(ValueError, match="sigma_px"):
        pose_fisher_information_quaternion(X, quaternion_from_matrix(R0), T0, K0, 0.0)


def test_public_signature_from_issue():
    """pose_fisher_information(points, R, t, K, sigma_px) with the left perturbation."""
    X = _points(np.random.default_rng(6))
    J = pose_fisher_information(points=X, R=R0, t=T0, K=intrinsic_matrix(10.0), sigma_px=0.1)
    assert J.shape == (6, 6)
