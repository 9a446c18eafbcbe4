"""Point sources on a pixel grid: Gaussian PSF rendering.

Pixel convention used across the library: the centre of pixel ``(row, col)`` is at
``x = col, y = row``; an image has shape ``(height, width)``.
"""

from __future__ import annotations

import numpy as np

from eotrack.validation import as_finite_array, as_points, check_int, check_positive

__all__ = ["render_gaussian_spots"]


def render_gaussian_spots(shape: tuple[int, int], xy: np.ndarray, flux: np.ndarray | float,
                          sigma_px: float, *, radius_sigma: float = 4.0,
                          integrate: bool = True, out: np.ndarray | None = None) -> np.ndarray:
    """Add Gaussian spots to an image.

    Each spot ``i`` contributes ``flux[i] · g(x − x_i) g(y − y_i)`` with ``g`` the normalised 1-D
    Gaussian of width ``sigma_px``; with ``integrate=True`` ``g`` is integrated over each pixel
    (error functions), so the image sums to ``flux`` for spots far from the edges.

    Parameters
    ----------
    shape
        ``(height, width)`` of the image.
    xy
        Spot centres ``(n, 2)`` in pixels (x = column, y = row); spots off the image are clipped.
    flux
        Total flux per spot (scalar or ``(n,)``, ≥ 0).
    sigma_px
        Gaussian standard deviation in pixels (> 0).
    radius_sigma
        Half-size of the rendered stamp in units of ``sigma_px``.
    integrate
        Integrate over pixel areas instead of sampling at pixel centres.
    out
        Image to add into (float, ``shape``); a new zero image if ``None``.

    Returns
    -------
    numpy.ndarray
        The image (``out`` if given).
    """
    if not (isinstance(shape, tuple | list) and len(shape) == 2):
        raise ValueError(f"shape must be (height, width), got {shape!r}")
    h = check_int(shape[0], "shape[0]", min_value=1)
    w = check_int(shape[1], "shape[1]", min_value=1)
    pts = as_points(xy, "xy")
    fl = np.broadcast_to(as_finite_array(flux, "flux", ndim=(0, 1)), (len(pts),)).astype(float)
    if np.any(fl < 0):
        raise ValueError("flux must be >= 0")
    sig = check_positive(sigma_px, "sigma_px")
    check_positive(radius_sigma, "radius_sigma")
    if out is None:
        img = np.zeros((h, w))
    else:
        if not isinstance(out, np.ndarray) or out.shape != (h, w) or \
                not np.issubdtype(out.dtype, np.floating):
            raise ValueError(f"out must be a float array of shape {(h, w)}")
        img = out
    if len(pts) == 0:
        return img
    half = max(1, int(np.ceil(radius_sigma * sig)))
    k = np.arange(-half, half + 1)
    x0 = np.rint(pts[:, 0]).astype(int)
    y0 = np.rint(pts[:, 1]).astype(int)
    cols = x0[:, None] + k  # (n, s)
    rows = y0[:, None] + k
    if integrate:
        from scipy.special import erf

        c = np.sqrt(2.0) * sig
        gx = 0.5 * (erf((cols + 0.5 - pts[:, :1]) / c) - erf((cols - 0.5 - pts[:, :1]) / c))
        gy = 0.5 * (erf((rows + 0.5 - pts[:, 1:]) / c) - erf((rows - 0.5 - pts[:, 1:]) / c))
    else:
        norm = 1.0 / (np.sqrt(2 * np.pi) * sig)
        gx = norm * np.exp(-0.5 * ((cols - pts[:, :1]) / sig) ** 2)
        gy = norm * np.exp(-0.5 * ((rows - pts[:, 1:]) / sig) ** 2)
    stamps = fl[:, None, None] * gy[:, :, None] * gx[:, None, :]  # (n, s, s)
    rr = np.broadcast_to(rows[:, :, None], stamps.shape)
    cc = np.broadcast_to(cols[:, None, :], stamps.shape)
    ok = (rr >= 0) & (rr < h) & (cc >= 0) & (cc < w)
    np.add.at(img, (rr[ok], cc[ok]), stamps[ok])
    return img
