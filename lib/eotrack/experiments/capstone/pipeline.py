"""The chain: frames → extraction → astrometry → star/target separation → initiation →
association → triangulation → orbit and prediction through the eclipse, and its error budget.

The frames are rendered with the TRUE camera attitude; everything after rendering sees only the
mount's BELIEVED pointing and solves each frame's plate from its stars
(:func:`eotrack.pipeline.measure_frame`: extraction, then
:func:`eotrack.astro.astrometry.solve_plate`). The true attitude is used again only to score.

Each burst (one station, one field, one visit) is one seeded *trial* of
:class:`eotrack.montecarlo.TrialRunner`: the same code runs serially, on local processes or on a
Dask cluster, with bit-identical results (trial ``i`` always gets the same generator).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np
import pandas as pd
from astropy import units as u
from scipy.stats import chi2, norm

from eotrack.geometry import (
    associate,
    epipolar_distances,
    fundamental_from_poses,
    pixel_rays,
    project_directions,
    triangulate_two_rays,
)
from eotrack.imaging import (
    BackgroundConfig,
    SkyConfig,
    render_gaussian_spots,
    star_count_slope,
    synthetic_faint_stars,
)
from eotrack.montecarlo import TrialRunner
from eotrack.tracking.initiation import ModifiedHoughInitiator
from eotrack.validation import check_positive

from .scenario import (
    ARCSEC_PER_RAD,
    EARTH_RATE_RAD_S,
    CapstoneConfig,
    NightPlan,
    camera_matrix,
    expected_field_stars,
    make_plan,
)

__all__ = [
    "PREDICTORS",
    "SKY_LEVELS",
    "BurstResult",
    "NightResult",
    "associate_tracklets",
    "burst_catalogue",
    "burst_index",
    "eclipse_check",
    "eclipse_status",
    "epipolar_gate_px",
    "error_budget",
    "expected_completeness",
    "expected_rates",
    "expected_ray_sigma_px",
    "expected_recall",
    "frame_id",
    "hypothesis_count_study",
    "measured_epipolar_sigma_px",
    "noise_sweep",
    "observe_burst",
    "paired_orbit_curve",
    "paired_series_rms",
    "pipeline_config",
    "predict_through_eclipse",
    "predicted_false_association",
    "predictor_isolation",
    "quick_config",
    "range_error_km",
    "ray_error_split",
    "render_frame",
    "run_night",
    "scorecard",
    "seed_stability",
    "sidereal_drift_px",
    "sigma_reconciliation",
    "sky_config",
    "target_peak_snr",
    "triangulate_pairs",
    "velocity_gate",
]

#: The robust predictors of notebook 01 compared through the eclipse.
PREDICTORS = ("lsq", "ransac", "wransac")
MATCH_PX = 2.5      # catalogue / sidereal-partner match radius (px)
TRUTH_PX = 2.0      # a detection within this of a true object is that object (scoring only)
CORRELATE_PX = 6.0  # a tracklet within this of an object's TLE prediction is that object
GATE_ALPHA = 0.01   # the epipolar gate: a true pair falls outside it with probability α
RATE_MARGIN = 1.5   # velocity gate = margin × the fastest expected rate (and ≥ 2 px per burst)
BLEND_SIGMA = 5.0   # TLE separations 3–5 PSF σ: resolved, but a warning names the frame


def burst_index(rng: np.random.Generator) -> int:
    """Index of the trial a runner's generator belongs to (its ``SeedSequence`` spawn key).

    :meth:`eotrack.montecarlo.TrialRunner.map` gives trial ``i`` the generator spawned ``i``-th
    from the root seed, on every backend; the spawn key carries ``i``.
    """
    key = rng.bit_generator.seed_seq.spawn_key
    if not key:
        raise ValueError("rng was not spawned by a TrialRunner (empty spawn key)")
    return int(key[-1])


def frame_id(plan: NightPlan, b, k: int) -> str:
    """A frame's name: station, visit, field and frame, e.g. ``Socorro-v012-28626-k3``."""
    st = plan.config.stations[b.station].name.split()[0]
    return f"{st}-v{b.visit:03d}-{plan.names[b.obj]}-k{k}"


@dataclass
class BurstResult:
    """What one burst produced (and its truth bookkeeping).

    Attributes
    ----------
    station, obj, visit, objs
        Burst identity (``obj`` the field object, ``objs`` every object in the field).
    n_detections, n_catalogue, n_candidates, n_false_candidates
        Per-frame counts: detections, detections matched to catalogue stars by the plate
        solution, target candidates left after separation, candidates that are no object.
    target_lit, target_detected, target_kept
        ``(n_objs, n_frames)``: object sunlit in the field; detected by the extractor; kept as
        a candidate.
    solved
        Per frame: the plate solution succeeded.
    plate_rms_arcsec, plate_n_matched
        Per frame: RMS residual of the matched stars and their number (NaN / 0 if unsolved).
    plate_err_arcsec
        Per frame: TRUE error of the solved WCS at the field objects' true pixels (mean over
        the objects; scoring only).
    plate_err_model_arcsec
        Per frame: the solution's OWN error model there (2-D RMS of
        :meth:`~eotrack.astro.astrometry.PlateSolution.position_error_arcsec` at the objects'
        TLE-predicted pixels) — what the chain believes its plate error is.
    cams
        Per solved frame ``k``: ``(K, R)`` of the plate solution (:func:`camera_from_wcs`).
    failures
        ``(frame, stage, reason)`` of every frame left out or object pair flagged.
    gospa
        Initiation GOSPA of the burst (:func:`eotrack.tracking.metrics.initiation_metrics`).
    v_max_px_s
        The velocity gate used (px/s).
    tracks
        One dict per confirmed track: ``frames`` (indices), ``xy`` ``(k, 2)``, ``dirs`` (unit
        GCRS directions from the plate solution ``(k, 3)``), ``true_obj`` (object index or −1,
        scoring), ``cat_obj`` (the object whose TLE prediction it correlates with, or −1),
        ``ray_err_arcsec`` (true angle error per hit, scoring).
    """

    station: int
    obj: int
    visit: int
    objs: tuple
    n_detections: np.ndarray
    n_catalogue: np.ndarray
    n_candidates: np.ndarray
    n_false_candidates: np.ndarray
    target_lit: np.ndarray
    target_detected: np.ndarray
    target_kept: np.ndarray
    solved: np.ndarray
    plate_rms_arcsec: np.ndarray
    plate_n_matched: np.ndarray
    plate_err_arcsec: np.ndarray
    cams: dict = field(default_factory=dict)
    failures: list = field(default_factory=list)
    gospa: dict = field(default_factory=dict)
    v_max_px_s: float = np.nan
    tracks: list = field(default_factory=list)
    plate_err_model_arcsec: np.ndarray = field(default_factory=lambda: np.zeros(0))


@lru_cache(maxsize=8)
def _catalogue_band(dec_deg: int, max_mag: float, jyear: float):
    """Catalogue stars brighter than ``max_mag`` within 10° of declination ``dec_deg`` (at
    epoch ``jyear``), as a :class:`~eotrack.astro.StarCatalog`."""
    from eotrack.astro import load_catalog

    cat = load_catalog()
    cat = cat.select(slice(0, int(np.searchsorted(cat.mag, float(max_mag), side="right"))))
    cat = cat.select(np.abs(cat.dec_deg - dec_deg) < 10.0).at_epoch(jyear)
    return cat, cat.unit_vectors()


def _band_for(plan: NightPlan, boresight: np.ndarray):
    """The catalogue band around ``boresight`` and its unit vectors (cached)."""
    dec0 = round(np.degrees(np.arcsin(np.clip(boresight[2], -1, 1))))
    return _catalogue_band(dec0, plan.config.catalogue_mag, round(float(plan.t0.jyear), 2))


def _stars_for_burst(rng, plan: NightPlan, b) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """RENDERING: unit directions, magnitudes and catalogue flags of the stars around the
    burst's true field.

    Catalogue stars (G ≤ ``catalogue_mag``) within 1.6 fields of the true boresight, plus
    synthetic fainter stars following the catalogue's own count slope (uncatalogued: only their
    motion marks them as stars).
    """
    cfg = plan.config
    bore = b.R[0][2]
    cat_b, u_ = _band_for(plan, bore)
    m = cat_b.mag
    cosang = u_ @ bore
    radius = cfg.fov_deg * 1.6
    near = cosang >= np.cos(np.radians(radius))
    wide = cosang >= np.cos(np.radians(8.0))
    a, slope = star_count_slope(m[wide], cfg.catalogue_mag - 3.0, cfg.catalogue_mag)
    cone_sr = 2 * np.pi * (1 - np.cos(np.radians(8.0)))
    # a square of 2 fields plus the burst's sidereal drift (60 px per frame at 5″/px)
    drift = sidereal_drift_px(cfg) * (cfg.burst_frames - 1)
    n_pix = int(np.ceil(2 * cfg.size_px + 2 * drift))
    K = camera_matrix(cfg)
    Kw = K.copy()
    Kw[0, 2] = Kw[1, 2] = (n_pix - 1) / 2.0
    img_sr = (n_pix / K[0, 0]) ** 2
    xy_f, mag_f = synthetic_faint_stars(rng, a, slope, cfg.catalogue_mag, cfg.render_limit,
                                        (n_pix, n_pix), area_fraction=img_sr / cone_sr)
    # the synthetic sky is laid out around the BELIEVED boresight (a 2 × 2 field square, widened
    # by the burst's drift, that covers the true field for pointing errors up to half a field
    # in every frame of the burst), so the chain's catalogue
    # does not depend on the true attitude
    dirs_f = pixel_rays(xy_f, Kw, b.R_believed[0]) if len(xy_f) else np.zeros((0, 3))
    dirs = np.concatenate([u_[near], dirs_f])
    mag = np.concatenate([m[near], mag_f])
    cat = np.concatenate([np.ones(near.sum(), bool), mag_f <= cfg.astrometry_limit])
    return dirs, mag, cat


def burst_catalogue(plan: NightPlan, b, dirs: np.ndarray, mag: np.ndarray, cat: np.ndarray):
    """The chain's catalogue for a burst: the real Gaia band around the BELIEVED boresight plus
    the synthetic stars brighter than ``astrometry_limit`` (standing in for the deeper Gaia DR3;
    see :class:`CapstoneConfig`), brightest first, as a :class:`~eotrack.astro.StarCatalog`."""
    from eotrack.astro.catalog import StarCatalog

    bore = b.R_believed[0][2]
    band, u_ = _band_for(plan, bore)
    # the believed field and more (2 fields: pointing errors of many arcminutes stay inside)
    band = band.select(u_ @ bore >= np.cos(np.radians(2.0 * plan.config.fov_deg)))
    n_real = int(np.sum(cat)) - int(np.sum(cat & (mag > plan.config.catalogue_mag)))
    syn = cat.copy()
    syn[:n_real] = False
    d = dirs[syn]
    ra = np.degrees(np.arctan2(d[:, 1], d[:, 0])) % 360.0
    dec = np.degrees(np.arcsin(np.clip(d[:, 2], -1, 1)))
    z = np.zeros(len(d))
    allc = StarCatalog(np.r_[band.source_id, np.full(len(d), -1, band.source_id.dtype)],
                       np.r_[band.ra_deg, ra], np.r_[band.dec_deg, dec], np.r_[band.mag, mag[syn]],
                       np.r_[band.pmra_mas_yr, z], np.r_[band.pmdec_mas_yr, z])
    return allc.select(np.argsort(allc.mag, kind="stable"))


