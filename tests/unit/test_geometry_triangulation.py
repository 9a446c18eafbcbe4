"""Triangulation of rays and the combination of pairwise estimates (§3)."""

import numpy as np
import pytest
from eotrack.geometry import (
    combine_estimates,
    max_z_score,
    triangulate_rays,
    triangulate_two_rays,
)
from hypothesis import given, settings
from hypothesis import strategies as st


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**31 - 1), st.integers(2, 6))
def test_exact_without_noise(seed, n):
    rng = np.random.default_rng(seed)
    X = rng.normal(size=3) * 1000
    orig = rng.normal(size=(n, 3)) * 100
    D = (X - orig) * rng.uniform(0.1, 10, (n, 1))
    assert np.allclose(triangulate_rays(orig, D), X, atol=1e-6 * 1000)
    mid, gap = triangulate_two_rays(orig[0], D[0], orig[1], D[1], return_gap=True)
    assert np.allclose(mid, X, atol=1e-6 * 1000) and gap < 1e-6


def test_two_rays_midpoint_and_vectorised():
    mid, gap = triangulate_two_rays([0, 0, 0], [1, 0, 0], [0, 1, 2], [0, 0, 1], return_gap=True)
    assert np.allclose(mid, [0, 0.5, 0]) and gap == pytest.approx(1.0)
    o1 = np.zeros((4, 3))
    d1 = np.tile([1.0, 0, 0], (4, 1))
    o2 = np.tile([5.0, -1, 0], (4, 1))
    d2 = np.tile([0.0, 1, 0], (4, 1))
    assert np.allclose(triangulate_two_rays(o1, d1, o2, d2), [[5, 0, 0]] * 4)


def test_paper_3sigma_rule_cannot_reject_small_samples():
    est = np.array([[0.0, 0, 0], [0.1, 0, 0], [500.0, 0, 0]])
    assert max_z_score(3) < 3
    assert combine_estimates(est, rule="paper").kept.all()
    mad = combine_estimates(est, rule="mad", scale_floor_km=0.5)
    assert mad.kept.tolist() == [True, True, False]
    assert np.allclose(mad.position, [0.05, 0, 0])
    gate = combine_estimates(est, rule="gate", gate_km=5.0)
    assert gate.kept.tolist() == [True, True, False]
    many = np.vstack([np.zeros((11, 3)), [[100.0, 0, 0]]])
    assert max_z_score(12) > 3
    assert combine_estimates(many, rule="paper").kept.tolist() == [True] * 11 + [False]


def test_bad_input():
    with pytest.raises(ValueError, match="parallel"):
        triangulate_two_rays([0, 0, 0], [1, 0, 0], [0, 1, 0], [2, 0, 0])
    with pytest.raises(ValueError, match="d1 contains a zero"):
        triangulate_two_rays([0, 0, 0], [0, 0, 0], [0, 1, 0], [2, 0, 0])
    with pytest.raises(ValueError, match="o1 must end in 3"):
        triangulate_two_rays([0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1])
    with pytest.raises(ValueError, match="origins needs at least 2"):
        triangulate_rays([[0, 0, 0]], [[1, 0, 0]])
    with pytest.raises(ValueError, match="origins and directions"):
        triangulate_rays(np.zeros((2, 3)), np.ones((3, 3)))
    with pytest.raises(ValueError, match="nearly\\) parallel"):
        triangulate_rays([[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 0, 0]])
    with pytest.raises(ValueError, match="rule must be one of"):
        combine_estimates(np.zeros((2, 3)), rule="median")
    with pytest.raises(ValueError, match="gate_km is required"):
        combine_estimates(np.zeros((2, 3)), rule="gate")
    with pytest.raises(ValueError, match="estimates must have shape"):
        combine_estimates(np.zeros((2, 2)))
    with pytest.raises(ValueError, match="k must be finite"):
        combine_estimates(np.zeros((2, 3)), k=-1)
    with pytest.raises(ValueError, match="n must be >= 2"):
        max_z_score(1)


