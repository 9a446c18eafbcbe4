"""Checkers of notebook 02's exercises: right answers pass, wrong ones fail, bad ones raise."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.exercises import check, exercise_ids
from eotrack.experiments import epipolar as E

SLUG = "epipolar"


def _right_2(F, p1, p2):
    h1 = np.column_stack([p1, np.ones(len(p1))])
    h2 = np.column_stack([p2, np.ones(len(p2))])
    lines = h1 @ F.T
    return np.abs(lines @ h2.T) / np.hypot(lines[:, 0], lines[:, 1])[:, None]


def _right_1():
    # independent of the module: scan n until (n - 1)/sqrt(n) exceeds 3
    return next(n for n in range(2, 100) if (n - 1) / np.sqrt(n) > 3)


def _right_3():
    st = E.threshold_study()
    th = np.linspace(0, st.l_max, 241)
    return float(th[np.argmin(st.rates(th)["total"])])


RIGHT = {
    "epipolar.1": _right_1,
    "epipolar.2": lambda: _right_2,
    "epipolar.3": _right_3,
    "epipolar.4": lambda: 0.01 * 512 / (2 * np.tan(np.radians(1.0))),
    "epipolar.5": lambda: E.error_budget_gate(
        E.build_scenario(), E.ErrorConfig(attitude_arcmin=np.sqrt(3.0)))[1],
}

WRONG = {
    "epipolar.1": lambda: 10,  # the off-by-one: (10 - 1)/sqrt(10) < 3
    "epipolar.2": lambda: (lambda F, p1, p2: np.abs(
        np.column_stack([p2, np.ones(len(p2))]) @ F
        @ np.column_stack([p1, np.ones(len(p1))]).T).T),  # algebraic, not normalised
    "epipolar.3": lambda: 10.0,  # the paper's threshold
    "epipolar.4": lambda: 0.01 * 206264.8 / 14.06 / 1000,  # mrad read as µrad
    "epipolar.5": lambda: E.error_budget_gate(E.build_scenario(), E.ErrorConfig())[1],
}


def test_at_least_four_exercises():
    assert len(exercise_ids(SLUG)) >= 4
    assert set(exercise_ids(SLUG)) == set(RIGHT) == set(WRONG)


@pytest.mark.parametrize("ex", sorted(RIGHT))
def test_right_answer_passes(ex):
    assert check(ex, RIGHT[ex]())


@pytest.mark.parametrize("ex", sorted(WRONG))
def test_wrong_answer_fails(ex):
    assert not check(ex, WRONG[ex]())


@pytest.mark.parametrize("ex", ["epipolar.1", "epipolar.3", "epipolar.4", "epipolar.5"])
def test_numeric_bad_type_raises(ex):
    with pytest.raises(TypeError):
        check(ex, "ten")
    with pytest.raises(ValueError):
        check(ex, float("nan"))


def test_function_bad_type_raises():
    with pytest.raises(TypeError):
        check("epipolar.2", 3.0)


def test_function_that_crashes_is_wrong():
    def broken(F, p1, p2):
        raise RuntimeError("not implemented")

    assert not check("epipolar.2", broken)
