"""Checkers of notebook 06's exercises: right answers pass, wrong fail, bad types raise."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.exercises import check, exercise_ids
from eotrack.exercises import ransac_crlb_pose as ex

SLUG = "ransac_crlb_pose"


def test_at_least_four_exercises():
    assert len(exercise_ids(SLUG)) >= 4


def _j1(convention="camera", sigma_power=2, use_R=True):
    """J₁ by hand, with the mistakes a student makes."""
    X, t = np.array(ex.EX1["X"]), np.array(ex.EX1["t"])
    R = ex._ex1_R() if use_R else np.eye(3)
    f, s = ex.EX1["f_mm"], ex.EX1["sigma_mm"]
    xc = R @ X + t
    u = f * xc[:2] / xc[2]
    D = np.array([[f, 0, -u[0]], [0, f, -u[1]]]) / xc[2]

    def sk(v):
        return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])

    dth = -sk(R @ X) if convention == "camera" else -R @ sk(X)
    G = D @ np.hstack([np.eye(3), dth])
    return G.T @ G / s**sigma_power


def test_ex1_fisher_one_point():
    right = ex._ex1_expected()
    assert check(f"{SLUG}.1", right)
    assert check(f"{SLUG}.1", _j1())
    assert np.linalg.matrix_rank(right) == 2
    assert not np.allclose(ex._ex1_R(), np.eye(3))
    assert not check(f"{SLUG}.1", 2 * right)
    # the body-frame perturbation −R[X]ₓ (another convention) is rejected now that R ≠ I
    assert not check(f"{SLUG}.1", _j1(convention="body"))
    # dividing by σ instead of σ², or ignoring R
    assert not check(f"{SLUG}.1", _j1(sigma_power=1))
    assert not check(f"{SLUG}.1", _j1(use_R=False))
    with pytest.raises(ValueError):
        check(f"{SLUG}.1", np.eye(3))
    with pytest.raises(TypeError):
        check(f"{SLUG}.1", "J")


def test_ex2_ratio():
    from eotrack.experiments.ransac_crlb_pose import Scenario, make_scene
    from eotrack.pose import pose_crlb, quaternion_crlb

    right = ex._ex2_expected()
    assert right > 1
    assert check(f"{SLUG}.2", right)
    assert not check(f"{SLUG}.2", 1.0)
    sc = Scenario()
    s = make_scene(np.random.default_rng(0), sc, outlier_fraction=0.0)
    # the unit-dependent answers: the 6×6 trace (m² + rad²) and the unit-weight 7-value sum
    tr6 = (np.trace(pose_crlb(s.points[:6], sc.R, sc.t, sc.K, s.sigma[:6]))
           / np.trace(pose_crlb(s.points, sc.R, sc.t, sc.K, s.sigma)))
    unit7 = (np.trace(quaternion_crlb(s.points[:6], sc.R, sc.t, sc.K, s.sigma[:6]))
             / np.trace(quaternion_crlb(s.points, sc.R, sc.t, sc.K, s.sigma)))
    assert not check(f"{SLUG}.2", tr6)
    assert not check(f"{SLUG}.2", unit7)
    assert not check(f"{SLUG}.2", 1.0 / right)   # inverted ratio
    with pytest.raises(TypeError):
        check(f"{SLUG}.2", "big")


def test_ex3_function():
    from eotrack.pose import information_monotonicity

    assert check(f"{SLUG}.3", ex.points_needed)
    assert not check(f"{SLUG}.3", lambda *a: 6)

    def unit_weights(points, R, t, K, sigma, frac):   # the score of the old exercise (m² + q²)
        s = information_monotonicity(points, R, t, K, sigma)
        return int(6 + np.flatnonzero(s <= (1.0 + frac) * s[-1])[0])

    def off_by_one(points, R, t, K, sigma, frac):
        return ex.points_needed(points, R, t, K, sigma, frac) + 1

    assert not check(f"{SLUG}.3", unit_weights)
    assert not check(f"{SLUG}.3", off_by_one)
    with pytest.raises(TypeError):
        check(f"{SLUG}.3", 42)


def test_ex4_exploration():
    from eotrack.experiments import ransac_crlb_pose as E

    right = ex._ex4_expected()
    assert check(f"{SLUG}.4", right)
    assert right[0] < 1 < right[1]   # 24 runs cannot tell the ratio from 1
    assert check(f"{SLUG}.4", np.array(E.bootstrap_ratio_ci(
        *_ex4_pair(0.01), seed=1)))   # another bootstrap seed is still right
    assert not check(f"{SLUG}.4", np.array(E.bootstrap_ratio_ci(*_ex4_pair(1.0), seed=0)))
    a, b = _ex4_pair(0.01)
    assert not check(f"{SLUG}.4", np.array(E.bootstrap_ratio_ci(b, a, seed=0)))   # inverse
    assert not check(f"{SLUG}.4", np.array([a.mean() / b.mean()] * 2))  # point estimate only
    with pytest.raises(ValueError):
        check(f"{SLUG}.4", np.array([1.0]))


def _ex4_pair(unit):
    from eotrack.experiments import ransac_crlb_pose as E

    att, _ = E.explore_selection(unit, "pooled", 0.01)
    return att, np.array([r["att_ransac"] for r in E.explore_runs(unit)])


@pytest.mark.parametrize("k, right, wrongs", [(5, "b", "acd"), (6, "b", "acd")])
def test_choices(k, right, wrongs):
    """Ex. 5: the tempting 'a noisy point raises the score' is wrong; ex. 6: recalling our
    actual choice ('pooled', c) is wrong for the changed model."""
    assert check(f"{SLUG}.{k}", right)
    for wrong in wrongs:
        assert not check(f"{SLUG}.{k}", wrong)
    with pytest.raises(ValueError):
        check(f"{SLUG}.{k}", "z")
