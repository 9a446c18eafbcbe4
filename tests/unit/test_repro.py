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
kind = "result"
central = true
[claims."demo.a".paper]
value = 1.5

[claims."demo.b"]
title = "B"
source = "Table 2"
statement = "The paper says b."
criterion = "Same ordering."
kind = "result"
directional = true
partial_band = "One place of the ordering differs."
[[claims."demo.b".history]]
date = "2026-11-01"
criterion = "Exact ordering."
reason = "The paper's ties are printed to one digit."
after_results = true
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
    assert list(df.columns) == ["claim", "kind", "central", "paper", "ours", "criterion",
                                "status", "note", "variant"]
    fig, ax = plt.subplots()
    ax.plot([0, 1])
    rep = Reproduction("demo", "Demo paper", rows, tables={"Table 2": pd.DataFrame({"x": [1.0]})},
                       figures={"fig1_demo": fig}, settings={"n": 3})
    assert rep.status_summary() == "results: 1/2 reproduced, 1 partial"
    out = tmp_path / "out"
    path = write_report(rep, out, claims=c)
    text = path.read_text()
    assert "**Verdict:** central claim demo.a: **reproduced**." in text
    assert "## Criterion history" in text and "after results were seen" in text
    assert "Stability: not run" in text
    assert "| demo.b |" in text and "![Figure](figures/fig1_demo.png)" in text  # untitled
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


# --------------------------------------------------------------------- claim kinds and statuses
def _toml(tmp_path, body, slug="demo"):
    (tmp_path / slug).mkdir(exist_ok=True)
    (tmp_path / slug / "claims.toml").write_text(body)
    return tmp_path


BASE = '''
[claims."demo.x"]
title = "X"
source = "Fig. 1"
statement = "s"
criterion = "c"
'''


@pytest.mark.parametrize(("extra", "match"), [
    ("", r"claim 'demo\.x' lacks \['kind'\]"),
    ('kind = "finding"\ncentral = true\n', r"claim 'demo\.x': kind must be one of"),
    ('kind = "check"\ncentral = true\n', r"claim 'demo\.x': a check cannot be central"),
    ('kind = "check"\npartial_band = "p"\n', r"claim 'demo\.x': a check passes or fails"),
    ('kind = "result"\ncentral = "yes"\n', r"claim 'demo\.x': central must be true or false"),
    ('kind = "result"\ncentral = true\npartial_bnad = "p"\n',
     r"claim 'demo\.x' has unknown key\(s\) \['partial_bnad'\]"),
    ('kind = "result"\n', r"no claim is marked central"),
    ('kind = "result"\ncentral = true\n[[claims."demo.x".history]]\ncriterion = "old"\n'
     'reason = "r"\nafter_results = false\n', r"claim 'demo\.x': history entry 0 needs a date"),
    ('kind = "result"\ncentral = true\n[[claims."demo.x".history]]\ndate = "2026-01-01"\n'
     'criterion = "old"\nreason = "r"\n', r"needs after_results"),
    ('kind = "result"\ncentral = true\n[[claims."demo.x".history]]\ndate = "yesterday"\n'
     'criterion = "old"\nreason = "r"\nafter_results = false\n', r"needs a date"),
])
def test_claims_toml_bad_input_names_the_claim(tmp_path, extra, match):
    root = _toml(tmp_path, BASE + extra)
    with pytest.raises(ValueError, match=match):
        load_claims("demo", root=root)


def test_history_with_toml_date(tmp_path):
    root = _toml(tmp_path, BASE + 'kind = "result"\ncentral = true\n[[claims."demo.x".history]]\n'
                 'date = 2026-01-02\ncriterion = "old"\nreason = "r"\nafter_results = true\n')
    h = load_claims("demo", root=root)["demo.x"].history
    assert h[0].date == "2026-01-02" and h[0].after_results


def test_statuses_allowed_by_the_claim(repro_root):
    from eotrack.repro import allowed_statuses

    c = load_claims("demo", root=repro_root)
    a, b = c["demo.a"], c["demo.b"]
    # demo.a: no band, not directional
    with pytest.raises(ValueError, match=r"claim demo\.a: status partial is not allowed: "
                                         r"claims\.toml states no partial_band"):
        ClaimResult.from_claim(a, ours="x", status="partial", note="n")
    with pytest.raises(ValueError, match=r"claim demo\.a: status contradicted is not allowed: "
                                         r"it is not marked directional"):
        ClaimResult.from_claim(a, ours="x", status="contradicted", note="n")
    r = ClaimResult.from_claim(b, ours="x", status="contradicted", note="reversed, CI [2, 3]")
    assert r.status is Status.CONTRADICTED and r.kind == "result" and not r.central
    assert Status.PARTIAL in allowed_statuses(b) and Status.CONTRADICTED in allowed_statuses(b)
    assert ClaimResult.from_claim(a, ours="x", status="reproduced").central


