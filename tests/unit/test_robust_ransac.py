"""The vectorised RANSAC engine and the linear trajectory models."""

import numpy as np
import pytest
from eotrack.robust import (
    Polynomial,
    SinusoidDrift,
    draw_samples,
    fit_free_sinusoid,
    fit_linear,
    get_loss,
    predict_linear,
    ransac,
    ransac_linear,
    wransac_linear,
)
from hypothesis import given, settings
from hypothesis import strategies as st

T = np.arange(0.0, 7200.0, 90.0)


def corrupt(rng, y, frac):
    y = y.copy()
    k = round(frac * len(y))
    idx = rng.choice(len(y), k, replace=False)
    y[idx] += rng.uniform(50, 500, k) * rng.choice([-1, 1], k)
    return y, idx


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), frac=st.floats(0.0, 0.3),
       theta=st.lists(st.floats(-100, 100), min_size=4, max_size=4))
def test_exact_recovery_up_to_30_percent_outliers(seed, frac, theta):
    rng = np.random.default_rng(seed)
    model = SinusoidDrift(t_ref_s=3600.0)
    y, out = corrupt(rng, predict_linear(model, np.array(theta), T), frac)
    for fit in (ransac_linear(model, T, y, threshold=1e-3, n_hypotheses=300, rng=rng),
                wransac_linear(model, T, y, threshold=1e-3, n_hypotheses=300, rng=rng)):
        np.testing.assert_allclose(predict_linear(model, fit.params, T[fit.inliers]),
                                   y[fit.inliers], atol=1e-6)
        assert not fit.inliers[out].any()
        assert fit.n_inliers == len(T) - len(out)


def test_polynomial_recovery_and_weights():
    rng = np.random.default_rng(1)
    m = Polynomial(2, t_ref_s=3600)
    y, _ = corrupt(rng, predict_linear(m, np.array([1.0, 2.0, -3.0]), T), 0.2)
    r = ransac_linear(m, T, y, threshold=1e-6, n_hypotheses=200, rng=rng)
    np.testing.assert_allclose(r.params, [1, 2, -3], atol=1e-8)
    assert set(np.unique(r.weights)) <= {0.0, 1.0}
    w = wransac_linear(m, T, y + rng.normal(0, 0.1, len(T)), threshold=0.5, n_hypotheses=200,
                       rng=rng)
    assert np.all((w.weights >= 0) & (w.weights <= 1))
    assert np.all(w.weights[~w.inliers] == 0)


def test_deterministic_given_seed():
    m = SinusoidDrift(t_ref_s=3600.0)
    y = predict_linear(m, np.array([5.0, 1.0, 2.0, 3.0]), T) + np.random.default_rng(0).normal(
        0, 3, len(T))
    a = wransac_linear(m, T, y, threshold=9, n_hypotheses=50, rng=np.random.default_rng(7))
    b = wransac_linear(m, T, y, threshold=9, n_hypotheses=50, rng=np.random.default_rng(7))
    np.testing.assert_array_equal(a.params, b.params)


def test_degenerate_samples_are_skipped():
    x = np.r_[np.zeros(10), np.arange(1.0, 5.0)]
    y = 2 * x + 1
    r = ransac_linear(Polynomial(1, time_scale_s=1.0), x, y, threshold=1e-9, n_hypotheses=200,
                      rng=np.random.default_rng(0))
    assert r.n_valid < 200
    np.testing.assert_allclose(r.params, [1, 2], atol=1e-9)


def test_all_degenerate_raises():
    with pytest.raises(ValueError, match="no minimal sample gave a well-posed fit"):
        ransac_linear(Polynomial(1), np.zeros(10), np.arange(10.0), threshold=1.0,
                      n_hypotheses=10, rng=np.random.default_rng(0))


def test_draw_samples_distinct():
    s = draw_samples(np.random.default_rng(0), 10, 4, 500)
    assert s.shape == (500, 4)
    assert all(len(set(row)) == 4 for row in s)
    with pytest.raises(ValueError, match="sample_size must be <= 10"):
        draw_samples(np.random.default_rng(0), 10, 11, 5)


def test_free_sinusoid_recovers_frequency():
    t = np.linspace(0, 86400, 200)
    y = 40 * np.sin(7.3e-5 * (t - t.mean()) + 0.3) + 5
    f = fit_free_sinusoid(t, y)
    assert f.omega_rad_s == pytest.approx(7.3e-5, rel=1e-6)
    np.testing.assert_allclose(f(t), y, atol=1e-6)


