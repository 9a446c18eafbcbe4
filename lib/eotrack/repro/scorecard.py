"""Scorecards: paper versus ours, one row per claim."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import asdict, dataclass
from enum import StrEnum

import pandas as pd

from .claims import Claim

__all__ = ["ClaimResult", "Status", "check_claims_complete", "scorecard"]


class Status(StrEnum):
    """Outcome of a claim."""

    REPRODUCED = "reproduced"
    PARTIAL = "partial"
    NOT_REPRODUCED = "not reproduced"
    NOT_REPRODUCIBLE = "not reproducible"


@dataclass(frozen=True)
class ClaimResult:
    """One scorecard row.

    ``paper`` and ``ours`` are short human-readable summaries; ``note`` must explain, with
    numbers, every status other than ``reproduced``.
    """

    claim: str
    paper: str
    ours: str
    criterion: str
    status: Status
    note: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "status", Status(self.status))
        if self.status is not Status.REPRODUCED and not self.note.strip():
            raise ValueError(f"claim {self.claim}: status {self.status} needs a note saying why")

    @classmethod
    def from_claim(cls, claim: Claim, *, ours: str, status: Status | str, paper: str | None = None,
                   note: str = "") -> ClaimResult:
        """Build a row from a :class:`Claim`, taking its criterion (and paper summary)."""
        return cls(claim=claim.id, paper=paper if paper is not None else claim.statement,
                   ours=ours, criterion=claim.criterion, status=Status(status), note=note)

    def to_dict(self) -> dict[str, str]:
        """Plain-dict form for JSON."""
        d = asdict(self)
        d["status"] = str(self.status)
        return d


def scorecard(results: Iterable[ClaimResult]) -> pd.DataFrame:
    """Tabulate claim results as a DataFrame (columns claim, paper, ours, criterion, status, note)."""
    rows = [r.to_dict() for r in results]
    cols = ["claim", "paper", "ours", "criterion", "status", "note"]
    return pd.DataFrame(rows, columns=cols)


def check_claims_complete(claims: Mapping[str, Claim], results: Iterable[ClaimResult]) -> None:
    """Raise if the results do not cover every claim exactly once."""
    ids = [r.claim for r in results]
    missing = sorted(set(claims) - set(ids))
    extra = sorted(set(ids) - set(claims))
    dup = sorted({i for i in ids if ids.count(i) > 1})
    if missing or extra or dup:
        raise ValueError(f"scorecard mismatch: missing {missing}, unknown {extra}, duplicated {dup}")
