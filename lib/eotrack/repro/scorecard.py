"""Scorecards: paper versus ours, one row per claim.

Results (what the paper found) and checks (a formula, an input or our own construction) are
counted apart: a check that passes is not a reproduction of the paper.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import asdict, dataclass
from enum import StrEnum

import pandas as pd

from .claims import KINDS, Claim

__all__ = ["CHECK_STATUSES", "ClaimResult", "Status", "allowed_statuses", "check_claims_complete",
           "scorecard", "status_summary"]


class Status(StrEnum):
    """Outcome of a claim.

    ``contradicted`` means the paper's direction or ordering is reversed with the criterion's
    pre-stated confidence (a paired interval that excludes the paper's side). For a check,
    ``reproduced`` reads "pass" and ``not reproduced`` reads "fail".
    """

    REPRODUCED = "reproduced"
    PARTIAL = "partial"
    NOT_REPRODUCED = "not reproduced"
    CONTRADICTED = "contradicted"
    NOT_REPRODUCIBLE = "not reproducible"


#: Statuses a check may have.
CHECK_STATUSES = (Status.REPRODUCED, Status.NOT_REPRODUCED)


def allowed_statuses(claim: Claim) -> tuple[Status, ...]:
    """The statuses ``claim``'s criterion allows (a check passes or fails; ``partial`` needs a
    band; ``contradicted`` needs a directional claim)."""
    if claim.is_check:
        return CHECK_STATUSES
    out = [Status.REPRODUCED]
    if claim.partial_band:
        out.append(Status.PARTIAL)
    out.append(Status.NOT_REPRODUCED)
    if claim.directional:
        out.append(Status.CONTRADICTED)
    out.append(Status.NOT_REPRODUCIBLE)
    return tuple(out)


@dataclass(frozen=True)
class ClaimResult:
    """One scorecard row.

    ``paper`` and ``ours`` are short human-readable summaries; ``note`` must explain, with
    numbers, every status other than ``reproduced``. ``kind`` and ``central`` come from the
    claim; ``variant`` reports a result obtained only by our own variant of the method (it
    never sets the status, which is the paper's method's).
    """

    claim: str
    paper: str
    ours: str
    criterion: str
    status: Status
    note: str = ""
    kind: str = "result"
    central: bool = False
    variant: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "status", Status(self.status))
        if self.kind not in KINDS:
            raise ValueError(f"claim {self.claim}: kind must be one of {list(KINDS)}, "
                             f"got {self.kind!r}")
        if self.status is not Status.REPRODUCED and not self.note.strip():
            raise ValueError(f"claim {self.claim}: status {self.status} needs a note saying why")
        if self.kind == "check" and self.status not in CHECK_STATUSES:
            raise ValueError(f"claim {self.claim}: a check passes (reproduced) or fails (not "
                             f"reproduced); got {self.status}")
        if self.kind == "check" and self.central:
            raise ValueError(f"claim {self.claim}: a check cannot be central")

    @classmethod
    def from_claim(cls, claim: Claim, *, ours: str, status: Status | str, paper: str | None = None,
                   note: str = "", variant: str = "") -> ClaimResult:
        """Build a row from a :class:`Claim`, taking its criterion, kind and central flag.

        Raises
        ------
        ValueError
            If the status is not one the claim's criterion allows: ``partial`` without a
            ``partial_band`` in claims.toml, ``contradicted`` on a claim that is not
            ``directional``, or anything but pass/fail on a check. The message names the claim.
        """
        st = Status(status)
        allowed = allowed_statuses(claim)
        if st not in allowed:
            why = {Status.PARTIAL: "claims.toml states no partial_band for it (a partial band "
                                   "must be written before the run)",
                   Status.CONTRADICTED: "it is not marked directional in claims.toml"}.get(
                st, f"a {claim.kind} allows only {[str(a) for a in allowed]}")
            raise ValueError(f"claim {claim.id}: status {st} is not allowed: {why}")
        return cls(claim=claim.id, paper=paper if paper is not None else claim.statement,
                   ours=ours, criterion=claim.criterion, status=st, note=note,
                   kind=claim.kind, central=claim.central, variant=variant)

    @property
    def verdict(self) -> str:
        """The status as a reader reads it: pass/fail for a check, the status for a result."""
        if self.kind == "check":
            return "pass" if self.status is Status.REPRODUCED else "fail"
        return str(self.status)

    def to_dict(self) -> dict[str, object]:
        """Plain-dict form for JSON."""
        d = asdict(self)
        d["status"] = str(self.status)
        return d


def scorecard(results: Iterable[ClaimResult]) -> pd.DataFrame:
    """Tabulate claim results (columns claim, kind, central, paper, ours, criterion, status,
    note, variant)."""
    rows = [r.to_dict() for r in results]
    cols = ["claim", "kind", "central", "paper", "ours", "criterion", "status", "note",
            "variant"]
    return pd.DataFrame(rows, columns=cols)


def status_summary(rows: Iterable[Mapping[str, object] | ClaimResult]) -> str:
    """E.g. ``"results: 2/24 reproduced, 3 contradicted, 5 partial; checks: 9/9 pass"``.

    Accepts :class:`ClaimResult` objects or their dict form (a ``scorecard.json`` row; a row
    without ``kind`` counts as a result).
    """
    res, chk = [], []
    for r in rows:
        d = r.to_dict() if isinstance(r, ClaimResult) else r
        (chk if d.get("kind", "result") == "check" else res).append(str(d["status"]))
    parts = []
    if res:
        s = f"results: {res.count(Status.REPRODUCED)}/{len(res)} reproduced"
        extra = [f"{res.count(st)} {st}" for st in Status
                 if st is not Status.REPRODUCED and res.count(st)]
        parts.append(", ".join([s, *extra]))
    if chk:
        parts.append(f"checks: {chk.count(Status.REPRODUCED)}/{len(chk)} pass")
    return "; ".join(parts) if parts else "no claims"


def check_claims_complete(claims: Mapping[str, Claim], results: Iterable[ClaimResult]) -> None:
    """Raise if the results do not cover every claim exactly once, or disagree with the claims'
    kind or central flag."""
    results = list(results)
    ids = [r.claim for r in results]
    missing = sorted(set(claims) - set(ids))
    extra = sorted(set(ids) - set(claims))
    dup = sorted({i for i in ids if ids.count(i) > 1})
    if missing or extra or dup:
        raise ValueError(f"scorecard mismatch: missing {missing}, unknown {extra}, duplicated {dup}")
    for r in results:
        c = claims[r.claim]
        if (r.kind, r.central) != (c.kind, c.central):
            raise ValueError(f"claim {r.claim}: the row says kind={r.kind!r}, central={r.central} "
                             f"but claims.toml says kind={c.kind!r}, central={c.central}; build "
                             "rows with ClaimResult.from_claim")
