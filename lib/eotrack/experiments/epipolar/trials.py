"""Trials of Huang, Zhang & Feng: association of one draw, the Monte Carlo over scenario draws
(Fig. 5, Tables 3–5 statistics), the Fig. 6 bound, the error-budget gate and the precomputed
threshold study behind the notebook's widget."""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from itertools import combinations

import numpy as np
import pandas as pd

from eotrack.geometry.association import (
    associate,
    chi2_gate,
    greedy_candidates,
    summary_table,
    three_view_check,
)
from eotrack.geometry.epipolar import (
    epipolar_distances,
    fundamental_from_poses,
    sampson_distances,
)
from eotrack.geometry.rotations import euler_321_from_matrix, look_at, rotation_321
from eotrack.geometry.triangulation import combine_estimates, triangulate_rays, triangulate_two_rays
from eotrack.montecarlo import TrialRunner, run_trials, trial_generators
from eotrack.validation import check_choice, check_generator, check_int, check_positive

from .scenario import (
    ARCMIN,
    PAIR_LABELS,
    PAIRS,
    ErrorConfig,
    Observation,
    Scenario,
    draw_observation,
    nominal_draw,
)

__all__ = [
    "DisplayedDraw",
    "MonteCarlo",
    "SweepResult",
    "ThresholdStudy",
    "associate_observation",
    "closest_other_object_px",
    "displayed_draw",
    "distance_sigma_px",
    "error_budget_gate",
    "fig6_trial",
    "gate_study",
    "objects_recovered",
    "pair_distances",
    "perfect_summary",
    "placement_trial",
    "row_labels",
    "run_fig6",
    "run_scenario_draws",
    "run_sweep",
    "scenario_trial",
    "score_matches",
    "summary_rows",
    "sweep_counts",
    "sweep_rates",
    "sweep_trial",
    "threshold_study",
    "triangulate_object",
    "triangulation_errors",
    "triangulation_trial",
]

_ERRORS = ErrorConfig()  # the paper's error model (default argument)


def pair_distances(obs: Observation, a: int, b: int, *, metric: str = "epipolar") -> np.ndarray:
    """Distance matrix between the points of maps a and b (F from the known poses)."""
    check_choice(metric, "metric", ("epipolar", "sampson"))
    ca, cb = obs.cameras[a], obs.cameras[b]
    F = fundamental_from_poses(ca.K, ca.R, ca.c, cb.K, cb.R, cb.c)
    fn = epipolar_distances if metric == "epipolar" else sampson_distances
    return fn(F, obs.points[a], obs.points[b])


def associate_observation(obs: Observation, threshold: float, *, rule: str = "paper",
                          metric: str = "epipolar", three_view: bool = False,
                          three_view_gate_px: float | None = None,
                          distances: dict | None = None
                          ) -> dict[tuple[int, int], tuple[np.ndarray, np.ndarray]]:
    """Steps 2–5 for every pair of maps: ``{(a, b): (pairs, distances)}``.

    ``three_view=True`` additionally drops pairs that fail :func:`three_view_check`; its gate
    defaults to 1.5 × ``threshold`` (a transferred point carries the triangulation error as
    well, so it scatters more than a point about its epipolar line). ``distances`` may hold
    precomputed ``{(a, b): matrix}``.
    """
    gate3 = 1.5 * max(float(threshold), 1e-6) if three_view_gate_px is None else \
        check_positive(three_view_gate_px, "three_view_gate_px")
    out = {}
    for a, b in PAIRS:
        d = distances[(a, b)] if distances is not None else \
            pair_distances(obs, a, b, metric=metric)
        pairs = associate(d, threshold, rule=rule)
        if three_view and len(pairs):
            others = [(obs.cameras[c], obs.points[c]) for c in range(len(obs.points))
                      if c not in (a, b)]
            keep = three_view_check(obs.points[a], obs.points[b], pairs, obs.cameras[a],
                                    obs.cameras[b], others, gate3)
            pairs = pairs[keep]
        out[(a, b)] = (pairs, d[pairs[:, 0], pairs[:, 1]] if len(pairs) else np.zeros(0))
    return out


