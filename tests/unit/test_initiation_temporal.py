"""Temporal-continuity (hypothesis-testing) track initiation."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.tracking import hypothesis as hyp
from eotrack.tracking.initiation.base import Initiator, Track
from eotrack.tracking.initiation.temporal import TemporalContinuityInitiator, TemporalTestConfig


def _frames(points_per_frame):
    return [(0.1 * k, np.asarray(p, float).reshape(-1, 2)) for k, p in enumerate(points_per_frame)]


def test_protocol_and_straight_target():
    ini = TemporalContinuityInitiator()
    assert isinstance(ini, Initiator)
    pts = [[[10 + 0.5 * k, 20 + 0.3 * k], [50 + 7 * k, 5 + 11 * k % 40]] for k in range(12)]
    tracks = ini.initiate(_frames(pts))
    assert len(tracks) == 1
    tr = tracks[0]
    assert isinstance(tr, Track)
    assert tr.confirmed_at == 4  # 5th hit (T_h = 5)
    assert tr.hits == [(k, 0) for k in range(12)]
    assert ini.stats["hypotheses"] >= 12


def test_missed_frames_and_rejection():
    # hits in frames 0,1,3,4,6 -> 5 of the first 7 frames: confirmed at frame 6
    keep = {0, 1, 3, 4, 6}
    pts = [[[30 + 0.4 * k, 30.0]] if k in keep else [] for k in range(9)]
    tracks = TemporalContinuityInitiator().initiate(_frames(pts))
    assert len(tracks) == 1 and tracks[0].confirmed_at == 6
    # only 4 of 7: rejected
    keep = {0, 1, 3, 6}
    pts = [[[30 + 0.4 * k, 30.0]] if k in keep else [] for k in range(9)]
    assert TemporalContinuityInitiator().initiate(_frames(pts)) == []


def test_gate_limits_association():
    # jumps of 2 px leave a 3x3 gate (n_k = 1); a 5x5 gate follows them
    pts = [[[10 + 2.0 * k, 10.0]] for k in range(8)]
    assert TemporalContinuityInitiator(TemporalTestConfig(predict="last")).initiate(
        _frames(pts)) == []
    cfg = TemporalTestConfig(gate=5, predict="last")
    assert len(TemporalContinuityInitiator(cfg).initiate(_frames(pts))) == 1
    # the velocity prediction follows the 2 px/frame target with a 5x5 gate as well
    assert len(TemporalContinuityInitiator(TemporalTestConfig(gate=5)).initiate(
        _frames(pts))) == 1


def test_curved_target_followed_with_velocity_prediction():
    phi = 0.05 * np.arange(30)
    pts = [[[60 + 20 * np.cos(p), 60 + 20 * np.sin(p)]] for p in phi]
    tracks = TemporalContinuityInitiator().initiate(_frames(pts))
    assert len(tracks) == 1 and len(tracks[0].hits) == 30


def test_false_track_rate_matches_eq9_on_random_lattice():
    # Bernoulli false alarms on a pixel lattice: fraction of hypotheses confirmed ~ eq. (9)
    rng = np.random.default_rng(0)
    p_f, n_fr, size = 0.005, 40, 150
    frames = []
    for k in range(n_fr):
        yy, xx = np.nonzero(rng.random((size, size)) < p_f)
        frames.append((float(k), np.column_stack([xx, yy]).astype(float)))
    cfg = TemporalTestConfig(gate=3, frames=7, min_hits=3)
    ini = TemporalContinuityInitiator(cfg)
    tracks = ini.initiate(frames)
    last = n_fr - cfg.frames
    n_conf = sum(t.info["start_frame"] <= last for t in tracks)
    n_hyp = sum(ini.stats["opened_per_frame"][:last + 1])
    # a hypothesis starts with one point, then needs T_h - 1 of the next T - 1 frames
    p_ft = hyp.track_false_alarm(p_f, 3, 6, 2)
    assert 0.6 * p_ft < n_conf / n_hyp < 1.4 * p_ft


def test_empty_frames():
    assert TemporalContinuityInitiator().initiate(_frames([[]] * 5)) == []
    assert TemporalContinuityInitiator().initiate([]) == []


def test_bad_input():
    with pytest.raises(ValueError, match="min_hits"):
        TemporalTestConfig(frames=5, min_hits=6)
    with pytest.raises(ValueError, match="gate"):
        TemporalTestConfig(gate=4)
    with pytest.raises(ValueError, match="gate"):
        TemporalTestConfig(gate=0)
    with pytest.raises(ValueError, match="predict"):
        TemporalTestConfig(predict="kalman")
    with pytest.raises(TypeError, match="config"):
        TemporalContinuityInitiator({"gate": 3})
    with pytest.raises(ValueError, match="frames"):
        TemporalContinuityInitiator().initiate([(0.0, np.zeros((1, 3)))])
    with pytest.raises(TypeError, match="frames"):
        TemporalContinuityInitiator().initiate(np.zeros((3, 2)))
