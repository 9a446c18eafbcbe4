"""Rebuild ``notebooks/X.ipynb`` from ``notebooks/py/X.py`` and execute it in place.

Usage: ``python .ci/execute_notebooks.py [STEM ...]`` (default: all). Execution timestamps and
widget state are stripped so re-runs do not churn the diff.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import jupytext
import nbformat
from nbclient import NotebookClient

top = Path(__file__).resolve().parents[1] / "notebooks"
# notebooks/py/X.py -> notebooks/X.ipynb; notebooks/solutions/py/X.py -> notebooks/solutions/X.ipynb
sources = {p.stem: p for d in (top, top / "solutions") for p in sorted((d / "py").glob("*.py"))}
stems = sys.argv[1:] or sorted(sources)
env_backend = os.environ.pop("MPLBACKEND", None)  # never let Agg reach the kernel
for stem in stems:
    if stem not in sources:
        sys.exit(f"no notebook source named {stem!r}; known: {sorted(sources)}")
    src = sources[stem]
    root = src.parent.parent
    nb = jupytext.read(src)
    nb.metadata["kernelspec"] = {"display_name": "Python 3", "language": "python",
                                 "name": "python3"}
    t0 = time.perf_counter()
    NotebookClient(nb, timeout=900, kernel_name="python3",
                   resources={"metadata": {"path": str(root)}}).execute()
    for cell in nb.cells:
        cell.metadata.pop("execution", None)
    nb.metadata.pop("widgets", None)
    nbformat.write(nb, root / f"{stem}.ipynb")
    print(f"{stem}: executed in {time.perf_counter() - t0:.1f} s")
