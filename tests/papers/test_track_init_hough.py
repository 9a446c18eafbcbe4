"""Xu & Wang (2016) reproduction: claims vs results (quick run)."""

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
from eotrack.experiments import track_init_hough as exp
from eotrack.repro import Status, load_claims

EXPECTED = {
    "track_init.xu_table2": Status.PARTIAL,
    "track_init.xu_fig3": Status.PARTIAL,
    "track_init.method_comparison": Status.REPRODUCED,
}


@pytest.fixture(scope="module")
def rep():
    return exp.reproduce(quick=True)


def test_one_row_per_claim(rep):
    ids = [r.claim for r in rep.claims]
    assert sorted(ids) == sorted(load_claims(exp.SLUG))
    assert len(ids) == len(set(ids))


@pytest.mark.parametrize("claim", sorted(EXPECTED))
def test_status(rep, claim):
    row = next(r for r in rep.claims if r.claim == claim)
    assert row.status is EXPECTED[claim], row.note


def test_paper_settings_are_the_library_defaults():
    from eotrack.tracking.initiation import ModifiedHoughInitiator

    cfg = exp.xu_config()
    ini = ModifiedHoughInitiator()
    assert (ini.d_rho, ini.d_theta_deg, ini.d_v, ini.v_min, ini.v_max, ini.m) == (
        cfg.cell_rho_px, cfg.cell_theta_deg, cfg.cell_v_px_s, *cfg.v_gate_px_s, cfg.rule_m)


def test_nominal_scene_with_26_neighbourhood_is_exact(rep):
    nominal = rep.data["nominal"]
    assert nominal[26]["exact"] and nominal[26]["n_tracks"] == 5
    assert {i: f + 1 for i, f in nominal[26]["confirm_frame"].items()} == \
        {0: 3, 1: 4, 2: 4, 3: 4, 4: 4}
    # the paper's 6-neighbourhood misses track 2: its two pair cells differ in ρ and θ
    assert 1 not in nominal[6]["confirm_frame"] and nominal[6]["false"] == 0


def test_table2_counts(rep):
    t2 = rep.data["table2"][6]
    assert t2["frame"].tolist() == [1, 2, 3, 4]
    assert t2["tracks confirmed"].tolist() == [0, 0, 1, 3]
    assert t2["velocity-gated pairs"].iloc[0] == 0
    assert np.all(t2["candidates"] >= 5) and np.all(t2["candidates"] <= 20)


def test_redraw_rates_in_honest_ranges(rep):
    r = rep.data["redraws"]
    ex6 = r[r["neighbourhood"] == 6]["exact"].mean()
    ex26 = r[r["neighbourhood"] == 26]["exact"].mean()
    assert 0.2 <= ex6 <= 0.85
    assert ex26 >= 0.9


def test_comparison_numbers(rep):
    c = rep.data["comparison"]
    cl = c[(c["sweep"] == "clutter")]
    mh = cl[cl["method"] == "modified Hough 3/4"].set_index("clutter")
    two = cl[cl["method"] == "logic 2/3"].set_index("clutter")
    assert mh.loc[0.0, "false_per_frame"] <= 0.05
    assert two.loc[10.0, "false_per_frame"] > 1.0
    assert np.all(c["p_correct"].between(0, 1))


def test_logic_analytic_close_to_measured_at_low_density(rep):
    lf = rep.data["logic_ft"]
    row = lf[(lf["method"] == "logic 3/4") & (lf["clutter"] == 8.0)].iloc[0]
    assert 0.3 <= row["measured"] / row["analytic"] <= 2.0


def test_scene_helpers():
    xy = exp.gnomonic_to_pixels([100.0], [0.0], 100.0, 0.0, 0.7 / 512, 256.0)
    np.testing.assert_allclose(xy, [[256.0, 256.0]])
    assert exp.distance_cdf_square(0.0, 1.0) == 0.0
    assert exp.distance_cdf_square(np.sqrt(2), 1.0) == pytest.approx(1.0)
    rng = np.random.default_rng(0)
    d = np.hypot(*(rng.random((200000, 2)) - rng.random((200000, 2))).T)
    for s in (0.3, 0.9, 1.2):
        assert exp.distance_cdf_square(s, 1.0) == pytest.approx(np.mean(d <= s), abs=0.005)
    with pytest.raises(ValueError, match="side"):
        exp.distance_cdf_square(0.5, 0.0)
