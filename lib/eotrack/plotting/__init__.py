"""House style and shared figure helpers (every helper takes ``ax=None``)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import numpy as np

__all__ = ["STYLE", "get_ax", "paper_marker", "savefig", "style"]

STYLE: dict[str, Any] = {
    "figure.figsize": (6.4, 4.0),
    "figure.dpi": 100,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "legend.frameon": False,
    "font.size": 10,
    "axes.titlesize": 11,
    "image.cmap": "gray",
}


def style() -> None:
    """Apply the house style to matplotlib's global rc settings."""
    plt.rcParams.update(STYLE)


def get_ax(ax: plt.Axes | None = None, **fig_kw: Any) -> plt.Axes:
    """Return ``ax`` or a new axes in a new figure."""
    if ax is not None:
        return ax
    _, ax = plt.subplots(**fig_kw)
    return ax


def paper_marker(ax: plt.Axes, x: Sequence[float], y: Sequence[float], *,
                 label: str = "paper", **kw: Any) -> Any:
    """Plot the paper's values as hollow black markers on ``ax``."""
    kw = {"marker": "o", "mfc": "none", "mec": "k", "ls": "none", "ms": 7, **kw}
    return ax.plot(np.asarray(x), np.asarray(y), label=label, **kw)


def savefig(fig: plt.Figure, path: str | Path, *, dpi: int = 110) -> Path:
    """Save ``fig`` to ``path`` (parents created) and return the path."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(p, dpi=dpi, bbox_inches="tight")
    return p
