"""The figure lint's data: each paper's report figures from a quick run, linted once and cached.

``report_lint(slug)`` runs ``reproduce(quick=True)`` under the house style with every public
figure function of the experiment wrapped, so the result also says which function drew which
report figure. What is cached is the lint's verdict per figure (a list of problems), not the
figures themselves.
"""

from __future__ import annotations

import importlib
import re
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from eotrack.plotting import house_style, lint_figure
from eotrack.plotting.lint import _figure_of

from .cache import ROOT, cached

#: Names of the public figure functions of an experiment's ``figures`` module.
FIGURE_NAME = re.compile(r"^(plot_|draw_|figure_)|_explorer$|^explore_figure$")


def figure_functions(slug: str) -> dict[str, Any]:
    """Public figure functions of ``eotrack.experiments.<slug>.figures`` (name → function)."""
    mod = importlib.import_module(f"eotrack.experiments.{slug}.figures")
    names = getattr(mod, "__all__", [n for n in dir(mod) if not n.startswith("_")])
    return {n: getattr(mod, n) for n in names
            if FIGURE_NAME.search(n) and callable(getattr(mod, n))}


def experiment_slugs() -> list[str]:
    """Every experiment package with a ``figures`` module."""
    return sorted(p.parent.name for p in (ROOT / "lib/eotrack/experiments").glob("*/figures.py"))


def report_slugs() -> list[str]:
    """Slugs with committed report figures (papers_repro/<slug>/figures/*.png)."""
    return sorted({p.parent.parent.name for p in (ROOT / "papers_repro").glob("*/figures/*.png")})


def report_figure_stems(slug: str) -> list[str]:
    return sorted(p.stem for p in (ROOT / "papers_repro" / slug / "figures").glob("*.png"))


def _run_report(slug: str) -> dict[str, Any]:
    pkg = importlib.import_module(f"eotrack.experiments.{slug}")
    funcs = figure_functions(slug)
    calls: list[tuple[str, Any]] = []
    patched: list[tuple[Any, str, Any]] = []

    def wrap(name, fn):
        def wrapper(*a, **k):
            out = fn(*a, **k)
            calls.append((name, out))
            return out
        return wrapper

    import sys
    mods = [m for n, m in list(sys.modules.items())
            if m is not None and (n == pkg.__name__ or n.startswith(pkg.__name__ + "."))]
    for m in mods:
        for name, fn in funcs.items():
            if getattr(m, name, None) is fn:
                patched.append((m, name, fn))
                setattr(m, name, wrap(name, fn))
    try:
        with house_style():
            from eotrack.montecarlo import TrialRunner

            rep = pkg.reproduce(quick=True, runner=TrialRunner(progress=False))
            lint = {stem: [(p.rule, p.message) for p in lint_figure(fig)]
                    for stem, fig in rep.figures.items()}
            by_id = {id(_figure_of(f)): stem for stem, f in rep.figures.items()}
            drew: dict[str, set[str]] = {}
            for name, out in calls:
                try:
                    stem = by_id.get(id(_figure_of(out)))
                except TypeError:
                    stem = None
                drew.setdefault(name, set())
                if stem:
                    drew[name].add(stem)
    finally:
        for m, name, fn in patched:
            setattr(m, name, fn)
        plt.close("all")
    return {"lint": lint, "drew": {k: sorted(v) for k, v in drew.items()}}


def report_lint(slug: str) -> dict[str, Any]:
    """``{"lint": {stem: [(rule, message)]}, "drew": {function: [stems]}}`` for ``slug``."""
    return cached(f"report-{slug}", (f"experiments/{slug}",), lambda: _run_report(slug))
