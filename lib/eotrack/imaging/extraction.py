"""Star extraction: a general sky extractor (default), the paper's adaptive-threshold method
(Sheng 2026, §1.3) and its global baseline.

Sky method (``method="sky"``, the default of :func:`extract_stars`) — for any astronomical frame:

1. background and noise maps from sigma-clipped meshes (:func:`eotrack.imaging.background_map`);
2. the background-subtracted image filtered by a 3×3 kernel; detection pixels where the filtered
   image exceeds ``thresh`` times its local noise (``0.375 · rms``, the kernel's noise gain);
3. 3×3 local maxima of the filtered image with at least ``min_area`` detection pixels around;
4. deblending: a maximum is a star of its own if it rises above the saddle to the nearest higher
   maximum of its region by ``deblend_nsigma`` local noise and ``deblend_contrast`` of that peak
   (:func:`eotrack.imaging.deblend_peaks`);
5. Gaussian-windowed centroids (window σ = the PSF σ estimated from the stars themselves) with
   pixels nearer a neighbour masked (:func:`eotrack.imaging.windowed_centroids`);
6. fluxes in a circular aperture of ``aperture_radius`` PSF σ around each centroid; every
   detection is returned, brightest first (an optional ``max_sources`` cap is applied after
   this ranking).

Paper's adaptive method (``method="adaptive"``):

1. grey histogram ``H(g)``, ``p(g) = H(g)/N``, CDF ``C(g)``; quantiles ``g5``, ``g95`` and the
   effective dynamic range ``R = (g95 − g5)/255`` (eqs. 15–18); for data that are not 8-bit
   grey levels the quantiles are taken on the values themselves and divided by the data's range
   (``max − min``) instead of 255 (:func:`dynamic_range`);
2. background ``B = I * G_{σ_b}`` (Gaussian blur, eq. 19) and ``I_f = I − B`` (eq. 20);
3. if ``R`` is below ``r_min`` (strong light, occlusion) the search is restricted to a region
   of interest: pixels with ``I_f ≥ T_f = μ_f + k σ_f`` (eqs. 21–22, with the comparison the
   right way round and σ_f the standard deviation), their connected components Ω_i and
   ``Ω_ROI = ∪ Ω_i`` grown by the local window (eq. 23); otherwise the whole image is searched;
4. in the ROI a local threshold ``T(x, y) = μ_b + k_b σ_b`` from the mean and standard deviation
   over a ``(2r+1)²`` window (box filters, eqs. 24–27); star pixels ``I ≥ T``;
5. connected components ℜ_k (8-connectivity, at least ``min_area`` pixels) and intensity-weighted
   centroids ``z = Σ x w / Σ w`` (eqs. 28–29) with weights ``w = I − B`` (the background-
   subtracted intensity; the paper writes ``I``, which pulls the centroid towards the middle of
   the pixel set whenever the background is not zero). By default each region is grown by
   ``centroid_grow = 2`` pixels before the centroid (the paper's region ℜ_k, ``centroid_grow =
   0``, cuts off the PSF wings and biases the centroid by ~0.1 px). No cap: every region is
   returned unless ``max_stars`` is set.

Global baseline (``method="global"``): one threshold ``T = μ + k σ`` of the whole image, star
pixels ``I ≥ T``, the same components and centroids with weights ``I − T``.

Pixel convention: ``x`` = column, ``y`` = row, pixel centres at integers (as
:func:`eotrack.imaging.render_gaussian_spots`).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, NamedTuple

import cv2
import numpy as np

from eotrack.imaging.background import BackgroundConfig, background_map
from eotrack.imaging.deblend import (
    deblend_peaks,
    estimate_psf_sigma,
    find_peaks,
    windowed_centroids,
)
from eotrack.validation import check_choice, check_int, check_positive

__all__ = [
    "FLAG_ELONGATED",
    "FLAG_SHARP",
    "ExtractionConfig",
    "ExtractionResult",
    "SkyConfig",
    "StarCentroids",
    "dynamic_range",
    "extract_stars",
    "grey_quantiles",
    "image_confidence",
    "psf_sharpness",
    "real_ccd_frames",
    "shape_flags",
]

#: flag bit: sharper than the PSF (cosmic-ray hit, hot pixel)
FLAG_SHARP = 1
#: flag bit: elongated (cosmic-ray track, satellite streak, edge)
FLAG_ELONGATED = 2


@dataclass(frozen=True)
class ExtractionConfig:
    """Parameters of star extraction.

    The paper gives ``k`` and ``k_b`` as 3–5 and no values for the others; ours are stated here.

    Attributes
    ----------
    sigma_b
        σ_b of the Gaussian background filter (pixels).
    k
        Filter-response threshold factor of eq. (21) (and the global threshold's factor).
    r
        Half-width of the local window W, ``(2r+1)²`` pixels (eq. 24).
    k_b
        Local threshold factor of eq. (27).
    r_min
        Dynamic range below which only the ROI is searched (eq. 18's "preset threshold").
    full_scale
        The grey-level range ``R`` is divided by (None: 255 for 8-bit data, otherwise the data's
        ``max − min``).
    robust_roi
        Eq. (21)'s ``μ_f`` and ``σ_f`` as the median and a MAD-based σ of ``I_f`` (default) or,
        as printed, the mean and standard deviation — which bright and crowded stars inflate,
        so that the region of interest drops the fainter stars.
    min_area
        Smallest component kept (pixels).
    max_area
        Largest component kept (pixels; larger blobs are glare or cloud edges).
    max_stars
        Keep at most this many detections, brightest (largest summed weight) first; None (the
        default) keeps every detection.
    centroid_grow
        Grow each region by this many pixels (8-neighbourhood) before the weighted centroid
        (0 = the paper's region ℜ_k; the default 2 includes the PSF wings cut off by the
        threshold and removes most of the pixel-locking bias of a thresholded centroid).
    """

    sigma_b: float = 6.0
    k: float = 4.0
    r: int = 7
    k_b: float = 3.0
    r_min: float = 0.2
    min_area: int = 2
    max_area: int = 400
    max_stars: int | None = None
    centroid_grow: int = 2
    full_scale: float | None = None
    robust_roi: bool = True

    def __post_init__(self) -> None:
        check_positive(self.sigma_b, "sigma_b")
        check_positive(self.k, "k", allow_zero=True)
        check_int(self.r, "r", min_value=1)
        check_positive(self.k_b, "k_b", allow_zero=True)
        check_positive(self.r_min, "r_min", allow_zero=True)
        check_int(self.min_area, "min_area", min_value=1)
        check_int(self.max_area, "max_area", min_value=self.min_area)
        if self.max_stars is not None:
            check_int(self.max_stars, "max_stars", min_value=1)
        check_int(self.centroid_grow, "centroid_grow", min_value=0, max_value=5)
        if self.full_scale is not None:
            check_positive(self.full_scale, "full_scale")


@dataclass(frozen=True)
class SkyConfig:
    """Parameters of the sky extractor (``method="sky"``).

    Attributes
    ----------
    thresh
        Detection threshold: filtered background-subtracted intensity over its local noise.
    min_area
        Detection pixels needed in a peak's 5×5 neighbourhood (rejects single hot pixels).
    background
        Mesh background settings (:class:`eotrack.imaging.BackgroundConfig`).
    deblend_nsigma, deblend_contrast
        Prominence a local maximum needs above the saddle to its higher neighbour, in local
        noise units and as a fraction of the higher peak.
    psf_sigma
        PSF σ in pixels for the centroid window and the aperture; None estimates it from the
        detected stars (:func:`eotrack.imaging.estimate_psf_sigma`).
    aperture_radius
        Aperture radius for the flux, in PSF σ (at least 1.5 px).
    centroid_iterations
        Windowed-centroid iterations.
    max_sources
        Optional cap, applied after ranking by aperture flux (None = every detection).
    reject_artifacts
        Drop detections flagged as cosmic rays / hot pixels (``FLAG_SHARP``) or tracks
        (``FLAG_ELONGATED``) — see :func:`shape_flags`. ``False`` keeps them, with their
        ``flags`` in the :class:`ExtractionResult` (the behaviour before the flags existed,
        apart from the threshold).
    local_background
        Re-test each peak against a local plane background and, on count data, a Poisson
        count test (see Notes). ``False`` restores the mesh-only test.
    sharp_margin
        A detection is ``FLAG_SHARP`` when its sharpness exceeds that of a centred Gaussian of
        the frame's PSF σ by more than ``max(sharp_margin, 3 σ_sharp)``.
    round_max
        A detection is ``FLAG_ELONGATED`` when its windowed ellipticity exceeds
        ``round_max + 3 / SNR_det``.

    Notes
    -----
    The default ``thresh = 4.5`` was set so that pure Gaussian noise gives at most one false
    detection per 10⁶ pixels (measured: none in 3.4·10⁷ noise pixels at 4.5, 0.48 per 10⁶ at
    4.0 and 86 per 10⁶ at the former default 3.0; ``tests/unit/test_extraction.py`` and
    ``benchmarks/bench_extraction.py``). Lower it for faint stars when false detections are
    affordable; completeness at equal false detections does not depend on this choice.

    That rate assumes FLAT Gaussian noise. Two departures broke it with the mesh background
    alone, and ``local_background = True`` (default) repairs them: (i) a background that curves
    on the 64 px mesh scale (a glow of 200 DN, σ = 150 px, on σ = 5 noise: 40-70 false
    detections per 1024² frame near its centre; a 0.3 DN/px ramp: ~10 at the far edge) — each
    peak is re-tested against a plane fitted to a 6-10 px annulus around it; (ii) low-count
    integer (Poisson) frames, whose skewed counts beat a Gaussian threshold (λ = 0.3: ~1,300
    per 10⁶ px) — on integer frames whose background variance is about its level, the 3×3
    counts must also reach the Poisson tail probability of ``thresh`` (divided by 9). Measured
    with the default: 0 on the glow and the ramp, 1 per 10⁶ px at λ = 0.3, 0 at λ = 3.

    (iii) Quantised frames — values on a lattice ``z0 + kΔ`` (integer ADU; integers times a
    gain plus an offset, in any dtype) with read noise σ ≲ Δ: the mesh noise collapsed (most
    samples equal the median; fixed in :func:`eotrack.imaging.background_map`, see its module
    notes) and, even with the right σ, the filtered noise is a sum of nine discrete values whose
    tail is far from Gaussian below σ ≈ 0.5 Δ. On such frames (σ ≤ 3 Δ) the threshold is
    raised, where needed, to the level the exact distribution of the filtered noise exceeds
    with the Gaussian tail probability of ``thresh`` — under the model of Gaussian noise
    rounded by the ADC, whose latent σ and offset match each mesh's sigma-clipped level and
    noise (so stars enter only through the clipped statistics; a first version built from the
    values' own histogram counted star wings as noise and lost most stars at peak SNR 3–6).
    On pure noise the floor is ≈ the Gaussian threshold for σ ≥ 0.5 Δ and 1.3–2.5× it at
    σ = 0.2–0.3 Δ on a step. Measured with the default (issue 28; ``bench_quantised`` and
    ``bench_quantised_scan`` of ``benchmarks/bench_extraction.py``, recorded in
    ``papers_repro/akf_star/bench_extraction.txt``): 1,600–4,200 false detections per 10⁶ px
    before, ≲ 0.03 after, over σ = 0.2–4 Δ, eight sub-step offsets and four
    gain/offset/dtype combinations; on frames with stars see ``bench_quantised_stars``
    there. Skewed noise the Gaussian model misses (low counts on a bias, gain < 1 e⁻/DN, a float
    master bias subtracted) is caught by an empirical guard: the exact tail of each mesh's own
    histogram, from pixels whose neighbours are quiet (review 28 #13: Poisson sky 0.3 e⁻ + bias
    100 gave 7–12 per 10⁶ px, now 0; ``bench_low_count_bias``). Up to ~20 % patched pixels keep
    the lattice (:func:`eotrack.imaging.quantisation_step`). Not covered: continuous-valued
    frames with skewed noise (flat-fielded low-count data), correlated noise — measure the rate
    on a blank frame of your own data.
    """

    thresh: float = 4.5
    min_area: int = 3
    background: BackgroundConfig = field(default_factory=BackgroundConfig)
    deblend_nsigma: float = 3.0
    deblend_contrast: float = 0.005
    psf_sigma: float | None = None
    aperture_radius: float = 2.5
    centroid_iterations: int = 4
    max_sources: int | None = None
    reject_artifacts: bool = True
    local_background: bool = True
    sharp_margin: float = 0.5
    round_max: float = 0.5

    def __post_init__(self) -> None:
        check_positive(self.thresh, "thresh")
        if not isinstance(self.reject_artifacts, (bool, np.bool_)):
            raise TypeError("reject_artifacts must be a bool, got "
                            f"{type(self.reject_artifacts).__name__}")
        if not isinstance(self.local_background, (bool, np.bool_)):
            raise TypeError("local_background must be a bool, got "
                            f"{type(self.local_background).__name__}")
        check_positive(self.sharp_margin, "sharp_margin")
        check_positive(self.round_max, "round_max")
        check_int(self.min_area, "min_area", min_value=1)
        if not isinstance(self.background, BackgroundConfig):
            raise TypeError("background must be a BackgroundConfig, got "
                            f"{type(self.background).__name__}")
        check_positive(self.deblend_nsigma, "deblend_nsigma", allow_zero=True)
        check_positive(self.deblend_contrast, "deblend_contrast", allow_zero=True)
        if self.psf_sigma is not None:
            check_positive(self.psf_sigma, "psf_sigma")
        check_positive(self.aperture_radius, "aperture_radius")
        check_int(self.centroid_iterations, "centroid_iterations", min_value=0, max_value=50)
        if self.max_sources is not None:
            check_int(self.max_sources, "max_sources", min_value=1)


class StarCentroids(NamedTuple):
    """Centroids ``xy`` ``(n, 2)`` (x = column, y = row) and fluxes ``(n,)``, brightest first."""

    xy: np.ndarray
    flux: np.ndarray


@dataclass(frozen=True)
class ExtractionResult:
    """Full output of :func:`extract_stars` with ``return_info=True``.

    Attributes
    ----------
    xy, flux
        Centroids and fluxes (sum of the centroid weights), brightest first.
    area
        Pixels per detection.
    peak
        Peak weight (background-subtracted intensity) per detection.
    snr
        ``peak / noise``, the noise being a robust (MAD) standard deviation of ``I − B``.
    dynamic_range
        ``R`` of eq. (18).
    roi_fraction
        Fraction of the image searched (1 when the whole image is searched).
    noise
        The robust noise estimate used for ``snr``.
    sharpness, roundness, flags
        Sky method only (``None`` for the paper's methods): DAOFIND-like sharpness (centre
        pixel minus the mean of its 8 neighbours, over the 3×3-filtered peak: ≈ 4 for a
        single hot pixel, ≈ 0.8 for a Gaussian star of σ = 1 px), windowed ellipticity
        (0 round, → 1 a line) and the bit flags ``FLAG_SHARP`` (1) and ``FLAG_ELONGATED`` (2)
        (see :func:`shape_flags`; 0 = point-like).
    psf_sigma
        PSF σ used for the centroids (sky method; ``nan`` otherwise).
    """

    xy: np.ndarray
    flux: np.ndarray
    area: np.ndarray
    peak: np.ndarray
    snr: np.ndarray
    dynamic_range: float
    roi_fraction: float
    noise: float
    sharpness: np.ndarray | None = None
    roundness: np.ndarray | None = None
    flags: np.ndarray | None = None
    psf_sigma: float = float("nan")

    def __len__(self) -> int:
        return len(self.flux)


def _check_image(image: Any) -> np.ndarray:
    if isinstance(image, (str, bytes)) or image is None:
        raise TypeError(f"image must be a 2-D numeric array, got {type(image).__name__}")
    arr = np.asarray(image)
    if not (np.issubdtype(arr.dtype, np.number) or arr.dtype == bool):
        raise TypeError(f"image must be a 2-D numeric array, got dtype {arr.dtype}")
    if arr.ndim != 2:
        raise ValueError(f"image must be 2-D (height, width), got shape {arr.shape}")
    if arr.size == 0:
        raise ValueError(f"image is empty (shape {arr.shape})")
    if min(arr.shape) < 3:
        raise ValueError(f"image must be at least 3×3 pixels, got shape {arr.shape}")
    img = arr.astype(np.float32)
    if not np.all(np.isfinite(img)):
        raise ValueError("image contains NaN or infinite values")
    if float(img.max()) == float(img.min()):
        raise ValueError("image is constant: there is nothing to extract")
    return img


def grey_quantiles(image: Any, q: tuple[float, float] = (0.05, 0.95)) -> tuple[int, int]:
    """Eqs. (15)–(17): ``g_q = min{g : C(g) ≥ q}`` of the 256-bin grey histogram.

    Images are treated as 8-bit grey levels: values are rounded and clipped to 0…255.
    """
    img = _check_image(image)
    g = np.clip(np.rint(img), 0, 255).astype(np.uint8)
    hist = cv2.calcHist([g], [0], None, [256], [0, 256]).ravel()
    cdf = np.cumsum(hist) / g.size
    lo, hi = q
    if not 0 <= lo <= hi <= 1:
        raise ValueError(f"q must be two probabilities lo <= hi, got {q}")
    return int(np.searchsorted(cdf, lo - 1e-12)), int(np.searchsorted(cdf, hi - 1e-12))


def dynamic_range(image: Any, full_scale: float | None = None) -> float:
    """Eq. (18): ``R = (g95 − g5) / 255``, scaled to the data's range.

    For 8-bit grey levels (all values in 0…255) this is the paper's formula. Other data (16-bit,
    float, with an offset) are not clipped to 0…255: the 5 % and 95 % quantiles of the values
    are divided by ``full_scale`` (default: the data's ``max − min``), so ``R`` keeps its
    meaning of "fraction of the range the bulk of the pixels spans".
    """
    if full_scale is not None:
        check_positive(full_scale, "full_scale")
    return _dynamic_range(_check_image(image), full_scale)


def _dynamic_range(img: np.ndarray, full_scale: float | None = None) -> float:
    lo, hi = float(img.min()), float(img.max())
    if lo >= 0 and hi <= 255:
        g = np.rint(img).astype(np.uint8)
        hist = cv2.calcHist([g], [0], None, [256], [0, 256]).ravel()
        cdf = np.cumsum(hist) / g.size
        g5 = int(np.searchsorted(cdf, 0.05 - 1e-12))
        g95 = int(np.searchsorted(cdf, 0.95 - 1e-12))
        return (g95 - g5) / (255.0 if full_scale is None else full_scale)
    step = max(1, int(np.sqrt(img.size / 65536)))
    q5, q95 = np.quantile(img[::step, ::step], [0.05, 0.95])
    scale = (hi - lo) if full_scale is None else full_scale
    return float((q95 - q5) / scale)


def _components(mask: np.ndarray, weights: np.ndarray, cfg: ExtractionConfig
                ) -> tuple[np.ndarray, ...]:
    n, labels = cv2.connectedComponents(mask.view(np.uint8), connectivity=8)
    if n <= 1:
        e = np.zeros(0)
        return np.zeros((0, 2)), e, e, e
    area = np.bincount(labels[mask], minlength=n)[1:].astype(float)
    if cfg.centroid_grow:
        size = 2 * cfg.centroid_grow + 1
        grown = cv2.dilate(labels.astype(np.float32), np.ones((size, size), np.uint8))
        # only background pixels join a region (touching regions keep their own pixels)
        labels = np.where(labels > 0, labels, grown.astype(labels.dtype))
        mask = labels > 0
    yy, xx = np.nonzero(mask)
    lab = labels[yy, xx]
    w = np.maximum(weights[yy, xx], 0).astype(float)
    sw = np.bincount(lab, w, minlength=n)[1:]
    sx = np.bincount(lab, w * xx, minlength=n)[1:]
    sy = np.bincount(lab, w * yy, minlength=n)[1:]
    order = np.argsort(w, kind="stable")
    peak = np.zeros(n)
    peak[lab[order]] = w[order]          # the last (largest) weight of each label wins
    peak = peak[1:]
    ok = (area >= cfg.min_area) & (area <= cfg.max_area) & (sw > 0)
    xy = np.stack([sx[ok] / sw[ok], sy[ok] / sw[ok]], axis=1)
    return xy, sw[ok], area[ok], peak[ok]


def _robust_std(a: np.ndarray) -> float:
    step = max(1, int(np.sqrt(a.size / 1024)))
    sub = a[::step, ::step].ravel()
    med = np.median(sub)
    return float(1.4826 * np.median(np.abs(sub - med))) or float(np.std(a)) or 1.0


#: 3×3 detection kernel (SExtractor's default) and its white-noise gain sqrt(Σ k²)
_KERNEL = np.array([[1, 2, 1], [2, 4, 2], [1, 2, 1]], np.float32) / 16.0
_KERNEL_GAIN = float(np.sqrt((_KERNEL ** 2).sum()))
_KERNEL_1D = np.array([0.25, 0.5, 0.25], np.float32)


#: annulus of the local background test (pixels from the peak)
_ANNULUS = (6.0, 10.0)
_ANN_DY, _ANN_DX = (a.ravel() for a in np.mgrid[-10:11, -10:11])
_ANN_R = np.hypot(_ANN_DX, _ANN_DY)
_ANN_DY, _ANN_DX = (a[(_ANN_R >= _ANNULUS[0]) & (_ANN_R <= _ANNULUS[1])]
                    for a in (_ANN_DY, _ANN_DX))
#: the 3×3 box of the Poisson count test
_BOX_DY, _BOX_DX = (a.ravel() for a in np.mgrid[-1:2, -1:2])


def _locally_significant(img: np.ndarray, sub: np.ndarray, det: np.ndarray, peaks: np.ndarray,
                         bg: Any, noise: np.ndarray, thresh: float) -> np.ndarray:
    """Which peaks stay significant against a LOCAL background: a plane fitted (one 3σ clip)
    to ``sub`` in an annulus of 6–10 px around each peak. This removes the residue of the
    64 px mesh on a curved background (a glow, stray light) and at the frame edges (a ramp).
    On integer-valued low-count frames (Poisson: the background's variance ≈ its level) the
    3×3 counts must also be Poisson-significant at the Gaussian tail probability of
    ``thresh`` (a Gaussian threshold is far too lenient for a skewed count distribution)."""
    from scipy.stats import norm, poisson

    H, W = sub.shape
    py, px = peaks[:, 1, None] + _ANN_DY, peaks[:, 0, None] + _ANN_DX        # (n, k)
    inside = (py >= 0) & (py < H) & (px >= 0) & (px < W)
    v = sub[np.clip(py, 0, H - 1), np.clip(px, 0, W - 1)].astype(np.float64)
    rms = bg.rms[peaks[:, 1], peaks[:, 0]].astype(np.float64)[:, None]
    counts = _is_count_data(img, bg)
    if counts:          # a collapsed mesh σ (most pixels equal) must not clip everything
        rms = np.maximum(rms, np.sqrt(max(bg.global_back, 0.0)) + 0.5)
    dx, dy = _ANN_DX.astype(np.float64), _ANN_DY.astype(np.float64)
    w = inside.astype(np.float64)
    half = v.shape[1] // 2                # outside pixels read as the nearest edge pixel
    med = np.partition(v, half, axis=1)[:, half]                               # a median
    w *= np.abs(v - med[:, None]) < 3 * rms                                    # stars out
    coef = np.zeros((len(v), 3))
    for _ in range(2):                    # weighted least-squares plane, then one 3σ clip
        s0, sx, sy = w.sum(axis=1), w @ dx, w @ dy
        M = np.stack([np.stack([s0, sx, sy], -1), np.stack([sx, w @ (dx * dx), w @ (dx * dy)], -1),
                      np.stack([sy, w @ (dx * dy), w @ (dy * dy)], -1)], -2) + 1e-9 * np.eye(3)
        wv = w * v
        b = np.stack([wv.sum(axis=1), wv @ dx, wv @ dy], -1)
        coef = np.linalg.solve(M, b[..., None])[..., 0]
        res = v - coef[:, :1] - coef[:, 1:2] * dx - coef[:, 2:3] * dy
        w = inside * (np.abs(res) < 3 * rms)
    level = coef[:, 0]                                                         # plane at peak
    ok = det[peaks[:, 1], peaks[:, 0]] - level > thresh * noise[peaks[:, 1], peaks[:, 0]]
    if counts:
        by = np.clip(peaks[:, 1, None] + _BOX_DY, 0, H - 1)
        bx = np.clip(peaks[:, 0, None] + _BOX_DX, 0, W - 1)
        N = img[by, bx].sum(axis=1)
        # local mean count: the raw annulus, stars (beyond 5 Poisson σ of its median) out
        raw = img[np.clip(py, 0, H - 1), np.clip(px, 0, W - 1)].astype(np.float64)
        rmed = np.median(raw, axis=1)[:, None]
        keep = inside & (raw <= rmed + 5 * np.sqrt(rmed + 1))
        mu = 9 * np.maximum((raw * keep).sum(axis=1) / np.maximum(keep.sum(axis=1), 1), 0.05)
        # the peak is the maximum of its 3×3 neighbourhood: tail probability / 9
        ok &= poisson.sf(np.round(N) - 1, mu) < norm.sf(thresh) / 9
    return ok


#: integer weights of the 3×3 detection kernel (16 · _KERNEL): centre, 4 edges, 4 corners
_KERNEL_INT = ((4, 1), (2, 4), (1, 4))
#: σ/Δ above which a quantised frame's filtered noise is treated as Gaussian
_QUANTISED_MAX_RATIO = 3.0


def _rounded_gaussian_table() -> tuple[np.ndarray, ...]:
    """Mean and std (in steps) of ``round(f + σ z)`` on a grid of latent σ and offsets f."""
    global _RG_TABLE
    if _RG_TABLE is None:
        from scipy.special import ndtr

        sig = np.geomspace(0.04, 3.5, 120)
        f = np.linspace(0.0, 0.5, 26)              # the table is symmetric in ±f
        k = np.arange(-20, 21)
        S, Fo = np.meshgrid(sig, f, indexing="ij")
        P = (ndtr((k + 0.5 - Fo[..., None]) / S[..., None])
             - ndtr((k - 0.5 - Fo[..., None]) / S[..., None]))
        mean = (P * k).sum(-1)
        sd = np.sqrt(np.maximum((P * k * k).sum(-1) - mean ** 2, 0.0))
        _RG_TABLE = (S.ravel(), Fo.ravel(), mean.ravel(), sd.ravel())
    return _RG_TABLE


_RG_TABLE: tuple[np.ndarray, ...] | None = None


def _tail_steps(pmf: np.ndarray, K: int, thresh: float) -> np.ndarray:
    """Per row of ``pmf`` (the distribution of one pixel in steps ``-K..K``): the smallest ``s``
    with ``P(S > s) <= Φ̄(thresh)``, ``S = Σ w_j d_j`` the 3×3 kernel sum in 1/16 steps of nine
    independent pixels (characteristic function ``φ(ω)⁴ φ(2ω)⁴ φ(4ω)``)."""
    from scipy.stats import norm

    nm = len(pmf)
    span = 16 * K
    N = 1 << int(np.ceil(np.log2(2 * span + 1)))
    P = np.zeros((nm, N))
    P[:, np.arange(-K, K + 1) % N] = pmf
    phi = np.fft.fft(P, axis=1)
    kk = np.arange(N)
    phis = np.ones((nm, N), complex)
    for w, count in _KERNEL_INT:
        phis *= phi[:, (w * kk) % N] ** count
    ps = np.maximum(np.fft.ifft(phis, axis=1).real, 0.0)[:, np.arange(-span, span + 1) % N]
    tail = np.cumsum(ps[:, ::-1], axis=1)[:, ::-1]            # tail[:, j] = P(S >= s_j)
    above = np.concatenate([tail[:, 1:], np.zeros((nm, 1))], axis=1)   # P(S > s_j)
    ok = above <= norm.sf(thresh)
    return np.argmax(ok, axis=1) - span                       # the first s with P(S > s) <= p


#: the empirical tail guard of a quantised frame: pixels whose 8 neighbours sum above the
#: noise by this many σ of that sum are left out of the histogram (stars), as are those within
#: ``_EMP_MASK_GROW`` px of a pixel whose filtered value exceeds ``_EMP_MASK_FACTOR`` times the
#: Gaussian threshold (bright stars' far wings; far above any noise, so the mask does not
#: select the noise's own tail); a mesh needs ``_EMP_MIN_PIXELS`` kept pixels
_EMP_RING_NSIGMA = 2.5
_EMP_MASK_GROW = 3
_EMP_MASK_FACTOR = 2.0
_EMP_MIN_PIXELS = 512
#: the histogram's range: ``_EMP_KMAX_NSIGMA`` clipped σ + 3 steps, at most ``_EMP_KMAX``
_EMP_KMAX_NSIGMA = 6.0
_EMP_KMAX = 24
#: frames with σ above ``_QUANTISED_MAX_RATIO`` steps: the empirical guard alone, on a lattice
#: of ``m`` steps, ``m`` the largest integer with ``m Δ <= σ / _EMP_COARSE_PER_SIGMA``
_EMP_COARSE_PER_SIGMA = 2.0


def _quantised_noise(img: np.ndarray, bg: Any, cfg: BackgroundConfig, thresh: float,
                     det: np.ndarray | None = None, noise: np.ndarray | None = None
                     ) -> np.ndarray | None:
    """Detection noise floor (filtered-image units) of a quantised frame, or None.

    On a frame whose values lie on a lattice of step Δ (``bg.quantum``) with σ ≤ 3 Δ, the
    3×3-filtered noise is a weighted sum of nine discrete values and far from Gaussian when σ is
    of the order of Δ or less (rare ±Δ jumps: at σ = 0.3 Δ a pair of +Δ pixels reaches 4.5
    filtered σ). Two levels, per mesh, and the floor is the higher:

    * model — each pixel is ``round(f + σ_L z)`` in steps from the lattice point nearest the
      background (a Gaussian read chain, then the ADC); ``f`` and the latent ``σ_L`` are those
      whose rounded mean and std match the mesh's sigma-clipped level and noise (a lookup
      table), so stars enter only through the clipped statistics;
    * empirical (with ``det`` and ``noise``) — the histogram of the mesh's own values in steps,
      from the pixels that are neither within ``_EMP_MASK_GROW`` px of a bright source (filtered
      value above twice the Gaussian threshold) nor have their 8 neighbours summing more than ``_EMP_RING_NSIGMA`` σ above the
      background (a star's pixels have bright neighbours; for independent noise this condition
      leaves the pixel's own distribution unchanged), and within 6 clipped σ + 3 steps of the
      level. It catches noise the Gaussian model does not describe: skewed counts under
      a bias (Poisson sky of 0.3 e⁻ on a bias of 100 DN: the model alone let 7–12 false
      detections per 10⁶ px through, review 28 #13) — the histogram of ALL values (the first
      version) counted star wings as noise and lost most stars at peak SNR 3–6.
      The ring cut does not remove the wings of faint stars whose neighbours are faint too: in
      crowded low-count fields (3,000 stars per 1024², sky 0.3 e⁻) completeness at peak SNR 3–4
      drops 0.28 → 0.18 with the guard (review 28 round 4 #9), ≤ 0.01 in sparse fields.

    For each pmf the distribution of ``S = Σ w_j d_j`` (w = 16 · kernel, integers) is exact
    (pixels independent); the level is the smallest ``s`` with ``P(S > s) ≤ Φ̄(thresh)`` — the
    Gaussian tail probability the threshold means on continuous data — half a step above it.
    The floor is that level over ``thresh`` (``det > thresh · noise`` then reads ``S > s``);
    meshes are median-filtered and interpolated like the background. On a lattice frame with
    σ > 3 Δ only the empirical level is used, on a lattice of ``m Δ ≈ σ/2`` (skewed noise with
    a large σ in steps: gain < 1 e⁻/DN, a float master bias subtracted — review 28 round 4 #2).
    Continuous data (Δ = 0): None (the Gaussian threshold holds). Of the histogram's cuts, the
    ring cut does not depend on the pixel's own value; the far cut (6 σ + 3 steps) and the
    bright-source mask (2× the Gaussian threshold) do, but remove far less of the noise's own
    tail than the tail probability the level is set at.
    """
    from scipy.special import ndtr

    delta = float(bg.quantum)
    if delta <= 0:
        return None
    coarse = float(bg.global_rms) > _QUANTISED_MAX_RATIO * delta
    if coarse:
        if det is None or noise is None:
            return None
        # a Gaussian-looking lattice: the empirical guard alone, on a coarser lattice
        delta *= max(1, int(float(bg.global_rms) / (_EMP_COARSE_PER_SIGMA * delta)))
    H, W = img.shape
    m = min(cfg.mesh, H, W)
    ny, nx = -(-H // m), -(-W // m)
    cy = np.minimum(np.arange(ny) * m + m // 2, H - 1)
    cx = np.minimum(np.arange(nx) * m + m // 2, W - 1)
    b = bg.back[cy[:, None], cx[None, :]].astype(np.float64).ravel()
    r = bg.rms[cy[:, None], cx[None, :]].astype(np.float64).ravel() / delta
    step = max(1, int(np.sqrt(img.size / 16384)))
    u, cnt = np.unique(img[::step, ::step], return_counts=True)
    z0 = float(u[np.argmax(cnt)])                 # the most frequent value: a lattice point
    ref = z0 + delta * np.rint((b - z0) / delta)              # lattice point nearest the level
    mu = (b - ref) / delta                                    # in steps, |mu| <= 1/2
    if coarse:
        s_star = np.full(len(b), -(16 * _EMP_KMAX + 1))
    else:
        ts, tf, tm, tsd = _rounded_gaussian_table()
        cost = (np.abs(mu)[:, None] - tm[None, :]) ** 2 + (r[:, None] - tsd[None, :]) ** 2
        j = np.argmin(cost, axis=1)
        sig, f = ts[j], np.sign(mu) * tf[j]
        K = int(np.clip(np.ceil(6 * sig.max() + 1), 2, 20))
        k = np.arange(-K, K + 1)
        pmf = (ndtr((k + 0.5 - f[:, None]) / sig[:, None])
               - ndtr((k - 0.5 - f[:, None]) / sig[:, None]))
        s_star = _tail_steps(pmf, K, thresh)
    if det is not None and noise is not None:
        s_emp = _empirical_tail_steps(img, cfg, thresh, det,
                                      noise * np.float32(_EMP_MASK_FACTOR * thresh),
                                      ref, b, r, delta, m, ny, nx)
        s_star = np.maximum(s_star, s_emp)
    level = ref + delta * (s_star + 0.5) / 16.0 - b           # filtered excess over the back
    grid = (np.maximum(level, 0.0) / thresh).reshape(ny, nx).astype(np.float32)
    if cfg.filter_size > 1 and min(ny, nx) >= cfg.filter_size:
        grid = cv2.medianBlur(grid, cfg.filter_size)
    if ny == 1 and nx == 1:
        return np.full((H, W), grid[0, 0], np.float32)
    return cv2.resize(grid, (nx * m, ny * m), interpolation=cv2.INTER_LINEAR)[:H, :W]


def _empirical_tail_steps(img: np.ndarray, cfg: BackgroundConfig, thresh: float,
                          det: np.ndarray, level: np.ndarray, ref: np.ndarray, b: np.ndarray,
                          r: np.ndarray, delta: float, m: int, ny: int, nx: int) -> np.ndarray:
    """The empirical level of :func:`_quantised_noise` per mesh, in 1/16 steps over ``ref``
    (very low where a mesh has too few clean pixels: the model level then holds)."""
    H, W = img.shape

    def per_pixel(v: np.ndarray, dt: Any = np.float32) -> np.ndarray:
        grid = np.asarray(v).reshape(ny, nx).astype(dt)
        return np.repeat(np.repeat(grid, m, axis=0), m, axis=1)[:H, :W]

    d = np.rint((img - per_pixel(ref)) * np.float32(1.0 / delta))
    ring = cv2.boxFilter(d, -1, (3, 3), normalize=False, borderType=cv2.BORDER_REFLECT) - d
    sd = np.sqrt(r * r + 1.0 / 12.0)
    cut = 8 * (b - ref) / delta + _EMP_RING_NSIGMA * np.sqrt(8.0) * sd
    keep = ring <= per_pixel(cut)
    src = (det > level).view(np.uint8)
    g = 2 * _EMP_MASK_GROW + 1
    keep &= cv2.dilate(src, np.ones((g, g), np.uint8)) == 0
    # far cut (the noise's own tail beyond it is < 1e-7 for counts up to a few per pixel; a
    # 3σ cut dropped 1-7e-5 of it, more than the tail probability the level is set at)
    kmax = np.minimum(np.ceil(_EMP_KMAX_NSIGMA * sd + 3.0), _EMP_KMAX)
    K = int(kmax.max())
    keep &= np.abs(d) <= per_pixel(kmax)
    nm = ny * nx
    mesh = per_pixel(np.arange(nm) * (2 * K + 1) + K, np.int32)
    idx = mesh[keep] + d[keep].astype(np.int32)
    hist = np.bincount(idx, minlength=nm * (2 * K + 1)).reshape(nm, 2 * K + 1).astype(float)
    tot = hist.sum(axis=1)
    pmf = hist / np.maximum(tot, 1.0)[:, None]
    s = _tail_steps(pmf, K, thresh)
    return np.where(tot >= _EMP_MIN_PIXELS, s, -(16 * K + 1))


def _is_count_data(img: np.ndarray, bg: Any) -> bool:
    """Integer-valued frame whose background variance is about its level (photon counts)."""
    sample = img[::7, ::7]
    if not np.all(sample == np.round(sample)):
        return False
    level = float(bg.global_back)           # the median of the mesh levels
    return 0 <= level <= 100 and 0.5 * level <= bg.global_rms ** 2 <= 2.0 * level + 1.0



def psf_sharpness(sigma: Any) -> np.ndarray:
    """Sharpness of a pixel-centred Gaussian star of PSF σ (the statistic of
    :func:`shape_flags`): ``4 (1 − (a + a²)/2) / (1 + a)²`` with ``a = exp(−1/(2σ²))``.

    Parameters
    ----------
    sigma
        PSF σ in pixels (> 0; scalar or array). A star centred off the pixel centre is less
        sharp, so this is the largest sharpness a star of that σ has without noise.
    """
    sg = np.asarray(sigma, dtype=float)
    if not np.all(np.isfinite(sg)) or np.any(sg <= 0):
        raise ValueError(f"sigma must be finite and > 0, got {sigma!r}")
    a = np.exp(-1.0 / (2 * sg * sg))
    return 4 * (1 - (a + a * a) / 2) / (1 + a) ** 2


def shape_flags(sub: Any, det: Any, peaks: Any, rms: Any, psf_sigma: float, *,
                sharp_margin: float = 0.5, round_max: float = 0.5
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Sharpness, roundness and artifact flags of detections (DAOFIND/SEP-like).

    Parameters
    ----------
    sub
        Background-subtracted image.
    det
        ``sub`` filtered by the 3×3 detection kernel.
    peaks
        Integer peak positions ``(n, 2)`` (x = column, y = row).
    rms
        Per-pixel noise map of ``sub`` (or a scalar).
    psf_sigma
        PSF σ of the frame (pixels).
    sharp_margin, round_max
        See :class:`SkyConfig`.

    Returns
    -------
    sharpness, roundness, flags : numpy.ndarray
        ``sharpness = (I_c − mean of the 8 neighbours) / det_c``; ``roundness`` is the
        ellipticity ``sqrt((m_xx − m_yy)² + 4 m_xy²) / (m_xx + m_yy)`` of the positive pixels
        of the 5×5 stamp under a Gaussian window of σ = max(PSF σ, 1); ``flags`` has
        ``FLAG_SHARP`` where ``sharpness > psf_sharpness(σ) + max(sharp_margin, 3 σ_s)``
        (``σ_s = 1.06 rms / det_c``, the noise of the sharpness) and ``FLAG_ELONGATED`` where
        ``roundness > round_max + 3 / SNR_det``.
    """
    img = np.asarray(sub, dtype=np.float32)
    d = np.asarray(det, dtype=np.float32)
    p = np.asarray(peaks)
    if img.ndim != 2 or d.shape != img.shape:
        raise ValueError(f"sub and det must be 2-D of equal shape, got {img.shape}, {d.shape}")
    if p.ndim != 2 or p.shape[1] != 2:
        raise ValueError(f"peaks must have shape (n, 2), got {p.shape}")
    check_positive(psf_sigma, "psf_sigma")
    check_positive(sharp_margin, "sharp_margin")
    check_positive(round_max, "round_max")
    n = len(p)
    if n == 0:
        e = np.zeros(0)
        return e, e, np.zeros(0, np.int8)
    H, W = img.shape
    x = np.clip(p[:, 0].astype(np.int64), 0, W - 1)
    y = np.clip(p[:, 1].astype(np.int64), 0, H - 1)
    pad = cv2.copyMakeBorder(img, 2, 2, 2, 2, cv2.BORDER_REFLECT)
    off = np.arange(-2, 3)
    S = pad[(y + 2)[:, None, None] + off[None, :, None],
            (x + 2)[:, None, None] + off[None, None, :]].astype(float)
    c = S[:, 2, 2]
    nb = (S[:, 1:4, 1:4].sum(axis=(1, 2)) - c) / 8.0
    dc = d[y, x].astype(float)
    dsafe = np.where(dc > 0, dc, np.inf)
    sharp = (c - nb) / dsafe
    r = np.broadcast_to(np.asarray(rms, dtype=float), img.shape)[y, x]
    sig_s = 1.06 * r / dsafe
    sw = max(float(psf_sigma), 1.0)
    g = np.exp(-(off[:, None] ** 2 + off[None, :] ** 2) / (2 * sw * sw))
    w = np.maximum(S, 0) * g[None]
    m0 = np.maximum(w.sum(axis=(1, 2)), 1e-30)
    mx = np.einsum("nij,j->n", w, off) / m0
    my = np.einsum("nij,i->n", w, off) / m0
    ddx = off[None, None, :] - mx[:, None, None]
    ddy = off[None, :, None] - my[:, None, None]
    mxx = (w * ddx * ddx).sum(axis=(1, 2)) / m0
    myy = (w * ddy * ddy).sum(axis=(1, 2)) / m0
    mxy = (w * ddx * ddy).sum(axis=(1, 2)) / m0
    tr = np.maximum(mxx + myy, 1e-30)
    roundness = np.sqrt((mxx - myy) ** 2 + 4 * mxy * mxy) / tr
    snr_det = dc / (r * _KERNEL_GAIN)
    flags = np.zeros(n, np.int8)
    flags[sharp > psf_sharpness(psf_sigma) + np.maximum(sharp_margin, 3 * sig_s)] |= FLAG_SHARP
    flags[roundness > round_max + 3.0 / np.maximum(snr_det, 1e-9)] |= FLAG_ELONGATED
    return sharp, roundness, flags


#: sharpness above which a peak is left out of the PSF σ estimate (a centred Gaussian of
#: σ = 0.6 px has 2.16; a single hot pixel 4, a two-pixel cosmic-ray hit 2.3)
_SHARP_FOR_PSF = 2.0
#: when no peak passes ``_SHARP_FOR_PSF``: the cut for a second try (σ = 0.5 px: 2.87; a hot
#: pixel 4), then the nominal σ; an estimated σ is never below ``_PSF_SIGMA_MIN`` (review 28,
#: round 4 #1: a starless frame with hot pixels set σ = 0.40 px from them, which switched the
#: sharpness flag off and returned the hot pixels as stars)
_SHARP_FALLBACK = 3.0
_PSF_SIGMA_NOMINAL = 1.0
_PSF_SIGMA_MIN = 0.6


def _extract_sky(img: np.ndarray, cfg: SkyConfig) -> ExtractionResult:
    bg = background_map(img, cfg.background)
    sub = img - bg.back
    det = cv2.sepFilter2D(sub, -1, _KERNEL_1D, _KERNEL_1D, borderType=cv2.BORDER_REFLECT)
    noise = bg.rms * np.float32(_KERNEL_GAIN)
    floor = _quantised_noise(img, bg, cfg.background, cfg.thresh, det, noise)
    if floor is not None:
        noise = np.maximum(noise, floor)
    mask = det > noise * np.float32(cfg.thresh)
    R = _dynamic_range(img)
    empty = np.zeros(0)
    none = ExtractionResult(np.zeros((0, 2)), empty, empty, empty, empty, R, 1.0, bg.global_rms,
                            empty, empty, np.zeros(0, np.int8), float("nan"))
    if cfg.min_area > 1:
        # at least min_area detection pixels in the peak's 5×5 neighbourhood
        cnt = cv2.boxFilter(mask.view(np.uint8), cv2.CV_16U, (5, 5), normalize=False,
                            borderType=cv2.BORDER_CONSTANT)
        mask &= cnt >= cfg.min_area
    peaks = find_peaks(det, mask)
    if len(peaks) == 0:
        return none
    keep = deblend_peaks(det, peaks, noise, nsigma=cfg.deblend_nsigma,
                         contrast=cfg.deblend_contrast)
    peaks = peaks[keep]
    if cfg.local_background:
        peaks = peaks[_locally_significant(img, sub, det, peaks, bg, noise, cfg.thresh)]
        if len(peaks) == 0:
            return none
    pk = det[peaks[:, 1], peaks[:, 0]]
    if cfg.psf_sigma is None:
        # sharpness at a nominal σ first: hot pixels and cosmic rays (often the brightest
        # peaks of a raw frame) must not set the PSF σ
        sharp0, _, _ = shape_flags(sub, det, peaks, bg.rms, _PSF_SIGMA_NOMINAL)
        cand = np.flatnonzero(sharp0 <= _SHARP_FOR_PSF)
        if len(cand) == 0:
            cand = np.flatnonzero(sharp0 <= _SHARP_FALLBACK)
        if len(cand) == 0:                           # hot pixels only: nothing to fit
            sigma = _PSF_SIGMA_NOMINAL
        else:
            order = cand[np.argsort(-pk[cand], kind="stable")]
            skip = len(order) // 10                  # the brightest may be saturated
            sigma = max(estimate_psf_sigma(sub, peaks[order[skip: skip + 50]]),
                        _PSF_SIGMA_MIN)
    else:
        sigma = cfg.psf_sigma
    sharp, rnd, flags = shape_flags(sub, det, peaks, bg.rms, sigma,
                                    sharp_margin=cfg.sharp_margin, round_max=cfg.round_max)
    if cfg.reject_artifacts and not np.any(flags == 0):
        return replace(none, psf_sigma=float(sigma))
    # centroids with every peak present (a rejected cosmic ray still masks its pixels from a
    # neighbour's window), then the flagged ones are dropped
    xy, flux = windowed_centroids(sub, peaks.astype(float), sigma,
                                  iterations=cfg.centroid_iterations,
                                  aperture=max(1.5, cfg.aperture_radius * sigma))
    if cfg.reject_artifacts:
        ok = flags == 0
        peaks, sharp, rnd, flags, xy, flux = (peaks[ok], sharp[ok], rnd[ok], flags[ok], xy[ok],
                                              flux[ok])
    peak = sub[peaks[:, 1], peaks[:, 0]].astype(float)
    snr = peak / bg.rms[peaks[:, 1], peaks[:, 0]]
    area = mask[np.clip(peaks[:, 1, None] + np.arange(-2, 3), 0, img.shape[0] - 1)[:, :, None],
                np.clip(peaks[:, 0, None] + np.arange(-2, 3), 0, img.shape[1] - 1)[:, None, :]
                ].sum(axis=(1, 2)).astype(float)
    order = np.argsort(-flux, kind="stable")
    if cfg.max_sources is not None:
        order = order[: cfg.max_sources]
    return ExtractionResult(xy[order], flux[order], area[order], peak[order], snr[order], R, 1.0,
                            bg.global_rms, sharp[order], rnd[order], flags[order], float(sigma))


def extract_stars(image: Any, *, method: str = "sky",
                  config: ExtractionConfig | SkyConfig | None = None,
                  return_info: bool = False) -> StarCentroids | ExtractionResult:
    """Extract star centroids from one image.

    Parameters
    ----------
    image
        2-D image (any real dtype, any range).
    method
        ``"sky"`` (default: mesh background and noise maps, deblending, windowed centroids —
        for any astronomical frame), ``"adaptive"`` (the paper's local-threshold method) or
        ``"global"`` (one ``μ + kσ`` threshold for the whole image, the paper's baseline).
    config
        :class:`SkyConfig` for ``"sky"``, :class:`ExtractionConfig` for the paper's methods
        (defaults stated there).
    return_info
        Return an :class:`ExtractionResult` with areas, peaks, SNRs, ``R`` and ROI size.

    Returns
    -------
    StarCentroids or ExtractionResult
        Centroids ``(n, 2)`` (x = column, y = row) and fluxes, brightest first; ``n`` may be 0.

    Raises
    ------
    ValueError
        If the image is empty, constant, not 2-D or contains non-finite values.
    """
    img = _check_image(image)
    check_choice(method, "method", ("sky", "adaptive", "global"))
    if method == "sky":
        scfg = SkyConfig() if config is None else config
        if not isinstance(scfg, SkyConfig):
            raise TypeError(f"config for method 'sky' must be a SkyConfig, got "
                            f"{type(scfg).__name__}")
        res = _extract_sky(img, scfg)
        return res if return_info else StarCentroids(res.xy, res.flux)
    cfg = ExtractionConfig() if config is None else config
    if not isinstance(cfg, ExtractionConfig):
        raise TypeError(f"config must be an ExtractionConfig, got {type(cfg).__name__}")
    R = _dynamic_range(img, cfg.full_scale)
    if method == "global":
        mu, sd = cv2.meanStdDev(img)
        T = float(mu[0, 0] + cfg.k * sd[0, 0])
        mask = img >= T
        w = img - T
        noise = _robust_std(img)
        roi_frac = 1.0
    else:
        bg = cv2.GaussianBlur(img, (0, 0), cfg.sigma_b, borderType=cv2.BORDER_REFLECT)
        f = img - bg
        noise = _robust_std(f)
        ksize = (2 * cfg.r + 1, 2 * cfg.r + 1)
        if R < cfg.r_min:
            if cfg.robust_roi:
                # median and MAD-σ of I_f: the stars' own light does not raise T_f
                mu0, sd0 = float(np.median(f[::4, ::4])), noise
            else:
                mu_f, sd_f = cv2.meanStdDev(f)
                mu0, sd0 = float(mu_f[0, 0]), float(sd_f[0, 0])
            high = f >= mu0 + cfg.k * sd0
            roi = cv2.dilate(high.astype(np.uint8), np.ones(ksize, np.uint8)) > 0
            roi_frac = float(roi.mean())
        else:
            roi = None
            roi_frac = 1.0
        mean = cv2.boxFilter(img, -1, ksize, borderType=cv2.BORDER_REFLECT)
        sq = cv2.boxFilter(img * img, -1, ksize, borderType=cv2.BORDER_REFLECT)
        std = np.sqrt(np.maximum(sq - mean * mean, 0))
        mask = img >= mean + cfg.k_b * std
        # a flat window (std ≈ 0, e.g. saturated or cloud-black) is not a star
        mask &= f > max(cfg.k_b * noise, 1e-6)
        if roi is not None:
            mask &= roi
        w = f
    xy, flux, area, peak = _components(mask, w, cfg)
    order = np.argsort(-flux, kind="stable")[: cfg.max_stars]   # [:None] keeps all
    xy, flux, area, peak = xy[order], flux[order], area[order], peak[order]
    if not return_info:
        return StarCentroids(xy, flux)
    return ExtractionResult(xy, flux, area, peak, peak / max(noise, 1e-9), R, roi_frac, noise)


def image_confidence(snr: Any, flux: Any, flux_ref: float, *, snr_ref: float = 8.0,
                     flux_tol: float = 0.7) -> np.ndarray:
    """``C_img`` — the image-feature confidence the paper uses but never defines (our definition).

    ``C_img = C_snr · C_flux`` with ``C_snr = 1 − exp(−(SNR/SNR_ref)²)`` (a faint, noisy spot is
    less trustworthy) and ``C_flux = exp(−ln²(F/F_ref) / (2 tol²))`` (a spot much dimmer — a
    translucent cloud — or much brighter — glare, a cloud edge, a neighbour — than the tracked
    star's reference flux is less trustworthy). Both factors lie in [0, 1].

    Parameters
    ----------
    snr, flux
        Peak SNR and flux of each candidate (arrays of equal shape).
    flux_ref
        The tracked star's reference flux (> 0), e.g. a running mean over trusted updates.
    snr_ref
        SNR at which ``C_snr`` reaches ``1 − e^{-1}``.
    flux_tol
        Tolerated spread of ``ln(F/F_ref)``.
    """
    s = np.asarray(snr, dtype=float)
    fl = np.asarray(flux, dtype=float)
    if s.shape != fl.shape:
        raise ValueError(f"snr and flux must have the same shape, got {s.shape} and {fl.shape}")
    fr = check_positive(flux_ref, "flux_ref")
    check_positive(snr_ref, "snr_ref")
    check_positive(flux_tol, "flux_tol")
    c_snr = -np.expm1(-(np.maximum(s, 0) / snr_ref) ** 2)
    ratio = np.log(np.maximum(fl, 1e-12) / fr)
    return c_snr * np.exp(-0.5 * (ratio / flux_tol) ** 2)


#: the repository's copies of the real CCD frames (provenance and licences in data/README.md)
CCD_DATA_DIR = Path(__file__).resolve().parents[3] / "data" / "ccd"
_CCD_FILES = {"saao_raw": "saao_a8280271.fits", "gmos": "gmos_S20190808S0048_cutout.fits"}


def real_ccd_frames(data_dir: str | Path | None = None
                    ) -> dict[str, tuple[np.ndarray, float, float]]:
    """Real CCD frames with cosmic rays, read from the repository's ``data/ccd/`` (copied from
    the ccdproc 2.5.1 and astroscrappy 1.3.0 wheels, BSD-3-Clause; provenance and sha256 in
    ``data/README.md``).

    * ``"saao_raw"`` — ccdproc's ``tests/data/a8280271.fits``: a raw 150 s frame of the SAAO
      1.0 m telescope (STE3 CCD, 2013-07-13), trimmed to its ``TRIMSEC`` (520×512, bias not
      removed): a few stars and many cosmic-ray hits;
    * ``"gmos"`` — astroscrappy's ``tests/data/gmos.fits`` (``SCI``): a 150×200 cutout of a
      Gemini-South GMOS spectrum (S20190808S0048, reduced with DRAGONS) with two cosmic-ray
      tracks, sky lines and no star.

    Parameters
    ----------
    data_dir
        Folder holding the two files (default :data:`CCD_DATA_DIR`).

    Returns
    -------
    dict
        name → ``(image float32, gain e⁻/ADU, read noise e⁻)`` (from the headers / the
        package's own test).

    Raises
    ------
    FileNotFoundError
        If a file is missing from ``data_dir`` (the message names it).
    """
    from astropy.io import fits

    root = CCD_DATA_DIR if data_dir is None else Path(data_dir)
    paths = {k: root / v for k, v in _CCD_FILES.items()}
    for p in paths.values():
        if not p.is_file():
            raise FileNotFoundError(f"real_ccd_frames: {p} is missing (see data/README.md)")
    with fits.open(paths["saao_raw"]) as h:
        hdr = h[0].header
        saao = np.asarray(h[0].data, dtype=np.float32)[:, 16:528]
        saao_gain, saao_rn = float(hdr["GAIN"]), float(hdr["RDNOISE"])
    with fits.open(paths["gmos"]) as h:
        gmos = np.asarray(h["SCI"].data, dtype=np.float32)
    return {"saao_raw": (saao, saao_gain, saao_rn), "gmos": (gmos, 1.933, 4.24)}
