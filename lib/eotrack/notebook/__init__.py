"""Notebook conventions shared by every notebook of the collection.

``setup_notebook()`` applies the display settings once (house plotting style, pandas and numpy
precision); ``eotrack.notebook.controls`` builds tidy widget panels (``panel``) whose controls
have readable labels and readouts at the step's precision. Each submodule lists its public
names in ``__all__``; they are re-exported here.
"""

from __future__ import annotations

from eotrack._reexport import reexport

__all__ = reexport(__name__, __path__, globals())
