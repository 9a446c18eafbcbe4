"""Imaging: star-field and target rendering, backgrounds, thresholds, detection, centroids.

Submodules are small and named for what they do; this package re-exports their public names.
"""

from __future__ import annotations

from .psf import render_gaussian_spots

__all__ = ["render_gaussian_spots"]
