"""Checkers of notebook 01's exercises: right answers pass, wrong ones fail, bad ones raise."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.exercises import check, exercise_ids
from eotrack.exercises import wransac as _checker
from eotrack.experiments import wransac as W
from eotrack.montecarlo import TrialRunner
from scipy.stats import f as f_dist

SLUG = "wransac"


def _design(t_ref):
    w = 7.2921150e-5

    def row(x):
        x = np.atleast_1d(x) - t_ref
        return np.stack([np.sin(w * x), np.cos(w * x), np.ones_like(x), x / 3600.0], -1)

    return row


def _gm(n_inliers: int, minutes: float, sigma: float = 3.0, from_last_inlier: bool = False):
    # independent of the library's gauss_markov: the normal equations by hand
    sc = W.make_scenario()
    t = sc.t_obs_s
    row = _design(t.mean())
    a = row(t[:n_inliers])
    t0 = t[n_inliers - 1] if from_last_inlier else t[-1]
    ap = row(t0 + minutes * 60.0)[0]
    return sigma * float(np.sqrt(ap @ np.linalg.solve(a.T @ a, ap)))


def _budget_err():
    # the checker's cached sweep (computed once); the arithmetic below is independent of it
    return _checker._budget_errors()


def _within(u: int, method: str, bound: float) -> float:
    # by hand from the error array: each run's worst |error| over the 72-min grid
    e = _budget_err()[:, W.BUDGETS.index(u), _checker.BUDGET_CHECK_METHODS.index(method)]
    return float(np.mean(np.abs(e).max(axis=-1) <= bound))


def _ratio():
    return _checker._paired_ratio_72_dec()  # the checker's cached 300 paired runs


def test_budget_subset_matches_the_notebooks_sweep():
    """The checker sweeps only two methods; with common random numbers their errors are those
    of the notebook's full sweep (few runs here)."""
    kw = dict(budgets=W.BUDGETS, n_runs=3, runner=TrialRunner(progress=False))
    full = W.budget_sweep(methods=W.BUDGET_METHODS, **kw)
    sub = W.budget_sweep(methods=_checker.BUDGET_CHECK_METHODS, **kw)
    for j, m in enumerate(_checker.BUDGET_CHECK_METHODS):
        np.testing.assert_array_equal(sub[:, :, j], full[:, :, W.BUDGET_METHODS.index(m)])


def _wls(a, y, w):
    a, y, w = (np.asarray(v, float) for v in (a, y, w))
    return np.linalg.solve(a.T @ (w[:, None] * a), a.T @ (w * y))


RIGHT = {
    "wransac.1": lambda: (-1 + np.sqrt(241)) / 2,  # ν² + ν − 60 = 0
    "wransac.2": lambda: _gm(60, 45),
    "wransac.3": lambda: _within(10, "wransac_hypothesis", 20.0),
    "wransac.4": lambda: float(f_dist.cdf(1 / _ratio(), 19, 19)),
    "wransac.5": lambda: _wls,
}

# the wrong answers a student would give, each with its mistake
WRONG = [
    ("wransac.1", lambda: 0.8),  # the fraction at ν = 5, not a ν
    ("wransac.1", lambda: 0.9),  # the fraction itself
    ("wransac.1", lambda: 7.0),  # rounded down
    ("wransac.1", lambda: 8.0),  # the smallest integer ν above it
    ("wransac.1", lambda: (-1 - np.sqrt(241)) / 2),  # the other root
    ("wransac.1", lambda: 5.0),  # the ν of the old exercise
    ("wransac.2", lambda: 3.0),  # σ itself: forgets the extrapolation leverage
    ("wransac.2", lambda: _gm(80, 45)),  # ignores the clouds: all 80 points inliers
    ("wransac.2", lambda: _gm(80, 72)),  # the all-inlier 72-min value printed in section 4.7
    ("wransac.2", lambda: _gm(60, 45) ** 2),  # a variance, not a standard deviation
    ("wransac.2", lambda: _gm(60, 45, from_last_inlier=True)),  # 45 min after the 60th point
    ("wransac.3", lambda: _within(10, "wransac_hypothesis", 27.0)),  # the table's 27″ bound
    ("wransac.3", lambda: _within(3, "wransac_hypothesis", 20.0)),  # U = 3, the paper's
    ("wransac.3", lambda: _within(30, "wransac_hypothesis", 20.0)),  # the next budget
    ("wransac.3", lambda: _within(10, "ransac", 20.0)),  # RANSAC, not WRANSAC
    ("wransac.3", lambda: 100 * _within(10, "wransac_hypothesis", 20.0)),  # a percentage
    ("wransac.4", lambda: 0.5),  # "a coin toss"
    ("wransac.4", lambda: float(f_dist.cdf(_ratio(), 19, 19))),  # P(ratio estimate < r)
    ("wransac.4", lambda: float(f_dist.cdf(1 / _ratio(), 20, 20))),  # 20 dof, not 19
    ("wransac.4", lambda: float(1 - f_dist.cdf(1 / _ratio(), 19, 19))),  # the complement
    ("wransac.5", lambda: (lambda a, y, w: np.linalg.lstsq(np.asarray(a), np.asarray(y),
                                                           rcond=None)[0])),  # ignores w
]

BAD = {
    "wransac.1": ("7.26", TypeError),
    "wransac.2": (float("nan"), ValueError),
    "wransac.3": ([0.5], TypeError),
    "wransac.4": ("0.1", TypeError),
    "wransac.5": (3.0, TypeError),
}


def test_at_least_four():
    assert len(exercise_ids(SLUG)) >= 4
    assert sorted(RIGHT) == exercise_ids(SLUG)


@pytest.mark.parametrize("ex", sorted(RIGHT))
def test_right_answer_passes(ex):
    assert check(ex, RIGHT[ex]())


@pytest.mark.parametrize(("ex", "wrong"), WRONG)
def test_wrong_answer_fails(ex, wrong):
    res = check(ex, wrong())
    assert not res
    assert "hint" in res.message


@pytest.mark.parametrize("ex", sorted(BAD))
def test_bad_answer_raises(ex):
    value, exc = BAD[ex]
    with pytest.raises(exc):
        check(ex, value)