def score_matches(obs: Observation, matches) -> pd.DataFrame:
    """Per map pair: true pairs, associated, correct, false, missed, mean distance."""
    rows = []
    for (a, b), (pairs, dist) in matches.items():
        la, lb = obs.labels[a], obs.labels[b]
        n_true = len(np.intersect1d(la[la >= 0], lb[lb >= 0]))
        ok = (la[pairs[:, 0]] == lb[pairs[:, 1]]) & (la[pairs[:, 0]] >= 0) if len(pairs) else \
            np.zeros(0, bool)
        rows.append({"pair": PAIR_LABELS[PAIRS.index((a, b))], "true": n_true,
                     "associated": len(pairs), "correct": int(ok.sum()),
                     "false": int((~ok).sum()), "missed": n_true - int(ok.sum()),
                     "mean_distance_px": float(dist.mean()) if len(dist) else np.nan})
    return pd.DataFrame(rows)


def summary_rows(obs: Observation, matches) -> np.ndarray:
    """Step 6 (Table 3): rows of point indices (−1 = absent), multi-map rows only."""
    rows = summary_table([len(p) for p in obs.points],
                         {k: v[0] for k, v in matches.items()})
    return rows[(rows >= 0).sum(1) >= 2]


def row_labels(obs: Observation, rows: np.ndarray) -> np.ndarray:
    """``(rows, maps)`` truth labels of a summary table (−1 false target, −2 absent)."""
    out = np.full(rows.shape, -2)
    for k in range(rows.shape[1]):
        has = rows[:, k] >= 0
        out[has, k] = obs.labels[k][rows[has, k]]
    return out


def perfect_summary(obs: Observation, rows: np.ndarray, scenario: Scenario) -> bool:
    """Whether the summary table is exactly Table 3's: one row per object, right maps, no
    false targets."""
    lab = row_labels(obs, rows)
    if len(lab) != scenario.visible.shape[1]:
        return False
    for r in lab:
        objs = set(r[r >= -1].tolist())
        if len(objs) != 1 or -1 in objs:
            return False
        j = objs.pop()
        if not np.array_equal(r >= 0, scenario.visible[:, j]):
            return False
    return True


def triangulate_object(obs: Observation, rows: np.ndarray, obj: int
                       ) -> tuple[dict[tuple[int, int], np.ndarray], np.ndarray | None]:
    """Pairwise estimates (km) of object ``obj`` from its summary row, and the N-ray estimate.

    The row is the one whose elements are mostly images of ``obj`` (truth used only to pick
    which row to report). Returns ``({}, None)`` if no row holds it.
    """
    lab = row_labels(obs, rows)
    votes = (lab == obj).sum(1)
    if len(votes) == 0 or votes.max() < 2:
        return {}, None
    row = rows[int(np.argmax(votes))]
    maps = np.flatnonzero(row >= 0)
    rays = {k: obs.cameras[k].rays(obs.points[k][row[k]][None])[0] for k in maps}
    est = {(a, b): triangulate_two_rays(obs.cameras[a].c, rays[a], obs.cameras[b].c, rays[b])
           for a, b in combinations(maps, 2)}
    allrays = triangulate_rays(np.stack([obs.cameras[k].c for k in maps]),
                               np.stack([rays[k] for k in maps]))
    return est, allrays


# --------------------------------------------------------------------------- error budget
def distance_sigma_px(scenario: Scenario, errors: ErrorConfig = _ERRORS, *,
                      step: float = 1e-7) -> pd.DataFrame:
    """Standard deviation of the point-to-line distance of every true pair, by linear error
    propagation (finite-difference Jacobian) of the error model of :class:`ErrorConfig`.

    Uniform attitude noise on ±α has variance α²/3; a uniform ball of radius ρ has per-axis
    variance ρ²/5; jitter σ per centroid axis.
    """
    var_att = (errors.attitude_arcmin * ARCMIN) ** 2 / 3
    var_pos = errors.position_km**2 / 5
    rows = []
    true_px = scenario.true_pixels()
    for a, b in PAIRS:
        common = np.flatnonzero(scenario.visible[a] & scenario.visible[b])
        ca, cb = scenario.cameras[a], scenario.cameras[b]
        ea, eb = euler_321_from_matrix(ca.R), euler_321_from_matrix(cb.R)
        base = np.concatenate([ea, ca.c, eb, cb.c])

        def dist(theta: np.ndarray, pa: np.ndarray, pb: np.ndarray, Ka: np.ndarray = ca.K,
                 Kb: np.ndarray = cb.K) -> np.ndarray:
            Ra = rotation_321(*theta[0:3])
            Rb = rotation_321(*theta[6:9])
            F = fundamental_from_poses(Ka, Ra, theta[3:6], Kb, Rb, theta[9:12])
            la = pa @ F[:, :2].T + F[:, 2]
            return (np.sum(la[:, :2] * pb, 1) + la[:, 2]) / np.hypot(la[:, 0], la[:, 1])

        pa, pb = true_px[a, common], true_px[b, common]
        d0 = dist(base, pa, pb)
        var = np.zeros(len(common))
        for i in range(12):
            h = step if i % 6 < 3 else 1e-3
            t = base.copy()
            t[i] += h
            g = (dist(t, pa, pb) - d0) / h
            var += g**2 * (var_att if i % 6 < 3 else var_pos)
        sig_c = errors.jitter_urad * 1e-6 * ca.K[0, 0]
        for which in (0, 1):
            for ax in (0, 1):
                qa, qb = pa.copy(), pb.copy()
                (qa if which == 0 else qb)[:, ax] += 1e-3
                g = (dist(base, qa, qb) - d0) / 1e-3
                var += g**2 * sig_c**2
        for j, s in zip(common, np.sqrt(var)):
            rows.append({"pair": PAIR_LABELS[PAIRS.index((a, b))],
                         "object": scenario.names[j], "sigma_px": float(s)})
    return pd.DataFrame(rows)


