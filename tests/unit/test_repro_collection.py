"""eotrack.repro.collection: the index notebook's tables, computed from scorecards and notebooks."""

from __future__ import annotations

import json

import pytest
from eotrack.repro import collection_notebooks, collection_scorecard, notebook_for_slug


def _nb(path, title, code=""):
    cells = [{"cell_type": "markdown", "metadata": {}, "source": [f"# {title}\n", "text"]},
             {"cell_type": "code", "metadata": {}, "source": code, "outputs": [],
              "execution_count": None}]
    path.write_text(json.dumps({"cells": cells, "metadata": {}, "nbformat": 4,
                                "nbformat_minor": 5}))


def _card(root, slug, statuses, summary=None, kinds=None, central=0):
    d = root / "papers_repro" / slug
    d.mkdir(parents=True)
    kinds = kinds or ["result"] * len(statuses)
    data = {"slug": slug, "title": f"Paper {slug}", "settings": {},
            "claims": [{"claim": f"{slug}.{i}", "status": s, "kind": k, "central": i == central}
                       for i, (s, k) in enumerate(zip(statuses, kinds, strict=True))]}
    if summary is not None:
        data["summary"] = summary
    (d / "scorecard.json").write_text(json.dumps(data))


@pytest.fixture
def repo(tmp_path):
    nbs = tmp_path / "notebooks"
    (nbs / "solutions").mkdir(parents=True)
    _nb(nbs / "00_index.ipynb", "00 · Start here")
    _nb(nbs / "01_alpha_topic.ipynb", "01 · Alpha", "from eotrack.experiments import alpha as A")
    _nb(nbs / "02_beta_topic.ipynb", "02 · Beta", "import eotrack.experiments.beta")
    _nb(nbs / "solutions" / "01_alpha_solutions.ipynb", "Solutions")
    _nb(nbs / "scratch.ipynb", "not numbered")
    _card(tmp_path, "beta", ["reproduced", "not reproduced"], summary="1/2 reproduced")
    _card(tmp_path, "alpha", ["reproduced", "partial", "partial", "contradicted"],
          kinds=["check", "result", "result", "result"], central=3)
    _card(tmp_path, "gamma", ["not reproducible"])
    return tmp_path


def test_scorecard_counts_and_order(repo):
    df = collection_scorecard(repo / "papers_repro")
    assert list(df["slug"]) == ["alpha", "beta", "gamma"]  # by notebook, then unmatched papers
    assert list(df["notebook"]) == ["01_alpha_topic", "02_beta_topic", ""]
    alpha = df.iloc[0]
    # the check counts apart: results 0/3 reproduced, checks 1/1 pass
    assert (alpha["claims"], alpha["results"], alpha["reproduced"], alpha["partial"],
            alpha["contradicted"], alpha["checks"], alpha["checks pass"]) == (4, 3, 0, 2, 1, 1, 1)
    assert alpha["summary"] == ("results: 0/3 reproduced, 2 partial, 1 contradicted; "
                                "checks: 1/1 pass")  # computed when the card has none
    assert alpha["central"] == "alpha.3: **contradicted**"
    assert df.iloc[1]["summary"] == "1/2 reproduced"
    assert df.iloc[2]["not reproducible"] == 1
    statuses = ["reproduced", "partial", "not reproduced", "contradicted", "not reproducible"]
    assert int(df[statuses].sum().sum()) == int(df["results"].sum())
    assert int(df["results"].sum() + df["checks"].sum()) == int(df["claims"].sum())


def test_central_verdict(repo):
    from eotrack.repro import central_verdict

    assert central_verdict("alpha", repo / "papers_repro") == "alpha.3: **contradicted**"
    with pytest.raises(ValueError, match="no scorecard for 'delta'"):
        central_verdict("delta", repo / "papers_repro")
    with pytest.raises(ValueError, match="slug must be"):
        central_verdict("../x", repo / "papers_repro")


def test_lesson_navigation(repo):
    from eotrack.notebook import lesson_footer, lesson_header, lesson_navigation

    nbs = repo / "notebooks"
    assert lesson_navigation("01", nbs) == ("← [00 · Start here](00_index.ipynb) · "
                                            "[02 · Beta](02_beta_topic.ipynb) →")
    assert lesson_navigation(2, nbs) == ("← [01 · Alpha](01_alpha_topic.ipynb) · "
                                         "[index](00_index.ipynb)")
    assert lesson_footer("00", nbs, show=False) == "[01 · Alpha](01_alpha_topic.ipynb) →"
    head = lesson_header("02", nbs, show=False)
    assert head.startswith("← [01 · Alpha]")
    with pytest.raises(ValueError, match="no notebook 05_"):
        lesson_navigation("05", nbs)
    with pytest.raises(ValueError, match="two-digit notebook number"):
        lesson_navigation("1a", nbs)
    with pytest.raises(TypeError, match="notebook number"):
        lesson_navigation(1.0, nbs)


def test_scorecard_of_the_repository():
    df = collection_scorecard()
    assert len(df) >= 1 and (df["claims"] > 0).all()


def test_notebooks_listing(repo):
    df = collection_notebooks(repo / "notebooks")
    assert list(df["number"]) == ["00", "01", "02"]
    assert list(df["title"]) == ["Start here", "Alpha", "Beta"]
    assert list(df["solutions"]) == ["", "solutions/01_alpha_solutions.ipynb", ""]


def test_notebook_for_slug(repo):
    assert notebook_for_slug("alpha", repo / "notebooks") == "01_alpha_topic"
    assert notebook_for_slug("beta", repo / "notebooks") == "02_beta_topic"
    assert notebook_for_slug("alph", repo / "notebooks") is None  # whole words only


@pytest.mark.parametrize("slug", ["", "Alpha", "a-b", 3, None])
def test_notebook_for_slug_bad_slug(slug, repo):
    with pytest.raises(ValueError, match="slug"):
        notebook_for_slug(slug, repo / "notebooks")


def test_missing_folders(tmp_path):
    with pytest.raises(FileNotFoundError, match="not a directory"):
        collection_scorecard(tmp_path / "nope")
    with pytest.raises(FileNotFoundError, match="not a directory"):
        collection_notebooks(tmp_path / "nope")


def test_bad_path_type():
    with pytest.raises(TypeError, match="path"):
        collection_scorecard(42)


def test_no_scorecards(tmp_path):
    (tmp_path / "papers_repro").mkdir()
    with pytest.raises(ValueError, match=r"no \*/scorecard\.json"):
        collection_scorecard(tmp_path / "papers_repro")


@pytest.mark.parametrize("content, match", [
    ("{not json", "not valid JSON"),
    ("[1, 2]", "expected a JSON object"),
    (json.dumps({"slug": "x", "title": "t"}), r"missing key\(s\) \['claims'\]"),
    (json.dumps({"slug": "x", "title": "t", "claims": {}}), "must be a list"),
    (json.dumps({"slug": "x", "title": "t", "claims": [{"status": "great"}]}),
     "'great' is not one of"),
])
def test_malformed_scorecard_names_the_file(tmp_path, content, match):
    d = tmp_path / "papers_repro" / "x"
    d.mkdir(parents=True)
    (d / "scorecard.json").write_text(content)
    with pytest.raises(ValueError, match=match) as info:
        collection_scorecard(tmp_path / "papers_repro")
    assert "scorecard.json" in str(info.value)


def test_malformed_notebook(tmp_path):
    nbs = tmp_path / "notebooks"
    nbs.mkdir()
    (nbs / "01_bad.ipynb").write_text("{}")
    with pytest.raises(ValueError, match="no 'cells' list"):
        collection_notebooks(nbs)
