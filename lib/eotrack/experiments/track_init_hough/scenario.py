"""Scenes of the Xu & Wang (2016) reproduction: the 4-frame experiment rebuilt on real star
positions, the method-comparison scenes, and random planted scenes the initiators were not tuned
to; plus the scoring of an initiator's tracks against the truth.

The paper's settings (field, frame rate, velocity gate, cells, rule) are read from
``papers_repro/track_init_hough/claims.toml``. Table 1 (the planted objects) is lost in the
source text: :data:`XU_TARGETS` is our choice, made to satisfy the text (one object in all four
frames, two that miss frame 3 and frame 2, two nearly overlapping ones that miss frame 1).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from eotrack.astro import stars_in_field
from eotrack.repro import load_claims
from eotrack.tracking.initiation.base import Track
from eotrack.tracking.initiation.hough import HoughInitiator
from eotrack.tracking.initiation.logic import LogicInitiator
from eotrack.tracking.initiation.modified_hough import ModifiedHoughInitiator
from eotrack.validation import check_generator, check_positive, check_probability

__all__ = [
    "HELDOUT_CODE",
    "HELDOUT_EARLY_RUNS",
    "HELDOUT_OPTS",
    "HELDOUT_SEED",
    "HELDOUT_SEED_FIRST",
    "HELDOUT_SEED_FOURTH",
    "HELDOUT_SEED_SECOND",
    "HELDOUT_SEED_THIRD",
    "HELDOUT_TARGETS",
    "SLUG",
    "XU_TARGETS",
    "ComparisonConfig",
    "PlantedConfig",
    "PlantedTarget",
    "Scene",
    "comparison_initiators",
    "comparison_scene",
    "gnomonic_to_pixels",
    "make_xu_scene",
    "planted_initiators",
    "planted_scene",
    "score_tracks",
    "xu_config",
    "xu_initiator",
]

SLUG = "track_init_hough"


# --------------------------------------------------------------------------- the Xu & Wang scene
@dataclass(frozen=True)
class PlantedTarget:
    """A constant-velocity object: position at frame 0 (pixels), velocity (px/s), frames seen."""

    name: str
    xy0_px: tuple[float, float]
    v_px_s: tuple[float, float]
    frames: tuple[int, ...]


#: Our Table 1 (the paper's numbers are lost): positions at the first frame's time (for tracks 4
#: and 5, which are first seen in frame 2, the back-extrapolated position), 0-based frames.
#: Tracks 4 and 5 follow nearly the same path (directions 0.8° apart; track 5 passes within
#: 4.5 px of where track 4 was one frame earlier) at different speeds: the speed axis of the
#: (ρ, θ, v, s) space separates them. (Revised once: our first choice put them 1.3 px apart in
#: frame 2, closer than the centroid noise can resolve; track 3 was moved once off a star.)
XU_TARGETS: tuple[PlantedTarget, ...] = (
    PlantedTarget("track 1 (real object)", (62.0, 431.0), (36.5, -21.0), (0, 1, 2, 3)),
    PlantedTarget("track 2", (71.0, 93.0), (41.0, 28.5), (0, 1, 3)),
    PlantedTarget("track 3", (446.0, 112.0), (-27.0, 46.0), (0, 2, 3)),
    PlantedTarget("track 4", (90.0, 308.0), (60.0, -8.0), (1, 2, 3)),
    PlantedTarget("track 5", (86.0, 311.0), (42.0, -5.0), (1, 2, 3)),
)


@dataclass(frozen=True)
class XuConfig:
    """The rebuilt 4-frame experiment; paper values are filled in from claims.toml.

    Attributes
    ----------
    ra_deg, dec_deg
        Pointing (ours: a Milky-Way field near the celestial equator, Monoceros).
    jyear
        Epoch of the star positions.
    max_mag
        Faintest catalogue star in the image (the catalogue is complete to G ≈ 10).
    residual_fraction
        Probability that star removal leaves a star in a frame (independent per star and frame).
    sigma_px
        Centroid noise (pixels, per axis).
    seed
        Seed of the nominal scene.
    """

    ra_deg: float = 100.0
    dec_deg: float = 0.0
    jyear: float = 2015.0
    max_mag: float = 10.0
    residual_fraction: float = 0.3
    sigma_px: float = 0.3
    seed: int = 2016
    targets: tuple[PlantedTarget, ...] = XU_TARGETS
    # paper settings (claims.toml), set by :func:`xu_config`
    width_px: int = 512
    fov_deg: float = 0.7
    frame_interval_s: float = 1.0
    n_frames: int = 4
    v_gate_px_s: tuple[float, float] = (10.0, 240.0)
    cell_rho_px: float = 5.0
    cell_theta_deg: float = 5.0
    cell_v_px_s: float = 3.0
    rule_m: int = 4


def xu_config(**changes: Any) -> XuConfig:
    """:class:`XuConfig` with the paper's settings loaded from claims.toml (plus ``changes``)."""
    p = load_claims(SLUG)["track_init.xu_table2"].paper
    base = XuConfig(width_px=int(p["image_px"][0]), fov_deg=float(p["field_deg"][0]),
                    frame_interval_s=1.0 / float(p["frame_rate_hz"]), n_frames=int(p["n_frames"]),
                    v_gate_px_s=tuple(float(v) for v in p["velocity_gate_px_s"]),
                    cell_rho_px=float(p["cell_rho_px"]), cell_theta_deg=float(p["cell_theta_deg"]),
                    cell_v_px_s=float(p["cell_v_px_s"]), rule_m=int(p["rule_m"]))
    return replace(base, **changes)


