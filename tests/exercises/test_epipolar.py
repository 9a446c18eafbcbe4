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
    # independent of the module: scan n until (n - 1)/sqrt(n) exceeds 2.5
    return next(n for n in range(2, 100) if (n - 1) / np.sqrt(n) > 2.5)


GRID = np.arange(0.5, 30.01, 0.5)  # the Explore slider's values


def _right_3():
    st = E.threshold_study(1.0, 6)
    return float(GRID[np.argmin(st.rates(GRID)["total"])])


RIGHT = {
    "epipolar.1": _right_1,
    "epipolar.2": lambda: _right_2,
    "epipolar.3": _right_3,
    "epipolar.4": lambda: 0.01 * 1024 / (2 * np.tan(np.radians(10.0))),
    "epipolar.5": lambda: E.error_budget_gate(
        E.build_scenario(), E.ErrorConfig(attitude_arcmin=np.sqrt(3.0), jitter_urad=100.0),
        p=0.90)[1],
}

WRONG = {
    "epipolar.1": lambda: 11,  # the paper's 3σ rule, not the 2.5σ one asked
    "epipolar.2": lambda: (lambda F, p1, p2: np.abs(
        np.column_stack([p2, np.ones(len(p2))]) @ F
        @ np.column_stack([p1, np.ones(len(p1))]).T).T),  # algebraic, not normalised
    "epipolar.3": lambda: 10.0,  # the paper's threshold
    "epipolar.4": lambda: 0.01 * 512 / (2 * np.tan(np.radians(1.0))),  # the experiment sensor
    "epipolar.5": lambda: E.error_budget_gate(
        E.build_scenario(), E.ErrorConfig(attitude_arcmin=np.sqrt(3.0), jitter_urad=100.0)
    )[1],  # the 99 % gate
}

MORE_WRONG = [
    ("epipolar.1", 8),  # population s (ddof = 0): sqrt(n - 1) > 2.5
    ("epipolar.1", 10),
    ("epipolar.3", None),  # the optimum with 3 false targets (the report's), filled in below
    ("epipolar.4", 0.01 * 1024 / (2 * np.tan(np.radians(10.0))) / 1000),  # µrad
    ("epipolar.4", 0.01 * 1024 / (2 * np.radians(10.0)) * 2),  # half field read as full
    ("epipolar.3", 4.0),  # the near-optimum of the 3-false case, one slider step off
    ("epipolar.5", "uniform90"),  # the ±1′ bound reading
    ("epipolar.5", "chi2_2"),  # two degrees of freedom
    ("epipolar.5", "no_jitter"),  # the printed σ_d (10 µrad jitter) × 1.645
    ("epipolar.5", "p95"),  # 95 % instead of 90 %
    ("epipolar.5", 3.761194070094244 * 1.959964),  # the old exercise: printed σ_d × z(0.975)
]


def _more_wrong(ex, v):
    from scipy.stats import chi2
    scen = E.build_scenario()
    rms = E.ErrorConfig(attitude_arcmin=np.sqrt(3.0), jitter_urad=100.0)
    if ex == "epipolar.3" and v is None:
        st = E.threshold_study(1.0, 3)
        return float(GRID[np.argmin(st.rates(GRID)["total"])])
    if v == "uniform90":
        return E.error_budget_gate(scen, E.ErrorConfig(jitter_urad=100.0), p=0.90)[1]
    if v == "chi2_2":
        s, _ = E.error_budget_gate(scen, rms)
        return s * np.sqrt(chi2.ppf(0.90, 2))
    if v == "no_jitter":
        return E.error_budget_gate(scen, E.ErrorConfig(attitude_arcmin=np.sqrt(3.0)), p=0.90)[1]
    if v == "p95":
        return E.error_budget_gate(scen, rms, p=0.95)[1]
    return v


@pytest.mark.parametrize(("ex", "v"), MORE_WRONG)
def test_more_wrong_answers_fail(ex, v):
    assert not check(ex, _more_wrong(ex, v))


def test_ex2_rejects_the_library_and_opencv():
    import functools

    import cv2
    from eotrack.geometry import epipolar_distances

    assert not check("epipolar.2", epipolar_distances)
    assert not check("epipolar.2", lambda F, p1, p2: epipolar_distances(F, p1, p2))
    assert not check("epipolar.2", functools.partial(epipolar_distances))
    assert not check("epipolar.2", lambda F, p1, p2: E.epipolar_distances(F, p1, p2))

    def with_cv(F, p1, p2):
        lines = cv2.computeCorrespondEpilines(p1.reshape(-1, 1, 2), 1, F).reshape(-1, 3)
        return np.abs(lines[:, :2] @ p2.T + lines[:, 2:])

    assert not check("epipolar.2", with_cv)

    # imports inside the body (review of issue 25): static, submodule, dynamic
    def inner_import(F, p1, p2):
        from eotrack.geometry import epipolar_distances as ed

        return ed(F, p1, p2)

    def inner_cv(F, p1, p2):
        import cv2 as c

        lines = c.computeCorrespondEpilines(p1.reshape(-1, 1, 2), 1, F).reshape(-1, 3)
        return np.abs(lines[:, :2] @ p2.T + lines[:, 2:])

    def dunder(F, p1, p2):
        return __import__("eotrack.geometry").geometry.epipolar_distances(F, p1, p2)

    def importlib_way(F, p1, p2):
        import importlib

        return importlib.import_module("eotrack.geometry").epipolar_distances(F, p1, p2)

    def nested(F, p1, p2):
        def go():
            from eotrack.geometry import epipolar_distances as ed

            return ed(F, p1, p2)

        return go()

    for f in (inner_import, inner_cv, dunder, importlib_way, nested):
        assert not check("epipolar.2", f), f.__name__
    assert check("epipolar.2", _right_2)  # numpy only passes


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
