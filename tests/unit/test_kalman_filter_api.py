"""KalmanFilter as a user drives it (the FilterPy habits): public matrices set between steps,
per-step F/Q for irregular time steps, missing (NaN) measurements — each against FilterPy."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.tracking.kalman import (
    ConfidenceConfig,
    ConfidenceKalmanFilter,
    FilterMode,
    KalmanFilter,
    constant_acceleration_model,
    constant_velocity_model,
    kalman_filter,
    white_acceleration_noise,
)

FPKF = pytest.importorskip("filterpy.kalman").KalmanFilter


def _pair(dt=0.2, q=3.0, r=0.5):
    F, H = constant_velocity_model(dt)
    Q = white_acceleration_noise(dt, q)
    R = r * np.eye(2)
    x0 = np.array([1.0, -2.0, 3.0, 0.5])
    P0 = np.diag([4.0, 4.0, 9.0, 9.0])
    ours = KalmanFilter(F, H, Q, R, x0, P0)
    fp = FPKF(dim_x=4, dim_z=2)
    fp.F, fp.H, fp.Q, fp.R, fp.x, fp.P = F, H, Q, R, x0.copy(), P0.copy()
    return ours, fp


def test_setting_F_and_Q_before_predict_matches_filterpy():
    ours, fp = _pair()
    rng = np.random.default_rng(1)
    for _ in range(30):
        dt = rng.uniform(0.05, 0.6)
        F, _ = constant_velocity_model(dt)
        Q = white_acceleration_noise(dt, 3.0)
        ours.F, ours.Q = F, Q
        fp.F, fp.Q = F, Q
        ours.predict()
        fp.predict()
        z = rng.normal(0, 1, 2) + ours.x[:2]
        ours.update(z)
        fp.update(z)
        np.testing.assert_allclose(ours.x, fp.x, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(ours.P, fp.P, rtol=1e-9, atol=1e-9)


def test_changed_F_is_used_not_a_cached_transpose():
    ours, _ = _pair(dt=0.2)
    F2, _ = constant_velocity_model(0.8)
    ours.F = F2
    P = ours.P.copy()
    ours.predict()
    np.testing.assert_allclose(ours.P, F2 @ P @ F2.T + ours.Q)


def test_per_step_F_Q_matches_filterpy_and_leaves_stored_ones():
    ours, fp = _pair()
    F_stored = ours.F.copy()
    rng = np.random.default_rng(2)
    dts = rng.uniform(0.05, 1.0, 25)
    zs = np.cumsum(rng.normal(0, 1, (25, 2)), axis=0)
    for dt, z in zip(dts, zs):
        F, _ = constant_velocity_model(dt)
        Q = white_acceleration_noise(dt, 3.0)
        ours.predict(F=F, Q=Q)
        fp.predict(F=F, Q=Q)
        ours.update(z)
        fp.update(z)
    np.testing.assert_allclose(ours.x, fp.x, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(ours.P, fp.P, rtol=1e-9, atol=1e-9)
    np.testing.assert_array_equal(ours.F, F_stored)


def test_kalman_filter_per_step_stacks_match_filterpy():
    rng = np.random.default_rng(3)
    n = 40
    dts = rng.uniform(0.05, 1.0, n)
    Fs = np.stack([constant_velocity_model(dt)[0] for dt in dts])
    Qs = np.stack([white_acceleration_noise(dt, 2.0) for dt in dts])
    _, H = constant_velocity_model(1.0)
    R = 0.3 * np.eye(2)
    x0, P0 = np.zeros(4), 10 * np.eye(4)
    zs = np.cumsum(rng.normal(0, 1, (n, 2)), axis=0)
    zs[7] = np.nan
    xs, Ps = kalman_filter(zs, Fs, H, Qs, R, x0, P0)
    fp = FPKF(dim_x=4, dim_z=2)
    fp.H, fp.R, fp.x, fp.P = H, R, x0.copy(), P0.copy()
    for k in range(n):
        fp.predict(F=Fs[k], Q=Qs[k])
        fp.update(None if np.isnan(zs[k]).any() else zs[k])
        np.testing.assert_allclose(xs[k], fp.x, rtol=1e-8, atol=1e-8)
        np.testing.assert_allclose(Ps[k], fp.P, rtol=1e-8, atol=1e-8)
    # a constant stack equals the constant-matrix filter
    xc, _ = kalman_filter(zs, np.broadcast_to(Fs[0], Fs.shape), H, Qs[0], R, x0, P0)
    xk, _ = kalman_filter(zs, Fs[0], H, Qs[0], R, x0, P0)
    np.testing.assert_allclose(xc, xk, rtol=1e-9, atol=1e-9)
    with pytest.raises(ValueError, match="F as a per-step stack"):
        kalman_filter(zs, Fs[:-1], H, Qs, R, x0, P0)


@pytest.mark.parametrize("z", [np.array([np.nan, 1.0]), np.array([np.nan, np.nan]), None])
def test_nan_measurement_is_missing(z):
    ours, fp = _pair()
    ours.predict()
    fp.predict()
    x_pred = ours.x.copy()
    assert ours.update(z) == FilterMode.PREDICT
    fp.update(None)
    assert np.all(np.isfinite(ours.x))
    np.testing.assert_allclose(ours.x, x_pred)
    np.testing.assert_allclose(ours.P, fp.P, rtol=1e-12)


def test_nan_measurement_is_missing_in_confidence_filter():
    F, H = constant_acceleration_model(0.2)
    f = ConfidenceKalmanFilter(F, H, np.diag([0, 0, 0, 0, 1.0, 1.0]), 0.25 * np.eye(2),
                               np.zeros(6), np.eye(6), ConfidenceConfig())
    f.predict()
    assert f.update(np.array([np.nan, 0.0])) == FilterMode.PREDICT
    assert np.all(np.isfinite(f.x)) and f.n_missed == 1


def test_confidence_filter_uses_assigned_Q_and_per_step_F():
    F, H = constant_acceleration_model(0.2)
    Q = np.diag([0, 0, 0, 0, 1.0, 1.0])
    f = ConfidenceKalmanFilter(F, H, Q, 0.25 * np.eye(2), np.zeros(6), np.eye(6))
    f.Q = 4 * Q
    P = f.P.copy()
    f.predict()
    np.testing.assert_allclose(f.P, F @ P @ F.T + 4 * Q)
    F2, _ = constant_acceleration_model(0.7)
    P = f.P.copy()
    f.predict(F=F2)
    np.testing.assert_allclose(f.P, F2 @ P @ F2.T + 4 * Q)
    np.testing.assert_array_equal(f.Q_base, f.Q)


def test_bad_assignments_and_measurements_raise():
    ours, _ = _pair()
    with pytest.raises(ValueError, match="F must have shape"):
        ours.F = np.eye(3)
    with pytest.raises(ValueError, match="Q"):
        ours.Q = -np.eye(4)
    with pytest.raises(ValueError, match="R must be positive definite"):
        ours.R = np.zeros((2, 2))
    with pytest.raises(ValueError, match="H must have shape"):
        ours.H = np.eye(4)
    with pytest.raises(ValueError, match="F"):
        ours.F = np.full((4, 4), np.nan)
    with pytest.raises(ValueError, match="Q"):
        ours.predict(Q=np.ones((4, 3)))
    ours.predict()
    with pytest.raises(ValueError, match="z must be finite"):
        ours.update(np.array([np.inf, 0.0]))
    with pytest.raises(ValueError, match="z must have shape"):
        ours.update(np.zeros(3))
    with pytest.raises(TypeError, match="z must be a numeric"):
        ours.update("ab")
    assert np.all(np.isfinite(ours.x))


def test_column_state_from_filterpy_is_flattened_and_matches_filterpy():
    """FilterPy's x is a (d, 1) column: assigning one must not broadcast (2,) − (2, 1) into a
    (4, 2) state (review of issue 28, finding 3)."""
    ours, fp = _pair()
    col = np.array([[0.0], [1.0], [0.0], [-1.0]])
    ours.x = col
    fp.x = col.copy()
    assert ours.x.shape == (4,)
    for z in ([1.0, 2.0], [1.3, 1.6], [1.1, 1.4]):
        ours.predict()
        fp.predict()
        assert ours.update(np.array(z)) == FilterMode.UPDATE
        fp.update(np.array(z))
        assert ours.x.shape == (4,)
        np.testing.assert_allclose(ours.x, fp.x[:, 0], atol=1e-12)
        np.testing.assert_allclose(ours.P, fp.P, atol=1e-12)


@pytest.mark.parametrize("bad", [np.zeros((4, 2)), np.zeros(3), np.zeros((1, 4)), [np.nan] * 4])
def test_bad_state_assignment_raises(bad):
    ours, _ = _pair()
    with pytest.raises(ValueError, match="x"):
        ours.x = bad


@pytest.mark.parametrize("bad", [np.zeros((3, 3)), -np.eye(4), np.triu(np.ones((4, 4))),
                                 np.full((4, 4), np.nan)])
def test_bad_covariance_assignment_raises(bad):
    ours, _ = _pair()
    with pytest.raises(ValueError, match="P"):
        ours.P = bad


@pytest.mark.parametrize("name", ["F", "H", "Q", "R", "x", "P", "x_prior", "P_prior"])
@pytest.mark.parametrize("cls", [KalmanFilter, ConfidenceKalmanFilter])
def test_in_place_edits_cannot_bypass_validation(name, cls):
    F, H = constant_acceleration_model(0.2)
    kf = cls(F, H, np.eye(6) * 0.1, 0.5 * np.eye(2), np.zeros(6), np.eye(6))
    kf.predict()
    kf.update(np.array([0.1, -0.1]))
    arr = getattr(kf, name)
    before = arr.copy()
    with pytest.raises(ValueError, match="read-only"):
        arr[(0,) * arr.ndim] = -5.0
    np.testing.assert_array_equal(getattr(kf, name), before)
    if name in ("Q", "P"):                 # a whole new array is validated
        with pytest.raises(ValueError, match="semi-definite"):
            setattr(kf, name, -np.eye(6))
