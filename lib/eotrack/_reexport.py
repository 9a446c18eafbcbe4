"""Re-export the public names of a package's submodules (each lists them in ``__all__``).

Packages that several modules contribute to (``imaging``, ``geometry``, ``pose``) use this so a
new module is picked up without editing the package's ``__init__``.
"""

from __future__ import annotations

import importlib
import pkgutil
from typing import Any


def reexport(package: str, path: list[str], namespace: dict[str, Any],
             skip: tuple[str, ...] = ()) -> list[str]:
    """Import every public submodule of ``package`` and copy its ``__all__`` into ``namespace``.

    Returns
    -------
    list of str
        The names exported, for the package's ``__all__``.
    """
    names: list[str] = []
    for info in sorted(pkgutil.iter_modules(path), key=lambda i: i.name):
        if info.name.startswith("_") or info.name in skip:
            continue
        mod = importlib.import_module(f"{package}.{info.name}")
        for name in getattr(mod, "__all__", ()):
            namespace[name] = getattr(mod, name)
            names.append(name)
    return names
