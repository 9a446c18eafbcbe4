"""Xu & Wang (2016): modified Hough track initiation for electro-optical tracking of space
objects — the 4-frame experiment (Table 2, Fig. 3) rebuilt on real star positions, and a Monte
Carlo comparison with logic 2/3 and 3/4, angle-constrained logic and the classic Hough.

The paper's settings (field, frame rate, velocity gate, cells, rule, the frames the tracks are
confirmed at) are read from ``papers_repro/track_init_hough/claims.toml``. Table 1 (the planted
objects) is lost in the source text: :data:`XU_TARGETS` is our choice, made to satisfy the text
(one object in all four frames, two that miss frame 3 and frame 2, two nearly overlapping ones
that miss frame 1). Entry point: :func:`reproduce`.
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field, replace
from datetime import datetime, timedelta
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from eotrack.astro import stars_in_field
from eotrack.montecarlo import TrialRunner
from eotrack.plotting import get_ax
from eotrack.repro import ClaimResult, Reproduction, Status, load_claims
from eotrack.tracking.initiation.base import Track, validate_frames
from eotrack.tracking.initiation.gating import TrackHandOff, canonical_order
from eotrack.tracking.initiation.hough import HoughInitiator
from eotrack.tracking.initiation.logic import LogicInitiator, logic_false_track_rate
from eotrack.tracking.initiation.modified_hough import ModifiedHoughInitiator
from eotrack.validation import check_generator, check_int, check_positive, check_probability

__all__ = [
    "SLUG",
    "TITLE",
    "XU_TARGETS",
    "ComparisonConfig",
    "PlantedTarget",
    "Scene",
    "StoneSoupInitiator",
    "XuConfig",
    "angle_constraint_table",
    "comparison_initiators",
    "comparison_scene",
    "distance_cdf_square",
    "gnomonic_to_pixels",
    "logic_false_track_table",
    "make_xu_scene",
    "plot_comparison",
    "plot_explore",
    "plot_fig3",
    "plot_logic_false_tracks",
    "plot_xu_frames",
    "prediction_inside_prob",
    "reproduce",
    "run_comparison",
    "score_tracks",
    "stonesoup_comparison",
    "timing_table",
    "xu_config",
    "xu_initiator",
    "xu_redraws",
    "xu_table2",
]

SLUG = "track_init_hough"
TITLE = ("Xu Z.W., Wang X., Track initiation in electro-optical tracking of space objects, Acta "
         "Astronomica Sinica 57(2):211-218, 2016 (modified Hough; with logic n/m, "
         "angle-constrained logic and classic Hough baselines)")


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


def xu_initiator(cfg: XuConfig, neighbourhood: int = 6) -> ModifiedHoughInitiator:
    """The modified Hough initiator with the experiment's settings.

    ``neighbourhood=6`` is the paper's rule; 26 is our robust variant (see the errata).
    """
    return ModifiedHoughInitiator(d_rho=cfg.cell_rho_px, d_theta_deg=cfg.cell_theta_deg,
                                  d_v=cfg.cell_v_px_s, v_min=cfg.v_gate_px_s[0],
                                  v_max=cfg.v_gate_px_s[1], m=cfg.rule_m,
                                  neighbourhood=neighbourhood, literal=True)


@dataclass
class Scene:
    """Frames of detections with their truth.

    ``labels[f][d]`` is the index of the planted object behind detection ``d`` of frame ``f``,
    or −1 (residual star / clutter). ``stars_px`` are all catalogue stars in the image.
    """

    frames: list[tuple[float, np.ndarray]]
    labels: list[np.ndarray]
    n_targets: int
    stars_px: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    truth_xy: list[np.ndarray] = field(default_factory=list)


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


def xu_table2(cfg: XuConfig, scene: Scene | None = None,
              neighbourhood: int = 6) -> tuple[pd.DataFrame, list[Track]]:
    """Run the modified Hough on the scene; per-frame log like Table 2 (1-based frames)."""
    scene = make_xu_scene(cfg) if scene is None else scene
    run = xu_initiator(cfg, neighbourhood).run(scene.frames, log=True)
    rows = []
    for e in run.log:
        k = e["frame"]
        who = [i for i, tr in enumerate(run.tracks) if tr.confirmed_at == k]
        names = []
        for i in who:
            ids = {int(scene.labels[f][d]) for f, d in run.tracks[i].hits}
            names.append(str(next(iter(ids)) + 1) if len(ids) == 1 and min(ids) >= 0 else "false")
        rows.append({"frame": k + 1, "candidates": e["candidates"],
                     "pairs removed by the velocity gate": e["rejected"],
                     "velocity-gated pairs": e["pairs"], "tracks created (cells)": e["created"],
                     "tracks destroyed (cells)": e["destroyed"],
                     "tentative after frame": e["tentative"], "tracks confirmed": e["confirmed"],
                     "confirmed track ids": ", ".join(names) or "–"})
    return pd.DataFrame(rows), run.tracks


def _xu_trial(rng: np.random.Generator, cfg: XuConfig) -> list[dict[str, Any]]:
    scene = make_xu_scene(cfg, rng)
    out = []
    for nb in (6, 26):
        tracks = xu_initiator(cfg, nb).initiate(scene.frames)
        sc = score_tracks(tracks, scene, n=cfg.rule_m - 1, m=cfg.rule_m)
        out.append({"neighbourhood": nb, "exact": sc["exact"], "false": sc["false"],
                    "correct": sc["correct"], "confirm_frame": sc["confirm_frame"],
                    "candidates": [len(f[1]) for f in scene.frames]})
    return out


def xu_redraws(cfg: XuConfig, n_trials: int, *, runner: TrialRunner | None = None,
               seed: int = 7) -> pd.DataFrame:
    """Seeded redraws of the residual stars and the centroid noise: one row per redraw and
    neighbourhood rule (6: the paper's; 26: ours)."""
    runner = runner or TrialRunner(progress=False)
    res = runner.map(_xu_trial, check_int(n_trials, "n_trials", min_value=1), seed=seed,
                     args=(cfg,), desc="Xu scene redraws")
    return pd.DataFrame([r for trial in res for r in trial])


def plot_xu_frames(scene: Scene, ax: plt.Axes | None = None) -> plt.Axes:
    """All candidates of the four frames in one image (like the paper's Fig. 2)."""
    ax = get_ax(ax, figsize=(5.2, 5.2))
    ax.plot(*scene.stars_px.T, "o", mfc="none", mec="0.75", ms=9, label="catalogue stars")
    cols = plt.cm.viridis(np.linspace(0, 0.9, len(scene.frames)))
    for k, ((_, xy), c) in enumerate(zip(scene.frames, cols)):
        ax.plot(*xy.T, "+", color=c, ms=7, label=f"frame {k + 1} candidates")
    _image_axes(ax, scene)
    ax.set_title("Candidates after star removal (4 frames)")
    ax.legend(fontsize=7, loc="upper right")
    return ax


def _image_axes(ax: plt.Axes, scene: Scene, width: float = 512) -> None:
    ax.set_xlim(0, width)
    ax.set_ylim(width, 0)
    ax.set_aspect("equal")
    ax.set_xlabel("x (px)")
    ax.set_ylabel("y (px)")


def plot_fig3(scene: Scene, tracks: list[Track], ax: plt.Axes | None = None) -> plt.Axes:
    """Fig. 3: the extracted tracks (lines through their detections) over the candidates."""
    ax = get_ax(ax, figsize=(5.2, 5.2))
    allxy = np.concatenate([xy for _, xy in scene.frames])
    ax.plot(*allxy.T, ".", color="0.7", ms=4, label="candidates")
    fr = validate_frames(scene.frames)
    for i, tr in enumerate(tracks):
        p = tr.positions(fr)
        ids = {int(scene.labels[f][d]) for f, d in tr.hits}
        name = (f"track {next(iter(ids)) + 1}" if len(ids) == 1 and min(ids) >= 0
                else f"false track {i + 1}")
        line = ax.plot(*p.T, "-o", ms=4, label=f"{name}: frames "
                       f"{','.join(str(f + 1) for f in tr.frame_indices)}; conf. {tr.confirmed_at + 1}")
        ax.annotate(name.replace("track ", "T"), p[-1], xytext=(4, 4),
                    textcoords="offset points", color=line[0].get_color(), fontsize=8)
    _image_axes(ax, scene)
    ax.set_title(f"Fig. 3 — extracted tracks ({len(tracks)})")
    ax.legend(fontsize=6.5, loc="lower right")
    return ax


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
    """The five initiators of the comparison, with the paper's gate and cells."""
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
    }