def xu_initiator(cfg: XuConfig, neighbourhood: int = 6, *,
                 literal: bool = True) -> ModifiedHoughInitiator:
    """The modified Hough initiator with the experiment's settings.

    ``literal=True`` (default) is the paper's procedure, with ``neighbourhood=6`` the paper's
    rule and 26 our robust variant (see the errata); ``literal=False`` is our verified
    initiator (χ² test at the centroid noise ``cfg.sigma_px``, best fit first).
    """
    return ModifiedHoughInitiator(d_rho=cfg.cell_rho_px, d_theta_deg=cfg.cell_theta_deg,
                                  d_v=cfg.cell_v_px_s, v_min=cfg.v_gate_px_s[0],
                                  v_max=cfg.v_gate_px_s[1], m=cfg.rule_m,
                                  neighbourhood=neighbourhood, literal=literal,
                                  sigma_px=cfg.sigma_px)


@dataclass
class Scene:
    """Frames of detections with their truth.

    ``labels[f][d]`` is the index of the planted object behind detection ``d`` of frame ``f``,
    or a negative code: −1 for clutter or a residual star of the Xu scene, ``−2 − s`` for
    residual star ``s`` of a planted scene. ``stars_px`` are all catalogue stars in the image;
    ``meta`` holds scene parameters (e.g. the clutter level).
    """

    frames: list[tuple[float, np.ndarray]]
    labels: list[np.ndarray]
    n_targets: int
    stars_px: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    truth_xy: list[np.ndarray] = field(default_factory=list)
    meta: dict = field(default_factory=dict)


def gnomonic_to_pixels(ra_deg: np.ndarray, dec_deg: np.ndarray, ra0_deg: float, dec0_deg: float,
                       scale_deg_px: float, centre_px: float) -> np.ndarray:
    """Gnomonic (tangent-plane) projection of sky positions to pixels, north up, east left.

    Returns ``(n, 2)`` pixel coordinates ``(x = column, y = row)``; ``(centre_px, centre_px)``
    is the pointing.
    """
    ra = np.radians(np.asarray(ra_deg, float))
    de = np.radians(np.asarray(dec_deg, float))
    a0, d0 = np.radians(float(ra0_deg)), np.radians(float(dec0_deg))
    cosc = np.sin(d0) * np.sin(de) + np.cos(d0) * np.cos(de) * np.cos(ra - a0)
    if np.any(cosc <= 0):
        raise ValueError("ra_deg/dec_deg include points 90° or more from the pointing")
    xi = np.cos(de) * np.sin(ra - a0) / cosc
    eta = (np.cos(d0) * np.sin(de) - np.sin(d0) * np.cos(de) * np.cos(ra - a0)) / cosc
    s = np.radians(check_positive(scale_deg_px, "scale_deg_px"))
    return np.stack([centre_px - xi / s, centre_px - eta / s], axis=1)


