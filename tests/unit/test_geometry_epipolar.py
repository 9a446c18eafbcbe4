"""Fundamental matrix from poses (eqs. 2–5) and point-to-epipolar-line distances (eq. 8)."""

import cv2
import numpy as np
import pytest
from eotrack.geometry import (
    cross_matrix,
    epipolar_distances,
    epipolar_lines,
    epipoles,
    fundamental_from_poses,
    intrinsics_from_fov,
    look_at,
    project_points,
    relative_pose,
    rotation_321,
    sampson_distances,
)
from hypothesis import given, settings
from hypothesis import strategies as st

K = intrinsics_from_fov(2.0, 2.0, 512, 512, 252.44, 235.33)


def random_pair(rng):
    target = rng.normal(size=3) * 40.0
    c1 = target + rng.normal(size=3) * 100
    c2 = target + rng.normal(size=3) * 100
    R1 = look_at(target - c1, up=rng.normal(size=3))
    R2 = look_at(target - c2, up=rng.normal(size=3))
    K2 = intrinsics_from_fov(30.0, 25.0, 640, 480)
    X = target + rng.normal(size=(25, 3)) * 5.0
    return K2, R1, c1, R2, c2, X


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**31 - 1))
def test_epipolar_constraint_holds_for_random_poses(seed):
    rng = np.random.default_rng(seed)
    K2, R1, c1, R2, c2, X = random_pair(rng)
    F = fundamental_from_poses(K2, R1, c1, K2, R2, c2)
    p1 = project_points(X, K2, R1, c1)
    p2 = project_points(X, K2, R2, c2)
    h1 = np.column_stack([p1, np.ones(len(p1))])
    h2 = np.column_stack([p2, np.ones(len(p2))])
    assert np.abs(np.einsum("ni,ij,nj->n", h2, F, h1)).max() < 1e-8
    d = epipolar_distances(F, p1, p2)
    assert np.diag(d).max() < 1e-6
    assert np.linalg.matrix_rank(F, tol=1e-10) == 2


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**31 - 1), st.floats(-1e3, 1e3).filter(lambda s: abs(s) > 1e-3))
def test_distances_invariant_to_scaling_F(seed, scale):
    rng = np.random.default_rng(seed)
    F = rng.normal(size=(3, 3))
    p1 = rng.uniform(0, 512, (7, 2))
    p2 = rng.uniform(0, 512, (5, 2))
    assert np.allclose(epipolar_distances(scale * F, p1, p2), epipolar_distances(F, p1, p2))
    assert np.allclose(sampson_distances(scale * F, p1, p2), sampson_distances(F, p1, p2))


def test_agrees_with_opencv_conventions():
    rng = np.random.default_rng(3)
    _K2, R1, c1, R2, c2, X = random_pair(rng)
    F = fundamental_from_poses(K, R1, c1, K, R2, c2)
    # OpenCV stereo convention: x2 = R x1 + T, E = [T]x R, F = K^-T E K^-1
    R = R2 @ R1.T
    T = R2 @ (c1 - c2)
    E = cross_matrix(T) @ R
    F_cv = np.linalg.inv(K).T @ E @ np.linalg.inv(K)
    F_cv /= np.linalg.norm(F_cv)
    assert min(np.abs(F - F_cv).max(), np.abs(F + F_cv).max()) < 1e-10
    # and with the 8-point estimate from noise-free projections
    p1 = project_points(X, K, R1, c1)
    p2 = project_points(X, K, R2, c2)
    F8, _ = cv2.findFundamentalMat(p1, p2, cv2.FM_8POINT)
    F8 /= np.linalg.norm(F8)
    assert min(np.abs(F - F8).max(), np.abs(F + F8).max()) < 1e-4


def test_distances_match_computecorrespondepilines():
    rng = np.random.default_rng(4)
    F = fundamental_from_poses(K, rotation_321(0.1, 0.2, 0.3), np.zeros(3), K,
                               rotation_321(0.12, 0.18, 0.31), np.array([1.0, 0.2, 0.1]))
    p1 = rng.uniform(0, 512, (10, 2))
    p2 = rng.uniform(0, 512, (8, 2))
    lines = cv2.computeCorrespondEpilines(p1.reshape(-1, 1, 2), 1, F).reshape(-1, 3)
    ref = np.abs(lines[:, :2] @ p2.T + lines[:, 2:])
    assert np.allclose(epipolar_distances(F, p1, p2), ref, atol=1e-6)
    assert np.allclose(np.hypot(*epipolar_lines(F, p1)[:, :2].T), 1)