def _comparison_trial(rng: np.random.Generator, cfg: ComparisonConfig, xu: XuConfig,
                      points: tuple[tuple[str, float, float], ...],
                      names: tuple[str, ...]) -> list[dict[str, Any]]:
    inits = comparison_initiators(cfg, xu)
    out = []
    for sweep, lam, pd_ in points:
        scene = comparison_scene(rng, cfg, lam, pd_)
        for name in names:
            tracks = inits[name].initiate(scene.frames)
            sc = score_tracks(tracks, scene, n=xu.rule_m - 1, m=xu.rule_m)
            out.append({"sweep": sweep, "clutter": lam, "p_detect": pd_, "method": name,
                        "correct": sc["correct"], "eligible": sc["eligible"],
                        "false": sc["false"]})
    return out


def run_comparison(cfg: ComparisonConfig, *, n_trials: int | None = None,
                   runner: TrialRunner | None = None, xu: XuConfig | None = None,
                   methods: tuple[str, ...] | None = None) -> pd.DataFrame:
    """Monte Carlo of every initiator versus clutter density and versus detection probability.

    Returns
    -------
    pandas.DataFrame
        One row per sweep point and method: ``p_correct`` (correct initiations / eligible
        objects), ``false_per_frame`` (false tracks per frame) and the trial count.
    """
    xu = xu or xu_config()
    runner = runner or TrialRunner(progress=False)
    n = cfg.n_trials if n_trials is None else check_int(n_trials, "n_trials", min_value=1)
    points = tuple([("clutter", float(c), cfg.p_detect_nominal) for c in cfg.clutter_levels]
                   + [("p_detect", cfg.clutter_nominal, float(p)) for p in cfg.pd_levels])
    names = tuple(methods or comparison_initiators(cfg, xu).keys())
    res = runner.map(_comparison_trial, n, seed=cfg.seed, args=(cfg, xu, points, names),
                     desc="method comparison")
    df = pd.DataFrame([r for trial in res for r in trial])
    g = df.groupby(["sweep", "clutter", "p_detect", "method"], sort=False)
    out = g.agg(correct=("correct", "sum"), eligible=("eligible", "sum"),
                false=("false", "sum"), trials=("false", "size")).reset_index()
    out["p_correct"] = out["correct"] / out["eligible"].clip(lower=1)
    out["false_per_frame"] = out["false"] / (out["trials"] * cfg.n_frames)
    return out


