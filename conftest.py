"""Order of the test files for ``make test``: longest first.

``make test`` runs one pytest session over two pytest-xdist workers with ``--dist loadfile``
(a file's items stay on one worker: nbval runs a notebook's cells in order in one kernel).
Which worker ends last decides the wall time, so the files are handed out longest first
(``--no-loadscope-reorder`` keeps this order instead of xdist's "most items first").

The seconds per file come from ``tests/file_durations.json``, written by a run with
``EOTRACK_WRITE_DURATIONS=1`` (``make durations``): a measurement of this machine, committed, so a
fresh clone orders its first run the same way. A notebook it does not list is estimated from
``notebooks/execution_times.json`` (scaled to an idle machine by the load it was executed at), a
paper test file counts as 20 s, any other file as 1 s. The order changes only the schedule, never
which tests run.
"""

from __future__ import annotations

import json
import os
from collections import defaultdict
from pathlib import Path

import pytest

try:  # property tests: the same examples on every machine and run (a fresh clone's `make test`
    # must not fail on one CPU and pass on another by luck of the draw); HYPOTHESIS_PROFILE=explore
    # draws fresh random examples (run it now and then to look for new failures, pin them with
    # @example).
    from hypothesis import settings as _hyp_settings

    _hyp_settings.register_profile("repeatable", derandomize=True, print_blob=True)
    _hyp_settings.register_profile("explore", derandomize=False, print_blob=True)
    _hyp_settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "repeatable"))
except ImportError:  # pragma: no cover - hypothesis is a test dependency
    pass

ROOT = Path(__file__).resolve().parent
DURATIONS = ROOT / "tests" / "file_durations.json"
_seconds: dict[str, float] = defaultdict(float)


def _file_of(item: pytest.Item) -> str:
    return Path(str(item.fspath)).resolve().relative_to(ROOT).as_posix()


def _measured() -> dict[str, float]:
    try:
        data = json.loads(DURATIONS.read_text())
    except (OSError, ValueError):
        return {}
    return {k: float(v) for k, v in data.get("seconds", {}).items()}


def _notebook_estimates() -> dict[str, float]:
    """Seconds per notebook from ``notebooks/execution_times.json`` (written when a notebook is
    executed), scaled to an idle machine by the load it was measured at."""
    try:
        data = json.loads((ROOT / "notebooks" / "execution_times.json").read_text())
    except (OSError, ValueError):
        return {}
    out = {}
    for stem, rec in data.items():
        cores = float(rec.get("cores", 2) or 2)
        busy = max(1.0, float(rec.get("load", cores) or cores) / cores)
        folder = "notebooks/solutions" if stem.endswith("_solutions") else "notebooks"
        out[f"{folder}/{stem}.ipynb"] = float(rec.get("seconds", 1.0)) / busy
    return out


def _known() -> dict[str, float]:
    """Measured seconds per file where known; notebook estimates; the paper tests next."""
    est = _notebook_estimates()
    est.update(_measured())
    return est


def _estimate(known: dict[str, float], path: str) -> float:
    if path in known:
        return known[path]
    return 20.0 if path.startswith("tests/papers/") else 1.0


def pytest_collection_modifyitems(session: pytest.Session, config: pytest.Config,
                                  items: list[pytest.Item]) -> None:
    known = _known()
    first_seen: dict[str, int] = {}
    for i, item in enumerate(items):
        first_seen.setdefault(_file_of(item), i)
    # stable within a file (cell order matters to nbval); files by measured time, longest first
    items.sort(key=lambda it: (-_estimate(known, _file_of(it)), first_seen[_file_of(it)]))


def pytest_runtest_logreport(report: pytest.TestReport) -> None:
    if os.environ.get("EOTRACK_WRITE_DURATIONS") == "1":
        _seconds[report.nodeid.split("::", 1)[0]] += report.duration


def pytest_sessionfinish(session: pytest.Session, exitstatus: int) -> None:
    if os.environ.get("EOTRACK_WRITE_DURATIONS") != "1" or not _seconds:
        return
    if hasattr(session.config, "workerinput"):  # xdist workers: the controller writes
        return
    old = _measured()
    old.update({k: round(v, 1) for k, v in _seconds.items()})
    DURATIONS.write_text(json.dumps(
        {"about": "seconds per test file on the 2-core reference machine (written by "
                  "`make durations`; used only to hand out the longest files first)",
         "seconds": dict(sorted(old.items(), key=lambda kv: -kv[1]))}, indent=1) + "\n")
