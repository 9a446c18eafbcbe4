"""Notebook 05 with ``QUICK = True``: its .py twin run as a script (the way
``benchmarks/bench_capstone.py`` runs notebook 07), in a subprocess with the Agg backend. The
notebook's own asserts are the checks (a failing one fails the script); the test also checks
that the live small study ran (not the stored one) and how long it took."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TWIN = ROOT / "notebooks" / "py" / "05_akf_star_tracking.py"


def _quick_source() -> str:
    src = TWIN.read_text(encoding="utf-8")
    src, n = re.subn(r"^QUICK = False", "QUICK = True", src, flags=re.M)
    assert n == 1, "the twin must set QUICK = False exactly once (the parameters cell)"
    # display() of IPython outside a kernel prints reprs; keep stdout small
    return src.replace("from IPython.display import Markdown, display",
                       "from IPython.display import Markdown\n\n\ndef display(*a, **k):\n"
                       "    pass")


def test_notebook_05_runs_with_quick(tmp_path):
    f = tmp_path / "nb05_quick.py"
    f.write_text(_quick_source(), encoding="utf-8")
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, str(f)], cwd=tmp_path, capture_output=True, text=True,
                         env={**os.environ, "MPLBACKEND": "Agg"}, timeout=600)
    wall = time.perf_counter() - t0
    assert out.returncode == 0, out.stderr[-3000:]
    assert "live" in out.stdout and "3 sequences × " in out.stdout, out.stdout[:2000]
    print(f"notebook 05 QUICK: {wall:.1f} s wall")
