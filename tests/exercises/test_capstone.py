"""Checkers of notebook 07's exercises: right answers pass, wrong ones fail, bad ones raise."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.exercises import check, exercise_ids

SLUG = "capstone"
RAD = 180 / np.pi * 3600


RIGHT = {
    # independent of the module: the formulas written out
    "capstone.1": lambda: 37_000.0 ** 2 * (1.0 / RAD) / 4_900.0,
    "capstone.2": lambda: 7.292115e-5 * 20.0 * RAD * np.cos(np.radians(30.0)) / 15.0,
    "capstone.3": lambda: 10 ** (-0.4 * (12.5 - 21.0)) / (2 * np.pi) / np.sqrt(6400 + 64),
    "capstone.4": lambda: "B",
    "capstone.5": lambda: _p_in(0.5, np.sqrt(2) * 0.3),
    "capstone.6": lambda: 1.5 * _max_rate() / 5.0,
}

WRONG = {
    "capstone.1": lambda: 37_000.0 * (1.0 / RAD) * 4_900.0,  # R σ B, not R² σ / B
    "capstone.2": lambda: 15.04 * 20.0 * np.cos(np.radians(30.0)),  # arcseconds, not pixels
    "capstone.3": lambda: 10 ** (-0.4 * (12.5 - 21.0)) / np.sqrt(6400),  # total flux, not peak
    "capstone.4": lambda: "D",
    "capstone.5": lambda: _p_in(0.5, 0.3),  # one point's σ, not √2 σ
    "capstone.6": lambda: 1.5 * _max_rate() / 15.0,  # the 15″/px gate
}

WRONG_MORE = {
    "capstone.2": [lambda: 7.292115e-5 * 20.0 * RAD / 15.0,  # cos δ forgotten
                   lambda: 2 * np.pi / 86400 * 20 * RAD * np.cos(np.radians(30.0)) / 15,  # solar
                   lambda: 15.0 * 20 * np.cos(np.radians(30.0)) / 15,  # 15″/s, not sidereal
                   lambda: 7.292115e-5 * 20.0 * RAD * np.sin(np.radians(30.0)) / 15.0],
    "capstone.5": [lambda: 1 - _p_in(0.5, np.sqrt(2) * 0.3),  # outside, not inside
                   lambda: 0.99],  # the true pair's probability
    "capstone.6": [lambda: _max_rate() / 5.0,  # no margin
                   lambda: 1.5 * _max_rate()],  # ″/s, not px/s
}


def _p_in(d0, sigma_e):
    """P(|d0 + ε| < g), ε ~ N(0, sigma_e²), g the χ²(1) 99 % gate of √2 × 0.3 px."""
    from scipy.stats import chi2, norm

    g = np.sqrt(2) * 0.3 * np.sqrt(chi2.ppf(0.99, 1))
    return norm.cdf((g - d0) / sigma_e) - norm.cdf((-g - d0) / sigma_e)


def _max_rate():
    from eotrack.experiments import capstone as C

    return float(C.expected_rates().to_numpy().max())


def test_at_least_four_exercises():
    assert len(exercise_ids(SLUG)) >= 4
    assert set(exercise_ids(SLUG)) == set(RIGHT) == set(WRONG)


@pytest.mark.parametrize("ex", sorted(RIGHT))
def test_right_answer_passes(ex):
    assert check(ex, RIGHT[ex]())


@pytest.mark.parametrize("ex", sorted(WRONG))
def test_wrong_answer_fails(ex):
    assert not check(ex, WRONG[ex]())


@pytest.mark.parametrize("ex", sorted(WRONG_MORE))
def test_more_wrong_answers_fail(ex):
    for wrong in WRONG_MORE[ex]:
        assert not check(ex, wrong())


@pytest.mark.parametrize("ex", ["capstone.1", "capstone.2", "capstone.3", "capstone.5",
                                "capstone.6"])
def test_numeric_bad_type_raises(ex):
    with pytest.raises(TypeError):
        check(ex, "ten")
    with pytest.raises(ValueError):
        check(ex, float("nan"))


def test_choice_bad_answer_raises():
    with pytest.raises(ValueError):
        check("capstone.4", "E")