# --------------------------------------------------------------------------- Monte Carlo trials
def sweep_counts(obs: Observation, thresholds, *, distances: dict | None = None,
                 metric: str = "epipolar") -> tuple[np.ndarray, np.ndarray, int]:
    """Correct and false associations of the paper's rule for every threshold (one greedy pass
    per map pair at the largest threshold), and the number of true pairs."""
    th = np.asarray(thresholds, float)
    correct = np.zeros(len(th))
    false = np.zeros(len(th))
    n_true = 0
    for a, b in PAIRS:
        d = distances[(a, b)] if distances is not None else \
            pair_distances(obs, a, b, metric=metric)
        la, lb = obs.labels[a], obs.labels[b]
        n_true += len(np.intersect1d(la[la >= 0], lb[lb >= 0]))
        same = (la[:, None] == lb[None, :]) & (la[:, None] >= 0)
        pairs = greedy_candidates(d, th.max())
        if len(pairs):
            dd = d[pairs[:, 0], pairs[:, 1]]
            ok = same[pairs[:, 0], pairs[:, 1]]
            below = dd[None, :] < th[:, None]
            correct += (below & ok).sum(1)
            false += (below & ~ok).sum(1)
    return correct, false, n_true


def sweep_trial(rng: np.random.Generator, scenario: Scenario, errors: ErrorConfig,
                thresholds: np.ndarray, metric: str = "epipolar"
                ) -> tuple[np.ndarray, np.ndarray, int]:
    """One draw of the Fig. 5 sweep only (see :func:`sweep_counts`)."""
    return sweep_counts(draw_observation(rng, scenario, errors), thresholds, metric=metric)


@dataclass(frozen=True)
class SweepResult:
    """Rates of the paper's rule versus threshold over many draws (Fig. 5)."""

    thresholds: np.ndarray
    accuracy: np.ndarray
    false_rate: np.ndarray
    miss_rate: np.ndarray
    error_rate: np.ndarray
    n_true: int
    n_associated: np.ndarray

    @property
    def best_threshold(self) -> float:
        """Threshold with the smallest total error rate."""
        return float(self.thresholds[int(np.argmin(self.error_rate))])


def sweep_rates(correct: np.ndarray, false: np.ndarray, n_true: float,
                thresholds: np.ndarray) -> SweepResult:
    """Turn summed counts into the Fig. 5 rates (correct and missed per true pair, false per
    associated pair, total error = (missed + false) per true pair)."""
    assoc = correct + false
    acc = correct / n_true
    fr = np.divide(false, assoc, out=np.zeros_like(false, dtype=float), where=assoc > 0)
    return SweepResult(np.asarray(thresholds, float), acc, fr, 1 - acc,
                       (n_true - correct + false) / n_true, int(n_true), assoc)


def run_sweep(scenario: Scenario, errors: ErrorConfig, thresholds, n_draws: int, *,
              seed: int = 20190401, metric: str = "epipolar",
              runner: TrialRunner | None = None) -> SweepResult:
    """Fig. 5 sweep over ``n_draws`` seeded scenario draws."""
    out = run_trials(sweep_trial, n_draws, seed=seed, runner=runner,
                     args=(scenario, errors, np.asarray(thresholds, float), metric),
                     desc="threshold sweep")
    return sweep_rates(np.sum([o[0] for o in out], 0), np.sum([o[1] for o in out], 0),
                       float(sum(o[2] for o in out)), thresholds)


