"""Logic n/m initiation (plain and angle-constrained) and the shared gating helpers."""

import numpy as np
import pytest
from eotrack.tracking.initiation import (
    AngleConstrainedLogicInitiator,
    LogicInitiator,
    TrackHandOff,
    angle_at_middle_deg,
    check_velocity_gate,
    fit_constant_velocity,
    logic_false_track_rate,
    validate_frames,
    velocity_gated_pairs,
)
from hypothesis import given, settings
from hypothesis import strategies as st

PLANTED = [((60.0, 420.0), (35.0, -22.0), (0, 1, 2, 3)),
           ((80.0, 80.0), (40.0, 30.0), (0, 1, 3)),
           ((450.0, 100.0), (-25.0, 45.0), (0, 2, 3)),
           ((150.0, 250.0), (60.0, 5.0), (1, 2, 3))]


def planted_frames(times=(0.0, 1.0, 2.0, 3.0), clutter=None):
    frames, truth = [], []
    for k, t in enumerate(times):
        xy, lab = [], []
        for i, (p, v, fs) in enumerate(PLANTED):
            if k in fs:
                xy.append(np.add(p, np.multiply(v, t)))
                lab.append(i)
        if clutter is not None:
            xy += list(clutter[k])
            lab += [-1] * len(clutter[k])
        frames.append((t, np.array(xy).reshape(-1, 2)))
        truth.append(np.array(lab))
    return frames, truth


def as_sets(tracks, frames):
    return {tuple(sorted((f, tuple(np.round(frames[f][1][d], 6))) for f, d in tr.hits))
            for tr in tracks}


def test_planted_scene_exact_recovery_3_of_4():
    frames, truth = planted_frames()
    tracks = LogicInitiator().initiate(frames)
    assert len(tracks) == 4
    got = {}
    for tr in tracks:
        ids = {int(truth[f][d]) for f, d in tr.hits}
        assert len(ids) == 1
        i = ids.pop()
        assert sorted(f for f, _ in tr.hits) == list(PLANTED[i][2])
        got[i] = tr.confirmed_at
    assert got == {0: 2, 1: 3, 2: 3, 3: 3}


def test_two_of_three_confirms_at_the_second_detection():
    frames = [(0.0, [[100.0, 100.0]]), (1.0, [[130.0, 100.0]]), (2.0, [[160.0, 100.0]])]
    tracks = LogicInitiator(n=2, m=3).initiate(frames)
    assert len(tracks) == 1 and tracks[0].confirmed_at == 1
    assert [f for f, _ in tracks[0].hits] == [0, 1, 2]  # the hand-off keeps the third


def test_uneven_times():
    frames, _ = planted_frames(times=(0.0, 0.6, 2.0, 2.5))
    assert len(LogicInitiator().initiate(frames)) == 4


def test_angle_constraint_rejects_v_shape():
    v_shape = [(0.0, [[100.0, 100.0]]), (1.0, [[130.0, 100.0]]), (2.0, [[120.0, 110.0]])]
    assert angle_at_middle_deg([100, 100], [130, 100], [120, 110]) == pytest.approx(45.0)
    plain = LogicInitiator(n=3, m=3, gate_px=50.0)
    angle = AngleConstrainedLogicInitiator(n=3, m=3, gate_px=50.0)
    assert len(plain.initiate(v_shape)) == 1
    assert angle.initiate(v_shape) == []
    straight = [(0.0, [[100.0, 100.0]]), (1.0, [[130.0, 100.0]]), (2.0, [[161.0, 101.0]])]
    assert len(angle.initiate(straight)) == 1
    assert angle.label == "angle logic 3/3" and plain.label == "logic 3/3"


def test_empty_frames():
    assert LogicInitiator().initiate([]) == []
    assert LogicInitiator().initiate([(0.0, np.zeros((0, 2)))] * 1) == []


@given(st.integers(0, 2**32 - 1))
@settings(max_examples=10, deadline=None)
def test_result_independent_of_detection_order(seed):
    rng = np.random.default_rng(seed)
    clutter = [rng.uniform(0, 512, (8, 2)) for _ in range(4)]
    frames, _ = planted_frames(clutter=clutter)
    for ini in (LogicInitiator(), LogicInitiator(n=2, m=3)):
        ref = as_sets(ini.initiate(frames), frames)
        shuffled = [(t, xy[rng.permutation(len(xy))]) for t, xy in frames]
        assert as_sets(ini.initiate(shuffled), shuffled) == ref


@pytest.mark.parametrize(("kw", "match"), [
    ({"m": 1}, "m must be >= 2"),
    ({"n": 4, "m": 3}, "n must be <= 3"),
    ({"n": 1}, "n must be >= 2"),
    ({"v_min": 50.0, "v_max": 20.0}, "v_min < v_max"),
    ({"gate_px": 0.0}, "gate_px"),
    ({"min_angle_deg": 180.0}, "min_angle_deg"),
])
def test_bad_config(kw, match):
    with pytest.raises(ValueError, match=match):
        LogicInitiator(**kw)


def test_bad_frames():
    with pytest.raises(ValueError, match="increasing time order"):
        LogicInitiator().initiate([(1.0, [[1, 2]]), (0.5, [[1, 2]])])
    with pytest.raises(ValueError, match="shape"):
        LogicInitiator().initiate([(0.0, [1, 2])])