def render_frame(rng, plan: NightPlan, b, k: int, dirs: np.ndarray, mag: np.ndarray
                 ) -> np.ndarray:
    """RENDERING (true attitude): one frame (e⁻) — trailed stars, every field object, sky with
    a gradient, Poisson + read noise; a clouded frame (``config.cloud_frames``) passes only
    ``config.cloud_transmission`` of the light of stars and objects."""
    cfg = plan.config
    K = camera_matrix(cfg)
    n = cfg.size_px
    trans = cfg.cloud_transmission if (b.station, b.obj, b.visit, k) in cfg.cloud_frames else 1.0
    mid = project_directions(dirs, K, b.R[k])
    end = project_directions(dirs, K, b.R_end[k])
    start = 2 * mid - end
    flux = 10 ** (-0.4 * (mag - cfg.zero_point_mag)) * trans
    trail = float(np.max(np.hypot(*(end - mid).T))) * 2 if len(mid) else 0.0
    sub = max(3, int(np.ceil(trail / cfg.psf_sigma_px)) + 1)  # spots ≤ 1 PSF σ apart
    w = np.linspace(0, 1, sub)
    pts = (start[None] + w[:, None, None] * (end - start)[None]).reshape(-1, 2)
    fl = np.tile(flux / sub, sub)
    ok = (pts[:, 0] > -8) & (pts[:, 0] < n + 8) & (pts[:, 1] > -8) & (pts[:, 1] < n + 8)
    yy, xx = np.mgrid[0:n, 0:n]
    img = cfg.sky_e * (1.0 + cfg.gradient * (xx + 0.5 * yy) / n)
    render_gaussian_spots((n, n), pts[ok], fl[ok], cfg.psf_sigma_px, out=img)
    lit = b.target_flux[:, k] > 0
    if lit.any():
        render_gaussian_spots((n, n), b.target_xy[lit, k], b.target_flux[lit, k] * trans,
                              cfg.psf_sigma_px, out=img)
    img = rng.poisson(img).astype(float)
    img += rng.normal(0.0, cfg.read_noise_e, img.shape)
    return img


def sky_config(config: CapstoneConfig) -> SkyConfig:
    """The extractor's settings (notebook 05's sky extractor, 32-px background meshes)."""
    return SkyConfig(psf_sigma=config.psf_sigma_px, thresh=config.detect_sigma,
                     background=BackgroundConfig(mesh=32, filter_size=1))


def pipeline_config(config: CapstoneConfig, v_max_px_s: float):
    """The :class:`eotrack.pipeline.PipelineConfig` of the night's cameras."""
    from eotrack.pipeline import PipelineConfig

    return PipelineConfig(sky=sky_config(config), catalog_mag=config.astrometry_limit,
                          star_radius_px=MATCH_PX,
                          max_rate_arcsec_s=v_max_px_s * config.pixel_scale_arcsec)


# ------------------------------------------------------------------ velocity gate
#: rates per configuration, also filled from a plan a worker receives (no second plan there)
_RATES: dict[CapstoneConfig, tuple[np.ndarray, np.ndarray]] = {}


def _rates_cached(cfg: CapstoneConfig, plan: NightPlan | None = None
                  ) -> tuple[np.ndarray, np.ndarray]:
    hit = _RATES.get(cfg)
    if hit is None:
        if len(_RATES) > 16:
            _RATES.clear()
        hit = _RATES[cfg] = _rates_of(make_plan(cfg) if plan is None else plan)
    return hit


def _rates_of(plan: NightPlan) -> tuple[np.ndarray, np.ndarray]:
    cfg = plan.config
    t = plan.grid_s
    rates = np.zeros((len(cfg.stations), len(plan.names)))
    for s in range(len(cfg.stations)):
        for o in range(len(plan.names)):
            d = plan.tle_direction(o, s, t)  # the TLE prediction: known before the night
            # into the Earth-fixed (staring mount) frame: undo the Earth's rotation about z
            a = -EARTH_RATE_RAD_S * t
            c, s_ = np.cos(a), np.sin(a)
            e = np.stack([c * d[:, 0] - s_ * d[:, 1], s_ * d[:, 0] + c * d[:, 1], d[:, 2]], 1)
            vis = plan.elevation_deg[s, o] > cfg.min_elevation_deg
            step = np.degrees(np.arccos(np.clip(np.sum(e[1:] * e[:-1], 1), -1, 1))) * 3600
            r = step / np.diff(t)
            vis_g = np.interp(t[:-1], plan.visit_s, vis.astype(float)) > 0.5
            rates[s, o] = r[vis_g].max() if vis_g.any() else r.max()
    return rates, plan.elevation_deg


def expected_rates(config: CapstoneConfig | None = None) -> pd.DataFrame:
    """Each object's fastest apparent motion (″/s) in the GEO-staring (Earth-fixed) mount frame,
    from its TLE prediction, while it is above the elevation limit.

    A station-kept GEO object barely moves in that frame; an inclined one swings north–south
    at up to ≈ i·ω⊕ (about 3″/s at 11.4°). The velocity gate (:func:`velocity_gate`) is
    derived from these rates and the pixel scale — not from a fixed px/s.
    """
    cfg = _config(config)
    rates, _ = _rates_cached(cfg)
    return pd.DataFrame(rates, index=[s.name for s in cfg.stations],
                        columns=list(cfg.object_names))


def velocity_gate(config: CapstoneConfig | None = None) -> float:
    """The initiator's largest velocity (px/s): ``RATE_MARGIN`` × the fastest expected rate
    (:func:`expected_rates`) over the pixel scale, and at least 2 px over a burst (so that the
    centroid scatter of a still object stays inside the gate)."""
    cfg = _config(config)
    r = float(expected_rates(cfg).to_numpy().max())
    span = (cfg.burst_frames - 1) * cfg.frame_interval_s
    return max(RATE_MARGIN * r / cfg.pixel_scale_arcsec, 2.0 / span)


def _initiator(cfg: CapstoneConfig, v_max: float) -> ModifiedHoughInitiator:
    # Velocity gate 0 … v_max (px/s) from the objects' expected rates and the pixel scale
    # (velocity_gate); the Hough velocity cell d_v = v_max / 10. The objects' angular
    # acceleration over a burst of seconds is far below a pixel, so the constant-acceleration
    # search is off (accel_px_s2=0): its widened disc grows with the square of the burst's span
    # and would only admit chance tracks (and cost ~1 s per frame here).
    return ModifiedHoughInitiator(d_rho=3.0, d_theta_deg=10.0, d_v=v_max / 10.0, v_min=0.0,
                                  v_max=v_max, m=min(cfg.burst_frames, 4), handoff_gate_px=3.0,
                                  sigma_px=pipeline_config(cfg, v_max).initiator_sigma_px,
                                  accel_px_s2=0.0)


# ------------------------------------------------------------------ one burst
def observe_burst(rng: np.random.Generator, plan: NightPlan) -> BurstResult:
    """Trial function: render, then extract, solve the plate, separate and initiate one burst
    of ``plan`` (the burst is ``plan.bursts[burst_index(rng)]``).

    Only rendering and scoring read the true attitude ``b.R``; the chain gets the believed
    pointing ``b.R_believed`` as each frame's initial WCS. A frame whose extraction or plate
    solution fails is left out (its ``(frame, stage, reason)`` in ``failures``) and the burst
    goes on with the others.
    """
    from eotrack.astro.astrometry import PlateSolveError, camera_from_wcs, wcs_from_camera
    from eotrack.pipeline import (
        Frame,
        initiate_tracks,
        measure_frame,
        separate_targets,
        target_border_px,
    )
    from eotrack.tracking.metrics import initiation_metrics

    b = plan.bursts[burst_index(rng)]
    cfg = plan.config
    K = camera_matrix(cfg)
    n = cfg.size_px
    nf = cfg.burst_frames
    n_o = len(b.objs)
    _rates_cached(cfg, plan)   # the gate from this plan (a worker does not build its own)
    v_max = velocity_gate(cfg)
    pcfg = pipeline_config(cfg, v_max)
    dirs, mag, cat = _stars_for_burst(rng, plan, b)
    catalog = burst_catalogue(plan, b, dirs, mag, cat)
    measured, kept_k, failures = [], [], []
    times = plan.t0 + b.times_s * u.s
    for k in range(nf):
        img = render_frame(rng, plan, b, k, dirs, mag)
        fr = Frame(image=img, time=times[k],
                   exposure_s=cfg.exposure_s, station=cfg.stations[b.station].name,
                   wcs_guess=wcs_from_camera(K, b.R_believed[k], (n, n)),
                   frame_id=frame_id(plan, b, k), sequence=f"v{b.visit}")
        try:
            measured.append(measure_frame(fr, catalog, config=pcfg))
            kept_k.append(k)
        except PlateSolveError as e:
            failures.append((fr.frame_id, "astrometry", str(e)))
        except ValueError as e:  # measure_frame's other refusals (extraction, catalogue cut)
            failures.append((fr.frame_id, "extraction or catalogue", str(e)))
    kept_k = np.array(kept_k, int)
    solved = np.zeros(nf, bool)
    solved[kept_k] = True
    inside = np.all((b.target_xy > 2) & (b.target_xy < n - 3), axis=2)      # (n_o, nf)
    lit = inside & (b.target_flux > 0)
    n_det, n_cat, n_cand, n_false, n_match = (np.zeros(nf, int) for _ in range(5))
    rms = np.full(nf, np.nan)
    perr = np.full(nf, np.nan)
    perr_model = np.full(nf, np.nan)
    t_det = np.zeros((n_o, nf), bool)
    t_kept = np.zeros((n_o, nf), bool)
    cams = {}
    cand = separate_targets(measured, radius_px=MATCH_PX,
                            border_px=target_border_px(measured[0].frame, pcfg)) \
        if measured else []
    for i, (k, m) in enumerate(zip(kept_k, measured)):
        d = m.xy
        sol = m.solution
        n_det[k], n_cat[k] = len(d), int(m.is_catalogue.sum())
        n_cand[k], n_match[k], rms[k] = int(cand[i].sum()), sol.n_matched, sol.rms_arcsec
        # scoring: the solution's true error at the objects' true pixels
        true_dir = b.target_gcrs_km[:, k] - b.c_km[k]
        true_dir /= np.linalg.norm(true_dir, axis=1, keepdims=True)
        got = sol.pixel_to_directions(b.target_xy[:, k])
        perr[k] = float(np.mean(np.degrees(np.arccos(np.clip(np.sum(got * true_dir, 1),
                                                                -1, 1))) * 3600))
        near_any = np.zeros(len(d), bool)
        for j in range(n_o):
            near = (np.hypot(*(d - b.target_xy[j, k]).T) < TRUTH_PX) & lit[j, k] if len(d) \
                else np.zeros(0, bool)
            near_any |= near
            t_det[j, k], t_kept[j, k] = bool(near.any()), bool((near & cand[i]).any())
        n_false[k] = int((cand[i] & ~near_any).sum())
    # catalogue correlation: each object's TLE-predicted pixel through the solved plate
    pred_xy = {}
    for k, m in zip(kept_k, measured):
        dtle = np.stack([plan.tle_direction(o, b.station, b.times_s[k])[0] for o in b.objs])
        ra = np.degrees(np.arctan2(dtle[:, 1], dtle[:, 0])) % 360
        dec = np.degrees(np.arcsin(np.clip(dtle[:, 2], -1, 1)))
        pred_xy[int(k)] = m.solution.radec_to_pixel(ra, dec)
        # the solution's own error model at those pixels (2-D RMS = √2 × per axis)
        perr_model[k] = float(np.sqrt(np.mean(2 * m.solution.position_error_arcsec(
            pred_xy[int(k)]) ** 2)))
    # unresolved objects: TLE predictions closer than the PSF can separate, both predicted in
    # the field and sunlit (the station's own knowledge: TLEs through the solved plate and the
    # predicted shadow — not the truth)
    merged: dict[int, set[int]] = {}
    for k, pxy in pred_xy.items():
        in_f = np.all((pxy > 2) & (pxy < n - 3), axis=1)
        sunlit = np.array([np.round(np.interp(b.times_s[k], plan.grid_s, plan.grid_shadow[o]))
                           != 2 for o in b.objs])
        for a_ in range(n_o):
            for c_ in range(a_ + 1, n_o):
                sep = float(np.hypot(*(pxy[a_] - pxy[c_])))
                if BLEND_SIGMA * cfg.psf_sigma_px > sep >= 3.0 * cfg.psf_sigma_px and \
                        in_f[[a_, c_]].all() and sunlit[[a_, c_]].all():
                    failures.append((frame_id(plan, b, k), "association (warning)",
                                     f"objects {plan.names[b.objs[a_]]} and "
                                     f"{plan.names[b.objs[c_]]} are {sep:.2f} px apart (< "
                                     f"{BLEND_SIGMA:g} PSF σ): resolved, but their centroids "
                                     "may pull towards each other — tracklets kept"))
                if sep < 3.0 * cfg.psf_sigma_px and in_f[[a_, c_]].all() and \
                        sunlit[[a_, c_]].all():
                    merged.setdefault(int(k), set()).update((a_, c_))
                    failures.append((frame_id(plan, b, k), "association",
                                     f"objects {plan.names[b.objs[a_]]} and "
                                     f"{plan.names[b.objs[c_]]} are unresolved ({sep:.2f} px "
                                     f"apart < 3 PSF σ = {3 * cfg.psf_sigma_px:g} px): their "
                                     "tracklets are left out of association and prediction"))
    from eotrack.tracking.initiation.base import Track

    tracks = []
    # the frames the chain measured (all detections; the tracks' hits index them)
    frames = [(float(b.times_s[k]), m.xy) for k, m in zip(kept_k, measured)]
    m_conf = min(nf, 4)
    hit_lists = initiate_tracks(measured, config=pcfg, initiator=_initiator(cfg, v_max)) \
        if len(measured) >= m_conf else []
    # as eotrack Tracks for the GOSPA (confirmed at its third hit, not before frame m − 1)
    init_tracks = [Track(hits=list(h), confirmed_at=max(h[min(len(h), 3) - 1][0], m_conf - 1))
                   for h in hit_lists]
    for tr in init_tracks:
        idx = np.array([f for f, _ in tr.hits])
        fi = kept_k[idx]
        xy = np.array([measured[f].xy[dd] for f, dd in tr.hits]).reshape(-1, 2)
        dirs_t = np.concatenate([measured[f].solution.pixel_to_directions(measured[f].xy[dd][None])
                                 for f, dd in tr.hits])
        for f in idx:  # the plate-solved camera of each frame a tracklet uses (association)
            if int(kept_k[f]) not in cams:
                cams[int(kept_k[f])] = camera_from_wcs(measured[f].solution.wcs)
        # scoring: which object (if any) is it; its true per-ray angle errors
        true_obj, ray_err = -1, np.full(len(fi), np.nan)
        for j in range(n_o):
            err = np.hypot(*(xy - b.target_xy[j, fi]).T)
            if np.sum((err < TRUTH_PX) & lit[j, fi]) >= 3:
                true_obj = b.objs[j]
                tdir = b.target_gcrs_km[j, fi] - b.c_km[fi]
                tdir /= np.linalg.norm(tdir, axis=1, keepdims=True)
                ray_err = np.degrees(np.arccos(np.clip(np.sum(dirs_t * tdir, 1), -1, 1))) * 3600
                break
        # correlation with the catalogue (TLE predictions through the solved plate)
        dist = np.array([np.mean([np.hypot(*(xy[q] - pred_xy[int(fi[q])][j]))
                                  for q in range(len(fi))]) for j in range(n_o)])
        j_best = int(np.argmin(dist))
        cat_obj = b.objs[j_best] if dist[j_best] < CORRELATE_PX else -1
        # unresolved: the tracklet lies at a merged pair's predicted pixel in one of its frames
        unres = any(j_best in merged.get(int(k), ()) for k in fi)
        half = np.zeros(len(fi), bool)  # scoring: the hit was taken in the penumbra
        if true_obj >= 0:
            jt = b.objs.index(true_obj)
            half = (b.target_flux[jt, fi] > 0) & (b.target_flux[jt, fi] < b.target_flux.max())
        tracks.append({"frames": fi, "xy": xy, "dirs": dirs_t, "true_obj": true_obj,
                       "true": true_obj >= 0, "cat_obj": cat_obj, "ray_err_arcsec": ray_err,
                       "penumbra": half, "unresolved": unres})
    # initiation GOSPA (Stone Soup) against the sunlit objects, from frame m − 1 on
    # (an object in the umbra cannot be seen: it is passed outside the field, i.e. not
    # present). Every burst with a solved frame is scored: one that lost a frame (a cloud)
    # keeps one scorable frame (initiation_metrics scores it by the SIAP reference count);
    # one with fewer than m solved frames cannot initiate and is scored at its last frame
    # (every sunlit object missed).
    gospa = {}
    if frames:
        truth = [np.where(lit[:, k, None], b.target_xy[:, k], -1e3) for k in kept_k]
        gospa = initiation_metrics(init_tracks, frames, truth, width=float(n), c=5.0, p=1.0,
                                   first_frame=min(m_conf - 1, len(frames) - 1))
    return BurstResult(b.station, b.obj, b.visit, b.objs, n_det, n_cat, n_cand, n_false, lit,
                       t_det, t_kept, solved, rms, n_match, perr, cams, failures, gospa, v_max,
                       tracks, perr_model)


