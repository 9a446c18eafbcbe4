"""Closed forms of Li et al. (2008), eqs. (4)-(13)."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.montecarlo import mc_agreement
from eotrack.tracking import hypothesis as hyp
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.stats import binom

probs = st.floats(0.0, 1.0, allow_nan=False)
odd = st.sampled_from([1, 3, 5, 7])


def test_snr_link_values():
    pd = hyp.snr_to_pd(np.array([1.0, 2.0, 3.0]), 0.003)
    np.testing.assert_allclose(pd, [0.0403, 0.2273, 0.5996], atol=5e-4)
    assert hyp.snr_to_pd(0.0, 0.2) == pytest.approx(0.2)
    assert isinstance(hyp.snr_to_pd(1.0, 0.01), float)


def test_area_false_alarm_matches_binomial_tail():
    s = np.arange(0, 26)
    got = hyp.area_false_alarm(0.003, 5, s)
    want = [sum(binom.pmf(t, 25, 0.003) for t in range(k, 26)) for k in s]
    np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-300)
    assert hyp.area_false_alarm(0.003, 5, 0) == 1.0


def test_area_detection_paper_form_and_clip():
    p1 = hyp.p1_paper(0.98, 0.03, 5, 9)
    assert p1 > 1  # the erratum: eq. (6) exceeds 1
    assert hyp.area_detection(0.98, 0.03, 5, 9, 25) == 1.0  # clipped to P_1 = 1
    p1 = hyp.p1_paper(0.2, 0.003, 5, 4)
    assert hyp.area_detection(0.2, 0.003, 5, 4, 3) == pytest.approx(binom.sf(2, 25, p1))


def test_exact_equals_convolution():
    pd, pf, ts = 0.4, 0.05, 4
    pmf = np.convolve(binom.pmf(np.arange(ts + 1), ts, pd),
                      binom.pmf(np.arange(22), 21, pf))
    for s in range(0, 26):
        assert hyp.area_detection_exact(pd, pf, 5, ts, s) == pytest.approx(pmf[s:].sum(),
                                                                           abs=1e-12)


def test_exact_reduces_to_false_alarm_when_pd_equals_pf():
    s = np.arange(1, 26)
    np.testing.assert_allclose(hyp.area_detection_exact(0.01, 0.01, 5, 4, s),
                               hyp.area_false_alarm(0.01, 5, s), rtol=1e-9, atol=1e-300)


def test_temporal_forms():
    assert hyp.track_detection(0.5, 7, 5) == pytest.approx(binom.sf(4, 7, 0.5))
    p0 = 1 - (1 - 0.01) ** 9
    assert hyp.track_false_alarm(0.01, 3, 7, 5) == pytest.approx(binom.sf(4, 7, p0))
    p1 = 0.3 + 0.7 * (1 - 0.99 ** 8)
    assert hyp.sequence_detection(0.3, 0.01, 3, 7, 5) == pytest.approx(binom.sf(4, 7, p1))


@settings(max_examples=60, deadline=None)
@given(pd=probs, pf=probs, w=odd, ts_frac=st.floats(0.01, 1.0))
def test_spatial_in_unit_interval_and_monotone_in_s(pd, pf, w, ts_frac):
    n = w * w
    ts = max(1, int(ts_frac * n))
    s = np.arange(0, n + 1)
    for f in (hyp.area_false_alarm(pf, w, s), hyp.area_detection(pd, pf, w, ts, s),
              hyp.area_detection_exact(pd, pf, w, ts, s)):
        assert np.all((f >= 0) & (f <= 1))
        assert np.all(np.diff(f) <= 1e-12)  # non-increasing in S


@settings(max_examples=60, deadline=None)
@given(pd=probs, pf=probs, g=odd, t=st.integers(1, 12))
def test_temporal_in_unit_interval_monotone_and_ordered(pd, pf, g, t):
    th = np.arange(0, t + 1)
    ds = hyp.sequence_detection(pd, pf, g, t, th)
    dt = hyp.track_detection(pd, t, th)
    ft = hyp.track_false_alarm(pf, g, t, th)
    for f in (ds, dt, ft):
        assert np.all((f >= 0) & (f <= 1))
        assert np.all(np.diff(f) <= 1e-12)  # non-increasing in T_h
    assert np.all(ds >= dt - 1e-12)  # P_DS >= P_DT (the paper's Fig. 2 reading)


@settings(max_examples=40, deadline=None)
@given(pd=st.floats(0.0, 0.9), pf=st.floats(0.0, 0.2))
def test_exact_never_above_paper_form_when_p1_is_valid(pd, pf):
    # eq. (6) gives all W_S pixels probability P_1 >= P_D, P_F: it overestimates the count
    s = np.arange(1, 26)
    paper = hyp.area_detection(pd, pf, 5, 4, s)
    exact = hyp.area_detection_exact(pd, pf, 5, 4, s)
    assert np.all(exact <= paper + 1e-12)


def test_monte_carlo_within_interval_of_exact():
    rng = np.random.default_rng(0)
    n, pd, pf = 200_000, 0.3, 0.02
    counts = (rng.random((n, 4)) < pd).sum(1) + (rng.random((n, 21)) < pf).sum(1)
    s = np.arange(1, 8)
    k = (counts[:, None] >= s).sum(axis=0)
    assert mc_agreement(k, n, hyp.area_detection_exact(pd, pf, 5, 4, s))
    assert not mc_agreement(k, n, hyp.area_detection(pd, pf, 5, 4, s))  # eq. (7) is not it


@pytest.mark.parametrize("call, match", [
    (lambda: hyp.area_false_alarm(1.2, 5, 3), "p_f"),
    (lambda: hyp.area_false_alarm(-0.1, 5, 3), "p_f"),
    (lambda: hyp.area_false_alarm(0.1, 4, 3), "window"),
    (lambda: hyp.area_false_alarm(0.1, 0, 3), "window"),
    (lambda: hyp.area_false_alarm(0.1, 5, 26), "s"),
    (lambda: hyp.area_detection(1.5, 0.1, 5, 4, 3), "p_d"),
    (lambda: hyp.area_detection(0.5, 0.1, 5, 30, 3), "target_pixels"),
    (lambda: hyp.area_detection(0.5, 0.1, 5, 4, 30), "s"),
    (lambda: hyp.area_detection_exact(0.5, 0.1, 6, 4, 3), "window"),
    (lambda: hyp.area_detection_exact(0.5, 2.0, 5, 4, 3), "p_f"),
    (lambda: hyp.p1_paper(0.5, 0.1, 5, 0), "target_pixels"),
    (lambda: hyp.track_false_alarm(0.1, 3, 7, 8), "min_hits"),
    (lambda: hyp.track_false_alarm(0.1, 2, 7, 5), "gate"),
    (lambda: hyp.sequence_detection(0.5, 0.1, 3, 0, 1), "frames"),
    (lambda: hyp.sequence_detection(-0.5, 0.1, 3, 7, 5), "p_d"),
    (lambda: hyp.track_detection(0.5, 7, 9), "min_hits"),
    (lambda: hyp.track_detection(np.nan, 7, 5), "p_d"),
    (lambda: hyp.snr_to_pd(-1.0, 0.1), "snr"),
    (lambda: hyp.snr_to_pd(1.0, 1.1), "p_f"),
    (lambda: hyp.clustering_threshold(1.1, 5, 1e-4), "p_f"),
    (lambda: hyp.clustering_threshold(0.01, 4, 1e-4), "window"),
    (lambda: hyp.clustering_threshold(0.01, 5, 0.0), "max_pfa"),
    (lambda: hyp.clustering_threshold(0.01, 5, 1.5), "max_pfa"),
])
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_bad_types():
    with pytest.raises(TypeError, match="s"):
        hyp.area_false_alarm(0.1, 5, 2.5)
    with pytest.raises(TypeError, match="window"):
        hyp.area_false_alarm(0.1, 5.0, 2)


def test_clustering_threshold_values():
    assert hyp.clustering_threshold(0.003, 5, 1e-4) == 3
    assert isinstance(hyp.clustering_threshold(0.003, 5, 1e-4), int)
    np.testing.assert_array_equal(hyp.clustering_threshold([0.003, 0.03], 5, 1e-4), [3, 6])
    assert hyp.clustering_threshold(1.0, 5, 0.5) == 26  # no S meets it: the test never fires
    assert hyp.clustering_threshold(0.0, 5, 0.5) == 1
    with pytest.raises(TypeError, match="window"):
        hyp.clustering_threshold(0.01, 5.5, 1e-4)


@settings(max_examples=80, deadline=None)
@given(pf=st.floats(1e-6, 0.5), w=odd, q=st.floats(1e-12, 1.0))
def test_clustering_threshold_is_the_smallest_s_meeting_the_requirement(pf, w, q):
    s = hyp.clustering_threshold(pf, w, q)
    n = w * w
    assert 0 <= s <= n + 1
    if s <= n:
        assert hyp.area_false_alarm(pf, w, s) <= q
    if s >= 1:
        assert hyp.area_false_alarm(pf, w, s - 1) > q