def error_budget_gate(scenario: Scenario, errors: ErrorConfig = _ERRORS, *,
                      p: float = 0.99) -> tuple[float, float]:
    """``(σ_rms, L)``: rms predicted distance spread of true pairs and the gate
    ``L = σ_rms · sqrt(χ²₁(p))`` (the distance is one signed Gaussian-like coordinate) —
    :func:`eotrack.geometry.chi2_gate`, the library's default gate."""
    sig = distance_sigma_px(scenario, errors)["sigma_px"].to_numpy()
    s = float(np.sqrt(np.mean(sig**2)))
    return s, chi2_gate(s, p)


def objects_recovered(obs: Observation, rows: np.ndarray, scenario: Scenario) -> int:
    """How many objects have a summary row made of exactly their images in exactly the maps
    that see them (Table 3's row)."""
    lab = row_labels(obs, rows)
    n = 0
    for j in range(scenario.visible.shape[1]):
        want = np.where(scenario.visible[:, j], j, -2)
        n += int(np.any(np.all(lab == want[None, :], axis=1)))
    return n


def triangulation_errors(obs: Observation, rows: np.ndarray, scenario: Scenario,
                          objects: tuple[int, ...] = (0, 4)) -> np.ndarray:
    """Max coordinate error (km) of the paper's combined estimate of each object (NaN if the
    object has no row)."""
    errs = []
    for obj in objects:
        est, _ = triangulate_object(obs, rows, obj)
        if est:
            comb = combine_estimates(np.stack(list(est.values())), rule="paper").position
            errs.append(np.abs(comb - scenario.objects_km[obj]).max())
        else:
            errs.append(np.nan)
    return np.array(errs)


def triangulation_trial(rng: np.random.Generator, scenario: Scenario, errors: ErrorConfig,
                        threshold: float = 10.0) -> np.ndarray:
    """One draw: associate (paper rule), summarise, triangulate GEO1 and GEO5; returns their
    max coordinate errors (km)."""
    obs = draw_observation(rng, scenario, errors)
    rows = summary_rows(obs, associate_observation(obs, threshold))
    return triangulation_errors(obs, rows, scenario)


def scenario_trial(rng: np.random.Generator, scenario: Scenario, errors: ErrorConfig,
                   thresholds: np.ndarray, nominal_px: float = 10.0) -> dict:
    """One seeded scenario draw: threshold sweep (paper rule), Table 3/4/5 statistics, the
    three-view check and the global assignment at ``nominal_px``.

    Each draw also has a noise-free twin with the same false targets (common random numbers:
    both come from one child seed of ``rng``), associated at ``nominal_px``, for the paired
    Table 4 comparison (``mean_d0``; ``*_true`` keys use the correct pairs only).
    """
    check_generator(rng)
    child = int(rng.integers(2**63))
    obs = draw_observation(np.random.default_rng(child), scenario, errors)
    obs0 = draw_observation(np.random.default_rng(child), scenario, errors.noise_free())
    dists = {(a, b): pair_distances(obs, a, b) for a, b in PAIRS}
    correct, false, n_true = sweep_counts(obs, thresholds, distances=dists)
    true_d = np.concatenate([
        dists[(a, b)][(obs.labels[a][:, None] == obs.labels[b][None, :])
                      & (obs.labels[a][:, None] >= 0)] for a, b in PAIRS])
    m = associate_observation(obs, nominal_px, distances=dists)
    sc = score_matches(obs, m)
    m3 = associate_observation(obs, nominal_px, three_view=True, distances=dists)
    sc3 = score_matches(obs, m3)
    mh = associate_observation(obs, nominal_px, rule="hungarian", distances=dists)
    sch = score_matches(obs, mh)
    rows = summary_rows(obs, m)
    errs = triangulation_errors(obs, rows, scenario)
    m0 = associate_observation(obs0, nominal_px)
    sc0 = score_matches(obs0, m0)
    return {"correct": correct, "false": false, "n_true": n_true, "true_d": true_d,
            "mean_d": sc["mean_distance_px"].to_numpy(),
            "mean_d0": sc0["mean_distance_px"].to_numpy(),
            "mean_d_true": _mean_true_distance(obs, m),
            "mean_d0_true": _mean_true_distance(obs0, m0),
            "all_true_associated": bool(sc["missed"].sum() == 0),
            "false_nominal": int(sc["false"].sum()), "missed_nominal": int(sc["missed"].sum()),
            "false_3view": int(sc3["false"].sum()), "missed_3view": int(sc3["missed"].sum()),
            "false_hungarian": int(sch["false"].sum()),
            "missed_hungarian": int(sch["missed"].sum()),
            "perfect_table": perfect_summary(obs, rows, scenario),
            "objects_recovered": objects_recovered(obs, rows, scenario),
            "tri_err_km": errs}


