"""Keep the README's notebook table in step with the computed scorecards.

``make repro`` calls :func:`update_readme` after writing the reports, so the status column of
the README is always the one computed by the last full run, never typed in.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

__all__ = ["central_summary", "notebook_table", "update_readme"]

START, END = "<!-- notebooks-table -->", "<!-- /notebooks-table -->"


def _notebook_for(slug: str, notebooks: Path) -> tuple[str, str] | None:
    """(stem, title) of the notebook whose twin imports ``eotrack.experiments.<slug>``."""
    pat = re.compile(rf"experiments(\.|\s+import\s+){slug}\b")
    for py in sorted((notebooks / "py").glob("*.py")):
        text = py.read_text()
        if pat.search(text):
            m = re.search(r"^# # (.+)$", text, re.MULTILINE)
            title = m.group(1).split("·", 1)[-1].strip() if m else py.stem
            return py.stem, title
    return None


def central_summary(cards: list[dict]) -> str:
    """One computed sentence: how many papers have their central claim(s) reproduced.

    A paper counts as reproduced only if every central claim is ``reproduced``.
    """
    from collections import Counter

    n = len(cards)
    verdicts = []
    for c in cards:
        st = [str(r["status"]) for r in c.get("claims", []) if r.get("central")]
        if not st:
            verdicts.append("no central claim marked")
        elif all(x == "reproduced" for x in st):
            verdicts.append("reproduced")
        else:
            # the paper's verdict is its weakest central claim
            order = ["contradicted", "not reproduced", "not reproducible", "partial"]
            verdicts.append(next(o for o in order if o in st))
    cnt = Counter(verdicts)
    rest = ", ".join(f"{k} {v}" for v, k in sorted(cnt.items()) if v != "reproduced")
    return (f"**Central claims, computed from the scorecards:** {cnt.get('reproduced', 0)} of {n} "
            f"papers have their central claim(s) reproduced" + (f"; {rest}" if rest else "")
            + " (a paper counts as its weakest central claim).")


def notebook_table(root: Path) -> str:
    """Markdown: the computed central-claim sentence, then one row per notebook with its paper,
    the verdict on its central claim(s) and its scorecard summary."""
    rows = []
    cards = []
    for card in sorted((root / "papers_repro").glob("*/scorecard.json")):
        data = json.loads(card.read_text())
        cards.append(data)
        slug = data["slug"]
        nb = _notebook_for(slug, root / "notebooks")
        if nb is None:
            continue
        stem, title = nb
        central = data.get("central") or "no central claim marked"
        rows.append((stem, f"| {stem[:2]} | [{title}](notebooks/{stem}.ipynb) | {data['title']} "
                           f"| {central} "
                           f"| [{slug}](papers_repro/{slug}/REPORT.md): {data['summary']} |"))
    head = ("| # | notebook | paper | verdict on the central claim | scorecard (last "
            "`make repro`) |\n|---|---|---|---|---|")
    return "\n".join([central_summary(cards), "", head, *[r for _, r in sorted(rows)]])


def update_readme(root: Path) -> bool:
    """Rewrite the table between the markers in ``root/README.md``; return whether it changed."""
    readme = root / "README.md"
    if not readme.is_file():
        return False
    text = readme.read_text()
    if START not in text or END not in text:
        return False
    before, rest = text.split(START, 1)
    _, after = rest.split(END, 1)
    new = f"{before}{START}\n{notebook_table(root)}\n{END}{after}"
    if new != text:
        readme.write_text(new)
    return new != text
