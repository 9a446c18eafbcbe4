"""Paper claims: the paper's numbers, kept in ``papers_repro/<slug>/claims.toml``.

Paper values live in those files and nowhere else in the code; experiments compute results and
the scorecard compares them with the references loaded here.

Each ``[claims."<id>"]`` table has ``title``, ``source``, ``statement``, ``criterion`` and:

``kind``
    ``"result"`` (something the paper found) or ``"check"`` (it verifies a formula, an input or
    our own construction; it passes or fails). Required.
``central``
    ``true`` on the paper's central claim(s); only on results. Every paper has at least one.
``partial_band``
    The text, written before the run, of what counts as ``partial``. A claim without one can
    never be scored ``partial``.
``directional``
    ``true`` when the paper states a direction or an ordering; its evaluator must then be able to
    return ``contradicted`` (the paper's side excluded by a pre-stated paired interval).
``[[claims."<id>".history]]``
    One entry per earlier criterion: ``date`` (YYYY-MM-DD), ``criterion`` (the earlier text),
    ``reason`` and ``after_results`` (whether the change was made after results were seen).
"""

from __future__ import annotations

import datetime as _dt
import os
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

__all__ = ["KINDS", "Claim", "CriterionChange", "load_claims", "papers_repro_dir"]

#: The two kinds of claim.
KINDS = ("result", "check")
_DATE = re.compile(r"^\d{4}-\d{2}-\d{2}$")


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
class CriterionChange:
    """An earlier criterion of a claim, kept when the criterion changed.

    Attributes
    ----------
    date
        ``YYYY-MM-DD`` of the change.
    criterion
        The earlier text.
    reason
        Why it changed.
    after_results
        Whether the change was made after results were seen (it then cannot, alone, make the
        claim reproduced).
    """

    date: str
    criterion: str
    reason: str
    after_results: bool


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
    kind
        ``"result"`` or ``"check"``.
    central
        Whether this is (one of) the paper's central claim(s).
    partial_band
        What counts as ``partial``, stated before the run (``""``: no partial status).
    directional
        Whether the paper states a direction or ordering (``contradicted`` is then reachable).
    history
        Earlier criteria, oldest first.
    """

    id: str
    title: str
    source: str
    statement: str
    criterion: str
    paper: dict[str, Any] = field(default_factory=dict)
    kind: str = "result"
    central: bool = False
    partial_band: str = ""
    directional: bool = False
    history: tuple[CriterionChange, ...] = ()

    @property
    def is_check(self) -> bool:
        """Whether the claim is a check of a formula, an input or our construction."""
        return self.kind == "check"


def _history(path: Path, cid: str, raw: Any) -> tuple[CriterionChange, ...]:
    if not isinstance(raw, list):
        raise ValueError(f"{path}: claim {cid!r}: 'history' must be an array of tables "
                         f'([[claims."{cid}".history]])')
    out = []
    for k, h in enumerate(raw):
        if not isinstance(h, dict):
            raise ValueError(f"{path}: claim {cid!r}: history entry {k} is not a table")
        date = h.get("date")
        if isinstance(date, _dt.date):
            date = date.isoformat()
        if not isinstance(date, str) or not _DATE.match(date):
            raise ValueError(f"{path}: claim {cid!r}: history entry {k} needs a date "
                             f"'YYYY-MM-DD', got {h.get('date')!r}")
        for key in ("criterion", "reason"):
            if not isinstance(h.get(key), str) or not h[key].strip():
                raise ValueError(f"{path}: claim {cid!r}: history entry {k} ({date}) needs a "
                                 f"non-empty {key!r}")
        if not isinstance(h.get("after_results"), bool):
            raise ValueError(f"{path}: claim {cid!r}: history entry {k} ({date}) needs "
                             "after_results = true or false (was it changed after results "
                             "were seen?)")
        out.append(CriterionChange(date=date, criterion=h["criterion"], reason=h["reason"],
                                   after_results=h["after_results"]))
    return tuple(out)


#: The keys a claim may have: anything else (a typo such as ``partial_bnad``) is an error, so
#: that a band or flag "stated before the run" cannot silently fail to exist.
CLAIM_KEYS = frozenset({"title", "source", "statement", "criterion", "kind", "paper", "central",
                        "directional", "partial_band", "history"})


def _claim(path: Path, cid: str, entry: dict[str, Any]) -> Claim:
    unknown = set(entry) - CLAIM_KEYS
    if unknown:
        raise ValueError(f"{path}: claim {cid!r} has unknown key(s) {sorted(unknown)}; "
                         f"allowed: {sorted(CLAIM_KEYS)}")
    missing = {"title", "source", "statement", "criterion", "kind"} - set(entry)
    if missing:
        raise ValueError(f"{path}: claim {cid!r} lacks {sorted(missing)}"
                         + (" (kind = \"result\" or \"check\")" if "kind" in missing else ""))
    kind = entry["kind"]
    if kind not in KINDS:
        raise ValueError(f"{path}: claim {cid!r}: kind must be one of {list(KINDS)}, got {kind!r}")
    central = entry.get("central", False)
    directional = entry.get("directional", False)
    for name, val in (("central", central), ("directional", directional)):
        if not isinstance(val, bool):
            raise ValueError(f"{path}: claim {cid!r}: {name} must be true or false, got {val!r}")
    if central and kind == "check":
        raise ValueError(f"{path}: claim {cid!r}: a check cannot be central (central = true is "
                         "for the paper's own results)")
    if directional and kind == "check":
        raise ValueError(f"{path}: claim {cid!r}: a check cannot be directional")
    band = entry.get("partial_band", "")
    if not isinstance(band, str):
        raise ValueError(f"{path}: claim {cid!r}: partial_band must be a string")
    if band and kind == "check":
        raise ValueError(f"{path}: claim {cid!r}: a check passes or fails; it has no partial_band")
    return Claim(id=cid, title=entry["title"], source=entry["source"],
                 statement=entry["statement"], criterion=entry["criterion"],
                 paper=dict(entry.get("paper", {})), kind=kind, central=central,
                 partial_band=band.strip(), directional=directional,
                 history=_history(path, cid, entry.get("history", [])))


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
        out[cid] = _claim(path, cid, entry)
    if not out:
        raise ValueError(f"{path} defines no [claims.\"<id>\"] tables")
    if not any(c.central for c in out.values()):
        raise ValueError(f"{path}: no claim is marked central = true; every paper marks its "
                         "central (comparative) result claim(s)")
    return out