# ------------------------------------------------------------------ cross-station stages
def expected_ray_sigma_px(config: CapstoneConfig | None = None) -> float:
    """Expected per-axis centroid error (px) of a sunlit target: the Cramér–Rao bound of a
    Gaussian PSF, ``σ² = σ_PSF²/F + 8π σ_PSF⁴ (b + r²)/F²`` (photon noise of the target plus
    the background ``b`` and read noise ``r`` per pixel: the sum of the photon- and
    background-limited limits for an UNPIXELATED Gaussian — an approximation, below the
    bound of the pixelated frames (review 30 round 3); cf. Méndez et al. 2013). Stated before
    any frame is rendered: the scorecard compares the measured per-ray error with it."""
    cfg = _config(config)
    f = 10 ** (-0.4 * (cfg.target_mag - cfg.zero_point_mag))
    s2 = cfg.psf_sigma_px ** 2 / f + 8 * np.pi * cfg.psf_sigma_px ** 4 * (
        cfg.sky_e + cfg.read_noise_e ** 2) / f ** 2
    return float(np.sqrt(s2))


def epipolar_gate_px(config: CapstoneConfig | None = None, *, sigma_px: float = 0.3,
                     alpha: float = GATE_ALPHA) -> float:
    """The epipolar gate (px): the χ²(1) bound ``σ_e √χ²₁(1 − α)`` on the epipolar distance of a
    true pair, ``σ_e = √2 σ`` (both points' errors, ``σ`` per axis — the initiator's 0.3 px)."""
    _config(config)
    if not 0 < alpha < 1:
        raise ValueError(f"alpha must lie in (0, 1), got {alpha}")
    return float(np.sqrt(2.0) * sigma_px * np.sqrt(chi2.ppf(1 - alpha, 1)))


def _epi_px(c_a, u_a, c_b, u_b, focal_px) -> float:
    """Noise-free epipolar distance (px) of direction ``u_b`` (from ``c_b``) to the epipolar
    plane of ray (``c_a``, ``u_a``): the angle to the plane times the focal length."""
    nrm = np.cross(c_b - c_a, u_a)
    nrm /= np.linalg.norm(nrm)
    return float(abs(np.arcsin(np.clip(nrm @ u_b, -1, 1))) * focal_px)


