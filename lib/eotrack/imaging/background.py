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

Quantised data. A frame whose values lie on a lattice ``z0 + kΔ`` (integer ADU, or integers
times a gain plus an offset, stored in any dtype; :func:`quantisation_step` finds Δ) with a noise
σ of the order of Δ or less has most of a mesh's samples EQUAL to its median: the interquartile
range is 0 (σ = 0.3 Δ: 90 % of the values are the median), the first clip then keeps only the
median value and the clipped σ collapses to 0 (it was ~10⁻⁴ DN for σ = 0.2–0.5 DN, and the
extractor found 1,600–4,200 false detections per 10⁶ px). Two changes make the estimate
quantisation-aware, and leave continuous data exactly as before (Δ = 0):

* the robust start takes the quartiles of the samples dithered by a fixed, equidistributed
  pattern ``Δ·u``, ``u ∈ (−½, ½)`` (a golden-ratio sequence over the sample index, independent of
  the values, so it acts like random dithering without a random number generator): the
  quartiles of a variable plus an independent uniform quantisation error, so the start is
  ≈ sqrt(σ² + Δ²/12) and never 0;
* a value ``kΔ`` stands for the interval ``±Δ/2`` around it, so the clip keeps values within
  ``nsigma · sqrt(std² + Δ²/12) + Δ/2`` of the mean: a value whose interval reaches the
  ``nsigma`` window of the dithered spread (the std of the quantised values alone
  underestimates the spread below σ ≈ 0.5 Δ — at σ = 0.2 Δ on a step it is 0.11 Δ, and a
  plain 3·std window would drop the ±Δ values and collapse again); the truncation correction
  of the clipped std uses that radius.

