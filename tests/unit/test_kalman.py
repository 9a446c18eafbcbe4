"""Tests of eotrack.tracking.kalman."""

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
    is_positive_definite,
    kalman_filter,
    kalman_filter_batch,
    nees,
    nis,
    sage_husa_update,
    sage_husa_weight,
    singer_acceleration_variance,
    singer_process_noise,
    track_nearest,
    white_acceleration_noise,
)
from hypothesis import given, settings
from hypothesis import strategies as st

DT = 0.2


def _model():
    F, H = constant_acceleration_model(DT)
    Q = singer_process_noise(DT, 0.7, 4.0)
    R = np.array([[0.25, 0.02], [0.02, 0.3]])
    return F, H, Q, R, np.zeros(6), np.diag([1.0, 1, 50, 50, 20, 20])


def _zs(rng, n=120):
    t = np.arange(n) * DT
    truth = np.c_[10 * np.sin(0.7 * t), 5 * np.cos(0.5 * t)]
    return truth, truth + rng.normal(0, 0.5, truth.shape)


def test_ca_model_structure():
    F, H = constant_acceleration_model(0.5)
    x = np.array([1.0, 2, 3, 4, 5, 6])
    np.testing.assert_allclose(F @ x, [1 + 1.5 + 0.625, 2 + 2 + 0.75, 3 + 2.5, 4 + 3, 5, 6])
    assert H.shape == (2, 6)
    Fc, Hc = constant_velocity_model(0.5)
    assert Fc.shape == (4, 4) and Hc.shape == (2, 4)


def test_singer_variance_limits():
    # small alpha*dt: q_a -> sigma_w^2 dt; large: -> sigma_w^2 / (2 alpha)
    assert singer_acceleration_variance(1e-3, 1e-3, 2.0) == pytest.approx(4e-3, rel=1e-3)
    assert singer_acceleration_variance(100.0, 1.0, 2.0) == pytest.approx(2.0)
    Q = singer_process_noise(0.2, 1.0, 2.0)
    assert np.count_nonzero(Q) == 2 and Q[4, 4] == Q[5, 5] > 0


def test_matches_filterpy():
    from filterpy.kalman import KalmanFilter as FKF

    F, H, Q, R, x0, P0 = _model()
    _, zs = _zs(np.random.default_rng(0))
    zs[30:50] = np.nan
    xs, Ps = kalman_filter(zs, F, H, Q, R, x0, P0)
    f = FKF(6, 2)
    f.F, f.H, f.Q, f.R, f.x, f.P = F, H, Q, R, x0.copy(), P0.copy()
    m, c, _, _ = f.batch_filter([None if np.isnan(z[0]) else z for z in zs])
    np.testing.assert_allclose(xs, m, atol=1e-9)
    np.testing.assert_allclose(Ps, c, atol=1e-8)


def test_generic_path_and_step_class_agree():
    F, H, Q, R, x0, P0 = _model()
    _, zs = _zs(np.random.default_rng(1))
    xs, _ = kalman_filter(zs, F, H, Q, R, x0, P0)
    # a permuted state (H no longer a selector) takes the generic path
    perm = np.array([2, 0, 1, 3, 4, 5])
    Pm = np.eye(6)[perm]
    xs2, _ = kalman_filter(zs, Pm @ F @ Pm.T, H @ Pm.T, Pm @ Q @ Pm.T, R, Pm @ x0,
                           Pm @ P0 @ Pm.T)
    np.testing.assert_allclose(xs2 @ Pm, xs, atol=1e-9)
    kf = KalmanFilter(F, H, Q, R, x0, P0)
    for k, z in enumerate(zs):
        kf.predict()
        kf.update(z)
        assert np.allclose(kf.x, xs[k], atol=1e-8)


def test_batch_matches_single():
    F, H, Q, R, x0, P0 = _model()
    rng = np.random.default_rng(2)
    zb = np.stack([_zs(rng, 60)[1] for _ in range(4)])
    zb[1, 10:20] = np.nan
    zb[3, 40:] = np.nan
    xb, Pb = kalman_filter_batch(zb, F, H, Q, R, x0, P0, return_covariances=True)
    for i in range(4):
        xs, Ps = kalman_filter(zb[i], F, H, Q, R, x0, P0)
        np.testing.assert_allclose(xb[i], xs, atol=1e-8)
        np.testing.assert_allclose(Pb[i], Ps, atol=1e-7)


