"""Browser tests: print the panels' change-to-settled table at the end of the run."""

from __future__ import annotations

import math
import os
from pathlib import Path

import pytest

LATENCY_FILE = Path(os.environ.get("EOTRACK_BROWSER_LATENCY", "/tmp/eotrack-browser-latency.txt"))
TARGET_S = 0.5  # TEACHING.md: a change redraws within 0.5 s on the 2-core machine
LATENCY_KEY = pytest.StashKey[list]()
RUNS_KEY = pytest.StashKey[list]()


@pytest.fixture(scope="session")
def latency_rows(request) -> list[dict]:
    """Rows ``{notebook, panel, control, settled_s}`` the browser tests append to."""
    return request.config.stash.setdefault(LATENCY_KEY, [])


@pytest.fixture(scope="session")
def run_rows(request) -> list[dict]:
    """Rows ``{notebook, run_s}``: time to run all cells in the browser."""
    return request.config.stash.setdefault(RUNS_KEY, [])


def latency_table(rows: list[dict]) -> str:
    """The rows as a fixed-width table, slowest first within each notebook."""
    lines = [f"{'notebook':<34} {'panel':>5}  {'settled (s)':>11}  {'≤0.5 s':<6}  control moved"]
    for r in rows:
        s = r["settled_s"]
        ok = "?" if math.isnan(s) else ("yes" if s <= TARGET_S else "NO")
        shown = "timeout" if math.isnan(s) else f"{s:.2f}"
        lines.append(f"{r['notebook'].removesuffix('.ipynb')[:34]:<34} {r['panel']:>5}  {shown:>11}  {ok:<6}  "
                     f"{r['control']}")
    return "\n".join(lines)


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    rows = config.stash.get(LATENCY_KEY, [])
    if not rows:
        return
    table = latency_table(rows)
    runs = config.stash.get(RUNS_KEY, [])
    if runs:
        table += "\n\nrun all cells in the browser:\n" + "\n".join(
            f"{r['notebook'].removesuffix('.ipynb')[:34]:<34} {r['run_s']:>7.0f} s" for r in runs)
    note = ("change-to-settled latency per panel (image replaced and kernel idle; a benchmark, "
            "not an assertion; measured under whatever load this machine had)")
    LATENCY_FILE.write_text(note + "\n" + table + "\n")
    terminalreporter.write_sep("-", "browser: panel latency")
    terminalreporter.write_line(note)
    terminalreporter.write_line(table)
    terminalreporter.write_line(f"(also in {LATENCY_FILE})")
