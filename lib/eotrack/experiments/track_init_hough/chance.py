"""Chance (false-track) rates: analytic expressions and their Monte Carlo checks.

* The **3-of-4 rule with a χ² confirmation test** at the measurement noise σ (our verified
  initiator): three detections of three frames, uniform and independent in the field, pass
  when their constant-velocity fit has ``RSS/σ² ≤ χ²₂(1 − α)`` and a speed in the gate. For
  frames at ``t₁ < t₂ < t₃`` the middle point must fall in a disc of area
  ``π χ²₂(1−α) σ² c`` around the point interpolated between the outer two,
  ``c = 1 + (1 − λ)² + λ²`` with ``λ = (t₂ − t₁)/(t₃ − t₁)``, so

  ``P(pass) = D(t₃ − t₁) · π χ²₂(1−α) σ² c / A``,

  with ``D(T)`` the probability that two uniform points of the square field are between
  ``v_min T`` and ``v_max T`` apart (:func:`distance_cdf_square`) and ``A`` the field's area.
  The expected number of chance tracks is this probability times the number of triples of
  distinct sources, less the passing triples that share a detection (only one of them is
  confirmed) and the detections used up by earlier chance tracks (:func:`chi2_chance_tracks`).
* The **n/m logic** (:func:`~eotrack.tracking.initiation.logic.logic_false_track_rate`), checked
  by :func:`logic_false_track_table`.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np
import pandas as pd
from scipy.stats import chi2

from eotrack.montecarlo import TrialRunner
from eotrack.tracking.initiation.logic import logic_false_track_rate
from eotrack.validation import check_int, check_positive

from .scenario import (
    ComparisonConfig,
    PlantedConfig,
    Scene,
    XuConfig,
    comparison_initiators,
    planted_initiators,
    planted_scene,
    xu_config,
)

__all__ = [
    "chance_rate_check",
    "chi2_chance_tracks",
    "distance_cdf_square",
    "logic_false_track_table",
    "prediction_inside_prob",
    "triplet_chance_probability",
    "triplet_shapes",
]


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




# --------------------------------------------------------------------------- χ² 3-of-4 rule
def triplet_chance_probability(t1: float, t2: float, t3: float, *, width: float, v_min: float,
                               v_max: float, sigma_px: float, alpha: float) -> float:
    """Probability that three independent uniform points of frames at ``t1 < t2 < t3`` pass
    the χ² constant-velocity test and the velocity gate (module docstring; small-disc and
    edge effects of the middle point's disc neglected)."""
    if not t1 < t2 < t3:
        raise ValueError(f"times must satisfy t1 < t2 < t3, got {t1}, {t2}, {t3}")
    w = check_positive(width, "width")
    s = check_positive(sigma_px, "sigma_px")
    a = check_positive(alpha, "alpha")
    if a >= 1:
        raise ValueError(f"alpha must lie in (0, 1), got {alpha}")
    span = t3 - t1
    lam = (t2 - t1) / span
    c = 1.0 + (1.0 - lam) ** 2 + lam**2
    d = float(distance_cdf_square(v_max * span, w) - distance_cdf_square(v_min * span, w))
    return d * math.pi * float(chi2.ppf(1 - a, 2)) * s**2 * c / w**2


def triplet_shapes(n_frames: int, m: int = 4) -> list[tuple[int, int, int]]:
    """Frame triples a 3-of-4 track is confirmed on, frame by frame: ``(k−2, k−1, k)`` and,
    once the window holds four frames, ``(k−3, k−2, k)`` and ``(k−3, k−1, k)``."""
    check_int(n_frames, "n_frames", min_value=0)
    if m != 4:
        raise ValueError(f"the chance rate is derived for the 3-of-4 rule (m = 4), got m={m}")
    out = []
    for k in range(2, n_frames):
        out.append((k - 2, k - 1, k))
        if k >= 3:
            out += [(k - 3, k - 2, k), (k - 3, k - 1, k)]
    return out


def chi2_chance_tracks(scene: Scene, *, v_min: float, v_max: float, sigma_px: float,
                       alpha: float, width: float = 512.0, depletion: bool = True,
                       conflicts: bool = True) -> float:
    """Expected chance tracks of the χ² 3-of-4 rule in a scene, from its non-object detections.

    For every frame triple of :func:`triplet_shapes`, the number of triples of detections from
    three distinct non-object sources (clutter points are distinct; a residual star present in
    two of the frames cannot pair with itself — inclusion–exclusion over its labels) times
    :func:`triplet_chance_probability`.

    With ``conflicts`` (default) the passing triples of one frame that share a detection are
    counted once: a detection of frame f lies in ``μ_f = E_f / N_f`` passing triples on average
    (``E_f`` the expected passing triples of the frame's shapes through f), Poisson; of every
    two sharing it only one is confirmed (disjoint conflict resolution), so
    ``Σ_f N_f μ_f² / 2 = Σ_f E_f² / (2 N_f)`` tracks are lost (second order; the term the
    clutter-only check found missing: without it the count is ~8 % high at 50 per frame).
    With ``depletion`` (default) the count is carried frame by frame in expectation: a chance
    track confirmed at frame k uses one detection in each of its three frames, which is then no
    longer available to later triples (mean-field: each frame's available count shrinks by the
    expected number of tracks through it). Without both, every triple is counted as if all
    detections stayed available — an upper bound, tight only at low density.
    """
    times = [t for t, _ in scene.frames]
    labs = [np.asarray(lab) for lab in scene.labels]
    n = [int(np.sum(lab < 0)) for lab in labs]
    avail = [float(v) for v in n]
    stars = [set(int(v) for v in lab[lab <= -2]) for lab in labs]
    total = 0.0
    shapes = triplet_shapes(len(times))
    for k in sorted({s[2] for s in shapes}):
        through = [0.0] * len(times)
        frame_e = []
        for f1, f2, f3 in (s for s in shapes if s[2] == k):
            s12, s13, s23 = (len(stars[f1] & stars[f2]), len(stars[f1] & stars[f3]),
                             len(stars[f2] & stars[f3]))
            s123 = len(stars[f1] & stars[f2] & stars[f3])
            count = n[f1] * n[f2] * n[f3] - s12 * n[f3] - s13 * n[f2] - s23 * n[f1] + 2 * s123
            if depletion and count > 0:
                full = n[f1] * n[f2] * n[f3]
                count *= (avail[f1] * avail[f2] * avail[f3]) / full
            e = count * triplet_chance_probability(times[f1], times[f2], times[f3],
                                                   width=width, v_min=v_min, v_max=v_max,
                                                   sigma_px=sigma_px, alpha=alpha)
            frame_e.append(((f1, f2, f3), e))
            for f in (f1, f2, f3):
                through[f] += e
        e_k = sum(e for _, e in frame_e)
        lost = 0.0
        if conflicts and e_k > 0:
            lost = sum(through[f] ** 2 / (2.0 * avail[f]) for f in range(len(times))
                       if through[f] > 0 and avail[f] > 0)
            lost = min(lost, 0.5 * e_k)  # second order: keep it a correction
        keep = (e_k - lost) / e_k if e_k > 0 else 0.0
        total += e_k - lost
        if depletion:
            for f in range(len(times)):
                avail[f] = max(avail[f] - keep * through[f], 0.0)
    return total


def _chance_trial(rng: np.random.Generator, cfg: PlantedConfig,
                  levels: tuple[float, ...]) -> list[dict[str, Any]]:
    # the χ² 3-of-4 rule the formula describes: the four-hit acceleration search off
    ini = replace(planted_initiators(cfg)["modified Hough 3/4 (ours)"], accel_px_s2=0.0)
    out = []
    for lam in levels:
        scene = planted_scene(rng, cfg, clutter_per_frame=lam, n_objects=0, n_stars=0)
        out.append({"clutter": lam, "measured": len(ini.initiate(scene.frames)),
                    "analytic": chi2_chance_tracks(scene, v_min=cfg.v_gate_px_s[0],
                                                   v_max=cfg.v_gate_px_s[1],
                                                   sigma_px=cfg.sigma_px, alpha=cfg.alpha,
                                                   width=cfg.width_px)})
    return out


def chance_rate_check(cfg: PlantedConfig | None = None, *,
                      levels: tuple[float, ...] = (20.0, 35.0, 50.0),
                      n_trials: int | tuple[int, ...] = 100,
                      runner: TrialRunner | None = None,
                      seed: int | np.random.SeedSequence = 99) -> pd.DataFrame:
    """Clutter-only scenes: chance tracks of the verified initiator, measured vs analytic.

    Parameters
    ----------
    cfg
        Planted-scene configuration (field, frames, gate, noise, α).
    levels
        Clutter levels (false alarms per frame).
    n_trials
        Scenes per level: one count for every level, or one per level (the full run uses more
        scenes at low density, where a scene holds fewer chance tracks, so that the Poisson
        standard error of every level's ratio is about 1.7 %).
    runner
        Trial runner.
    seed
        Root seed; every level gets its own child stream.

    Returns
    -------
    pandas.DataFrame
        One row per clutter level with the summed ``measured`` and ``analytic`` counts over
        its scenes, their ratio and the Poisson standard error of the ratio.
    """
    cfg = cfg or PlantedConfig()
    runner = runner or TrialRunner(progress=False)
    levels = tuple(float(v) for v in levels)
    counts = (n_trials,) * len(levels) if isinstance(n_trials, (int, np.integer)) \
        else tuple(n_trials)
    if len(counts) != len(levels):
        raise ValueError(f"n_trials must be one count or one per level ({len(levels)}), "
                         f"got {n_trials!r}")
    counts = tuple(check_int(c, "n_trials", min_value=1) for c in counts)
    ss = seed if isinstance(seed, np.random.SeedSequence) else np.random.SeedSequence(seed)
    rows = []
    for lam, n_l, kid in zip(levels, counts, ss.spawn(len(levels))):
        res = runner.map(_chance_trial, n_l, seed=kid, args=(cfg, (lam,)),
                         desc=f"chance rate {lam:g}/frame")
        rows.extend(r for trial in res for r in trial)
    df = pd.DataFrame(rows)
    g = df.groupby("clutter").agg(measured=("measured", "sum"), analytic=("analytic", "sum"),
                                  scenes=("measured", "size")).reset_index()
    g["measured per scene"] = g["measured"] / g["scenes"]
    g["analytic per scene"] = g["analytic"] / g["scenes"]
    g["ratio"] = g["measured"] / g["analytic"]
    g["ratio s.e."] = np.sqrt(g["measured"].clip(lower=1)) / g["analytic"]
    return g