def _field_stars(cfg: XuConfig) -> np.ndarray:
    half = cfg.fov_deg / 2
    cat = stars_in_field(cfg.ra_deg, cfg.dec_deg, half * np.sqrt(2) * 1.01, max_mag=cfg.max_mag,
                         jyear=cfg.jyear)
    xy = gnomonic_to_pixels(cat.ra_deg, cat.dec_deg, cfg.ra_deg, cfg.dec_deg,
                            cfg.fov_deg / cfg.width_px, cfg.width_px / 2)
    inside = np.all((xy >= 0) & (xy < cfg.width_px), axis=1)
    return xy[inside]


def make_xu_scene(cfg: XuConfig, rng: np.random.Generator | None = None) -> Scene:
    """The 4-frame scene: the planted objects plus the stars left by imperfect star removal.

    The telescope tracks the stars (sidereal), so stars stay at fixed pixels; each star is left
    in each frame with probability ``residual_fraction``; every centroid gets Gaussian noise.
    Detections of a frame are shuffled.
    """
    rng = np.random.default_rng(cfg.seed) if rng is None else check_generator(rng)
    stars = _field_stars(cfg)
    frames, labels, truth = [], [], []
    for k in range(cfg.n_frames):
        t = k * cfg.frame_interval_s
        xy, lab = [], []
        tk = []
        for i, tg in enumerate(cfg.targets):
            p = np.array(tg.xy0_px) + np.array(tg.v_px_s) * t
            tk.append(p)
            if k in tg.frames:
                xy.append(p)
                lab.append(i)
        left = stars[rng.random(len(stars)) < cfg.residual_fraction]
        xy = np.concatenate([np.reshape(xy, (-1, 2)), left])
        lab = np.concatenate([np.asarray(lab, int), np.full(len(left), -1)])
        xy = xy + rng.normal(0.0, cfg.sigma_px, xy.shape)
        perm = rng.permutation(len(xy))
        frames.append((t, xy[perm]))
        labels.append(lab[perm])
        truth.append(np.array(tk))
    return Scene(frames, labels, len(cfg.targets), stars, truth)


# --------------------------------------------------------------------------- scoring
def score_tracks(tracks: list[Track], scene: Scene, *, n: int = 3, m: int = 4) -> dict[str, Any]:
    """Correct initiations and false tracks of one run.

    A track is *correct* when every detection up to its confirmation comes from one planted
    object (the first such track per object; later ones count as false). ``eligible`` objects
    have at least ``n`` detections in some ``m`` consecutive frames.

    Returns
    -------
    dict
        ``correct``, ``eligible``, ``false``, ``exact`` (every eligible object found with all
        its detections and no false track), ``confirm_frame`` (object → frame index).
    """
    found: dict[int, int] = {}
    complete: dict[int, bool] = {}
    n_false = 0
    for tr in tracks:
        ids = {int(scene.labels[f][d]) for f, d in tr.hits if f <= tr.confirmed_at}
        ident = next(iter(ids)) if len(ids) == 1 else -1
        if ident >= 0 and ident not in found:
            found[ident] = tr.confirmed_at
            all_ids = [int(scene.labels[f][d]) for f, d in tr.hits]
            n_obj = sum(int(np.sum(lab == ident)) for lab in scene.labels)
            complete[ident] = all(i == ident for i in all_ids) and len(all_ids) == n_obj
        else:
            n_false += 1
    n_frames = len(scene.labels)
    eligible = []
    for i in range(scene.n_targets):
        seen = np.array([np.any(lab == i) for lab in scene.labels], dtype=int)
        win = np.convolve(seen, np.ones(min(m, n_frames), dtype=int), mode="valid")
        if len(win) and win.max() >= n:
            eligible.append(i)
    correct = sum(1 for i in eligible if i in found)
    exact = (correct == len(eligible) and n_false == 0
             and all(complete.get(i, False) for i in eligible))
    return {"correct": correct, "eligible": len(eligible), "false": n_false,
            "exact": bool(exact), "confirm_frame": dict(found)}


