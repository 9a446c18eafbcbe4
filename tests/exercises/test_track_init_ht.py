"""Checkers of notebook 03's exercises: right answers pass, wrong ones fail, bad ones raise."""

from __future__ import annotations

import math

import numpy as np
import pytest
from eotrack.exercises import check, exercise_ids
from eotrack.experiments.track_init_ht import paper_settings
from eotrack.tracking import hypothesis as hyp
from scipy.optimize import brentq
from scipy.stats import binom

SLUG = "track_init_ht"


def _right_1(p_f, w_s, s):
    return binom.sf(s - 1, w_s, p_f)


def _right_3():
    # independent of the module's helper: scan S and solve for the SNR with scipy directly
    p_f = 10 ** -2.5
    best = np.inf
    for s in range(1, 26):
        if binom.sf(s - 1, 25, p_f) > 1e-4:
            continue
        def f(snr, s=s):
            return hyp.area_detection_exact(hyp.snr_to_pd(snr, p_f), p_f, 5, 4, s) - 0.9
        if f(30.0) > 0:
            best = min(best, brentq(f, 0, 30))
    return best


def _right_4():
    ps = paper_settings()
    p_f = ps["fig1_p_f"]
    p_d = float(hyp.snr_to_pd(2.0, p_f))
    pmf = np.convolve(binom.pmf(np.arange(5), 4, p_d), binom.pmf(np.arange(22), 21, p_f))
    return float(pmf[4:].sum())


RIGHT = {
    "track_init_ht.1": _right_1,
    "track_init_ht.2": lambda: next(s for s in range(26)
                                    if binom.sf(s - 1, 25, paper_settings()["cfar_p_f"]) <= 1e-6),
    "track_init_ht.3": _right_3,
    "track_init_ht.4": _right_4,
    "track_init_ht.5": lambda: (1 - paper_settings()["cfar_p_f"]) ** 16,
}

WRONG = {
    "track_init_ht.1": lambda p_f, w_s, s: binom.sf(s, w_s, p_f),  # the off-by-one: D > S
    "track_init_ht.2": lambda: 7,  # the paper's S: P_FA is above 1e-6 there
    "track_init_ht.3": lambda: 2.0,
    "track_init_ht.4": lambda: hyp.area_detection(hyp.snr_to_pd(2.0, 0.003), 0.003, 5, 4, 4),
    "track_init_ht.5": lambda: 1 - 0.03,
}

BAD = {
    "track_init_ht.1": ("not a function", TypeError),
    "track_init_ht.2": ("eight", TypeError),
    "track_init_ht.3": ([3.8, 3.9], TypeError),
    "track_init_ht.4": (float("nan"), ValueError),
    "track_init_ht.5": (None, TypeError),
}


def _answer(eid, table):
    a = table[eid]
    return a if eid == "track_init_ht.1" else a()


def test_at_least_four_exercises():
    ids = exercise_ids(SLUG)
    assert len(ids) >= 4
    assert set(ids) == set(RIGHT) == set(WRONG) == set(BAD)


@pytest.mark.parametrize("eid", sorted(RIGHT))
def test_right_answer_passes(eid):
    assert check(eid, _answer(eid, RIGHT))


@pytest.mark.parametrize("eid", sorted(WRONG))
def test_wrong_answer_fails(eid):
    res = check(eid, _answer(eid, WRONG))
    assert not res
    assert "hint" in res.message


@pytest.mark.parametrize("eid", sorted(BAD))
def test_bad_answer_raises(eid):
    answer, exc = BAD[eid]
    with pytest.raises(exc):
        check(eid, answer)


def test_function_exercise_rejects_a_crashing_function():
    assert not check("track_init_ht.1", lambda p_f, w_s, s: math.sqrt(-1))


def test_widget_reading_within_step():
    # a reading off the panel's 0.1-step SNR slider is accepted
    exact = _right_3()
    assert check("track_init_ht.3", round(exact, 1))
