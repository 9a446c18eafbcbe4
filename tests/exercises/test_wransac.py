"""Checkers of notebook 01's exercises: right answers pass, wrong ones fail, bad ones raise."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest
from eotrack.exercises import check, exercise_ids
from eotrack.experiments import wransac as W
from eotrack.montecarlo import TrialRunner

SLUG = "wransac"


def _gm72():
    # independent of the library's gauss_markov: the normal equations by hand
    sc = W.make_scenario()
    t = sc.t_obs_s
    tau = t - t.mean()
    w = 7.2921150e-5

    def row(x):
        x = np.atleast_1d(x) - t.mean()
        return np.stack([np.sin(w * x), np.cos(w * x), np.ones_like(x), x / 3600.0], -1)

    a = row(t)
    ap = row(t[-1] + 72 * 60.0)[0]
    assert a.shape == (len(tau), 4)
    return 3.0 * float(np.sqrt(ap @ np.linalg.solve(a.T @ a, ap)))


@lru_cache(maxsize=1)
def _budget_u3():
    err = W.budget_sweep(budgets=W.BUDGETS, methods=W.BUDGET_METHODS,
                         runner=TrialRunner(progress=False))
    return float(W.budget_table(err, W.BUDGETS, W.BUDGET_METHODS).loc[3, "ransac"])


def _wls(a, y, w):
    a, y, w = (np.asarray(v, float) for v in (a, y, w))
    return np.linalg.solve(a.T @ (w[:, None] * a), a.T @ (w * y))


RIGHT = {
    "wransac.1": lambda: (5 + 3) * (5 - 2) / (5 * (5 + 1)),
    "wransac.2": _gm72,
    "wransac.3": _budget_u3,
    "wransac.4": lambda: "b",
    "wransac.5": lambda: _wls,
}

WRONG = {
    "wransac.1": lambda: 1.0,  # "OLS is already optimal"
    "wransac.2": lambda: 3.0,  # σ itself: forgets the extrapolation leverage
    "wransac.3": lambda: _budget_u3() + 0.2,
    "wransac.4": lambda: "a",
    "wransac.5": lambda: (lambda a, y, w: np.linalg.lstsq(np.asarray(a), np.asarray(y),
                                                          rcond=None)[0]),  # ignores w
}

BAD = {
    "wransac.1": ("0.8", TypeError),
    "wransac.2": (float("nan"), ValueError),
    "wransac.3": ([0.5], TypeError),
    "wransac.4": ("e", ValueError),
    "wransac.5": (3.0, TypeError),
}


def test_at_least_four():
    assert len(exercise_ids(SLUG)) >= 4
    assert sorted(RIGHT) == exercise_ids(SLUG)


@pytest.mark.parametrize("ex", sorted(RIGHT))
def test_right_answer_passes(ex):
    assert check(ex, RIGHT[ex]())


@pytest.mark.parametrize("ex", sorted(WRONG))
def test_wrong_answer_fails(ex):
    res = check(ex, WRONG[ex]())
    assert not res
    assert "hint" in res.message


@pytest.mark.parametrize("ex", sorted(BAD))
def test_bad_answer_raises(ex):
    value, exc = BAD[ex]
    with pytest.raises(exc):
        check(ex, value)
