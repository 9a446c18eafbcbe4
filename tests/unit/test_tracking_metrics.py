"""GOSPA and SIAP of track initiation: Stone Soup against hand implementations."""

import numpy as np
import pytest
from eotrack.tracking.initiation import ModifiedHoughInitiator
from eotrack.tracking.initiation.base import Track
from eotrack.tracking.metrics import (
    _siap_stonesoup,
    gospa,
    gospa_reference,
    initiation_metrics,
    siap_reference,
    track_states,
)


@pytest.mark.parametrize("seed", range(6))
def test_gospa_stonesoup_equals_hand_assignment(seed):
    rng = np.random.default_rng(seed)
    x = rng.uniform(0, 50, (rng.integers(0, 7), 2))
    y = rng.uniform(0, 50, (rng.integers(0, 7), 2))
    for p in (1.0, 2.0):
        a, b = gospa(x, y, c=10.0, p=p), gospa_reference(x, y, c=10.0, p=p)
        for k in ("distance", "localisation", "missed", "false"):
            assert a[k] == pytest.approx(b[k], abs=1e-9), (k, p)
        assert (a["n_missed"], a["n_false"]) == (b["n_missed"], b["n_false"])


def test_gospa_by_hand():
    # one pair 3 px apart, one truth missed, two false estimates far away; c = 10, p = 1
    x = np.array([[0.0, 0.0], [100.0, 0.0], [200.0, 0.0]])
    y = np.array([[3.0, 0.0], [0.0, 100.0]])
    g = gospa(x, y, c=10.0)
    assert g["localisation"] == pytest.approx(3.0)
    assert g["missed"] == pytest.approx(5.0) and g["false"] == pytest.approx(10.0)
    assert g["distance"] == pytest.approx(18.0)
    assert gospa(np.zeros((0, 2)), np.zeros((0, 2)), c=10.0)["distance"] == 0.0


def test_gospa_bad_input():
    with pytest.raises(ValueError, match="estimates"):
        gospa(np.zeros((3, 3)), np.zeros((1, 2)), c=1.0)
    with pytest.raises(ValueError, match="c"):
        gospa_reference(np.zeros((1, 2)), np.zeros((1, 2)), c=0.0)
    with pytest.raises(ValueError, match="p must be >= 1"):
        gospa(np.zeros((1, 2)), np.zeros((1, 2)), c=1.0, p=0.5)


def _scene():
    """Two straight objects over 5 frames, one leaving the field; one false track."""
    times = np.arange(5.0)
    truth = [np.array([[10.0 + 5 * t, 20.0], [90.0 + 4 * t, 50.0]]) for t in times]
    frames = [(t, np.vstack([tr, [[60.0 + 7 * t, 80.0]]])) for t, tr in zip(times, truth)]
    tracks = [Track(hits=[(k, 0) for k in range(5)], confirmed_at=2),
              Track(hits=[(k, 2) for k in range(5)], confirmed_at=3)]
    return frames, truth, tracks


def test_siap_stonesoup_equals_hand_count():
    frames, truth, tracks = _scene()
    pos = track_states(tracks, frames)
    ks = range(2, 5)
    ref = siap_reference(pos, truth, threshold=5.0, width=100.0, frames_eval=ks)
    # by hand: truth points at k = 2, 3, 4: object 0 (3) + object 1 inside (98 ≥ 100 at k=4?
    # 90 + 4k: 98, 102 → present at k = 2 only) = 4; associated: object 0 at 3 frames → JT = 3
    assert (ref["J"], ref["JT"]) == (4, 3)
    # track points: track 0 at k = 2, 3, 4, track 1 at k = 3, 4 → N = 5, NA = 3
    assert (ref["N"], ref["NA"]) == (5, 3)
    c, s = _siap_stonesoup(pos, truth, np.arange(5.0), threshold=5.0, width=100.0,
                           frames_eval=ks)
    assert c == pytest.approx(ref["completeness"]) and c == pytest.approx(0.75)
    assert s == pytest.approx(ref["spuriousness"]) and s == pytest.approx(0.4)


def test_initiation_metrics_on_a_small_scene():
    rng = np.random.default_rng(3)
    times = np.arange(6.0)
    p0 = np.array([[50.0, 60.0], [300.0, 200.0], [100.0, 400.0]])
    v = np.array([[20.0, 5.0], [-15.0, 12.0], [30.0, -25.0]])
    truth = [p0 + v * t for t in times]
    frames = [(t, np.vstack([tr + rng.normal(0, 0.3, tr.shape), rng.uniform(0, 512, (15, 2))]))
              for t, tr in zip(times, truth)]
    tracks = ModifiedHoughInitiator(v_min=3, v_max=240).initiate(frames)
    m = initiation_metrics(tracks, frames, truth, width=512.0, c=10.0, first_frame=3)
    assert m["siap completeness"] == pytest.approx(1.0)
    assert 0 <= m["siap spuriousness"] < 0.5
    assert m["gospa missed"] == pytest.approx(0.0)
    assert m["gospa localisation"] < 3 * 1.0  # three tracks at ~0.3 px each
    assert m["gospa"] == pytest.approx(m["gospa localisation"] + m["gospa missed"]
                                       + m["gospa false"])
    with pytest.raises(ValueError, match="truth_xy"):
        initiation_metrics(tracks, frames, truth[:-1], width=512.0)
    with pytest.raises(ValueError, match="first_frame"):
        initiation_metrics(tracks, frames, truth, width=512.0, first_frame=9)
    with pytest.raises(TypeError, match="Track"):
        track_states([object()], frames)


def test_siap_with_nothing_to_score():
    c, s = _siap_stonesoup([], [np.zeros((0, 2))] * 3, np.arange(3.0), threshold=5.0,
                           width=100.0, frames_eval=range(3))
    assert np.isnan(c) and s == 0.0
    assert np.isnan(siap_reference([], [np.zeros((0, 2))] * 3, threshold=5.0, width=100.0,
                                   frames_eval=range(3))["completeness"])


def test_initiation_metrics_one_scored_frame_and_ragged_truth():
    """One scored frame (a burst that lost frames) gives SIAP by the hand count instead of
    Stone Soup's time-range error; per-frame truth arrays of different lengths are refused."""
    frames, truth, tracks = _scene()
    last = len(frames) - 1
    m = initiation_metrics(tracks, frames, truth, width=100.0, c=5.0, first_frame=last)
    ref = siap_reference(track_states(tracks, frames), truth, threshold=5.0, width=100.0,
                         frames_eval=[last])
    assert m["siap completeness"] == pytest.approx(ref["completeness"], nan_ok=True)
    assert m["siap spuriousness"] == pytest.approx(ref["spuriousness"], nan_ok=True)
    ragged = [t if k else t[:1] for k, t in enumerate(truth)]
    with pytest.raises(ValueError, match="same number of rows"):
        initiation_metrics(tracks, frames, ragged, width=100.0)
