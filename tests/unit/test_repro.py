"""Claims, scorecards, reports, slug discovery and the CLI."""

import json

import matplotlib.pyplot as plt
import pandas as pd
import pytest
from eotrack.repro import (
    ClaimResult,
    Reproduction,
    Status,
    available_slugs,
    check_claims_complete,
    experiment_module,
    load_claims,
    scorecard,
    write_report,
)

CLAIMS = """
[claims."demo.a"]
title = "A"
source = "Fig. 1"
statement = "The paper says a."
criterion = "Within 1 %."
[claims."demo.a".paper]
value = 1.5

[claims."demo.b"]
title = "B"
source = "Table 2"
statement = "The paper says b."
criterion = "Same ordering."
"""


@pytest.fixture
def repro_root(tmp_path):
    (tmp_path / "demo").mkdir()
    (tmp_path / "demo" / "claims.toml").write_text(CLAIMS)
    return tmp_path


def test_load_claims(repro_root):
    c = load_claims("demo", root=repro_root)
    assert list(c) == ["demo.a", "demo.b"]
    assert c["demo.a"].paper == {"value": 1.5}
    assert c["demo.b"].paper == {}


def test_load_claims_errors(repro_root):
    with pytest.raises(ValueError, match="no claims for slug 'other'; known slugs: \\['demo'\\]"):
        load_claims("other", root=repro_root)
    with pytest.raises(ValueError, match="slug must be a paper slug"):
        load_claims("../etc", root=repro_root)
    (repro_root / "bad").mkdir()
    (repro_root / "bad" / "claims.toml").write_text('[claims."bad.x"]\ntitle = "x"\n')
    with pytest.raises(ValueError, match="lacks"):
        load_claims("bad", root=repro_root)


def test_claim_result_needs_note_unless_reproduced(repro_root):
    c = load_claims("demo", root=repro_root)["demo.a"]
    ok = ClaimResult.from_claim(c, ours="1.49", status="reproduced")
    assert ok.status is Status.REPRODUCED and ok.criterion == "Within 1 %."
    with pytest.raises(ValueError, match="needs a note"):
        ClaimResult.from_claim(c, ours="3", status=Status.NOT_REPRODUCED)
    with pytest.raises(ValueError, match=r"is not a valid Status"):
        ClaimResult.from_claim(c, ours="3", status="maybe", note="x")


def test_scorecard_and_report(repro_root, tmp_path):
    c = load_claims("demo", root=repro_root)
    rows = [ClaimResult.from_claim(c["demo.a"], ours="1.49", status="reproduced"),
            ClaimResult.from_claim(c["demo.b"], ours="reversed", status="partial",
                                   note="ordering differs by one place")]
    check_claims_complete(c, rows)
    with pytest.raises(ValueError, match=r"missing \['demo\.b'\]"):
        check_claims_complete(c, rows[:1])
    df = scorecard(rows)
    assert list(df.columns) == ["claim", "paper", "ours", "criterion", "status", "note"]
    fig, ax = plt.subplots()
    ax.plot([0, 1])
    rep = Reproduction("demo", "Demo paper", rows, tables={"Table 2": pd.DataFrame({"x": [1.0]})},
                       figures={"fig1_demo": fig}, settings={"n": 3})
    assert rep.status_summary() == "1/2 reproduced, 1 partial"
    out = tmp_path / "out"
    path = write_report(rep, out)
    text = path.read_text()
    assert "| demo.b |" in text and "![fig1_demo](figures/fig1_demo.png)" in text
    assert (out / "figures" / "fig1_demo.png").stat().st_size > 1000
    data = json.loads((out / "scorecard.json").read_text())
    assert data["claims"][1]["status"] == "partial"
    plt.close(fig)


def test_discovery():
    slugs = available_slugs()
    assert "wransac" in slugs
    assert experiment_module("wransac").SLUG == "wransac"
    with pytest.raises(ValueError, match="unknown paper slug 'nope'"):
        experiment_module("nope")


def test_cli_rejects_unknown_slug():
    from eotrack.repro.__main__ import main

    with pytest.raises(ValueError, match="unknown paper slug"):
        main(["nope", "--quick"])


def test_readme_table_from_scorecards(tmp_path):
    from eotrack.repro.readme import update_readme

    (tmp_path / "papers_repro" / "demo").mkdir(parents=True)
    (tmp_path / "papers_repro" / "demo" / "scorecard.json").write_text(json.dumps(
        {"slug": "demo", "title": "A. Author, Demo paper, 2020", "summary": "1/2 reproduced"}))
    (tmp_path / "notebooks" / "py").mkdir(parents=True)
    (tmp_path / "notebooks" / "py" / "07_demo_topic.py").write_text(
        "# # 07 · Demo topic\nfrom eotrack.experiments import demo as D\n")
    readme = tmp_path / "README.md"
    readme.write_text("intro\n<!-- notebooks-table -->\nold\n<!-- /notebooks-table -->\nend\n")
    assert update_readme(tmp_path)
    text = readme.read_text()
    assert "[Demo topic](notebooks/07_demo_topic.ipynb)" in text and "1/2 reproduced" in text
    assert "old" not in text and text.endswith("end\n")
    assert not update_readme(tmp_path)  # idempotent
