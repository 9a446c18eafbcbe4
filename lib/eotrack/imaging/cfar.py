"""Constant-false-alarm-rate (CFAR) segmentation of a single image.

The background and the noise level are estimated robustly on a mesh of tiles (median and
scaled MAD per tile, as SExtractor / ``sep`` do, interpolated back to full resolution), and the
threshold is set so that a pixel of Gaussian noise exceeds it with probability ``p_f``::

    threshold = background + Q⁻¹(p_f) · sigma

A few bright pixels (targets, stars) barely move a median, so the estimate is not pulled up by
what one wants to detect.

Operating range (held-out tests in ``tests/unit/test_cfar.py``): on images of any size (tiles
need not divide it) with background clutter no stronger than the noise and smoother than two
tiles, the measured false-alarm rate is within 15 % of ``p_f`` for ``p_f`` in [0.01, 0.1].
Clutter finer than a tile or several times the noise leaks through the mesh: the rate rises
(≈ 1.2× at 3× noise with 8-px clutter and ``p_f`` = 0.03; ≈ 2× at 6× noise and
``p_f`` = 0.003). Per-tile estimates also err together over a tile, so false pixels cluster
more than independent ones (see :mod:`eotrack.tracking.hypothesis`).
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np
from scipy.stats import norm

from eotrack.validation import as_finite_array, check_int, check_probability

__all__ = ["CfarResult", "cfar_segment", "cfar_threshold", "tile_background_noise"]

_MAD_TO_SIGMA = 1.482602218505602  # 1 / Φ⁻¹(3/4)


def _image(image: np.ndarray, name: str = "image") -> np.ndarray:
    arr = as_finite_array(image, name, ndim=2)
    if arr.shape[0] < 1 or arr.shape[1] < 1:
        raise ValueError(f"{name} must be a non-empty 2-D image, got shape {arr.shape}")
    return arr


def _tile_stat(img: np.ndarray, t: int, stat) -> np.ndarray:
    """``stat`` (a reducer over the last axis) of every ``t × t`` block (remainders merged)."""
    h, w = img.shape
    ny, nx = max(1, h // t), max(1, w // t)
    if h % ny == 0 and w % nx == 0:
        blocks = img.reshape(ny, h // ny, nx, w // nx).transpose(0, 2, 1, 3).reshape(ny, nx, -1)
        return stat(blocks)
    ey = np.linspace(0, h, ny + 1).astype(int)
    ex = np.linspace(0, w, nx + 1).astype(int)
    out = np.empty((ny, nx))
    for i in range(ny):
        for j in range(nx):
            out[i, j] = stat(img[ey[i]:ey[i + 1], ex[j]:ex[j + 1]].reshape(1, 1, -1))[0, 0]
    return out


def _mesh_to_image(mesh: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    """Bilinear interpolation of block values (nodes at the block centres) to every pixel.

    Beyond the outermost block centres (the half-tile border) the mesh is extrapolated linearly
    rather than held constant, so a background gradient is followed up to the image edge.
    """
    if mesh.shape == (1, 1):
        return np.full(shape, mesh[0, 0])
    h, w = shape
    ny, nx = mesh.shape
    m = mesh.astype(np.float64)
    # one node of linear extrapolation on each side (a single row/column is held constant)
    if ny > 1:
        m = np.vstack([2 * m[:1] - m[1:2], m, 2 * m[-1:] - m[-2:-1]])
    else:
        m = np.vstack([m, m, m])
    if nx > 1:
        m = np.hstack([2 * m[:, :1] - m[:, 1:2], m, 2 * m[:, -1:] - m[:, -2:-1]])
    else:
        m = np.hstack([m, m, m])
    # pixel centre -> padded mesh index (block j has its centre at (j + 0.5) w / nx - 0.5)
    mx = ((np.arange(w) + 0.5) * nx / w - 0.5 + 1).astype(np.float32)
    my = ((np.arange(h) + 0.5) * ny / h - 0.5 + 1).astype(np.float32)
    map_x = np.broadcast_to(mx[None, :], (h, w)).copy()
    map_y = np.broadcast_to(my[:, None], (h, w)).copy()
    return cv2.remap(m, map_x, map_y, interpolation=cv2.INTER_LINEAR,
                     borderMode=cv2.BORDER_REPLICATE)


def _median(b: np.ndarray) -> np.ndarray:
    return np.median(b, axis=-1)


def _mad_sigma(b: np.ndarray) -> np.ndarray:
    return _MAD_TO_SIGMA * np.median(np.abs(b - np.median(b, axis=-1, keepdims=True)), axis=-1)


def tile_background_noise(image: np.ndarray,
                          tile: int | None = 16) -> tuple[np.ndarray, np.ndarray]:
    """Robust local background and noise maps (two passes over a mesh of tiles).

    Pass 1: the median of every ``tile × tile`` block, interpolated bilinearly to every pixel, is
    the background. Pass 2: ``1.4826 · MAD`` of the background-subtracted image in every block,
    interpolated the same way, is the noise standard deviation. Estimating the noise on the
    residual keeps a background that varies inside a tile from inflating it.

    Parameters
    ----------
    image
        2-D image.
    tile
        Block side in pixels (≥ 4); ``None`` for one global estimate.

    Returns
    -------
    background, sigma : numpy.ndarray
        Full-size maps, ``sigma > 0``.
    """
    img = _image(image)
    t = max(img.shape) if tile is None else check_int(tile, "tile", min_value=4)
    bg = _mesh_to_image(_tile_stat(img, t, _median), img.shape)
    sig = _tile_stat(img - bg, t, _mad_sigma)
    pos = sig[sig > 0]
    floor = (float(np.median(pos)) * 1e-3) if pos.size else 1e-12
    sig = np.maximum(sig, max(floor, 1e-12))
    return bg, _mesh_to_image(sig, img.shape)


def cfar_threshold(image: np.ndarray, p_f: float, *, tile: int | None = 16) -> np.ndarray:
    """Per-pixel CFAR threshold ``background + Q⁻¹(p_f) · sigma``.

    Parameters
    ----------
    image
        2-D image.
    p_f
        Per-pixel false-alarm probability in (0, 1).
    tile
        Tile size of the background mesh (see :func:`tile_background_noise`).

    Returns
    -------
    numpy.ndarray
        Threshold map, same shape as ``image``.
    """
    pf = check_probability(p_f, "p_f", open_low=True, open_high=True)
    bg, sd = tile_background_noise(image, tile)
    return bg + norm.isf(pf) * sd


@dataclass(frozen=True)
class CfarResult:
    """A segmented image with the maps that produced it."""

    binary: np.ndarray
    threshold: np.ndarray
    background: np.ndarray
    sigma: np.ndarray


def cfar_segment(image: np.ndarray, p_f: float, *, tile: int | None = 16,
                 full: bool = False) -> np.ndarray | CfarResult:
    """Binary image ``G`` of pixels above the CFAR threshold.

    Parameters
    ----------
    image
        2-D image.
    p_f
        Per-pixel false-alarm probability in (0, 1) (the paper uses 0.03).
    tile
        Tile size of the background mesh; ``None`` for a global estimate.
    full
        Also return the threshold, background and noise maps (a :class:`CfarResult`).

    Returns
    -------
    numpy.ndarray or CfarResult
        ``uint8`` image with 1 where ``image > threshold``.
    """
    img = _image(image)
    pf = check_probability(p_f, "p_f", open_low=True, open_high=True)
    bg, sd = tile_background_noise(img, tile)
    thr = bg + norm.isf(pf) * sd
    binary = (img > thr).astype(np.uint8)
    if full:
        return CfarResult(binary=binary, threshold=thr, background=bg, sigma=sd)
    return binary
