"""Simulated deep-space image sequences with dim small moving targets.

Each frame is ``level + clutter + noise + stars + targets``:

* ``clutter`` — a fluctuating background: a smooth Gaussian random field (correlation scale
  ``clutter_scale_px``) that evolves from frame to frame as a first-order autoregression with
  coefficient ``clutter_memory``, standard deviation ``clutter_sigma``;
* ``noise`` — white Gaussian noise of standard deviation ``noise_sigma``;
* ``stars`` — optional static image (e.g. :func:`m13_star_field`, a real 300 × 300 sky image
  shipped with astropy's test data);
* ``targets`` — Gaussian spots of eq. (1) of Li et al. (2008),
  ``s(x, y) = a · exp(−½[(x/δ)² + (y/δ)²])`` with peak ``a = snr · noise_sigma``, rendered with
  :func:`eotrack.imaging.render_gaussian_spots`, on straight or curved paths, with optional
  per-frame jitter.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import cv2
import numpy as np

from eotrack.imaging.psf import render_gaussian_spots
from eotrack.validation import (
    as_finite_array,
    as_points,
    check_generator,
    check_int,
    check_positive,
)

__all__ = [
    "DimSequence",
    "DimSequenceConfig",
    "DimTarget",
    "curved_path",
    "fwhm_to_sigma",
    "m13_star_field",
    "peak_snr_for_pixel_pd",
    "simulate_dim_sequence",
    "straight_path",
]


def straight_path(start_xy: Sequence[float], velocity_xy: Sequence[float],
                  n_frames: int) -> np.ndarray:
    """Positions ``start + k · velocity`` for ``k = 0 … n_frames − 1``.

    Parameters
    ----------
    start_xy
        ``(x, y)`` in pixels at frame 0.
    velocity_xy
        ``(vx, vy)`` in pixels per frame.
    n_frames
        Number of frames (≥ 1).

    Returns
    -------
    numpy.ndarray
        ``(n_frames, 2)`` positions.
    """
    p0 = as_finite_array(start_xy, "start_xy", shape=(2,))
    v = as_finite_array(velocity_xy, "velocity_xy", shape=(2,))
    n = check_int(n_frames, "n_frames", min_value=1)
    return p0 + np.arange(n)[:, None] * v


def curved_path(centre_xy: Sequence[float], radius_px: float, start_angle_rad: float,
                angular_rate_rad: float, n_frames: int) -> np.ndarray:
    """Positions on a circular arc ``centre + r (cos φ_k, sin φ_k)``, ``φ_k = φ_0 + k ω``.

    Parameters
    ----------
    centre_xy
        Arc centre ``(x, y)`` in pixels.
    radius_px
        Radius (> 0).
    start_angle_rad
        ``φ_0``.
    angular_rate_rad
        ``ω`` per frame.
    n_frames
        Number of frames (≥ 1).

    Returns
    -------
    numpy.ndarray
        ``(n_frames, 2)`` positions.
    """
    c = as_finite_array(centre_xy, "centre_xy", shape=(2,))
    r = check_positive(radius_px, "radius_px")
    phi0 = float(as_finite_array(start_angle_rad, "start_angle_rad", ndim=0))
    om = float(as_finite_array(angular_rate_rad, "angular_rate_rad", ndim=0))
    n = check_int(n_frames, "n_frames", min_value=1)
    phi = phi0 + om * np.arange(n)
    return c + r * np.column_stack([np.cos(phi), np.sin(phi)])


@dataclass(frozen=True, eq=False)
class DimTarget:
    """A dim target: its path, peak SNR and spot width.

    Attributes
    ----------
    path_xy
        ``(n, 2)`` positions (x = column, y = row), one per frame from ``first_frame`` on.
    snr
        Peak amplitude ``a`` over the noise standard deviation.
    sigma_px
        Spot width ``δ`` of eq. (1) (≈ 1 px gives a 3 × 3 pixel spot).
    first_frame
        Frame index of ``path_xy[0]``.
    """

    path_xy: np.ndarray
    snr: float
    sigma_px: float = 1.0
    first_frame: int = 0

    def __post_init__(self) -> None:
        object.__setattr__(self, "path_xy", as_points(self.path_xy, "path_xy"))
        if len(self.path_xy) == 0:
            raise ValueError("path_xy must hold at least one position")
        check_positive(self.snr, "snr", allow_zero=True)
        check_positive(self.sigma_px, "sigma_px")
        check_int(self.first_frame, "first_frame", min_value=0)

    def position(self, frame: int) -> np.ndarray | None:
        """Position at ``frame`` or ``None`` if the target is absent."""
        k = frame - self.first_frame
        if 0 <= k < len(self.path_xy):
            return self.path_xy[k]
        return None


@dataclass(frozen=True, eq=False)
class DimSequenceConfig:
    """Scene parameters (defaults: a 256 × 256, 50-frame sequence with strong clutter).

    Attributes
    ----------
    shape
        ``(height, width)``.
    n_frames
        Number of frames.
    frame_interval_s
        Time between frames.
    level
        Mean background level (DN).
    noise_sigma
        White-noise standard deviation (DN); the SNR unit.
    clutter_sigma
        Standard deviation of the fluctuating background (DN).
    clutter_scale_px
        Correlation scale (Gaussian kernel σ) of the clutter field.
    clutter_memory
        Frame-to-frame correlation of the clutter in [0, 1).
    jitter_px
        Standard deviation of the per-frame random displacement of every target (line-of-sight
        jitter; widens the recovered track line, as the paper notes for Fig. 6).
    stars
        Optional static image (same shape) added to every frame.
    targets
        The targets.
    """

    shape: tuple[int, int] = (256, 256)
    n_frames: int = 50
    frame_interval_s: float = 0.04
    level: float = 100.0
    noise_sigma: float = 10.0
    clutter_sigma: float = 30.0
    clutter_scale_px: float = 24.0
    clutter_memory: float = 0.9
    jitter_px: float = 0.0
    stars: np.ndarray | None = None
    targets: tuple[DimTarget, ...] = field(default_factory=tuple)

    def __post_init__(self) -> None:
        if not (isinstance(self.shape, tuple | list) and len(self.shape) == 2):
            raise ValueError(f"shape must be (height, width), got {self.shape!r}")
        h = check_int(self.shape[0], "shape[0]", min_value=8)
        w = check_int(self.shape[1], "shape[1]", min_value=8)
        object.__setattr__(self, "shape", (h, w))
        check_int(self.n_frames, "n_frames", min_value=1)
        check_positive(self.frame_interval_s, "frame_interval_s")
        as_finite_array(self.level, "level", ndim=0)
        check_positive(self.noise_sigma, "noise_sigma")
        check_positive(self.clutter_sigma, "clutter_sigma", allow_zero=True)
        check_positive(self.clutter_scale_px, "clutter_scale_px")
        m = float(self.clutter_memory)
        if not 0 <= m < 1:
            raise ValueError(f"clutter_memory must lie in [0, 1), got {self.clutter_memory!r}")
        check_positive(self.jitter_px, "jitter_px", allow_zero=True)
        if self.stars is not None:
            st = as_finite_array(self.stars, "stars", ndim=2)
            if st.shape != (h, w):
                raise ValueError(f"stars must have shape {(h, w)}, got {st.shape}")
            object.__setattr__(self, "stars", st)
        targets = tuple(self.targets)
        for i, t in enumerate(targets):
            if not isinstance(t, DimTarget):
                raise TypeError(f"targets[{i}] must be a DimTarget, got {type(t).__name__}")
        object.__setattr__(self, "targets", targets)


@dataclass(frozen=True, eq=False)
class DimSequence:
    """A simulated sequence and its truth.

    Attributes
    ----------
    images
        ``(T, H, W)`` float32 frames.
    times_s
        ``(T,)`` frame times.
    truth_xy
        ``(n_targets, T, 2)`` true (jittered) target positions, NaN where a target is absent.
    config
        The scene parameters.
    """

    images: np.ndarray
    times_s: np.ndarray
    truth_xy: np.ndarray
    config: DimSequenceConfig


def _clutter_field(rng: np.random.Generator, shape: tuple[int, int], scale_px: float,
                   n: int) -> np.ndarray:
    """``n`` independent unit-variance smooth Gaussian fields (generated at low resolution)."""
    h, w = shape
    step = max(1, int(scale_px // 4))
    lh, lw = -(-h // step) + 2, -(-w // step) + 2
    sig = scale_px / step
    white = rng.standard_normal((n, lh, lw))
    out = np.empty((n, h, w), dtype=np.float64)
    norm_ = 2.0 * np.sqrt(np.pi) * sig  # std of Gaussian-filtered unit white noise is 1/norm_
    for k in range(n):
        low = cv2.GaussianBlur(white[k], (0, 0), sig, borderType=cv2.BORDER_REFLECT) * norm_
        big = cv2.resize(low, ((lw) * step, (lh) * step), interpolation=cv2.INTER_CUBIC)
        out[k] = big[step:step + h, step:step + w]
    return out


def simulate_dim_sequence(config: DimSequenceConfig, rng: np.random.Generator) -> DimSequence:
    """Render an image sequence with a fluctuating background and dim targets.

    Parameters
    ----------
    config
        Scene parameters.
    rng
        Random generator (noise, clutter, jitter).

    Returns
    -------
    DimSequence
        Frames and truth.
    """
    if not isinstance(config, DimSequenceConfig):
        raise TypeError(f"config must be a DimSequenceConfig, got {type(config).__name__}")
    rng = check_generator(rng)
    c = config
    h, w = c.shape
    n = c.n_frames
    imgs = c.level + c.noise_sigma * rng.standard_normal((n, h, w))
    if c.clutter_sigma > 0:
        innov = _clutter_field(rng, c.shape, c.clutter_scale_px, n)
        rho = c.clutter_memory
        clutter = innov[0]
        imgs[0] += c.clutter_sigma * clutter
        for k in range(1, n):
            clutter = rho * clutter + np.sqrt(1 - rho * rho) * innov[k]
            imgs[k] += c.clutter_sigma * clutter
    if c.stars is not None:
        imgs += c.stars
    truth = np.full((len(c.targets), n, 2), np.nan)
    jitter = c.jitter_px * rng.standard_normal((n, 2)) if c.jitter_px > 0 else np.zeros((n, 2))
    for k in range(n):
        for i, t in enumerate(c.targets):
            p = t.position(k)
            if p is not None:
                truth[i, k] = p + jitter[k]
        for i, t in enumerate(c.targets):
            if np.isfinite(truth[i, k, 0]):
                a = t.snr * c.noise_sigma
                flux = a * 2.0 * np.pi * t.sigma_px ** 2
                render_gaussian_spots((h, w), truth[i, k][None], flux, t.sigma_px,
                                      integrate=False, out=imgs[k])
    times = c.frame_interval_s * np.arange(n)
    return DimSequence(images=imgs.astype(np.float32), times_s=times, truth_xy=truth, config=c)


def m13_star_field(shape: tuple[int, int] = (256, 256)) -> np.ndarray:
    """A real sky image as a static star background: the M13 field shipped with astropy.

    ``astropy/io/fits/hdu/compressed/tests/data/m13.fits`` (300 × 300, SkyView survey image of the
    globular cluster M13, ``int16``). The sky level (median) is subtracted; the image is cropped
    (centred) or reflected to ``shape``.

    Parameters
    ----------
    shape
        ``(height, width)`` of the returned image.

    Returns
    -------
    numpy.ndarray
        Float image in the survey's counts above the sky median.
    """
    if not (isinstance(shape, tuple | list) and len(shape) == 2):
        raise ValueError(f"shape must be (height, width), got {shape!r}")
    h = check_int(shape[0], "shape[0]", min_value=1)
    w = check_int(shape[1], "shape[1]", min_value=1)
    from astropy.io import fits
    from astropy.utils.data import get_pkg_data_filename

    path = get_pkg_data_filename("data/m13.fits", package="astropy.io.fits.hdu.compressed.tests")
    with fits.open(path) as hdul:
        data = np.asarray(hdul[0].data, dtype=float)
    data -= np.median(data)
    ph, pw = max(0, h - data.shape[0]), max(0, w - data.shape[1])
    if ph or pw:
        data = np.pad(data, ((ph // 2, ph - ph // 2), (pw // 2, pw - pw // 2)), mode="reflect")
    y0 = (data.shape[0] - h) // 2
    x0 = (data.shape[1] - w) // 2
    return data[y0:y0 + h, x0:x0 + w].copy()


def fwhm_to_sigma(fwhm_px: float) -> float:
    """Gaussian ``δ`` whose full width at half maximum is ``fwhm_px`` (``δ = FWHM / 2.3548``)."""
    return check_positive(fwhm_px, "fwhm_px") / (2.0 * np.sqrt(2.0 * np.log(2.0)))


def peak_snr_for_pixel_pd(p_d: float, p_f: float, sigma_px: float, size: int = 3) -> float:
    """Peak SNR at which a centred spot's ``size × size`` core is detected with mean rate ``p_d``.

    Pixel ``i`` of the core holds ``a · g_i`` (eq. 1 sampled at pixel centres, ``g`` = 1 at the
    centre) in unit Gaussian noise and is detected above the CFAR threshold ``Q⁻¹(p_f)`` with
    probability ``Q(Q⁻¹(p_f) − a g_i)``; the peak ``a`` is solved so that the mean over the core
    equals ``p_d``.

    Parameters
    ----------
    p_d
        Wanted mean per-pixel detection probability, in (p_f, 1).
    p_f
        Per-pixel false-alarm probability in (0, 1).
    sigma_px
        Spot width ``δ``.
    size
        Odd side of the core (≥ 1).

    Returns
    -------
    float
        Peak amplitude over the noise standard deviation.
    """
    from scipy.optimize import brentq
    from scipy.stats import norm

    from eotrack.validation import check_probability

    pf = check_probability(p_f, "p_f", open_low=True, open_high=True)
    pd = check_probability(p_d, "p_d", open_low=True, open_high=True)
    if pd <= pf:
        raise ValueError(f"p_d must exceed p_f ({pf}), got {pd}")
    sig = check_positive(sigma_px, "sigma_px")
    n = check_int(size, "size", min_value=1)
    if n % 2 == 0:
        raise ValueError(f"size must be odd, got {n}")
    k = np.arange(n) - n // 2
    g = np.exp(-0.5 * np.add.outer(k ** 2, k ** 2).ravel() / sig ** 2)
    z = norm.isf(pf)
    return float(brentq(lambda a: norm.sf(z - a * g).mean() - pd, 0.0, 1e3))