def plot_comparison(df: pd.DataFrame, sweep: str, metric: str,
                    ax: plt.Axes | None = None) -> plt.Axes:
    """One metric (``p_correct`` / ``false_per_frame``) versus the sweep variable, per method."""
    ax = get_ax(ax)
    sub = df[df["sweep"] == sweep]
    x = "clutter" if sweep == "clutter" else "p_detect"
    for name, g in sub.groupby("method", sort=False):
        # the angle-constrained logic often coincides with logic 3/4: draw it dashed on top
        style = "--s" if name.startswith("angle") else "-o"
        ax.plot(g[x], g[metric], style, ms=4, mfc="none" if name.startswith("angle") else None,
                label=name)
    ax.set_xlabel("false alarms per frame" if x == "clutter" else "detection probability P_D")
    ax.set_ylabel({"p_correct": "P(correct initiation)",
                   "false_per_frame": "false tracks per frame"}[metric])
    if metric == "false_per_frame":
        ax.set_yscale("symlog", linthresh=0.01)
    ax.legend(fontsize=7)
    return ax


def timing_table(cfg: ComparisonConfig, n_candidates: tuple[int, ...] = (10, 25, 50, 100),
                 *, n_frames: int = 5, repeats: int = 3, seed: int = 11,
                 xu: XuConfig | None = None,
                 skip: dict[str, int] | None = None) -> pd.DataFrame:
    """Median wall time per frame of every initiator versus candidates per frame (uniform).

    ``skip[name] = N`` leaves out a method above N candidates (too slow). Timings depend on the
    machine; they are not part of any claim.
    """
    inits = comparison_initiators(cfg, xu)
    rng = np.random.default_rng(seed)
    skip = skip or {}
    rows = []
    for nc in n_candidates:
        frames = [(float(k), rng.uniform(0, cfg.width_px, (nc, 2))) for k in range(n_frames)]
        for name, ini in inits.items():
            if nc > skip.get(name, 10**9):
                continue
            ts = []
            for _ in range(repeats):
                t0 = time.perf_counter()
                ini.initiate(frames)
                ts.append(time.perf_counter() - t0)
            rows.append({"candidates per frame": nc, "method": name,
                         "ms per frame": 1e3 * float(np.median(ts)) / n_frames})
    return pd.DataFrame(rows)


# --------------------------------------------------------------------------- logic: analytic
def distance_cdf_square(d: np.ndarray | float, side: float) -> np.ndarray:
    """CDF of the distance between two independent uniform points in a square of side ``side``.

    Closed form (e.g. Philip 2007): with ``s = d / side``, ``F = π s² − 8 s³/3 + s⁴/2`` for
    ``s ≤ 1`` and ``F = 1/3 + (π − 2) s² − s⁴/2 + 4/3 (2 s² + 1) √(s² − 1) − 4 s² arccos(1/s)``
    for ``1 < s ≤ √2``; 1 beyond.
    """
    s = np.asarray(d, float) / check_positive(side, "side")
    s = np.clip(s, 0.0, np.sqrt(2.0))
    lo = np.pi * s**2 - 8 * s**3 / 3 + s**4 / 2
    with np.errstate(invalid="ignore", divide="ignore"):
        hi = (1 / 3 + (np.pi - 2) * s**2 - s**4 / 2
              + 4 / 3 * (2 * s**2 + 1) * np.sqrt(np.maximum(s**2 - 1, 0))
              - 4 * s**2 * np.arccos(np.minimum(1.0, 1 / np.maximum(s, 1e-300))))
    return np.where(s <= 1, lo, np.minimum(hi, 1.0))


def prediction_inside_prob(width: float, v_min: float, v_max: float, m: int,
                           grid: int = 32) -> list[list[float]]:
    """Probability that the constant-velocity prediction of a random clutter pair stays in the
    field: ``out[Δ−1][j−1]`` for a pair ``Δ`` frames apart predicted ``j`` frames past its second
    point (deterministic midpoint quadrature on a ``grid⁴`` lattice of pair positions)."""
    c = (np.arange(grid) + 0.5) / grid * width
    ax, ay = np.meshgrid(c, c, indexing="ij")
    a = np.stack([ax.ravel(), ay.ravel()], 1)
    d = a[None, :, :] - a[:, None, :]  # b − a for every (a, b)
    dist = np.hypot(d[..., 0], d[..., 1])
    out = []
    for gap in range(1, m):
        ring = (dist >= v_min * gap) & (dist <= v_max * gap)
        row = []
        for j in range(1, m - gap):
            pred = a[None, :, :] + d * (j / gap)
            inside = np.all((pred >= 0) & (pred <= width), axis=2)
            row.append(float(inside[ring].mean()) if ring.any() else 0.0)
        out.append(row)
    return out


def _clutter_only_trial(rng: np.random.Generator, cfg: ComparisonConfig, xu: XuConfig,
                        levels: tuple[float, ...], n_frames: int) -> list[dict[str, Any]]:
    inits = comparison_initiators(cfg, xu)
    out = []
    for lam in levels:
        frames = [(float(k), rng.uniform(0, cfg.width_px, (rng.poisson(lam), 2)))
                  for k in range(n_frames)]
        for name in ("logic 2/3", "logic 3/4"):
            ini = inits[name]
            tracks = ini.initiate(frames)
            steady = sum(1 for t in tracks if t.confirmed_at >= ini.m - 1)
            out.append({"clutter": lam, "method": name, "false": steady,
                        "frames": n_frames - (ini.m - 1)})
    return out