def test_check_passes_or_fails(tmp_path):
    root = _toml(tmp_path, BASE + 'kind = "check"\n' + BASE.replace("demo.x", "demo.y")
                 + 'kind = "result"\ncentral = true\n')
    c = load_claims("demo", root=root)
    ok = ClaimResult.from_claim(c["demo.x"], ours="x", status="reproduced")
    bad = ClaimResult.from_claim(c["demo.x"], ours="x", status="not reproduced", note="off by 2")
    assert (ok.verdict, bad.verdict) == ("pass", "fail")
    with pytest.raises(ValueError, match=r"claim demo\.x: status not reproducible is not allowed"):
        ClaimResult.from_claim(c["demo.x"], ours="x", status="not reproducible", note="n")
    with pytest.raises(ValueError, match="a check passes"):
        ClaimResult("demo.x", "p", "o", "c", Status.PARTIAL, note="n", kind="check")
    res = ClaimResult.from_claim(c["demo.y"], ours="x", status="not reproduced", note="n")
    from eotrack.repro import status_summary

    assert status_summary([ok, bad, res]) == ("results: 0/1 reproduced, 1 not reproduced; "
                                              "checks: 1/2 pass")
    # a row built by hand with the wrong kind is caught against the claims
    wrong = ClaimResult("demo.y", "p", "o", "c", Status.REPRODUCED, kind="check")
    with pytest.raises(ValueError, match=r"claim demo\.y: the row says kind='check'"):
        check_claims_complete(c, [ok.__class__.from_claim(c["demo.x"], ours="x",
                                                          status="reproduced"), wrong])


# --------------------------------------------------------------------------- stability
def test_stability_file_and_report(repro_root, tmp_path):
    from eotrack.repro import read_stability, write_stability

    c = load_claims("demo", root=repro_root)
    rows = [ClaimResult.from_claim(c["demo.a"], ours="1", status="reproduced"),
            ClaimResult.from_claim(c["demo.b"], ours="2", status="partial", note="n")]
    out = tmp_path / "o"
    out.mkdir()
    assert read_stability(out) is None
    write_stability(out, [1, 2, 3], {"demo.a": ["reproduced"] * 3,
                                     "demo.b": ["partial", "not reproduced", "partial"]},
                    date="2026-12-01")
    st = read_stability(out)
    assert st.k == 3 and st.share("demo.a", "reproduced") == 1.0
    assert st.fragile("demo.b", Status.PARTIAL) and not st.fragile("demo.a", "reproduced")
    assert st.cell("demo.b", "partial") == "2/3 **fragile** (1× not reproduced)"
    assert st.share("demo.zzz", "partial") is None
    rep = Reproduction("demo", "Demo paper", rows)
    text = write_report(rep, out, claims=c).read_text()
    assert "3/3" in text and "**fragile**" in text and "2026-12-01" in text
    assert "central claim demo.a: **reproduced** (3/3 seeds)" in text
    card = json.loads((out / "scorecard.json").read_text())
    assert card["claims"][1]["fragile"] is True and card["stability"]["k"] == 3
    with pytest.raises(ValueError, match="statuses for 3 seeds"):
        write_stability(out, [1, 2, 3], {"demo.a": ["reproduced"]})
    with pytest.raises(ValueError, match="at least one root seed"):
        write_stability(out, [], {})
    (out / "stability.json").write_text("{not json")
    with pytest.raises(ValueError, match=r"stability\.json is not a stability file"):
        read_stability(out)


def test_cli_seeds_needs_a_seed_parameter(monkeypatch):
    import types

    from eotrack.repro import __main__ as cli

    mod = types.SimpleNamespace(reproduce=lambda *, quick=False, runner=None: None)
    with pytest.raises(SystemExit, match="takes no `seed`"):
        cli._seeded(mod, "demo")
    with pytest.raises(SystemExit):
        cli.main(["wransac", "--seeds", "-1"])


def test_central_summary_counts_the_weakest_central_claim():
    from eotrack.repro.readme import central_summary

    cards = [{"claims": [{"central": True, "status": "reproduced"}]},
             {"claims": [{"central": True, "status": "reproduced"},
                         {"central": True, "status": "contradicted"}]},
             {"claims": [{"central": True, "status": "partial"},
                         {"central": False, "status": "not reproduced"}]},
             {"claims": [{"status": "reproduced"}]}]
    s = central_summary(cards)
    assert s.startswith("**Central claims, computed from the scorecards:** 1 of 4 papers")
    assert "1 contradicted" in s and "1 partial" in s and "1 no central claim marked" in s
