"""Frames → extraction → astrometry → star/target separation → initiation → measurements.

:func:`measure_frame` is one frame's extraction and plate solution (the call a burst loop
makes); :func:`measure_frames` runs the whole chain over many frames and returns the per-object
measurements as an astropy :class:`~astropy.table.Table`.

Failures: a frame that cannot be read, whose extraction fails or whose plate solution fails is
**skipped** and the run goes on. Each skip emits one :class:`FrameSkippedWarning` whose message
names the frame (and its file), the stage and the reason; the same records are in the table's
``meta["skipped"]`` (a list of ``{"frame", "file", "stage", "reason"}`` dicts, kept in ECSV).
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from os import PathLike
from pathlib import Path
from typing import Any

import numpy as np
from astropy import units as u
from astropy.table import Table
from astropy.time import Time
from scipy.spatial import cKDTree

from eotrack.astro.astrometry import (
    ARCSEC_PER_DEG,
    PlateSolution,
    PlateSolveError,
    catalog_in_field,
    pixel_scale_arcsec,
    solve_plate,
)
from eotrack.astro.catalog import StarCatalog
from eotrack.imaging import SkyConfig, extract_stars
from eotrack.imaging.background import BackgroundConfig, background_map
from eotrack.imaging.trails import extract_trailed
from eotrack.tracking.initiation import ModifiedHoughInitiator
from eotrack.validation import as_points, check_choice, check_int, check_positive

from .frames import FitsFrameError, Frame, read_fits

__all__ = [
    "MEASUREMENT_COLUMNS",
    "FrameMeasurement",
    "FrameSkippedWarning",
    "PipelineConfig",
    "cross_trail_psf_sigma",
    "default_initiator",
    "extract_frame",
    "initiate_tracks",
    "measure_frame",
    "measure_frames",
    "separate_targets",
    "star_trail_px",
    "target_border_px",
]

#: Earth's rotation rate (rad/s): a staring (Earth-fixed) mount sees the stars drift at it
_EARTH_RATE_RAD_S = 7.292115e-5

#: Columns of :func:`measure_frames`' table, with their units.
MEASUREMENT_COLUMNS = (("time", None), ("ra", u.deg), ("dec", u.deg),
                       ("sigma_arcsec", u.arcsec), ("station", None), ("frame", None),
                       ("track", None), ("x", u.pix), ("y", u.pix), ("sequence", None))


class FrameSkippedWarning(UserWarning):
    """A frame was left out of a run; the message names it, the stage and the reason."""


@dataclass(frozen=True)
class PipelineConfig:
    """Settings of the frames pipeline.

    Attributes
    ----------
    sky
        Extraction settings (:class:`eotrack.imaging.SkyConfig`). Default: 4σ threshold, PSF σ
        estimated (across the star trails when they trail), and a background of 32-px meshes
        without the median filter: with the extractor's default (64-px meshes, 3×3 median
        filter) a 256-px frame of trailed stars at 5–8″/px gave ≈ 20 false tracks per sequence
        on the side where the stars enter (review 30 round 3).
    catalog_mag
        Faintest catalogue star used for matching (the Gaia extract is complete to G ≈ 10).
    match_radius_px, max_offset_arcsec, max_roll_deg, max_scale_error, min_stars, clip_sigma
        Plate-solution settings (:func:`eotrack.astro.astrometry.solve_plate`).
    star_radius_px
        A detection this close (px) to a catalogue star of the solved frame, or to a detection
        at the same RA/Dec in the previous or next frame of its sequence, is a star.
    max_rate_arcsec_s
        Initiator velocity gate (″/s, in the frame's pixel coordinates): converted to px/s with
        each sequence's solved plate scale (7.5″/s = 0.5 px/s at 15″/px). A GEO-staring mount
        sees GEO objects at 0 to a few ″/s; a sidereally tracking mount sees them at ≈ 15″/s
        — raise it there.
    centroid_k
        Per-axis centroid error of a detection, ``centroid_k / SNR`` px (SNR = peak over the
        local noise, from the extractor): √(2/π) ≈ 0.8 is the background-limited bound of a
        Gaussian PSF; the default 1.0 allows for the windowed centroid.
    centroid_floor_px
        Smallest per-axis centroid error (px) used in ``sigma_arcsec`` (bright targets of
        :func:`eotrack.pipeline.simulate_sequence` measure ≈ 0.03 px: the windowed centroid's
        own bias).
    initiator_sigma_px
        Centroid noise per axis of the initiator's χ² tests.
    max_gap_s
        Frames of a station without a ``sequence`` label are split into sequences where the
        time between two frames exceeds this (s).
    mount
        ``"staring"`` (fixed to the Earth, the GEO survey mode: stars trail at the sidereal
        rate over the exposure, :func:`star_trail_px`) or ``"sidereal"`` (stars are points).
    trail_min_px
        Star trails at least this long (px) are extracted trail-aware
        (:func:`eotrack.imaging.trails.extract_trailed`: matched filters for points and trails,
        trail centroids at the trail's midpoint = mid-exposure); shorter ones with the point
        extractor (``sky``). 3 px: a 2-px trail (2 s at 15″/px) is still round enough for the
        point extractor's shape test, a 6-px one (2 s at 5″/px) is rejected by it as
        elongated.
    """

    sky: SkyConfig = field(default_factory=lambda: SkyConfig(
        thresh=4.0, background=BackgroundConfig(mesh=32, filter_size=1)))
    catalog_mag: float = 10.0
    match_radius_px: float = 2.0
    max_offset_arcsec: float = 600.0
    max_roll_deg: float = 1.0
    max_scale_error: float = 0.0
    min_stars: int = 6
    clip_sigma: float = 3.0
    star_radius_px: float = 2.5
    max_rate_arcsec_s: float = 7.5
    centroid_k: float = 1.0
    centroid_floor_px: float = 0.03
    initiator_sigma_px: float = 0.3
    max_gap_s: float = 300.0
    mount: str = "staring"
    trail_min_px: float = 3.0

    def __post_init__(self) -> None:
        if not isinstance(self.sky, SkyConfig):
            raise TypeError(f"sky must be a SkyConfig, got {type(self.sky).__name__}")
        check_positive(self.catalog_mag, "catalog_mag", allow_zero=True)
        check_positive(self.match_radius_px, "match_radius_px")
        check_positive(self.max_offset_arcsec, "max_offset_arcsec")
        check_positive(self.max_roll_deg, "max_roll_deg", allow_zero=True)
        if not check_positive(self.max_scale_error, "max_scale_error", allow_zero=True) < 0.3:
            raise ValueError(f"max_scale_error must be < 0.3, got {self.max_scale_error}")
        check_int(self.min_stars, "min_stars", min_value=4)
        check_positive(self.clip_sigma, "clip_sigma")
        check_positive(self.star_radius_px, "star_radius_px")
        check_positive(self.max_rate_arcsec_s, "max_rate_arcsec_s")
        check_positive(self.centroid_k, "centroid_k")
        check_positive(self.centroid_floor_px, "centroid_floor_px")
        check_positive(self.initiator_sigma_px, "initiator_sigma_px")
        check_positive(self.max_gap_s, "max_gap_s")
        check_choice(self.mount, "mount", ("staring", "sidereal"))
        check_positive(self.trail_min_px, "trail_min_px")


@dataclass(frozen=True)
class FrameMeasurement:
    """One frame after extraction and astrometry.

    Attributes
    ----------
    frame
        The frame.
    xy, flux, snr
        Detections ``(n, 2)`` (px), their fluxes and peak SNRs (``nan`` when the detections
        were given without SNR).
    solution
        The plate solution.
    ra_deg, dec_deg
        Every detection through the solved WCS.
    is_catalogue
        Detections within ``star_radius_px`` of a catalogue star of the solved frame.
    """

    frame: Frame
    xy: np.ndarray
    flux: np.ndarray
    snr: np.ndarray
    solution: PlateSolution
    ra_deg: np.ndarray
    dec_deg: np.ndarray
    is_catalogue: np.ndarray

    @property
    def pixel_scale_arcsec(self) -> float:
        """Plate scale (″/px) of the solved WCS."""
        return self.solution.pixel_scale_arcsec

    def sigma_arcsec(self, config: PipelineConfig | None = None) -> np.ndarray:
        """Per-axis 1σ angular uncertainty (″) of every detection.

        Centroid error ``max(centroid_k / SNR, centroid_floor_px)`` (px, times the plate
        scale) combined in quadrature with the plate solution's own error at the detection
        (:meth:`eotrack.astro.astrometry.PlateSolution.position_error_arcsec`: the fit's
        covariance, larger where the matched stars do not reach). Detections given without
        SNR use ``initiator_sigma_px``.
        """
        cfg = PipelineConfig() if config is None else config
        c_px = np.where(np.isfinite(self.snr), cfg.centroid_k / np.maximum(self.snr, 1e-9),
                        cfg.initiator_sigma_px)
        c_px = np.maximum(c_px, cfg.centroid_floor_px)
        sol = self.solution
        plate = sol.position_error_arcsec(self.xy) if len(self.xy) else np.zeros(0)
        return np.hypot(c_px * self.pixel_scale_arcsec, plate)


# ------------------------------------------------------------------ per frame
_CAT_CACHE: dict[tuple[int, float], tuple[StarCatalog, StarCatalog]] = {}


def _bright(catalog: StarCatalog | None, max_mag: float) -> StarCatalog:
    """The catalogue cut at ``max_mag`` (cached per catalogue object)."""
    from eotrack.astro import load_catalog

    cat = load_catalog() if catalog is None else catalog
    key = (id(cat), float(max_mag))
    hit = _CAT_CACHE.get(key)
    if hit is not None and hit[0] is cat:
        return hit[1]
    sel = cat.select(cat.mag <= float(max_mag))
    if len(_CAT_CACHE) > 4:
        _CAT_CACHE.clear()
    _CAT_CACHE[key] = (cat, sel)   # keeps ``cat`` alive, so its id is not reused
    return sel


def star_trail_px(frame: Frame, mount: str = "staring") -> np.ndarray:
    """A star's displacement ``(dx, dy)`` (px) over ``frame``'s exposure, at the frame's centre,
    from its believed WCS: for a ``"staring"`` (Earth-fixed) mount the sidereal drift
    ``ω⊕ × exposure`` along the RA axis (≈ 15″/s × cos δ), for a ``"sidereal"`` one zero."""
    if not isinstance(frame, Frame):
        raise TypeError(f"frame must be a Frame, got {type(frame).__name__}")
    if check_choice(mount, "mount", ("staring", "sidereal")) == "sidereal":
        return np.zeros(2)
    ny, nx = frame.shape
    w = frame.wcs_guess
    ra, dec = w.wcs_pix2world([[(nx - 1) / 2.0, (ny - 1) / 2.0]], 0)[0]
    half = np.degrees(_EARTH_RATE_RAD_S * frame.exposure_s / 2.0)
    p = w.wcs_world2pix([[ra - half, dec], [ra + half, dec]], 0)
    return np.asarray(p[1] - p[0], float)


def cross_trail_psf_sigma(image: Any, xy: Any, trail_px: Any, *,
                          background: BackgroundConfig | None = None, window: float = 2.0,
                          n_stars: int = 50, default: float = 1.0) -> float:
    """PSF σ (px) measured across the star trails of a frame.

    A Gaussian PSF drawn along a straight trail is separable in the (along, across) axes, and
    its profile across the trail is the PSF itself, whatever the trail's length. For each of
    the brightest detections (``xy``, brightest first; the first tenth skipped — saturation —,
    then ``n_stars``) the background-subtracted stamp is weighted by a Gaussian window of σ
    ``window`` across the trail and a box of the trail's length + 2 px along it; the windowed
    second moment across, ``m``, gives ``σ² = m w² / (w² − m)`` (the estimate of
    :func:`eotrack.imaging.estimate_psf_sigma`, along one axis). The median over the stars is
    returned, clipped to 0.4–6 px (``default`` when no star gives a valid moment).
    """
    img = np.asarray(image, float)
    if img.ndim != 2:
        raise ValueError(f"image must be 2-D, got shape {img.shape}")
    p = as_points(xy, "xy")
    t = np.asarray(trail_px, float).reshape(-1)
    if t.shape != (2,) or not np.all(np.isfinite(t)):
        raise ValueError(f"trail_px must be a finite (dx, dy), got {trail_px!r}")
    w = check_positive(window, "window")
    n = check_int(n_stars, "n_stars", min_value=1)
    length = float(np.hypot(*t))
    if length == 0 or len(p) == 0:
        return float(default)
    ua = t / length
    up = np.array([-ua[1], ua[0]])
    sub = img - background_map(img, background).back
    half = length / 2 + 1.0
    h = int(np.ceil(half + 3 * w))
    H, W = img.shape
    pick = p[len(p) // 10: len(p) // 10 + n]
    sig2 = []
    off = np.arange(-h, h + 1)
    for x, y in pick:
        ix, iy = int(np.rint(x)), int(np.rint(y))
        if ix - h < 0 or iy - h < 0 or ix + h >= W or iy + h >= H:
            continue                                  # a stamp cut by the edge
        st = np.maximum(sub[iy - h: iy + h + 1, ix - h: ix + h + 1], 0.0)
        dx = (ix + off)[None, :] - x
        dy = (iy + off)[:, None] - y
        a = dx * ua[0] + dy * ua[1]
        q = dx * up[0] + dy * up[1]
        box = np.abs(a) <= half
        c = 0.0
        for _ in range(3):                            # re-centre across the trail
            wt = st * box * np.exp(-(q - c) ** 2 / (2 * w * w))
            s = wt.sum()
            if s <= 0:
                break
            c = float((wt * q).sum() / s)
        wt = st * box * np.exp(-(q - c) ** 2 / (2 * w * w))
        s = wt.sum()
        if s <= 0:
            continue
        m = float((wt * (q - c) ** 2).sum() / s)
        if 0 < m < 0.95 * w * w:
            sig2.append(m * w * w / (w * w - m))
    if not sig2:
        return float(default)
    return float(np.clip(np.sqrt(np.median(sig2)), 0.4, 6.0))


def extract_frame(frame: Frame, config: PipelineConfig | None = None
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Detections ``(xy (n, 2), flux, snr)`` of one frame, brightest first.

    The point extractor (:func:`eotrack.imaging.extract_stars`, ``config.sky``) finds every
    source. When the stars trail at least ``config.trail_min_px`` over the exposure
    (:func:`star_trail_px`), the trails found by
    :func:`eotrack.imaging.trails.extract_trailed` (a trail's centroid is its midpoint, the
    star at mid-exposure) replace the point detections inside their footprints (a trail's
    length plus 2 PSF σ along it, 2 σ across); point detections elsewhere (the targets) stay.
    """
    cfg = PipelineConfig() if config is None else config
    if not isinstance(cfg, PipelineConfig):
        raise TypeError(f"config must be a PipelineConfig, got {type(cfg).__name__}")
    trail = star_trail_px(frame, cfg.mount)
    length = float(np.hypot(*trail))
    sky = cfg.sky
    res = extract_stars(frame.image, config=sky, return_info=True)
    if length >= cfg.trail_min_px and sky.psf_sigma is None:
        # the point extractor's own PSF estimate (second moments of the brightest detections)
        # is inflated by the trails (≈ 1.8 px for a 1-px PSF and 6-px trails), and a matched
        # filter that wide loses faint point targets: measure the width across the trails
        # and extract again with it
        sky = replace(sky, psf_sigma=cross_trail_psf_sigma(frame.image, res.xy, trail,
                                                           background=sky.background))
        res = extract_stars(frame.image, config=sky, return_info=True)
    xy, flux, snr = res.xy.reshape(-1, 2), res.flux, res.snr
    if length < cfg.trail_min_px:
        return xy, flux, snr
    # trailed stars: their trail-aware midpoints replace whatever the point extractor made of
    # them (a point detection inside a trail's footprint); the point detections elsewhere
    # (targets, and faint stars the trail filter did not take) are kept as they are
    sig = float(sky.psf_sigma)
    tr = extract_trailed(frame.image, trail, psf_sigma=sig, thresh=sky.thresh,
                         background=sky.background)
    txy = tr.xy[tr.is_trail]
    if len(txy) and len(xy):
        u_ = trail / length
        d = xy[:, None, :] - txy[None, :, :]
        along = np.abs(d @ u_)
        perp = np.abs(d @ np.array([-u_[1], u_[0]]))
        on = ((along <= length / 2 + 2 * sig) & (perp <= 2 * sig)).any(axis=1)
        xy, flux, snr = xy[~on], flux[~on], snr[~on]
    xy = np.concatenate([txy, xy])
    flux = np.concatenate([tr.flux[tr.is_trail], flux])
    snr = np.concatenate([tr.snr[tr.is_trail], snr])
    order = np.argsort(-flux, kind="stable")
    if sky.max_sources is not None:
        order = order[: sky.max_sources]
    return xy[order], flux[order], snr[order]


def measure_frame(frame: Frame, catalog: StarCatalog | None = None, *,
                  config: PipelineConfig | None = None,
                  detections: tuple[Any, Any] | None = None) -> FrameMeasurement:
    """Extraction and plate solution of one frame.

    Parameters
    ----------
    frame
        The frame (its ``wcs_guess`` is the believed pointing).
    catalog
        Star catalogue (default :func:`eotrack.astro.load_catalog`), cut at
        ``config.catalog_mag`` and moved to the frame's epoch by proper motion.
    config
        Settings (default :class:`PipelineConfig`).
    detections
        ``(xy, flux)`` or ``(xy, flux, snr)`` already extracted (then ``frame.image`` is not
        searched); ``xy`` ``(n, 2)`` px, brightest first. Default :func:`extract_frame`
        (trail-aware when the stars trail ≥ ``config.trail_min_px``).

    Returns
    -------
    FrameMeasurement

    Raises
    ------
    PlateSolveError
        Stage ``astrometry`` (its ``reason``: too few stars — clouds —, no consistent match…).
    ValueError, TypeError
        Bad arguments.
    """
    if not isinstance(frame, Frame):
        raise TypeError(f"frame must be a Frame, got {type(frame).__name__}")
    cfg = PipelineConfig() if config is None else config
    if not isinstance(cfg, PipelineConfig):
        raise TypeError(f"config must be a PipelineConfig, got {type(cfg).__name__}")
    if detections is None:
        xy, flux, snr = extract_frame(frame, cfg)
    else:
        if not isinstance(detections, (tuple, list)) or len(detections) not in (2, 3):
            raise TypeError("detections must be (xy, flux) or (xy, flux, snr)")
        xy = as_points(detections[0], "detections[0] (xy)")
        flux = np.asarray(detections[1], float).reshape(-1)
        snr = (np.asarray(detections[2], float).reshape(-1) if len(detections) == 3
               else np.full(len(xy), np.nan))
        if len(flux) != len(xy) or len(snr) != len(xy):
            raise ValueError(f"detections: xy has {len(xy)} rows but flux/snr have "
                             f"{len(flux)}/{len(snr)}")
    ny, nx = frame.shape
    scale = pixel_scale_arcsec(frame.wcs_guess)
    margin = cfg.max_offset_arcsec / scale + 2 * cfg.match_radius_px
    cat = catalog_in_field(frame.wcs_guess, (ny, nx), max_mag=None, jyear=float(frame.time.jyear),
                           margin_px=margin, catalog=_bright(catalog, cfg.catalog_mag))
    sol = solve_plate(xy, np.column_stack([cat.ra_deg, cat.dec_deg]), frame.wcs_guess,
                      image_shape=(ny, nx), match_radius_px=cfg.match_radius_px,
                      max_offset_arcsec=cfg.max_offset_arcsec, max_roll_deg=cfg.max_roll_deg,
                      max_scale_error=cfg.max_scale_error, min_stars=cfg.min_stars,
                      clip_sigma=cfg.clip_sigma)
    ra, dec = sol.pixel_to_radec(xy)
    is_cat = np.zeros(len(xy), bool)
    if len(xy):
        pred = sol.radec_to_pixel(cat.ra_deg, cat.dec_deg)
        d, _ = cKDTree(pred).query(xy)
        is_cat = d < cfg.star_radius_px
        is_cat[sol.det_index] = True
    return FrameMeasurement(frame, xy, flux, snr, sol, ra, dec, is_cat)


# ------------------------------------------------------------------ per sequence
def _unit(ra_deg: np.ndarray, dec_deg: np.ndarray) -> np.ndarray:
    ra, de = np.radians(ra_deg), np.radians(dec_deg)
    return np.stack([np.cos(de) * np.cos(ra), np.cos(de) * np.sin(ra), np.sin(de)], -1
                    ).reshape(-1, 3)


def target_border_px(frame: Frame, config: PipelineConfig | None = None) -> np.ndarray:
    """Border ``(bx, by)`` (px) of ``frame`` in which no detection is a target candidate.

    A star whose trail is cut by the frame's edge is centroided off its mid-exposure position,
    so the neighbouring frame's detection of it is not at the same RA/Dec and the separation
    would keep it as a candidate; lined up along the edge, such fragments form false tracks
    (at 5″/px and 1,600 e⁻/px, 30 in 6 bursts, all within 4 px of the edge). The border is
    half the star trail (:func:`star_trail_px`) plus 3 PSF σ per axis (``config.sky.psf_sigma``,
    1 px if None), and at least 1 px.
    """
    cfg = PipelineConfig() if config is None else config
    t = np.abs(star_trail_px(frame, cfg.mount))
    sig = cfg.sky.psf_sigma or 1.0
    if float(np.hypot(*t)) < cfg.trail_min_px:
        return np.ones(2)
    return np.maximum(t / 2 + 3 * sig, 1.0)


def separate_targets(measured: Sequence[FrameMeasurement], *, radius_px: float = 2.5,
                     border_px: Any = 1.0) -> list[np.ndarray]:
    """Target-candidate masks of the frames of one sequence (time order).

    A detection is a star if it is a catalogue star (``is_catalogue``) or if a detection of
    the previous or next frame lies at the same RA/Dec (within ``radius_px`` times the plate
    scale — uncatalogued faint stars). A detection whose sky position falls outside both
    neighbouring frames cannot be tested (a star entering or leaving the field) and is not a
    candidate either, nor one within ``border_px`` (a number or ``(bx, by)``;
    :func:`target_border_px` for trailed stars) of its own frame's edge. Everything else is a
    target candidate.
    """
    r = check_positive(radius_px, "radius_px")
    bxy = np.broadcast_to(np.asarray(border_px, float), (2,))
    if not np.all(np.isfinite(bxy) & (bxy >= 0)):
        raise ValueError(f"border_px must be ≥ 0 (a number or (bx, by)), got {border_px!r}")
    n = len(measured)
    units = [_unit(m.ra_deg, m.dec_deg) for m in measured]
    trees = [cKDTree(v) if len(v) else None for v in units]
    out = []
    for k, m in enumerate(measured):
        nd = len(m.xy)
        fixed = np.zeros(nd, bool)
        testable = np.zeros(nd, bool)
        for j in (k - 1, k + 1):
            if not 0 <= j < n or nd == 0:
                continue
            mj = measured[j]
            ny, nx = mj.frame.shape
            p = mj.solution.radec_to_pixel(m.ra_deg, m.dec_deg)
            inside = (p[:, 0] > 1.0) & (p[:, 0] < nx - 2.0) & (p[:, 1] > 1.0) & \
                (p[:, 1] < ny - 2.0)
            testable |= inside
            if trees[j] is not None:
                chord = 2 * np.sin(np.radians(r * mj.pixel_scale_arcsec / ARCSEC_PER_DEG) / 2)
                d, _ = trees[j].query(units[k])
                fixed |= inside & (d < chord)
        ny0, nx0 = m.frame.shape
        inner = (m.xy[:, 0] >= bxy[0]) & (m.xy[:, 0] <= nx0 - 1 - bxy[0]) & \
            (m.xy[:, 1] >= bxy[1]) & (m.xy[:, 1] <= ny0 - 1 - bxy[1]) if nd else \
            np.zeros(0, bool)
        out.append(~(m.is_catalogue | fixed) & testable & inner)
    return out


def default_initiator(pixel_scale_arcsec: float, n_frames: int,
                      config: PipelineConfig | None = None) -> ModifiedHoughInitiator:
    """The modified Hough initiator with the capstone's settings and a velocity gate in ″/s.

    ``v_max = max_rate_arcsec_s / pixel_scale_arcsec`` px/s (``d_v = v_max / 10``), 3-px
    cells of ρ, 10° of θ, ``m = min(n_frames, 4)`` (3 of 4 hits), no acceleration search.
    """
    cfg = PipelineConfig() if config is None else config
    scale = check_positive(pixel_scale_arcsec, "pixel_scale_arcsec")
    n = check_int(n_frames, "n_frames", min_value=4)
    v_max = cfg.max_rate_arcsec_s / scale
    return ModifiedHoughInitiator(d_rho=3.0, d_theta_deg=10.0, d_v=v_max / 10.0, v_min=0.0,
                                  v_max=v_max, m=min(n, 4), handoff_gate_px=3.0,
                                  sigma_px=cfg.initiator_sigma_px, accel_px_s2=0.0)


def initiate_tracks(measured: Sequence[FrameMeasurement], *, config: PipelineConfig | None = None,
                    initiator: Any = None) -> list[list[tuple[int, int]]]:
    """Confirmed tracks of one sequence (frames of one station, in time order).

    Returns
    -------
    list of list of (frame_index, detection_index)
        Per track, its hits; ``detection_index`` indexes ``measured[frame_index].xy``.

    Raises
    ------
    ValueError
        Fewer than 4 frames (the verified initiator's window), or times not increasing.
    """
    cfg = PipelineConfig() if config is None else config
    if len(measured) < 4:
        raise ValueError(f"initiation needs at least 4 frames of a sequence, got "
                         f"{len(measured)}")
    cand = separate_targets(measured, radius_px=cfg.star_radius_px,
                            border_px=target_border_px(measured[0].frame, cfg))
    t0 = measured[0].frame.time
    times = [float((m.frame.time - t0).to_value(u.s)) for m in measured]
    idx = [np.flatnonzero(c) for c in cand]
    frames = [(t, m.xy[i]) for t, m, i in zip(times, measured, idx)]
    if initiator is None:
        scale = float(np.median([m.pixel_scale_arcsec for m in measured]))
        initiator = default_initiator(scale, len(measured), cfg)
    if not hasattr(initiator, "initiate"):
        raise TypeError(f"initiator must have an initiate(frames) method, got "
                        f"{type(initiator).__name__}")
    return [[(int(f), int(idx[f][d])) for f, d in tr.hits] for tr in initiator.initiate(frames)]


# ------------------------------------------------------------------ the run
def _sequences(frames: list[Frame], max_gap_s: float) -> list[list[int]]:
    """Indices of the frames of each (station, sequence), in time order."""
    order = sorted(range(len(frames)), key=lambda i: (frames[i].station,
                                                      str(frames[i].sequence),
                                                      frames[i].time.jd1, frames[i].time.jd2))
    groups: list[list[int]] = []
    last = None
    for i in order:
        f = frames[i]
        key = (f.station, f.sequence)
        if last is not None and key == (frames[last].station, frames[last].sequence) and (
                f.sequence is not None
                or (f.time - frames[last].time).to_value(u.s) <= max_gap_s):
            groups[-1].append(i)
        else:
            groups.append([i])
        last = i
    return groups


def _skip(log: list[dict], frame: str, file: str | None, stage: str, reason: str) -> None:
    log.append({"frame": frame, "file": file or "", "stage": stage, "reason": reason})
    where = f"frame '{frame}'" + (f" ({file})" if file else "")
    warnings.warn(f"{where}: stage '{stage}': {reason} — frame skipped",
                  FrameSkippedWarning, stacklevel=3)


def measure_frames(frames: Sequence[Frame | str | PathLike], catalog: StarCatalog | None = None,
                   *, config: PipelineConfig | None = None, initiator: Any = None) -> Table:
    """Run extraction → astrometry → separation → initiation over frames; the measurements.

    Parameters
    ----------
    frames
        :class:`Frame` objects or FITS paths (read with :func:`eotrack.pipeline.read_fits`),
        of one or several stations and sequences, in any order.
    catalog
        Star catalogue (default :func:`eotrack.astro.load_catalog`).
    config
        Settings (default :class:`PipelineConfig`).
    initiator
        Anything with ``initiate(frames)`` (default :func:`default_initiator` per sequence).

    Returns
    -------
    astropy.table.Table
        One row per detection of a confirmed track: ``time`` (Time, UTC, mid-exposure),
        ``ra``, ``dec`` (deg, the catalogue's frame: ICRS astrometric), ``sigma_arcsec``
        (per-axis 1σ, see :meth:`FrameMeasurement.sigma_arcsec`), ``station``, ``frame``
        (frame id), ``track`` (int, unique in the run), ``x``, ``y`` (px), ``sequence``.
        ``meta``: ``"skipped"`` (frames left out: frame, file, stage, reason) and
        ``"plate_solutions"`` (per solved frame: frame, n_matched, rms_arcsec,
        pixel_scale_arcsec). Write it with ``table.write("m.ecsv")``.

    Warns
    -----
    FrameSkippedWarning
        One per frame left out (stage ``read``, ``extraction`` or ``astrometry``) and per
        sequence too short to initiate (stage ``initiation``).
    """
    cfg = PipelineConfig() if config is None else config
    if not isinstance(cfg, PipelineConfig):
        raise TypeError(f"config must be a PipelineConfig, got {type(cfg).__name__}")
    if isinstance(frames, (str, PathLike, Frame)):
        frames = [frames]
    if not isinstance(frames, Sequence):
        raise TypeError(f"frames must be a sequence of Frame objects or FITS paths, got "
                        f"{type(frames).__name__}")
    skipped: list[dict] = []
    good: list[Frame] = []
    for i, f in enumerate(frames):
        if isinstance(f, Frame):
            good.append(f)
        elif isinstance(f, (str, PathLike)):
            try:
                good.extend(read_fits([f]))
            except (FitsFrameError, FileNotFoundError) as exc:
                reason = str(exc)
                if reason.startswith(f"{f}: "):      # the messages start with the path
                    reason = reason[len(f"{f}: "):]
                _skip(skipped, Path(f).stem, str(f), "read", reason)
        else:
            raise TypeError(f"frames[{i}] must be a Frame or a FITS path, got "
                            f"{type(f).__name__}")
    ids = [f.frame_id for f in good]
    if len(set(ids)) != len(ids):
        dup = sorted({x for x in ids if ids.count(x) > 1})
        raise ValueError(f"frame ids must be unique within a run; repeated: {dup}")
    solved: dict[int, FrameMeasurement] = {}
    solutions = []
    for i, f in enumerate(good):
        stage = "extraction"
        try:
            det = extract_frame(f, cfg)
            stage = "astrometry"
            m = measure_frame(f, catalog, config=cfg, detections=det)
        except PlateSolveError as exc:
            _skip(skipped, f.frame_id, f.path, "astrometry", f"{exc} [{exc.reason}]")
            continue
        except ValueError as exc:
            _skip(skipped, f.frame_id, f.path, stage, str(exc))
            continue
        solved[i] = m
        solutions.append({"frame": f.frame_id, "n_matched": int(m.solution.n_matched),
                          "rms_arcsec": float(m.solution.rms_arcsec),
                          "pixel_scale_arcsec": float(m.pixel_scale_arcsec)})
    rows: dict[str, list] = {c: [] for c, _ in MEASUREMENT_COLUMNS}
    times: list[Time] = []
    track_id = 0
    for grp in _sequences(good, cfg.max_gap_s):
        ms = [solved[i] for i in grp if i in solved]
        if not ms:
            continue
        if len(ms) < 4:
            f0 = ms[0].frame
            _skip(skipped, ",".join(m.frame.frame_id for m in ms), None, "initiation",
                  f"sequence {f0.sequence!r} of station {f0.station!r} has {len(ms)} solved "
                  "frame(s); initiation needs at least 4")
            continue
        for hits in initiate_tracks(ms, config=cfg, initiator=initiator):
            for fi, di in hits:
                m = ms[fi]
                sig = m.sigma_arcsec(cfg)
                times.append(m.frame.time)
                rows["ra"].append(float(m.ra_deg[di]))
                rows["dec"].append(float(m.dec_deg[di]))
                rows["sigma_arcsec"].append(float(sig[di]))
                rows["station"].append(m.frame.station)
                rows["frame"].append(m.frame.frame_id)
                rows["track"].append(track_id)
                rows["x"].append(float(m.xy[di, 0]))
                rows["y"].append(float(m.xy[di, 1]))
                rows["sequence"].append("" if m.frame.sequence is None else m.frame.sequence)
            track_id += 1
    rows["time"] = Time(times, scale="utc") if times else Time([], format="jd", scale="utc")
    tab = Table()
    for c, unit in MEASUREMENT_COLUMNS:
        data = rows[c]
        if c in ("station", "frame", "sequence"):
            data = np.array(data, dtype=str)
        elif c == "track":
            data = np.array(data, dtype=np.int64)
        elif c != "time":
            data = np.array(data, dtype=float)
        tab[c] = data if unit is None else u.Quantity(data, unit)
    tab.meta["skipped"] = skipped
    tab.meta["plate_solutions"] = solutions
    return tab
