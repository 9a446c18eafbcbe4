"""Checkers of notebook 04's exercises: right answers pass, wrong ones fail, bad ones raise."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.exercises import check, exercise_ids
from eotrack.experiments import track_init_hough as TH

SLUG = "track_init_hough"


def _right_1(t1, t2, t3, which):
    # directly from the variance of (x_which − prediction from the other two)
    t = [t1, t2, t3]
    a, b = [t[i] for i in range(3) if i != which]
    tau = (t[which] - b) / (b - a)
    return 1.0 + (1.0 + tau) ** 2 + tau**2


def _scene2():
    cfg = TH.PlantedConfig()
    return cfg, TH.planted_scene(np.random.default_rng(2016), cfg, clutter_per_frame=30.0,
                                 n_objects=0, n_stars=0)


def _right_2():
    # the literal §4.6 recipe: no depletion (for a clutter-only scene = chi2_chance_tracks's
    # upper bound)
    cfg, sc = _scene2()
    return TH.chi2_chance_tracks(sc, v_min=cfg.v_gate_px_s[0], v_max=cfg.v_gate_px_s[1],
                                 sigma_px=cfg.sigma_px, alpha=cfg.alpha, depletion=False,
                                 conflicts=False)


def _corrected_2(depletion=True, conflicts=True):
    # the expected chance tracks (depletion and/or conflicts), which the exercise does not ask for
    cfg, sc = _scene2()
    return TH.chi2_chance_tracks(sc, v_min=cfg.v_gate_px_s[0], v_max=cfg.v_gate_px_s[1],
                                 sigma_px=cfg.sigma_px, alpha=cfg.alpha, depletion=depletion,
                                 conflicts=conflicts)


def _depleted_2():
    return _corrected_2()


def _depletion_only_2():
    return _corrected_2(conflicts=False)


def _conflicts_only_2():
    return _corrected_2(depletion=False)


def _consecutive_only_2():
    # only the (k-2, k-1, k) triples (forgetting the two 3-of-4 shapes with a gap)
    _cfg, sc = _scene2()
    t = [tt for tt, _ in sc.frames]
    n = [len(xy) for _, xy in sc.frames]
    return sum(n[k - 2] * n[k - 1] * n[k] * TH.triplet_chance_probability(
        t[k - 2], t[k - 1], t[k], width=512, v_min=3, v_max=240, sigma_px=0.3, alpha=1e-3)
        for k in range(2, len(t)))


def _right_3():
    return float(TH.explore_results(35.0, 6, False, False)["false"].mean())


RIGHT = {
    "track_init_hough.1": _right_1,
    "track_init_hough.2": _right_2,
    "track_init_hough.3": _right_3,
    "track_init_hough.4": lambda: 1.0,
    "track_init_hough.5": lambda: (400 * np.arccos(0.75) - 15 * np.sqrt(175)) / (400 * np.pi),
}

WRONG = {
    "track_init_hough.1": lambda t1, t2, t3, which: 1.5,  # the evenly spaced middle only
    "track_init_hough.2": lambda: 2 * _right_2(),
    "track_init_hough.3": lambda: _right_3() + 3.0,
    "track_init_hough.4": lambda: 2.0,  # the paper's 5 px × 5° × 3 px/s cells' count
    "track_init_hough.5": lambda: 0.0,  # the 10 px gate's answer (the constraint cannot act)
}


@pytest.mark.parametrize("wrong", [_depleted_2, _depletion_only_2, _conflicts_only_2,
                                   _consecutive_only_2])
def test_exercise2_rejects_the_other_recipes(wrong):
    assert abs(wrong() / _right_2() - 1) > 0.05
    assert not check("track_init_hough.2", wrong())


def test_at_least_four_exercises():
    assert len(exercise_ids(SLUG)) >= 4
    assert sorted(exercise_ids(SLUG)) == sorted(RIGHT)


@pytest.mark.parametrize("ex", sorted(RIGHT))
def test_right_answer_passes(ex):
    ans = RIGHT[ex] if ex == "track_init_hough.1" else RIGHT[ex]()
    assert check(ex, ans)


@pytest.mark.parametrize("ex", sorted(WRONG))
def test_wrong_answer_fails(ex):
    ans = WRONG[ex] if ex == "track_init_hough.1" else WRONG[ex]()
    assert not check(ex, ans)


@pytest.mark.parametrize(("ex", "bad", "exc"), [
    ("track_init_hough.1", 3.0, TypeError),
    ("track_init_hough.2", "many", TypeError),
    ("track_init_hough.3", [1.0, 2.0], TypeError),
    ("track_init_hough.4", "a", TypeError),
    ("track_init_hough.5", "b", TypeError),
])
def test_bad_answer_raises(ex, bad, exc):
    with pytest.raises(exc):
        check(ex, bad)


@pytest.mark.parametrize("wrong", [0.0, 2.0, 3.0])
def test_exercise4_rejects_other_counts(wrong):
    assert not check("track_init_hough.4", wrong)


@pytest.mark.parametrize("wrong", [
    0.0,                                   # the 10 px setting of §4.7
    0.5,                                   # half the gate (the perpendicular through the centre)
    1 - RIGHT["track_init_hough.5"](),     # the complement (candidates kept)
    15 / 20 / 2,                           # a linear guess d / (2r)
])
def test_exercise5_rejects_wrong_fractions(wrong):
    assert not check("track_init_hough.5", wrong)


def test_exercise3_rejects_the_panels_levels():
    """The panel's own levels (its title shows them) are not the answer at 35 per frame."""
    for lam in (20.0, 50.0):
        other = float(TH.explore_results(lam, 6, False, False)["false"].mean())
        if abs(other / _right_3() - 1) > 0.02:
            assert not check("track_init_hough.3", other)
    assert not check("track_init_hough.3",
                     float(TH.explore_results(35.0, 6, False, True)["false"].mean()))


def test_exercise2_rejects_the_xu_scenes_gate():
    """Review r3 #5: the Xu configuration's gate (10 px/s) instead of the planted one (3 px/s)
    is 0.75 % off and must be rejected."""
    cfg = TH.PlantedConfig()
    sc = TH.planted_scene(np.random.default_rng(2016), cfg, clutter_per_frame=30.0, n_objects=0,
                          n_stars=0)
    t = [tt for tt, _ in sc.frames]
    n = [len(xy) for _, xy in sc.frames]
    wrong = sum(n[a] * n[b] * n[c] * TH.triplet_chance_probability(
        t[a], t[b], t[c], width=cfg.width_px, v_min=10.0, v_max=cfg.v_gate_px_s[1],
        sigma_px=cfg.sigma_px, alpha=cfg.alpha) for a, b, c in TH.triplet_shapes(len(t)))
    assert abs(wrong / _right_2() - 1) > 1e-3
    assert not check("track_init_hough.2", wrong)


def test_exercise2_accepts_four_significant_digits():
    """Review rev04 #10: the right answer written with the notebook's display precision (four
    significant digits) passes; three significant digits' worth of error would not."""
    right = _right_2()
    assert check("track_init_hough.2", float(f"{right:.4g}"))
    assert not check("track_init_hough.2", right * 1.005)
