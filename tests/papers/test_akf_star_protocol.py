"""The pre-registered confirmatory protocol of akf_star (claims.toml ``[protocol]``, fixed on
2026-12-02 before any run on its seeds): the code runs exactly the settings and the root seeds it
states, and those seeds are none of the earlier, exploratory readings'."""

from __future__ import annotations

import numpy as np
from eotrack.experiments import akf_star as A
from eotrack.repro import load_claims


def test_code_runs_the_protocol_settings():
    p = A.read_protocol()
    cfg = A.AblationConfig()
    c = cfg.confidence
    assert p["date"] == "2026-12-02" and p["kind"] == "pre-registered confirmatory run"
    assert c == A.STATUS_CONFIDENCE
    assert c.gamma == p["gamma"]
    assert list(c.r_bounds) == p["r_bounds_px2"]
    assert list(c.q_bounds_ratio) == p["q_bounds_ratio"]
    assert p["gate_cap"] == "none" and cfg.gate_max_px >= 1e5
    assert p["hold_after"] == "none" and cfg.hold_after is None
    assert cfg.extraction.centroid_grow == p["centroid_grow_px"]
    assert cfg.extraction.robust_roi is p["robust_roi"]
    assert cfg.r_px2 == p["r0_px2"] and cfg.gate_px == p["gate_px"]
    assert cfg.gate_sigma == p["gate_sigma"] and cfg.epsilon_px == p["epsilon_px"]
    assert cfg.n_seeds == p["n_sequences_per_scenario"] and cfg.n_frames == p["n_frames"]


def test_root_seeds_are_the_protocols_and_new():
    p = A.read_protocol()
    assert A.PROTOCOL_SEED_ENTROPY == p["seed_entropy"]
    new = [A.protocol_seeds(k)[0] for k in range(6)]
    assert A.AblationConfig().seed == new[0]
    ss = np.random.SeedSequence([p["seed_entropy"], 3]).spawn(2)[0]
    assert new[3] == int(ss.generate_state(1)[0])
    # the earlier readings: root seed 20260404 and SeedSequence(1..5) (5 scenarios: +0..4)
    old = [20260404] + [int(np.random.SeedSequence(k).spawn(2)[0].generate_state(1)[0])
                        for k in range(1, 6)]
    assert min(abs(a - b) for a in old for b in new) > 10


def test_every_criterion_states_the_protocol_and_keeps_the_old_reading():
    for cid, claim in load_claims("akf_star").items():
        assert claim.criterion.startswith("PRE-REGISTERED CONFIRMATORY PROTOCOL"), cid
        last = claim.history[-1]
        assert str(last.date) == "2026-12-02" and last.after_results, cid
        assert "exploratory history" in last.reason, cid
