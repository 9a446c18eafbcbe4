"""WRANSAC weighting readings, shared minimal samples (common random numbers), IRLS M-estimators."""

import numpy as np
import pytest
from eotrack.robust import (
    M_ESTIMATORS,
    REFITS,
    WEIGHTED_REFITS,
    SinusoidDrift,
    draw_samples,
    fit_linear,
    irls_linear,
    m_weights,
    predict_linear,
    ransac_linear,
    sinusoidal_loss,
    wransac_linear,
)
from hypothesis import given, settings
from hypothesis import strategies as st

T = np.arange(0.0, 7200.0, 90.0)
MODEL = SinusoidDrift(t_ref_s=3600.0)
THETA = np.array([40.0, -15.0, 3.0, 2.0])


def data(seed, frac=0.05, sigma=3.0):
    rng = np.random.default_rng(seed)
    y = predict_linear(MODEL, THETA, T) + sigma * rng.standard_normal(len(T))
    bad = rng.random(len(T)) < frac
    return y + np.where(bad, rng.uniform(100, 300, len(T)), 0.0), bad


def test_readings_are_registered():
    assert set(WEIGHTED_REFITS) <= set(REFITS)
    assert WEIGHTED_REFITS[0] == "weighted"


def test_shared_samples_make_methods_see_the_same_hypotheses():
    y, _ = data(0)
    idx = draw_samples(np.random.default_rng(1), len(T), 4, 50)
    a = ransac_linear(MODEL, T, y, threshold=9, n_hypotheses=50, rng=np.random.default_rng(2),
                      samples=idx)
    b = ransac_linear(MODEL, T, y, threshold=9, n_hypotheses=50, rng=np.random.default_rng(3),
                      samples=idx)
    np.testing.assert_array_equal(a.params, b.params)
    # the same samples as drawing with the generator that made them
    c = ransac_linear(MODEL, T, y, threshold=9, n_hypotheses=50, rng=np.random.default_rng(1))
    np.testing.assert_array_equal(a.params, c.params)


def test_hypothesis_reading_matches_hand_computation():
    y, _ = data(4)
    fit = wransac_linear(MODEL, T, y, threshold=9, n_hypotheses=100, rng=np.random.default_rng(0))
    e = y - predict_linear(MODEL, fit.hypothesis_params, T)
    w = np.where(np.abs(e) <= 9, 1 - sinusoidal_loss(e, 9), 0.0)
    np.testing.assert_allclose(fit.weights, w, atol=1e-12)
    np.testing.assert_allclose(fit.params, fit_linear(MODEL, T, y, weights=w), rtol=1e-10)
    assert fit.refit_iterations == 1


def test_refit_and_iterated_readings():
    y, _ = data(5)
    kw = {"threshold": 9.0, "n_hypotheses": 100}
    one = wransac_linear(MODEL, T, y, rng=np.random.default_rng(0), weighting="weighted_refit",
                         **kw)
    it = wransac_linear(MODEL, T, y, rng=np.random.default_rng(0),
                        weighting="weighted_iterated", **kw)
    # one step: weights from the OLS refit on the inliers
    ols = fit_linear(MODEL, T, y, weights=one.inliers.astype(float))
    e = y - predict_linear(MODEL, ols, T)
    w = np.where(one.inliers, 1 - sinusoidal_loss(e, 9.0), 0.0)
    np.testing.assert_allclose(one.params, fit_linear(MODEL, T, y, weights=w), rtol=1e-9)
    assert one.refit_iterations == 1
    # iterated: a fixed point of the weighting step
    e = y - predict_linear(MODEL, it.params, T)
    w = np.where(it.inliers, 1 - sinusoidal_loss(e, 9.0), 0.0)
    np.testing.assert_allclose(fit_linear(MODEL, T, y, weights=w), it.params, rtol=1e-6,
                               atol=1e-6)
    assert it.refit_iterations > 1


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_every_reading_recovers_noise_free_data(seed):
    rng = np.random.default_rng(seed)
    y = predict_linear(MODEL, THETA, T)
    y[rng.choice(len(T), 5, replace=False)] += 200.0
    for wt in WEIGHTED_REFITS:
        fit = wransac_linear(MODEL, T, y, threshold=1.0, n_hypotheses=200,
                             rng=np.random.default_rng(seed), weighting=wt)
        np.testing.assert_allclose(fit.params, THETA, atol=1e-6)


def test_samples_bad_input():
    y, _ = data(0)
    rng = np.random.default_rng(0)
    with pytest.raises(ValueError, match="samples must be an integer array"):
        ransac_linear(MODEL, T, y, threshold=9, n_hypotheses=3, rng=rng, samples=np.zeros((3, 3)))
    with pytest.raises(ValueError, match="rows but n_hypotheses"):
        ransac_linear(MODEL, T, y, threshold=9, n_hypotheses=4, rng=rng,
                      samples=np.zeros((3, 4), int))
    with pytest.raises(ValueError, match="samples must index"):
        ransac_linear(MODEL, T, y, threshold=9, n_hypotheses=1, rng=rng,
                      samples=np.array([[0, 1, 2, 500]]))
    with pytest.raises(ValueError, match="weighting must be one of"):
        wransac_linear(MODEL, T, y, threshold=9, n_hypotheses=3, rng=rng, weighting="lsq")


def test_m_weights_and_irls():
    u = np.array([0.0, 1.0, 3.0, 10.0])
    for kind in M_ESTIMATORS:
        w = m_weights(u, kind)
        assert w[0] == 1.0 and np.all(np.diff(w) <= 0) and np.all(w >= 0)
    y, _bad = data(7, frac=0.1)
    start = ransac_linear(MODEL, T, y, threshold=9, n_hypotheses=200,
                          rng=np.random.default_rng(0)).params
    for kind in ("huber", "cauchy", "tukey"):
        th = irls_linear(MODEL, T, y, start, scale=3.0, kind=kind)
        assert np.max(np.abs(predict_linear(MODEL, th - THETA, T))) < 10.0
    with pytest.raises(ValueError, match="kind must be one of"):
        m_weights(u, "bisquare")
    with pytest.raises(ValueError, match="theta0 must have shape"):
        irls_linear(MODEL, T, y, np.zeros(3), scale=3.0)
    with pytest.raises(ValueError, match="scale must be"):
        irls_linear(MODEL, T, y, start, scale=0.0)
