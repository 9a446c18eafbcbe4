"""Find the experiment module of each paper slug (no central list to edit).

A slug is the name of a package ``eotrack.experiments.<slug>``; listing the slugs imports none
of them, so one experiment that fails to import never stops another from running.
"""

from __future__ import annotations

import importlib
import pkgutil
import re
from pathlib import Path
from types import ModuleType

__all__ = ["available_slugs", "experiment_module"]


_REPRODUCE = re.compile(r"^def reproduce\(", re.MULTILINE)


def available_slugs() -> list[str]:
    """Slugs of the experiment packages in ``eotrack.experiments`` whose ``__init__.py`` defines
    ``reproduce`` (read from the source: none is imported here)."""
    import eotrack.experiments as pkg

    out = []
    for info in pkgutil.iter_modules(pkg.__path__):
        if not info.ispkg or info.name.startswith("_"):
            continue
        init = Path(info.module_finder.path) / info.name / "__init__.py"  # type: ignore[union-attr]
        if init.is_file() and _REPRODUCE.search(init.read_text(encoding="utf-8")):
            out.append(info.name)
    return sorted(out)


def experiment_module(slug: str) -> ModuleType:
    """Import ``eotrack.experiments.<slug>``.

    Raises
    ------
    ValueError
        If no experiment with that slug exists, or it defines no ``reproduce``.
    """
    known = available_slugs()
    if slug not in known:
        raise ValueError(f"unknown paper slug {slug!r}; available: {known}")
    mod = importlib.import_module(f"eotrack.experiments.{slug}")
    if not callable(getattr(mod, "reproduce", None)):
        raise ValueError(f"eotrack.experiments.{slug} defines no reproduce(); it is not a paper "
                         "experiment")
    return mod