@pytest.mark.parametrize(("kw", "exc", "match"), [
    ({"threshold": -1.0}, ValueError, "threshold must be"),
    ({"n_hypotheses": 0}, ValueError, "n_hypotheses must be >= 1"),
    ({"loss": "cauchy"}, ValueError, "loss must be one of"),
    ({"rng": 3}, TypeError, "rng must be a numpy.random.Generator"),
])
def test_ransac_bad_input(kw, exc, match):
    args = {"threshold": 1.0, "n_hypotheses": 10, "rng": np.random.default_rng(0)}
    args.update(kw)
    with pytest.raises(exc, match=match):
        ransac_linear(SinusoidDrift(), T, np.zeros_like(T), **args)


def test_ransac_bad_data():
    rng = np.random.default_rng(0)
    with pytest.raises(ValueError, match="x and y must have the same length"):
        ransac_linear(SinusoidDrift(), T, np.zeros(3), threshold=1, n_hypotheses=3, rng=rng)
    with pytest.raises(ValueError, match="y contains NaN"):
        ransac_linear(SinusoidDrift(), T, np.full_like(T, np.nan), threshold=1, n_hypotheses=3,
                      rng=rng)
    with pytest.raises(ValueError, match="need at least sample_size=4"):
        ransac_linear(SinusoidDrift(), T[:3], np.zeros(3), threshold=1, n_hypotheses=3, rng=rng)
    with pytest.raises(ValueError, match="weighting must be one of"):
        ransac(T, np.zeros_like(T), sample_size=2, fit_batch=None, residuals_batch=None,
               refit=None, threshold=1, n_hypotheses=2, rng=rng, weighting="irls")


def test_models_bad_input():
    with pytest.raises(ValueError, match="omega_rad_s must be"):
        SinusoidDrift(omega_rad_s=0)
    with pytest.raises(ValueError, match="degree must be <= 12"):
        Polynomial(20)
    with pytest.raises(TypeError, match="model must be a linear model"):
        fit_linear(object(), T, T)
    with pytest.raises(ValueError, match="weights must be >= 0"):
        fit_linear(Polynomial(1), T, T, weights=-np.ones_like(T))
    with pytest.raises(ValueError, match="need at least 2 points"):
        fit_linear(Polynomial(1), T, T, weights=np.r_[1.0, np.zeros(len(T) - 1)])
    with pytest.raises(ValueError, match="theta must have 4 parameters"):
        predict_linear(SinusoidDrift(), np.zeros(3), T)
    with pytest.raises(ValueError, match="need at least 4 points"):
        fit_free_sinusoid(T[:3], T[:3])


@pytest.mark.parametrize("loss", ["msac", "msac_squared", "sinusoidal"])
@pytest.mark.parametrize("order", [(0, 1), (1, 0)])
def test_selects_minimum_cost_not_largest_inlier_set(loss, order):
    """With a graded loss the best hypothesis is the one of least cost Σ L(e), which here has
    fewer inliers than the other (a mutation keeping the largest inlier set fails this)."""
    # constant model, t = 1: hypothesis B (c = 0) has 11 inliers and a small cost; hypothesis A
    # (c = 0.9) has all 13 points within t but large residuals on ten of them
    y = np.r_[0.9, np.zeros(10), 1.5, 1.5]
    x = np.arange(len(y), dtype=float)
    model = Polynomial(0, t_ref_s=0.0)
    samples = np.array([[0], [1]])[list(order)]
    fit = ransac_linear(model, x, y, threshold=1.0, n_hypotheses=2,
                        rng=np.random.default_rng(0), loss=loss, samples=samples)
    assert fit.hypothesis_params[0] == pytest.approx(0.0)
    assert fit.n_inliers == 11
    costs = {c: get_loss(loss)(y - c, 1.0).sum() for c in (0.0, 0.9)}
    assert fit.cost == pytest.approx(costs[0.0]) and costs[0.0] < costs[0.9]
    # with the 0-1 loss, minimum cost *is* the largest inlier set: hypothesis A
    zo = ransac_linear(model, x, y, threshold=1.0, n_hypotheses=2,
                       rng=np.random.default_rng(0), loss="zero_one", samples=samples)
    assert zo.hypothesis_params[0] == pytest.approx(0.9) and zo.n_inliers == 13