def placement_trial(rng: np.random.Generator, scenario: Scenario, errors: ErrorConfig,
                    thresholds: np.ndarray, nominal_px: float = 10.0) -> dict:
    """One draw of the lighter study used to compare object placements: the Fig. 5 sweep counts,
    the Table 3 statistic (objects recovered, paper rule at ``nominal_px``) and the Table 5 /
    Fig. 8 triangulation errors of GEO1 and GEO5 (NaN where the object has no row).

    Draws the observation exactly as :func:`scenario_trial` does (one child seed), so the same
    seed and count give the same draws, and the same numbers, as the main Monte Carlo.
    """
    check_generator(rng)
    child = int(rng.integers(2**63))
    obs = draw_observation(np.random.default_rng(child), scenario, errors)
    dists = {(a, b): pair_distances(obs, a, b) for a, b in PAIRS}
    correct, false, n_true = sweep_counts(obs, thresholds, distances=dists)
    rows = summary_rows(obs, associate_observation(obs, nominal_px, distances=dists))
    return {"correct": correct, "false": false, "n_true": n_true,
            "objects_recovered": objects_recovered(obs, rows, scenario),
            "tri_err_km": triangulation_errors(obs, rows, scenario)}


def _mean_true_distance(obs: Observation, matches) -> np.ndarray:
    """Per map pair: mean distance of the *correct* associated pairs (NaN if none)."""
    out = []
    for (a, b), (pairs, dist) in matches.items():
        if not len(pairs):
            out.append(np.nan)
            continue
        la, lb = obs.labels[a][pairs[:, 0]], obs.labels[b][pairs[:, 1]]
        ok = (la == lb) & (la >= 0)
        out.append(float(dist[ok].mean()) if ok.any() else np.nan)
    return np.array(out)


def closest_other_object_px(scenario: Scenario) -> dict[str, float]:
    """Per map pair: the smallest noise-free distance of an object's image from the epipolar
    line of a *different* object — how confusable the pair is."""
    px = scenario.true_pixels()
    out = {}
    for a, b in PAIRS:
        ca, cb = scenario.cameras[a], scenario.cameras[b]
        ia, ib = np.flatnonzero(scenario.visible[a]), np.flatnonzero(scenario.visible[b])
        d = epipolar_distances(fundamental_from_poses(ca.K, ca.R, ca.c, cb.K, cb.R, cb.c),
                               px[a, ia], px[b, ib])
        other = ia[:, None] != ib[None, :]
        out[f"{a + 1}-{b + 1}"] = float(d[other].min()) if other.any() else np.nan
    return out


def _line_length_in_box(lines: np.ndarray, w: float, h: float) -> np.ndarray:
    """Length of each line a u + b v + c = 0 inside [−0.5, w − 0.5] × [−0.5, h − 0.5]."""
    a, b, c = lines.T
    lo_u, hi_u, lo_v, hi_v = -0.5, w - 0.5, -0.5, h - 0.5
    pts = []
    with np.errstate(divide="ignore", invalid="ignore"):
        for u in (lo_u, hi_u):
            v = -(a * u + c) / b
            pts.append(np.stack([np.full_like(v, u), v], 1))
        for v in (lo_v, hi_v):
            u = -(b * v + c) / a
            pts.append(np.stack([u, np.full_like(u, v)], 1))
    P = np.stack(pts, 1)  # (n, 4, 2)
    ok = np.isfinite(P).all(2) & (P[..., 0] >= lo_u - 1e-9) & (P[..., 0] <= hi_u + 1e-9) & \
        (P[..., 1] >= lo_v - 1e-9) & (P[..., 1] <= hi_v + 1e-9)
    P = np.where(ok[..., None], P, np.nan)
    diff = P[:, :, None, :] - P[:, None, :, :]
    dist = np.sqrt(np.nansum(diff**2, -1))
    dist = np.where(np.isnan(diff).any(-1), 0.0, dist)
    return dist.reshape(len(lines), -1).max(1)


