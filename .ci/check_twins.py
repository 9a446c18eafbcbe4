"""Check that every notebook has its jupytext percent twin and that the two agree.

Works on a fresh clone (file times are meaningless there): each ``notebooks/py/X.py`` is
converted in memory and its cells' sources compared with ``notebooks/X.ipynb``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import jupytext

top = Path(__file__).resolve().parents[1] / "notebooks"
problems = []
# notebooks/X.ipynb <-> notebooks/py/X.py and notebooks/solutions/X.ipynb <-> .../solutions/py/X.py
pys = {p.stem: p for d in (top, top / "solutions") for p in (d / "py").glob("*.py")}
nbs = {p.stem: p for d in (top, top / "solutions") for p in d.glob("*.ipynb")}
for stem in sorted(set(pys) | set(nbs)):
    if stem not in pys:
        problems.append(f"notebooks/{stem}.ipynb has no twin notebooks/py/{stem}.py")
        continue
    if stem not in nbs:
        problems.append(f"notebooks/py/{stem}.py has no notebooks/{stem}.ipynb "
                        "(run `make execute`)")
        continue
    src = jupytext.read(pys[stem])
    ipy = jupytext.read(nbs[stem])
    a = [(c.cell_type, c.source.strip()) for c in src.cells]
    b = [(c.cell_type, c.source.strip()) for c in ipy.cells]
    if a != b:
        first = next((i for i, (x, y) in enumerate(zip(a, b, strict=False)) if x != y),
                     min(len(a), len(b)))
        problems.append(f"{stem}: .py and .ipynb differ (first at cell {first}; "
                        f"{len(a)} vs {len(b)} cells) — run `make execute`")
if problems:
    print("notebook twins out of sync:\n  " + "\n  ".join(problems))
    sys.exit(1)
print(f"notebook twins in sync ({len(pys)} notebooks, solutions included)")