def test_sampson_below_one_sided_and_epipoles():
    rng = np.random.default_rng(5)
    K2, R1, c1, R2, c2, _ = random_pair(rng)
    F = fundamental_from_poses(K2, R1, c1, K2, R2, c2)
    p1 = rng.uniform(0, 640, (6, 2))
    p2 = rng.uniform(0, 480, (6, 2))
    assert np.all(sampson_distances(F, p1, p2) <= epipolar_distances(F, p1, p2) + 1e-12)
    e1, e2 = epipoles(F)
    assert np.allclose(F @ e1, 0, atol=1e-12) and np.allclose(F.T @ e2, 0, atol=1e-12)
    r12, t = relative_pose(R1, c1, R2, c2)
    assert np.allclose(r12, R2 @ R1.T) and np.allclose(t, R1 @ (c2 - c1))


def test_empty_point_sets():
    F = np.arange(9.0).reshape(3, 3)
    assert epipolar_distances(F, np.zeros((0, 2)), [[1.0, 2.0]]).shape == (0, 1)
    assert epipolar_distances(F, [[1.0, 2.0]], []).shape == (1, 0)
    assert sampson_distances(F, [], []).shape == (0, 0)


def test_bad_input():
    R = np.eye(3)
    with pytest.raises(ValueError, match="K1 must be a 3x3"):
        fundamental_from_poses(np.eye(2), R, np.zeros(3), K, R, np.ones(3))
    with pytest.raises(ValueError, match="K2 is singular"):
        fundamental_from_poses(K, R, np.zeros(3), np.diag([0, 1, 1.0]), R, np.ones(3))
    with pytest.raises(ValueError, match="R2 is not orthonormal"):
        fundamental_from_poses(K, R, np.zeros(3), K, 1.1 * R, np.ones(3))
    with pytest.raises(ValueError, match="zero baseline"):
        fundamental_from_poses(K, R, np.ones(3), K, R, np.ones(3))
    with pytest.raises(ValueError, match="c1 must have shape"):
        fundamental_from_poses(K, R, np.ones(2), K, R, np.ones(3))
    F = np.arange(9.0).reshape(3, 3)
    with pytest.raises(ValueError, match="pts1 must have shape"):
        epipolar_distances(F, np.zeros((3, 3)), np.zeros((2, 2)))
    with pytest.raises(ValueError, match="pts2 must have shape"):
        epipolar_distances(F, np.zeros((3, 2)), [1.0, 2.0])
    with pytest.raises(ValueError, match="F must be a 3x3"):
        epipolar_distances(np.eye(2), np.zeros((3, 2)), np.zeros((2, 2)))
    with pytest.raises(ValueError, match="zero matrix"):
        sampson_distances(np.zeros((3, 3)), np.zeros((3, 2)), np.zeros((2, 2)))
    with pytest.raises(ValueError, match="t must have shape"):
        cross_matrix([1, 2])


def test_non_finite_and_epipole_rejected_on_the_fast_path():
    rng = np.random.default_rng(3)
    F = rng.normal(size=(3, 3))
    p1 = rng.uniform(0, 512, (4, 2))
    p2 = rng.uniform(0, 512, (3, 2))
    for bad_F, bad_1, bad_2, what in ((F, p1, p2.copy(), "pts2"), (F, p1.copy(), p2, "pts1")):
        arr = bad_2 if what == "pts2" else bad_1
        arr[1, 0] = np.nan
        with pytest.raises(ValueError, match=what):
            epipolar_distances(bad_F, bad_1, bad_2)
    Fn = F.copy()
    Fn[2, 2] = np.inf
    with pytest.raises(ValueError, match="F"), np.errstate(all="ignore"):
        epipolar_distances(Fn, p1, p2)
    # a point at the epipole of image 1 has no epipolar line
    Fe = cross_matrix([0.0, 0.0, 1.0])  # epipole of image 1 at pixel (0, 0)
    at_epipole = np.vstack([p1, [0.0, 0.0]])
    with pytest.raises(ValueError, match="epipole"), np.errstate(all="ignore"):
        epipolar_distances(Fe, at_epipole, p2)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**31 - 1), st.integers(1, 40), st.integers(1, 40))