def fig6_trial(rng: np.random.Generator, thresholds: np.ndarray, n_points: int = 100,
               size: int = 512, mode: str = "overlapping", f_px: float | None = None
               ) -> tuple[np.ndarray, np.ndarray]:
    """One simulation of the Fig. 6 bound.

    A random F, ``n_points`` uniform points in each ``size``×``size`` image; the bound is the
    share of image-1 points with more than one candidate within L of their epipolar line.

    Modes
    -----
    ``"overlapping"``: two cameras with the experiment's intrinsics look at a common point
    36,000–40,000 km away from random positions 1,000–10,000 km apart (random roll) — the
    geometry of the paper's problem; epipolar lines cross the whole image.
    ``"random_f"``: F has i.i.d. standard normal entries (rank 2 enforced) in image
    coordinates normalised to [−1, 1]; many epipolar lines miss the image.

    Returns
    -------
    (mc, analytic, poisson) : numpy.ndarray
        Per threshold: the simulated bound, its binomial expectation given the lines
        (``P(N ≥ 2)``, ``N ~ Binomial(n_points, 2 L ℓ / size²)``, ℓ = line length in image)
        and the Poisson approximation ``1 − e^{−λ}(1 + λ)``, ``λ = n_points · 2 L ℓ / size²``.
    """
    check_generator(rng)
    check_choice(mode, "mode", ("overlapping", "random_f"))
    th = np.asarray(thresholds, float)
    if mode == "overlapping":
        f = f_px if f_px is not None else size / (2 * np.tan(np.radians(1.0)))
        K = np.array([[f, 0, (size - 1) / 2], [0, f, (size - 1) / 2], [0, 0, 1.0]])
        target = rng.normal(size=3)
        target *= rng.uniform(36000, 40000) / np.linalg.norm(target)
        c1 = np.zeros(3)
        v = rng.normal(size=3)
        c2 = v / np.linalg.norm(v) * rng.uniform(1000, 10000)
        cams = []
        for c in (c1, c2):
            up = rng.normal(size=3)
            cams.append(look_at(target - c, up=up))
        F = fundamental_from_poses(K, cams[0], c1, K, cams[1], c2)
    else:
        G = rng.normal(size=(3, 3))
        u, s, vt = np.linalg.svd(G)
        G = u @ np.diag([s[0], s[1], 0.0]) @ vt
        half = size / 2
        T = np.array([[1 / half, 0, -1.0], [0, 1 / half, -1.0], [0, 0, 1.0]])  # px -> [-1, 1]
        F = T.T @ G @ T
    p1 = rng.uniform(-0.5, size - 0.5, (n_points, 2))
    p2 = rng.uniform(-0.5, size - 0.5, (n_points, 2))
    d = epipolar_distances(F, p1, p2)
    n_cand = (d[:, :, None] < th[None, None, :]).sum(1)  # (n1, n_th)
    mc = (n_cand > 1).mean(0)
    lines = p1 @ F[:, :2].T + F[:, 2]
    lines /= np.hypot(lines[:, 0], lines[:, 1])[:, None]
    ell = _line_length_in_box(lines, size, size)
    p = np.clip(2 * th[None, :] * ell[:, None] / size**2, 0, 1)
    n = n_points
    analytic = 1 - (1 - p) ** n - n * p * (1 - p) ** (n - 1)
    lam = n * p
    poisson = 1 - np.exp(-lam) * (1 + lam)
    return mc, analytic.mean(0), poisson.mean(0)