# --------------------------------------------------------------------------- method comparison
@dataclass(frozen=True)
class ComparisonConfig:
    """Seeded scenes of the method comparison (all ours: the papers give no Monte Carlo).

    Attributes
    ----------
    n_targets, n_frames
        Objects per scene and frames per scene (1 Hz).
    speed_px_s
        Object speeds, uniform in this range (they stay in the field for all frames).
    clutter_levels
        Mean uniform Poisson false alarms per frame for the clutter sweep (at ``p_detect_nominal``).
    pd_levels
        Detection probabilities for the miss sweep (at ``clutter_nominal``).
    sigma_px
        Centroid noise.
    logic_gate_px
        Constant-velocity prediction gate of the logic initiators.
    hough_d_theta_deg
        θ cell of the classic Hough (its ρ cell is the paper's δρ).
    """

    n_targets: int = 4
    n_frames: int = 6
    width_px: int = 512
    speed_px_s: tuple[float, float] = (15.0, 70.0)
    clutter_levels: tuple[float, ...] = (0.0, 5.0, 10.0, 20.0, 30.0)
    pd_levels: tuple[float, ...] = (1.0, 0.9, 0.8, 0.7, 0.6)
    clutter_nominal: float = 10.0
    p_detect_nominal: float = 0.9
    sigma_px: float = 0.3
    logic_gate_px: float = 10.0
    hough_d_theta_deg: float = 1.0
    n_trials: int = 25
    seed: int = 5


def comparison_scene(rng: np.random.Generator, cfg: ComparisonConfig, clutter_per_frame: float,
                     p_detect: float) -> Scene:
    """Constant-velocity objects in uniform Poisson clutter, each detected with ``p_detect``."""
    check_generator(rng)
    lam = check_positive(clutter_per_frame, "clutter_per_frame", allow_zero=True)
    pd_ = check_probability(p_detect, "p_detect")
    w = float(cfg.width_px)
    span = cfg.n_frames - 1
    starts, vels = [], []
    while len(starts) < cfg.n_targets:
        sp = rng.uniform(*cfg.speed_px_s)
        ang = rng.uniform(0, 2 * np.pi)
        v = sp * np.array([np.cos(ang), np.sin(ang)])
        lo = np.maximum(0.0, -v * span) + 5
        hi = np.minimum(w, w - v * span) - 5
        if np.any(hi <= lo):
            continue
        starts.append(rng.uniform(lo, hi))
        vels.append(v)
    frames, labels, truth = [], [], []
    for k in range(cfg.n_frames):
        t = float(k)
        tk = np.array([s + v * t for s, v in zip(starts, vels)])
        det = rng.random(cfg.n_targets) < pd_
        nc = rng.poisson(lam)
        xy = np.concatenate([tk[det] + rng.normal(0, cfg.sigma_px, (int(det.sum()), 2)),
                             rng.uniform(0, w, (nc, 2))])
        lab = np.concatenate([np.flatnonzero(det), np.full(nc, -1)])
        perm = rng.permutation(len(xy))
        frames.append((t, xy[perm]))
        labels.append(lab[perm])
        truth.append(tk)
    return Scene(frames, labels, cfg.n_targets, truth_xy=truth)




def comparison_initiators(cfg: ComparisonConfig, xu: XuConfig | None = None) -> dict[str, Any]:
    """The initiators of the comparison, with the paper's gate and cells: the five methods of
    the collection (the modified Hough as the paper states it), its 26-neighbourhood variant
    and our verified modified Hough."""
    xu = xu or xu_config()
    vmin, vmax = xu.v_gate_px_s
    m = xu.rule_m
    return {
        "logic 2/3": LogicInitiator(n=2, m=3, v_min=vmin, v_max=vmax, gate_px=cfg.logic_gate_px),
        "logic 3/4": LogicInitiator(n=m - 1, m=m, v_min=vmin, v_max=vmax,
                                    gate_px=cfg.logic_gate_px),
        "angle logic 3/4": LogicInitiator(n=m - 1, m=m, v_min=vmin, v_max=vmax,
                                          gate_px=cfg.logic_gate_px, min_angle_deg=90.0),
        "classic Hough 3/4": HoughInitiator(d_rho=xu.cell_rho_px,
                                            d_theta_deg=cfg.hough_d_theta_deg, n=m - 1, m=m),
        "modified Hough 3/4": xu_initiator(xu),
        "modified Hough 3/4 (26-nbhd)": xu_initiator(xu, 26),
        "modified Hough 3/4 (ours)": xu_initiator(xu, literal=False),
    }