def associate_tracklets(plan: NightPlan, results: list[BurstResult], *,
                        gate_px: float | None = None) -> pd.DataFrame:
    """Associate tracklets of the two stations visit by visit with the epipolar constraint.

    At each visit every tracklet of station 0 is compared with every tracklet of station 1 at
    a common frame: the fundamental matrix of the two PLATE-SOLVED cameras
    (:func:`eotrack.astro.astrometry.camera_from_wcs`) gives the epipolar distance (px, in
    station 1's image), then a one-to-one assignment below ``gate_px`` (default
    :func:`epipolar_gate_px`; Hungarian, :func:`eotrack.geometry.associate`). Tracklets in a
    frame flagged unresolved are left out.

    Returns
    -------
    pandas.DataFrame
        One row per associated pair: visit, frame, truth objects (scoring) and catalogue
        labels of each side, ``correct``, ``cluster`` (the field holds several objects), the
        epipolar distance, ``n_in_gate`` (station-1 tracklets inside the gate of the station-0
        one), directions, station positions, the tracklets' mean times and directions, and the
        true per-ray errors (scoring).
    """
    cfg = plan.config
    gate = epipolar_gate_px(cfg) if gate_px is None else float(gate_px)
    by_visit: dict[int, list[list]] = {}
    for r, b in zip(results, plan.bursts):
        for tr in r.tracks:
            if not tr["unresolved"]:
                by_visit.setdefault(r.visit, [[], []])[r.station].append((r, b, tr))
    rows = []
    for j, (a_list, b_list) in sorted(by_visit.items()):
        if not a_list or not b_list:
            continue
        D = np.full((len(a_list), len(b_list)), np.inf)
        frame = np.full(D.shape, -1)
        for ia, (ra, ba, ta) in enumerate(a_list):
            for ib, (rb, bb, tb) in enumerate(b_list):
                common = [k for k in np.intersect1d(ta["frames"], tb["frames"])
                          if int(k) in ra.cams and int(k) in rb.cams]
                if not common:
                    continue
                k = int(common[len(common) // 2])
                Ka, Ra = ra.cams[k]
                Kb, Rb = rb.cams[k]
                F = fundamental_from_poses(Ka, Ra, ba.c_km[k], Kb, Rb, bb.c_km[k])
                xa = ta["xy"][ta["frames"] == k]
                xb = tb["xy"][tb["frames"] == k]
                D[ia, ib] = float(epipolar_distances(F, xa, xb)[0, 0])
                frame[ia, ib] = k
        pairs = associate(np.where(np.isfinite(D), D, 1e9), gate, rule="hungarian")
        for ia, ib in pairs:
            ra, ba, ta = a_list[ia]
            rb, bb, tb = b_list[ib]
            k = int(frame[ia, ib])
            ha = int(np.flatnonzero(ta["frames"] == k)[0])
            hb = int(np.flatnonzero(tb["frames"] == k)[0])
            oa = ta["true_obj"]
            truth = None
            if oa >= 0:
                truth = ba.target_gcrs_km[ba.objs.index(oa), k]
            rows.append({"visit": j, "frame": k, "t_s": float(ba.times_s[k]),
                         "obj_a": oa, "obj_b": tb["true_obj"],
                         "cat_a": ta["cat_obj"], "cat_b": tb["cat_obj"],
                         "correct": bool(oa >= 0 and oa == tb["true_obj"]),
                         "cluster": len(ba.objs) > 1 or len(bb.objs) > 1,
                         "epipolar_px": float(D[ia, ib]),
                         "n_in_gate": int(np.sum(D[ia] < gate)),
                         "dir_a": ta["dirs"][ha], "c_a": ba.c_km[k],
                         "dir_b": tb["dirs"][hb], "c_b": bb.c_km[k],
                         "tm_a": float(ba.times_s[ta["frames"]].mean()),
                         "um_a": _unit(ta["dirs"].mean(0)),
                         "tm_b": float(bb.times_s[tb["frames"]].mean()),
                         "um_b": _unit(tb["dirs"].mean(0)),
                         "ray_err_a": float(ta["ray_err_arcsec"][ha]),
                         "ray_err_b": float(tb["ray_err_arcsec"][hb]),
                         "truth_km": truth})
    return pd.DataFrame(rows)


def predicted_false_association(plan: NightPlan, *, gate_px: float | None = None,
                                sigma_px: float = 0.3) -> pd.DataFrame:
    """The epipolar gate's false-association rate from its χ² bound, before any frame.

    Only what a station knows is read: the schedule (each visit's first frame time), the
    stations' positions, the objects' **TLE predictions** (:meth:`NightPlan.tle_direction`)
    and their predicted Earth shadow (:meth:`NightPlan.tle_sunlit`) — no rendered pixel and
    no truth array of the bursts. For every visit, station-0 object ``o`` and station-1
    object ``o' ≠ o`` both predicted sunlit in the visit, the noise-free epipolar distance
    ``d₀`` of the wrong pairing and the probability that it falls inside the gate,
    ``P(|d₀ + ε| < g)``, ``ε ~ N(0, σ_e²)``, ``σ_e = √2 σ`` — the gate's own noise model
    (``sigma_px`` per axis: the gate's 0.3 px, or one the chain measured,
    :func:`measured_epipolar_sigma_px`).

    Returns
    -------
    pandas.DataFrame
        One row per (visit, object): ``cluster`` flag, ``p_wrong_in_gate`` = the probability
        that at least one wrong partner lies inside the gate, and ``p_wrong_nearer`` = the
        probability that one lies nearer than the true partner (``P(|d₀ + ε_w| < |ε_t|)``,
        Gauss–Hermite quadrature) — what a nearest-first assignment would get wrong.
    """
    cfg = plan.config
    sigma_px = check_positive(sigma_px, "sigma_px")
    gate = epipolar_gate_px(cfg, sigma_px=sigma_px) if gate_px is None else float(gate_px)
    se = np.sqrt(2.0) * sigma_px
    seen: dict[int, list[list]] = {}
    for b in plan.bursts:
        t = float(b.times_s[0])
        c = _station_at(plan, b.station, t)
        for o in b.objs:
            if plan.tle_sunlit(o, t):
                seen.setdefault(b.visit, [[], []])[b.station].append(
                    (o, c, plan.tle_direction(o, b.station, t)[0], len(b.objs) > 1))
    rows = []
    for v, (sa, sb) in sorted(seen.items()):
        for o, ca, ua, clus in sa:
            if not any(o2 == o for o2, *_ in sb):
                continue
            p_none, p_keep = 1.0, 1.0
            for o2, cb, ub, _ in sb:
                if o2 == o:
                    continue
                d0 = _epi_px(ca, ua, cb, ub, cfg.focal_px)
                p_in = norm.cdf((gate - d0) / se) - norm.cdf((-gate - d0) / se)
                p_none *= 1.0 - p_in
                # the wrong partner nearer than the true one: P(|d₀ + ε_w| < |ε_t|)
                p_keep *= 1.0 - float(np.sum(_W * (norm.cdf((np.abs(_E) * se - d0) / se)
                                                   - norm.cdf((-np.abs(_E) * se - d0) / se))))
            rows.append({"visit": v, "object": plan.names[o], "cluster": clus,
                         "p_wrong_in_gate": 1.0 - p_none, "p_wrong_nearer": 1.0 - p_keep})
    return pd.DataFrame(rows, columns=["visit", "object", "cluster", "p_wrong_in_gate",
                                       "p_wrong_nearer"])


def measured_epipolar_sigma_px(pairs: pd.DataFrame) -> float:
    """Per-axis point error (px) the chain measures from its own associations, no truth:
    ``RMS(d) / √2`` over the epipolar distances ``d`` of the unambiguous pairs (one
    candidate inside the gate, ``n_in_gate == 1``; ``d`` holds both points' errors,
    ``σ_e = √2 σ``). NaN without such pairs."""
    if not isinstance(pairs, pd.DataFrame):
        raise TypeError(f"pairs must be a DataFrame, got {type(pairs).__name__}")
    if not len(pairs) or "epipolar_px" not in pairs:
        return float("nan")
    d = pairs.loc[pairs["n_in_gate"] == 1, "epipolar_px"].to_numpy(float)
    return float(np.sqrt(np.mean(d ** 2)) / np.sqrt(2.0)) if len(d) else float("nan")


#: Gauss–Hermite nodes and weights for expectations over a standard normal ε.
_E, _W = np.polynomial.hermite_e.hermegauss(40)
_W = _W / _W.sum()


def _unit(v: np.ndarray) -> np.ndarray:
    v = np.asarray(v, float)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def triangulate_pairs(pairs: pd.DataFrame) -> pd.DataFrame:
    """Triangulate every associated pair (midpoint of the common perpendicular).

    Adds ``range_km`` (from station 0), ``range_err_km`` and ``pos_err_km`` (against SGP4,
    correct pairs only), ``gap_km`` (miss distance of the two rays), ``b_perp_km`` (baseline
    component perpendicular to station 0's line of sight) and the first-order range error
    ``sigma_r_km`` expected from the pair's own TRUE in-plane ray errors (scoring).
    """
    if len(pairs) == 0:
        return pairs.assign(range_km=[], range_err_km=[], pos_err_km=[], gap_km=[],
                            b_perp_km=[], inplane_a=[], inplane_b=[])
    o1 = np.stack(pairs["c_a"].to_numpy())
    d1 = np.stack(pairs["dir_a"].to_numpy())
    o2 = np.stack(pairs["c_b"].to_numpy())
    d2 = np.stack(pairs["dir_b"].to_numpy())
    p, gap = triangulate_two_rays(o1, d1, o2, d2, return_gap=True)
    rng_km = np.linalg.norm(p - o1, axis=1)
    base = o2 - o1
    b_perp = np.linalg.norm(np.cross(base, d1), axis=1)
    err_r = np.full(len(p), np.nan)
    err_p = np.full(len(p), np.nan)
    ina = np.full(len(p), np.nan)
    inb = np.full(len(p), np.nan)
    for i, (ok, tr) in enumerate(zip(pairs["correct"], pairs["truth_km"])):
        if ok and tr is not None:
            err_r[i] = rng_km[i] - np.linalg.norm(tr - o1[i])
            err_p[i] = np.linalg.norm(p[i] - tr)
            # the rays' true errors resolved in the epipolar plane (the part that moves range)
            for dm, o, out in ((d1[i], o1[i], ina), (d2[i], o2[i], inb)):
                ut = _unit(tr - o)
                nrm = _unit(np.cross(base[i], ut))
                inplane = _unit(np.cross(nrm, ut))
                out[i] = float((dm - ut) @ inplane) * ARCSEC_PER_RAD
    return pairs.assign(range_km=rng_km, range_err_km=err_r, pos_err_km=err_p, gap_km=gap,
                        b_perp_km=b_perp, inplane_a=ina, inplane_b=inb)


def sigma_reconciliation(pairs: pd.DataFrame, config: CapstoneConfig | None = None
                         ) -> dict[str, float]:
    """σ_R ≈ R²σ_θ/B with assumed and MEASURED inputs, beside the measured range error.

    ``assumed``: σ_θ = 0.2 px (the old text) and the full baseline; ``measured``: σ_θ the RMS
    of the rays' measured in-plane errors (both rays: √(σ_a² + σ_b²)) and each pair's
    perpendicular baseline ``B⊥``; ``range_rms_km``: the measured RMS range error.
    """
    cfg = _config(config)
    tri = pairs.dropna(subset=["range_err_km"]) if len(pairs) else pairs
    if len(tri) == 0:
        return {k: np.nan for k in ("sigma_a_arcsec", "sigma_b_arcsec", "ray_rms_arcsec",
                                    "assumed_km", "measured_km", "range_rms_km", "range_km",
                                    "baseline_km", "b_perp_km")}
    R = float(np.sqrt(np.mean(tri["range_km"] ** 2)))
    base = float(np.mean(np.linalg.norm(np.stack(tri["c_b"].to_numpy())
                                        - np.stack(tri["c_a"].to_numpy()), axis=1)))
    sa = float(np.sqrt(np.mean(tri["inplane_a"] ** 2)))
    sb = float(np.sqrt(np.mean(tri["inplane_b"] ** 2)))
    fac = tri["range_km"] ** 2 / tri["b_perp_km"] / ARCSEC_PER_RAD
    meas = float(np.sqrt(np.mean(fac ** 2 * (sa ** 2 + sb ** 2))))
    ray = np.r_[tri["ray_err_a"], tri["ray_err_b"]]
    return {"sigma_a_arcsec": sa, "sigma_b_arcsec": sb,
            "ray_rms_arcsec": float(np.sqrt(np.nanmean(ray ** 2))),
            "assumed_km": range_error_km(R, base, 0.2 * cfg.pixel_scale_arcsec),
            "measured_km": meas, "range_rms_km": float(np.sqrt(np.mean(tri["range_err_km"] ** 2))),
            "range_km": R, "baseline_km": base, "b_perp_km": float(tri["b_perp_km"].mean())}


def _radec_deg(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    d = _unit(d)
    return (np.degrees(np.arctan2(d[..., 1], d[..., 0])) % 360.0,
            np.degrees(np.arcsin(np.clip(d[..., 2], -1, 1))))


def _radec_arcsec(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    d = _unit(d)
    ra = np.unwrap(np.arctan2(d[..., 1], d[..., 0]))
    dec = np.arcsin(np.clip(d[..., 2], -1, 1))
    return ra * ARCSEC_PER_RAD, dec * ARCSEC_PER_RAD


def _tracklet_series(plan: NightPlan, results: list[BurstResult], pairs: pd.DataFrame
                     ) -> dict[str, dict[tuple[int, int], list]]:
    """Per series and (station, object): ``(t, unit direction, true object)`` of tracklets.

    ``field``: every tracklet of the object's field bursts (the old chain; field objects only).
    ``catalogue``: tracklets correlated with the object's TLE prediction.
    ``confirmed``: tracklets of associated pairs whose two sides correlate with the object.
    """
    out: dict[str, dict] = {"field": {}, "catalogue": {}, "confirmed": {}}
    for r, b in zip(results, plan.bursts):
        for tr in r.tracks:
            if tr["unresolved"]:  # a blended centroid: kept out of every series
                continue
            item = (float(b.times_s[tr["frames"]].mean()), _unit(tr["dirs"].mean(0)),
                    tr["true_obj"])
            out["field"].setdefault((r.station, r.obj), []).append(item)
            if tr["cat_obj"] >= 0:
                out["catalogue"].setdefault((r.station, tr["cat_obj"]), []).append(item)
    if len(pairs):
        for _, p in pairs.iterrows():
            if p["cat_a"] >= 0 and p["cat_a"] == p["cat_b"]:
                o = int(p["cat_a"])
                out["confirmed"].setdefault((0, o), []).append((p["tm_a"], p["um_a"], p["obj_a"]))
                out["confirmed"].setdefault((1, o), []).append((p["tm_b"], p["um_b"], p["obj_b"]))
    return out


def _hhmm(plan: NightPlan, t_s: float) -> str:
    return (plan.t0 + float(t_s) * u.s).datetime.strftime("%H:%M UTC")


def eclipse_status(plan: NightPlan, times: dict[tuple[int, int], np.ndarray] | None = None, *,
                   min_points: int = 6, fit_window_s: float = 7200.0) -> pd.DataFrame:
    """Which (station, object) can be predicted through an eclipse, and why not.

    The one eclipse criterion of the chain: at least ``min_points`` observations in the
    ``fit_window_s`` before the umbra entry AND at least one after it (the object is seen
    again, so the prediction can be checked). ``times=None``: the PLANNED visits at which the
    object can be seen (station dark, field above the elevation limit, object not in the
    umbra — checked before any frame is rendered); otherwise the tracklet times per
    (station, object) that the run produced.

    Returns
    -------
    pandas.DataFrame
        ``station, object, umbra_in, umbra_out, n_before, n_after, ok, reason``.
    """
    cfg = plan.config
    what = "planned visits" if times is None else "tracklets"
    rows = []
    for o, name in enumerate(plan.names):
        umb = plan.grid_shadow[o] == 2
        fld = cfg.field_of[o]
        for s, spec in enumerate(cfg.stations):
            base = {"station": spec.name, "object": name}
            if not umb.any():
                rows.append({**base, "umbra_in": "", "umbra_out": "", "n_before": 0,
                             "n_after": 0, "ok": False,
                             "reason": "does not enter the umbra during the night"})
                continue
            t_in = plan.grid_s[np.argmax(umb)]
            t_out = plan.grid_s[len(umb) - 1 - np.argmax(umb[::-1])]
            if times is None:  # planned visits at which the object can be seen (sunlit)
                ok = plan.dark[s] & (plan.elevation_deg[s, fld] > cfg.min_elevation_deg) & \
                    (plan.shadow[o] != 2)
                t = plan.visit_s[ok]
            else:
                t = np.asarray(times.get((s, o), []), float)
            nb = int(np.sum((t < t_in) & (t >= t_in - fit_window_s)))
            na = int(np.sum(t >= t_in))
            reason = ""
            if nb < min_points:
                dark = plan.visit_s[plan.dark[s]]
                reason = (f"only {nb} {what} in the {fit_window_s / 3600:g} h before the umbra "
                          f"entry at {_hhmm(plan, t_in)} (need {min_points}; darkness at "
                          f"{spec.name} from {_hhmm(plan, dark.min()) if len(dark) else '—'})")
            elif na == 0:
                reason = (f"{nb} {what} before the umbra entry at {_hhmm(plan, t_in)} but none "
                          "after it")
            rows.append({**base, "umbra_in": _hhmm(plan, t_in), "umbra_out": _hhmm(plan, t_out),
                         "n_before": nb, "n_after": na, "ok": not reason, "reason": reason})
    return pd.DataFrame(rows)


def eclipse_check(plan: NightPlan, times: dict | None = None, **kw) -> list[tuple[int, int]]:
    """The (station, object) pairs :func:`eclipse_status` passes.

    Raises
    ------
    ValueError
        Stage ``prediction``: no pair passes — the message lists each pair's reason (e.g.
        "7 tracklets before the umbra entry at 05:25 UTC but none after it").
    """
    st = eclipse_status(plan, times, **kw)
    ok = [(s, o) for (s, o), good in zip(
        [(s, o) for o in range(len(plan.names)) for s in range(len(plan.config.stations))],
        st["ok"]) if good]
    if not ok:
        why = "; ".join(f"{r.object} from {r.station}: {r.reason}" for r in st.itertuples())
        raise ValueError("stage 'prediction': no object can be predicted through an eclipse "
                         f"(from {plan.t0.iso}, {plan.config.night_hours:g} h) — {why}. GEO "
                         "eclipses happen within about 6 weeks of an equinox, around the "
                         "satellite's local midnight")
    return ok


def _truth_err(plan, o, s, tq, v):
    truth = plan.truth_direction(o, s, tq)
    return np.degrees(np.arccos(np.clip(np.sum(v * truth, 1), -1, 1))) * 3600


def _watch_mask(plan: NightPlan, s: int, o: int, tq: np.ndarray) -> np.ndarray:
    """Times ``tq`` at which station ``s`` could watch object ``o`` (dark, above the limit)."""
    cfg = plan.config
    ok = plan.dark[s] & (plan.elevation_deg[s, cfg.field_of[o]] > cfg.min_elevation_deg)
    return np.interp(tq, plan.visit_s, ok.astype(float)) > 0.5


def predict_through_eclipse(plan: NightPlan, results: list[BurstResult],
                            pairs: pd.DataFrame | None = None, *,
                            methods: tuple[str, ...] = PREDICTORS, min_points: int = 6,
                            threshold_arcsec: float = 6.0, fit_window_s: float = 7200.0,
                            orbit_dynamics: str = "j2") -> tuple[pd.DataFrame, pd.DataFrame]:
    """Predict each object's angles through its umbra passage, from the ``fit_window_s`` before.

    Sinusoid-plus-drift predictors (:func:`eotrack.experiments.wransac.fit_predict`, notebook
    01) per station on three tracklet series (:func:`_tracklet_series`): ``field`` (every
    tracklet of the object's field — the old chain), ``catalogue`` (tracklets correlated with
    the object's TLE prediction) and ``confirmed`` (tracklets of epipolar-associated pairs).
    And an ORBIT (:func:`eotrack.astro.fit_orbit`: Gauss start, robust Cauchy least squares,
    two-body + J2) fitted to BOTH stations' catalogue-correlated angles in the same window,
    whose predicted angles are scored from each station. Errors are great-circle angles (″)
    against SGP4 on a 1-min grid inside the umbra, where the station could watch (dark, object
    above the limit).

    Returns
    -------
    prediction, status
        Prediction rows ``station, object, series, method, n_fit, n_wrong, eclipse_min,
        rms_arcsec, max_arcsec, note`` (``n_wrong``: fitted tracklets of another or no object,
        scoring; ``note``: why a fit failed, its errors then NaN) and the
        :func:`eclipse_status` of the catalogue-correlated tracklets.

    Raises
    ------
    ValueError
        Stage ``prediction``: no (station, object) passes :func:`eclipse_status` on the run's
        catalogue-correlated tracklets (the message names each pair's reason).
    """
    from eotrack.astro import fit_orbit
    from eotrack.experiments.wransac import fit_predict

    cfg = plan.config
    pairs = pd.DataFrame() if pairs is None else pairs
    series = _tracklet_series(plan, results, pairs)
    kw = {"min_points": min_points, "fit_window_s": fit_window_s}
    cat_times = {k: np.array([p[0] for p in v]) for k, v in series["catalogue"].items()}
    status = eclipse_status(plan, cat_times, **kw)
    eclipse_check(plan, cat_times, **kw)
    rng = np.random.default_rng(cfg.seed + 1)
    rows = []
    names = plan.names

    def window(o):
        umb = plan.grid_shadow[o] == 2
        t_in = plan.grid_s[np.argmax(umb)]
        t_out = plan.grid_s[len(umb) - 1 - np.argmax(umb[::-1])]
        return t_in, t_out, plan.grid_s[(plan.grid_s >= t_in) & (plan.grid_s <= t_out)]

    def row(s, o, name, m, n_fit, n_wrong, t_in, t_out, err):
        return {"station": cfg.stations[s].name, "object": names[o], "series": name,
                "method": m, "n_fit": int(n_fit), "n_wrong": int(n_wrong),
                "eclipse_min": (t_out - t_in) / 60,
                "rms_arcsec": float(np.sqrt(np.mean(err ** 2))), "max_arcsec": float(err.max()),
                "note": ""}

    def ok_in(st, s, o):
        sel = st[(st["station"] == cfg.stations[s].name) & (st["object"] == names[o])]
        return bool(sel["ok"].iloc[0]) if len(sel) else False

    for name in ("field", "catalogue", "confirmed"):
        times = {k: np.array([p[0] for p in v]) for k, v in series[name].items()}
        st = eclipse_status(plan, times, **kw)
        for (s, o), pts in sorted(series[name].items()):
            if not ok_in(st, s, o):
                continue
            t_in, t_out, tq = window(o)
            tq = tq[_watch_mask(plan, s, o, tq)]
            if len(tq) == 0:
                continue
            order = np.argsort([p[0] for p in pts], kind="stable")
            t = np.array([pts[i][0] for i in order])
            d = np.stack([pts[i][1] for i in order])
            tru = np.array([pts[i][2] for i in order])
            before = (t < t_in) & (t >= t_in - fit_window_s)
            ra, dec = _radec_arcsec(d[before])
            for m in methods:
                try:
                    pr = fit_predict(m, t[before], ra - ra[0], tq, rng=rng,
                                     threshold=threshold_arcsec)
                    pd_ = fit_predict(m, t[before], dec - dec[0], tq, rng=rng,
                                      threshold=threshold_arcsec)
                except ValueError as e:  # e.g. several objects' tracklets at the same times
                    rows.append({**row(s, o, name, m, before.sum(), np.sum(tru[before] != o),
                                       t_in, t_out, np.full(1, np.nan)), "note": str(e)})
                    continue
                ra_p = (pr + ra[0]) / ARCSEC_PER_RAD
                de_p = (pd_ + dec[0]) / ARCSEC_PER_RAD
                v = np.stack([np.cos(de_p) * np.cos(ra_p), np.cos(de_p) * np.sin(ra_p),
                              np.sin(de_p)], 1)
                rows.append(row(s, o, name, m, before.sum(), np.sum(tru[before] != o), t_in,
                                t_out, _truth_err(plan, o, s, tq, v)))
    # the orbit: both stations' catalogue-correlated angles in the window, one fit per object
    sig = max(np.sqrt(2) * expected_ray_sigma_px(cfg) * cfg.pixel_scale_arcsec, 0.5)
    for o in range(len(names)):
        if not (plan.grid_shadow[o] == 2).any():
            continue
        t_in, t_out, tq_all = window(o)
        obs = [(tt, s, uu, tr) for s in range(2) for tt, uu, tr in series["catalogue"].get(
            (s, o), []) if t_in - fit_window_s <= tt < t_in]
        after = sum(tt >= t_in for s in range(2) for tt, _, _ in series["catalogue"].get(
            (s, o), []))
        if len(obs) < min_points or after == 0:
            continue
        obs.sort(key=lambda q: (q[0], q[1]))
        # the two stations observe at the same instants: fit_orbit takes equal times from
        # different sites as they are
        t = np.array([q[0] for q in obs])
        site = np.stack([_station_at(plan, q[1], q[0]) for q in obs])
        ra_d, de_d = _radec_deg(np.stack([q[2] for q in obs]))
        try:
            fit = fit_orbit(t, ra_d, de_d, site, sigma_arcsec=sig, loss="cauchy",
                            dynamics=orbit_dynamics)
        except ValueError as e:
            for s in range(2):
                rows.append({**row(s, o, "catalogue, both stations", "orbit", len(obs), 0,
                                   t_in, t_out, np.full(1, np.nan)), "note": str(e)})
            continue
        tru = np.array([q[3] for q in obs])
        for s in range(2):
            tq = tq_all[_watch_mask(plan, s, o, tq_all)]
            if len(tq) == 0:
                continue
            site_q = np.stack([_station_at(plan, s, x) for x in tq])
            ra_p, de_p = np.radians(fit.predict(tq, site_q))
            v = np.stack([np.cos(de_p) * np.cos(ra_p), np.cos(de_p) * np.sin(ra_p),
                          np.sin(de_p)], 1)
            rows.append(row(s, o, "catalogue, both stations", "orbit", len(obs),
                            np.sum(tru != o), t_in, t_out, _truth_err(plan, o, s, tq, v)))
    cols = ["station", "object", "series", "method", "n_fit", "n_wrong", "eclipse_min",
            "rms_arcsec", "max_arcsec", "note"]
    return pd.DataFrame(rows, columns=cols), status


def _station_at(plan: NightPlan, s: int, t_s: float) -> np.ndarray:
    return np.array([np.interp(t_s, plan.grid_s, plan.grid_station_km[s][:, i])
                     for i in range(3)])


@dataclass
class NightResult:
    """Everything the chain produced for one night."""

    plan: NightPlan
    bursts: list[BurstResult]
    pairs: pd.DataFrame
    prediction: pd.DataFrame
    budget: pd.DataFrame
    eclipse: pd.DataFrame = field(default_factory=pd.DataFrame)
    failures: pd.DataFrame = field(default_factory=pd.DataFrame)
    false_association: pd.DataFrame = field(default_factory=pd.DataFrame)
    sigma: dict = field(default_factory=dict)
    wall_s: dict = field(default_factory=dict)
    error: str = ""  #: the stage error of a non-strict run (empty if every stage ran)


def _rms(x) -> float:
    x = np.asarray(x, float)
    x = x[np.isfinite(x)]
    return float(np.sqrt(np.mean(x ** 2))) if len(x) else np.nan


def error_budget(plan: NightPlan, bursts: list[BurstResult], pairs: pd.DataFrame,
                 prediction: pd.DataFrame, false_assoc: pd.DataFrame | None = None,
                 sigma: dict | None = None) -> pd.DataFrame:
    """The stage-by-stage error budget (one row per metric)."""
    lit = np.concatenate([r.target_lit.ravel() for r in bursts])
    det = np.concatenate([r.target_detected.ravel() for r in bursts])
    kept = np.concatenate([r.target_kept.ravel() for r in bursts])
    solved = np.concatenate([r.solved for r in bursts])
    n_frames = len(solved)
    false_c = int(sum(r.n_false_candidates.sum() for r in bursts))
    n_det = int(sum(r.n_detections.sum() for r in bursts))
    plate_rms = np.concatenate([r.plate_rms_arcsec for r in bursts])
    plate_err = np.concatenate([r.plate_err_arcsec for r in bursts])
    n_match = np.concatenate([r.plate_n_matched for r in bursts])[solved]
    n_lit_b = found = 0
    for r in bursts:
        for j, o in enumerate(r.objs):
            if r.target_lit[j].sum() >= 3:
                n_lit_b += 1
                found += any(t["true_obj"] == o for t in r.tracks)
    n_tracks = sum(len(r.tracks) for r in bursts)
    false_t = sum(t["true_obj"] < 0 for r in bursts for t in r.tracks)
    g = [r.gospa for r in bursts if r.gospa]
    gm = {k: float(np.mean([x[k] for x in g])) if g else np.nan
          for k in ("gospa", "gospa localisation", "gospa missed", "gospa false")}
    n_pairs = len(pairs)
    correct = float(pairs["correct"].mean()) if n_pairs else np.nan
    clus = pairs[pairs["cluster"]] if n_pairs else pairs
    tri = pairs.dropna(subset=["range_err_km"]) if n_pairs else pairs
    fa = false_assoc if false_assoc is not None else pd.DataFrame(
        columns=["cluster", "p_wrong_in_gate", "p_wrong_nearer"])
    sg = sigma or {}
    ray = np.concatenate([np.ravel(t["ray_err_arcsec"]) for r in bursts for t in r.tracks]) \
        if n_tracks else np.zeros(0)
    rows = [
        ("frames", "frames rendered", n_frames, "count"),
        ("frames", "frames left out (no plate solution, or extraction failed)",
         int(n_frames - solved.sum()), "count"),
        ("extraction", "detections per frame", n_det / max(n_frames, 1), ""),
        ("extraction", "target completeness (sunlit frames)", det[lit].mean() if lit.any()
         else np.nan, "fraction"),
        ("astrometry", "matched stars per frame (median)",
         float(np.median(n_match)) if len(n_match) else np.nan, "count"),
        ("astrometry", "plate solution: RMS star residual (median)",
         float(np.nanmedian(plate_rms)) if np.isfinite(plate_rms).any() else np.nan,
         "arcsec"),
        ("astrometry", "plate solution: true error at the objects (RMS)", _rms(plate_err),
         "arcsec"),
        ("astrometry", "plate solution: its own error model at the objects (RMS)",
         _rms(np.concatenate([r.plate_err_model_arcsec for r in bursts])), "arcsec"),
        ("separation", "target kept as candidate", kept[lit].mean() if lit.any() else np.nan,
         "fraction"),
        ("separation", "false candidates per frame", false_c / max(n_frames, 1), ""),
        ("initiation", "velocity gate", float(bursts[0].v_max_px_s) if bursts else np.nan,
         "px/s"),
        ("initiation", "recall (object-bursts with ≥ 3 sunlit frames)",
         found / max(n_lit_b, 1), "fraction"),
        ("initiation", "false tracks", false_t, "count"),
        ("initiation", "tracks", n_tracks, "count"),
        ("initiation", "GOSPA: bursts scored", len(g), "count"),
        ("initiation", "GOSPA per burst (mean, c = 5 px)", gm["gospa"], "px"),
        ("initiation", "GOSPA: missed part", gm["gospa missed"], "px"),
        ("initiation", "GOSPA: false part", gm["gospa false"], "px"),
        ("initiation", "GOSPA: localisation part", gm["gospa localisation"], "px"),
        ("association", "epipolar gate (χ², α = 0.01)", epipolar_gate_px(plan.config), "px"),
        ("association", "pairs associated", n_pairs, "count"),
        ("association", "correct pairs", correct, "fraction"),
        ("association", "correct pairs, cluster field", float(clus["correct"].mean())
         if len(clus) else np.nan, "fraction"),
        ("association", "χ² bound: wrong partner inside the gate, cluster field",
         float(fa[fa["cluster"]]["p_wrong_in_gate"].mean()) if fa["cluster"].any() else np.nan,
         "fraction"),
        ("association", "χ² model: wrong partner nearer than the true one, cluster field",
         float(fa[fa["cluster"]]["p_wrong_nearer"].mean()) if fa["cluster"].any() else np.nan,
         "fraction"),
        ("association", "pairs with a second candidate inside the gate, cluster field",
         float((clus["n_in_gate"] > 1).mean()) if len(clus) else np.nan, "fraction"),
        ("association", "χ² bound: wrong partner inside the gate, single fields",
         float(fa[~fa["cluster"].astype(bool)]["p_wrong_in_gate"].mean())
         if (~fa["cluster"].astype(bool)).any() else np.nan, "fraction"),
        ("triangulation", "per-ray angle error (RMS, tracklet hits)", _rms(ray), "arcsec"),
        ("triangulation", "expected RMS range error from the measured in-plane ray errors",
         sg.get("measured_km", np.nan), "km"),
        ("triangulation", "RMS range error", _rms(tri["range_err_km"]) if len(tri) else np.nan,
         "km"),
        ("triangulation", "median |range error|",
         float(np.median(np.abs(tri["range_err_km"]))) if len(tri) else np.nan, "km"),
        ("triangulation", "RMS position error", _rms(tri["pos_err_km"]) if len(tri) else np.nan,
         "km"),
    ]
    for series, methods in (("field", PREDICTORS), ("catalogue", PREDICTORS),
                            ("confirmed", PREDICTORS), ("catalogue, both stations", ("orbit",))):
        for m in methods:
            sel = prediction[(prediction["series"] == series) & (prediction["method"] == m)] \
                if len(prediction) else prediction
            rows.append(("prediction", f"{m} ({series}): RMS error through the eclipse",
                         _rms(sel["rms_arcsec"]) if len(sel) else np.nan, "arcsec"))
    return pd.DataFrame(rows, columns=["stage", "metric", "value", "unit"])


def quick_config(config: CapstoneConfig | None = None) -> CapstoneConfig:
    """The QUICK night: only the cluster field (XM-3 and its two companions), 03:20–07:50 UTC
    around XM-3's eclipse (Haleakalā joins after the umbra), 15-min visits, one clouded
    frame — every stage runs."""
    cfg = _config(config)
    return replace(cfg, norad_ids=(28626,), night_start_utc="2006-03-25T03:20:00",
                   night_hours=4.5, cloud_frames=((0, 0, 2, 1),))


def run_night(config: CapstoneConfig | None = None, *, runner: TrialRunner | None = None,
              strict: bool = True) -> NightResult:
    """Run the whole chain for one night.

    Parameters
    ----------
    config
        The night (default :class:`CapstoneConfig`).
    runner
        Where the bursts run (default serial); any backend gives the same numbers.
    strict
        Raise when a stage produces nothing (default). ``False``: the later stages are skipped
        and their budget entries are NaN (used by the noise sweep).

    Raises
    ------
    ValueError
        Naming the stage that produced nothing: ``sky`` (an object never rises),
        ``prediction`` (no eclipse can be watched — checked on the plan before any frame is
        rendered — or, after the run, no object has the tracklets before AND after its umbra
        entry), ``extraction`` (no object detected in any frame), ``initiation`` (no track),
        ``association`` (no cross-station pair). Frames whose plate solution fails and
        unresolved objects do not stop the night: they are listed in ``failures``.
    """
    cfg = _config(config)
    runner = runner if runner is not None else TrialRunner(progress=False)
    if not isinstance(runner, TrialRunner):
        raise TypeError(f"runner must be a TrialRunner, got {type(runner).__name__}")
    wall = {}
    t = time.perf_counter()
    plan = make_plan(cfg)
    eclipse_check(plan)
    velocity_gate(cfg)
    fa = predicted_false_association(plan)
    wall["sky"] = time.perf_counter() - t
    t = time.perf_counter()
    bursts = runner.map(observe_burst, len(plan.bursts), seed=cfg.seed, args=(plan,),
                        desc="bursts")
    wall["frames"] = time.perf_counter() - t
    failures = pd.DataFrame([{"frame": f, "stage": st, "reason": why} for r in bursts
                             for f, st, why in r.failures], columns=["frame", "stage", "reason"])
    empty_pairs = triangulate_pairs(pd.DataFrame())
    empty_pred = pd.DataFrame(columns=["station", "object", "series", "method", "n_fit",
                                       "n_wrong", "eclipse_min", "rms_arcsec", "max_arcsec",
                                       "note"])
    t = time.perf_counter()
    pairs, pred, status, sig, error = empty_pairs, empty_pred, pd.DataFrame(), {}, ""
    try:
        if not any(r.solved.any() for r in bursts):
            why = failures.groupby(failures["reason"].str.split(":").str[0]).size()
            raise ValueError(f"stage 'astrometry': no plate solution in any of "
                             f"{sum(len(r.solved) for r in bursts)} frames ("
                             + ", ".join(f"{k} {v}" for k, v in why.items())
                             + f") — about {expected_field_stars(cfg):.1f} detectable catalogue "
                             "stars per field expected (widen the field, lower sky_e, deepen "
                             "astrometry_mag)")
        if not any(r.target_kept.any() for r in bursts):
            raise ValueError(f"stage 'extraction': no object detected in any of "
                             f"{sum(len(r.solved) for r in bursts)} frames — no detection "
                             f"left after star removal lies at an object (objects of magnitude "
                             f"{cfg.target_mag} against a sky of {cfg.sky_e} e⁻/px)")
        if not any(r.tracks for r in bursts):
            raise ValueError("stage 'initiation': no track confirmed in any of "
                             f"{len(bursts)} bursts")
        pairs = triangulate_pairs(associate_tracklets(plan, bursts))
        sig = sigma_reconciliation(pairs, cfg)
        if len(pairs) == 0:
            n_un = sum(t["unresolved"] for r in bursts for t in r.tracks)
            if n_un and not any(not t["unresolved"] for r in bursts for t in r.tracks):
                import re

                objs = sorted({" and ".join(re.match(r"objects (\S+) and (\S+) are", m).groups())
                               for m in failures["reason"] if "unresolved" in m
                               and re.match(r"objects (\S+) and (\S+) are", m)})
                raise ValueError(f"stage 'association': all {n_un} tracklets were left out as "
                                 f"unresolved (objects {'; '.join(objs)}): nothing left to "
                                 "associate")
            raise ValueError("stage 'association': no tracklet of one station matched one of "
                             "the other — do the stations observe at the same times?")
        pred, status = predict_through_eclipse(plan, bursts, pairs)
    except ValueError as e:
        if strict:
            raise
        error = str(e)
    wall["cross-station"] = time.perf_counter() - t
    return NightResult(plan, bursts, pairs, pred,
                       error_budget(plan, bursts, pairs, pred, fa, sig), status, failures, fa,
                       sig, wall, error)


def _config(config) -> CapstoneConfig:
    cfg = CapstoneConfig() if config is None else config
    if not isinstance(cfg, CapstoneConfig):
        raise TypeError(f"config must be a CapstoneConfig, got {type(cfg).__name__}")
    return cfg


def target_peak_snr(config: CapstoneConfig | None = None) -> float:
    """Peak signal-to-noise ratio of a sunlit target: peak e⁻ over the background σ.

    The PSF's peak pixel holds ``F / (2π σ²)`` of the flux ``F``; the noise is
    ``sqrt(sky + read²)`` (the gradient ignored).
    """
    cfg = _config(config)
    flux = 10 ** (-0.4 * (cfg.target_mag - cfg.zero_point_mag))
    return float(flux / (2 * np.pi * cfg.psf_sigma_px ** 2)
                 / np.sqrt(cfg.sky_e + cfg.read_noise_e ** 2))


def sidereal_drift_px(config: CapstoneConfig | None = None, dec_deg: float = 0.0) -> float:
    """Distance (px) a star drifts between two frames of a GEO-staring camera at ``dec_deg``."""
    cfg = _config(config)
    if not -90 <= float(dec_deg) <= 90:
        raise ValueError(f"dec_deg must lie in [-90, 90], got {dec_deg}")
    return float(EARTH_RATE_RAD_S * cfg.frame_interval_s * ARCSEC_PER_RAD
                 * np.cos(np.radians(dec_deg)) / cfg.pixel_scale_arcsec)


def range_error_km(range_km: float, baseline_km: float, sigma_arcsec: float) -> float:
    """First-order range error of a two-station triangulation: ``σ_R ≈ R² σ_θ / B``.

    Valid when the baseline ``B`` is perpendicular to the line of sight and ``B ≪ R``.
    """
    for v, n in ((range_km, "range_km"), (baseline_km, "baseline_km"),
                 (sigma_arcsec, "sigma_arcsec")):
        if not (np.isfinite(v) and v > 0):
            raise ValueError(f"{n} must be a positive finite number, got {v}")
    return float(range_km ** 2 * sigma_arcsec / ARCSEC_PER_RAD / baseline_km)


def paired_orbit_curve(prediction: pd.DataFrame) -> tuple[pd.Series, pd.Series]:
    """The orbit's and the best sinusoid predictor's RMS errors (″) on the catalogue-correlated
    tracklets, on the (station, object) cases where both predict."""
    if len(prediction) == 0:
        return pd.Series(dtype=float), pd.Series(dtype=float)
    sel = prediction[(prediction["series"] == "catalogue") | (prediction["method"] == "orbit")]
    tab = sel.pivot_table(index=["station", "object"], columns="method", values="rms_arcsec")
    if "orbit" not in tab.columns:
        return pd.Series(dtype=float), pd.Series(dtype=float)
    curves = [m for m in PREDICTORS if m in tab.columns]
    both = tab.dropna(subset=["orbit", *curves])
    return both["orbit"], both[curves].min(axis=1)


def predictor_isolation(night: NightResult, *, methods: tuple[str, ...] = PREDICTORS,
                        fit_window_s: float = 7200.0, threshold_arcsec: float = 6.0
                        ) -> pd.DataFrame:
    """Why the curve predictors fail on a cluster's field series, isolated (scoring).

    For the first field with companions that a station can predict, the predictors are fitted
    to four series before the field object's umbra entry and scored against the FIELD OBJECT's
    truth through the umbra: its own tracklets; one companion's only (a consistent wrong track:
    error ≈ the separation?); every object's tracklets with one tracklet per instant (mixed, no
    repeated times); and every tracklet (the old chain's field series).
    """
    from eotrack.experiments.wransac import fit_predict

    plan, cfg = night.plan, night.plan.config
    field = _tracklet_series(plan, night.bursts, pd.DataFrame())["field"]
    rng = np.random.default_rng(cfg.seed + 2)
    rows = []
    for (s, o), pts in sorted(field.items()):
        comps = [m for m, fo in enumerate(cfg.field_of) if fo == o and m != o]
        umb = plan.grid_shadow[o] == 2
        if not comps or not umb.any():
            continue
        t_in = plan.grid_s[np.argmax(umb)]
        t_out = plan.grid_s[len(umb) - 1 - np.argmax(umb[::-1])]
        tq = plan.grid_s[(plan.grid_s >= t_in) & (plan.grid_s <= t_out)]
        tq = tq[_watch_mask(plan, s, o, tq)]
        pts = sorted((p for p in pts if t_in - fit_window_s <= p[0] < t_in), key=lambda p: p[0])
        if len(tq) == 0 or len(pts) < 6:
            continue
        t_all = np.array([p[0] for p in pts])
        who = np.array([p[2] for p in pts])
        uniq = np.unique(t_all)
        objs = [o, *comps]
        one_per_t = np.zeros(len(pts), bool)
        for i, tt in enumerate(uniq):  # cycle through the objects, one tracklet per instant
            cand = np.flatnonzero((t_all == tt) & (who == objs[i % len(objs)]))
            cand = cand if len(cand) else np.flatnonzero(t_all == tt)
            one_per_t[cand[0]] = True
        variants = {"field object only": who == o, f"one companion only ({plan.names[comps[0]]})":
                    who == comps[0], "mixed, one tracklet per instant": one_per_t,
                    "all tracklets (the old field series)": np.ones(len(pts), bool)}
        sep = np.degrees(np.arccos(np.clip(np.sum(plan.truth_direction(o, s, tq)
                                                  * plan.truth_direction(comps[0], s, tq), 1),
                                           -1, 1))).mean() * 3600
        for name, sel in variants.items():
            if sel.sum() < 4:
                continue
            t = t_all[sel]
            d = np.stack([pts[i][1] for i in np.flatnonzero(sel)])
            ra, dec = _radec_arcsec(d)
            row = {"station": cfg.stations[s].name, "object": plan.names[o], "series": name,
                   "n_fit": int(sel.sum()), "repeated_times": int(len(t) - len(np.unique(t))),
                   "companion_separation_arcsec": float(sep)}
            for m in methods:
                try:
                    pr = fit_predict(m, t, ra - ra[0], tq, rng=rng, threshold=threshold_arcsec)
                    pd_ = fit_predict(m, t, dec - dec[0], tq, rng=rng,
                                      threshold=threshold_arcsec)
                except ValueError:
                    row[m] = np.nan
                    continue
                ra_p = (pr + ra[0]) / ARCSEC_PER_RAD
                de_p = (pd_ + dec[0]) / ARCSEC_PER_RAD
                v = np.stack([np.cos(de_p) * np.cos(ra_p), np.cos(de_p) * np.sin(ra_p),
                              np.sin(de_p)], 1)
                row[m] = float(np.sqrt(np.mean(_truth_err(plan, o, s, tq, v) ** 2)))
            rows.append(row)
        break  # the first cluster field a station can predict
    return pd.DataFrame(rows)


def paired_series_rms(prediction: pd.DataFrame, method: str = "lsq",
                      series: tuple[str, ...] = ("field", "catalogue", "confirmed")
                      ) -> pd.DataFrame:
    """A PAIRED comparison of the tracklet series: ``method``'s RMS error through the eclipse
    (″) on the (station, object) cases that every one of ``series`` predicts, one column per
    series, plus the RMS over those common cases (row ``"RMS (paired)"``). An RMS over each
    series' own rows would compare different objects (a case that drops out of one series
    moves its RMS)."""
    if not isinstance(prediction, pd.DataFrame):
        raise TypeError(f"prediction must be a DataFrame, got {type(prediction).__name__}")
    sel = prediction[(prediction["method"] == method) & prediction["series"].isin(series)]
    tab = sel.pivot_table(index=["station", "object"], columns="series", values="rms_arcsec")
    tab = tab.reindex(columns=list(series)).dropna()
    if len(tab):
        tab.loc[("RMS (paired)", f"{len(tab)} cases"), :] = np.sqrt((tab ** 2).mean())
    return tab


def hypothesis_count_study(night: NightResult, *, n_hypotheses: tuple[int, ...] = (3, 100),
                           fit_window_s: float = 7200.0, threshold_arcsec: float = 6.0
                           ) -> pd.DataFrame:
    """Why the RANSAC-type predictors can be far worse than least squares on CLEAN series.

    On every (series, station, object) whose fitted tracklets are all the object's own
    (scoring: ``n_wrong = 0``), RANSAC and WRANSAC are fitted with each number of minimal
    samples U in ``n_hypotheses`` (the capstone uses notebook 01's paper value U = 3) and
    scored like :func:`predict_through_eclipse`. Per row: points fitted, the RMS errors
    through the eclipse (″) of LSQ and of each method and U, the worse of the two over LSQ,
    ``ransac inliers U=…`` — the smallest fraction of the points (of the two coordinates) the
    best RANSAC hypothesis kept for its least-squares refit (1: the refit IS least squares) —
    and ``wransac weight U=…`` — the smallest mean refit weight ``1 − L_s`` of WRANSAC (1: its
    refit is least squares). Few points (one per tracklet) on a 4-parameter
    sinusoid-plus-drift: a minimal sample of 4 out of ≈ 8 is often ill-conditioned; with only
    3 draws the best one may leave good points outside the 6″ threshold (RANSAC refits on
    part of the window) or give them large residuals, hence small weights (WRANSAC refits
    with weights that distort the fit).
    """
    from eotrack.experiments.wransac import fit_predict

    plan, cfg = night.plan, night.plan.config
    series = _tracklet_series(plan, night.bursts, night.pairs)
    rows = []
    for name in ("field", "catalogue", "confirmed"):
        for (s, o), pts in sorted(series[name].items()):
            umb = plan.grid_shadow[o] == 2
            if not umb.any():
                continue
            t_in = plan.grid_s[np.argmax(umb)]
            t_out = plan.grid_s[len(umb) - 1 - np.argmax(umb[::-1])]
            tq = plan.grid_s[(plan.grid_s >= t_in) & (plan.grid_s <= t_out)]
            tq = tq[_watch_mask(plan, s, o, tq)]
            pts = sorted((p for p in pts if t_in - fit_window_s <= p[0] < t_in),
                         key=lambda p: p[0])
            if len(tq) == 0 or len(pts) < 6 or any(p[2] != o for p in pts):
                continue
            t = np.array([p[0] for p in pts])
            if len(np.unique(t)) < len(t):
                continue
            ra, dec = _radec_arcsec(np.stack([p[1] for p in pts]))
            row = {"series": name, "station": cfg.stations[s].name, "object": plan.names[o],
                   "n_fit": len(t)}

            def score(pr, pd_, ra=ra, dec=dec, o=o, s=s, tq=tq):
                ra_p = (pr + ra[0]) / ARCSEC_PER_RAD
                de_p = (pd_ + dec[0]) / ARCSEC_PER_RAD
                v = np.stack([np.cos(de_p) * np.cos(ra_p), np.cos(de_p) * np.sin(ra_p),
                              np.sin(de_p)], 1)
                return float(np.sqrt(np.mean(_truth_err(plan, o, s, tq, v) ** 2)))

            rng = np.random.default_rng(cfg.seed + 3)
            row["lsq"] = score(fit_predict("lsq", t, ra - ra[0], tq, rng=rng),
                               fit_predict("lsq", t, dec - dec[0], tq, rng=rng))
            for u_ in n_hypotheses:
                kept = []
                for m in ("ransac", "wransac"):
                    pr, fa = fit_predict(m, t, ra - ra[0], tq, rng=rng, n_hypotheses=u_,
                                         threshold=threshold_arcsec, return_fit=True)
                    pd_, fd = fit_predict(m, t, dec - dec[0], tq, rng=rng, n_hypotheses=u_,
                                          threshold=threshold_arcsec, return_fit=True)
                    row[f"{m} U={u_}"] = score(pr, pd_)
                    if m == "ransac":
                        kept += [fa.inliers.mean(), fd.inliers.mean()]
                    else:
                        wts = min(fa.weights.mean(), fd.weights.mean())
                row[f"worst / lsq, U={u_}"] = max(row[f"ransac U={u_}"],
                                                  row[f"wransac U={u_}"]) / row["lsq"]
                row[f"ransac inliers U={u_}"] = float(min(kept))
                row[f"wransac weight U={u_}"] = float(wts)
            rows.append(row)
    return pd.DataFrame(rows)


def ray_error_split(night: NightResult) -> pd.DataFrame:
    """Per-ray angle error (RMS, ″) of the tracklet hits by true object and by light (sunlit
    or penumbra), with the hit counts — which part of the chain's per-ray error comes from
    where (scoring)."""
    rows = []
    for r in night.bursts:
        for t in r.tracks:
            if t["true_obj"] < 0:
                continue
            for e, h in zip(t["ray_err_arcsec"], t["penumbra"]):
                rows.append((night.plan.names[t["true_obj"]], "penumbra" if h else "sunlit", e))
    d = pd.DataFrame(rows, columns=["object", "light", "err"])
    if len(d) == 0:
        return pd.DataFrame(columns=["object", "light", "hits", "rms_arcsec"])
    g = d.groupby(["object", "light"])["err"]
    out = pd.DataFrame({"hits": g.size(), "rms_arcsec": g.apply(lambda x: _rms(x))})
    for light in ("sunlit", "penumbra"):
        sel = d[d["light"] == light]["err"]
        out.loc[("all", light), :] = [len(sel), _rms(sel)]
    out.loc[("all", "all"), :] = [len(d), _rms(d["err"])]
    return out


def expected_completeness(config: CapstoneConfig | None = None) -> float:
    """Expected fraction of sunlit frames in which the extractor finds an object, before the
    run: the peak pixel (PSF centred at a uniformly random sub-pixel phase) above
    ``detect_sigma`` background σ, ``mean Φ(S/N_peak(phase) − detect_sigma)``. Blends with
    stars and the field edge are not in it (they can only lower the measured value)."""
    cfg = _config(config)
    f = 10 ** (-0.4 * (cfg.target_mag - cfg.zero_point_mag))
    from scipy.special import erf

    ph = (np.arange(8) + 0.5) / 8 - 0.5
    px, py = np.meshgrid(ph, ph)
    s = cfg.psf_sigma_px * np.sqrt(2)

    def frac(p):  # flux fraction of the pixel holding the PSF centre, 1-D
        return 0.5 * (erf((0.5 - p) / s) + erf((0.5 + p) / s))

    peak = f * frac(px) * frac(py)
    noise = np.sqrt(cfg.sky_e + cfg.read_noise_e ** 2 + peak)
    return float(np.mean(norm.cdf(peak / noise - cfg.detect_sigma)))


def expected_recall(config: CapstoneConfig | None = None, *,
                    completeness: float | None = None) -> float:
    """Expected initiation recall before the run: the initiator's ``(m−1)/m`` confirmation
    rule (``m = min(n, 4)``: 3 hits in some window of 4 consecutive frames of the burst's
    ``n``) met, each frame detected independently with probability ``completeness`` (default
    :func:`expected_completeness`). Exact sum over the ``2ⁿ`` detection patterns.

    It can exceed the per-frame completeness (0.67 per frame gives 0.70 with n = 5): a
    tracklet survives a missed frame. An earlier version required ``m`` of ``n`` frames (4 of
    5), which is not the initiator's rule and gave a lower expectation.
    """
    import itertools

    cfg = _config(config)
    p = expected_completeness(cfg) if completeness is None else float(completeness)
    if not 0.0 <= p <= 1.0:
        raise ValueError(f"completeness must lie in [0, 1], got {completeness}")
    n = cfg.burst_frames
    m = min(n, 4)
    total = 0.0
    for pat in itertools.product((0, 1), repeat=n):
        if any(sum(pat[i:i + m]) >= m - 1 for i in range(n - m + 1)):
            k = sum(pat)
            total += p ** k * (1.0 - p) ** (n - k)
    return float(total)


def scorecard(night: NightResult, *, same_on_cluster: bool | None = None,
              night_wall_s: float | None = None, night_cpu_s: float | None = None
              ) -> pd.DataFrame:
    """Stage criteria stated before the run (from the configuration alone), and the verdicts.

    Each row: a short ``key`` (the same for every seed, :func:`seed_stability`), the stage, the
    criterion with its expected value (computed from the settings — S/N, CRLB, χ² bound,
    baseline — not from the run), the measured value and pass/fail.
    """
    cfg = night.plan.config
    val = dict(zip(night.budget["metric"], night.budget["value"]))
    c_exp = expected_completeness(cfg)
    r_exp = expected_recall(cfg)
    ray_exp = np.sqrt(2) * expected_ray_sigma_px(cfg) * cfg.pixel_scale_arcsec  # 2-D RMS ″
    sg = night.sigma or {}
    R = sg.get("range_km", np.nan)
    bperp = sg.get("b_perp_km", np.nan)
    sr_crlb = R ** 2 / bperp * ray_exp / ARCSEC_PER_RAD  # √2 × per-axis CRLB = both rays
    n_cl = int(night.pairs["cluster"].sum()) if len(night.pairs) else 0
    fa = night.false_association
    p_w = float(fa[fa["cluster"]]["p_wrong_nearer"].mean()) if len(fa) and fa["cluster"].any() \
        else 0.0
    slack = 3 * np.sqrt(max(p_w * (1 - p_w), 1e-12) / max(n_cl, 1))
    pm = val["plate solution: its own error model at the objects (RMS)"]
    pt = val["plate solution: true error at the objects (RMS)"]
    rows = [
        ("completeness", "extraction", f"completeness ≥ S/N expectation {c_exp:.3f} − 0.10 (an allowance, fixed "
         "before the run, for blends with stars and the field edge, which the S/N model omits)",
         val["target completeness (sunlit frames)"],
         val["target completeness (sunlit frames)"] >= c_exp - 0.10),
        ("plate error", "astrometry", "true plate error (RMS) within ×/÷ 1.5 of the solution's own error model "
         f"({pm:.3f}″)", pt, bool(np.isfinite(pm) and 1 / 1.5 <= pt / pm <= 1.5)),
        ("recall", "initiation", f"recall ≥ 0.9 × expected {r_exp:.3f} (3 of 4 consecutive frames "
         "detected)",
         val["recall (object-bursts with ≥ 3 sunlit frames)"],
         val["recall (object-bursts with ≥ 3 sunlit frames)"] >= 0.9 * r_exp),
        ("per-ray error", "triangulation", f"per-ray error (RMS) ≤ 1.5 × CRLB {ray_exp:.2f}″",
         val["per-ray angle error (RMS, tracklet hits)"],
         val["per-ray angle error (RMS, tracklet hits)"] <= 1.5 * ray_exp),
        ("range error", "triangulation", f"RMS range error ≤ 1.5 × R²σ/B⊥ with the CRLB σ ({sr_crlb:.2f} km; R "
         "and B⊥ of the associated pairs)", val["RMS range error"],
         bool(np.isfinite(sr_crlb) and val["RMS range error"] <= 1.5 * sr_crlb)),
        ("range consistency", "triangulation", "consistency check AFTER the run: RMS range error within ×/÷ 1.5 of "
         f"R²σ_θ/B⊥ with the measured in-plane ray errors ({sg.get('measured_km', np.nan):.2f} "
         "km)", val["RMS range error"],
         bool(np.isfinite(sg.get("measured_km", np.nan))
              and 1 / 1.5 <= val["RMS range error"] / sg["measured_km"] <= 1.5)),
        ("cluster association", "association", f"correct pairs, cluster field ≥ 1 − χ² expectation {p_w:.3f} (wrong "
         f"partner nearer, the gate's σ) − 3 binomial σ over {n_cl} pairs ({slack:.3f})",
         val["correct pairs, cluster field"],
         val["correct pairs, cluster field"] >= 1 - p_w - slack),
    ]
    orb, cur = paired_orbit_curve(night.prediction)
    rows.append(("orbit vs curve", "prediction", "orbit RMS through the eclipse ≤ the best sinusoid predictor, "
                 f"paired on the {len(orb)} station–object cases both predict (curve "
                 f"{_rms(cur):.2f}″)", _rms(orb), bool(len(orb) and _rms(orb) <= _rms(cur))))
    if night_wall_s is not None:
        import os

        rows.append(("night wall time", "runtime", "whole night ≤ 120 s wall on this machine (load "
                     f"{os.getloadavg()[0]:.0f} on 2 cores at the end)", night_wall_s,
                     night_wall_s <= 120.0))
    if night_cpu_s is not None:
        rows.append(("night CPU time", "runtime", "whole night ≤ 120 s CPU (what an idle machine takes)",
                     night_cpu_s, night_cpu_s <= 120.0))
    if same_on_cluster is not None:
        rows.append(("serial == cluster", "runtime", "serial == Dask LocalCluster (identical budget)",
                     float(same_on_cluster), bool(same_on_cluster)))
    return pd.DataFrame(rows, columns=["key", "stage", "criterion (stated before the run)",
                                       "measured", "pass"])


def seed_stability(scorecards: dict[int, pd.DataFrame]) -> pd.DataFrame:
    """The scorecard over independent root seeds (``{seed: scorecard(...)}``, the criteria as
    stated before the runs, unchanged): per criterion ``key``, the measured value and
    pass/fail per seed, and ``passes`` = ``"k/K"`` — a criterion that passes on some seeds only
    is **fragile**, as in the repro machinery's stability runs (``--seeds K``)."""
    if not isinstance(scorecards, dict) or not scorecards:
        raise ValueError("scorecards must be a non-empty {seed: scorecard} dict")
    keys = list(dict.fromkeys(k for sc in scorecards.values() for k in sc["key"]))
    rows = []
    for k in keys:
        row = {"key": k}
        n_pass = 0
        for sd, sc in scorecards.items():
            hit = sc[sc["key"] == k]
            if not len(hit):
                row[f"seed {sd}"] = "—"
                continue
            ok = bool(hit["pass"].iloc[0])
            n_pass += ok
            row[f"seed {sd}"] = f"{hit['measured'].iloc[0]:.3g} {'✓' if ok else '✗'}"
        n = sum(1 for sc in scorecards.values() if (sc["key"] == k).any())
        row["passes"] = f"{n_pass}/{n}" + ("" if n_pass in (0, n) else " fragile")
        rows.append(row)
    return pd.DataFrame(rows).set_index("key")


#: Sky levels (e⁻/px) of the noise sweep behind the widget.
SKY_LEVELS = (400.0, 1600.0, 6400.0, 25600.0)


def noise_sweep(config: CapstoneConfig | None = None, levels: tuple[float, ...] = SKY_LEVELS,
                *, runner: TrialRunner | None = None,
                known: dict[float, NightResult] | None = None) -> pd.DataFrame:
    """The error budget at several sky levels (non-strict runs: a failed stage gives NaN).

    Returns
    -------
    pandas.DataFrame
        Rows = budget metrics (``stage · metric``), columns = sky levels, plus the target's
        peak S/N per level in the row ``"target peak S/N"``; ``attrs["nights"]`` says which
        night (the QUICK night, or how many bursts) — the Explore figure's title shows it.

    Parameters
    ----------
    known
        Runs already made, keyed by sky level (reused instead of re-running that level).
    """
    cfg = _config(config)
    if len(levels) == 0 or not all(np.isfinite(v) and v > 0 for v in levels):
        raise ValueError(f"levels must be positive sky levels (e⁻/px), got {levels!r}")
    cols = {}
    for lv in levels:
        c = replace(cfg, sky_e=float(lv))
        res = (known or {}).get(float(lv))
        if res is None or res.plan.config != c:
            res = run_night(c, runner=runner, strict=False)
        b = res.budget
        col = pd.Series(b["value"].to_numpy(float),
                        index=[f"{s} · {m}" for s, m in zip(b["stage"], b["metric"])])
        col["target peak S/N"] = target_peak_snr(c)
        cols[float(lv)] = col
    out = pd.DataFrame(cols)
    n_b = len(make_plan(cfg).bursts)
    out.attrs["nights"] = ("QUICK nights" if replace(cfg, sky_e=quick_config().sky_e)
                           == quick_config() else f"nights of {n_b} bursts")
    return out
