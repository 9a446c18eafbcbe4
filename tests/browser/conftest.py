"""Browser tests: print the panels' change-to-settled table at the end of the run."""

from __future__ import annotations

import math
import os
import statistics
from pathlib import Path

import pytest

LATENCY_FILE = Path(os.environ.get("EOTRACK_BROWSER_LATENCY", "/tmp/eotrack-browser-latency.txt"))
TARGET_S = 0.5  # TEACHING.md: a change redraws within 0.5 s on the 2-core machine
LATENCY_KEY = pytest.StashKey[list]()
RUNS_KEY = pytest.StashKey[list]()


@pytest.fixture(scope="session")
def latency_rows(request) -> list[dict]:
    """Rows ``{notebook, panel, control, settled_s}`` (``settled_s``: a list, one per move)."""
    return request.config.stash.setdefault(LATENCY_KEY, [])


@pytest.fixture(scope="session")
def run_rows(request) -> list[dict]:
    """Rows ``{notebook, run_s}``: time to run all cells in the browser."""
    return request.config.stash.setdefault(RUNS_KEY, [])


def _seconds(v: float) -> str:
    return "timeout" if math.isnan(v) else f"{v:.2f}"


def latency_table(rows: list[dict]) -> str:
    """The rows as a fixed-width table: median and slowest of each panel's moves."""
    lines = [f"{'notebook':<34} {'panel':>5}  {'moves':>5}  {'median (s)':>10}  {'max (s)':>7}  "
             f"{'≤0.5 s':<6}  control moved; every move (s)"]
    for r in rows:
        times = r["settled_s"]
        times = list(times) if isinstance(times, list | tuple) else [times]
        ok_times = [t for t in times if not math.isnan(t)]
        if len(ok_times) < len(times) or not ok_times:
            med = mx = float("nan")
            ok = "?"
        else:
            med, mx = statistics.median(ok_times), max(ok_times)
            ok = "yes" if mx <= TARGET_S else ("median" if med <= TARGET_S else "NO")
        lines.append(f"{r['notebook'].removesuffix('.ipynb')[:34]:<34} {r['panel']:>5}  "
                     f"{len(times):>5}  {_seconds(med):>10}  {_seconds(mx):>7}  {ok:<6}  "
                     f"{r['control']}; {' '.join(_seconds(t) for t in times)}")
    lines.append("(≤0.5 s: yes = every move; median = the median move only; NO = neither)")
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
