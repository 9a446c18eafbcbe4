"""Every lint case: the explicit ones of ``cases_<slug>.py`` and the automatic ones.

A case is a function of no argument returning what the figure function returns (a Figure,
Axes or array of Axes), drawn on real data. ``cases_<slug>.py`` files hold the explicit cases
of one experiment (a dict ``CASES``: figure function name → case; each paper's helper may add
and own the file of their experiment). A public figure function whose parameters all have
defaults (schematics, analytic curves) gets an automatic case: called with no argument.
"""

from __future__ import annotations

import importlib
import inspect
from collections.abc import Callable
from pathlib import Path
from typing import Any

from .runs import experiment_slugs, figure_functions

HERE = Path(__file__).resolve().parent


def explicit_cases(slug: str) -> dict[str, Callable[[], Any]]:
    if not (HERE / f"cases_{slug}.py").is_file():
        return {}
    return dict(importlib.import_module(f"tests.figures.cases_{slug}").CASES)


def _all_defaults(fn: Any) -> bool:
    try:
        sig = inspect.signature(fn)
    except (TypeError, ValueError):
        return False
    return all(p.default is not inspect.Parameter.empty or p.kind in (p.VAR_POSITIONAL,
                                                                     p.VAR_KEYWORD)
               for p in sig.parameters.values())


def all_cases() -> dict[str, tuple[str, str, Callable[[], Any]]]:
    """``"slug.function" → (slug, kind, case)``; kind ``"explicit"`` or ``"auto"``."""
    out: dict[str, tuple[str, str, Callable[[], Any]]] = {}
    for slug in experiment_slugs():
        funcs = figure_functions(slug)
        explicit = explicit_cases(slug)
        for name, fn in funcs.items():
            if name in explicit:
                out[f"{slug}.{name}"] = (slug, "explicit", explicit[name])
            elif _all_defaults(fn):
                out[f"{slug}.{name}"] = (slug, "auto", fn)
    return out