# --------------------------------------------------------------------------- planted scenes
@dataclass(frozen=True)
class PlantedConfig:
    """Random planted scenes (the criterion of claim ``track_init.planted_scenes``).

    Every scene draws its own number of objects, speeds and directions, residual stars and
    clutter level from these ranges, so no initiator can be tuned to one scene.

    Attributes
    ----------
    n_scenes
        Scenes of the Monte Carlo (``make repro`` and the notebook).
    width_px, n_frames, frame_interval_s
        Image side, frames per scene and their spacing.
    n_objects
        Objects per scene, uniform integer in this inclusive range.
    speed_px_s
        Object speed, uniform in this range (random direction, start anywhere in the field;
        an object is detected only while inside).
    p_detect
        Probability that an object is detected in a frame (missed frames).
    n_stars, star_residual
        Static residual stars per scene (uniform integer range) and the probability that star
        removal leaves one in a frame.
    clutter_per_frame
        Per-scene mean of the uniform Poisson clutter, uniform in this range.
    sigma_px
        Centroid noise (per axis).
    v_gate_px_s
        Velocity gate of every initiator.
    alpha
        False-rejection probability of the verified initiator's χ² test.
    logic_gate_px
        Prediction gate of the logic initiators.
    seed
        Master seed.
    """

    n_scenes: int = 100
    width_px: int = 512
    n_frames: int = 6
    frame_interval_s: float = 1.0
    n_objects: tuple[int, int] = (2, 8)
    speed_px_s: tuple[float, float] = (5.0, 150.0)
    p_detect: float = 0.9
    n_stars: tuple[int, int] = (10, 40)
    star_residual: float = 0.3
    clutter_per_frame: tuple[float, float] = (5.0, 50.0)
    sigma_px: float = 0.3
    v_gate_px_s: tuple[float, float] = (3.0, 240.0)
    alpha: float = 1e-3
    logic_gate_px: float = 10.0
    seed: int = 15


def planted_scene(rng: np.random.Generator, cfg: PlantedConfig | None = None, *,
                  clutter_per_frame: float | None = None, n_objects: int | None = None,
                  n_stars: int | None = None) -> Scene:
    """One random planted scene: constant-velocity objects, static residual stars, clutter.

    ``clutter_per_frame``, ``n_objects`` and ``n_stars`` override the random draws (e.g.
    ``n_objects=0, n_stars=0`` for the clutter-only scenes that check the chance rate).
    Labels: object index, −1 clutter, ``−2 − s`` residual star ``s``.
    """
    check_generator(rng)
    cfg = cfg or PlantedConfig()
    w = float(cfg.width_px)
    n_obj = int(rng.integers(cfg.n_objects[0], cfg.n_objects[1] + 1)) if n_objects is None \
        else int(n_objects)
    n_st = int(rng.integers(cfg.n_stars[0], cfg.n_stars[1] + 1)) if n_stars is None \
        else int(n_stars)
    lam = float(rng.uniform(*cfg.clutter_per_frame)) if clutter_per_frame is None else \
        check_positive(clutter_per_frame, "clutter_per_frame", allow_zero=True)
    if n_obj < 0 or n_st < 0:
        raise ValueError(f"n_objects and n_stars must be >= 0, got {n_obj} and {n_st}")
    speed = rng.uniform(*cfg.speed_px_s, n_obj)
    ang = rng.uniform(0, 2 * np.pi, n_obj)
    vel = speed[:, None] * np.stack([np.cos(ang), np.sin(ang)], 1)
    start = rng.uniform(0, w, (n_obj, 2))
    stars = rng.uniform(0, w, (n_st, 2))
    frames, labels, truth = [], [], []
    for k in range(cfg.n_frames):
        t = k * cfg.frame_interval_s
        pos = start + vel * t
        inside = np.all((pos >= 0) & (pos < w), axis=1)
        det = inside & (rng.random(n_obj) < cfg.p_detect)
        left = rng.random(n_st) < cfg.star_residual
        nc = int(rng.poisson(lam))
        xy = np.concatenate([pos[det], stars[left]])
        xy = xy + rng.normal(0.0, cfg.sigma_px, xy.shape)
        xy = np.concatenate([xy, rng.uniform(0, w, (nc, 2))])
        lab = np.concatenate([np.flatnonzero(det), -2 - np.flatnonzero(left),
                              np.full(nc, -1)]).astype(int)
        perm = rng.permutation(len(xy))
        frames.append((t, xy[perm]))
        labels.append(lab[perm])
        truth.append(pos)
    return Scene(frames, labels, n_obj, stars_px=stars, truth_xy=truth,
                 meta={"clutter_per_frame": lam, "n_stars": n_st, "speed_px_s": speed})


