"""Paper test for Huang, Zhang & Feng (epipolar association): ``reproduce(quick=True)``.

The quick run uses 100 scenario draws and 200 Fig. 6 simulations (the full run: 300 and 600);
the statuses below are what both measure (see papers_repro/epipolar/REPORT.md for the notes).
"""

import numpy as np
import pytest
from eotrack.experiments import epipolar as E
from eotrack.geometry import epipolar_distances, fundamental_from_poses
from eotrack.montecarlo import TrialRunner
from eotrack.repro import Status, load_claims

EXPECTED = {
    "epipolar.table1": Status.REPRODUCED,
    "epipolar.fig3": Status.REPRODUCED,
    "epipolar.fig4": Status.PARTIAL,
    "epipolar.table3": Status.NOT_REPRODUCED,
    "epipolar.table4": Status.REPRODUCED,
    "epipolar.fig5": Status.PARTIAL,
    "epipolar.fig6": Status.NOT_REPRODUCED,
    "epipolar.table5": Status.NOT_REPRODUCED,
    "epipolar.fig8": Status.NOT_REPRODUCED,
}


@pytest.fixture(scope="module")
def rep():
    return E.reproduce(quick=True, runner=TrialRunner(progress=False))


def test_every_claim_once(rep):
    ids = [r.claim for r in rep.claims]
    assert sorted(ids) == sorted(load_claims("epipolar"))
    assert len(ids) == len(set(ids)) == 9


@pytest.mark.parametrize("claim", sorted(EXPECTED))
def test_status(rep, claim):
    row = next(r for r in rep.claims if r.claim == claim)
    assert row.status is EXPECTED[claim], row.note


def test_core_numbers(rep):
    """The measured facts behind the statuses, as ranges a regression would leave."""
    f5 = rep.tables["Fig. 5"].set_index("L (px)")
    # misses fall and false associations rise with the threshold
    assert f5.loc[0.5, "missed"] > 0.6 > 0.2 > f5.loc[10.5, "missed"]
    assert f5.loc[1.5, "false (of associated)"] < f5.loc[19.5, "false (of associated)"]
    assert 0.80 < f5.loc[10.5, "correct"] < 0.95
    f6 = rep.tables["Fig. 6"].set_index("L (px)")
    # Monte Carlo against its binomial expectation, and far above the paper's bound
    assert np.allclose(f6["ours MC (overlapping views)"], f6["binomial (overlapping)"], atol=0.03)
    assert np.allclose(f6["Poisson (overlapping)"], f6["binomial (overlapping)"], atol=0.03)
    assert f6.loc[5, "ours MC (overlapping views)"] > 3 * f6.loc[5, "paper"]
    t4 = rep.tables["Table 4"]
    assert (t4["ours noise-free (px)"].iloc[[2, 4]] < 0.01).all()  # exact poses: ~0 px
    beyond = rep.tables["Beyond: association rules at L = 10 px"].set_index("rule")
    paper = beyond.loc["paper (greedy nearest)"]
    three = beyond.loc["paper + three-view check"]
    assert three["false associations"] < 0.5 * paper["false associations"]
    assert three["missed true pairs"] <= 1.05 * paper["missed true pairs"]
    t5 = rep.tables["Table 5"]
    truth = t5[t5["pair"] == "truth"]["ours − truth max |Δ| (km)"]
    assert (truth == 0).all()
    mean = t5[t5["pair"] == "mean"]["ours − truth max |Δ| (km)"]
    assert (mean > 3).all() and (mean < 500).all()


def test_scenario_visibility_matches_table3():
    scen = E.build_scenario()
    t3 = load_claims("epipolar")["epipolar.table3"].paper
    for k in range(4):
        want = [len(uv) > 0 for uv in t3[f"map{k + 1}"]]
        assert scen.visible[k].tolist() == want
    assert scen.los_clear[scen.visible].all()
    # map 4 reproduces Table 3's pixels (objects were placed along those lines of sight)
    assert np.nanmax(np.abs(scen.true_pixels()[3] - scen.paper_px[3])) < 0.01


def test_noise_free_draw_is_exact():
    scen = E.build_scenario()
    obs = E.draw_observation(np.random.default_rng(1), scen, E.ErrorConfig().noise_free())
    for a, b in E.PAIRS:
        ca, cb = obs.cameras[a], obs.cameras[b]
        F = fundamental_from_poses(ca.K, ca.R, ca.c, cb.K, cb.R, cb.c)
        d = epipolar_distances(F, obs.points[a], obs.points[b])
        la, lb = obs.labels[a], obs.labels[b]
        same = (la[:, None] == lb[None, :]) & (la[:, None] >= 0)
        assert np.all(d[same] < 0.01)  # only lens distortion (< 0.01 px) remains
    rows = E.summary_rows(obs, E.associate_observation(obs, 10.0))
    for obj in range(9):
        _est, nray = E.triangulate_object(obs, rows, obj)
        if nray is not None:
            assert np.linalg.norm(nray - scen.objects_km[obj]) < 0.5


def test_bad_input():
    with pytest.raises(ValueError, match="attitude_arcmin"):
        E.ErrorConfig(attitude_arcmin=-1)
    with pytest.raises(ValueError, match="n_false"):
        E.ErrorConfig(n_false=-2)
    with pytest.raises(TypeError, match="rng"):
        E.draw_observation(0, E.build_scenario())
    with pytest.raises(ValueError, match="mode must be one of"):
        E.fig6_trial(np.random.default_rng(0), np.array([5.0]), mode="uniform")