def logic_false_track_table(cfg: ComparisonConfig, *,
                            levels: tuple[float, ...] = (1.0, 2.0, 4.0, 8.0),
                            n_trials: int = 20, n_frames: int = 20,
                            runner: TrialRunner | None = None,
                            xu: XuConfig | None = None) -> pd.DataFrame:
    """Measured false tracks per frame of the logic rules in clutter only, beside the analytic
    rate of :func:`~eotrack.tracking.initiation.logic.logic_false_track_rate`.

    The pair probabilities use the exact distance distribution of two uniform points in the
    square field (:func:`distance_cdf_square`); the prediction gate ignores the field's edge.
    """
    xu = xu or xu_config()
    runner = runner or TrialRunner(progress=False)
    res = runner.map(_clutter_only_trial, n_trials, seed=cfg.seed + 1,
                     args=(cfg, xu, tuple(float(v) for v in levels), n_frames),
                     desc="logic false tracks")
    df = pd.DataFrame([r for trial in res for r in trial])
    g = df.groupby(["clutter", "method"], sort=False).agg(false=("false", "sum"),
                                                          frames=("frames", "sum")).reset_index()
    g["measured"] = g["false"] / g["frames"]
    vmin, vmax = xu.v_gate_px_s
    w = float(cfg.width_px)
    gate = np.pi * cfg.logic_gate_px**2 / w**2
    ana, ana0 = [], []
    inits = comparison_initiators(cfg, xu)
    inside = {}
    for _, r in g.iterrows():
        ini = inits[r["method"]]
        if ini.m not in inside:
            inside[ini.m] = prediction_inside_prob(w, vmin, vmax, ini.m)
        pp = [float(distance_cdf_square(vmax * gap, w) - distance_cdf_square(vmin * gap, w))
              for gap in range(1, ini.m)]
        ana.append(logic_false_track_rate(ini.n, ini.m, r["clutter"], pp, gate, inside[ini.m]))
        ana0.append(logic_false_track_rate(ini.n, ini.m, r["clutter"], pp, gate))
    g["analytic"] = ana
    g["analytic, edges ignored"] = ana0
    return g


def plot_logic_false_tracks(df: pd.DataFrame, ax: plt.Axes | None = None) -> plt.Axes:
    """Measured (markers) and analytic (lines) false tracks per frame of the logic rules."""
    ax = get_ax(ax)
    for name, g in df.groupby("method", sort=False):
        line = ax.plot(g["clutter"], g["analytic"], "-", label=f"{name} analytic")
        ax.plot(g["clutter"], g["measured"], "o", color=line[0].get_color(),
                label=f"{name} measured")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("false alarms per frame")
    ax.set_ylabel("false tracks per frame")
    ax.legend(fontsize=7)
    return ax


def _angle_trial(rng: np.random.Generator, cfg: ComparisonConfig, xu: XuConfig,
                 gates: tuple[float, ...]) -> list[dict[str, Any]]:
    scene = comparison_scene(rng, cfg, cfg.clutter_nominal, cfg.p_detect_nominal)
    vmin, vmax = xu.v_gate_px_s
    out = []
    for g in gates:
        for name, ang in (("logic 3/4", None), ("angle logic 3/4", 90.0)):
            ini = LogicInitiator(n=xu.rule_m - 1, m=xu.rule_m, v_min=vmin, v_max=vmax,
                                 gate_px=g, min_angle_deg=ang)
            sc = score_tracks(ini.initiate(scene.frames), scene, n=xu.rule_m - 1, m=xu.rule_m)
            out.append({"gate_px": g, "method": name, "correct": sc["correct"],
                        "eligible": sc["eligible"], "false": sc["false"]})
    return out


def angle_constraint_table(cfg: ComparisonConfig, *, gates: tuple[float, ...] = (10.0, 20.0,
                                                                                  40.0, 80.0),
                           n_trials: int = 30, runner: TrialRunner | None = None,
                           xu: XuConfig | None = None) -> pd.DataFrame:
    """Logic 3/4 with and without the angle constraint versus the prediction-gate radius.

    The constraint can only act when the gate reaches behind the last point, i.e. when the
    gate radius exceeds the displacement per frame (≥ v_min · Δt).
    """
    xu = xu or xu_config()
    runner = runner or TrialRunner(progress=False)
    res = runner.map(_angle_trial, n_trials, seed=cfg.seed + 3,
                     args=(cfg, xu, tuple(float(g) for g in gates)), desc="angle constraint")
    df = pd.DataFrame([r for trial in res for r in trial])
    g = df.groupby(["gate_px", "method"], sort=False).agg(
        correct=("correct", "sum"), eligible=("eligible", "sum"), false=("false", "sum"),
        trials=("false", "size")).reset_index()
    g["p_correct"] = g["correct"] / g["eligible"].clip(lower=1)
    g["false_per_frame"] = g["false"] / (g["trials"] * cfg.n_frames)
    return g


