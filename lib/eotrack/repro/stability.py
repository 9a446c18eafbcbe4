"""Seed stability: does each claim's status survive independent root seeds?

``python -m eotrack.repro --seeds K`` re-runs a paper at its full counts on the root seeds
``1 … K`` (the committed run uses each experiment's default seeds) and stores every seed's
status per claim in ``papers_repro/<slug>/stability.json``. The report then shows, per claim,
the share of seeds that give the committed status; a claim whose status differs on any seed is
**fragile**.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

from .scorecard import Status

__all__ = ["Stability", "read_stability", "write_stability"]

FILE = "stability.json"


@dataclass(frozen=True)
class Stability:
    """Every seed's status per claim, from one stability run.

    Attributes
    ----------
    date
        ``YYYY-MM-DD`` of the run.
    seeds
        The root seeds.
    statuses
        claim id → the status on each seed (same order as ``seeds``).
    quick
        Whether the run used the reduced (test) counts — then it says nothing about the
        committed report.
    """

    date: str
    seeds: tuple[int, ...]
    statuses: Mapping[str, tuple[str, ...]]
    quick: bool = False

    @property
    def k(self) -> int:
        """Number of seeds."""
        return len(self.seeds)

    def share(self, claim: str, committed: Status | str) -> float | None:
        """Share of seeds whose status equals ``committed`` (``None``: claim not in the run)."""
        st = self.statuses.get(claim)
        if not st:
            return None
        return sum(s == str(committed) for s in st) / len(st)

    def fragile(self, claim: str, committed: Status | str) -> bool:
        """Whether any seed gave another status than ``committed``."""
        s = self.share(claim, committed)
        return s is not None and s < 1.0

    def cell(self, claim: str, committed: Status | str) -> str:
        """E.g. ``"5/5"`` or ``"3/5 fragile (2× partial)"`` for a report table."""
        st = self.statuses.get(claim)
        if not st:
            return "not run"
        same = sum(s == str(committed) for s in st)
        if same == len(st):
            return f"{same}/{len(st)}"
        others = sorted({s for s in st if s != str(committed)})
        detail = ", ".join(f"{sum(x == o for x in st)}× {o}" for o in others)
        return f"{same}/{len(st)} **fragile** ({detail})"


def write_stability(out_dir: str | os.PathLike[str], seeds: Sequence[int],
                    statuses: Mapping[str, Sequence[Status | str]], *, quick: bool = False,
                    date: str | None = None) -> Path:
    """Write ``stability.json`` into ``out_dir``; return its path."""
    seeds = tuple(int(s) for s in seeds)
    if not seeds:
        raise ValueError("seeds must name at least one root seed")
    for cid, st in statuses.items():
        if len(st) != len(seeds):
            raise ValueError(f"claim {cid}: {len(st)} statuses for {len(seeds)} seeds")
    data = {"date": date or _dt.date.today().isoformat(), "seeds": list(seeds), "quick": quick,
            "statuses": {cid: [str(Status(s)) for s in st] for cid, st in statuses.items()}}
    path = Path(out_dir) / FILE
    path.write_text(json.dumps(data, indent=2) + "\n")
    return path


def read_stability(out_dir: str | os.PathLike[str]) -> Stability | None:
    """Read ``stability.json`` from ``out_dir`` (``None`` if there is none).

    Raises
    ------
    ValueError
        If the file is malformed (the message names it).
    """
    path = Path(out_dir) / FILE
    if not path.is_file():
        return None
    try:
        data = json.loads(path.read_text())
        seeds = tuple(int(s) for s in data["seeds"])
        statuses = {str(k): tuple(str(Status(s)) for s in v) for k, v in data["statuses"].items()}
        date = str(data["date"])
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise ValueError(f"{path} is not a stability file written by `python -m eotrack.repro "
                         f"--seeds K`: {exc}") from None
    return Stability(date=date, seeds=seeds, statuses=statuses, quick=bool(data.get("quick")))