def planted_initiators(cfg: PlantedConfig | None = None, xu: XuConfig | None = None,
                       ) -> dict[str, Any]:
    """Every initiator of the planted-scene Monte Carlo, all with the scenes' velocity gate.

    The paper's cells and 3/4 rule for the Hough initiators; ``"modified Hough 3/4 (ours)"`` is
    the verified variant (``literal=False``: χ² test at ``cfg.sigma_px``, best fit first).
    """
    cfg = cfg or PlantedConfig()
    xu = xu or xu_config()
    vmin, vmax = cfg.v_gate_px_s
    m = xu.rule_m
    lit = {"d_rho": xu.cell_rho_px, "d_theta_deg": xu.cell_theta_deg, "d_v": xu.cell_v_px_s,
           "v_min": vmin, "v_max": vmax, "m": m}
    return {
        "logic 2/3": LogicInitiator(n=2, m=3, v_min=vmin, v_max=vmax, gate_px=cfg.logic_gate_px),
        "logic 3/4": LogicInitiator(n=m - 1, m=m, v_min=vmin, v_max=vmax,
                                    gate_px=cfg.logic_gate_px),
        "angle logic 3/4": LogicInitiator(n=m - 1, m=m, v_min=vmin, v_max=vmax,
                                          gate_px=cfg.logic_gate_px, min_angle_deg=90.0),
        "classic Hough 3/4": HoughInitiator(d_rho=xu.cell_rho_px, d_theta_deg=1.0, n=m - 1, m=m),
        "modified Hough 3/4 (paper)": ModifiedHoughInitiator(**lit, literal=True),
        "modified Hough 3/4 (ours)": ModifiedHoughInitiator(v_min=vmin, v_max=vmax, m=m,
                                                            sigma_px=cfg.sigma_px,
                                                            alpha=cfg.alpha),
    }


# --------------------------------------------------------------------------- held-out scenes
@dataclass(frozen=True)
class HeldOutConfig:
    """Held-out scenes the paper never had (issue 27): mildly accelerating objects, a clutter
    burst in one frame, irregular frame intervals and a lower detection probability.

    Attributes
    ----------
    n_frames, width_px
        Frames per scene and image side.
    dt_s
        Frame intervals drawn uniformly in this range (s).
    n_objects, speed_px_s
        Objects per scene and their initial speeds (uniform).
    accel_px_s2
        Along- and cross-track accelerations, each uniform in ``±accel_px_s2``.
    p_detect
        Detection probability.
    clutter_per_frame, burst
        Uniform Poisson clutter per frame (per-scene mean uniform in the range) and the extra
        false alarms of one random frame.
    n_stars, star_residual, sigma_px
        Residual stars, their per-frame probability and the centroid noise.
    """

    n_frames: int = 8
    width_px: int = 512
    dt_s: tuple[float, float] = (0.6, 1.6)
    n_objects: tuple[int, int] = (3, 8)
    speed_px_s: tuple[float, float] = (10.0, 120.0)
    accel_px_s2: float = 3.0
    p_detect: float = 0.8
    clutter_per_frame: tuple[float, float] = (5.0, 30.0)
    burst: int = 150
    n_stars: tuple[int, int] = (10, 30)
    star_residual: float = 0.3
    sigma_px: float = 0.3