# --------------------------------------------------------------------------- Stone Soup baseline
class StoneSoupInitiator:
    """Stone Soup's ``MultiMeasurementInitiator`` behind the common ``initiate(frames)`` interface.

    A 2-D constant-velocity Kalman model (position measured with ``sigma_px``), a single-point
    initiator whose velocity prior is zero-mean with standard deviation ``v_sigma_px_s``, a
    Mahalanobis distance hypothesiser (missed distance ``gate_sigma``), global nearest neighbour
    association, confirmation at ``min_points`` updates and deletion after ``max_misses`` frames
    without an update. Confirmed tracks are handed off exactly as for our initiators.
    """

    def __init__(self, *, min_points: int = 3, max_misses: int = 2, sigma_px: float = 0.5,
                 v_sigma_px_s: float = 120.0, q: float = 1.0, gate_sigma: float = 3.0,
                 handoff_gate_px: float = 5.0) -> None:
        self.min_points = check_int(min_points, "min_points", min_value=2)
        self.max_misses = check_int(max_misses, "max_misses", min_value=1)
        self.sigma_px = check_positive(sigma_px, "sigma_px")
        self.v_sigma_px_s = check_positive(v_sigma_px_s, "v_sigma_px_s")
        self.q = check_positive(q, "q")
        self.gate_sigma = check_positive(gate_sigma, "gate_sigma")
        self.handoff_gate_px = check_positive(handoff_gate_px, "handoff_gate_px")

    def initiate(self, frames) -> list[Track]:
        """Confirmed tracks from ``frames`` (a sequence of ``(time_s, xy)``)."""
        from stonesoup.dataassociator.neighbour import GNNWith2DAssignment
        from stonesoup.deleter.time import UpdateTimeStepsDeleter
        from stonesoup.hypothesiser.distance import DistanceHypothesiser
        from stonesoup.initiator.simple import MultiMeasurementInitiator
        from stonesoup.measures import Mahalanobis
        from stonesoup.models.measurement.linear import LinearGaussian
        from stonesoup.models.transition.linear import (
            CombinedLinearGaussianTransitionModel,
            ConstantVelocity,
        )
        from stonesoup.predictor.kalman import KalmanPredictor
        from stonesoup.types.detection import Detection
        from stonesoup.types.state import GaussianState
        from stonesoup.types.update import Update
        from stonesoup.updater.kalman import KalmanUpdater

        fr = validate_frames(frames)
        perms = [canonical_order(f.xy) for f in fr]
        xys = [f.xy[p] for f, p in zip(fr, perms)]
        work = [type(f)(f.time_s, x) for f, x in zip(fr, xys)]
        trans = CombinedLinearGaussianTransitionModel([ConstantVelocity(self.q)] * 2)
        meas = LinearGaussian(ndim_state=4, mapping=(0, 2),
                              noise_covar=np.eye(2) * self.sigma_px**2)
        predictor = KalmanPredictor(trans)
        updater = KalmanUpdater(meas)
        hyp = DistanceHypothesiser(predictor, updater, measure=Mahalanobis(),
                                   missed_distance=self.gate_sigma)
        prior = GaussianState(np.zeros((4, 1)),
                              np.diag([1.0, self.v_sigma_px_s**2, 1.0, self.v_sigma_px_s**2]))
        ini = MultiMeasurementInitiator(prior_state=prior,
                                        deleter=UpdateTimeStepsDeleter(self.max_misses),
                                        data_associator=GNNWith2DAssignment(hyp),
                                        updater=updater, measurement_model=meas,
                                        min_points=self.min_points)
        t0 = datetime(2016, 1, 1)
        handoff = TrackHandOff(self.handoff_gate_px)
        avail = [np.ones(len(x), dtype=bool) for x in xys]
        for k, f in enumerate(work):
            handoff.claim(k, f.time_s, f.xy, avail[k])
            ts = t0 + timedelta(seconds=f.time_s)
            dets = {Detection(np.array([[x], [y]]), timestamp=ts, measurement_model=meas,
                              metadata={"frame": k, "det": int(d)})
                    for d, (x, y) in enumerate(f.xy) if avail[k][d]}
            sure = ini.initiate(dets, ts)
            for tr in sorted(sure, key=lambda t: (t.state_vector[0, 0], t.state_vector[2, 0])):
                hits = [(s.hypothesis.measurement.metadata["frame"],
                         s.hypothesis.measurement.metadata["det"])
                        for s in tr.states if isinstance(s, Update)]
                if any(not avail[f2][d2] for f2, d2 in hits):
                    continue
                for f2, d2 in hits:
                    avail[f2][d2] = False
                handoff.confirm(hits, k, work, info={"method": "stonesoup"})
        return handoff.tracks(perms)


def _stonesoup_trial(rng: np.random.Generator, cfg: ComparisonConfig, lam: float,
                     pd_: float, xu: XuConfig) -> dict[str, Any]:
    scene = comparison_scene(rng, cfg, lam, pd_)
    out = {}
    for name, ini in (("Stone Soup MultiMeasurementInitiator (3 updates)", StoneSoupInitiator()),
                      ("modified Hough 3/4", xu_initiator(xu)),
                      ("logic 3/4", comparison_initiators(cfg, xu)["logic 3/4"])):
        sc = score_tracks(ini.initiate(scene.frames), scene, n=xu.rule_m - 1, m=xu.rule_m)
        out[name] = (sc["correct"], sc["eligible"], sc["false"])
    return out


def stonesoup_comparison(cfg: ComparisonConfig, *, levels: tuple[float, ...] = (0.0, 10.0),
                         n_trials: int = 10, runner: TrialRunner | None = None,
                         xu: XuConfig | None = None) -> pd.DataFrame:
    """Stone Soup's initiator beside ours on the same seeded scenes (P_D nominal)."""
    xu = xu or xu_config()
    runner = runner or TrialRunner(progress=False)
    rows = []
    for lam in levels:
        res = runner.map(_stonesoup_trial, n_trials, seed=cfg.seed + 2,
                         args=(cfg, float(lam), cfg.p_detect_nominal, xu), desc="Stone Soup")
        for name in res[0]:
            c = sum(r[name][0] for r in res)
            e = sum(r[name][1] for r in res)
            f = sum(r[name][2] for r in res)
            rows.append({"clutter": lam, "method": name, "p_correct": c / max(e, 1),
                         "false_per_frame": f / (n_trials * cfg.n_frames)})
    return pd.DataFrame(rows)


