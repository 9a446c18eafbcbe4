"""A small synthetic sequence of frames with a known truth, for examples, tests and benchmarks.

A GEO-staring camera (fixed to the Earth, so the stars drift west at the sidereal rate) looks at
a real star field from the Gaia extract, plus uncatalogued fainter stars, one moving target,
sky background with Poisson and read noise, and optional clouds (a per-frame transparency). The
mount believes it points where it does **not**: its believed attitude is the truth turned by a
fixed pointing error and roll error, and that belief is all the frames carry
(``Frame.wcs_guess``). The true WCS of each frame is returned beside, for scoring.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from astropy import units as u
from astropy.coordinates import EarthLocation
from astropy.time import Time
from astropy.wcs import WCS

from eotrack.astro.astrometry import (
    axis_rotation as _rot,
)
from eotrack.astro.astrometry import (
    catalog_in_field,
    look_at_radec,
    wcs_from_camera,
)
from eotrack.geometry import pixel_rays, project_directions
from eotrack.imaging import render_gaussian_spots
from eotrack.validation import (
    as_finite_array,
    check_generator,
    check_int,
    check_positive,
    check_probability,
)

from .frames import Frame

__all__ = ["SimulatedSequence", "simulate_sequence"]

_ARCSEC_PER_RAD = 180.0 / np.pi * 3600.0
_EARTH_RATE_RAD_S = 7.292115e-5


@dataclass(frozen=True)
class SimulatedSequence:
    """Frames and their truth.

    Attributes
    ----------
    frames
        The frames (believed pointing in ``wcs_guess``).
    true_wcs
        The true TAN WCS of each frame (mid-exposure).
    target_xy
        True target pixel position per frame ``(n, 2)``.
    target_ra_deg, target_dec_deg
        True target RA/Dec per frame.
    pointing_error_arcsec, roll_error_deg
        The mount error applied (believed = truth turned by it).
    star_dirs, star_mag, star_catalogued
        Every rendered star: unit direction ``(m, 3)``, magnitude, and whether it is a
        catalogue star (the others are the uncatalogued faint ones).
    """

    frames: tuple[Frame, ...]
    true_wcs: tuple[WCS, ...]
    target_xy: np.ndarray
    target_ra_deg: np.ndarray
    target_dec_deg: np.ndarray
    pointing_error_arcsec: float
    roll_error_deg: float
    star_dirs: np.ndarray
    star_mag: np.ndarray
    star_catalogued: np.ndarray


def simulate_sequence(rng: np.random.Generator, *, ra_deg: float = 80.0, dec_deg: float = -5.0,
                      n_frames: int = 5, interval_s: float = 20.0, exposure_s: float = 2.0,
                      size_px: int = 256, pixel_scale_arcsec: float = 15.0,
                      pointing_error_arcsec: float = 120.0, roll_error_deg: float = 0.2,
                      target_mag: float = 11.0, target_rate_px_s: tuple[float, float] = (0.1,
                                                                                      0.05),
                      sky_e: float = 400.0, read_noise_e: float = 8.0,
                      psf_sigma_px: float = 1.0, zero_point_mag: float = 21.0,
                      faint_stars: int = 30, transparency: tuple[float, ...] | None = None,
                      start_utc: str = "2026-03-20T08:00:00", station: str = "Socorro NM",
                      sequence: str = "seq0", catalog=None) -> SimulatedSequence:
    """Render one station's sequence of a GEO-staring camera.

    Parameters
    ----------
    rng
        Random generator (noise, faint stars, the direction of the pointing error).
    ra_deg, dec_deg
        True boresight of the first frame (deg).
    n_frames, interval_s, exposure_s
        Frames, time between them (s), exposure (s).
    size_px, pixel_scale_arcsec
        Square frame side and plate scale.
    pointing_error_arcsec, roll_error_deg
        The mount's error: believed boresight off by this angle (random direction), believed
        roll off by this (sign random).
    target_mag, target_rate_px_s
        Target brightness and its constant motion in the frame (px/s); it starts near the
        centre.
    sky_e, read_noise_e, psf_sigma_px, zero_point_mag
        Background (e⁻/px), read noise (e⁻), Gaussian PSF σ (px), magnitude of 1 e⁻ per
        exposure.
    faint_stars
        Uncatalogued stars (G 10.5–12.5) scattered over the field (fixed on the sky).
    transparency
        Per-frame sky transparency (1 clear, ~0 clouds); default all 1.
    start_utc, station, sequence
        Time of the first frame (mid-exposure), station name, sequence label.
    catalog
        Star catalogue (default :func:`eotrack.astro.load_catalog`).
    """
    g = check_generator(rng)
    n = check_int(n_frames, "n_frames", min_value=1)
    size = check_int(size_px, "size_px", min_value=32)
    scale = check_positive(pixel_scale_arcsec, "pixel_scale_arcsec")
    dt = check_positive(interval_s, "interval_s")
    exp = check_positive(exposure_s, "exposure_s")
    err = check_positive(pointing_error_arcsec, "pointing_error_arcsec", allow_zero=True)
    roll = float(as_finite_array(roll_error_deg, "roll_error_deg", ndim=0))
    rate = as_finite_array(target_rate_px_s, "target_rate_px_s", shape=(2,))
    trans = np.ones(n) if transparency is None else as_finite_array(
        transparency, "transparency", shape=(n,))
    for i, v in enumerate(trans):
        check_probability(float(v), f"transparency[{i}]")
    f = _ARCSEC_PER_RAD / scale
    c = (size - 1) / 2.0
    K = np.array([[f, 0, c], [0, f, c], [0, 0, 1.0]])
    R0 = look_at_radec(float(ra_deg), float(dec_deg))
    t_s = np.arange(n) * dt

    def attitude(t):  # GEO staring: the camera turns with the Earth about the pole
        return R0 @ _rot(2, _EARTH_RATE_RAD_S * t).T

    phi = g.uniform(0, 2 * np.pi)
    e_rad = err / _ARCSEC_PER_RAD
    E = _rot(2, np.radians(roll) * g.choice([-1.0, 1.0])) @ _rot(
        0, e_rad * np.sin(phi)) @ _rot(1, e_rad * np.cos(phi))
    true_R = [attitude(t) for t in t_s]
    w_true = [wcs_from_camera(K, R, (size, size)) for R in true_R]
    # stars: catalogue (the whole sequence's footprint) + faint uncatalogued ones
    drift = _EARTH_RATE_RAD_S * t_s[-1] * _ARCSEC_PER_RAD / scale
    jyear = float(Time(start_utc, scale="utc").jyear)
    cat = catalog_in_field(w_true[0], (size, size), max_mag=None, jyear=jyear,
                           margin_px=drift + 10.0, catalog=catalog)
    dirs = [cat.unit_vectors()]
    mags = [cat.mag]
    nf = check_int(faint_stars, "faint_stars", min_value=0)
    if nf:
        span = np.array([size + 2 * drift + 20, size + 2 * drift + 20])
        xy_f = g.uniform(0, 1, (nf, 2)) * span - (drift + 10)
        dirs.append(pixel_rays(xy_f, K, true_R[0]))
        mags.append(g.uniform(10.5, 12.5, nf))
    dirs_all = np.concatenate(dirs)
    flux_all = 10 ** (-0.4 * (np.concatenate(mags) - zero_point_mag))
    p0 = np.array([c, c]) + g.uniform(-20, 20, 2)
    t_xy = p0 + t_s[:, None] * rate
    t_dirs = np.stack([pixel_rays(t_xy[k][None], K, true_R[k])[0] for k in range(n)])
    t_ra = np.degrees(np.arctan2(t_dirs[:, 1], t_dirs[:, 0])) % 360.0
    t_dec = np.degrees(np.arcsin(np.clip(t_dirs[:, 2], -1, 1)))
    t_flux = 10 ** (-0.4 * (target_mag - zero_point_mag))
    loc = EarthLocation.from_geodetic(-106.66 * u.deg, 33.82 * u.deg, 1510.0 * u.m)
    t0 = Time(start_utc, scale="utc")
    yy, xx = np.mgrid[0:size, 0:size]
    frames = []
    # the stars trail over the exposure: spots at most 1.25 PSF σ apart along the trail (the
    # sum's ripple is < 10⁻⁵ of its level); 3 spots for the 2-px trails of 15″ pixels
    trail = _EARTH_RATE_RAD_S * exp * _ARCSEC_PER_RAD / scale
    sub = np.linspace(-0.5, 0.5, max(3, int(np.ceil(trail / (1.25 * psf_sigma_px))) + 1)) * exp
    for k in range(n):
        img = np.full((size, size), float(sky_e)) * (1.0 + 0.2 * (xx + 0.5 * yy) / size)
        pts = np.concatenate([project_directions(dirs_all, K, attitude(t_s[k] + s))
                              for s in sub])
        fl = np.tile(flux_all / len(sub), len(sub)) * trans[k]
        ok = np.all((pts > -8) & (pts < size + 8), axis=1)
        render_gaussian_spots((size, size), pts[ok], fl[ok], psf_sigma_px, out=img)
        render_gaussian_spots((size, size), t_xy[k][None], t_flux * trans[k], psf_sigma_px,
                              out=img)
        img = g.poisson(img).astype(float) + g.normal(0.0, read_noise_e, img.shape)
        frames.append(Frame(img, t0 + t_s[k] * u.s, exp, station,
                            wcs_from_camera(K, E @ true_R[k], (size, size)),
                            f"{sequence}_{k:03d}", loc, sequence))
    catalogued = np.r_[np.ones(len(cat), bool), np.zeros(nf, bool)]
    return SimulatedSequence(tuple(frames), tuple(w_true), t_xy, t_ra, t_dec, err,
                             float(roll), dirs_all, np.concatenate(mags), catalogued)