@pytest.mark.parametrize("axis_symmetric", [True, False])
def test_batch_independent_dropouts_match_single(axis_symmetric):
    F, H, Q, R, x0, P0 = _model()
    if axis_symmetric:                           # one 3 × 3 covariance per sequence
        R = 0.25 * np.eye(2)
    else:                                        # the general (d, d, B) path
        P0 = P0 + np.diag([0.5, 0, 0, 0, 0, 0])
    rng = np.random.default_rng(7)
    zb = np.stack([_zs(rng, 50)[1] for _ in range(6)])
    zb[rng.random(zb.shape[:2]) < 0.2] = np.nan
    xb, Pb = kalman_filter_batch(zb, F, H, Q, R, x0, P0, return_covariances=True)
    _, Pf = kalman_filter_batch(zb, F, H, Q, R, x0, P0)
    np.testing.assert_allclose(Pf, Pb[:, -1], atol=1e-12)
    for i in range(6):
        xs, Ps = kalman_filter(zb[i], F, H, Q, R, x0, P0)
        np.testing.assert_allclose(xb[i], xs, atol=1e-8)
        np.testing.assert_allclose(Pb[i], Ps, atol=1e-7)


def test_never_visible_is_pure_prediction():
    F, H, Q, R, x0, P0 = _model()
    x0 = np.array([1.0, 2, 0.5, 0, 0, 0])
    zs = np.full((20, 2), np.nan)
    xs, Ps = kalman_filter(zs, F, H, Q, R, x0, P0)
    np.testing.assert_allclose(xs[-1], np.linalg.matrix_power(F, 20) @ x0)
    assert np.all(np.diff([np.trace(P) for P in Ps]) > 0)
    res = track_nearest(ConfidenceKalmanFilter(F, H, Q, R, x0, P0), [np.zeros((0, 2))] * 20)
    assert np.all(res.modes == FilterMode.PREDICT)


def test_track_nearest_hold_and_gate():
    F, H, Q, R, _, P0 = _model()
    x0 = np.array([10.0, 10.0, 5.0, 0.0, 1.0, 0.0])
    dets = [np.zeros((0, 2))] * 40
    res = track_nearest(KalmanFilter(F, H, Q, R, x0, P0), dets, hold_after=5)
    assert np.all(res.xs[5:, 2:] == 0) and np.ptp(res.xs[5:, 0]) == 0
    free = track_nearest(KalmanFilter(F, H, Q, R, x0, P0), dets, hold_after=None)
    assert free.xs[-1, 0] > res.xs[-1, 0] + 50
    # a spot beyond the largest gate is never associated
    far = [np.array([[200.0, 200.0]])] * 5
    out = track_nearest(KalmanFilter(F, H, Q, R, x0, P0), far, gate_max_px=30.0)
    assert np.all(np.isnan(out.z))
    with pytest.raises(ValueError, match="gate_max_px"):
        track_nearest(KalmanFilter(F, H, Q, R, x0, P0), far, gate_px=10.0, gate_max_px=5.0)
    with pytest.raises(ValueError, match="c_img"):
        track_nearest(KalmanFilter(F, H, Q, R, x0, P0), far, c_img=[np.ones(1)])


def test_confidence_all_trusted_equals_standard():
    F, H, Q, R, x0, P0 = _model()
    _, zs = _zs(np.random.default_rng(3))
    xs, Ps = kalman_filter(zs, F, H, Q, R, x0, P0)
    cfg = ConfidenceConfig(omega=1.0, adaptive_noise=False)
    akf = ConfidenceKalmanFilter(F, H, Q, R, x0, P0, cfg)
    for k, z in enumerate(zs):
        akf.predict()
        assert akf.update(z, 1.0) == FilterMode.UPDATE
        np.testing.assert_allclose(akf.x, xs[k], atol=1e-8)
        np.testing.assert_allclose(akf.P, Ps[k], atol=1e-7)


