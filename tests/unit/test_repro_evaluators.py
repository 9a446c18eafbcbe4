"""Every claim of every paper has a pure evaluator whose synthetic cases reach every status its
criterion allows (a status function with a floor fails here), and the machinery itself."""

from __future__ import annotations

import importlib
import tomllib

import pytest
from eotrack.repro import (
    Status,
    available_slugs,
    check_evaluator,
    evaluate,
    evaluator,
    load_claims,
    papers_repro_dir,
    registered_evaluators,
)

SLUGS = available_slugs()


def _claim_ids():
    """(slug, claim id) from the raw TOML, so one paper's bad file fails only its own tests."""
    out = []
    for slug in SLUGS:
        raw = tomllib.loads((papers_repro_dir() / slug / "claims.toml").read_text())
        out += [pytest.param(slug, cid, id=cid) for cid in raw.get("claims", {})]
    return out


@pytest.mark.parametrize(("slug", "cid"), _claim_ids())
def test_every_status_reachable(slug, cid):
    importlib.import_module(f"eotrack.experiments.{slug}")
    problems = check_evaluator(load_claims(slug)[cid])
    assert not problems, "\n".join(problems)


def test_no_evaluator_without_a_claim():
    ids = set()
    for slug in SLUGS:
        importlib.import_module(f"eotrack.experiments.{slug}")
        ids |= set(load_claims(slug))
    extra = {c for c in registered_evaluators() if not c.startswith("demo.")} - ids
    assert not extra, f"evaluators registered for claims not in any claims.toml: {sorted(extra)}"


def test_machinery_catches_a_floor(tmp_path):
    (tmp_path / "demo").mkdir()
    (tmp_path / "demo" / "claims.toml").write_text(
        '[claims."demo.f"]\ntitle = "t"\nsource = "s"\nstatement = "s"\ncriterion = "c"\n'
        'kind = "result"\ncentral = true\ndirectional = true\npartial_band = "p"\n')
    claim = load_claims("demo", root=tmp_path)["demo.f"]

    @evaluator("demo.f", cases=[(0.9, Status.REPRODUCED), (0.5, Status.PARTIAL)])
    def floored(x):  # never worse than partial: the defect the test exists for
        return Status.REPRODUCED if x > 0.8 else Status.PARTIAL

    problems = check_evaluator(claim)
    assert any("no case reaches ['contradicted', 'not reproduced']" in p for p in problems)

    @evaluator("demo.f", cases=[(0.9, "reproduced"), (0.5, "partial"), (0.1, "not reproduced"),
                                (-1, "contradicted"), (0.3, "reproduced")])
    def full(x):
        if x < 0:
            return Status.CONTRADICTED
        return (Status.REPRODUCED if x > 0.8 else Status.PARTIAL if x > 0.4
                else Status.NOT_REPRODUCED)

    problems = check_evaluator(claim)
    assert problems == ["demo.f: case 4 gives not reproduced, expected reproduced"]
    assert evaluate("demo.f", -2) is Status.CONTRADICTED


def test_evaluator_bad_input():
    with pytest.raises(ValueError, match="claim_id must be"):
        evaluator("nodot", cases=[(1, "reproduced")])
    with pytest.raises(ValueError, match="at least one case"):
        evaluator("demo.z", cases=[])
    with pytest.raises(ValueError, match="is not a valid Status"):
        evaluator("demo.z", cases=[(1, "maybe")])
    with pytest.raises(ValueError, match=r"no evaluator registered for claim 'demo\.nope'"):
        evaluate("demo.nope", 1)
