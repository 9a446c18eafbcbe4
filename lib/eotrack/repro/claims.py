"""Paper claims: the paper's numbers, kept in ``papers_repro/<slug>/claims.toml``.

Paper values live in those files and nowhere else in the code; experiments compute results and
the scorecard compares them with the references loaded here.
"""

from __future__ import annotations

import os
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

__all__ = ["Claim", "load_claims", "papers_repro_dir"]


def papers_repro_dir(root: str | os.PathLike[str] | None = None) -> Path:
    """Locate the ``papers_repro`` directory.

    Search order: ``root`` if given, the ``EOTRACK_PAPERS_REPRO`` environment variable, the
    repository that contains this package (editable install), the current directory.

    Raises
    ------
    FileNotFoundError
        If no candidate exists.
    """
    candidates: list[Path] = []
    if root is not None:
        candidates.append(Path(root))
    if os.environ.get("EOTRACK_PAPERS_REPRO"):
        candidates.append(Path(os.environ["EOTRACK_PAPERS_REPRO"]))
    candidates.append(Path(__file__).resolve().parents[3] / "papers_repro")
    candidates.append(Path.cwd() / "papers_repro")
    for c in candidates:
        if c.is_dir():
            return c
    raise FileNotFoundError(
        "papers_repro/ not found; run from the eotrack repository or set EOTRACK_PAPERS_REPRO "
        f"(looked in {[str(c) for c in candidates]})"
    )


@dataclass(frozen=True)
class Claim:
    """One claim of a paper.

    Attributes
    ----------
    id
        Stable claim id, e.g. ``"wransac.table1"``.
    title
        Short name.
    source
        Where the paper states it (figure, table, section).
    statement
        What the paper says, in words.
    criterion
        What counts as reproduced.
    paper
        The paper's values (numbers, tables), exactly as printed.
    """

    id: str
    title: str
    source: str
    statement: str
    criterion: str
    paper: dict[str, Any] = field(default_factory=dict)


def load_claims(slug: str, root: str | os.PathLike[str] | None = None) -> dict[str, Claim]:
    """Load ``papers_repro/<slug>/claims.toml``.

    Parameters
    ----------
    slug
        Paper slug, e.g. ``"wransac"``.
    root
        Optional ``papers_repro`` directory.

    Returns
    -------
    dict
        Claim id → :class:`Claim`, in file order.
    """
    if not isinstance(slug, str) or not slug.isidentifier():
        raise ValueError(f"slug must be a paper slug such as 'wransac', got {slug!r}")
    base = papers_repro_dir(root)
    path = base / slug / "claims.toml"
    if not path.is_file():
        known = sorted(p.parent.name for p in base.glob("*/claims.toml"))
        raise ValueError(f"no claims for slug {slug!r}; known slugs: {known}")
    with path.open("rb") as fh:
        data = tomllib.load(fh)
    out: dict[str, Claim] = {}
    for cid, entry in data.get("claims", {}).items():
        missing = {"title", "source", "statement", "criterion"} - set(entry)
        if missing:
            raise ValueError(f"{path}: claim {cid!r} lacks {sorted(missing)}")
        out[cid] = Claim(
            id=cid,
            title=entry["title"],
            source=entry["source"],
            statement=entry["statement"],
            criterion=entry["criterion"],
            paper=dict(entry.get("paper", {})),
        )
    if not out:
        raise ValueError(f"{path} defines no [claims.\"<id>\"] tables")
    return out
