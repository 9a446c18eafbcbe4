"""Checkers of notebook 05's exercises: right answers pass, wrong ones fail, bad ones raise."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest
from eotrack.exercises import check, exercise_ids
from eotrack.experiments import akf_star as A

SLUG = "akf_star"


def _qa():
    # independent of the library: integrate d Var/dt = -2α Var + σ_w² numerically
    alpha, sw, dt = 1.5, 3.0, 0.5          # re-posed off the notebook's own setting
    v, h = 0.0, dt / 20000
    for _ in range(20000):
        v += h * (-2 * alpha * v + sw * sw)
    return v


def _d(k, b):
    return (1 - b) / (1 - b ** (k + 1))


@lru_cache(maxsize=1)
def _explore():
    return float(A.ExploreSession().errors("cloud", seed=0, occlusion_frames=25)["BEAK-ST"]
                 .mean())


_BASE = np.array([3.62, 3.48, 3.21, 3.75, 3.94])      # Table 1 as printed
_BEAK = np.array([1.63, 1.89, 1.58, 1.69, 1.81])


def _reduction():
    return float(np.median(100 * (1 - _BEAK / _BASE)))


RIGHT = {
    "akf_star.1": _qa,
    "akf_star.2": lambda: _d,
    "akf_star.3": lambda: float(A.diurnal_check(n_stars=60, min_alt_deg=30)["rel_error_paper"]
                                .median()),
    "akf_star.4": _explore,
    "akf_star.5": _reduction,
    "akf_star.6": lambda: "d",
}

WRONG = {
    "akf_star.1": lambda: 3.0 ** 2 * 0.5,                  # white-noise variance σ_w² ΔT... no decay
    "akf_star.2": lambda: (lambda k, b: (1 - b) / (1 - b ** k) if k else 1.0),  # printed form
    "akf_star.3": lambda: 0.05,                            # "a few per cent"
    "akf_star.4": lambda: _explore() * 1.5 + 1.0,
    "akf_star.5": lambda: 40.0,                            # the abstract's number
    "akf_star.6": lambda: "a",
}

BAD = {
    "akf_star.1": ("0.5", TypeError),
    "akf_star.2": (3.0, TypeError),
    "akf_star.3": (float("nan"), ValueError),
    "akf_star.4": ([1.0], TypeError),
    "akf_star.5": (np.inf, ValueError),
    "akf_star.6": ("e", ValueError),
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


def _ex3_other_mapping(kind):
    """Eq. (12)'s rates under another mapping of (u̇, v̇) onto (cos h·Ȧ, ḣ) — what a student
    who guesses the convention computes."""
    d = A.diurnal_check(n_stars=60, min_alt_deg=30)
    obs = np.c_[d["astropy_cosh_Adot"], d["astropy_hdot"]]
    p = np.c_[d["paper_cosh_Adot"], d["paper_hdot"]]
    p = {"swapped": p[:, ::-1], "sign": -p, "swapped sign": -p[:, ::-1]}[kind]
    return float(np.median(np.linalg.norm(p - obs, axis=1) / np.linalg.norm(obs, axis=1)))


@pytest.mark.parametrize("wrong", [
    lambda: float(A.diurnal_check()["rel_error_paper"].median()),   # the notebook's 30 stars
    lambda: _ex3_other_mapping("swapped"),
    lambda: _ex3_other_mapping("sign"),
    lambda: _ex3_other_mapping("swapped sign"),
    lambda: float(A.diurnal_check(n_stars=60, min_alt_deg=30)["rel_error_paper"].mean()),
])
def test_exercise3_rejects_other_star_sets_mappings_and_the_mean(wrong):
    assert not check("akf_star.3", wrong())


@pytest.mark.parametrize("wrong", [
    100 * (1 - _BEAK.mean() / _BASE.mean()),             # the reduction of the means (printed)
    float(np.mean(100 * (1 - _BEAK / _BASE))),           # mean of the reductions
    100 * (1 - np.median(_BEAK) / np.median(_BASE)),     # ratio of the medians
    float(np.median(1 - _BEAK / _BASE)),                 # a fraction, not per cent
    float(np.min(100 * (1 - _BEAK / _BASE))),            # the worst scenario
    40.0,
])
def test_exercise5_rejects_the_printed_mean_and_other_summaries(wrong):
    assert not check("akf_star.5", wrong)


@pytest.mark.parametrize("ex", sorted(BAD))
def test_bad_answer_raises(ex):
    value, exc = BAD[ex]
    with pytest.raises(exc):
        check(ex, value)


@pytest.mark.parametrize("written", ["d", "(d)", "d)", "[d]", "D.", " ( d ) ",
                                     "(d) for no observer", "d) for no observer"])
def test_exercise6_accepts_the_option_as_labelled(written):
    # the question labels its options "(a)" … "(d)": a student who copies the label is judged
    assert check("akf_star.6", written)


@pytest.mark.parametrize("written", ["(a)", "b)", "[c]", "(a) at the equator"])
def test_exercise6_labelled_wrong_options_fail(written):
    assert not check("akf_star.6", written)


@pytest.mark.parametrize("written", ["(e)", "(dd)", "", "d or a"])
def test_exercise6_not_an_option_raises(written):
    with pytest.raises(ValueError, match="expected one of"):
        check("akf_star.6", written)


def test_ex1_value_printed_in_the_notebook_is_wrong():
    """Exercise 1 is re-posed off the notebook's own eq. (34) check (α 0.7, σ_w 4, ΔT 0.2, whose
    q_a the notebook prints): copying that number must fail (review 28 round 3 #10)."""
    from eotrack.tracking.kalman import singer_acceleration_variance
    assert not check("akf_star.1", singer_acceleration_variance(0.2, 0.7, 4.0))
