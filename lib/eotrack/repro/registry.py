"""Find the experiment module of each paper slug (no central list to edit)."""

from __future__ import annotations

import importlib
import pkgutil
from types import ModuleType

__all__ = ["available_slugs", "experiment_module"]


def available_slugs() -> list[str]:
    """Slugs of the experiment modules in ``eotrack.experiments`` that define ``reproduce``."""
    import eotrack.experiments as pkg

    slugs = []
    for info in pkgutil.iter_modules(pkg.__path__):
        if info.name.startswith("_"):
            continue
        mod = importlib.import_module(f"eotrack.experiments.{info.name}")
        if callable(getattr(mod, "reproduce", None)):
            slugs.append(getattr(mod, "SLUG", info.name))
    return sorted(slugs)


def experiment_module(slug: str) -> ModuleType:
    """Import ``eotrack.experiments.<slug>``.

    Raises
    ------
    ValueError
        If no experiment with that slug exists.
    """
    known = available_slugs()
    if slug not in known:
        raise ValueError(f"unknown paper slug {slug!r}; available: {known}")
    return importlib.import_module(f"eotrack.experiments.{slug}")