#: the previous opt-in settings of :class:`~eotrack.tracking.initiation.ModifiedHoughInitiator`
#: for accelerating objects among clutter bursts, on the causal engine (chosen on seeds 11 and
#: 777: exploratory); since the growth stage became the default they are a comparison only
HELDOUT_OPTS: dict[str, Any] = {"grow": False, "hold_triplets": True, "accel_triplets": True,
                                "chance_budget": 2.0}
#: the first decisive held-out seed (fixed with its targets in commit 5dac231, 00:17 UTC, before it
#: was drawn). Its first run (60 scenes) is the result that counts for that code: recall 0.827,
#: 16.85 false tracks per scene; the density cap was changed after it (twice: the field over all
#: detections, then causal), so later numbers on this seed are post hoc.
HELDOUT_SEED_FIRST = 20261202
#: the second decisive seed (fixed 2026-12-02 01:43 UTC, before it was drawn): its run of that
#: code (default 0.665 recall / 13.88 false, opt-ins 0.812 / 17.03, logic 3/4 0.759 / 43.83) is the
#: result that counts for that code; from 05:55 UTC it is a development seed (the growth stage was
#: designed on it, on 11 and on 777), so numbers on it for later code are post hoc.
HELDOUT_SEED_SECOND = 20261204
#: the decisive held-out seed for the code after 05:55 UTC (fixed 2026-12-02 05:55 UTC, before it
#: was drawn, with the criterion below: the DEFAULT ``ModifiedHoughInitiator(v_min=3, v_max=240)``
#: on 60 scenes of :class:`HeldOutConfig` at ±3 px/s² must reach recall >= 0.90 with false tracks
#: per scene <= those of ``LogicInitiator(n=3, m=4, v_min=3, v_max=240, gate_px=10)`` on the same
#: scenes; the times per frame of ``benchmarks/bench_track_init_hough.py`` section 2 <= 5 ms at 200
#: and <= 50 ms at 1,000 candidates, measured at load < 2.5). Its single run (code 1fbbc7c: growth always on) met the criterion — recall 0.916, 32.57 false
#: per scene vs logic 3/4's 44.85 — but that code changed the paper's scenes (the Xu redraws exact
#: in 73 % instead of 100 %, planted false tracks 2.9x the chance rate), so the growth now runs
#: only where the data show accelerating objects and the result above is that earlier code's.
HELDOUT_SEED_THIRD = 20261207
#: the decisive seed for the code 64e5a2f (fixed at 06:51 UTC, before it was drawn; the same
#: criterion as for ``HELDOUT_SEED_THIRD``). Its single run: recall 0.885, 28.77 false per scene vs
#: logic 3/4's 0.774 / 43.57 — NOT met (the growth ran only where the causal result held an
#: accelerating track). Post hoc from 2026-12-02 15:35 UTC.
HELDOUT_SEED_FOURTH = 20261208
#: the decisive seed for the code 1b1c4c2 (fixed 2026-12-02 15:35 UTC, before it was drawn, with
#: the same criterion as for ``HELDOUT_SEED_THIRD``: the DEFAULT
#: ``ModifiedHoughInitiator(v_min=3, v_max=240)`` on 60 scenes of :class:`HeldOutConfig` at
#: ±3 px/s² must reach recall >= 0.90 with false tracks per scene <= those of
#: ``LogicInitiator(n=3, m=4, v_min=3, v_max=240, gate_px=10)`` on the same scenes; the times per
#: frame of ``benchmarks/bench_track_init_hough.py`` section 2 <= 5 ms at 200 and <= 50 ms at
#: 1,000 candidates, measured at load < 2.5). Run once for that code; the result is recorded
#: whatever it is. Its single run (2026-12-02 15:36 UTC, load 1.08 -> 1.04;
#: ``papers_repro/track_init_hough/heldout_benchmark.json``): recall 0.922, 33.62 false per
#: scene vs logic 3/4's 0.754 / 47.95 (recall and false-track parts met); CPU per frame 6.83 ms at
#: 200 candidates (> 5: NOT met; the unchanged causal engine that runs there took 6.57 ms in the
#: same run, 3.67 ms in 64e5a2f's record) and 37.6 ms at 1,000 (met): the criterion as a whole
#: is NOT met, on its time part.
HELDOUT_SEED = 20261209
#: the code the decisive run of :data:`HELDOUT_SEED` judges
HELDOUT_CODE = "1b1c4c2"
#: the first two decisive runs, as recorded when they were made (no JSON record was kept then;
#: ``None``: not recorded). The later runs are in ``papers_repro/track_init_hough/heldout_benchmark*.json``.
HELDOUT_EARLY_RUNS: tuple[dict[str, Any], ...] = (
    {"code": "of 00:17 UTC", "decisive seed": HELDOUT_SEED_FIRST, "recall": 0.827,
     "false per scene": 16.85, "logic 3/4 recall": None, "logic 3/4 false": None},
    {"code": "of 01:43 UTC", "decisive seed": HELDOUT_SEED_SECOND, "recall": 0.665,
     "false per scene": 13.88, "logic 3/4 recall": 0.759, "logic 3/4 false": 43.83},
)
#: issue 27's targets on :data:`HELDOUT_SEED` (60 scenes of :class:`HeldOutConfig` at ±3 px/s²)
HELDOUT_TARGETS: dict[str, Any] = {"recall": 0.90, "false <= logic 3/4": True,
                                   "ms per frame at 200": 5.0, "ms per frame at 1000": 50.0}


