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


# ---------------------------------------------------------------- area_detection_pixels
def test_pixels_form_equals_exact_for_equal_pixels_and_convolution_otherwise():
    s = np.arange(0, 26)
    np.testing.assert_allclose(hyp.area_detection_pixels([0.3] * 4, 0.02, 5, s),
                               hyp.area_detection_exact(0.3, 0.02, 5, 4, s), atol=1e-14)
    p = np.array([0.95, 0.6, 0.6, 0.6, 0.6, 0.25, 0.25, 0.25, 0.25])
    pmf = np.array([1.0])
    for q in p:
        pmf = np.convolve(pmf, [1 - q, q])
    pmf = np.convolve(pmf, binom.pmf(np.arange(41), 40, 0.01))  # 7x7 window: 49 - 9 noise px
    s7 = np.arange(0, 50)
    np.testing.assert_allclose(hyp.area_detection_pixels(p, 0.01, 7, s7),
                               pmf[::-1].cumsum()[::-1][s7], atol=1e-13)
    # the mean-P_D binomial is a different count (it overstates the upper tail here)
    assert not np.allclose(hyp.area_detection_pixels(p, 0.01, 7, 6),
                           hyp.area_detection_exact(p.mean(), 0.01, 7, 9, 6), rtol=1e-3)
    assert isinstance(hyp.area_detection_pixels(p, 0.01, 7, 6), float)
    assert hyp.area_detection_pixels(p, [0.01, 0.02], 7, 6).shape == (2,)


@pytest.mark.parametrize("call, match", [
    (lambda: hyp.area_detection_pixels([], 0.01, 5, 3), "p_d_pixels"),
    (lambda: hyp.area_detection_pixels([[0.5]], 0.01, 5, 3), "p_d_pixels"),
    (lambda: hyp.area_detection_pixels([1.5], 0.01, 5, 3), "p_d_pixels"),
    (lambda: hyp.area_detection_pixels([0.5] * 10, 0.01, 3, 3), "p_d_pixels"),
    (lambda: hyp.area_detection_pixels([0.5], 0.01, 4, 3), "window"),
    (lambda: hyp.area_detection_pixels([0.5], 0.01, 5, 26), "s"),
    (lambda: hyp.area_detection_pixels([0.5], -0.1, 5, 3), "p_f"),
])
def test_pixels_form_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


# ---------------------------------------------------------------- held-out scenes
# Settings the paper did not use (and the reproduction was not tuned on): a 7x7 window, a
# Gaussian spot of FWHM 2.5 px whose pixels differ, P_F = 0.01, a 160x192 image, lighter
# clutter, faster targets. They fix the operating range stated in the module docstrings.
def test_held_out_spot_pixel_monte_carlo_follows_the_pixels_form():
    """A sampled Gaussian spot in white noise (7x7 window, FWHM 2.5 px, P_F 0.01)."""
    from eotrack.imaging.dim_targets import fwhm_to_sigma
    from scipy.stats import norm

    rng = np.random.default_rng(2024)
    sig, snr, pf, n = fwhm_to_sigma(2.5), 2.5, 0.01, 200_000
    k = np.arange(-1, 2)
    g = np.exp(-0.5 * np.add.outer(k ** 2, k ** 2) / sig ** 2).ravel()  # 3x3 core profile
    p_pix = norm.sf(norm.isf(pf) - snr * g)
    thr = norm.isf(pf)
    tgt = (rng.standard_normal((n, 9)) + snr * g > thr).sum(axis=1)
    noise = (rng.standard_normal((n, 40)) > thr).sum(axis=1)
    d = tgt + noise
    s = np.arange(1, 10)
    hits = (d[:, None] >= s).sum(axis=0)
    assert mc_agreement(hits, n, hyp.area_detection_pixels(p_pix, pf, 7, s), familywise=True)
    # the single-P_D forms at the core's mean probability do not describe the spot
    assert not mc_agreement(hits, n, hyp.area_detection_exact(p_pix.mean(), pf, 7, 9, s))
    assert not mc_agreement(hits, n, hyp.area_detection(p_pix.mean(), pf, 7, 9, s))


def _faster_target_coverage(speed: float, gate: int, seed: int,
                            direction: tuple[float, float] = (0.8, 0.6)) -> tuple[float, int]:
    from eotrack.experiments.track_init_ht import match_tracks
    from eotrack.imaging import DimSequenceConfig, DimTarget, candidate_frames
    from eotrack.imaging.dim_targets import (
        fwhm_to_sigma,
        peak_snr_for_pixel_pd,
        simulate_dim_sequence,
        straight_path,
    )
    from eotrack.tracking.initiation.temporal import (
        TemporalContinuityInitiator,
        TemporalTestConfig,
    )

    sig = fwhm_to_sigma(3)
    snr = peak_snr_for_pixel_pd(0.98, 0.03, sig, 3)
    path = straight_path((30.0, 40.0), (direction[0] * speed, direction[1] * speed), 30)
    cfg = DimSequenceConfig(shape=(160, 192), n_frames=30, clutter_sigma=10.0,
                            clutter_scale_px=40.0, targets=(DimTarget(path, snr=snr, sigma_px=sig),))
    seq = simulate_dim_sequence(cfg, np.random.default_rng(seed))
    fr, _, _ = candidate_frames(seq.images, seq.times_s, 0.03, 5, 7)
    tracks = TemporalContinuityInitiator(TemporalTestConfig(gate=gate)).initiate(fr)
    owner, cov, _ = match_tracks(tracks, fr, seq.truth_xy)
    return float(cov[0]), int(np.sum(owner < 0))


