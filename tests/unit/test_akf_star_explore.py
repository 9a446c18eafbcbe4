"""Tests of the akf_star Explore session: the reproduction's measurements re-filtered, nothing
simulated on a panel control, the same sequences as the ablation and as a fresh session."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.experiments import akf_star as A
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
    # one panel per scenario; the spare cell of the grid holds only the legend
    # the title at any location: the house style (rcParams, set by an earlier test in the same
    # process) places titles on the left
    titles = [" ".join(ax.get_title(loc=k) for k in ("left", "center", "right")).strip()
              for ax in fig.axes]
    assert [t for t in titles if t] == ["cloud occlusion", "ship sway"]
    assert sum(ax.get_legend() is not None for ax in fig.axes) == 1
    plt.close(fig)
    with pytest.raises(ValueError, match="kind"):
        A.plot_curves_by_scenario(res, "median")