The clipped std is then the standard deviation of the quantised values themselves — the
variance the detection filter sees (for σ ≳ 0.5 Δ it is ≈ σ² + Δ²/12; below it depends on where
the level sits between two steps: at σ = 0.3 Δ it is 0.31 Δ on a step and 0.5 Δ half-way). The
shape of that noise is not Gaussian at low σ/Δ (rare ±Δ jumps): :func:`eotrack.imaging.extract_stars`
sets its threshold on quantised frames from the exact distribution (see ``SkyConfig``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, NamedTuple

import cv2
import numpy as np

from eotrack.validation import check_int, check_positive

__all__ = ["BackgroundConfig", "BackgroundMap", "background_map", "quantisation_step"]

#: std of a unit normal truncated to ±3σ (the clipped std underestimates σ by this factor)
_CLIP3_STD = 0.98658
#: fixed dither pattern in (−½, ½): golden-ratio (Weyl) sequence over the sample index
_GOLDEN = 0.6180339887498949


def _truncated_std_factor(c: np.ndarray) -> np.ndarray:
    """std of a unit normal truncated to ±c (c > 0, array)."""
    from scipy.special import erf

    c = np.maximum(np.asarray(c, dtype=np.float64), 1e-6)
    mass = erf(c / np.sqrt(2.0))
    return np.sqrt(np.maximum(1.0 - 2.0 * c * np.exp(-0.5 * c * c) / np.sqrt(2 * np.pi)
                              / np.maximum(mass, 1e-300), 1e-12))


#: share of the sampled values a lattice must hold: all but ``1 − _ON_STRICT`` of them, or at
#: least ``_ON_TOLERANT`` when the rest looks patched (see :func:`quantisation_step`)
_ON_STRICT = 0.99
_ON_TOLERANT = 0.8


def _lattice(image: Any) -> tuple[float, float]:
    """(Δ, z0) of the lattice ``z0 + kΔ`` the sampled values lie on, or (0, 0) (see
    :func:`quantisation_step` for the rule)."""
    img = _as_image(image)
    step = max(1, int(np.sqrt(img.size / 16384)))
    v = img[::step, ::step].ravel().astype(np.float64)
    u, cnt = np.unique(v, return_counts=True)
    if len(u) < 2:
        return 0.0, 0.0
    # float32 holds the values; a step must span several of its units at the largest value
    ulp = float(np.spacing(np.float32(np.abs(u).max())))
    tol = 2.0 * ulp
    popular = cnt >= max(3, int(2e-3 * len(v)))          # the levels the noise populates
    pop = u[popular]
    if len(pop) < 2:
        return 0.0, 0.0
    d0 = float(np.diff(pop).min())
    if d0 < 4.0 * ulp:                                   # the float32 grid itself
        return 0.0, 0.0
    z0 = float(u[np.argmax(cnt)])                        # the most frequent value
    best = (0.0, 0.0)
    n = float(len(v))
    for mult in range(1, 13):                            # the coarsest lattice that fits
        delta = mult * d0
        r = (u - z0) / delta                             # on the distinct values, weighted
        on = np.abs(r - np.rint(r)) * delta <= 0.01 * delta + tol
        share = float(cnt[on].sum()) / n
        if share >= _ON_STRICT or (share >= _ON_TOLERANT and _looks_patched(
                u, cnt, popular, z0, delta, d0, mult, tol)):
            k = np.rint(r[on])
            dk = np.diff(np.unique(k))
            if len(dk) and dk.min() >= 1:
                best = (_refined(pop, z0, delta, tol), z0)
    return best


def _refined(pop: np.ndarray, z0: float, delta: float, tol: float) -> float:
    """The step from the span of the populated levels on the lattice (a step taken as a
    multiple of a spacing between float32 patch values is a few float32 units off)."""
    k = (pop - z0) / delta
    on = np.abs(k - np.rint(k)) * delta <= 0.01 * delta + tol
    ks = np.rint(k[on])
    if on.sum() < 2 or ks.max() == ks.min():
        return delta
    return float((pop[on].max() - pop[on].min()) / (ks.max() - ks.min()))


def _looks_patched(u: np.ndarray, cnt: np.ndarray, popular: np.ndarray, z0: float,
                   delta: float, d0: float, mult: int, tol: float) -> bool:
    """Whether the values off the lattice ``z0 + kΔ`` are patches (interpolated or replaced
    pixels) rather than the noise of a finer lattice: with at least 3 populated levels, either
    none of the populated levels is off the lattice (patches spread over many values), or the
    lattice point next to the mode holds clearly more values than the finer level just inside
    it (the noise of a finer lattice falls off monotonically from the mode)."""
    rel = (u - z0) / delta
    onl = np.abs(rel - np.rint(rel)) * delta <= 0.01 * delta + tol
    if int(popular.sum()) < 3:
        return False
    if not np.any(popular & ~onl):
        return True
    if mult < 2:
        return False

    def count_at(x: float) -> int:
        return int(cnt[np.abs(u - x) <= 0.01 * d0 + tol].sum())

    for sign in (1.0, -1.0):
        outer, inner = count_at(z0 + sign * delta), count_at(z0 + sign * (delta - d0))
        if outer > 2 * inner + 10:
            return True
    return False


def quantisation_step(image: Any) -> float:
    """Step Δ of the lattice ``z0 + kΔ`` that the values of ``image`` lie on, or 0.0.

    Integer ADU (Δ = 1), integers times a gain plus an offset stored as floats (Δ = gain) and
    8-bit frames are quantised (integers up to ~3·10⁶ and beyond as long as the step spans 4
    float32 units of the largest value); data with continuous values give 0.0. Checked on up to
    ~16,000 pixels (every k-th row and column): the step is found from the values the noise
    populates (each at least 0.2 % of the sample) and is the coarsest multiple of their
    smallest spacing that ≥ 99 % of ALL sampled values lie on (to 1 % of Δ plus the float32
    rounding) — or ≥ 80 % when the values off it look like patches (a bad column
    interpolated, hot pixels replaced by floats): none of them is a populated level, or the
    lattice point next to the mode holds more than twice the values of the finer level just
    inside it (the noise of a genuinely finer lattice falls off from the mode). So up to ~20 %
    patched pixels do not switch a quantised frame to the continuous treatment or to a finer
    step (review 28 #14: 5 % of pixels set to the mean of three neighbours gave Δ = 1/3 and
    ~250 false detections per 10⁶ px, 2 % set to arbitrary floats Δ = 0 and ~2,100).

    Raises
    ------
    TypeError, ValueError
        If the image is not a finite 2-D numeric array of at least 3×3 pixels.
    """
    return _lattice(image)[0]


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
    quantum
        Quantisation step Δ of the values (None: found by :func:`quantisation_step`; 0: treat
        the data as continuous). See the module notes.
    """

    mesh: int = 64
    filter_size: int = 3
    nsigma: float = 3.0
    iterations: int = 3
    subsample: int = 2
    quantum: float | None = None

    def __post_init__(self) -> None:
        check_int(self.mesh, "mesh", min_value=4)
        if self.filter_size not in (1, 3, 5):
            raise ValueError(f"filter_size must be 1, 3 or 5, got {self.filter_size!r}")
        check_positive(self.nsigma, "nsigma")
        check_int(self.iterations, "iterations", min_value=0, max_value=20)
        check_int(self.subsample, "subsample", min_value=1, max_value=8)
        if self.quantum is not None:
            check_positive(self.quantum, "quantum", allow_zero=True)


class BackgroundMap(NamedTuple):
    """Full-resolution background ``back`` and noise ``rms`` (float32, image shape), their
    global (median over meshes) values and the quantisation step used (0.0: continuous)."""

    back: np.ndarray
    rms: np.ndarray
    global_back: float
    global_rms: float
    quantum: float = 0.0


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
    delta = quantisation_step(img) if cfg.quantum is None else float(cfg.quantum)
    if delta > 0:
        # quartiles of the dithered samples: never 0 when most samples equal the median
        u = (np.arange(k) * _GOLDEN) % 1.0 - 0.5
        xs = xs + (delta * u).astype(np.float32)
    qs = np.partition(xs, (k // 4, k // 2, (3 * k) // 4), axis=1)
    mean = qs[:, k // 2].astype(np.float64)
    std = np.maximum((qs[:, (3 * k) // 4] - qs[:, k // 4]).astype(np.float64) / 1.349, 1e-12)
    half = 0.5 * delta            # a quantised value stands for ±Δ/2 around it
    q12 = delta * delta / 12.0    # variance of the quantisation error
    radius = cfg.nsigma * std + half
    for _ in range(cfg.iterations):
        radius = cfg.nsigma * np.sqrt(np.maximum(std * std, 1e-24) + q12) + half
        dev = np.abs(x - mean[:, None].astype(np.float32))
        keep = dev < radius[:, None].astype(np.float32)
        cnt = np.maximum(keep.sum(axis=1), 1)
        xk = np.where(keep, x, np.float32(0))
        mean = xk.sum(axis=1, dtype=np.float64) / cnt
        var = np.einsum("ij,ij->i", xk, xk, dtype=np.float64) / cnt - mean * mean
        std = np.sqrt(np.maximum(var, 0.0))
    if cfg.iterations and delta == 0 and cfg.nsigma == 3.0:
        std = std / _CLIP3_STD
    elif cfg.iterations and delta > 0:
        std = std / _truncated_std_factor(radius / np.maximum(std, 1e-12))
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
    return BackgroundMap(np.ascontiguousarray(back), np.ascontiguousarray(rms), gb, gr, delta)
