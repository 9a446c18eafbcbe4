"""eotrack — executable reproductions of papers on electro-optical space-target tracking.

The library is organised by concern (``robust``, ``geometry``, ``astro``, ``imaging``,
``tracking``, ``pose``, ``montecarlo``, ``repro``, ``plotting``); ``experiments`` holds one thin
module per paper composed from those parts.
"""

from __future__ import annotations

__version__ = "0.1.0"
__all__ = ["__version__"]