@pytest.mark.parametrize("speed, gate, direction, recovered", [
    (1.0, 3, (0.8, 0.6), True),   # within n_k = 1 px/frame of the last point: the paper's gate
    (3.0, 3, (0.8, 0.6), False),  # 3 px/frame leaves the 3x3 gate before the velocity fit starts
    (3.0, 5, (0.8, 0.6), True),   # ... a 5x5 gate (n_k = 2) starts it: (2.4, 1.8) px per axis
    (2.0, 5, (1.0, 0.0), True),   # along an axis: 2 px/frame = n_k is inside the 5x5 gate
    (3.0, 5, (1.0, 0.0), False),  # ... 3 px/frame on one axis is not: the limit is per axis
])
def test_held_out_faster_target_and_the_gate(speed, gate, direction, recovered):
    """A 160x192 scene, clutter = noise sigma, P_F 0.03: the temporal test's speed range."""
    res = [_faster_target_coverage(speed, gate, seed, direction) for seed in (1, 2, 3)]
    cov = np.array([c for c, _ in res])
    assert all(f == 0 for _, f in res)  # no false track in this lighter clutter
    if recovered:
        assert np.all(cov >= 0.8)
    else:
        assert np.all(cov < 0.2)


def _chain_event(occ: np.ndarray, gate: int, frames: int, min_hits: int, edge: int):
    """Starts (frame, index) whose nearest-point chain through the gate of the last point
    reaches ``min_hits`` points within ``frames`` frames (the event of eq. 9, followed directly),
    mapped to the chain's points ``(frame, x, y)``."""
    n_fr, h, w = occ.shape
    r = gate // 2
    offs = sorted(((dx, dy) for dx in range(-r, r + 1) for dy in range(-r, r + 1)),
                  key=lambda o: (o[0] ** 2 + o[1] ** 2, o[1], o[0]))  # ties: row-major, as the initiator
    pts = [np.column_stack(np.nonzero(occ[k])[::-1]) for k in range(n_fr)]
    ok, n = {}, 0
    for k in range(n_fr - frames + 1):
        for i, (x, y) in enumerate(pts[k]):
            if not (edge <= x < w - edge and edge <= y < h - edge):
                continue
            n += 1
            cx, cy, chain = x, y, [(k, x, y)]
            for j in range(1, frames):
                hit = next(((dx, dy) for dx, dy in offs if occ[k + j, cy + dy, cx + dx]), None)
                if hit is not None:
                    cx, cy = cx + hit[0], cy + hit[1]
                    chain.append((k + j, cx, cy))
                if len(chain) >= min_hits:
                    ok[(k, i)] = chain
                    break
    return ok, n, pts


@pytest.mark.parametrize("gate, frames, min_hits, p_f, shape", [
    (5, 5, 3, 0.002, (120, 160)),  # held out: a 5x5 gate, T = 5, a rectangular lattice
    (3, 7, 3, 0.005, (150, 150)),  # the notebook's section 4.7 setting
])
def test_held_out_eq9_event_and_the_initiator_below_it(gate, frames, min_hits, p_f, shape):
    """Eq. (9) is exact for its event (inside the 99.9 % Clopper-Pearson interval); every false
    track of the initiator starts where that event succeeded, so eq. (9) bounds it from above."""
    from eotrack.tracking.initiation.temporal import (
        TemporalContinuityInitiator,
        TemporalTestConfig,
    )

    occ = np.random.default_rng(99).random((40, *shape)) < p_f
    edge = 2 * (gate // 2) + 1
    ok, n, pts = _chain_event(occ, gate, frames, min_hits, edge)
    pred = hyp.track_false_alarm(p_f, gate, frames - 1, min_hits - 1)
    assert mc_agreement(len(ok), n, pred, method="clopper-pearson")
    fr = [(float(k), p.astype(float)) for k, p in enumerate(pts)]
    cfg = TemporalTestConfig(gate=gate, frames=frames, min_hits=min_hits, predict="last")
    starts = {t.hits[0] for t in TemporalContinuityInitiator(cfg).initiate(fr)
              if t.hits[0][0] <= len(pts) - frames}
    starts = {(k, i) for k, i in starts
              if np.all((pts[k][i] >= edge) & (pts[k][i] < np.array(shape[::-1]) - edge))}
    assert starts and starts <= set(ok)
    # the initiator drops hypotheses sharing points with a confirmed track: it reports the
    # distinct chains (those reusing no point of an earlier one), up to a few
    used, distinct = set(), 0
    for key in sorted(ok):
        if not used.intersection(ok[key]):
            distinct += 1
            used.update(ok[key])
    assert abs(len(starts) - distinct) <= max(3, 0.05 * distinct)
    # a wrong gate (one size larger) is rejected by the same interval
    assert not mc_agreement(len(ok), n, hyp.track_false_alarm(p_f, gate + 2, frames - 1,
                                                              min_hits - 1))
