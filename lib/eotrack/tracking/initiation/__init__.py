"""Track initiation behind one interface: ``initiator.initiate(frames) -> list[Track]``.

Each initiator lives in its own module and lists its public names in ``__all__``; they are
re-exported here.
"""

from __future__ import annotations

from eotrack._reexport import reexport

__all__ = reexport(__name__, __path__, globals())
