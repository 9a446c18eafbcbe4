"""Paper test for Yan et al. 2019 (WRANSAC): a fresh full-scale run against claims.toml.

The full reproduction takes ~10 s, so the test runs it at the paper's 20 runs: the statuses
checked here are the ones `make repro` writes to papers_repro/wransac/REPORT.md.
"""

import json
import subprocess
import sys

import numpy as np
import pytest
from eotrack.experiments import wransac as W
from eotrack.montecarlo import TrialRunner
from eotrack.repro import Status, load_claims

# What a fresh run measures (see the scorecard notes for the reasons behind each non-reproduced
# row). A change in any of these is a change in the science and must be looked at.
EXPECTED = {
    "wransac.coords": Status.PARTIAL,
    "wransac.fig1": Status.REPRODUCED,
    "wransac.fig2": Status.REPRODUCED,
    "wransac.min_samples": Status.REPRODUCED,
    "wransac.table1": Status.PARTIAL,
    "wransac.short_horizon": Status.PARTIAL,
    "wransac.long_horizon": Status.PARTIAL,
    "wransac.fig4": Status.REPRODUCED,
    "wransac.fig5": Status.REPRODUCED,
    "wransac.fig6": Status.REPRODUCED,
    "wransac.fig7": Status.PARTIAL,
}


@pytest.fixture(scope="module")
def rep():
    return W.reproduce(runner=TrialRunner(progress=False))


def test_every_claim_once(rep):
    ids = [r.claim for r in rep.claims]
    assert sorted(ids) == sorted(load_claims("wransac"))
    assert len(ids) == len(set(ids)) == 11


@pytest.mark.parametrize("claim", sorted(EXPECTED))
def test_status(rep, claim):
    row = next(r for r in rep.claims if r.claim == claim)
    assert row.status is EXPECTED[claim], row.note


def test_core_numbers(rep):
    """The measured facts behind the statuses, as ranges that a regression would leave."""
    t = rep.tables["Table 1 — Dec prediction errors (arcsec), paper beside ours"]
    var72 = t.loc[(72, "variance")]
    # LSQ diverges with gross outliers; RANSAC with a sufficient budget does not
    assert var72["lsq (ours)"] > 20 * var72["ransac (ours)"]
    # RANSAC with 100 draws is as good as an outlier-free least-squares fit (≈ 100 ″²)
    assert 20 < var72["ransac (ours)"] < 300
    literal = rep.tables["Table 1 with exactly U = 3 hypotheses (literal reading) — Dec"]
    assert literal.loc[(72, "variance")]["ransac (ours)"] > 10 * var72["ransac (ours)"]
    budget = rep.tables[
        "Beyond — fraction of runs with 72-min Dec error ≤ 60″ vs number of hypotheses"]
    assert budget["ransac"].iloc[0] < budget["ransac"].iloc[-1]


def test_fit_predict_public_contract():
    rng = np.random.default_rng(0)
    t = np.arange(0.0, 7200.0, 90.0)
    y = 10 * np.sin(7.29e-5 * t) + 0.001 * t + 3
    y[5] += 500.0
    t_new = np.array([7200.0, 9000.0])
    for m in W.METHODS:
        p = W.fit_predict(m, t, y, t_new, rng=rng)
        assert p.shape == (2,) and np.all(np.isfinite(p))
    good = 10 * np.sin(7.29e-5 * t_new) + 0.001 * t_new + 3
    np.testing.assert_allclose(W.fit_predict("ransac", t, y, t_new, rng=rng, threshold=1e-3,
                                             n_hypotheses=100), good, atol=1e-6)
    with pytest.raises(ValueError, match="method must be one of"):
        W.fit_predict("kalman", t, y, t_new, rng=rng)
    with pytest.raises(ValueError, match="t_s and y must have the same length"):
        W.fit_predict("lsq", t, y[:-1], t_new, rng=rng)
    with pytest.raises(ValueError, match="y contains NaN"):
        W.fit_predict("lsq", t, np.where(t > 100, y, np.nan), t_new, rng=rng)
    with pytest.raises(ValueError, match="need at least 4 observations"):
        W.fit_predict("wransac", t[:3], y[:3], t_new, rng=rng)
    with pytest.raises(TypeError, match=r"rng must be a numpy\.random\.Generator"):
        W.fit_predict("wransac", t, y, t_new, rng=0)
    with pytest.raises(ValueError, match="model must be one of"):
        W.fit_predict("lsq", t, y, t_new, rng=rng, model="spline")


def test_cli_writes_report(tmp_path):
    out = subprocess.run([sys.executable, "-m", "eotrack.repro", "wransac", "--quick", "--out",
                          str(tmp_path), "--no-progress"], capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 0, out.stderr
    assert "wransac.table1" in out.stdout
    d = tmp_path / "wransac"
    data = json.loads((d / "scorecard.json").read_text())
    assert len(data["claims"]) == 11
    assert (d / "REPORT.md").read_text().count("![") >= 6
    assert len(list((d / "figures").glob("*.png"))) >= 6