# ---------------------------------------------------------------- analytic false-track rate
def test_false_track_rate_properties():
    pp = [0.4, 0.9, 0.95]
    assert logic_false_track_rate(3, 4, 0.0, pp, 0.001) == 0.0
    r = [logic_false_track_rate(3, 4, lam, pp, 0.001) for lam in (1, 2, 4, 8)]
    assert np.all(np.diff(r) > 0)
    # 2/3: every gated pair is a track -> N_c^2 (p1 + p2)
    assert logic_false_track_rate(2, 3, 2.0, pp, 0.001) == pytest.approx(4 * (0.4 + 0.9))
    # the prediction leaving the field lowers the rate
    assert logic_false_track_rate(3, 4, 4.0, pp, 0.01, [[0.5, 0.3], [0.5], []]) < \
        logic_false_track_rate(3, 4, 4.0, pp, 0.01)


def test_false_track_rate_bad_input():
    with pytest.raises(ValueError, match="pair_prob"):
        logic_false_track_rate(3, 4, 1.0, [0.4], 0.01)
    with pytest.raises(ValueError, match="clutter_per_frame"):
        logic_false_track_rate(3, 4, -1.0, [0.4, 0.5, 0.6], 0.01)


# ---------------------------------------------------------------- gating helpers
def test_velocity_gated_pairs():
    a = np.array([[0.0, 0.0], [100.0, 0.0]])
    b = np.array([[5.0, 0.0], [30.0, 0.0], [400.0, 0.0]])
    ia, ib, vel = velocity_gated_pairs(a, 0.0, b, 2.0, 10.0, 100.0)
    got = {(int(i), int(j)) for i, j in zip(ia, ib)}
    assert got == {(0, 1), (1, 0), (1, 1)}  # speeds 15, 47.5, 35 px/s
    np.testing.assert_allclose(vel[0], [15.0, 0.0])
    with pytest.raises(ValueError, match="t_b must be later"):
        velocity_gated_pairs(a, 1.0, b, 1.0, 10.0, 100.0)
    with pytest.raises(ValueError, match="v_min < v_max"):
        velocity_gated_pairs(a, 0.0, b, 1.0, 100.0, 10.0)


def test_check_velocity_gate():
    assert check_velocity_gate(0, 5) == (0.0, 5.0)
    with pytest.raises(ValueError, match="v_min"):
        check_velocity_gate(-1, 5)
    with pytest.raises(ValueError, match="v_min < v_max"):
        check_velocity_gate(5, 5)


@given(st.floats(-50, 50), st.floats(-50, 50), st.floats(-20, 20), st.floats(-20, 20))
@settings(max_examples=30, deadline=None)
def test_fit_constant_velocity_exact_on_lines(x0, y0, vx, vy):
    t = np.array([0.0, 0.5, 2.0, 3.5])
    xy = np.stack([x0 + vx * t, y0 + vy * t], 1)
    pm, v = fit_constant_velocity(t, xy)
    np.testing.assert_allclose(v, [vx, vy], atol=1e-9)
    np.testing.assert_allclose(pm + v * (0.0 - t.mean()), [x0, y0], atol=1e-9)


def test_fit_constant_velocity_bad_input():
    with pytest.raises(ValueError, match="two distinct times"):
        fit_constant_velocity([1.0, 1.0], [[0, 0], [1, 1]])
    with pytest.raises(ValueError, match="same length"):
        fit_constant_velocity([1.0, 2.0, 3.0], [[0, 0], [1, 1]])


@given(st.floats(0.1, 179.9))
@settings(max_examples=30, deadline=None)
def test_angle_at_middle(angle):
    a = np.radians(angle)
    p0 = [10.0, 0.0]
    p2 = [10 * np.cos(a), 10 * np.sin(a)]
    assert angle_at_middle_deg(p0, [0.0, 0.0], p2) == pytest.approx(angle, abs=1e-6)


def test_handoff_claims_nearest_and_validates():
    with pytest.raises(ValueError, match="gate_px"):
        TrackHandOff(0.0)
    fr = validate_frames([(0.0, [[0.0, 0.0]]), (1.0, [[10.0, 0.0]]),
                          (2.0, [[20.5, 0.0], [23.0, 0.0]])])
    h = TrackHandOff(2.0)
    h.confirm([(0, 0), (1, 0)], 1, fr)
    avail = np.ones(2, dtype=bool)
    claimed = h.claim(2, 2.0, fr[2].xy, avail)
    assert claimed.tolist() == [True, False] and avail.tolist() == [False, True]
    assert h.tracks()[0].hits == [(0, 0), (1, 0), (2, 0)]


@given(st.integers(0, 2**32 - 1), st.sampled_from([3, 4, 5]), st.booleans(),
       st.sampled_from([15.0, 60.0]))
@settings(max_examples=30, deadline=None)
def test_triplet_fast_path_equals_row_engine(seed, m, angle, gate):
    """The n = 3 fast path (no stored tentative tracks) gives the row engine's tracks."""
    from eotrack.tracking.initiation import logic as L
    from eotrack.tracking.initiation.gating import canonical_order

    rng = np.random.default_rng(seed)
    t = np.cumsum(rng.uniform(0.5, 1.5, 6))
    frames = [(float(tk), rng.uniform(0, 300, (rng.integers(0, 40), 2))) for tk in t]
    obj = rng.uniform(50, 250, 2), rng.uniform(-30, 30, 2)
    frames = [(tk, np.concatenate([xy, [obj[0] + obj[1] * (tk - t[0])]])) for tk, xy in frames]
    cfg = L.LogicInitiator(n=3, m=m, gate_px=gate, min_angle_deg=90.0 if angle else None)
    perms = [canonical_order(xy) for _, xy in frames]
    xys = [xy[p] for (_, xy), p in zip(frames, perms)]
    fast = L._TripletLogicRun(cfg, xys, t).run(perms)
    rows = L._LogicRun(cfg, xys, t).run(perms)
    assert [(tr.hits, tr.confirmed_at) for tr in fast] == [(tr.hits, tr.confirmed_at)
                                                            for tr in rows]
