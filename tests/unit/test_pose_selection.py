"""Unit tests for eotrack.pose.selection (CRLB feature selection, budgeted design)."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.pose import (
    attitude_matrix,
    crlb_weight_matrix,
    greedy_design,
    information_monotonicity,
    intrinsic_matrix,
    pose_crlb,
    project_points,
    quaternion_crlb,
    select_features_crlb,
    set_score,
)
from hypothesis import given, settings
from hypothesis import strategies as st

K0 = intrinsic_matrix(10.0)
R0 = attitude_matrix([15, 20, 10])
T0 = np.array([1.0, 1.2, 10.0])


def _pts(seed, n=60):
    rng = np.random.default_rng(seed)
    X = np.c_[rng.uniform(-1, 1, (n, 2)), np.full(n, -1.0)]
    sig = np.where(rng.random(n) < 0.5, 0.01, 0.03)
    r = rng.normal(size=(n, 2)) * sig[:, None]
    return X, sig, r


def test_score_is_weighted_sum_of_seven_crlbs():
    X, sig, _ = _pts(0)
    C7 = quaternion_crlb(X, R0, T0, K0, sig)
    w = np.arange(1.0, 8.0)
    assert set_score(X, R0, T0, K0, rule="exact", sigma_px=sig, weights=w) == pytest.approx(
        float(w @ np.diag(C7)), rel=1e-9)
    W = crlb_weight_matrix(R0, w)
    assert np.trace(W @ pose_crlb(X, R0, T0, K0, sig)) == pytest.approx(float(w @ np.diag(C7)))


@given(st.integers(0, 10_000))
@settings(max_examples=20, deadline=None)
def test_exact_score_monotone_and_rule_keeps_everything(seed):
    X, sig, _r = _pts(seed, 30)
    rng = np.random.default_rng(seed)
    s = information_monotonicity(X, R0, T0, K0, sig, rng.permutation(30))
    assert np.all(np.diff(s) <= 1e-12 * s[0])
    sel = select_features_crlb(X, R0, T0, K0, rng, rule="exact", start="per_point",
                               sigma_px=sig)
    assert sel.fallback or sel.selected.all()
    printed = select_features_crlb(X, R0, T0, K0, rng, rule="exact", start="paper",
                                   sigma_px=sig, max_draws=20)
    assert printed.fallback and printed.selected.all() and printed.n_draws == 20


def test_pooled_and_sandwich_drop_noisy_points():
    X, sig, r = _pts(1, 120)
    rng = np.random.default_rng(2)
    for rule in ("pooled", "sandwich"):
        sel = select_features_crlb(X, R0, T0, K0, rng, rule=rule, sigma_px=sig, residuals=r)
        assert not sel.fallback
        assert 6 <= sel.n_selected < 120
        assert sel.score_selected < sel.score_all
        # kept points are on average the less noisy ones
        assert sig[sel.selected].mean() < sig.mean()


def test_tolerance_rule_keeps_fewer():
    X, sig, _r = _pts(3, 100)
    sel = select_features_crlb(X, R0, T0, K0, np.random.default_rng(0), rule="tolerance",
                               sigma_px=sig, tol=0.02)
    assert sel.n_selected < 100


def test_greedy_design_beats_random():
    X, sig, _ = _pts(4, 100)
    for crit in ("D", "A"):
        idx = greedy_design(X, R0, T0, K0, 10, sig, criterion=crit)
        assert len(set(idx.tolist())) == 10
        best = set_score(X[idx], R0, T0, K0, sigma_px=sig[idx])
        rng = np.random.default_rng(5)
        rand = [set_score(X[j], R0, T0, K0, sigma_px=sig[j])
                for j in (rng.choice(100, 10, replace=False) for _ in range(20))]
        assert best < np.median(rand)


def test_bad_inputs():
    X, sig, r = _pts(6, 20)
    rng = np.random.default_rng(0)
    with pytest.raises(ValueError, match="rule must be one of"):
        select_features_crlb(X, R0, T0, K0, rng, rule="bogus")
    with pytest.raises(ValueError, match="start must be one of"):
        select_features_crlb(X, R0, T0, K0, rng, start="bogus", residuals=r)
    with pytest.raises(ValueError, match="residuals"):
        select_features_crlb(X, R0, T0, K0, rng, rule="pooled")
    with pytest.raises(ValueError, match="sigma_px is required"):
        select_features_crlb(X, R0, T0, K0, rng, rule="exact")
    with pytest.raises(ValueError, match="at least 6"):
        select_features_crlb(X[:5], R0, T0, K0, rng, residuals=r[:5])
    with pytest.raises(ValueError, match="sigma_px must be > 0"):
        set_score(X, R0, T0, K0, rule="exact", sigma_px=-sig)
    with pytest.raises(ValueError, match="weights must be >= 0"):
        crlb_weight_matrix(R0, -np.ones(7))
    with pytest.raises(ValueError, match="order must be a permutation"):
        information_monotonicity(X, R0, T0, K0, sig, order=np.zeros(20, int))
    with pytest.raises(ValueError, match="k must be"):
        greedy_design(X, R0, T0, K0, 50, sig)
    with pytest.raises(ValueError, match="criterion must be one of"):
        greedy_design(X, R0, T0, K0, 8, sig, criterion="E")
    with pytest.raises(ValueError, match="order must be one of"):
        select_features_crlb(X, R0, T0, K0, rng, residuals=r, order="bogus")
    with pytest.raises(ValueError, match="behind the camera"):
        set_score(X, R0, [0, 0, -10.0], K0, rule="exact", sigma_px=sig)
    assert project_points(X, R0, T0, K0).shape == (20, 2)


def test_scaled_weights_make_the_score_unit_free():
    """Unit weights add m² to quaternion²; scaled weights give the same selection in any unit."""
    from eotrack.pose import (
        attitude_matrix,
        intrinsic_matrix,
        scaled_crlb_weights,
        score_shares,
        set_score,
    )

    rng = np.random.default_rng(3)
    X = rng.uniform(-1, 1, (40, 3))
    R, t, K = attitude_matrix([10, 20, 30]), np.array([0.5, -0.3, 9.0]), intrinsic_matrix(800.0)
    sig = rng.uniform(0.3, 1.5, 40)
    w = scaled_crlb_weights(np.linalg.norm(t))
    np.testing.assert_allclose(w, [1 / 81.34] * 3 + [1] * 4, rtol=1e-3)
    # the same scene in mm: unit-weight score changes by 1e6 in its t part, scaled does not
    mm = 1e3
    s_m = set_score(X[:10], R, t, K, sigma_px=sig[:10], weights=w)
    s_mm = set_score(X[:10] * mm, R, t * mm, K, sigma_px=sig[:10],
                     weights=scaled_crlb_weights(np.linalg.norm(t * mm)))
    assert s_mm == pytest.approx(s_m, rel=1e-6)
    u_m = set_score(X[:10], R, t, K, sigma_px=sig[:10])
    u_mm = set_score(X[:10] * mm, R, t * mm, K, sigma_px=sig[:10])
    assert u_mm / u_m > 1e5
    sh = score_shares(X, R, t, K, sig)
    assert sh["translation"] + sh["quaternion"] == pytest.approx(1.0)
    assert score_shares(X, R, t, K, sig, w)["translation"] < sh["translation"]
    with pytest.raises(ValueError, match="length_m"):
        scaled_crlb_weights(0.0)
    with pytest.raises(ValueError, match="weights"):
        score_shares(X, R, t, K, sig, weights=np.ones(6))