def test_confidence_modes_reject_outlier():
    F, H, Q, R, x0, P0 = _model()
    truth, zs = _zs(np.random.default_rng(4), 60)
    akf = ConfidenceKalmanFilter(F, H, Q, R, x0, P0)
    modes = []
    for k, z in enumerate(zs):
        akf.predict()
        zz = z + (40.0 if k in (45, 50) else 0.0)
        modes.append(akf.update(zz, 0.2 if k == 45 else 1.0))
    # C = ω C_img + (1 − ω) C_motion: a far-off spot with a poor image is not used at all,
    # one with a perfect image only with λ R
    assert modes[45] == FilterMode.PREDICT
    assert modes[50] == FilterMode.INFLATED
    assert np.linalg.norm(akf.x[:2] - truth[-1]) < 3


@settings(max_examples=5, deadline=None)
@given(st.integers(0, 10_000))
def test_covariances_stay_spd_long_run(seed):
    """10^5 steps in total (5 examples × 20 000), with occlusions of up to 150 frames."""
    rng = np.random.default_rng(seed)
    F, H, Q, R, x0, P0 = _model()
    n = 20_000
    zs = np.cumsum(rng.normal(0, 0.3, (n, 2)), axis=0)
    start = rng.integers(0, n - 150, 40)
    for s0, length in zip(start, rng.integers(5, 150, 40)):
        zs[s0:s0 + length] = np.nan
    _, Ps = kalman_filter(zs, F, H, Q, R, x0, P0)
    assert np.allclose(Ps, np.swapaxes(Ps, 1, 2))
    assert np.all(np.linalg.eigvalsh(Ps[::50])[:, 0] > 0)
    akf = ConfidenceKalmanFilter(F, H, Q, R, x0, P0)
    for z in zs[:3000]:
        akf.predict()
        akf.update(None if np.isnan(z[0]) else z, 0.9)
        assert is_positive_definite(akf.P) and is_positive_definite(akf.R)


def test_sage_husa_weight_and_safeguard():
    assert sage_husa_weight(0, 0.97) == pytest.approx(1.0)
    assert sage_husa_weight(10_000, 0.97) == pytest.approx(0.03)
    F, H, Q, R, _, P0 = _model()
    P = P0.copy()
    K = P @ H.T @ np.linalg.inv(H @ P @ H.T + R)
    # a tiny innovation makes e e^T - H P H^T negative definite
    args = dict(e=np.zeros(2), K=K, H=H, F=F, P_prior=P, P_post=P, P_prev=P, d=1.0)
    Rraw, _ = sage_husa_update(R, Q, safeguard=False, **args)
    assert not is_positive_definite(Rraw)
    Rsafe, Qsafe = sage_husa_update(R, Q, q_structure=np.diag(Q) > 0, **args)
    assert is_positive_definite(Rsafe)
    assert np.all(np.linalg.eigvalsh(Qsafe) >= 0)


def test_nees_nis():
    P = np.stack([np.eye(2) * 4] * 3)
    e = np.array([[2.0, 0], [0, 0], [np.nan, 1]])
    out = nees(e, P)
    np.testing.assert_allclose(out[:2], [1.0, 0.0])
    assert np.isnan(out[2])
    assert nis(e[:2], P[:2])[0] == 1.0