# --------------------------------------------------------------------------- explore
def plot_explore(*, clutter_per_frame: float = 10.0, p_detect: float = 0.9, d_rho: float = 5.0,
                 d_theta_deg: float = 5.0, d_v: float = 3.0, v_min: float = 10.0,
                 v_max: float = 240.0, m: int = 4, neighbourhood: int = 6, seed: int = 0,
                 cfg: ComparisonConfig | None = None, axes=None):
    """One seeded comparison scene: tracks of the modified Hough and of the (m−1)/m logic.

    Returns the figure; the titles give correct / eligible objects and false tracks.
    """
    cfg = cfg or ComparisonConfig()
    scene = comparison_scene(np.random.default_rng(seed), cfg, clutter_per_frame, p_detect)
    inits = {
        f"modified Hough {m - 1}/{m} ({neighbourhood}-nbhd)": ModifiedHoughInitiator(
            d_rho=d_rho, d_theta_deg=d_theta_deg, d_v=d_v, v_min=v_min, v_max=v_max, m=m,
            neighbourhood=neighbourhood),
        f"logic {m - 1}/{m}": LogicInitiator(n=m - 1, m=m, v_min=v_min, v_max=v_max,
                                            gate_px=cfg.logic_gate_px),
    }
    if axes is None:
        fig, axes = plt.subplots(1, 2, figsize=(10, 5))
    else:
        fig = axes[0].figure
    fr = validate_frames(scene.frames)
    truth = np.array(scene.truth_xy)
    for ax, (name, ini) in zip(axes, inits.items()):
        tracks = ini.initiate(scene.frames)
        sc = score_tracks(tracks, scene, n=m - 1, m=m)
        allxy = np.concatenate([xy for _, xy in scene.frames])
        ax.plot(*allxy.T, ".", color="0.7", ms=3)
        for i in range(truth.shape[1]):
            ax.plot(*truth[:, i].T, ":", color="k", lw=1)
        for tr in tracks:
            ids = {int(scene.labels[f][d]) for f, d in tr.hits if f <= tr.confirmed_at}
            good = len(ids) == 1 and min(ids) >= 0
            ax.plot(*tr.positions(fr).T, "-o" if good else "-x", ms=3,
                    color="tab:green" if good else "tab:red")
        _image_axes(ax, scene, cfg.width_px)
        ax.set_title(f"{name}: {sc['correct']}/{sc['eligible']} found, {sc['false']} false",
                     fontsize=9)
    return fig


# --------------------------------------------------------------------------- claims
def _xu_status(ok6: bool, frac6: float, ok26: bool, frac26: float, full: float,
               part: float) -> Status:
    if ok6 and frac6 >= full:
        return Status.REPRODUCED
    if (ok6 and frac6 >= part) or (ok26 and frac26 >= full):
        return Status.PARTIAL
    return Status.NOT_REPRODUCED


