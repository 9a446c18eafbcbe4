"""Keep the README's notebook table in step with the computed scorecards.

``make repro`` calls :func:`update_readme` after writing the reports, so the status column of
the README is always the one computed by the last full run, never typed in.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

__all__ = ["notebook_table", "update_readme"]

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


def notebook_table(root: Path) -> str:
    """Markdown table: one row per notebook with its paper and computed scorecard summary."""
    rows = []
    for card in sorted((root / "papers_repro").glob("*/scorecard.json")):
        data = json.loads(card.read_text())
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
    return "\n".join([head, *[r for _, r in sorted(rows)]])


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