def test_closest_points_ends_of_common_perpendicular():
    from eotrack.geometry import closest_points_two_rays

    q1, q2 = closest_points_two_rays([0, 0, 0], [1, 0, 0], [0, 1, 2], [0, 0, 1])
    assert np.allclose(q1, [0, 0, 0]) and np.allclose(q2, [0, 1, 0])
    rng = np.random.default_rng(0)
    o1, o2 = rng.normal(size=(2, 5, 3))
    d1, d2 = rng.normal(size=(2, 5, 3))
    q1, q2 = closest_points_two_rays(o1, d1, o2, d2)
    seg = q2 - q1
    # the segment is perpendicular to both rays, and its midpoint is the triangulation
    assert np.allclose(np.einsum("ni,ni->n", seg, d1), 0, atol=1e-9)
    assert np.allclose(np.einsum("ni,ni->n", seg, d2), 0, atol=1e-9)
    assert np.allclose(0.5 * (q1 + q2), triangulate_two_rays(o1, d1, o2, d2))
    with pytest.raises(ValueError, match="parallel"):
        closest_points_two_rays([0, 0, 0], [1, 0, 0], [0, 1, 0], [2, 0, 0])
    with pytest.raises(ValueError, match="d1"):
        closest_points_two_rays([0, 0, 0], [0, 0, 0], [0, 1, 0], [1, 0, 0])
    with pytest.raises(ValueError, match="o1 must end in 3"):
        closest_points_two_rays([0, 0], [1, 0, 0], [0, 1, 0], [1, 0, 0])


def test_held_out_short_baseline_error_scaling():
    """Held out: the range error of two-ray triangulation under angular noise ε grows as
    ε·R²/B (range R, baseline B) — the reason the paper's short baselines hurt. Checked over
    baselines 100–3000 km at GEO range, against the first-order prediction σ_R ≈ √2·ε·R²/B
    (the difference of two independent in-plane angular errors) to within a factor 2 on the
    median."""
    rng = np.random.default_rng(7)
    eps = 1e-5  # rad, per axis
    R = 36000.0
    for B in (100.0, 500.0, 3000.0):
        errs = []
        for _ in range(400):
            X = np.array([0.0, 0.0, R])
            o1, o2 = np.array([-B / 2, 0, 0]), np.array([B / 2, 0, 0])
            d1 = X - o1 + rng.normal(size=3) * eps * R
            d2 = X - o2 + rng.normal(size=3) * eps * R
            errs.append(np.linalg.norm(triangulate_two_rays(o1, d1, o2, d2) - X))
        # first order: the in-plane angular errors (σ = ε each, two rays) move the
        # intersection along the line of sight by R²/B per radian of their difference
        pred = eps * np.sqrt(2) * R**2 / B
        med = np.median(errs) / 0.6745  # median |N(0, σ)| = 0.6745 σ
        assert 0.5 < med / pred < 2.0, (B, med, pred)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**31 - 1), st.integers(2, 8))
def test_held_out_rays_match_least_squares_reference(seed, n):
    """Held out: noisy rays from random origins; triangulate_rays equals the independent
    normal-equation solution Σ(I − d dᵀ) X = Σ(I − d dᵀ) o."""
    rng = np.random.default_rng(seed)
    X = rng.normal(size=3) * 4e4
    o = rng.normal(size=(n, 3)) * 7e3
    d = X - o + rng.normal(size=(n, 3)) * 50.0
    u = d / np.linalg.norm(d, axis=1, keepdims=True)
    A = sum(np.eye(3) - np.outer(ui, ui) for ui in u)
    b = sum((np.eye(3) - np.outer(ui, ui)) @ oi for ui, oi in zip(u, o))
    ref = np.linalg.solve(A, b)
    np.testing.assert_allclose(triangulate_rays(o, d), ref, rtol=1e-7, atol=1e-6)


def test_robust_rules_need_three_estimates_and_refuse_an_empty_result():
    two = np.array([[0.0, 0, 0], [100.0, 0, 0]])
    # n = 2: the median is the midpoint, so "gate" keeps both or none, "mad" keeps both
    assert combine_estimates(two, rule="gate", gate_km=60.0).kept.tolist() == [True, True]
    assert combine_estimates(two, rule="mad").kept.tolist() == [True, True]
    with pytest.raises(ValueError, match="no estimate survives"):
        combine_estimates(two, rule="gate", gate_km=1.0)
    three = np.array([[0.0, 0, 0], [1.0, 0, 0], [100.0, 0, 0]])
    assert combine_estimates(three, rule="gate", gate_km=5.0).kept.tolist() == [True, True, False]
