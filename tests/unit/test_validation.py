"""Shared input validation."""

import numpy as np
import pytest
from eotrack.validation import (
    as_finite_array,
    as_points,
    check_choice,
    check_generator,
    check_int,
    check_positive,
    check_probability,
    check_same_length,
)


def test_as_finite_array():
    assert as_finite_array([1, 2], "x").dtype == float
    with pytest.raises(ValueError, match="x contains NaN or infinite"):
        as_finite_array([1, np.nan], "x")
    assert np.isnan(as_finite_array([np.nan], "x", allow_nan=True)[0])
    with pytest.raises(ValueError, match="x contains infinite"):
        as_finite_array([np.inf], "x", allow_nan=True)
    with pytest.raises(ValueError, match="x must have 2 dimension"):
        as_finite_array([1.0], "x", ndim=2)
    with pytest.raises(ValueError, match=r"x must have shape \(n, 3\)"):
        as_finite_array(np.zeros((2, 2)), "x", shape=(None, 3))
    with pytest.raises(TypeError, match="x must be numeric"):
        as_finite_array("12", "x")
    with pytest.raises(ValueError, match="x needs at least 3 entries"):
        as_finite_array([1.0], "x", min_size=3)


def test_as_points():
    assert as_points([], "p").shape == (0, 2)
    with pytest.raises(ValueError, match="wrap it"):
        as_points([1.0, 2.0], "p")
    with pytest.raises(ValueError, match=r"p must have shape \(n, 2\)"):
        as_points(np.zeros((3, 3)), "p")


def test_scalars():
    assert check_probability(0.5, "p") == 0.5
    with pytest.raises(ValueError, match=r"p must lie in \(0, 1\]"):
        check_probability(0.0, "p", open_low=True)
    with pytest.raises(TypeError, match="p must be a real number"):
        check_probability(True, "p")
    with pytest.raises(ValueError, match="s must be finite and > 0"):
        check_positive(0, "s")
    assert check_positive(0, "s", allow_zero=True) == 0
    with pytest.raises(ValueError, match="k must be <= 3"):
        check_int(4, "k", max_value=3)
    with pytest.raises(TypeError, match="k must be an integer"):
        check_int(np.float64(2), "k")
    assert check_int(np.int64(2), "k") == 2
    with pytest.raises(ValueError, match="m must be one of"):
        check_choice("x", "m", ["a"])
    with pytest.raises(TypeError, match="m must be a string"):
        check_choice(1, "m", ["a"])
    with pytest.raises(TypeError, match=r"rng must be a numpy\.random\.Generator"):
        check_generator(np.random.RandomState(0))
    with pytest.raises(ValueError, match="a and b must have the same length"):
        check_same_length("a", np.zeros(2), "b", np.zeros(3))
