"""The chain: frames → extraction → star/target separation → initiation → association →
triangulation → prediction through the eclipse, and its error budget.

Each burst (one station, one object, one visit) is one seeded *trial* of
:class:`eotrack.montecarlo.TrialRunner`: the same code runs serially, on local processes or on a
Dask cluster, with bit-identical results (trial ``i`` always gets the same generator).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np
import pandas as pd

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
    extract_stars,
    render_gaussian_spots,
    star_count_slope,
    synthetic_faint_stars,
)
from eotrack.montecarlo import TrialRunner
from eotrack.tracking.initiation import ModifiedHoughInitiator

from .scenario import (
    ARCSEC_PER_RAD,
    EARTH_RATE_RAD_S,
    CapstoneConfig,
    NightPlan,
    camera_matrix,
    make_plan,
)

__all__ = [
    "PREDICTORS",
    "SKY_LEVELS",
    "BurstResult",
    "NightResult",
    "associate_tracklets",
    "burst_index",
    "eclipse_check",
    "error_budget",
    "noise_sweep",
    "observe_burst",
    "predict_through_eclipse",
    "range_error_km",
    "render_frame",
    "run_night",
    "separate_targets",
    "sidereal_drift_px",
    "target_peak_snr",
    "triangulate_pairs",
]

#: The robust predictors of notebook 01 compared through the eclipse.
PREDICTORS = ("lsq", "ransac", "wransac")
MATCH_PX = 2.5      # catalogue / sidereal-partner match radius (px)
TRUTH_PX = 2.0      # a detection within this of the true target is the target


def burst_index(rng: np.random.Generator) -> int:
    """Index of the trial a runner's generator belongs to (its ``SeedSequence`` spawn key).

    :meth:`eotrack.montecarlo.TrialRunner.map` gives trial ``i`` the generator spawned ``i``-th
    from the root seed, on every backend; the spawn key carries ``i``.
    """
    key = rng.bit_generator.seed_seq.spawn_key
    if not key:
        raise ValueError("rng was not spawned by a TrialRunner (empty spawn key)")
    return int(key[-1])


@dataclass
class BurstResult:
    """What one burst produced (and its truth bookkeeping).

    Attributes
    ----------
    station, obj, visit
        Burst identity.
    n_detections, n_catalogue, n_candidates, n_false_candidates
        Per-frame counts: detections, detections matched to catalogue stars, target candidates
        left after separation, candidates that are not the target.
    target_lit, target_detected, target_kept
        Per frame: target sunlit in the field; detected by the extractor; kept as candidate.
    tracks
        One dict per confirmed track: ``frames`` (indices), ``xy`` ``(k, 2)``, ``dirs``
        (unit GCRS directions ``(k, 3)``), ``true`` (the target's track).
    """

    station: int
    obj: int
    visit: int
    n_detections: np.ndarray
    n_catalogue: np.ndarray
    n_candidates: np.ndarray
    n_false_candidates: np.ndarray
    target_lit: np.ndarray
    target_detected: np.ndarray
    target_kept: np.ndarray
    tracks: list = field(default_factory=list)


@lru_cache(maxsize=8)
def _catalogue_band(dec_deg: int, max_mag: float, jyear: float):
    """Catalogue stars brighter than ``max_mag`` within 10° of declination ``dec_deg``."""
    from eotrack.astro import load_catalog

    cat = load_catalog()
    cat = cat.select(slice(0, int(np.searchsorted(cat.mag, float(max_mag), side="right"))))
    cat = cat.select(np.abs(cat.dec_deg - dec_deg) < 10.0).at_epoch(jyear)
    return cat.unit_vectors(), cat.mag


def _stars_for_burst(rng, plan: NightPlan, b) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Unit directions, magnitudes and catalogue flags of the stars around the burst's field.

    Catalogue stars (G ≤ ``catalogue_mag``) within 1.6 fields of the boresight, plus synthetic
    fainter stars following the catalogue's own count slope (uncatalogued: only their motion
    marks them as stars).
    """
    cfg = plan.config
    bore = b.R[0][2]
    dec0 = round(np.degrees(np.arcsin(bore[2])))
    u, m = _catalogue_band(dec0, cfg.catalogue_mag, round(float(plan.t0.jyear), 2))
    cosang = u @ bore
    radius = cfg.fov_deg * 1.6
    near = cosang >= np.cos(np.radians(radius))
    wide = cosang >= np.cos(np.radians(8.0))
    a, slope = star_count_slope(m[wide], cfg.catalogue_mag - 3.0, cfg.catalogue_mag)
    cone_sr = 2 * np.pi * (1 - np.cos(np.radians(8.0)))
    n_pix = 2 * cfg.size_px
    K = camera_matrix(cfg)
    Kw = K.copy()
    Kw[0, 2] = Kw[1, 2] = (n_pix - 1) / 2.0
    img_sr = (n_pix / K[0, 0]) ** 2
    xy_f, mag_f = synthetic_faint_stars(rng, a, slope, cfg.catalogue_mag, cfg.star_limit_mag,
                                        (n_pix, n_pix), area_fraction=img_sr / cone_sr)
    dirs_f = pixel_rays(xy_f, Kw, b.R[0]) if len(xy_f) else np.zeros((0, 3))
    dirs = np.concatenate([u[near], dirs_f])
    mag = np.concatenate([m[near], mag_f])
    cat = np.concatenate([np.ones(near.sum(), bool), np.zeros(len(mag_f), bool)])
    return dirs, mag, cat


def render_frame(rng, plan: NightPlan, b, k: int, dirs: np.ndarray, mag: np.ndarray
                 ) -> np.ndarray:
    """One frame (e⁻): trailed stars, the target, sky with a gradient, Poisson + read noise."""
    cfg = plan.config
    K = camera_matrix(cfg)
    n = cfg.size_px
    mid = project_directions(dirs, K, b.R[k])
    end = project_directions(dirs, K, b.R_end[k])
    start = 2 * mid - end
    flux = 10 ** (-0.4 * (mag - cfg.zero_point_mag))
    sub = 3  # trail sampled at 3 sub-exposures
    w = np.linspace(0, 1, sub)
    pts = (start[None] + w[:, None, None] * (end - start)[None]).reshape(-1, 2)
    fl = np.tile(flux / sub, sub)
    ok = (pts[:, 0] > -8) & (pts[:, 0] < n + 8) & (pts[:, 1] > -8) & (pts[:, 1] < n + 8)
    yy, xx = np.mgrid[0:n, 0:n]
    img = cfg.sky_e * (1.0 + cfg.gradient * (xx + 0.5 * yy) / n)
    render_gaussian_spots((n, n), pts[ok], fl[ok], cfg.psf_sigma_px, out=img)
    if b.target_flux[k] > 0:
        render_gaussian_spots((n, n), b.target_xy[k][None], b.target_flux[k], cfg.psf_sigma_px,
                              out=img)
    img = rng.poisson(img).astype(float)
    img += rng.normal(0.0, cfg.read_noise_e, img.shape)
    return img


def separate_targets(det: list[np.ndarray], star_xy: list[np.ndarray], drift: np.ndarray,
                     size: int, radius: float = MATCH_PX
                     ) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Split detections into stars and target candidates.

    A detection is a star if it lies within ``radius`` of a catalogue star's predicted position,
    or if a detection of the previous (next) frame lies within ``radius`` of it shifted back
    (forward) by the sidereal drift ``drift[k]`` (px per frame step, ``(n-1, 2)``). A detection
    whose shifted positions fall off the frame in both neighbours cannot be tested (a star
    entering or leaving the field) and is not a candidate either.

    Parameters
    ----------
    det
        Detections ``(m_k, 2)`` per frame.
    star_xy
        Predicted positions of the catalogue stars per frame.
    drift
        Sidereal drift per frame step ``(n-1, 2)`` (px).
    size
        Frame side (px).
    radius
        Match radius (px).

    Returns
    -------
    is_catalogue, is_candidate
        Boolean masks per frame.
    """
    from scipy.spatial import cKDTree

    n = len(det)
    dr = np.asarray(drift, float).reshape(-1, 2)
    if len(dr) != n - 1 or len(star_xy) != n:
        raise ValueError(f"drift must have {n - 1} rows and star_xy {n} frames, got {len(dr)} "
                         f"and {len(star_xy)}")
    is_cat, is_cand = [], []
    trees = [cKDTree(d) if len(d) else None for d in det]

    def inside(p):
        return np.all((p > 1.0) & (p < size - 2.0), axis=1)

    for k in range(n):
        d = np.asarray(det[k], float).reshape(-1, 2)
        cat = np.zeros(len(d), bool)
        mov = np.zeros(len(d), bool)
        testable = np.zeros(len(d), bool)
        if len(d) and len(star_xy[k]):
            dist, _ = cKDTree(star_xy[k]).query(d)
            cat = dist < radius
        for j, sign in ((k - 1, -1.0), (k + 1, 1.0)):
            if not 0 <= j < n or not len(d):
                continue
            p = d + sign * dr[min(k, j)]
            ok = inside(p)
            testable |= ok
            if trees[j] is not None:
                dist, _ = trees[j].query(p)
                mov |= ok & (dist < radius)
        is_cat.append(cat)
        is_cand.append(~(cat | mov) & testable)
    return is_cat, is_cand


def _initiator(cfg: CapstoneConfig) -> ModifiedHoughInitiator:
    # GEO targets: 0 … 0.5 px/s in a GEO-staring frame at 15″/px (inclined drifters ≈ 0.2 px/s).
    # Their angular acceleration over a burst of seconds is far below a pixel, so the
    # constant-acceleration search is off (accel_px_s2=0): its widened disc grows with the square
    # of the burst's span and would only admit chance tracks (and cost ~1 s per frame here).
    return ModifiedHoughInitiator(d_rho=3.0, d_theta_deg=10.0, d_v=0.05, v_min=0.0, v_max=0.5,
                                  m=min(cfg.burst_frames, 4), handoff_gate_px=3.0, sigma_px=0.3,
                                  accel_px_s2=0.0)


def observe_burst(rng: np.random.Generator, plan: NightPlan) -> BurstResult:
    """Trial function: render, extract, separate and initiate one burst of ``plan``.

    The burst is ``plan.bursts[burst_index(rng)]``.
    """
    b = plan.bursts[burst_index(rng)]
    cfg = plan.config
    K = camera_matrix(cfg)
    n = cfg.size_px
    dirs, mag, cat = _stars_for_burst(rng, plan, b)
    sky = SkyConfig(psf_sigma=cfg.psf_sigma_px, thresh=cfg.detect_sigma,
                    background=BackgroundConfig(mesh=32, filter_size=1))
    det, star_xy = [], []
    for k in range(cfg.burst_frames):
        img = render_frame(rng, plan, b, k, dirs, mag)
        det.append(np.asarray(extract_stars(img, config=sky).xy).reshape(-1, 2))
        star_xy.append(project_directions(dirs[cat], K, b.R[k]))
    c = np.array([[(n - 1) / 2, (n - 1) / 2]])
    rays_c = pixel_rays(c, K, b.R[0])
    track_c = np.array([project_directions(rays_c, K, b.R[k])[0]
                        for k in range(cfg.burst_frames)])
    drift = np.diff(track_c, axis=0)  # sidereal drift per frame step (px)
    is_cat, is_cand = separate_targets(det, star_xy, drift, n)
    inside = np.all((b.target_xy > 2) & (b.target_xy < n - 3), axis=1)
    lit = inside & (b.target_flux > 0)
    n_det, n_cat, n_cand, n_false = (np.zeros(cfg.burst_frames, int) for _ in range(4))
    t_det = np.zeros(cfg.burst_frames, bool)
    t_kept = np.zeros(cfg.burst_frames, bool)
    frames = []
    for k in range(cfg.burst_frames):
        d = det[k]
        near = np.hypot(*(d - b.target_xy[k]).T) < TRUTH_PX if len(d) else np.zeros(0, bool)
        near &= lit[k]
        n_det[k], n_cat[k] = len(d), int(is_cat[k].sum())
        n_cand[k] = int(is_cand[k].sum())
        n_false[k] = int((is_cand[k] & ~near).sum())
        t_det[k], t_kept[k] = bool(near.any()), bool((near & is_cand[k]).any())
        frames.append((float(b.times_s[k]), d[is_cand[k]]))
    tracks = []
    for tr in _initiator(cfg).initiate(frames):
        fi = np.array(tr.frame_indices)
        xy = np.array([frames[f][1][d] for f, d in tr.hits]).reshape(-1, 2)
        ray_cam = np.c_[(xy - K[0, 2]) / K[0, 0], np.ones(len(xy))]
        dirs_t = np.einsum("kji,kj->ki", b.R[fi], ray_cam)  # camera → world: Rᵀ
        dirs_t /= np.linalg.norm(dirs_t, axis=1, keepdims=True)
        err = np.hypot(*(xy - b.target_xy[fi]).T)
        true = bool(np.sum((err < TRUTH_PX) & lit[fi]) >= 3)
        tracks.append({"frames": fi, "xy": xy, "dirs": dirs_t, "true": true})
    return BurstResult(b.station, b.obj, b.visit, n_det, n_cat, n_cand, n_false, lit, t_det,
                       t_kept, tracks)


# ------------------------------------------------------------------ cross-station stages
def _track_dir(plan, res, tr, k):
    """Direction and station position of a track at frame k (None if no hit there)."""
    hit = np.flatnonzero(tr["frames"] == k)
    return None if len(hit) == 0 else tr["dirs"][hit[0]]


def associate_tracklets(plan: NightPlan, results: list[BurstResult], *, gate_px: float = 2.0
                        ) -> pd.DataFrame:
    """Associate tracklets of the two stations visit by visit with the epipolar constraint.

    At each visit, every tracklet of station 0 is compared with every tracklet of station 1 at
    a common frame: the epipolar distance (px, in station 1's image) of the pair, then
    one-to-one assignment below ``gate_px`` (:func:`eotrack.geometry.associate`, Hungarian).

    Returns
    -------
    pandas.DataFrame
        One row per associated pair: visit, frame, objects (truth) of each side, ``correct``,
        the two directions and station positions, the epipolar distance.
    """
    cfg = plan.config
    K = camera_matrix(cfg)
    by_visit: dict[int, list[list]] = {}
    for r, b in zip(results, plan.bursts):
        for tr in r.tracks:
            by_visit.setdefault(r.visit, [[], []])[r.station].append((r, b, tr))
    rows = []
    for j, (a_list, b_list) in sorted(by_visit.items()):
        if not a_list or not b_list:
            continue
        D = np.full((len(a_list), len(b_list)), np.inf)
        frame = np.full(D.shape, -1)
        for ia, (_ra, ba, ta) in enumerate(a_list):
            for ib, (_rb, bb, tb) in enumerate(b_list):
                common = np.intersect1d(ta["frames"], tb["frames"])
                if len(common) == 0:
                    continue
                k = int(common[len(common) // 2])
                F = fundamental_from_poses(K, ba.R[k], ba.c_km[k], K, bb.R[k], bb.c_km[k])
                xa = ta["xy"][ta["frames"] == k]
                xb = tb["xy"][tb["frames"] == k]
                D[ia, ib] = float(epipolar_distances(F, xa, xb)[0, 0])
                frame[ia, ib] = k
        pairs = associate(np.where(np.isfinite(D), D, 1e9), gate_px, rule="hungarian")
        for ia, ib in pairs:
            ra, ba, ta = a_list[ia]
            rb, bb, tb = b_list[ib]
            k = int(frame[ia, ib])
            rows.append({"visit": j, "frame": k, "t_s": float(ba.times_s[k]),
                         "obj_a": ra.obj if ta["true"] else -1,
                         "obj_b": rb.obj if tb["true"] else -1,
                         "correct": bool(ta["true"] and tb["true"] and ra.obj == rb.obj),
                         "epipolar_px": float(D[ia, ib]),
                         "dir_a": _track_dir(plan, ra, ta, k), "c_a": ba.c_km[k],
                         "dir_b": _track_dir(plan, rb, tb, k), "c_b": bb.c_km[k],
                         "truth_km": ba.target_gcrs_km[k] if ta["true"] else None})
    return pd.DataFrame(rows)


def triangulate_pairs(pairs: pd.DataFrame) -> pd.DataFrame:
    """Triangulate every associated pair (midpoint of the common perpendicular).

    Adds ``range_km`` (from station 0), ``range_err_km`` and ``pos_err_km`` (against SGP4,
    correct pairs only) and ``gap_km`` (miss distance of the two rays).
    """
    if len(pairs) == 0:
        return pairs.assign(range_km=[], range_err_km=[], pos_err_km=[], gap_km=[])
    o1 = np.stack(pairs["c_a"].to_numpy())
    d1 = np.stack(pairs["dir_a"].to_numpy())
    o2 = np.stack(pairs["c_b"].to_numpy())
    d2 = np.stack(pairs["dir_b"].to_numpy())
    p, gap = triangulate_two_rays(o1, d1, o2, d2, return_gap=True)
    rng_km = np.linalg.norm(p - o1, axis=1)
    err_r = np.full(len(p), np.nan)
    err_p = np.full(len(p), np.nan)
    for i, (ok, tr) in enumerate(zip(pairs["correct"], pairs["truth_km"])):
        if ok and tr is not None:
            err_r[i] = rng_km[i] - np.linalg.norm(tr - o1[i])
            err_p[i] = np.linalg.norm(p[i] - tr)
    return pairs.assign(range_km=rng_km, range_err_km=err_r, pos_err_km=err_p, gap_km=gap)


def _series(plan: NightPlan, results: list[BurstResult]) -> dict:
    """Per (station, object): times and measured unit directions of true-or-not tracklets."""
    out: dict[tuple[int, int], list] = {}
    for r, b in zip(results, plan.bursts):
        for tr in r.tracks:
            t = b.times_s[tr["frames"]]
            out.setdefault((r.station, r.obj), []).append((t.mean(), tr["dirs"].mean(0)))
    return out


def _radec_arcsec(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    d = d / np.linalg.norm(d, axis=-1, keepdims=True)
    ra = np.unwrap(np.arctan2(d[..., 1], d[..., 0]))
    dec = np.arcsin(np.clip(d[..., 2], -1, 1))
    return ra * ARCSEC_PER_RAD, dec * ARCSEC_PER_RAD


def predict_through_eclipse(plan: NightPlan, results: list[BurstResult], *,
                            methods: tuple[str, ...] = PREDICTORS, min_points: int = 6,
                            threshold_arcsec: float = 6.0, fit_window_s: float = 7200.0
                            ) -> pd.DataFrame:
    """Fit each station's pre-eclipse RA/Dec series of each object and predict through the umbra.

    Uses :func:`eotrack.experiments.wransac.fit_predict` (notebook 01's predictors, the
    sinusoid-plus-drift model); errors are against the SGP4 truth on a 1-min grid inside the
    umbra, as the great-circle angle (″). Only the ``fit_window_s`` before the umbra entry are
    fitted (notebook 01's paper fits 2 h).

    Raises
    ------
    ValueError
        Stage ``prediction``: no object enters the umbra during a station's observations.
    """
    from eotrack.experiments.wransac import fit_predict

    series = _series(plan, results)
    rows = []
    rng = np.random.default_rng(plan.config.seed + 1)
    any_eclipse = False
    for (s, o), pts in sorted(series.items()):
        umb = plan.grid_shadow[o] == 2
        if not umb.any():
            continue
        t_in = plan.grid_s[np.argmax(umb)]
        t_out = plan.grid_s[len(umb) - 1 - np.argmax(umb[::-1])]
        t = np.array([p[0] for p in pts])
        d = np.stack([p[1] for p in pts])
        before = (t < t_in) & (t >= t_in - fit_window_s)
        if before.sum() < min_points or t.max() < t_in:
            continue
        any_eclipse = True
        tq = plan.grid_s[(plan.grid_s >= t_in) & (plan.grid_s <= t_out)]
        ra, dec = _radec_arcsec(d[before])
        truth = plan.truth_direction(o, s, tq)
        for m in methods:
            pr = fit_predict(m, t[before], ra - ra[0], tq, rng=rng, threshold=threshold_arcsec)
            pd_ = fit_predict(m, t[before], dec - dec[0], tq, rng=rng,
                              threshold=threshold_arcsec)
            ra_p = (pr + ra[0]) / ARCSEC_PER_RAD
            de_p = (pd_ + dec[0]) / ARCSEC_PER_RAD
            v = np.stack([np.cos(de_p) * np.cos(ra_p), np.cos(de_p) * np.sin(ra_p),
                          np.sin(de_p)], 1)
            err = np.degrees(np.arccos(np.clip(np.sum(v * truth, 1), -1, 1))) * 3600
            rows.append({"station": plan.config.stations[s].name, "object": plan.names[o],
                         "method": m, "n_fit": int(before.sum()),
                         "eclipse_min": (t_out - t_in) / 60, "rms_arcsec": float(np.sqrt(
                             np.mean(err ** 2))), "max_arcsec": float(err.max())})
    if not any_eclipse:
        raise ValueError("stage 'prediction': no object enters the Earth's umbra while a "
                         f"station has at least {min_points} tracklets of it before — a night "
                         "with no eclipse (GEO eclipses happen near the equinoxes, around the "
                         "satellite's local midnight)")
    return pd.DataFrame(rows)


@dataclass
class NightResult:
    """Everything the chain produced for one night."""

    plan: NightPlan
    bursts: list[BurstResult]
    pairs: pd.DataFrame
    prediction: pd.DataFrame
    budget: pd.DataFrame
    wall_s: dict = field(default_factory=dict)


def error_budget(plan: NightPlan, bursts: list[BurstResult], pairs: pd.DataFrame,
                 prediction: pd.DataFrame) -> pd.DataFrame:
    """The stage-by-stage error budget (one row per metric)."""
    lit = np.concatenate([r.target_lit for r in bursts])
    det = np.concatenate([r.target_detected for r in bursts])
    kept = np.concatenate([r.target_kept for r in bursts])
    n_frames = len(lit)
    false_c = int(sum(r.n_false_candidates.sum() for r in bursts))
    n_det = int(sum(r.n_detections.sum() for r in bursts))
    lit_b = [r for r in bursts if r.target_lit.sum() >= 3]
    found = sum(any(t["true"] for t in r.tracks) for r in lit_b)
    n_tracks = sum(len(r.tracks) for r in bursts)
    false_t = sum(not t["true"] for r in bursts for t in r.tracks)
    n_pairs = len(pairs)
    correct = int(pairs["correct"].sum()) if n_pairs else 0
    tri = pairs.dropna(subset=["range_err_km"]) if n_pairs else pairs
    rows = [
        ("frames", "frames rendered", n_frames, ""),
        ("extraction", "detections per frame", n_det / max(n_frames, 1), ""),
        ("extraction", "target completeness (sunlit frames)", det[lit].mean() if lit.any()
         else np.nan, "fraction"),
        ("separation", "target kept as candidate", kept[lit].mean() if lit.any() else np.nan,
         "fraction"),
        ("separation", "false candidates per frame", false_c / max(n_frames, 1), ""),
        ("initiation", "recall (bursts with ≥ 3 sunlit frames)",
         found / max(len(lit_b), 1), "fraction"),
        ("initiation", "false tracks", false_t, "count"),
        ("initiation", "tracks", n_tracks, "count"),
        ("association", "pairs associated", n_pairs, "count"),
        ("association", "correct pairs", correct / max(n_pairs, 1), "fraction"),
        ("triangulation", "median |range error|",
         float(np.median(np.abs(tri["range_err_km"]))) if len(tri) else np.nan, "km"),
        ("triangulation", "RMS position error",
         float(np.sqrt(np.mean(tri["pos_err_km"] ** 2))) if len(tri) else np.nan, "km"),
    ]
    for m in PREDICTORS:
        sel = prediction[prediction["method"] == m] if len(prediction) else prediction
        rows.append(("prediction", f"{m}: RMS error through the eclipse",
                     float(np.sqrt(np.mean(sel["rms_arcsec"] ** 2))) if len(sel) else np.nan,
                     "arcsec"))
    return pd.DataFrame(rows, columns=["stage", "metric", "value", "unit"])


def eclipse_check(plan: NightPlan, *, min_lead_s: float = 7200.0) -> list[tuple[int, int]]:
    """(station, object) pairs whose umbra entry a station watches with ``min_lead_s`` of dark
    observing before it.

    Raises
    ------
    ValueError
        Stage ``prediction``: a night with no eclipse to predict through.
    """
    cfg = plan.config
    out = []
    for o in range(len(cfg.norad_ids)):
        umb = plan.grid_shadow[o] == 2
        if not umb.any():
            continue
        t_in = plan.grid_s[np.argmax(umb)]
        for s in range(len(cfg.stations)):
            ok = plan.dark[s] & (plan.elevation_deg[s, o] > cfg.min_elevation_deg)
            watched = plan.visit_s[ok]
            if np.any((watched < t_in) & (watched >= t_in - min_lead_s)) and \
                    np.any(watched >= t_in):
                out.append((s, o))
    if not out:
        raise ValueError(f"stage 'prediction': a night with no eclipse — no object enters the "
                         f"Earth's umbra while a station watches it (from {plan.t0.iso}, "
                         f"{cfg.night_hours} h); GEO eclipses happen within about 6 weeks of "
                         "an equinox, around the satellite's local midnight")
    return out


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
        ``prediction`` (a night with no eclipse; checked before any frame is rendered),
        ``extraction`` (no target detected in any frame), ``initiation`` (no track),
        ``association`` (no cross-station pair).
    """
    cfg = config or CapstoneConfig()
    if not isinstance(cfg, CapstoneConfig):
        raise TypeError(f"config must be a CapstoneConfig, got {type(cfg).__name__}")
    runner = runner if runner is not None else TrialRunner(progress=False)
    if not isinstance(runner, TrialRunner):
        raise TypeError(f"runner must be a TrialRunner, got {type(runner).__name__}")
    wall = {}
    t = time.perf_counter()
    plan = make_plan(cfg)
    eclipse_check(plan)
    wall["sky"] = time.perf_counter() - t
    t = time.perf_counter()
    bursts = runner.map(observe_burst, len(plan.bursts), seed=cfg.seed, args=(plan,),
                        desc="bursts")
    wall["frames"] = time.perf_counter() - t
    empty_pairs = triangulate_pairs(pd.DataFrame())
    empty_pred = pd.DataFrame(columns=["station", "object", "method", "rms_arcsec"])
    t = time.perf_counter()
    pairs, pred = empty_pairs, empty_pred
    try:
        if not any(r.target_kept.any() for r in bursts):
            raise ValueError(f"stage 'extraction': no target detected in any of "
                             f"{sum(len(r.target_lit) for r in bursts)} frames — no detection "
                             f"left after star removal lies at a target (targets of magnitude "
                             f"{cfg.target_mag} against a sky of {cfg.sky_e} e⁻/px)")
        if not any(r.tracks for r in bursts):
            raise ValueError("stage 'initiation': no track confirmed in any of "
                             f"{len(bursts)} bursts")
        pairs = triangulate_pairs(associate_tracklets(plan, bursts))
        if len(pairs) == 0:
            raise ValueError("stage 'association': no tracklet of one station matched one of "
                             "the other — do the stations observe at the same times?")
        pred = predict_through_eclipse(plan, bursts)
    except ValueError:
        if strict:
            raise
        pred = empty_pred
    wall["cross-station"] = time.perf_counter() - t
    return NightResult(plan, bursts, pairs, pred, error_budget(plan, bursts, pairs, pred), wall)


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
        peak S/N per level in the row ``"target peak S/N"``.

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
    return pd.DataFrame(cols)
