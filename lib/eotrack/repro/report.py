"""A paper's reproduction and the report files written from it."""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pandas as pd

from .scorecard import ClaimResult, Status, scorecard

__all__ = ["Reproduction", "write_report"]


@dataclass
class Reproduction:
    """Everything one paper's reproduction produced.

    Attributes
    ----------
    slug
        Paper slug (``papers_repro/<slug>``).
    title
        Paper citation, one line.
    claims
        One :class:`ClaimResult` per claim id.
    tables
        Named tables (e.g. ``"Table 1"``) as DataFrames, paper values beside ours.
    figures
        Named matplotlib figures; the key is the file stem.
    text
        Markdown paragraphs for the report (setup, deviations).
    settings
        The trial counts and parameters used (written to the report).
    data
        The experiment's own result objects (not written), so a notebook can reuse a run
        instead of repeating it.
    """

    slug: str
    title: str
    claims: list[ClaimResult]
    tables: dict[str, pd.DataFrame] = field(default_factory=dict)
    figures: dict[str, Any] = field(default_factory=dict)
    text: str = ""
    settings: dict[str, Any] = field(default_factory=dict)
    data: dict[str, Any] = field(default_factory=dict)

    @property
    def scorecard(self) -> pd.DataFrame:
        """Scorecard table."""
        return scorecard(self.claims)

    def status_summary(self) -> str:
        """E.g. ``"9/11 reproduced, 2 partial"``."""
        counts = {s: sum(r.status is s for r in self.claims) for s in Status}
        parts = [f"{counts[Status.REPRODUCED]}/{len(self.claims)} reproduced"]
        parts += [f"{n} {s}" for s, n in counts.items() if n and s is not Status.REPRODUCED]
        return ", ".join(parts)


def _md_table(df: pd.DataFrame) -> str:
    """Markdown table without the optional ``tabulate`` dependency."""
    df = df.reset_index() if not isinstance(df.index, pd.RangeIndex) else df

    def fmt(v: Any) -> str:
        if isinstance(v, float):
            return f"{v:.4g}"
        return str(v).replace("|", "\\|").replace("\n", " ")

    head = "| " + " | ".join(map(str, df.columns)) + " |"
    sep = "|" + "---|" * len(df.columns)
    body = ["| " + " | ".join(fmt(v) for v in row) + " |" for row in df.itertuples(index=False)]
    return "\n".join([head, sep, *body])


def write_report(rep: Reproduction, out_dir: str | os.PathLike[str], *, dpi: int = 110) -> Path:
    """Write ``REPORT.md``, ``scorecard.json`` and ``figures/*.png`` into ``out_dir``.

    Returns
    -------
    pathlib.Path
        The report path.
    """
    out = Path(out_dir)
    fig_dir = out / "figures"
    fig_dir.mkdir(parents=True, exist_ok=True)
    for old in fig_dir.glob("*.png"):
        old.unlink()
    lines = [f"# Reproduction report: `{rep.slug}`", "", rep.title, "",
             f"**Status:** {rep.status_summary()}", "",
             "Written by `python -m eotrack.repro` (`make repro`); do not edit by hand.", ""]
    if rep.settings:
        lines += ["## Settings", ""]
        lines += [f"- `{k}` = {v}" for k, v in rep.settings.items()]
        lines.append("")
    lines += ["## Scorecard", "", _md_table(rep.scorecard), ""]
    if rep.text:
        lines += [rep.text.strip(), ""]
    for name, df in rep.tables.items():
        lines += [f"## {name}", "", _md_table(df), ""]
    if rep.figures:
        lines += ["## Figures", ""]
        for stem, fig in rep.figures.items():
            fig.savefig(fig_dir / f"{stem}.png", dpi=dpi, bbox_inches="tight")
            lines += [f"![{stem}](figures/{stem}.png)", ""]
    report = out / "REPORT.md"
    report.write_text("\n".join(lines))
    (out / "scorecard.json").write_text(
        json.dumps({"slug": rep.slug, "title": rep.title, "summary": rep.status_summary(),
                    "settings": {k: str(v) for k, v in rep.settings.items()},
                    "claims": [r.to_dict() for r in rep.claims]}, indent=2) + "\n")
    return report
