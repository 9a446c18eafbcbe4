"""Track initiation behind one interface: ``initiator.initiate(frames) -> list[Track]``.

Each initiator lives in its own module and lists its public names in ``__all__``; they are
re-exported here.
"""

from __future__ import annotations

import importlib as _importlib
import pkgutil as _pkgutil

from .base import Frame, Initiator, Track, validate_frames

__all__ = ["Frame", "Initiator", "Track", "validate_frames"]

for _info in _pkgutil.iter_modules(__path__):
    if _info.name in {"base"} or _info.name.startswith("_"):
        continue
    _mod = _importlib.import_module(f"{__name__}.{_info.name}")
    for _name in getattr(_mod, "__all__", ()):
        globals()[_name] = getattr(_mod, _name)
        __all__.append(_name)
del _importlib, _pkgutil
