"""Cached small runs for the figure lint: computed once, pickled under build/figure-lint-cache/.

The key of an entry is a hash of the source it depends on (the experiment package and
``eotrack.plotting``), so a changed experiment recomputes its data and an unchanged one is read
back in well under a second. Delete the folder to force a fresh run.
"""

from __future__ import annotations

import functools
import hashlib
import pickle
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
CACHE_DIR = ROOT / "build" / "figure-lint-cache"
LIB = ROOT / "lib" / "eotrack"


@functools.cache
def source_hash(*packages: str) -> str:
    """SHA-256 (16 hex digits) of the ``.py`` files of ``eotrack.<package>`` folders (computed
    once per test session, so edits made while the lint runs do not restart its runs)."""
    h = hashlib.sha256()
    for pkg in (*packages, "plotting"):
        for p in sorted((LIB / pkg.replace(".", "/")).rglob("*.py")):
            h.update(p.relative_to(LIB).as_posix().encode())
            h.update(p.read_bytes())
    return h.hexdigest()[:16]


def cached(name: str, depends: tuple[str, ...], compute: Callable[[], Any]) -> Any:
    """``compute()`` once per source state of ``depends``; later calls read the pickle."""
    CACHE_DIR.mkdir(parents=True, exist_ok=True)
    path = CACHE_DIR / f"{name}-{source_hash(*depends)}.pkl"
    if path.is_file():
        try:
            with path.open("rb") as f:
                return pickle.load(f)
        except Exception:
            path.unlink(missing_ok=True)
    value = compute()
    for old in CACHE_DIR.glob(f"{name}-*.pkl"):
        old.unlink(missing_ok=True)
    tmp = path.with_suffix(".tmp")
    with tmp.open("wb") as f:
        pickle.dump(value, f, protocol=pickle.HIGHEST_PROTOCOL)
    tmp.replace(path)
    return value
