"""A paper's reproduction and the report files written from it."""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pandas as pd

from eotrack.plotting import describe_figure

from .claims import Claim, load_claims
from .scorecard import ClaimResult, scorecard, status_summary
from .stability import Stability, read_stability

__all__ = ["Reproduction", "central_line", "pickle_figure", "write_lint_sidecar", "write_report"]


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
        """E.g. ``"results: 1/6 reproduced, 2 contradicted, 3 partial; checks: 3/3 pass"``."""
        return status_summary(self.claims)

    def central_line(self, stability: Stability | None = None) -> str:
        """One line: the verdict on the paper's central claim(s)."""
        return central_line([r.to_dict() for r in self.claims], stability)


def central_line(rows: list[dict[str, Any]], stability: Stability | None = None) -> str:
    """``"central claim wransac.table1: contradicted (5/5 seeds)"`` from scorecard rows.

    Rows without a central claim give ``"no central claim marked"``.
    """
    parts = []
    for r in rows:
        if not r.get("central"):
            continue
        st = str(r["status"])
        stab = ""
        if stability is not None and not stability.quick:
            share = stability.share(r["claim"], st)
            if share is not None:
                n = round(share * stability.k)
                stab = f" ({n}/{stability.k} seeds{', fragile' if n < stability.k else ''})"
        parts.append(f"{r['claim']}: **{st}**{stab}")
    if not parts:
        return "no central claim marked"
    return ("central claim " if len(parts) == 1 else "central claims ") + "; ".join(parts)


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


def _scorecard_table(rep: Reproduction, stability: Stability | None) -> pd.DataFrame:
    rows = []
    for r in rep.claims:
        row = {"claim": r.claim, "kind": r.kind + (" (central)" if r.central else ""),
               "status": r.verdict}
        if stability is not None:
            row["stability"] = stability.cell(r.claim, r.status)
        row.update(paper=r.paper, ours=r.ours, criterion=r.criterion, note=r.note)
        if any(x.variant for x in rep.claims):
            row["our variant"] = r.variant
        rows.append(row)
    return pd.DataFrame(rows)


def _history_lines(claims: dict[str, Claim]) -> list[str]:
    out = []
    for c in claims.values():
        for h in c.history:
            seen = "**after results were seen**" if h.after_results else "before results were seen"
            out.append(f"- `{c.id}`, changed {h.date} ({seen}): {h.reason} Earlier criterion: "
                       f"“{h.criterion}”")
    return out


#: Largest pickled figure (gzip) written beside a REPORT figure; a larger one (an image kept at
#: full resolution in float64) keeps only the lint's verdict.
MAX_FIGURE_BYTES = 2_000_000


def pickle_figure(fig: Any) -> bytes:
    """``fig`` pickled and gzipped, as :func:`write_lint_sidecar` stores it. Pickle a figure
    before its first ``savefig``: a layout engine (``layout="constrained"``) moves the axes
    when the figure is drawn, so a figure pickled after saving renders a little differently."""
    import gzip
    import pickle

    return gzip.compress(pickle.dumps(fig, protocol=pickle.HIGHEST_PROTOCOL), compresslevel=9,
                         mtime=0)


