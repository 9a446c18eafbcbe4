"""A camera-like star frame: Poisson sky and stars, Gaussian read noise, gain and bias, rounded
by the ADC (the frames of the extractor's quantisation tests and benchmarks, issue 28).

Model, in electrons then DN: ``e = Poisson(stars + sky) + N(0, read_noise²)``,
``DN = e / gain + bias``, rounded to integers (``quantise=True``) and, for an integer
``dtype``, clipped to its range (the ADC saturates). Stars are Gaussian spots of PSF σ
``psf_sigma`` (pixel-integrated, :func:`eotrack.imaging.render_gaussian_spots`) at uniform
positions with a peak SNR uniform in ``snr_range``; the peak SNR is measured against the sky and
read noise BEFORE the ADC, ``flux = SNR · sqrt(sky + read_noise²) · 2π σ²`` electrons:
rounding adds ``gain²/12`` e⁻² (at gain 16 e⁻/DN on sky 20 e⁻ and read noise 3 e⁻ the peak SNR
after the ADC is 0.76× the stated one).
"""

from __future__ import annotations

from numbers import Real
from typing import Any, NamedTuple

import numpy as np

from eotrack.imaging.psf import render_gaussian_spots
from eotrack.validation import check_generator, check_int, check_positive

__all__ = ["CameraFrame", "camera_frame"]


class CameraFrame(NamedTuple):
    """Output of :func:`camera_frame`: the ``image`` (DN, ``dtype``), star positions ``xy``
    ``(n, 2)`` (x = column, y = row) and their peak SNR ``snr`` ``(n,)``."""

    image: np.ndarray
    xy: np.ndarray
    snr: np.ndarray


def camera_frame(rng: np.random.Generator, size: int = 512, n_stars: int = 120, *,
                 sky: float = 20.0, read_noise: float = 3.0, gain: float = 1.0,
                 bias: float = 100.0, psf_sigma: float = 1.4,
                 snr_range: tuple[float, float] = (3.0, 12.0), margin: int = 12,
                 dtype: Any = np.uint16, quantise: bool = True) -> CameraFrame:
    """Simulate a camera-like square star frame (see the module notes for the model).

    Parameters
    ----------
    rng
        Random generator (draws, in this order: positions, SNRs, Poisson counts, read noise).
    size
        Frame side in pixels (≥ 16).
    n_stars
        Number of stars (≥ 0; 0 gives a frame of pure noise).
    sky
        Sky level in electrons per pixel (≥ 0).
    read_noise
        Read noise σ in electrons (≥ 0).
    gain
        Electrons per DN (> 0).
    bias
        Offset in DN added before rounding (finite).
    psf_sigma
        Gaussian PSF σ in pixels (> 0).
    snr_range
        ``(low, high)`` of the uniform peak SNR, ``0 < low ≤ high``.
    margin
        Stars keep this many pixels from the edges (``0 ≤ 2·margin < size``).
    dtype
        Output dtype; an integer dtype needs ``quantise=True`` (values clipped to its range).
    quantise
        Round to integer DN (the ADC); ``False`` returns the unrounded DN (float dtype only).

    Returns
    -------
    CameraFrame
        ``image``, ``xy``, ``snr``.

    Raises
    ------
    TypeError
        If ``rng`` is not a numpy Generator, a number is not a number, ``dtype`` is not
        numeric or ``quantise`` not a bool.
    ValueError
        If a number is out of its range, ``snr_range`` is not ``0 < low ≤ high``, stars are
        requested on a frame with no noise (``sky + read_noise² = 0``), or an integer
        ``dtype`` is asked for without rounding.
    """
    gen = check_generator(rng, "rng")
    n = check_int(size, "size", min_value=16)
    k = check_int(n_stars, "n_stars", min_value=0)
    sky_e = check_positive(sky, "sky", allow_zero=True)
    rn = check_positive(read_noise, "read_noise", allow_zero=True)
    g = check_positive(gain, "gain")
    sig = check_positive(psf_sigma, "psf_sigma")
    mg = check_int(margin, "margin", min_value=0)
    if 2 * mg >= n:
        raise ValueError(f"margin must be below size / 2 = {n / 2:g}, got {margin}")
    if isinstance(bias, bool) or not isinstance(bias, Real):
        raise TypeError(f"bias must be a real number, got {type(bias).__name__}")
    b = float(bias)
    if not np.isfinite(b):
        raise ValueError(f"bias must be finite, got {bias!r}")
    try:
        lo, hi = (float(v) for v in snr_range)
    except (TypeError, ValueError):
        raise ValueError(f"snr_range must be two numbers (low, high), got {snr_range!r}") from None
    if not (np.isfinite(lo) and np.isfinite(hi) and 0 < lo <= hi):
        raise ValueError(f"snr_range must satisfy 0 < low <= high, got {snr_range!r}")
    if not isinstance(quantise, (bool, np.bool_)):
        raise TypeError(f"quantise must be a bool, got {type(quantise).__name__}")
    try:
        dt = np.dtype(dtype)
    except TypeError:
        raise TypeError(f"dtype must be a numeric dtype, got {dtype!r}") from None
    if not (np.issubdtype(dt, np.integer) or np.issubdtype(dt, np.floating)):
        raise TypeError(f"dtype must be an integer or float dtype, got {dt}")
    if np.issubdtype(dt, np.integer) and not quantise:
        raise ValueError(f"dtype {dt} is an integer type: it needs quantise=True")
    noise_e = np.sqrt(sky_e + rn * rn)
    if k and noise_e == 0:
        raise ValueError("stars need a noise to set their SNR: sky + read_noise² is 0")
    xy = gen.uniform(mg, n - mg, (k, 2))
    snr = gen.uniform(lo, hi, k)
    flux = snr * noise_e * 2 * np.pi * sig * sig
    e = gen.poisson(render_gaussian_spots((n, n), xy, flux, sig) + sky_e).astype(np.float64)
    if rn > 0:
        e += gen.normal(0.0, rn, (n, n))
    dn = e / g + b
    if quantise:
        dn = np.round(dn)
    if np.issubdtype(dt, np.integer):
        info = np.iinfo(dt)
        dn = np.clip(dn, info.min, info.max)
    return CameraFrame(dn.astype(dt), xy, snr)