def gate_study(scenario: Scenario, attitudes_arcmin=(0.25, 0.5, 1.0, 2.0, 3.0), *,
               gaussian: bool = False, thresholds=None, n_draws: int = 100, p: float = 0.99,
               runner: TrialRunner | None = None) -> pd.DataFrame:
    """Best threshold of the Fig. 5 sweep versus the error-budget gate, per attitude error.

    ``gaussian=True`` reads the attitude figure as an rms value instead of a bound (uniform
    noise of bound ``√3 · value`` has that rms).
    """
    th = np.arange(0.5, 30.01, 0.5) if thresholds is None else np.asarray(thresholds, float)
    rows = []
    for att in attitudes_arcmin:
        bound = float(att) * (np.sqrt(3.0) if gaussian else 1.0)
        err = ErrorConfig(attitude_arcmin=bound)
        sw = run_sweep(scenario, err, th, n_draws, runner=runner)
        sig, gate = error_budget_gate(scenario, err, p=p)
        i = int(np.argmin(sw.error_rate))
        rows.append({"attitude (′)": att, "σ_d predicted (px)": sig,
                     f"gate χ²₁ {100 * p:g} % (px)": gate, "best L (px)": sw.best_threshold,
                     "total error at best L": sw.error_rate[i],
                     "total error at gate": float(np.interp(gate, th, sw.error_rate)),
                     "correct at gate": float(np.interp(gate, th, sw.accuracy))})
    out = pd.DataFrame(rows)
    out.attrs["reading"] = "rms" if gaussian else "bound"
    return out




# --------------------------------------------------------------------------- runs used by the
# report and the notebook (same seeds, so the notebook's numbers are the REPORT's)
@dataclass(frozen=True)
class DisplayedDraw:
    """The draw shown in Figs. 3–4 and Tables 3–5: noisy and noise-free (same false targets),
    their associations at the threshold, per-pair scores and the summary rows."""

    obs: Observation
    obs0: Observation
    matches: dict
    matches0: dict
    scores: pd.DataFrame
    scores0: pd.DataFrame
    rows: np.ndarray
    threshold: float


def displayed_draw(scenario: Scenario, errors: ErrorConfig = _ERRORS,
                   threshold: float = 10.0, seed: int = 2019) -> DisplayedDraw:
    """Draw, associate (paper rule) and summarise the displayed instant (seed 2019)."""
    obs, obs0 = nominal_draw(scenario, seed, errors)
    m = associate_observation(obs, threshold)
    m0 = associate_observation(obs0, threshold)
    return DisplayedDraw(obs, obs0, m, m0, score_matches(obs, m), score_matches(obs0, m0),
                         summary_rows(obs, m), float(threshold))


@dataclass(frozen=True)
class MonteCarlo:
    """Outputs of :func:`scenario_trial` over the seeded draws and the Fig. 5 sweep."""

    trials: list
    sweep: SweepResult
    threshold: float

    @property
    def n_draws(self) -> int:
        """Number of scenario draws."""
        return len(self.trials)

    def total(self, key: str) -> int:
        """Sum of an integer per-draw count (e.g. ``"false_nominal"``)."""
        return int(sum(o[key] for o in self.trials))

    def stack(self, key: str) -> np.ndarray:
        """Per-draw values of ``key`` stacked along axis 0."""
        return np.stack([np.asarray(o[key]) for o in self.trials])


def run_scenario_draws(scenario: Scenario, errors: ErrorConfig = _ERRORS,
                       thresholds=None, threshold: float = 10.0, n_draws: int = 300, *,
                       seed: int = 20190401, runner: TrialRunner | None = None) -> MonteCarlo:
    """The Monte Carlo of Fig. 5 and Tables 3–5: ``n_draws`` seeded :func:`scenario_trial`."""
    th = np.arange(0.5, 20.01, 0.5) if thresholds is None else np.asarray(thresholds, float)
    n = check_int(n_draws, "n_draws", min_value=1)
    out = run_trials(scenario_trial, n, seed=seed, runner=runner,
                     args=(scenario, errors, th, float(threshold)),
                     desc="epipolar scenario draws")
    sw = sweep_rates(np.sum([o["correct"] for o in out], 0),
                     np.sum([o["false"] for o in out], 0),
                     float(sum(o["n_true"] for o in out)), th)
    return MonteCarlo(out, sw, float(threshold))


