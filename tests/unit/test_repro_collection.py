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


def _card(root, slug, statuses, summary=None):
    d = root / "papers_repro" / slug
    d.mkdir(parents=True)
    data = {"slug": slug, "title": f"Paper {slug}", "settings": {},
            "claims": [{"claim": f"{slug}.{i}", "status": s} for i, s in enumerate(statuses)]}
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
    _card(tmp_path, "alpha", ["reproduced", "partial", "partial"])
    _card(tmp_path, "gamma", ["not reproducible"])
    return tmp_path


def test_scorecard_counts_and_order(repo):
    df = collection_scorecard(repo / "papers_repro")
    assert list(df["slug"]) == ["alpha", "beta", "gamma"]  # by notebook, then unmatched papers
    assert list(df["notebook"]) == ["01_alpha_topic", "02_beta_topic", ""]
    alpha = df.iloc[0]
    assert (alpha["claims"], alpha["reproduced"], alpha["partial"]) == (3, 1, 2)
    assert alpha["summary"] == "1 reproduced, 2 partial"  # computed when the card has none
    assert df.iloc[1]["summary"] == "1/2 reproduced"
    assert df.iloc[2]["not reproducible"] == 1
    assert int(df[["reproduced", "partial", "not reproduced", "not reproducible"]].sum().sum()) \
        == int(df["claims"].sum())


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