def write_lint_sidecar(fig: Any, png: str | os.PathLike[str], *, dpi: int = 110,
                       pickled: bytes | None = None) -> Path:
    """Beside a saved figure ``<name>.png`` write ``<name>.lint.json`` and ``<name>.fig.gz``
    (issue 23): the figure lint's verdict on that very Figure object, the SHA-256 of the PNG
    written and the pickled Figure itself (gzip), so the lint test re-lints the committed PNG's
    figure with the current rules — checking first that it renders to that PNG — without
    running the paper again. ``pickled``: the figure as :func:`pickle_figure` returned it
    before the PNG was saved (default: pickled now). A figure that cannot be pickled, or whose
    pickle is over :data:`MAX_FIGURE_BYTES`, keeps only the verdict.

    Returns
    -------
    pathlib.Path
        The sidecar's path.
    """
    import hashlib

    from eotrack.plotting import figure_lint_record

    png = Path(png)
    rec = {"png": png.name, "sha256": hashlib.sha256(png.read_bytes()).hexdigest(), "dpi": dpi,
           **figure_lint_record(fig)}
    pkl = png.with_suffix(".fig.gz")
    pkl.unlink(missing_ok=True)
    try:
        blob = pickle_figure(fig) if pickled is None else pickled
    except Exception as exc:  # a lambda formatter, an open file, …: verdict only
        rec["figure"] = None
        rec["figure_error"] = f"{type(exc).__name__}: {exc}"
    else:
        if len(blob) > MAX_FIGURE_BYTES:  # the repository is no place for it: verdict only
            rec["figure"] = None
            rec["figure_error"] = (f"pickled figure {len(blob) / 1e6:.1f} MB > "
                                   f"{MAX_FIGURE_BYTES / 1e6:.0f} MB")
        else:
            pkl.write_bytes(blob)
            rec["figure"] = pkl.name
    side = png.with_suffix(".lint.json")
    side.write_text(json.dumps(rec, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    return side


def write_report(rep: Reproduction, out_dir: str | os.PathLike[str], *, dpi: int = 110,
                 claims: dict[str, Claim] | None = None) -> Path:
    """Write ``REPORT.md``, ``scorecard.json`` and ``figures/*.png`` into ``out_dir``.

    The stability column comes from ``out_dir/stability.json`` (written by ``python -m
    eotrack.repro --seeds K``) when it exists; the criterion history from ``claims`` (default:
    the paper's claims.toml, when the slug has one).

    Returns
    -------
    pathlib.Path
        The report path.
    """
    out = Path(out_dir)
    fig_dir = out / "figures"
    fig_dir.mkdir(parents=True, exist_ok=True)
    for old in [*fig_dir.glob("*.png"), *fig_dir.glob("*.lint.json"), *fig_dir.glob("*.fig.gz")]:
        old.unlink()
    stability = read_stability(out)
    if claims is None:
        try:
            claims = load_claims(rep.slug)
        except (ValueError, FileNotFoundError):
            claims = {}
    lines = [f"# Reproduction report: {rep.title}", "", f"Paper slug `{rep.slug}`.", "",
             f"**Verdict:** {rep.central_line(stability)}.", "",
             f"**Status:** {rep.status_summary()}", "",
             "Results are the paper's findings; checks verify a formula, an input or our own "
             "construction and are not counted as reproductions.", "",
             "Written by `python -m eotrack.repro` (`make repro`); do not edit by hand.", ""]
    if rep.settings:
        lines += ["## Settings", ""]
        lines += [f"- `{k}` = {v}" for k, v in rep.settings.items()]
        lines.append("")
    lines += ["## Scorecard", ""]
    if stability is not None:
        run = "quick counts — not the committed run's" if stability.quick else "full counts"
        lines += [f"Stability: share of {stability.k} independent root seeds "
                  f"({', '.join(map(str, stability.seeds))}; {run}; run {stability.date}) that "
                  "give the committed status; **fragile** where any seed differs.", ""]
    else:
        lines += ["Stability: not run (`make repro-stability`).", ""]
    lines += [_md_table(_scorecard_table(rep, stability)), ""]
    hist = _history_lines(claims)
    if hist:
        lines += ["## Criterion history", "", *hist, ""]
    if rep.text:
        lines += [rep.text.strip(), ""]
    for name, df in rep.tables.items():
        lines += [f"## {name}", "", _md_table(df), ""]
    if rep.figures:
        lines += ["## Figures", ""]
        for stem, fig in rep.figures.items():
            try:
                blob = pickle_figure(fig)  # before the first draw (see pickle_figure)
            except Exception:
                blob = None  # write_lint_sidecar records why
            fig.savefig(fig_dir / f"{stem}.png", dpi=dpi, bbox_inches="tight")
            write_lint_sidecar(fig, fig_dir / f"{stem}.png", dpi=dpi, pickled=blob)
            alt = describe_figure(fig).replace("[", "(").replace("]", ")")
            lines += [f"![{alt}](figures/{stem}.png)", "", f"*{stem}*", ""]
    report = out / "REPORT.md"
    report.write_text("\n".join(lines))
    rows = []
    for r in rep.claims:
        d = r.to_dict()
        if stability is not None:
            d["stability"] = stability.share(r.claim, r.status)
            d["fragile"] = stability.fragile(r.claim, r.status)
        rows.append(d)
    card = {"slug": rep.slug, "title": rep.title, "summary": rep.status_summary(),
            "central": rep.central_line(stability),
            "stability": None if stability is None else
            {"date": stability.date, "k": stability.k, "seeds": list(stability.seeds),
             "quick": stability.quick},
            "settings": {k: str(v) for k, v in rep.settings.items()}, "claims": rows}
    (out / "scorecard.json").write_text(json.dumps(card, indent=2) + "\n")
    return report
