"""The growth engine of the verified modified Hough initiator (issue 27, ``grow=True``)."""

from dataclasses import replace

import numpy as np
import pytest
from eotrack.experiments import track_init_hough as TH
from eotrack.tracking.initiation import LogicInitiator, ModifiedHoughInitiator
from eotrack.tracking.initiation.modified_hough import _ca_fit, _ca_predict
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.stats import chi2


def test_constant_acceleration_fit_matches_polyfit():
    rng = np.random.default_rng(3)
    t = np.cumsum(rng.uniform(0.6, 1.6, 7))
    xy = rng.uniform(0, 500, (70, 2))
    rows = np.full((3, 7), -1)
    for i, cols in enumerate(([0, 2, 3, 5, 6], [1, 2, 4], [0, 1, 2, 3, 4, 5, 6])):
        rows[i, cols] = np.array(cols) * 10 + i
    tm, coef, rss, _ = _ca_fit(t, xy, rows)
    tq = t[[1, 0, 3]]
    pred, lev = _ca_predict(t, xy, rows, tq)
    for i in range(3):
        m = rows[i] >= 0
        X = np.vander(t[m] - tm[i], 3, increasing=True)
        c, *_ = np.linalg.lstsq(X, xy[rows[i][m]], rcond=None)
        assert np.allclose(coef[i], c)
        assert rss[i] == pytest.approx(np.sum((X @ c - xy[rows[i][m]]) ** 2), abs=1e-6)
        x = np.array([1.0, tq[i] - tm[i], (tq[i] - tm[i]) ** 2])
        assert pred[i] == pytest.approx(x @ c)
        assert lev[i] == pytest.approx(x @ np.linalg.inv(X.T @ X) @ x)


@given(st.integers(0, 2**32 - 1))
@settings(max_examples=15, deadline=None)
def test_grown_tracks_pass_their_tests(seed):
    """Every track: one detection per frame, 3 of some 4 consecutive frames by its
    confirmation, the velocity gate, the constant-acceleration χ² (>= 4 hits) or the
    constant-velocity / acceleration-widened test (3 hits); a detection is in two tracks only
    when two three-hit tracks share it (``share_missed``)."""
    rng = np.random.default_rng(seed)
    frames = [(float(k) + rng.uniform(0, 0.5), rng.uniform(0, 200, (rng.integers(0, 25), 2)))
              for k in range(7)]
    ini = ModifiedHoughInitiator(sigma_px=0.8, grow_min_accelerating=0)  # growth forced
    tracks = ini.initiate(frames)
    owner: dict = {}
    for tr in tracks:
        fs = [f for f, _ in tr.hits]
        assert len(set(fs)) == len(fs) >= 3
        conf = np.array([f for f in fs if f <= tr.confirmed_at])
        assert any(np.sum((conf >= k - 3) & (conf <= k)) >= 3 for k in conf)
        t = np.array([frames[f][0] for f in fs])
        xy = np.array([frames[f][1][d] for f, d in tr.hits])
        coef = np.polyfit(t, xy, 1)
        assert ini.v_min - 1e-9 <= np.hypot(*coef[0]) <= ini.v_max + 1e-9
        if len(fs) >= 4:
            q = np.polyfit(t, xy, 2)
            rq = np.sum((np.polyval(q[:, 0], t) - xy[:, 0]) ** 2
                        + (np.polyval(q[:, 1], t) - xy[:, 1]) ** 2)
            assert rq / ini.sigma_px**2 <= chi2.ppf(1 - ini.alpha, 2 * (len(fs) - 3)) + 1e-6
        for h in tr.hits:
            owner.setdefault(h, []).append(len(fs))
    for h, ns in owner.items():
        assert len(ns) == 1 or (len(ns) == 2 and ns == [3, 3]), (h, ns)


def test_a_burst_frame_cannot_take_a_longer_track():
    """An accelerating object seen in 6 of 7 irregular frames, with 150 false alarms in one
    frame and a decoy on the constant-velocity chord of its first hits: one pure track."""
    rng = np.random.default_rng(21)
    t = np.array([0.0, 0.9, 2.3, 3.0, 4.4, 5.1, 6.5])
    p0, v0, acc = np.array([90.0, 140.0]), np.array([45.0, 20.0]), np.array([3.0, -2.8])
    frames = []
    for k, tk in enumerate(t):
        obj = (p0 + v0 * tk + 0.5 * acc * tk**2 + rng.normal(0, 0.3, 2))[None]
        if k == 4:
            obj = obj[:0]  # missed
        n_fa = 150 if k == 2 else 10
        frames.append((float(tk), np.vstack([obj, rng.uniform(0, 512, (n_fa, 2))])))
    tracks = ModifiedHoughInitiator(v_min=3, v_max=240, grow_min_accelerating=0).initiate(frames)
    pure = [tr for tr in tracks if all(d == 0 for _, d in tr.hits)]
    assert len(pure) == 1 and len(pure[0].hits) == 6