def heldout_scene(rng: np.random.Generator, cfg: HeldOutConfig | None = None) -> Scene:
    """One held-out scene (:class:`HeldOutConfig`); labels as in :func:`planted_scene`."""
    check_generator(rng)
    cfg = cfg or HeldOutConfig()
    w = float(cfg.width_px)
    n_obj = int(rng.integers(cfg.n_objects[0], cfg.n_objects[1] + 1))
    n_st = int(rng.integers(cfg.n_stars[0], cfg.n_stars[1] + 1))
    lam = float(rng.uniform(*cfg.clutter_per_frame))
    t = np.concatenate([[0.0], np.cumsum(rng.uniform(*cfg.dt_s, cfg.n_frames - 1))])
    speed = rng.uniform(*cfg.speed_px_s, n_obj)
    ang = rng.uniform(0, 2 * np.pi, n_obj)
    u = np.stack([np.cos(ang), np.sin(ang)], 1)
    nrm = np.stack([-u[:, 1], u[:, 0]], 1)
    acc = (rng.uniform(-cfg.accel_px_s2, cfg.accel_px_s2, (n_obj, 1)) * u
           + rng.uniform(-cfg.accel_px_s2, cfg.accel_px_s2, (n_obj, 1)) * nrm)
    start = rng.uniform(0, w, (n_obj, 2))
    stars = rng.uniform(0, w, (n_st, 2))
    burst_frame = int(rng.integers(0, cfg.n_frames))
    frames, labels, truth = [], [], []
    for k in range(cfg.n_frames):
        pos = start + speed[:, None] * u * t[k] + 0.5 * acc * t[k] ** 2
        inside = np.all((pos >= 0) & (pos < w), axis=1)
        det = inside & (rng.random(n_obj) < cfg.p_detect)
        left = rng.random(n_st) < cfg.star_residual
        nc = int(rng.poisson(lam)) + (cfg.burst if k == burst_frame else 0)
        xy = np.concatenate([pos[det], stars[left]])
        xy = xy + rng.normal(0.0, cfg.sigma_px, xy.shape)
        xy = np.concatenate([xy, rng.uniform(0, w, (nc, 2))])
        lab = np.concatenate([np.flatnonzero(det), -2 - np.flatnonzero(left),
                              np.full(nc, -1)]).astype(int)
        perm = rng.permutation(len(xy))
        frames.append((float(t[k]), xy[perm]))
        labels.append(lab[perm])
        truth.append(pos)
    return Scene(frames, labels, n_obj, stars_px=stars, truth_xy=truth,
                 meta={"clutter_per_frame": lam, "burst_frame": burst_frame,
                       "speed_px_s": speed, "accel_px_s2": acc})
