"""The collection at a glance: its notebooks and every paper's computed scorecard.

Used by ``notebooks/00_index`` so the landing page never types a result: the table is read
from the ``papers_repro/<slug>/scorecard.json`` files that ``make repro`` writes.
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path

import pandas as pd

from .claims import papers_repro_dir
from .scorecard import Status, status_summary

__all__ = ["central_verdict", "collection_notebooks", "collection_scorecard",
           "notebook_for_slug"]

_STEM = re.compile(r"^(\d\d)_[A-Za-z0-9_]+$")
_STATUSES = [str(s) for s in Status]


def _dir(path: str | os.PathLike[str], what: str) -> Path:
    if not isinstance(path, str | os.PathLike):
        raise TypeError(f"{what} must be a path (str or os.PathLike), got {type(path).__name__}")
    p = Path(path)
    if not p.is_dir():
        raise FileNotFoundError(f"{what} {str(p)!r} is not a directory")
    return p


def _notebooks_dir(notebooks: str | os.PathLike[str] | None) -> Path:
    if notebooks is None:
        return _dir(papers_repro_dir().parent / "notebooks", "notebooks")
    return _dir(notebooks, "notebooks")


def _cells(path: Path) -> list[dict]:
    try:
        nb = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError) as exc:
        raise ValueError(f"{path} is not a readable notebook: {exc}") from None
    cells = nb.get("cells") if isinstance(nb, dict) else None
    if not isinstance(cells, list):
        raise ValueError(f"{path} is not a notebook (no 'cells' list)")
    return cells


def _source(cell: dict) -> str:
    src = cell.get("source", "")
    return "".join(src) if isinstance(src, list) else str(src)


def _title(cells: list[dict], stem: str) -> str:
    for cell in cells:
        if cell.get("cell_type") == "markdown":
            m = re.search(r"^#\s+(.+)$", _source(cell), re.MULTILINE)
            if m:
                return m.group(1).split("·", 1)[-1].strip()
    return stem


def notebook_for_slug(slug: str, notebooks: str | os.PathLike[str] | None = None) -> str | None:
    """Stem of the first notebook (in name order) whose code imports ``eotrack.experiments.<slug>``.

    Parameters
    ----------
    slug : str
        A paper slug such as ``"wransac"``.
    notebooks : path, optional
        The notebooks folder; default: the repository's ``notebooks/``.

    Returns
    -------
    str or None
        e.g. ``"01_wransac_trajectory_prediction"``, or ``None`` when no notebook uses it.
    """
    if not isinstance(slug, str) or not re.fullmatch(r"[a-z][a-z0-9_]*", slug):
        raise ValueError(f"slug must be a lower-case identifier such as 'wransac', got {slug!r}")
    pat = re.compile(rf"experiments(\.|\s+import\s+){slug}\b")
    for path in sorted(_notebooks_dir(notebooks).glob("*.ipynb")):
        code = "\n".join(_source(c) for c in _cells(path) if c.get("cell_type") == "code")
        if pat.search(code):
            return path.stem
    return None


def collection_notebooks(notebooks: str | os.PathLike[str] | None = None) -> pd.DataFrame:
    """The collection's numbered notebooks, in reading order.

    Parameters
    ----------
    notebooks : path, optional
        The notebooks folder; default: the repository's ``notebooks/``.

    Returns
    -------
    pandas.DataFrame
        One row per ``NN_<name>.ipynb`` with columns ``number``, ``stem``, ``title`` (the first
        Markdown heading, without its ``"NN ·"`` prefix), ``path`` (relative to the notebooks
        folder) and ``solutions`` (the worked-solutions notebook's relative path, or ``""``).
    """
    top = _notebooks_dir(notebooks)
    sol = {p.stem[:2]: p for p in (top / "solutions").glob("*.ipynb")} \
        if (top / "solutions").is_dir() else {}
    rows = []
    for path in sorted(top.glob("*.ipynb")):
        m = _STEM.match(path.stem)
        if not m:
            continue
        number = m.group(1)
        s = sol.get(number)
        rows.append({"number": number, "stem": path.stem,
                     "title": _title(_cells(path), path.stem), "path": path.name,
                     "solutions": f"solutions/{s.name}" if s is not None else ""})
    return pd.DataFrame(rows, columns=["number", "stem", "title", "path", "solutions"])


def _load_card(path: Path) -> dict:
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError) as exc:
        raise ValueError(f"{path} is not valid JSON: {exc}") from None
    if not isinstance(data, dict):
        raise ValueError(f"{path}: expected a JSON object, got {type(data).__name__}")
    missing = [k for k in ("slug", "title", "claims") if k not in data]
    if missing:
        raise ValueError(f"{path}: missing key(s) {missing}; a scorecard.json written by "
                         "`make repro` has slug, title, summary, settings and claims")
    if not isinstance(data["claims"], list):
        raise ValueError(f"{path}: 'claims' must be a list of claim rows")
    for row in data["claims"]:
        status = row.get("status") if isinstance(row, dict) else None
        if status not in _STATUSES:
            raise ValueError(f"{path}: claim status {status!r} is not one of {_STATUSES}")
    return data


def collection_scorecard(papers_repro: str | os.PathLike[str] | None = None, *,
                         notebooks: str | os.PathLike[str] | None = None) -> pd.DataFrame:
    """Every paper's scorecard in one table, read from ``papers_repro/*/scorecard.json``.

    Parameters
    ----------
    papers_repro : path, optional
        The ``papers_repro`` folder; default: found by :func:`eotrack.repro.papers_repro_dir`.
    notebooks : path, optional
        The notebooks folder used to name each paper's notebook; default: ``notebooks/``
        beside ``papers_repro``.

    Returns
    -------
    pandas.DataFrame
        One row per paper, ordered by notebook number: ``notebook`` (stem, ``""`` if none),
        ``slug``, ``paper`` (the citation), ``claims`` (count), ``results`` (how many claims are
        the paper's results), one count column per status **over the results only**
        (``reproduced``, ``partial``, ``not reproduced``, ``contradicted``,
        ``not reproducible``), ``checks`` and ``checks pass`` (checks of a formula, an input or
        our construction, counted apart), ``fragile`` (claims whose status changed on some seed
        of the last stability run), ``central`` (the verdict line on the central claims) and
        ``summary``. A row without ``kind`` counts as a result.

    Raises
    ------
    FileNotFoundError
        If a folder does not exist.
    ValueError
        If there is no scorecard, or one is malformed (the message names the file).
    """
    cards_dir = papers_repro_dir() if papers_repro is None else _dir(papers_repro,
                                                                      "papers_repro")
    if notebooks is None:
        nb_dir = cards_dir.parent / "notebooks"
        nb_dir = nb_dir if nb_dir.is_dir() else None
    else:
        nb_dir = _dir(notebooks, "notebooks")
    paths = sorted(cards_dir.glob("*/scorecard.json"))
    if not paths:
        raise ValueError(f"no */scorecard.json under {str(cards_dir)!r}; run `make repro`")
    rows = []
    for path in paths:
        data = _load_card(path)
        res = [r for r in data["claims"] if r.get("kind", "result") != "check"]
        chk = [r for r in data["claims"] if r.get("kind", "result") == "check"]
        counts = {s: sum(1 for r in res if r["status"] == s) for s in _STATUSES}
        stem = (notebook_for_slug(data["slug"], nb_dir) if nb_dir is not None else None) or ""
        summary = data.get("summary") or status_summary(data["claims"])
        rows.append({"notebook": stem, "slug": data["slug"], "paper": data["title"],
                     "claims": len(data["claims"]), "results": len(res), **counts,
                     "checks": len(chk),
                     "checks pass": sum(1 for r in chk if r["status"] == Status.REPRODUCED),
                     "fragile": sum(1 for r in data["claims"] if r.get("fragile")),
                     "central": _central(data), "summary": summary})
    df = pd.DataFrame(rows, columns=["notebook", "slug", "paper", "claims", "results",
                                     *_STATUSES, "checks", "checks pass", "fragile", "central",
                                     "summary"])
    # papers with a notebook first, in reading order; the rest by slug
    order = df["notebook"].where(df["notebook"] != "", "~" + df["slug"])
    return df.iloc[order.argsort(kind="stable")].reset_index(drop=True)


def _central(data: dict) -> str:
    if data.get("central"):
        return str(data["central"])
    parts = [f"{r['claim']}: **{r['status']}**" for r in data["claims"] if r.get("central")]
    return "; ".join(parts) if parts else "no central claim marked"


def central_verdict(slug: str, papers_repro: str | os.PathLike[str] | None = None) -> str:
    """The computed one-line verdict on ``slug``'s central claim(s), from its scorecard.json.

    Parameters
    ----------
    slug : str
        A paper slug such as ``"wransac"``.
    papers_repro : path, optional
        The ``papers_repro`` folder; default: found by :func:`eotrack.repro.papers_repro_dir`.

    Returns
    -------
    str
        e.g. ``"central claim wransac.table1: **contradicted** (5/5 seeds)"`` (Markdown).

    Raises
    ------
    ValueError
        If the slug is malformed or has no scorecard (run ``make repro``).
    """
    if not isinstance(slug, str) or not re.fullmatch(r"[a-z][a-z0-9_]*", slug):
        raise ValueError(f"slug must be a lower-case identifier such as 'wransac', got {slug!r}")
    base = papers_repro_dir() if papers_repro is None else _dir(papers_repro, "papers_repro")
    path = base / slug / "scorecard.json"
    if not path.is_file():
        raise ValueError(f"no scorecard for {slug!r} at {str(path)!r}; run `make repro`")
    return _central(_load_card(path))
