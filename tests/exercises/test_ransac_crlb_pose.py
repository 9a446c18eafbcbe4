"""Checkers of notebook 06's exercises: right answers pass, wrong fail, bad types raise."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.exercises import check, exercise_ids
from eotrack.exercises import ransac_crlb_pose as ex

SLUG = "ransac_crlb_pose"


def test_at_least_four_exercises():
    assert len(exercise_ids(SLUG)) >= 4


def test_ex1_fisher_one_point():
    right = ex._ex1_expected()
    assert check(f"{SLUG}.1", right)
    assert np.linalg.matrix_rank(right) == 2
    assert not check(f"{SLUG}.1", 2 * right)
    with pytest.raises(ValueError):
        check(f"{SLUG}.1", np.eye(3))
    with pytest.raises(TypeError):
        check(f"{SLUG}.1", "J")


def test_ex2_ratio():
    right = ex._ex2_expected()
    assert right > 1
    assert check(f"{SLUG}.2", right)
    assert not check(f"{SLUG}.2", 1.0)
    with pytest.raises(TypeError):
        check(f"{SLUG}.2", "big")


def test_ex3_function():
    assert check(f"{SLUG}.3", ex.points_needed)
    assert not check(f"{SLUG}.3", lambda *a: 6)
    with pytest.raises(TypeError):
        check(f"{SLUG}.3", 42)


def test_ex4_exploration():
    right = ex._ex4_expected()
    assert check(f"{SLUG}.4", right)
    assert not check(f"{SLUG}.4", right * 1.2)
    with pytest.raises(ValueError):
        check(f"{SLUG}.4", float("nan"))


@pytest.mark.parametrize("k, right, wrong", [(5, "b", "a"), (6, "c", "b")])
def test_choices(k, right, wrong):
    assert check(f"{SLUG}.{k}", right)
    assert not check(f"{SLUG}.{k}", wrong)
    with pytest.raises(ValueError):
        check(f"{SLUG}.{k}", "z")
