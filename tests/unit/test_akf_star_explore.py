"""Tests of the akf_star Explore session: the reproduction's measurements re-filtered, nothing
simulated on a panel control, the same sequences as the ablation and as a fresh session."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from eotrack.experiments import akf_star as A
from eotrack.montecarlo import TrialRunner
from eotrack.tracking.kalman import ConfidenceConfig

N_FRAMES = 30
SCS = ("strong_light", "cloud")          # cloud keeps its index in SCENARIOS (1)


@pytest.fixture(scope="module")
def res():
    return A.run_ablation(A.AblationConfig(n_seeds=2, n_frames=N_FRAMES), scenarios=SCS)


def test_ablation_keeps_its_measurements(res):
    assert len(res.measurements) == len(SCS)
    assert all(len(m) == 2 for m in res.measurements)
    m = res.measurements[1][0]
    assert m.truth.shape == (N_FRAMES, 2) and m.x0.shape == (2,)
    assert set(m.detections) == {"global", "adaptive"}
    assert len(m.detections["adaptive"][0]) == N_FRAMES


def test_session_reproduces_the_ablation_without_simulating(res):
    s = A.ExploreSession(ablation=res)
    for i, sc in enumerate(SCS):
        for k in range(2):
            e = s.errors(sc, seed=k)
            for j, v in enumerate(A.VARIANTS):
                np.testing.assert_allclose(e[v], res.errors[i, k, j], atol=1e-4)
    assert s.n_simulated == 0


def test_fresh_session_simulates_the_same_sequence(res):
    s = A.ExploreSession(n_frames=N_FRAMES)
    e = s.errors("cloud", seed=1)
    for j, v in enumerate(A.VARIANTS):
        np.testing.assert_allclose(e[v], res.errors[1, 1, j], atol=1e-4)
    assert s.n_simulated == 1
    s.errors("cloud", seed=1, confidence=ConfidenceConfig(gamma=3.0))
    assert s.n_simulated == 1


def test_precompute_then_no_control_simulates(res):
    s = A.ExploreSession(ablation=res)
    assert s.precompute(seeds=(0, 1), occlusions=(10, 25)) == 2   # cloud × 25 frames only
    n = s.n_simulated
    for sc in SCS:
        for k in (0, 1):
            for occ in (10, 25):
                for g in (3.0, 5.0):
                    s.errors(sc, seed=k, occlusion_frames=occ,
                             confidence=ConfidenceConfig(gamma=g))
    assert s.n_simulated == n
    # no clouds: the occlusion length is the same sequence
    a = s.errors("strong_light", seed=0, occlusion_frames=10)
    b = s.errors("strong_light", seed=0, occlusion_frames=25)
    assert all(a[v] is b[v] for v in A.VARIANTS)
    # clouds: another occlusion length is another sequence with the same truth (ship motion)
    assert np.array_equal(s.measurements("cloud", 0, 25).truth,
                          s.measurements("cloud", 0, 10).truth)


def test_filter_setting_reruns_only_the_confidence_filter(res):
    s = A.ExploreSession(ablation=res)
    a = s.errors("cloud", seed=0)
    b = s.errors("cloud", seed=0, confidence=ConfidenceConfig(lam=1.0, gamma=1.0, eta=5.0))
    assert a["Baseline"] is b["Baseline"] and a["BEAK-ST-SKF"] is b["BEAK-ST-SKF"]
    assert not np.array_equal(a["BEAK-ST"], b["BEAK-ST"])
    assert s.errors("cloud", seed=0)["BEAK-ST"] is a["BEAK-ST"]          # cached
    assert not a["BEAK-ST"].flags.writeable
    assert list(s.errors("cloud", variants=("BEAK-ST", "Baseline"))) == ["Baseline", "BEAK-ST"]


def test_bad_input(res):
    with pytest.raises(TypeError, match="ablation"):
        A.ExploreSession(ablation="res")
    bare = A.AblationResult(res.errors, res.modes, res.visible, res.scenarios, res.variants,
                            res.config)
    with pytest.raises(ValueError, match="measurements"):
        A.ExploreSession(ablation=bare)
    with pytest.raises(ValueError, match="n_frames"):
        A.ExploreSession(n_frames=N_FRAMES + 1, ablation=res)
    with pytest.raises(ValueError, match="maxsize"):
        A.ExploreSession(maxsize=0)
    s = A.ExploreSession(ablation=res)
    with pytest.raises(ValueError, match="scenario_name"):
        s.errors("sway")                       # not among this ablation's scenarios
    with pytest.raises(ValueError, match="seed"):
        s.errors("cloud", seed=-1)
    with pytest.raises(ValueError, match="occlusion_frames"):
        s.errors("cloud", occlusion_frames=0)
    with pytest.raises(ValueError, match="variants"):
        s.errors("cloud", variants=("Kalman",))
    with pytest.raises(TypeError, match="confidence"):
        s.errors("cloud", confidence={"gamma": 3.0})
    with pytest.raises(ValueError, match="methods"):
        A.measure_sequence(np.random.default_rng(0), "cloud", res.config, methods=("otsu",))
    only_adaptive = A.SequenceMeasurements(
        res.measurements[0][0].truth, res.measurements[0][0].x0,
        res.measurements[0][0].sensor,
        {"adaptive": res.measurements[0][0].detections["adaptive"]},
        res.measurements[0][0].visible)
    with pytest.raises(ValueError, match="global"):
        A.track_measurements(only_adaptive, res.config)
    with pytest.raises(ValueError, match="scenario_index"):
        A.sequence_seed(res.config, -1)
    with pytest.raises(ValueError, match="errors"):
        A.plot_explore_errors({}, "empty")


def test_curves_by_scenario_one_panel_per_scenario_and_bad_kind():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    import pytest
    from eotrack.experiments import akf_star as A

    cfg = A.AblationConfig(n_seeds=2, n_frames=20)
    res = A.AblationResult(np.ones((2, 2, 4, 20), np.float32), np.zeros((2, 2, 4, 20), np.int8),
                           np.ones((2, 2, 20)), ("cloud", "sway"), A.VARIANTS, cfg)
    fig = A.plot_curves_by_scenario(res, "success")
    # one panel per scenario; the spare cell of the grid holds only the (figure) legend
    # the title at any location: the house style (rcParams, set by an earlier test in the same
    # process) places titles on the left
    titles = [" ".join(ax.get_title(loc=k) for k in ("left", "center", "right")).strip()
              for ax in fig.axes]
    assert [t for t in titles if t] == ["cloud occlusion", "ship sway"]
    assert len(fig.axes) == 2 and len(fig.legends) == 1
    assert all(ax.get_legend() is None for ax in fig.axes)
    plt.close(fig)
    with pytest.raises(ValueError, match="kind"):
        A.plot_curves_by_scenario(res, "median")


# ---- the committed run's stored study (ablation_study.npz) --------------------------------

@pytest.fixture(scope="module")
def tiny_study():
    cfg = A.AblationConfig(n_seeds=2, n_frames=20)    # 2: the verdicts need 2 runs
    return A.run_study(cfg, runner=TrialRunner(progress=False), n_consistency=1,
                       n_sensitivity=1, n_centroid_frames=2, explore_seeds=(0,))


def test_study_round_trip(tiny_study, tmp_path):
    path = tmp_path / A.STUDY_FILE
    A.write_study(path, tiny_study)
    back = A.read_study(path)
    a, b = tiny_study.ablation, back.ablation
    assert b.config == a.config and b.scenarios == a.scenarios
    assert np.array_equal(a.errors, b.errors) and np.array_equal(a.modes, b.modes)
    assert list(b.extra) == list(a.extra)
    for name in a.extra:
        assert np.array_equal(a.extra[name].errors, b.extra[name].errors)
        assert b.extra[name].config == a.extra[name].config
    for name, t in tiny_study.tables.items():
        pd.testing.assert_frame_equal(t, back.tables[name], check_dtype=False, check_exact=False)
    # the stored sequences re-filtered by this code give the stored errors (BEAK-ST included),
    # the 25-frame occlusion too, and the reader's session simulates nothing
    for sc in a.scenarios:
        e_old = tiny_study.session.errors(sc, seed=0)
        e_new = back.session.errors(sc, seed=0)
        assert all(np.allclose(e_old[v], e_new[v], atol=1e-4) for v in A.VARIANTS), sc
    e_old = tiny_study.session.errors("cloud", seed=0, occlusion_frames=25)
    e_new = back.session.errors("cloud", seed=0, occlusion_frames=25)
    assert all(np.allclose(e_old[v], e_new[v]) for v in A.VARIANTS)
    assert back.session.n_simulated == 0
    assert A.claim_results(b)[0].status == A.claim_results(a)[0].status


def test_study_refuses_a_stale_or_missing_file(tiny_study, tmp_path):
    import dataclasses

    with pytest.raises(FileNotFoundError, match=r"eotrack\.repro akf_star"):
        A.read_study(tmp_path / "none.npz")
    stale = dataclasses.replace(tiny_study.ablation,
                                config=dataclasses.replace(tiny_study.ablation.config,
                                                           gate_px=12.0))
    path = tmp_path / "stale.npz"
    A.write_study(path, dataclasses.replace(tiny_study, ablation=stale))
    with pytest.raises(ValueError, match="gate_px"):
        A.read_study(path)


def test_run_study_bad_input():
    with pytest.raises(TypeError, match="cfg"):
        A.run_study("default")
    with pytest.raises(ValueError, match="explore_seeds"):
        A.run_study(A.AblationConfig(n_seeds=1, n_frames=20), explore_seeds=(3,))


def test_add_measurements_bad_input(tiny_study):
    s = tiny_study.session
    with pytest.raises(TypeError, match="meas"):
        s.add_measurements("cloud", 0, 10, "x")
    m = s.measurements("cloud", seed=0)
    short = dataclasses_replace_truth(m)
    with pytest.raises(ValueError, match="frames"):
        s.add_measurements("cloud", 0, 10, short)


def dataclasses_replace_truth(m):
    import dataclasses

    return dataclasses.replace(m, truth=m.truth[:5])