@pytest.mark.xfail(reason="not met: recall 35/40 on this sample with the default of 2026-12-02 "
                          "15:30 UTC (the growth engine runs on every scene of this family, as "
                          "with growth always on; 30/40 before); issue 27's held-out target, see "
                          "the benchmark", strict=False)
def test_small_held_out_sample():
    """A regression guard on a small sample of the held-out family (seed 3: neither the
    decisive seed nor a tuning one; the criterion is judged in the benchmark on 60 scenes):
    recall >= 0.90 and no more false tracks than logic 3/4."""
    rng = np.random.default_rng(3)
    ours = ModifiedHoughInitiator(v_min=3, v_max=240)
    logic = LogicInitiator(n=3, m=4, v_min=3, v_max=240, gate_px=10.0)
    tot = np.zeros((2, 3))
    for _ in range(12):
        sc = TH.heldout_scene(rng, TH.HeldOutConfig())
        for i, ini in enumerate((ours, logic)):
            r = TH.score_tracks(ini.initiate(sc.frames), sc)
            tot[i] += (r["correct"], r["eligible"], r["false"])
    assert tot[0, 0] / tot[0, 1] >= 0.90
    assert tot[0, 2] <= tot[1, 2]


def test_constant_velocity_scenes_keep_the_causal_engine():
    """No accelerating track in the causal result: the causal engine's tracks are returned."""
    rng = np.random.default_rng(4)
    sc = TH.planted_scene(rng, TH.PlantedConfig())
    a = ModifiedHoughInitiator(v_min=3, v_max=240).initiate(sc.frames)
    b = ModifiedHoughInitiator(v_min=3, v_max=240, grow=False).initiate(sc.frames)
    assert [tr.hits for tr in a] == [tr.hits for tr in b]


@pytest.mark.parametrize("lam", [30.0, 50.0])
def test_clutter_only_scenes_keep_the_causal_engine(lam):
    """Pure clutter (no object, no burst): chance four-hit tracks that only a
    constant-acceleration fit explains must not switch the growth engine on."""
    rng = np.random.default_rng(7)
    cfg = replace(TH.PlantedConfig(), clutter_per_frame=(lam, lam))
    ini = ModifiedHoughInitiator(v_min=3, v_max=240)
    for _ in range(6):
        sc = TH.planted_scene(rng, cfg, n_objects=0, n_stars=0)
        a = ini.initiate(sc.frames)
        b = replace(ini, grow=False).initiate(sc.frames)
        assert [tr.hits for tr in a] == [tr.hits for tr in b]


def test_a_clutter_burst_runs_the_growth_engine():
    """One frame with 150 extra false alarms: the growth engine's tracks are returned even when
    the causal result shows no accelerating track."""
    rng = np.random.default_rng(5)
    frames = [(float(k), rng.uniform(0, 512, (20 + (150 if k == 3 else 0), 2)))
              for k in range(6)]
    ini = ModifiedHoughInitiator(v_min=3, v_max=240)
    a = ini.initiate(frames)
    g = replace(ini, grow_min_accelerating=0).initiate(frames)
    c = replace(ini, grow_burst=0.0).initiate(frames)
    assert [tr.hits for tr in a] == [tr.hits for tr in g]
    assert [tr.hits for tr in a] != [tr.hits for tr in c]


def test_grow_burst_is_checked():
    with pytest.raises(ValueError, match="grow_burst"):
        ModifiedHoughInitiator(grow_burst=-1.0)


def test_crowded_frames_run_the_causal_engine():
    rng = np.random.default_rng(1)
    frames = [(float(k), rng.uniform(0, 512, (1000, 2))) for k in range(4)]
    a = ModifiedHoughInitiator(grow_min_accelerating=0).initiate(frames)
    b = ModifiedHoughInitiator(grow=False).initiate(frames)
    assert [tr.hits for tr in a] == [tr.hits for tr in b]
