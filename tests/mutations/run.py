"""Run the hand mutations of ``tests/mutations/mutations.toml`` and print the mutation score.

Each mutation is applied to a scratch copy of ``lib/`` (the working tree is never touched), and
its tests run there with that copy first on ``PYTHONPATH``. A mutation is *killed* when a test
fails; one that survives is a gap in the unit tests. The unmutated copy is run first: its tests
must pass, or the score would mean nothing. Exit status 1 if a mutation survives or is stale.

Usage: ``python tests/mutations/run.py [NAME-SUBSTRING ...]`` (``make mutation``).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _pytest(scratch: Path, tests: list[str]) -> int:
    env = dict(os.environ, PYTHONPATH=str(scratch / "lib"),
               EOTRACK_PAPERS_REPRO=str(ROOT / "papers_repro"), MPLBACKEND="Agg")
    cmd = [sys.executable, "-m", "pytest", "-q", "-x", "-p", "no:cacheprovider",
           "-p", "no:randomly", *tests]
    return subprocess.run(cmd, cwd=scratch, env=env, capture_output=True).returncode


def main(argv: list[str]) -> int:
    spec = tomllib.loads((ROOT / "tests" / "mutations" / "mutations.toml").read_text())
    muts = [m for m in spec["mutation"] if not argv or any(a in m["name"] for a in argv)]
    if not muts:
        print(f"no mutation matches {argv}")
        return 2
    with tempfile.TemporaryDirectory(prefix="eotrack-mut-") as tmp:
        scratch = Path(tmp)
        shutil.copytree(ROOT / "lib", scratch / "lib",
                        ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
        shutil.copytree(ROOT / "tests", scratch / "tests",
                        ignore=shutil.ignore_patterns("__pycache__", "browser", "mutations"))
        shutil.copy(ROOT / "pyproject.toml", scratch / "pyproject.toml")
        if (ROOT / "data").is_dir():
            os.symlink(ROOT / "data", scratch / "data")
        all_tests = sorted({t for m in muts for t in m["tests"]})
        rc = _pytest(scratch, all_tests)
        if rc != 0:
            print(f"the unmutated tests fail (exit {rc}): fix them before scoring mutations")
            return 1
        killed, survived, stale = [], [], []
        for m in muts:
            path = scratch / m["file"]
            original = (ROOT / m["file"]).read_text()
            if original.count(m["old"]) != 1:
                stale.append(m["name"])
                print(f"  STALE     {m['name']}: `old` occurs {original.count(m['old'])}× in "
                      f"{m['file']}")
                continue
            path.write_text(original.replace(m["old"], m["new"]))
            t0 = time.perf_counter()
            rc = _pytest(scratch, m["tests"])
            path.write_text(original)
            dt = time.perf_counter() - t0
            (killed if rc != 0 else survived).append(m["name"])
            print(f"  {'killed' if rc else 'SURVIVED':<9} {m['name']}  [{dt:.1f} s]", flush=True)
    n = len(killed) + len(survived)
    score = len(killed) / n if n else float("nan")
    print(f"mutation score: {len(killed)}/{n} killed ({score:.0%}); {len(stale)} stale")
    for s in survived:
        print(f"  gap: {s}")
    return 0 if not survived and not stale else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
