"""Eq. (1)–(2): minimal-sample counts."""

import math

import pytest
from eotrack.robust import min_samples, min_samples_real, success_probability
from hypothesis import given
from hypothesis import strategies as st


def test_paper_setting():
    assert min_samples(0.995, 0.03, 4) == 3
    assert min_samples_real(0.995, 0.03, 4) == pytest.approx(2.4468, abs=1e-3)


@pytest.mark.parametrize(("eps", "u"), [(0.1, 4.3), (0.3, 16.8), (0.5, 71.4)])
def test_figure1_check_values(eps, u):
    assert round(min_samples_real(0.99, eps, 4), 1) == u


@given(p=st.floats(0.5, 0.9999), e=st.floats(0.0, 0.8), m=st.integers(1, 10))
def test_rounded_count_achieves_confidence(p, e, m):
    u = min_samples(p, e, m)
    assert success_probability(u, e, m) >= p - 1e-12
    if u > 1:
        assert success_probability(u - 1, e, m) < p + 1e-12


@given(p=st.floats(0.5, 0.999), e1=st.floats(0.01, 0.7), e2=st.floats(0.01, 0.7),
       m=st.integers(1, 8))
def test_monotone_in_outlier_ratio(p, e1, e2, m):
    lo, hi = sorted((e1, e2))
    assert min_samples_real(p, lo, m) <= min_samples_real(p, hi, m) + 1e-9


def test_no_outliers_one_sample():
    assert min_samples(0.99, 0.0, 5) == 1
    assert math.isfinite(min_samples_real(0.99, 0.0, 5))


@pytest.mark.parametrize(("args", "exc", "match"), [
    ((1.0, 0.1, 4), ValueError, "confidence must lie in"),
    ((0.0, 0.1, 4), ValueError, "confidence must lie in"),
    ((0.99, 1.0, 4), ValueError, "outlier_ratio must lie in"),
    ((0.99, -0.1, 4), ValueError, "outlier_ratio must lie in"),
    ((0.99, 0.1, 0), ValueError, "sample_size must be >= 1"),
    ((0.99, 0.1, 2.5), TypeError, "sample_size must be an integer"),
    (("0.9", 0.1, 4), TypeError, "confidence must be a real number"),
])
def test_bad_input(args, exc, match):
    with pytest.raises(exc, match=match):
        min_samples(*args)
    with pytest.raises(exc, match=match):
        min_samples_real(*args)


def test_success_probability_bad():
    with pytest.raises(ValueError, match="n_samples must be >= 0"):
        success_probability(-1, 0.1, 4)
