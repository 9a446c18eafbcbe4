"""Paper akf_star: reproduce(quick=True) covers every claim; the statistics rules of the verdicts
(paired sequences, >= 20 per scenario in the default run, intervals, Bonferroni, the status
settings — fixed with results seen, so the statuses under the first-commit and tuned settings
are tabulated beside) are enforced on the configuration and on the measurements."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest
from eotrack.experiments import akf_star
from eotrack.experiments.akf_star import claims as C
from eotrack.repro import Status, load_claims, papers_repro_dir
from eotrack.repro.evaluators import check_evaluator

#: statuses of the quick run (4 sequences: too few for any ordering to hold; the protocol's
#: root seed k = 0 since 2026-12-02)
EXPECTED_QUICK = {
    "akf_star.table1": Status.NOT_REPRODUCED,
    "akf_star.table2": Status.NOT_REPRODUCED,
    "akf_star.ablation_pattern": Status.NOT_REPRODUCED,
    "akf_star.fig6": Status.NOT_REPRODUCED,
    "akf_star.fig7": Status.NOT_REPRODUCED,
    "akf_star.headline": Status.NOT_REPRODUCED,
}


@pytest.fixture(scope="module")
def rep():
    return akf_star.reproduce(quick=True)


def test_every_claim_once(rep):
    ids = [r.claim for r in rep.claims]
    assert sorted(ids) == sorted(load_claims("akf_star"))
    assert len(ids) == len(set(ids))


def test_statuses(rep):
    got = {r.claim: r.status for r in rep.claims}
    assert got == EXPECTED_QUICK


def test_evaluators_registered_and_cases_pass():
    for claim in load_claims("akf_star").values():
        assert check_evaluator(claim) == [], claim.id


def test_default_run_obeys_the_statistics_rules():
    cfg = akf_star.AblationConfig()
    assert cfg.n_seeds >= 20                       # >= 20 sequences for an ordering
    # the status settings (fixed 2026-12-01 with results seen), not the tuned ones
    assert cfg.confidence == akf_star.STATUS_CONFIDENCE
    assert cfg.confidence.gamma == 3.0
    assert cfg.confidence.r_bounds == (0.01, 25.0)
    assert cfg.hold_after is None and cfg.gate_max_px >= 1e5
    ex = akf_star.exploratory_config(cfg)
    assert ex.confidence.gamma == 5.0 and ex.hold_after == 5 and ex.gate_max_px == 30.0
    for claim in load_claims("akf_star").values():
        assert claim.directional and "Bonferroni" in claim.criterion
        assert claim.history and all(h.after_results for h in claim.history)
    assert sum(c.central for c in load_claims("akf_star").values()) >= 1


def test_settings_sets_are_tabulated_and_the_protocol_is_stated(rep):
    first = akf_star.first_commit_config()
    assert first.confidence.r_bounds == (0.01, 1.0)          # what 9ea01e8 ran
    assert first.confidence.q_bounds_ratio == (0.25, 100.0)
    keys = [k for k in rep.tables if k.startswith("Statuses under each settings set")]
    assert len(keys) == 1
    tab = rep.tables[keys[0]]
    assert list(tab.columns) == ["status settings (decide)", "first commit 9ea01e8",
                                 "exploratory (tuned)"]
    got = {r.claim: r.status.value for r in rep.claims}
    assert tab["status settings (decide)"].to_dict() == got
    for h in (load_claims("akf_star")[c].history for c in got):
        assert any(x.criterion.startswith("(settings)") and x.after_results for x in h)
    # the statuses come from the pre-registered protocol (frozen 2026-12-02, new seeds); the
    # report says so and that those settings had been chosen with earlier results seen
    assert "PRE-REGISTERED CONFIRMATORY RUN" in rep.text and "with results seen" in rep.text
    for claim in load_claims("akf_star").values():
        assert claim.criterion.startswith("PRE-REGISTERED CONFIRMATORY PROTOCOL")


def test_committed_report_is_the_default_run():
    card = json.loads((papers_repro_dir() / "akf_star" / "scorecard.json").read_text())
    rows = card["claims"] if isinstance(card, dict) else card
    assert {r["claim"] for r in rows} == set(load_claims("akf_star"))
    for r in rows:
        assert "20 sequences" in r["ours"] or r["claim"] != "akf_star.table1"
        assert r["variant"].startswith("tuned settings (exploratory)")


def test_measurements_are_paired_and_bonferroni(rep):
    res = akf_star.run_ablation(akf_star.AblationConfig(n_seeds=3, n_frames=40),
                                scenarios=("sway", "low_snr"),
                                extras=(("CV baseline", akf_star.AblationConfig(n_seeds=3,
                                                                               n_frames=40),
                                         akf_star.CV_BASELINE),))
    # the CV baseline and the variants see the same sequences (common random numbers)
    assert res.extra["CV baseline"].errors.shape[:2] == res.errors.shape[:2]
    m = C.claim_measurements(res)
    assert len(m["akf_star.table1"]["scenarios"]) == 2
    # the table1 intervals use alpha / (5 comparisons x 2 scenarios)
    E = res.sequence_mean_error()
    d = E[0, :, 0] - E[0, :, 3]
    _, lo, hi = C.paired_interval(d, C.FAMILY_ALPHA / 10)
    got = m["akf_star.table1"]["scenarios"]["ship sway"][0]
    assert got[1] == pytest.approx(float(lo)) and got[2] == pytest.approx(float(hi))


def test_paired_interval_bad_input():
    with pytest.raises(ValueError, match="at least 2"):
        C.paired_interval(np.ones(1))
    with pytest.raises(ValueError, match="alpha"):
        C.paired_interval(np.ones(5), alpha=1.5)
    with pytest.raises(ValueError, match="finite"):
        C.paired_interval(np.array([1.0, np.nan]))


def test_seed_gives_same_statuses(monkeypatch):
    # tiny runs (2 sequences × 30 frames) through reproduce's own seed path
    real = akf_star.AblationConfig

    @dataclasses.dataclass(frozen=True)
    class Tiny(real):
        n_seeds: int = 2
        n_frames: int = 30

    monkeypatch.setattr(akf_star, "AblationConfig", Tiny)
    a, b, c = (akf_star.reproduce(seed=s) for s in (3, 3, 4))
    assert [r.status for r in a.claims] == [r.status for r in b.claims]
    t = next(k for k in a.tables if k.startswith("Table 1 —"))
    assert a.tables[t].equals(b.tables[t]) and not a.tables[t].equals(c.tables[t])
    assert a.settings["root_seed_of_sequences"] != real().seed


def test_key_numbers(rep):
    t1 = next(v for k, v in rep.tables.items() if k.startswith("Table 1 —"))
    # adaptive extraction keeps the star under strong light where the global threshold loses it
    assert t1.loc["strong light", "BEAK-ST-SKF ours"] < 1.0
    assert t1.loc["strong light", "Baseline ours"] > 3.0
    cv = next(v for k, v in rep.tables.items() if k.startswith("Beyond: constant"))
    assert cv.loc["ship sway", "CV KF (px)"] < 0.2        # the plain CV filter under sway
    assert t1.loc["ship sway", "BEAK-ST paper"] == pytest.approx(1.58)
    assert set(rep.figures) == {"fig6_mean_tracking_error", "fig7_success_rate"}