def _evaluate(claims, cfg: XuConfig, table2: pd.DataFrame, nominal: dict[int, dict],
              redraws: pd.DataFrame, comp: pd.DataFrame) -> list[ClaimResult]:
    rows = []
    p2 = claims["track_init.xu_table2"].paper
    want = {0: int(p2["confirm_frame_track1"]), 1: int(p2["confirm_frame_track2"]),
            2: int(p2["confirm_frame_track3"]), 3: cfg.n_frames, 4: cfg.n_frames}

    def frames_ok(cf: dict, n_false: int) -> bool:
        return {i: f + 1 for i, f in cf.items()} == want and n_false == 0

    ok, frac, got = {}, {}, {}
    for nb in (6, 26):
        got[nb] = {i + 1: f + 1 for i, f in sorted(nominal[nb]["confirm_frame"].items())}
        ok[nb] = frames_ok(nominal[nb]["confirm_frame"], nominal[nb]["false"])
        r = redraws[redraws["neighbourhood"] == nb]
        frac[nb] = float(np.mean([frames_ok(cf, fl) for cf, fl in
                                  zip(r["confirm_frame"], r["false"])]))
    n_red = int((redraws["neighbourhood"] == 6).sum())
    status = _xu_status(ok[6], frac[6], ok[26], frac[26], 0.95, 0.0)
    note = ""
    if status is not Status.REPRODUCED:
        note = (f"paper's 6-neighbourhood: nominal scene track→frame {got[6]} (want "
                f"{ {i + 1: f for i, f in want.items()} }), false {nominal[6]['false']}; same "
                f"frames and no false track in {100 * frac[6]:.0f} % of {n_red} redraws. A track "
                "whose pair cells differ in two of (ρ, θ, v) is split and never reaches 3 votes. "
                f"With the 26-neighbourhood (our deviation): nominal {got[26]}, "
                f"{100 * frac[26]:.0f} % of redraws")
    rows.append(ClaimResult.from_claim(
        claims["track_init.xu_table2"],
        paper=f"track 1 confirmed at frame {want[0]}, tracks 2 and 3 at frame {want[1]}, tracks "
              "4 and 5 identified; Table 2 counts lost",
        ours=(f"6-nbhd (paper): confirmed per frame {table2['tracks confirmed'].tolist()}, "
              f"track→frame {got[6]}, {100 * frac[6]:.0f} % of {n_red} redraws right; "
              f"26-nbhd: {got[26]}, {100 * frac[26]:.0f} %; candidates per frame "
              f"{table2['candidates'].tolist()}"),
        status=status, note=note))

    p3 = claims["track_init.xu_fig3"].paper
    n_want = int(p3["n_tracks_extracted"])
    ok3, frac3 = {}, {}
    for nb in (6, 26):
        ok3[nb] = bool(nominal[nb]["exact"] and nominal[nb]["n_tracks"] == n_want)
        frac3[nb] = float(redraws[redraws["neighbourhood"] == nb]["exact"].mean())
    status = _xu_status(ok3[6], frac3[6], ok3[26], frac3[26], 0.95, 0.8)
    mean_false = {nb: float(redraws[redraws["neighbourhood"] == nb]["false"].mean())
                  for nb in (6, 26)}
    note = ""
    if status is not Status.REPRODUCED:
        note = (f"paper's 6-neighbourhood: nominal {nominal[6]['n_tracks']} tracks "
                f"(exact={nominal[6]['exact']}), exact recovery in {100 * frac3[6]:.0f} % of "
                f"{n_red} redraws (mean false tracks {mean_false[6]:.2f}); 26-neighbourhood "
                f"(our deviation): nominal exact={nominal[26]['exact']}, "
                f"{100 * frac3[26]:.0f} % (mean false {mean_false[26]:.2f})")
    rows.append(ClaimResult.from_claim(
        claims["track_init.xu_fig3"],
        paper=f"{n_want} tracks extracted = the {p3['n_objects']} planted, "
              f"{p3['n_false_tracks']} false",
        ours=(f"6-nbhd: {nominal[6]['n_tracks']} tracks, exact={nominal[6]['exact']}, exact in "
              f"{100 * frac3[6]:.0f} % of redraws; 26-nbhd: {nominal[26]['n_tracks']} tracks, "
              f"exact={nominal[26]['exact']}, {100 * frac3[26]:.0f} %"),
        status=status, note=note))

    cl = comp[(comp["sweep"] == "clutter") & (comp["clutter"] > 0)]
    piv_f = cl.pivot(index="clutter", columns="method", values="false_per_frame")
    piv_c = cl.pivot(index="clutter", columns="method", values="p_correct")
    a_ok = bool(np.all(piv_f.idxmax(axis=1) == "logic 2/3"))
    b_ok = bool(np.all(piv_f["angle logic 3/4"] <= piv_f["logic 3/4"] + 1e-12)
                and np.all(np.abs(piv_c["angle logic 3/4"] - piv_c["logic 3/4"]) <= 0.02))
    nominal_rows = comp[(comp["sweep"] == "clutter") & (comp["clutter"] <= 10)
                        & (comp["method"] == "modified Hough 3/4")]
    pd_rows = comp[(comp["sweep"] == "p_detect") & (comp["p_detect"] >= 0.9)
                   & (comp["method"] == "modified Hough 3/4")]
    mh_pc = float(min(nominal_rows["p_correct"].min(), pd_rows["p_correct"].min()))
    c_ok = bool(np.all(piv_f["modified Hough 3/4"] < piv_f["classic Hough 3/4"])) and mh_pc >= 0.9
    n_ok = a_ok + b_ok + c_ok
    status = (Status.REPRODUCED if n_ok == 3 else Status.PARTIAL if n_ok == 2
              else Status.NOT_REPRODUCED)
    top = piv_f.index.max()
    ours = (f"(a) 2/3 most false tracks at every density: {a_ok}; (b) angle ≤ 3/4 false and "
            f"|ΔP_correct| ≤ 0.02: {b_ok}; (c) modified < classic Hough false tracks: "
            f"{bool(np.all(piv_f['modified Hough 3/4'] < piv_f['classic Hough 3/4']))}, "
            f"modified Hough P_correct ≥ {mh_pc:.3f}. At {top:g} false alarms/frame, false "
            "tracks/frame: " + ", ".join(f"{k} {v:.3f}" for k, v in piv_f.loc[top].items()))
    ang = piv_f["angle logic 3/4"] - piv_f["logic 3/4"]
    note = ("(b) at the 10 px prediction gate the angle constraint never acts (a point within "
            "10 px of a prediction at least v_min·Δt = 10 px ahead always makes an angle > 90°); "
            f"false-track differences angle − plain {ang.round(4).to_dict()}; see the "
            "angle-versus-gate table for wider gates")
    if status is not Status.REPRODUCED:
        parts = [note]
        if not a_ok:
            parts.append("(a) fails: most false tracks per density "
                         f"{piv_f.idxmax(axis=1).to_dict()}")
        if not b_ok:
            parts.append("(b) fails: angle − plain false tracks "
                         f"{(piv_f['angle logic 3/4'] - piv_f['logic 3/4']).round(4).to_dict()}, "
                         "ΔP_correct "
                         f"{(piv_c['angle logic 3/4'] - piv_c['logic 3/4']).round(3).to_dict()}")
        if not c_ok:
            parts.append("(c) fails: modified vs classic Hough false tracks "
                         f"{piv_f['modified Hough 3/4'].round(3).to_dict()} vs "
                         f"{piv_f['classic Hough 3/4'].round(3).to_dict()}, modified Hough "
                         f"P_correct min {mh_pc:.3f}")
        note = "; ".join(parts)
    rows.append(ClaimResult.from_claim(
        claims["track_init.method_comparison"],
        paper="2/3 too loose; angle constraint fewer false tracks at equal P_correct; classic "
              "Hough heavy, modified Hough initiates several objects in a few frames",
        ours=ours, status=status, note=note))
    return rows


