"""Peaks, deblending of touching stars and accurate (windowed) centroids — all vectorised.

* :func:`find_peaks` — local maxima of a detection image inside above-threshold regions; a flat
  top (a saturated core) counts once, at the centre of its plateau.
* :func:`deblend_peaks` — keeps a peak only if it stands out from the *saddle* that joins it to
  the nearest higher peak of the same region by at least ``nsigma`` local noise and a fraction
  ``contrast`` of that higher peak (the idea of SExtractor's multi-threshold deblending, with
  the saddle sampled along the segment between the two peaks).
* :func:`windowed_centroids` — iterative Gaussian-windowed centroids (SExtractor's ``XWIN``):
  ``x ← x + 2 Σ w I (x_i − x) / Σ w I`` with ``w = exp(−r²/2σ_w²)``; for a Gaussian star with
  ``σ_w = σ_PSF`` the fixed point is the star's centre, and pixels nearer to a neighbouring
  peak than to the star are left out, so touching stars do not pull each other.

No Python loop runs over sources: stamps are gathered with fancy indexing into an
``(n, S, S)`` array and the neighbours come from one k-d tree query.
"""

from __future__ import annotations

from typing import Any

import cv2
import numpy as np
from scipy.spatial import cKDTree

from eotrack.validation import check_int, check_positive

__all__ = ["aperture_flux", "deblend_peaks", "estimate_psf_sigma", "find_peaks", "windowed_centroids"]


def _img(a: Any, name: str) -> np.ndarray:
    arr = np.asarray(a)
    if arr.ndim != 2 or not np.issubdtype(arr.dtype, np.number):
        raise ValueError(f"{name} must be a 2-D numeric array, got shape {arr.shape}")
    return np.ascontiguousarray(arr, dtype=np.float32)


