"""Intrinsics (eqs. 6–7), projection, back-projection, distortion against OpenCV."""

import cv2
import numpy as np
import pytest
from eotrack.geometry import (
    PinholeCamera,
    check_intrinsics,
    distort_normalized,
    intrinsics_from_focal,
    intrinsics_from_fov,
    look_at,
    opencv_coefficients,
    pixel_rays,
    project_points,
    undistort_pixels,
)

K = intrinsics_from_fov(2.0, 2.0, 512, 512, 252.44, 235.33)
DIST = np.array([-0.2, 0.05, 1e-3, -2e-3])  # strong enough to test the model


def test_intrinsics_eq6_eq7():
    k = intrinsics_from_focal(50.0, 0.005, 0.005, 256, 256)
    assert k[0, 0] == pytest.approx(10000.0)
    # eq. 7: a 2° field over 512 px
    assert K[0, 0] == pytest.approx(512 / (2 * np.tan(np.radians(1.0))))
    assert K[0, 2] == 252.44 and K[1, 2] == 235.33
    k2 = intrinsics_from_fov(20, 10, 1024, 512)
    assert k2[0, 2] == pytest.approx(511.5)


def test_projection_matches_opencv():
    rng = np.random.default_rng(0)
    R = look_at([1.0, 0.2, 0.1])
    c = np.array([10.0, -5.0, 3.0])
    X = c + (R.T @ np.column_stack([rng.uniform(-0.3, 0.3, (20, 2)), np.ones(20)]).T).T * 100
    ours = project_points(X, K, R, c, DIST)
    rvec, _ = cv2.Rodrigues(R)
    ref, _ = cv2.projectPoints(X, rvec, -R @ c, K, DIST)
    assert np.allclose(ours, ref.reshape(-1, 2), atol=1e-6)


def test_distortion_roundtrip_with_opencv_undistort():
    rng = np.random.default_rng(1)
    xy = rng.uniform(-0.2, 0.2, (30, 2))
    d = distort_normalized(xy, DIST)
    uv = d @ K[:2, :2].T + K[:2, 2]
    back = undistort_pixels(uv, K, DIST)
    assert np.allclose(back, xy @ K[:2, :2].T + K[:2, 2], atol=1e-4)


def test_paper_coefficients_are_negligible_for_2deg_sensor():
    dist = opencv_coefficients((-4.85e-5, -1.45e-5), (4.63e-5, -3.04e-7))
    assert np.allclose(dist, [-4.85e-5, -1.45e-5, 4.63e-5, -3.04e-7])
    corner = np.array([[np.tan(np.radians(1)), np.tan(np.radians(1))]])
    shift = (distort_normalized(corner, dist) - corner) * K[0, 0]
    assert np.abs(shift).max() < 0.01


def test_rays_invert_projection():
    R = look_at([0.3, -1, 0.2])
    c = np.array([1.0, 2.0, 3.0])
    X = c + 1000 * np.array([[0.3, -1, 0.2], [0.31, -1, 0.21]])
    uv = project_points(X, K, R, c, DIST)
    d = pixel_rays(uv, K, R, DIST)
    want = (X - c) / np.linalg.norm(X - c, axis=1, keepdims=True)
    assert np.allclose(d, want, atol=1e-9)


def test_camera_sees_and_empty_input():
    cam = PinholeCamera(K, look_at([0, 0, 1], up=[0, 1, 0]), np.zeros(3))
    assert cam.sees([[0, 0, 10.0], [0, 0, -10.0], [10, 0, 10]]).tolist() == [True, False, False]
    assert cam.project(np.zeros((0, 3))).shape == (0, 2)
    assert cam.rays(np.zeros((0, 2))).shape == (0, 3)


def test_bad_input():
    with pytest.raises(ValueError, match="K must be a 3x3"):
        check_intrinsics(np.eye(4))
    with pytest.raises(ValueError, match="singular"):
        check_intrinsics(np.diag([0.0, 1.0, 1.0]))
    with pytest.raises(ValueError, match="last row"):
        check_intrinsics([[1, 0, 0], [0, 1, 0], [1, 0, 1]])
    with pytest.raises(ValueError, match="fov_x_deg"):
        intrinsics_from_fov(0, 2, 512, 512)
    with pytest.raises(ValueError, match="fov_x_deg and fov_y_deg must be < 180"):
        intrinsics_from_fov(190, 2, 512, 512)
    with pytest.raises(ValueError, match="f_mm"):
        intrinsics_from_focal(-1, 1, 1, 0, 0)
    with pytest.raises(ValueError, match="X_world must have shape"):
        project_points(np.zeros((3, 2)), K, np.eye(3), np.zeros(3))
    with pytest.raises(ValueError, match="R is not orthonormal"):
        project_points(np.zeros((1, 3)), K, 2 * np.eye(3), np.zeros(3))
    with pytest.raises(ValueError, match="dist must hold 4 or 5"):
        distort_normalized(np.zeros((1, 2)), [1, 2])
    with pytest.raises(ValueError, match="radial"):
        opencv_coefficients((1, 2, 3))
    with pytest.raises(ValueError, match="pts must have shape"):
        pixel_rays(np.zeros((2, 3)), K, np.eye(3))
    with pytest.raises(ValueError, match="c must have shape"):
        PinholeCamera(K, np.eye(3), np.zeros(2))
