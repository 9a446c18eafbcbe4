"""Display settings for the notebooks: meaningful digits only, wide tables, the house style."""

from __future__ import annotations

import importlib.metadata as md
import numbers

import numpy as np
import pandas as pd

from eotrack import plotting

__all__ = ["DISPLAY_SIGNIFICANT", "format_sig", "setup_notebook", "versions"]

#: Significant digits shown for floats in tables and printed arrays. Monte Carlo tables are
#: checked with ``assert`` and tolerances, never by nbval's text comparison.
DISPLAY_SIGNIFICANT = 4

_PACKAGES = ("numpy", "scipy", "pandas", "matplotlib", "opencv-python-headless", "astropy",
             "eotrack")


def format_sig(x: float, digits: int = DISPLAY_SIGNIFICANT) -> str:
    """Format ``x`` with ``digits`` significant digits (``'{:.4g}'``-style, no trailing noise).

    Parameters
    ----------
    x : float
        The number.
    digits : int
        Significant digits, at least 1.

    Raises
    ------
    ValueError
        If ``digits`` is not a positive integer.
    TypeError
        If ``x`` is not a real number.
    """
    if isinstance(x, bool) or not isinstance(x, numbers.Real):
        raise TypeError(f"x must be a real number, got {x!r}")
    if isinstance(digits, bool) or not isinstance(digits, int | np.integer) or digits < 1:
        raise ValueError(f"digits must be a positive integer, got {digits!r}")
    return f"{x:.{int(digits)}g}"


def versions(packages: tuple[str, ...] = _PACKAGES) -> dict[str, str]:
    """Installed versions of ``packages`` (``'not installed'`` where missing).

    Raises
    ------
    TypeError
        If ``packages`` is a string or holds anything but distribution names (strings).
    """
    if isinstance(packages, str) or not all(isinstance(p, str) and p for p in packages):
        raise TypeError(f"packages must be a sequence of distribution names, got {packages!r}")
    out = {}
    for p in packages:
        try:
            out[p] = md.version(p)
        except md.PackageNotFoundError:
            out[p] = "not installed"
    return out


def setup_notebook(*, digits: int = DISPLAY_SIGNIFICANT) -> None:
    """Apply the collection's display settings; call once in each notebook's Setup.

    - matplotlib: the house style (:func:`eotrack.plotting.style`);
    - pandas: floats with ``digits`` significant digits, columns wide enough for the
      scorecards' notes, no column or row elision for tables of the size we show;
    - numpy: ``digits`` significant digits when printing arrays.

    Parameters
    ----------
    digits : int
        Significant digits for displayed floats.
    """
    fmt = format_sig(1.0, digits) and (lambda v: format_sig(v, digits))
    plotting.style()
    pd.set_option("display.float_format", fmt)
    pd.set_option("display.max_colwidth", 400)
    pd.set_option("display.width", 250)
    pd.set_option("display.max_columns", 40)
    pd.set_option("display.max_rows", 200)
    np.set_printoptions(precision=digits - 1, floatmode="maxprec", suppress=False)