def run_fig6(n_sims: int = 600, thresholds=(5.0, 10.0, 15.0, 20.0), n_points: int = 100,
             size: int = 512, *, seed: int = 600, runner: TrialRunner | None = None
             ) -> dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Fig. 6 in both variants: ``{mode: (running mean (n_sims, n_L), binomial, Poisson)}``."""
    n = check_int(n_sims, "n_sims", min_value=1)
    th = np.asarray(thresholds, float)
    res = {}
    for mode in ("overlapping", "random_f"):
        o6 = run_trials(fig6_trial, n, seed=seed, runner=runner,
                        args=(th, int(n_points), int(size), mode), desc=f"Fig. 6 {mode}")
        mc = np.stack([r[0] for r in o6])
        run = np.cumsum(mc, 0) / np.arange(1, len(mc) + 1)[:, None]
        res[mode] = (run, np.stack([r[1] for r in o6]).mean(0),
                     np.stack([r[2] for r in o6]).mean(0))
    return res


# --------------------------------------------------------------------------- widget study
@dataclass(frozen=True)
class ThresholdStudy:
    """Accepted pairs of the paper's rule at a large threshold, over seeded draws: the counts
    at any smaller L follow by counting (no re-simulation, no new distances).

    ``correct_d`` / ``false_d`` are the sorted distances of the correct / false accepted pairs;
    ``n_true`` the number of true pairs; ``sigma_px`` and ``gate_px`` the error-budget spread
    and its 99 % χ²₁ gate for the same error model.
    """

    correct_d: np.ndarray
    false_d: np.ndarray
    n_true: int
    n_draws: int
    l_max: float
    sigma_px: float
    gate_px: float
    errors: ErrorConfig

    def counts(self, threshold) -> tuple[np.ndarray, np.ndarray]:
        """Correct and false associations for threshold(s) ``L`` (≤ ``l_max``)."""
        L = np.asarray(threshold, float)
        if np.any(L < 0) or np.any(L > self.l_max):
            raise ValueError(f"threshold must lie in [0, {self.l_max:g}] px")
        return (np.searchsorted(self.correct_d, L, side="left"),
                np.searchsorted(self.false_d, L, side="left"))

    def rates(self, threshold) -> dict[str, np.ndarray]:
        """Missed and false associations per true pair, and their sum (total error)."""
        c, f = self.counts(threshold)
        missed = (self.n_true - c) / self.n_true
        false = f / self.n_true
        return {"missed": missed, "false": false, "total": missed + false,
                "correct": c / self.n_true}

    def curves(self, n: int = 241) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """``(thresholds, rates)`` on ``n`` thresholds from 0 to ``l_max``."""
        th = np.linspace(0.0, self.l_max, n)
        return th, self.rates(th)

    def histograms(self, n_bins: int = 60) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(edges, correct counts, false counts)`` of the accepted pairs' distances."""
        edges = np.linspace(0.0, self.l_max, n_bins + 1)
        return (edges, np.histogram(self.correct_d, edges)[0],
                np.histogram(self.false_d, edges)[0])


@lru_cache(maxsize=32)
def _study(attitude_arcmin: float, n_false: int, n_draws: int, l_max: float,
           seed: int) -> ThresholdStudy:
    from .scenario import build_scenario

    scen = build_scenario()
    err = ErrorConfig(attitude_arcmin=attitude_arcmin, n_false=n_false)
    ok_d, bad_d, n_true = [], [], 0
    for rng in trial_generators(seed, n_draws):
        obs = draw_observation(rng, scen, err)
        for a, b in PAIRS:
            d = pair_distances(obs, a, b)
            la, lb = obs.labels[a], obs.labels[b]
            n_true += len(np.intersect1d(la[la >= 0], lb[lb >= 0]))
            pairs = greedy_candidates(d, l_max)
            if len(pairs):
                ok = (la[pairs[:, 0]] == lb[pairs[:, 1]]) & (la[pairs[:, 0]] >= 0)
                dd = d[pairs[:, 0], pairs[:, 1]]
                ok_d.append(dd[ok])
                bad_d.append(dd[~ok])
    sig, gate = error_budget_gate(scen, err)
    return ThresholdStudy(np.sort(np.concatenate(ok_d)) if ok_d else np.zeros(0),
                          np.sort(np.concatenate(bad_d)) if bad_d else np.zeros(0),
                          int(n_true), n_draws, l_max, sig, gate, err)


def threshold_study(attitude_arcmin: float = 1.0, n_false: int = 3, *, n_draws: int = 60,
                    l_max: float = 30.0, seed: int = 20190401) -> ThresholdStudy:
    """Precompute (and cache) the :class:`ThresholdStudy` of the built scenario for one error
    setting; the notebook's widget re-counts it for every threshold."""
    att = check_positive(attitude_arcmin, "attitude_arcmin", allow_zero=True)
    nf = check_int(n_false, "n_false", min_value=0)
    n = check_int(n_draws, "n_draws", min_value=1)
    lm = check_positive(l_max, "l_max")
    return _study(float(att), nf, n, float(lm), int(seed))