def test_bad_inputs():
    F, H, Q, R, x0, P0 = _model()
    zs = np.zeros((5, 2))
    with pytest.raises(ValueError, match="Q"):
        kalman_filter(zs, F, H, np.ones((6, 5)), R, x0, P0)
    with pytest.raises(ValueError, match="R must be symmetric"):
        kalman_filter(zs, F, H, Q, np.array([[1.0, 0.5], [0.0, 1.0]]), x0, P0)
    with pytest.raises(ValueError, match="P0 must be positive definite"):
        kalman_filter(zs, F, H, Q, R, x0, -P0)
    with pytest.raises(ValueError, match="H must have 6 columns"):
        kalman_filter(zs, F, np.eye(2), Q, R, x0, P0)
    with pytest.raises(ValueError, match="zs must have shape"):
        kalman_filter(np.zeros((5, 3)), F, H, Q, R, x0, P0)
    with pytest.raises(ValueError, match="x0"):
        kalman_filter(zs, F, H, Q, R, np.zeros(5), P0)
    with pytest.raises(ValueError, match="zs"):
        kalman_filter_batch(zs, F, H, Q, R, x0, P0)
    with pytest.raises(ValueError, match="b must lie in"):
        sage_husa_weight(3, 1.0)
    with pytest.raises(ValueError, match="forgetting"):
        ConfidenceConfig(forgetting=0.0)
    with pytest.raises(ValueError, match="lam must be >= 1"):
        ConfidenceConfig(lam=0.5)
    with pytest.raises(ValueError, match="dt"):
        constant_acceleration_model(0.0)
    with pytest.raises(ValueError, match="alpha"):
        singer_process_noise(0.1, -1.0, 1.0)
    with pytest.raises(ValueError, match="q"):
        white_acceleration_noise(0.1, -1.0)
    with pytest.raises(TypeError, match="filt"):
        track_nearest("kf", [])
    with pytest.raises(ValueError, match="P must have shape"):
        nees(np.zeros((2, 2)), np.zeros((3, 2, 2)))
    with pytest.raises(ValueError, match="d must lie"):
        sage_husa_update(R, Q, e=np.zeros(2), K=np.zeros((6, 2)), H=H, F=F, P_prior=P0,
                         P_post=P0, P_prev=P0, d=0.0)


# ---- ConfidenceKalmanFilter on a user's noise scale (review of 05, finding 11) -------------

def _ca(sigma_px: float):
    F, H = constant_acceleration_model(0.2)
    Q = singer_process_noise(0.2, 0.7, 4.0)
    return F, H, Q, sigma_px ** 2 * np.eye(2), np.zeros(6), np.eye(6)


@pytest.mark.parametrize("sigma", [3.0, 6.0])
def test_confidence_filter_refuses_noise_outside_its_r_bounds(sigma):
    # a 3-6 px centroid noise with the default R bounds (≤ 1 px²) would be clipped silently to
    # 1 px² at the first update (1.7-2x the error of a plain KF): refuse, naming r_bounds
    F, H, Q, R, x0, P0 = _ca(sigma)
    with pytest.raises(ValueError, match="r_bounds"):
        ConfidenceKalmanFilter(F, H, Q, R, x0, P0)
    ok = ConfidenceKalmanFilter(F, H, Q, R, x0, P0,
                                ConfidenceConfig(r_bounds=(0.01, 100.0 * sigma ** 2)))
    assert np.allclose(ok.R, R)
    # without the adaptation there is nothing to clip
    ConfidenceKalmanFilter(F, H, Q, R, x0, P0, ConfidenceConfig(adaptive_noise=False))


def test_confidence_filter_keeps_a_large_noise_when_bounded_to_it():
    g = np.random.default_rng(5)
    F, H, Q, R, x0, P0 = _ca(3.0)
    t = np.arange(300) * 0.2
    truth = np.c_[3 * t + 20 * np.sin(0.5 * t), 10 * np.cos(0.3 * t)]
    zs = truth + g.normal(0, 3.0, truth.shape)
    kf = kalman_filter(zs, F, H, Q, R, x0, P0)[0][:, :2]
    ckf = ConfidenceKalmanFilter(F, H, Q, R, x0, P0, ConfidenceConfig(r_bounds=(0.1, 900.0)))
    xs = []
    for z in zs:
        ckf.predict()
        ckf.update(z, 1.0)
        xs.append(ckf.x[:2])
    e_kf = np.hypot(*(kf - truth).T).mean()
    e_ckf = np.hypot(*(np.array(xs) - truth).T).mean()
    assert np.linalg.eigvalsh(ckf.R).max() > 1.0          # not clipped to the 1 px² default
    assert e_ckf < 1.5 * e_kf


@pytest.mark.parametrize("c_img", [5.0, -1.0, float("nan")])
def test_confidence_filter_rejects_an_image_confidence_outside_0_1(c_img):
    F, H, Q, R, x0, P0 = _ca(0.5)
    akf = ConfidenceKalmanFilter(F, H, Q, R, x0, P0)
    akf.predict()
    with pytest.raises(ValueError, match="c_img"):
        akf.update(np.zeros(2), c_img)
    with pytest.raises(TypeError, match="c_img"):
        akf.update(np.zeros(2), "high")