def _xy(a: Any, name: str) -> np.ndarray:
    arr = np.asarray(a, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{name} must have shape (n, 2), got {arr.shape}")
    return arr


def find_peaks(det: Any, mask: Any) -> np.ndarray:
    """Local maxima (3×3) of ``det`` inside ``mask``.

    Every pixel of a flat top (a saturated core) is returned; :func:`deblend_peaks` keeps one
    of them (ties are broken by position, and the others have zero prominence).

    Parameters
    ----------
    det
        Detection image (e.g. the filtered, background-subtracted image).
    mask
        Boolean mask of the pixels allowed to hold a peak (same shape).

    Returns
    -------
    numpy.ndarray
        Integer peak positions ``(n, 2)`` as (x = column, y = row), in raster order.
    """
    d = _img(det, "det")
    msk = np.asarray(mask, dtype=bool)
    if msk.shape != d.shape:
        raise ValueError(f"mask must have the image's shape {d.shape}, got {msk.shape}")
    is_max = (d >= cv2.dilate(d, np.ones((3, 3), np.uint8))) & msk
    yy, xx = np.nonzero(is_max)
    return np.stack([xx, yy], axis=1).astype(np.int64)


def deblend_peaks(det: Any, peaks: Any, noise: Any, *, nsigma: float = 3.0,
                  contrast: float = 0.005, k: int = 8, samples: int = 12) -> np.ndarray:
    """Which peaks are separate stars (a boolean per peak).

    For each peak the nearest higher peak (among its ``k`` nearest peaks; equal values are
    ordered by position, so one pixel of a plateau wins) is found; the saddle is the minimum of
    ``det`` along the segment joining them. The peak is kept if
    ``det[peak] − saddle ≥ max(nsigma · noise[peak], contrast · det[higher])``, or if it has
    no higher neighbour. Two stars whose regions do not touch are separated by a saddle below
    the detection threshold, so they pass this test without any region labelling.

    Parameters
    ----------
    det
        Detection image.
    peaks
        Integer peak positions ``(n, 2)`` (x, y), e.g. from :func:`find_peaks`.
    noise
        Noise of ``det`` per pixel (array of its shape) or a scalar.
    nsigma, contrast
        Prominence needed, in noise units and as a fraction of the higher peak.
    k
        Neighbours examined per peak.
    samples
        Points sampled along each peak-to-peak segment.
    """
    d = _img(det, "det")
    p = np.asarray(peaks, dtype=np.int64).reshape(-1, 2)
    check_positive(nsigma, "nsigma", allow_zero=True)
    check_positive(contrast, "contrast", allow_zero=True)
    check_int(k, "k", min_value=1)
    check_int(samples, "samples", min_value=2)
    n = len(p)
    if n and (p.min() < 0 or p[:, 0].max() >= d.shape[1] or p[:, 1].max() >= d.shape[0]):
        raise ValueError("peaks must lie inside the image")
    if n <= 1:
        return np.ones(n, dtype=bool)
    px, py = p[:, 0], p[:, 1]
    val = d[py, px]
    nz_arr = np.asarray(noise, dtype=np.float32)
    nz = nz_arr[py, px] if nz_arr.ndim == 2 else np.full(n, float(nz_arr))
    rank = np.empty(n, np.int64)                    # strict order: value, then position
    rank[np.lexsort((-np.arange(n), val))] = np.arange(n)
    kk = min(k + 1, n)
    dist, idx = cKDTree(p).query(p, k=kk)
    idx, dist = idx[:, 1:], dist[:, 1:]
    ok = (rank[idx] > rank[:, None]) & np.isfinite(dist)
    has = ok.any(axis=1)
    first = np.argmax(ok, axis=1)
    j = idx[np.arange(n), first]
    keep = np.ones(n, dtype=bool)
    sel = np.flatnonzero(has)
    if sel.size:
        t = np.linspace(0.0, 1.0, samples)[1:-1]
        a, b = p[sel].astype(np.float32), p[j[sel]].astype(np.float32)
        pts = a[:, None, :] + t[None, :, None].astype(np.float32) * (b - a)[:, None, :]
        sx = np.rint(pts[..., 0]).astype(np.int64)
        sy = np.rint(pts[..., 1]).astype(np.int64)
        saddle = d[sy, sx].min(axis=1)
        prom = val[sel] - saddle
        need = np.maximum(nsigma * nz[sel], contrast * val[j[sel]])
        keep[sel] = (prom >= need) & (prom > 0)
    return keep


def _stamps(img: np.ndarray, p: np.ndarray, h: int) -> tuple[np.ndarray, ...]:
    """Stamps ``(n, S, S)`` around the rounded positions (zero outside the image) and their
    pixel coordinates."""
    H, W = img.shape
    ix = np.clip(np.rint(p[:, 0]).astype(np.int64), 0, W - 1)
    iy = np.clip(np.rint(p[:, 1]).astype(np.int64), 0, H - 1)
    off = np.arange(-h, h + 1)
    rows = iy[:, None] + off[None, :]
    cols = ix[:, None] + off[None, :]
    st = img[np.clip(rows, 0, H - 1)[:, :, None], np.clip(cols, 0, W - 1)[:, None, :]]
    if ix.min() < h or iy.min() < h or ix.max() >= W - h or iy.max() >= H - h:
        inside = ((rows >= 0) & (rows < H))[:, :, None] & ((cols >= 0) & (cols < W))[:, None, :]
        st = np.where(inside, st, np.float32(0))
    return st, cols.astype(np.float32), rows.astype(np.float32)


def windowed_centroids(image: Any, xy0: Any, sigma: float, *, iterations: int = 4,
                       neighbours: Any = None, aperture: float | None = None
                       ) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
    """Gaussian-windowed centroids (SExtractor ``XWIN``) of stars near ``xy0``.

    ``x ← x + 2 Σ w I (x_i − x) / Σ w I`` with ``w = exp(−r²/2σ²)`` over a stamp of half-size
    ``⌈3σ⌉`` around the start position; negative pixels count as zero and pixels nearer to a
    neighbouring star than to this one get no weight.

    Parameters
    ----------
    image
        Background-subtracted image.
    xy0
        Starting positions ``(n, 2)`` (x, y), e.g. the peaks.
    sigma
        Window σ (pixels); the star's PSF σ gives an unbiased centre for Gaussian stars.
    iterations
        Fixed-point iterations.
    neighbours
        Positions ``(m, 2)`` of all detected stars (default ``xy0``).
    aperture
        If given, also return the flux in a circle of this radius (≤ ``3σ``) around each
        centroid (same stamps, neighbours' pixels excluded).

    Returns
    -------
    numpy.ndarray or (numpy.ndarray, numpy.ndarray)
        Centroids ``(n, 2)`` (the start position where the window holds no positive light or
        the iteration runs away), and the aperture fluxes if requested.
    """
    img = _img(image, "image")
    p0 = _xy(xy0, "xy0")
    sw = check_positive(sigma, "sigma")
    check_int(iterations, "iterations", min_value=0)
    if aperture is not None:
        check_positive(aperture, "aperture")
    n = len(p0)
    if n == 0:
        return (p0.copy(), np.zeros(0)) if aperture is not None else p0.copy()
    h = int(np.ceil(max(3.0 * sw, 0.0 if aperture is None else aperture)))
    raw, gx, gy = _stamps(img, p0, h)
    st = np.maximum(raw, np.float32(0))
    nb = p0 if neighbours is None else _xy(neighbours, "neighbours")
    x = p0[:, 0].astype(np.float32)
    y = p0[:, 1].astype(np.float32)
    if len(nb) > 1:
        kk = min(4, len(nb))
        _, idx = cKDTree(nb).query(p0, k=kk)
        nbp = nb[idx].astype(np.float32)                     # (n, kk, 2)
        same = np.hypot(*(nbp - p0[:, None, :]).transpose(2, 0, 1)) < 0.5
        nbp[same] = np.inf
        d_own = (gx[:, None, :] - x[:, None, None]) ** 2 + (gy[:, :, None] - y[:, None, None]) ** 2
        d_nb = np.full(st.shape, np.inf, np.float32)
        for q in range(kk):                                  # kk <= 4 neighbours, not sources
            dq = (gx[:, None, :] - nbp[:, q, 0, None, None]) ** 2 + \
                (gy[:, :, None] - nbp[:, q, 1, None, None]) ** 2
            np.minimum(d_nb, dq, out=d_nb)
        st = np.where(d_own <= d_nb, st, np.float32(0))
    inv = np.float32(1.0 / (2 * sw * sw))
    for _ in range(iterations):
        dx = gx - x[:, None]
        dy = gy - y[:, None]
        wx = np.exp(-dx * dx * inv)
        wy = np.exp(-dy * dy * inv)
        row = np.matmul(st, wx[:, :, None])[:, :, 0]        # Σ_j I_ij wx_j   (n, S)
        col = np.matmul(wy[:, None, :], st)[:, 0, :]        # Σ_i wy_i I_ij   (n, S)
        s = np.einsum("ni,ni->n", wy, row)
        sx = np.einsum("nj,nj->n", col * wx, dx)
        sy = np.einsum("ni,ni->n", wy * dy, row)
        good = s > 0
        den = np.where(good, s, 1)
        x = x + np.clip(np.where(good, 2 * sx / den, 0), -1, 1)
        y = y + np.clip(np.where(good, 2 * sy / den, 0), -1, 1)
    x = x.astype(float)
    y = y.astype(float)
    far = (np.abs(x - p0[:, 0]) > h) | (np.abs(y - p0[:, 1]) > h)
    x[far], y[far] = p0[far, 0], p0[far, 1]
    xy = np.stack([x, y], axis=1)
    if aperture is None:
        return xy
    dx = gx - x[:, None].astype(np.float32)
    dy = gy - y[:, None].astype(np.float32)
    inside = dy[:, :, None] ** 2 + dx[:, None, :] ** 2 <= np.float32(aperture * aperture)
    if len(nb) > 1:
        raw = np.where(st > 0, raw, np.minimum(raw, np.float32(0)))   # neighbours' light out
    flux = np.where(inside, raw, np.float32(0)).sum(axis=(1, 2), dtype=np.float64)
    return xy, flux


def estimate_psf_sigma(image: Any, xy: Any, *, window: float = 2.0, default: float = 1.0
                       ) -> float:
    """PSF σ (pixels) from Gaussian-windowed second moments of the given (bright) stars.

    With a Gaussian window σ_w and a Gaussian star σ_p the windowed second moment is
    ``m = σ_p² σ_w² / (σ_p² + σ_w²)``, so ``σ_p² = m σ_w² / (σ_w² − m)``; the median over the
    stars is returned, clipped to 0.4–6 px (``default`` when no star gives a valid moment).
    """
    img = _img(image, "image")
    p = _xy(xy, "xy")
    check_positive(window, "window")
    if len(p) == 0:
        return float(default)
    h = int(np.ceil(3.0 * window))
    H, W = img.shape
    padded = cv2.copyMakeBorder(img, h, h, h, h, cv2.BORDER_CONSTANT, value=0.0)
    ix = np.clip(np.rint(p[:, 0]).astype(np.int64), 0, W - 1)
    iy = np.clip(np.rint(p[:, 1]).astype(np.int64), 0, H - 1)
    off = np.arange(-h, h + 1)
    st = np.maximum(padded[(iy + h)[:, None, None] + off[None, :, None],
                           (ix + h)[:, None, None] + off[None, None, :]], 0).astype(float)
    dx = (ix[:, None] + off[None, :]) - p[:, 0, None]
    dy = (iy[:, None] + off[None, :]) - p[:, 1, None]
    w = np.exp(-dy[:, :, None] ** 2 / (2 * window ** 2)) * \
        np.exp(-dx[:, None, :] ** 2 / (2 * window ** 2))
    wI = st * w
    s = wI.sum(axis=(1, 2))
    m = (np.einsum("nij,nj->n", wI, dx ** 2) + np.einsum("nij,ni->n", wI, dy ** 2)) / \
        (2 * np.where(s > 0, s, 1.0))
    w2 = window ** 2
    ok = (s > 0) & (m > 0) & (m < 0.95 * w2)
    if not ok.any():
        return float(default)
    sig2 = m[ok] * w2 / (w2 - m[ok])
    return float(np.clip(np.sqrt(np.median(sig2)), 0.4, 6.0))


def aperture_flux(image: Any, xy: Any, radius: float) -> np.ndarray:
    """Sum of ``image`` over circular apertures (pixel centres within ``radius`` of ``xy``).

    A robust flux for ranking detections: a fixed aperture around the accurate centroid is not
    shrunk by the detection threshold and does not depend on how a blend was segmented.
    """
    img = _img(image, "image")
    p = _xy(xy, "xy")
    r = check_positive(radius, "radius")
    if len(p) == 0:
        return np.zeros(0)
    h = int(np.ceil(r))
    H, W = img.shape
    padded = cv2.copyMakeBorder(img, h + 1, h + 1, h + 1, h + 1, cv2.BORDER_CONSTANT, value=0.0)
    ix = np.clip(np.rint(p[:, 0]).astype(np.int64), 0, W - 1)
    iy = np.clip(np.rint(p[:, 1]).astype(np.int64), 0, H - 1)
    off = np.arange(-h, h + 1)
    st = padded[(iy + h + 1)[:, None, None] + off[None, :, None],
                (ix + h + 1)[:, None, None] + off[None, None, :]].astype(float)
    dx = (ix[:, None] + off[None, :]) - p[:, 0, None]
    dy = (iy[:, None] + off[None, :]) - p[:, 1, None]
    inside = dy[:, :, None] ** 2 + dx[:, None, :] ** 2 <= r * r
    return np.where(inside, st, 0.0).sum(axis=(1, 2))
