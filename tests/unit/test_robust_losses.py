"""Loss functions: values, properties of the corrected L_s, the printed erratum, bad input."""

import numpy as np
import pytest
from eotrack.robust import (
    LOSSES,
    get_loss,
    loss_weights,
    msac_loss,
    sinusoidal_loss,
    sinusoidal_loss_as_printed,
    zero_one_loss,
)
from hypothesis import given
from hypothesis import strategies as st

finite = st.floats(-1e6, 1e6, allow_nan=False)
pos = st.floats(1e-3, 1e3)


def test_known_values():
    e = np.array([0.0, 0.5, 1.0, 1.5])
    assert zero_one_loss(e, 1.0).tolist() == [0, 0, 0, 1]
    assert msac_loss(e, 1.0).tolist() == [0, 0.5, 1, 1]
    assert msac_loss(e, 1.0, "squared").tolist() == [0, 0.25, 1, 1]
    np.testing.assert_allclose(sinusoidal_loss(e, 1.0), [0, 0.5, 1, 1], atol=1e-15)


@given(t=pos)
def test_sinusoidal_zero_at_zero_one_at_t(t):
    assert sinusoidal_loss(np.array([0.0]), t)[0] == 0.0
    assert sinusoidal_loss(np.array([t]), t)[0] == pytest.approx(1.0)


@given(t=pos)
def test_sinusoidal_continuous_slope(t):
    """Zero slope at 0 and at t (continuous first derivative across the threshold)."""
    h = 1e-6 * t
    left = (1.0 - sinusoidal_loss(np.array([t - h]), t)[0]) / h
    right = (sinusoidal_loss(np.array([h]), t)[0]) / h
    assert abs(left) * t < 1e-4 and abs(right) * t < 1e-4


@given(e=finite, t=pos)
def test_sinusoidal_below_then_above_msac(e, t):
    a = abs(e)
    ls, lm = sinusoidal_loss(np.array([e]), t)[0], msac_loss(np.array([e]), t)[0]
    if 1e-6 * t < a < 0.5 * t * (1 - 1e-9):
        assert ls < lm
    elif 0 <= a <= 1e-6 * t:  # both ≈ 0; L_s underflows first (quadratic vs linear)
        assert ls <= lm
    elif 0.5 * t * (1 + 1e-9) < a < t * (1 - 1e-9):
        assert ls > lm
    elif a > t:
        assert ls == lm == 1.0


@given(e=finite, t=pos)
def test_all_losses_bounded_and_even(e, t):
    for fn in LOSSES.values():
        v = fn(np.array([e, -e]), t)
        assert np.all((v >= 0) & (v <= 1))
        assert v[0] == v[1]


def test_printed_form_is_an_erratum():
    t = 2.0
    v = sinusoidal_loss_as_printed(np.array([0.0, t * (1 - 1e-9), 1.01 * t]), t)
    assert v[0] == 1.0  # largest penalty for a perfect fit
    assert v[1] < 0.95  # then a jump back to 1 beyond t
    assert v[2] == 1.0


def test_weights():
    w = loss_weights(np.array([0.0, 1.0, 3.0]), 2.0)
    np.testing.assert_allclose(w, [1.0, 0.5, 0.0], atol=1e-12)


@pytest.mark.parametrize("fn", list(LOSSES.values()))
def test_bad_threshold(fn):
    with pytest.raises(ValueError, match="t must be"):
        fn(np.array([1.0]), 0.0)
    with pytest.raises(ValueError, match="e contains"):
        fn(np.array([np.nan]), 1.0)


def test_bad_names():
    with pytest.raises(ValueError, match="loss must be one of"):
        get_loss("cauchy")
    with pytest.raises(ValueError, match="form must be one of"):
        msac_loss(np.array([1.0]), 1.0, form="cubic")
    with pytest.raises(TypeError, match="e must be numeric"):
        zero_one_loss("abc", 1.0)
