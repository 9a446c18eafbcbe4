"""The figure lint (issue 23): house style on, Agg backend, a summary table at the end."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import pytest
from eotrack.plotting import house_style

from .cache import ROOT

SUMMARY = ROOT / "build" / "figure-lint.txt"
ROWS = pytest.StashKey[list]()


@pytest.fixture(autouse=True)
def _house_style():
    with house_style():
        yield
    plt.close("all")


@pytest.fixture
def lint_rows(request) -> list:
    """Rows ``(figure id, owner, problems)`` for the summary table."""
    return request.config.stash.setdefault(ROWS, [])


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    rows = config.stash.get(ROWS, [])
    if not rows:
        return
    lines = [f"{'figure':<58} {'owner':<5} {'problems':>8}  by rule"]
    for fid, owner, problems in sorted(rows):
        rules: dict[str, int] = {}
        for rule, _ in problems:
            rules[rule] = rules.get(rule, 0) + 1
        lines.append(f"{fid[:58]:<58} {owner:<5} {len(problems):>8}  "
                     + ", ".join(f"{r} {n}" for r, n in sorted(rules.items())))
    bad = sum(1 for r in rows if r[2])
    lines.append(f"{len(rows)} figures linted, {bad} with problems")
    SUMMARY.parent.mkdir(parents=True, exist_ok=True)
    SUMMARY.write_text("\n".join(lines) + "\n")
    terminalreporter.write_sep("-", "figure lint")
    terminalreporter.write_line(f"{len(rows)} figures linted, {bad} with problems; the table "
                                f"per figure is in {SUMMARY.relative_to(ROOT)}")
