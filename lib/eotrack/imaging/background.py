"""Sky background and noise maps from sigma-clipped meshes (the SExtractor/SEP recipe).

The image is cut into square meshes (boxes) of ``mesh`` pixels. In each mesh the pixel values
are sigma-clipped (``|I − mean| < nsigma · std``, iterated from the median and the
interquartile σ) so that stars, cosmic rays and
saturated cores do not bias the level; the clipped mean and standard deviation of every mesh
form two coarse grids. A median filter over ``filter_size × filter_size`` meshes removes meshes
spoiled by a bright star or a crowded core, and bilinear interpolation between mesh centres
gives full-resolution background and noise maps.

Everything is vectorised: the meshes are one reshaped array (the clipping is a masked mean over
its last axis), the median filter and the interpolation are OpenCV primitives. Statistics are
taken on every ``subsample``-th pixel in each direction (a 64 px mesh still has 1,024 samples).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, NamedTuple

import cv2
import numpy as np

from eotrack.validation import check_int, check_positive

__all__ = ["BackgroundConfig", "BackgroundMap", "background_map"]

#: std of a unit normal truncated to ±3σ (the clipped std underestimates σ by this factor)
_CLIP3_STD = 0.98658


@dataclass(frozen=True)
class BackgroundConfig:
    """Mesh background settings.

    Attributes
    ----------
    mesh
        Mesh (box) size in pixels; about 4–10 star FWHM so a star cannot dominate a mesh.
    filter_size
        Median filter over the mesh grid (1 = none, 3 or 5).
    nsigma
        Clipping threshold in standard deviations.
    iterations
        Clipping iterations.
    subsample
        Use every ``subsample``-th pixel of each mesh for its statistics (1 = all).
    """

    mesh: int = 64
    filter_size: int = 3
    nsigma: float = 3.0
    iterations: int = 3
    subsample: int = 2

    def __post_init__(self) -> None:
        check_int(self.mesh, "mesh", min_value=4)
        if self.filter_size not in (1, 3, 5):
            raise ValueError(f"filter_size must be 1, 3 or 5, got {self.filter_size!r}")
        check_positive(self.nsigma, "nsigma")
        check_int(self.iterations, "iterations", min_value=0, max_value=20)
        check_int(self.subsample, "subsample", min_value=1, max_value=8)


class BackgroundMap(NamedTuple):
    """Full-resolution background ``back`` and noise ``rms`` (float32, image shape) and their
    global (median over meshes) values."""

    back: np.ndarray
    rms: np.ndarray
    global_back: float
    global_rms: float


def _as_image(image: Any) -> np.ndarray:
    if isinstance(image, (str, bytes)) or image is None:
        raise TypeError(f"image must be a 2-D numeric array, got {type(image).__name__}")
    arr = np.asarray(image)
    if not (np.issubdtype(arr.dtype, np.number) or arr.dtype == bool):
        raise TypeError(f"image must be a 2-D numeric array, got dtype {arr.dtype}")
    if arr.ndim != 2:
        raise ValueError(f"image must be 2-D (height, width), got shape {arr.shape}")
    if min(arr.shape) < 3:
        raise ValueError(f"image must be at least 3×3 pixels, got shape {arr.shape}")
    img = np.ascontiguousarray(arr, dtype=np.float32)
    if not np.isfinite(img).all():
        raise ValueError("image contains NaN or infinite values")
    return img


def background_map(image: Any, config: BackgroundConfig | None = None) -> BackgroundMap:
    """Background and noise maps of an image from sigma-clipped meshes.

    Parameters
    ----------
    image
        2-D image (any real dtype; computed in float32).
    config
        :class:`BackgroundConfig` (defaults: 64 px meshes, 3×3 median filter, 3σ clipping).

    Returns
    -------
    BackgroundMap
        ``back`` and ``rms`` of the image's shape, and their global values.

    Raises
    ------
    TypeError, ValueError
        If the image is not a finite 2-D numeric array of at least 3×3 pixels, or the config
        is not a :class:`BackgroundConfig`.
    """
    img = _as_image(image)
    cfg = BackgroundConfig() if config is None else config
    if not isinstance(cfg, BackgroundConfig):
        raise TypeError(f"config must be a BackgroundConfig, got {type(cfg).__name__}")
    H, W = img.shape
    m = min(cfg.mesh, H, W)
    s = cfg.subsample if m % cfg.subsample == 0 and m // cfg.subsample >= 4 else 1
    ny, nx = -(-H // m), -(-W // m)
    pad = img
    if ny * m != H or nx * m != W:
        pad = cv2.copyMakeBorder(img, 0, ny * m - H, 0, nx * m - W, cv2.BORDER_REFLECT_101)
    q = m // s
    x = pad[::s, ::s].reshape(ny, q, nx, q).transpose(0, 2, 1, 3).reshape(ny * nx, q * q)
    # robust start: median and interquartile σ of a quarter of the samples (stars cannot drag
    # the first clip the way they drag a plain mean and std)
    xs = x[:, ::4] if x.shape[1] >= 64 else x
    k = xs.shape[1]
    qs = np.partition(xs, (k // 4, k // 2, (3 * k) // 4), axis=1)
    mean = qs[:, k // 2].astype(np.float64)
    std = np.maximum((qs[:, (3 * k) // 4] - qs[:, k // 4]).astype(np.float64) / 1.349, 1e-12)
    for _ in range(cfg.iterations):
        dev = np.abs(x - mean[:, None].astype(np.float32))
        keep = dev < (cfg.nsigma * np.maximum(std, 1e-12))[:, None].astype(np.float32)
        cnt = np.maximum(keep.sum(axis=1), 1)
        xk = np.where(keep, x, np.float32(0))
        mean = xk.sum(axis=1, dtype=np.float64) / cnt
        var = np.einsum("ij,ij->i", xk, xk, dtype=np.float64) / cnt - mean * mean
        std = np.sqrt(np.maximum(var, 0.0))
    if cfg.iterations and cfg.nsigma == 3.0:
        std = std / _CLIP3_STD
    bgrid = mean.reshape(ny, nx).astype(np.float32)
    rgrid = std.reshape(ny, nx).astype(np.float32)
    if cfg.filter_size > 1 and min(ny, nx) >= cfg.filter_size:
        bgrid = cv2.medianBlur(bgrid, cfg.filter_size)
        rgrid = cv2.medianBlur(rgrid, cfg.filter_size)
    gb, gr = float(np.median(bgrid)), float(np.median(rgrid))
    if gr <= 0:
        gr = float(np.std(img)) or 1.0
    rgrid = np.maximum(rgrid, np.float32(1e-3 * gr))
    if ny == 1 and nx == 1:
        back = np.full((H, W), bgrid[0, 0], np.float32)
        rms = np.full((H, W), rgrid[0, 0], np.float32)
    else:
        back = cv2.resize(bgrid, (nx * m, ny * m), interpolation=cv2.INTER_LINEAR)[:H, :W]
        rms = cv2.resize(rgrid, (nx * m, ny * m), interpolation=cv2.INTER_LINEAR)[:H, :W]
    return BackgroundMap(np.ascontiguousarray(back), np.ascontiguousarray(rms), gb, gr)