def reproduce(*, quick: bool = False, runner: TrialRunner | None = None,
              comparison: ComparisonConfig | None = None, n_redraws: int | None = None,
              n_trials: int | None = None, n_aux_trials: int | None = None) -> Reproduction:
    """Run the 4-frame experiment, its redraws, the method comparison and the extras.

    ``quick`` uses fewer redraws and Monte Carlo trials (tests); ``n_redraws`` (Xu scene
    redraws), ``n_trials`` (comparison trials per point) and ``n_aux_trials`` (analytic-logic,
    angle-constraint and Stone Soup trials) override the counts (the notebook uses smaller ones).
    """
    claims = load_claims(SLUG)
    runner = runner or TrialRunner(progress=False)
    cfg = xu_config()
    comp_cfg = comparison or ComparisonConfig()
    if n_redraws is None:
        n_redraws = 20 if quick else 100
    if n_trials is None:
        n_trials = 4 if quick else comp_cfg.n_trials
    if n_aux_trials is None:
        n_aux_trials = 4 if quick else 20
    n_comp = n_trials
    scene = make_xu_scene(cfg)
    nominal, logs, all_tracks = {}, {}, {}
    for nb in (6, 26):
        logs[nb], all_tracks[nb] = xu_table2(cfg, scene, nb)
        nominal[nb] = score_tracks(all_tracks[nb], scene, n=cfg.rule_m - 1, m=cfg.rule_m)
        nominal[nb]["n_tracks"] = len(all_tracks[nb])
    table2, tracks = logs[6], all_tracks[6]
    redraws = xu_redraws(cfg, n_redraws, runner=runner)
    comp = run_comparison(comp_cfg, n_trials=n_comp, runner=runner, xu=cfg)
    logic_ft = logic_false_track_table(comp_cfg, n_trials=n_aux_trials, runner=runner, xu=cfg)
    angle = angle_constraint_table(comp_cfg, n_trials=n_aux_trials, runner=runner, xu=cfg)
    try:
        stone = stonesoup_comparison(comp_cfg, n_trials=n_aux_trials, runner=runner, xu=cfg)
    except ImportError as exc:  # pragma: no cover - optional baseline
        stone = pd.DataFrame({"note": [f"Stone Soup unavailable: {exc}"]})
    tables: dict[str, pd.DataFrame] = {
        "Table 1 (ours; the paper's numbers are lost) — planted objects": pd.DataFrame(
            [{"track": i + 1, "name": t.name, "x0 (px)": t.xy0_px[0], "y0 (px)": t.xy0_px[1],
              "vx (px/s)": t.v_px_s[0], "vy (px/s)": t.v_px_s[1],
              "frames seen": ",".join(str(f + 1) for f in t.frames)}
             for i, t in enumerate(cfg.targets)]),
        "Table 2 — per-frame log, paper's 6-neighbourhood (paper's counts lost)": table2,
        "Table 2 — per-frame log, 26-neighbourhood (our deviation)": logs[26],
        "Method comparison — Monte Carlo": comp,
        "Beyond — logic false tracks per frame, analytic vs measured (clutter only)": logic_ft,
        "Beyond — angle constraint versus prediction-gate radius (clutter 10/frame)": angle,
        "Beyond — Stone Soup MultiMeasurementInitiator on the same scenes": stone,
    }
    figs = {}
    fig, ax = plt.subplots(figsize=(5.4, 5.4))
    plot_xu_frames(scene, ax=ax)
    figs["fig2_candidates"] = fig
    fig, axes = plt.subplots(1, 2, figsize=(10.5, 5.4))
    plot_fig3(scene, tracks, ax=axes[0])
    axes[0].set_title(f"Fig. 3 — paper's 6-neighbourhood ({len(tracks)} tracks)")
    plot_fig3(scene, all_tracks[26], ax=axes[1])
    axes[1].set_title(f"Fig. 3 — 26-neighbourhood ({len(all_tracks[26])} tracks)")
    fig.tight_layout()
    figs["fig3_extracted_tracks"] = fig
    fig, axes = plt.subplots(2, 2, figsize=(10, 7))
    for i, sweep in enumerate(("clutter", "p_detect")):
        for j, metric in enumerate(("p_correct", "false_per_frame")):
            plot_comparison(comp, sweep, metric, ax=axes[j, i])
    fig.tight_layout()
    figs["comparison_monte_carlo"] = fig
    fig, ax = plt.subplots()
    plot_logic_false_tracks(logic_ft, ax=ax)
    figs["beyond_logic_false_track_rate"] = fig
    rows = _evaluate(claims, cfg, table2, nominal, redraws, comp)
    text = (
        "## Scenario\n\n"
        f"Field {cfg.fov_deg}° × {cfg.fov_deg}°, {cfg.width_px} px, {cfg.n_frames} frames at "
        f"{1 / cfg.frame_interval_s:g} Hz; Gaia DR3 stars (G ≤ {cfg.max_mag:g}) around RA "
        f"{cfg.ra_deg:g}°, Dec {cfg.dec_deg:g}° ({len(scene.stars_px)} in the image), projected "
        "gnomonically; each star is left by the star removal with probability "
        f"{cfg.residual_fraction:g} per frame; centroid noise σ = {cfg.sigma_px:g} px. The five "
        "objects are our Table 1 (the paper's is lost). Redraws re-sample residual stars and "
        f"noise ({n_redraws}). Method comparison: {comp_cfg.n_targets} objects, "
        f"{comp_cfg.n_frames} frames, {n_comp} trials per point, uniform Poisson clutter; "
        "logic gate "
        f"{comp_cfg.logic_gate_px:g} px; classic Hough δρ = {cfg.cell_rho_px:g} px, "
        f"δθ = {comp_cfg.hough_d_theta_deg:g}°.\n\n"
        "Vote counting (our reading, see the notebook's errata): P(t) is the number of distinct "
        "frames among the detections recorded in Q(t); a confirmed track must also be one "
        "constant-velocity line consistent with its cell (one detection per frame).")
    settings = {"quick": quick, "n_redraws": n_redraws, "n_comparison_trials": n_comp,
                **{k: v for k, v in asdict(cfg).items() if k != "targets"},
                **{f"comparison.{k}": v for k, v in asdict(comp_cfg).items()}}
    return Reproduction(slug=SLUG, title=TITLE, claims=rows, tables=tables, figures=figs,
                        text=text, settings=settings,
                        data={"scene": scene, "tracks": all_tracks, "table2": logs,
                              "nominal": nominal,
                              "redraws": redraws, "comparison": comp, "logic_ft": logic_ft,
                              "angle": angle, "stonesoup": stone})
