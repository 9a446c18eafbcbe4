"""Trailed stars: a matched-filter pair (point + trail) and a trail-aware centroid.

A camera that stares at the geostationary belt (fixed to the Earth) sees the stars drift west
at the sidereal rate, ≈ 15″/s × cos δ: over a 2-s exposure a star draws a trail of 30″ —
2 px at 15″/px (a point extractor copes), 6 px at 5″/px (it does not: the trail is flagged
elongated and rejected, or split by the deblender, and a window of the PSF's size centroids
one end of it). The targets, nearly still in that frame, stay points.

:func:`extract_trailed` detects both kinds with two matched filters — the PSF (points) and
the PSF convolved with the known trail segment (stars) — thresholds the larger of the two
significances and keeps one peak per trail footprint. Each detection is then centroided twice
by an iterated template-weighted first moment (the fixed point of ``c = Σ T(p − c) I(p) p /
Σ T(p − c) I(p)`` is the centre of any source symmetric like the template ``T``): with the
trail template it converges to the trail's **midpoint** — the star's position at
mid-exposure, the time a plate solution is referred to —, with the point template to a
point's centre. The model with the smaller χ² (amplitude fitted) decides whether the
detection is a trail (a star) or a point (a target candidate).

The trail profile (unit flux) of a segment of length ``L`` along unit vector ``u`` convolved
with a Gaussian of σ, at offset ``d`` from the midpoint (``a = d·u``, ``b = d·n``):
``T(d) = exp(−b²/2σ²) / (√(2π) σ) · [Φ((a + L/2)/σ) − Φ((a − L/2)/σ)] / L``.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import cv2
import numpy as np
from scipy.special import ndtr

from eotrack.validation import as_finite_array, check_int, check_positive

from .background import BackgroundConfig, background_map

__all__ = ["TrailExtraction", "extract_trailed", "trail_profile"]

#: trails shorter than this (px) are points: the two templates would not differ
_MIN_TRAIL_PX = 0.5


class TrailExtraction(NamedTuple):
    """Detections of :func:`extract_trailed`, brightest first.

    Attributes
    ----------
    xy
        ``(n, 2)`` px: trail midpoints (mid-exposure) for trails, centres for points.
    flux
        Fitted total flux (image units) of the chosen model.
    snr
        Peak significance of the chosen matched filter (filtered signal over its noise).
    is_trail
        ``True`` where the trail model fits better than the point model.
    """

    xy: np.ndarray
    flux: np.ndarray
    snr: np.ndarray
    is_trail: np.ndarray


def trail_profile(dx: Any, dy: Any, trail_px: Any, psf_sigma: float) -> np.ndarray:
    """Unit-flux profile of a Gaussian PSF drawn along a straight trail, at offsets from its
    midpoint.

    Parameters
    ----------
    dx, dy
        Offsets from the trail's midpoint (px), broadcastable arrays.
    trail_px
        The trail's displacement ``(dx, dy)`` over the exposure (px); its sign does not matter.
        Shorter than 0.5 px: the Gaussian PSF itself.
    psf_sigma
        Gaussian PSF σ (px).

    Returns
    -------
    numpy.ndarray
        Profile values (per px², integrates to 1), of the broadcast shape.
    """
    s = check_positive(psf_sigma, "psf_sigma")
    t = as_finite_array(trail_px, "trail_px", shape=(2,))
    dx, dy = np.asarray(dx, float), np.asarray(dy, float)
    length = float(np.hypot(*t))
    if length < _MIN_TRAIL_PX:
        return np.exp(-(dx * dx + dy * dy) / (2 * s * s)) / (2 * np.pi * s * s)
    ux, uy = t / length
    a = dx * ux + dy * uy
    b = -dx * uy + dy * ux
    along = (ndtr((a + length / 2) / s) - ndtr((a - length / 2) / s)) / length
    return np.exp(-b * b / (2 * s * s)) / (np.sqrt(2 * np.pi) * s) * along


def _kernel(trail: np.ndarray, sigma: float, half: int) -> np.ndarray:
    g = np.arange(-half, half + 1, dtype=float)
    k = trail_profile(g[None, :], g[:, None], trail, sigma)
    return (k / k.sum()).astype(np.float32)


def _refine(sub: np.ndarray, w2: np.ndarray, peaks: np.ndarray, trail: np.ndarray,
            sigma: float, half: int, iterations: int) -> tuple[np.ndarray, np.ndarray,
                                                             np.ndarray]:
    """Template-weighted centroids (``(n, 2)``), fitted fluxes and noise-weighted χ² of one
    template at every peak (vectorised over the peaks)."""
    pad = cv2.copyMakeBorder(sub, half, half, half, half, cv2.BORDER_CONSTANT, value=0.0)
    wpad = cv2.copyMakeBorder(w2, half, half, half, half, cv2.BORDER_CONSTANT, value=0.0)
    off = np.arange(-half, half + 1)
    rows = peaks[:, 1, None, None] + half + off[None, :, None]
    cols = peaks[:, 0, None, None] + half + off[None, None, :]
    S = pad[rows, cols].astype(float)             # (n, 2h+1, 2h+1)
    Wt = wpad[rows, cols].astype(float)           # inverse variance (0 off the image)
    gx = off[None, None, :].astype(float)
    gy = off[None, :, None].astype(float)
    c = np.zeros((len(peaks), 2))
    for _ in range(iterations):
        T = trail_profile(gx - c[:, 0, None, None], gy - c[:, 1, None, None], trail, sigma)
        m0 = (T * S).sum(axis=(1, 2))
        ok = m0 > 0
        new = np.stack([(T * S * gx).sum(axis=(1, 2)), (T * S * gy).sum(axis=(1, 2))], 1)
        new = np.where(ok[:, None], new / np.where(ok, m0, 1.0)[:, None], c)
        c = np.clip(new, -half / 2, half / 2)
    T = trail_profile(gx - c[:, 0, None, None], gy - c[:, 1, None, None], trail, sigma)
    amp = (Wt * T * S).sum(axis=(1, 2)) / np.maximum((Wt * T * T).sum(axis=(1, 2)), 1e-300)
    chi2 = (Wt * (S - amp[:, None, None] * T) ** 2).sum(axis=(1, 2))
    return peaks + c, amp, chi2


def extract_trailed(image: Any, trail_px: Any, *, psf_sigma: float = 1.0, thresh: float = 4.5,
                    background: BackgroundConfig | None = None, min_area: int = 3,
                    iterations: int = 6, max_sources: int | None = None) -> TrailExtraction:
    """Detect and centroid trailed stars and point sources of one frame.

    Parameters
    ----------
    image
        2-D frame (counts).
    trail_px
        A star's displacement ``(dx, dy)`` over the exposure (px) — for a staring mount the
        sidereal drift times the exposure (:func:`eotrack.pipeline.star_trail_px`). Trails
        shorter than 0.5 px make both filters the PSF (every detection is a point).
    psf_sigma
        Gaussian PSF σ (px).
    thresh
        Detection threshold: the larger matched-filter significance (filtered signal over its
        noise, from the mesh background's noise map) must exceed it.
    background
        Mesh background settings (default :class:`BackgroundConfig`).
    min_area
        Pixels above the threshold needed in the peak's 5×5 neighbourhood (hot pixels).
    iterations
        Iterations of the template-weighted centroid.
    max_sources
        Keep only the brightest ones (None = all).

    Returns
    -------
    TrailExtraction

    Raises
    ------
    TypeError, ValueError
        Bad image or settings (each message names the argument).

    Notes
    -----
    One peak is kept per trail footprint (local maxima of the significance over the trail
    template's support), so two sources closer than a trail length along the trail's
    direction merge into one. The centroids use the background-subtracted pixels of a
    ``(2h+1)²`` stamp, ``h = ⌈L/2 + 3σ⌉``, weighted by the noise map; a neighbour inside the
    stamp pulls them.
    """
    s = check_positive(psf_sigma, "psf_sigma")
    check_positive(thresh, "thresh")
    t = as_finite_array(trail_px, "trail_px", shape=(2,))
    check_int(min_area, "min_area", min_value=1, max_value=25)
    it = check_int(iterations, "iterations", min_value=1, max_value=50)
    if max_sources is not None:
        check_int(max_sources, "max_sources", min_value=1)
    if background is not None and not isinstance(background, BackgroundConfig):
        raise TypeError(f"background must be a BackgroundConfig, got "
                        f"{type(background).__name__}")
    length = float(np.hypot(*t))
    img_shape = np.shape(image)
    if len(img_shape) == 2 and length > max(img_shape) / 2:
        raise ValueError(f"trail_px {tuple(t)} ({length:.1f} px) is longer than half the "
                         f"frame {img_shape}: not a star trail of this frame")
    bg = background_map(image, background)      # validates the image
    img = np.ascontiguousarray(image, dtype=np.float32)
    sub = img - bg.back
    rms = np.maximum(bg.rms, np.float32(1e-12))
    hp = int(np.ceil(3 * s))
    ht = int(np.ceil(length / 2 + 3 * s))
    kp = _kernel(np.zeros(2), s, hp)
    kt = _kernel(t, s, ht)
    sig_p = cv2.filter2D(sub, -1, kp, borderType=cv2.BORDER_REFLECT) / (
        rms * np.float32(np.sqrt((kp.astype(float) ** 2).sum())))
    sig_t = cv2.filter2D(sub, -1, kt, borderType=cv2.BORDER_REFLECT) / (
        rms * np.float32(np.sqrt((kt.astype(float) ** 2).sum())))
    sig = np.maximum(sig_p, sig_t)
    mask = sig > np.float32(thresh)
    if min_area > 1:
        cnt = cv2.boxFilter(mask.view(np.uint8), cv2.CV_16U, (5, 5), normalize=False,
                            borderType=cv2.BORDER_CONSTANT)
        mask &= cnt >= min_area
    foot = (kt >= 0.05 * kt.max()).astype(np.uint8)
    foot[ht, ht] = 1
    local_max = sig >= cv2.dilate(sig, foot, borderType=cv2.BORDER_REFLECT)
    yy, xx = np.nonzero(mask & local_max)
    empty = np.zeros(0)
    if len(xx) == 0:
        return TrailExtraction(np.zeros((0, 2)), empty, empty, np.zeros(0, bool))
    peaks = np.column_stack([xx, yy])
    w2 = (1.0 / (rms.astype(float) ** 2)).astype(np.float32)
    half = ht
    xy_t, f_t, chi_t = _refine(sub, w2, peaks, t, s, half, it)
    xy_p, f_p, chi_p = _refine(sub, w2, peaks, np.zeros(2), s, half, it)
    is_trail = (chi_t < chi_p) if length >= _MIN_TRAIL_PX else np.zeros(len(peaks), bool)
    xy = np.where(is_trail[:, None], xy_t, xy_p)
    flux = np.where(is_trail, f_t, f_p)
    snr = np.where(is_trail, sig_t[yy, xx], sig_p[yy, xx]).astype(float)
    order = np.argsort(-flux, kind="stable")
    if max_sources is not None:
        order = order[:max_sources]
    return TrailExtraction(xy[order], flux[order], snr[order], is_trail[order])
