"""Binomial intervals and the Monte Carlo ↔ closed-form agreement test."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.montecarlo import Agreement, binomial_interval, mc_agreement
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.stats import binomtest

SCIPY_NAME = {"wilson": "wilson", "clopper-pearson": "exact"}


@pytest.mark.parametrize("method", ["wilson", "clopper-pearson"])
@pytest.mark.parametrize("k,n", [(0, 1), (0, 10), (3, 10), (10, 10), (50, 1000), (999, 1000),
                                 (7, 2_000_000)])
@pytest.mark.parametrize("conf", [0.95, 0.999])
def test_matches_scipy_binomtest(method, k, n, conf):
    lo, hi = binomial_interval(k, n, confidence=conf, method=method)
    ci = binomtest(k, n).proportion_ci(confidence_level=conf, method=SCIPY_NAME[method])
    assert lo.shape == () and hi.shape == ()
    np.testing.assert_allclose([lo, hi], [ci.low, ci.high], rtol=1e-6, atol=1e-15)


def test_vectorised_and_broadcast():
    k = np.array([[0, 5], [10, 20]])
    lo, hi = binomial_interval(k, 20)
    assert lo.shape == hi.shape == (2, 2)
    assert lo[0, 0] == 0.0 and hi[1, 1] == 1.0
    for (i, j), kk in np.ndenumerate(k):
        l1, h1 = binomial_interval(int(kk), 20)
        assert lo[i, j] == pytest.approx(float(l1)) and hi[i, j] == pytest.approx(float(h1))


def test_clopper_pearson_wider_than_wilson_in_the_middle():
    lw, hw = binomial_interval(30, 100, method="wilson")
    lc, hc = binomial_interval(30, 100, method="clopper-pearson")
    assert lc < lw and hc > hw


def test_agreement_detects_a_wrong_formula():
    rng = np.random.default_rng(1)
    n = 100_000
    p = np.array([0.001, 0.05, 0.3, 0.7])
    k = rng.binomial(n, p)
    good = mc_agreement(k, n, p)
    assert isinstance(good, Agreement) and good and good.all_inside
    assert good.fraction_inside == 1.0 and good.n_points == 4 and good.n_outside == 0
    bad = mc_agreement(k, n, p * 1.2)
    assert not bad and bad.n_outside >= 2
    assert "Wilson" in good.summary() and "4/4" in good.summary()


def test_familywise_widens_intervals():
    k, n = np.full(50, 30), 1000
    a = mc_agreement(k, n, 0.03)
    b = mc_agreement(k, n, 0.03, familywise=True)
    assert a.point_confidence == 0.999
    assert b.point_confidence == pytest.approx(1 - 0.001 / 50)
    assert np.all(b.lo <= a.lo) and np.all(b.hi >= a.hi)
    assert a.familywise_bound == pytest.approx(0.05)
    assert b.familywise_bound == pytest.approx(0.001)


def test_coverage_close_to_nominal():
    # 2000 estimates of a true p: the 95 % interval must cover it about 95 % of the time
    rng = np.random.default_rng(7)
    p, n = 0.02, 2000
    k = rng.binomial(n, p, size=2000)
    for method in ("wilson", "clopper-pearson"):
        frac = mc_agreement(k, n, p, confidence=0.95, method=method).fraction_inside
        assert 0.93 < frac <= 1.0


@pytest.mark.parametrize("kw,exc", [
    ({"k": -1, "n": 10}, ValueError),
    ({"k": 11, "n": 10}, ValueError),
    ({"k": 1.5, "n": 10}, ValueError),
    ({"k": 1, "n": 0}, ValueError),
    ({"k": np.nan, "n": 10}, ValueError),
    ({"k": True, "n": 10}, TypeError),
    ({"k": "three", "n": 10}, TypeError),
    ({"k": 1, "n": 10, "confidence": 1.0}, ValueError),
    ({"k": 1, "n": 10, "confidence": 0.0}, ValueError),
    ({"k": 1, "n": 10, "confidence": "high"}, TypeError),
    ({"k": 1, "n": 10, "method": "wald"}, ValueError),
])
def test_bad_input_interval(kw, exc):
    with pytest.raises(exc):
        binomial_interval(**kw)


@pytest.mark.parametrize("args,kw,exc", [
    ((3, 10, 1.5), {}, ValueError),
    ((3, 10, -0.1), {}, ValueError),
    ((3, 10, "p"), {}, TypeError),
    ((3, 10, True), {}, TypeError),
    (([3, 4], 10, [0.1, 0.2, 0.3]), {}, ValueError),
    ((3, 10, 0.3), {"familywise": 1}, TypeError),
    ((3, 10, 0.3), {"confidence": 2}, ValueError),
    ((3, 10, 0.3), {"method": None}, ValueError),
])
def test_bad_input_agreement(args, kw, exc):
    with pytest.raises(exc):
        mc_agreement(*args, **kw)


@settings(max_examples=200, deadline=None)
@given(n=st.integers(1, 10_000), data=st.data(),
       conf=st.floats(0.5, 0.9999), method=st.sampled_from(["wilson", "clopper-pearson"]))
def test_interval_properties(n, data, conf, method):
    k = data.draw(st.integers(0, n))
    lo, hi = binomial_interval(k, n, confidence=conf, method=method)
    p = k / n
    # a valid interval in [0, 1] that contains the point estimate
    assert 0.0 <= lo <= p + 1e-12 and p - 1e-12 <= hi <= 1.0
    # more confidence never narrows it
    lo2, hi2 = binomial_interval(k, n, confidence=min(0.99999, conf + (1 - conf) / 2),
                                 method=method)
    assert lo2 <= lo + 1e-12 and hi2 >= hi - 1e-12
    # symmetry: the interval of n - k failures mirrors that of k successes
    lo3, hi3 = binomial_interval(n - k, n, confidence=conf, method=method)
    assert lo3 == pytest.approx(1 - hi, abs=1e-9) and hi3 == pytest.approx(1 - lo, abs=1e-9)
    # the point estimate always agrees with itself
    assert mc_agreement(k, n, p, confidence=conf, method=method)