def test_fast_kernel_matches_opencv_to_1e6_px(seed, n1, n2):
    rng = np.random.default_rng(seed)
    F = rng.normal(size=(3, 3))
    p1 = rng.uniform(0, 512, (n1, 2))
    p2 = rng.uniform(0, 512, (n2, 2))
    lines = cv2.computeCorrespondEpilines(p1.reshape(-1, 1, 2), 1, F).reshape(-1, 3)
    ref = np.abs(lines[:, :2] @ p2.T + lines[:, 2:])
    got = epipolar_distances(F, p1, p2)
    assert got.shape == (n1, n2) and got.dtype == np.float64
    assert np.abs(got - ref).max() < 1e-6
    # lists and float32 input take the validated path and give the same numbers
    np.testing.assert_allclose(epipolar_distances(F.tolist(), p1.tolist(), p2), got)


def test_huge_F_scale_still_works():
    # the fast path's finiteness check can overflow for absurd scales; it then re-validates
    rng = np.random.default_rng(5)
    F = rng.normal(size=(3, 3))
    p1 = rng.uniform(0, 512, (4, 2))
    p2 = rng.uniform(0, 512, (3, 2))
    with np.errstate(over="ignore"):
        np.testing.assert_allclose(epipolar_distances(1e160 * F, p1, p2),
                                   epipolar_distances(F, p1, p2))


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**31 - 1), st.sampled_from([(2.0, 512), (10.0, 2048), (20.0, 1024)]))
def test_held_out_geo_ranges_short_baselines(seed, sensor):
    """Held out: sensors at LEO radius looking at GEO-range points (range/baseline 5–400,
    the paper's regime and beyond), random rolls, other fields of view and resolutions:
    true projections sit on their epipolar lines (≤ 1e-6 px) and the distances agree with
    OpenCV's epilines for random points."""
    fov, n = sensor
    rng = np.random.default_rng(seed)
    Kc = intrinsics_from_fov(fov, fov, n, n, n / 2 + rng.uniform(-20, 20),
                             n / 2 + rng.uniform(-20, 20))
    target = rng.normal(size=3)
    target *= 42164.0 / np.linalg.norm(target)
    c1 = rng.normal(size=3)
    c1 *= 7000.0 / np.linalg.norm(c1)
    c1 = c1 if c1 @ target > 0 else -c1
    base = rng.uniform(100.0, 7000.0)
    v = rng.normal(size=3)
    c2 = c1 + base * v / np.linalg.norm(v)
    R1 = look_at(target - c1, up=rng.normal(size=3))
    R2 = look_at(target - c2, up=rng.normal(size=3))
    rng_km = np.linalg.norm(target - c1)
    X = target + rng.normal(size=(20, 3)) * rng_km * np.radians(fov) / 8
    F = fundamental_from_poses(Kc, R1, c1, Kc, R2, c2)
    p1, p2 = project_points(X, Kc, R1, c1), project_points(X, Kc, R2, c2)
    assert np.diag(epipolar_distances(F, p1, p2)).max() < 1e-6
    q1, q2 = rng.uniform(0, n, (15, 2)), rng.uniform(0, n, (11, 2))
    lines = cv2.computeCorrespondEpilines(q1.reshape(-1, 1, 2), 1, F).reshape(-1, 3)
    np.testing.assert_allclose(epipolar_distances(F, q1, q2),
                               np.abs(lines[:, :2] @ q2.T + lines[:, 2:]), atol=1e-6)


def test_point_at_the_epipole_of_a_converging_pair_is_refused():
    """Held-out (review of issue 25): a wide-field converging pair whose epipole lies inside
    image 1. There F p1 is round-off, so distances would be arbitrary numbers; refused."""
    from eotrack.geometry import epipoles, fundamental_from_poses, intrinsics_from_fov
    from eotrack.geometry.rotations import look_at

    K = intrinsics_from_fov(20.0, 20.0, 1024, 1024, 512.0, 512.0)
    c1, c2 = np.zeros(3), np.array([0.1, 0.05, 1.0])
    target = np.array([0.0, 0.0, 20.0])
    up = (0.0, 1.0, 0.0)
    F = fundamental_from_poses(K, look_at(target - c1, up), c1, K, look_at(target - c2, up), c2)
    e1 = epipoles(F)[0]
    e1 = e1[:2] / e1[2] if e1.shape == (3,) else e1
    assert np.all((e1 > 0) & (e1 < 1024))  # the epipole is inside image 1
    p2 = np.array([[100.0, 200.0], [700.0, 300.0]])
    with pytest.raises(ValueError, match="epipole"):
        epipolar_distances(F, e1[None], p2)
    # a point one pixel away still has a well-defined line
    d = epipolar_distances(F, e1[None] + [1.0, 0.0], p2)
    assert np.all(np.isfinite(d))
