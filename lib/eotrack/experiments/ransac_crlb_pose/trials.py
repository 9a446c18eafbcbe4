"""Trials of the RANSAC + CRLB experiment: one run, the Monte Carlo loops and their tables."""

from __future__ import annotations

import time
from dataclasses import replace
from typing import Any

import numpy as np
import pandas as pd
from scipy import stats
from scipy.spatial.transform import Rotation

from eotrack.montecarlo import TrialRunner, run_trials
from eotrack.pose import (
    best_initial_pose,
    crlb_weight_matrix,
    greedy_design,
    information_monotonicity,
    pose_crlb,
    project_points,
    projection_jacobian,
    ransac_pose_dlt,
    refine_pose,
    scaled_crlb_weights,
    select_features_crlb,
)
from eotrack.validation import check_choice, check_int, check_positive

from .scenario import (
    READINGS,
    Scenario,
    Settings,
    estimate_point_sigma,
    make_scene,
    pose_errors,
)

__all__ = [
    "budget_experiment",
    "efficiency_experiment",
    "error_summary",
    "holm",
    "ml_pose_samples",
    "monotonicity_curves",
    "readings_table",
    "run_pose_experiment",
    "run_trial",
    "select_and_refit",
    "weights_study",
    "wilcoxon_less",
]


def select_and_refit(reading: str, X: np.ndarray, u: np.ndarray, K: np.ndarray,
                     R: np.ndarray, t: np.ndarray, sigma: np.ndarray,
                     rng: np.random.Generator, settings: Settings | None = None,
                     weights: Any = None) -> dict:
    """Apply one reading of the §2.4 rule to RANSAC inliers and re-estimate the pose.

    Parameters
    ----------
    reading
        A key of :data:`READINGS`.
    X, u, K
        Inlier target points, image points (mm) and intrinsics.
    R, t
        The RANSAC pose (the Jacobians and residuals are evaluated there).
    sigma
        The simulator's per-point σ (used only by readings whose noise source is ``"true"``).
    rng
        Generator for the start draws and the order of the rest.
    settings
        :class:`Settings` (start draws, tolerance).
    weights
        (7,) weights of the score's 7 CRLB values (default ones: m² + quaternion², as the
        reproduction; :func:`eotrack.pose.scaled_crlb_weights` makes it dimensionless).

    Returns
    -------
    dict
        ``selected`` (mask), ``fallback``, ``R``, ``t`` (unweighted LM on the selection).
    """
    check_choice(reading, "reading", list(READINGS))
    st = settings or Settings()
    rule, start, noise = READINGS[reading]
    resid = u - project_points(X, R, t, K)
    sig = estimate_point_sigma(resid) if noise == "est" else sigma
    sel = select_features_crlb(X, R, t, K, rng, rule=rule, start=start, sigma_px=sig,
                               residuals=resid, max_draws=st.crlb_max_draws, tol=st.tolerance,
                               weights=weights)
    S = sel.selected
    Rs, ts = (R, t) if S.all() else refine_pose(X[S], u[S], K, R, t)
    return {"selected": S, "fallback": sel.fallback, "R": Rs, "t": ts}


def run_trial(rng: np.random.Generator, scenario: Scenario, settings: Settings,
              n_points: int | None = None, outlier_fraction: float | None = None) -> dict:
    """One run: RANSAC, then every selection reading, each followed by an unweighted LM pose.

    Returns a flat dict: ``success``, ``n_points``, ``n_inliers``, ``gross_kept``,
    ``pos_<method>`` (m), ``att_<method>`` (deg), ``n_<reading>``, ``fallback_<reading>`` for
    methods ``ransac``, ``ml`` (weighted by the true σ_i, for reference) and each reading.
    """
    scene = make_scene(rng, scenario, n_points=n_points, outlier_fraction=outlier_fraction)
    out: dict[str, Any] = {"n_points": len(scene.points)}
    res = ransac_pose_dlt(scene.points, scene.pixels, scene.K, rng,
                          settings.ransac_config(scenario))
    out["success"] = res.success
    out["ransac_draws"] = res.n_draws
    if not res.success:
        return out
    inl = res.inliers
    X, u, sig = scene.points[inl], scene.pixels[inl], scene.sigma[inl]
    out["n_inliers"] = int(inl.sum())
    out["gross_kept"] = int((inl & scene.gross).sum())
    out["pos_ransac"], out["att_ransac"] = pose_errors(res.R, res.t, scene)
    Rm, tm = refine_pose(X, u, scene.K, res.R, res.t, sigma_px=sig)
    out["pos_ml"], out["att_ml"] = pose_errors(Rm, tm, scene)
    # one independent stream per reading, so a reading's result does not depend on which
    # other readings are computed in the same run
    sel_seed = int(rng.integers(2**62))
    for name in settings.readings:
        rng_sel = np.random.default_rng([sel_seed, list(READINGS).index(name)])
        r = select_and_refit(name, X, u, scene.K, res.R, res.t, sig, rng_sel, settings)
        out[f"pos_{name}"], out[f"att_{name}"] = pose_errors(r["R"], r["t"], scene)
        out[f"n_{name}"] = int(r["selected"].sum())
        out[f"fallback_{name}"] = bool(r["fallback"])
    return out


def _weights_trial(rng: np.random.Generator, scenario: Scenario, settings: Settings,
                   reading: str) -> dict:
    scene = make_scene(rng, scenario)
    res = ransac_pose_dlt(scene.points, scene.pixels, scene.K, rng,
                          settings.ransac_config(scenario))
    if not res.success:
        return {"success": False}
    inl = res.inliers
    X, u, sig = scene.points[inl], scene.pixels[inl], scene.sigma[inl]
    out: dict[str, Any] = {"success": True, "n_inliers": int(inl.sum())}
    out["pos_ransac"], out["att_ransac"] = pose_errors(res.R, res.t, scene)
    seed = int(rng.integers(2**62))
    L = float(np.linalg.norm(res.t))
    for name, w in (("unit", None), ("scaled", scaled_crlb_weights(L))):
        r = select_and_refit(reading, X, u, scene.K, res.R, res.t, sig,
                             np.random.default_rng(seed), settings, weights=w)
        out[f"pos_{name}"], out[f"att_{name}"] = pose_errors(r["R"], r["t"], scene)
        out[f"frac_{name}"] = float(r["selected"].mean())
    return out


def weights_study(n_runs: int = 80, *, reading: str = "pooled", scenario: Scenario | None = None,
                  settings: Settings | None = None, runner: TrialRunner | None = None,
                  seed: int = 29) -> pd.DataFrame:
    """The score's units (beyond the paper): unit weights (m² + quaternion²) versus the
    dimensionless weights of :func:`eotrack.pose.scaled_crlb_weights` with ``L = |t̂|``.

    Each run: one image, RANSAC, then ``reading`` with both weightings from the same start
    stream (paired). Columns ``pos_/att_/frac_`` × ``unit``/``scaled`` and ``*_ransac``.
    """
    check_choice(reading, "reading", list(READINGS))
    rows = run_trials(_weights_trial, check_int(n_runs, "n_runs", min_value=2), seed=seed,
                      args=(scenario or Scenario(), settings or Settings(), reading),
                      runner=runner, desc="weights study")
    df = pd.DataFrame(rows)
    return df[df["success"]].reset_index(drop=True)


def run_pose_experiment(n_runs: int, *, scenario: Scenario | None = None,
                        settings: Settings | None = None, runner: TrialRunner | None = None,
                        seed: int | None = None, n_points: int | None = None,
                        outlier_fraction: float | None = None) -> pd.DataFrame:
    """``n_runs`` seeded runs of :func:`run_trial` as a DataFrame (one row per run)."""
    sc = scenario or Scenario()
    st = settings or Settings()
    n_runs = check_int(n_runs, "n_runs", min_value=1)
    for r in st.readings:
        check_choice(r, "settings.readings", list(READINGS))
    rows = run_trials(run_trial, n_runs, seed=st.seed if seed is None else seed,
                      args=(sc, st, n_points, outlier_fraction), runner=runner,
                      desc="pose runs")
    return pd.DataFrame(rows)


def error_summary(df: pd.DataFrame, methods: tuple[str, ...] = ("ransac", *READINGS, "ml")
                  ) -> pd.DataFrame:
    """Mean / median position (m) and attitude (deg) errors, points used, per method."""
    ok = df[df["success"]]
    rows = []
    for m in methods:
        if f"pos_{m}" not in ok:
            continue
        n_used = ok["n_inliers"] if m in ("ransac", "ml") else ok[f"n_{m}"]
        rows.append({
            "method": m,
            "pos mean (m)": ok[f"pos_{m}"].mean(), "pos median (m)": ok[f"pos_{m}"].median(),
            "att mean (deg)": ok[f"att_{m}"].mean(), "att median (deg)": ok[f"att_{m}"].median(),
            "points used": n_used.mean(),
            "fraction of inliers": (n_used / ok["n_inliers"]).mean(),
            "fallback runs": int(ok[f"fallback_{m}"].sum()) if f"fallback_{m}" in ok else 0,
        })
    return pd.DataFrame(rows).set_index("method")


def wilcoxon_less(a: Any, b: Any) -> float:
    """One-sided paired Wilcoxon signed-rank p-value for ``a < b`` (1.0 if all pairs tie)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    if a.shape != b.shape or a.ndim != 1:
        raise ValueError(f"a and b must be 1-D of equal length, got {a.shape} and {b.shape}")
    if np.all(a - b == 0):
        return 1.0
    return float(stats.wilcoxon(a, b, alternative="less").pvalue)


def holm(pvalues: Any) -> np.ndarray:
    """Holm–Bonferroni adjusted p-values (step-down; controls the family-wise error rate).

    ``p_(k)`` sorted ascending is multiplied by ``m − k + 1`` (k = 1…m), made monotone by a
    running maximum and clipped at 1; reject where the adjusted value is below α.
    """
    p = np.asarray(pvalues, float)
    if p.ndim != 1 or np.any((p < 0) | (p > 1)) or not np.all(np.isfinite(p)):
        raise ValueError("pvalues must be a 1-D array of probabilities in [0, 1]")
    m = len(p)
    order = np.argsort(p)
    adj = np.maximum.accumulate(p[order] * (m - np.arange(m)))
    out = np.empty(m)
    out[order] = np.minimum(adj, 1.0)
    return out


def readings_table(df: pd.DataFrame, primary: str = "pooled") -> pd.DataFrame:
    """Per reading × metric: kept fraction, mean ratio, win rate, raw and Holm-adjusted p.

    The ``primary`` reading is the protocol's confirmatory test (uncorrected p; fixed from the
    text after earlier results were seen); every
    other reading present in ``df`` is exploratory, and its p-values are Holm-adjusted over the
    whole exploratory family (readings × 2 metrics).
    """
    ok = df[df["success"]]
    rows = []
    for name in READINGS:
        if f"pos_{name}" not in ok:
            continue
        for q in ("pos", "att"):
            a, b = ok[f"{q}_{name}"].to_numpy(), ok[f"{q}_ransac"].to_numpy()
            rows.append({"reading": name, "metric": q,
                         "role": "primary" if name == primary else "exploratory",
                         "noise to selector": READINGS[name][2],
                         "kept / inliers": float((ok[f"n_{name}"] / ok["n_inliers"]).mean()),
                         "mean ratio": a.mean() / b.mean(),
                         "win rate": float(np.mean(a < b)),
                         "p": wilcoxon_less(a, b)})
    out = pd.DataFrame(rows)
    expl = out["role"] == "exploratory"
    out["p (Holm)"] = out["p"]
    if expl.any():
        out.loc[expl, "p (Holm)"] = holm(out.loc[expl, "p"].to_numpy())
    out["family size"] = np.where(expl, int(expl.sum()), 1)
    return out.set_index(["reading", "metric"])


# ---------------------------------------------------------------- monotonicity (§2.4)

def monotonicity_curves(rng: np.random.Generator, scenario: Scenario | None = None,
                        n_orders: int = 5) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Scores of nested sets for several random orders of one scene's (gross-error-free) points.

    Returns
    -------
    sizes, exact, sandwich
        (m,) set sizes 6…n; (n_orders, m) exact-CRLB scores (non-increasing along each row);
        (n_orders, m) "sandwich" scores — the covariance of the unweighted pose — for the same
        orders, which can rise when a noisy point is added.
    """
    sc = scenario or Scenario()
    n_orders = check_int(n_orders, "n_orders", min_value=1)
    scene = make_scene(rng, sc, outlier_fraction=0.0)
    n = len(scene.points)
    orders = [rng.permutation(n) for _ in range(n_orders)]
    exact = np.array([information_monotonicity(scene.points, sc.R, sc.t, sc.K, scene.sigma, o)
                      for o in orders])
    G = projection_jacobian(scene.points, sc.R, sc.t, sc.K)
    A = np.einsum("nki,nkj->nij", G, G)
    W = crlb_weight_matrix(sc.R)
    sand = []
    for o in orders:
        H = np.cumsum(A[o], axis=0)[5:]
        S = np.cumsum(A[o] * scene.sigma[o, None, None] ** 2, axis=0)[5:]
        Hi = np.linalg.inv(H)
        sand.append(np.einsum("ij,nij->n", W, Hi @ S @ Hi))
    return np.arange(6, n + 1), exact, np.array(sand)


# ---------------------------------------------------------------- beyond: efficiency

def _ml_trial(rng: np.random.Generator, points: np.ndarray, sigma: np.ndarray,
              scenario: Scenario, linear_start: bool) -> np.ndarray:
    u0 = project_points(points, scenario.R, scenario.t, scenario.K)
    u = u0 + rng.normal(size=u0.shape) * sigma[:, None]
    out = []
    for w in (sigma, None):   # ML (weighted) and unweighted least squares, from the truth
        R, t = refine_pose(points, u, scenario.K, scenario.R, scenario.t, sigma_px=w)
        out.append(np.concatenate([t - scenario.t,
                                   Rotation.from_matrix(R @ scenario.R.T).as_rotvec()]))
    if linear_start:
        Rd, td = best_initial_pose(points, u, scenario.K)  # ML from a linear start (global)
        R, t = refine_pose(points, u, scenario.K, Rd, td, sigma_px=sigma)
        out.append(np.concatenate([t - scenario.t, Rotation.from_matrix(R @ scenario.R.T)
                                   .as_rotvec()]))
    return np.array(out)


def ml_pose_samples(n_mc: int, *, scenario: Scenario | None = None, seed: int = 7,
                    n_points: int = 40, runner: TrialRunner | None = None
                    ) -> tuple[np.ndarray, np.ndarray, Any]:
    """Monte Carlo errors ``(δt, δθ)`` of the ML pose of one fixed gross-error-free geometry.

    Returns
    -------
    errors, crlb, scene
        (n_mc, 6) ML errors (m, rad) started at the truth, the 6×6 CRLB, and the geometry.
    """
    sc = scenario or Scenario()
    geo = make_scene(np.random.default_rng(seed), sc, outlier_fraction=0.0,
                     n_points=check_int(n_points, "n_points", min_value=6))
    res = run_trials(_ml_trial, check_int(n_mc, "n_mc", min_value=2), seed=seed,
                     args=(geo.points, geo.sigma, sc, False),
                     runner=runner or TrialRunner(progress=False), desc="ML samples")
    errs = np.array(res)[:, 0]
    return errs, pose_crlb(geo.points, sc.R, sc.t, sc.K, geo.sigma), geo


def efficiency_experiment(noise_units_mm: tuple[float, ...] = (1.0, 0.01), n_mc: int = 200,
                          *, scenario: Scenario | None = None, runner: TrialRunner | None = None,
                          seed: int = 7) -> pd.DataFrame:
    """Monte Carlo RMS error of the ML / unweighted / linear-started ML pose versus the CRLB.

    One fixed geometry (the paper's scene, gross errors removed); ``n_mc`` noise draws per
    noise unit. Returns one row per (noise unit, estimator) with the RMS of the position and
    attitude errors, the CRLB's, and their ratio (efficiency ≈ 1 means the bound is attained).
    """
    sc0 = scenario or Scenario()
    rows = []
    geo = make_scene(np.random.default_rng(seed), sc0, outlier_fraction=0.0)
    for unit in noise_units_mm:
        sc = replace(sc0, noise_unit_mm=check_positive(float(unit), "noise_units_mm"))
        sigma = geo.sigma / sc0.noise_unit_mm * unit
        C = pose_crlb(geo.points, sc.R, sc.t, sc.K, sigma)
        G = projection_jacobian(geo.points, sc.R, sc.t, sc.K)
        H = np.einsum("nki,nkj->ij", G, G)
        Sg = np.einsum("nki,nkj->ij", G * sigma[:, None, None], G * sigma[:, None, None])
        Cu = np.linalg.solve(H, np.linalg.solve(H, Sg).T)
        res = np.array(run_trials(_ml_trial, n_mc, seed=seed,
                                  args=(geo.points, sigma, sc, True), runner=runner,
                                  desc="efficiency"))
        for k, name in enumerate(("ML (from truth)", "unweighted LS (from truth)",
                                  "ML (from DLT/IPPE)")):
            e = res[:, k]
            rows.append({"noise unit (mm)": unit, "estimator": name,
                         "pos RMS (m)": float(np.sqrt(np.mean(np.sum(e[:, :3] ** 2, axis=1)))),
                         "CRLB pos (m)": float(np.sqrt(np.trace(C[:3, :3]))),
                         "att RMS (deg)": float(np.degrees(np.sqrt(np.mean(
                             np.sum(e[:, 3:] ** 2, axis=1))))),
                         "CRLB att (deg)": float(np.degrees(np.sqrt(np.trace(C[3:, 3:])))),
                         "LS bound pos (m)": float(np.sqrt(np.trace(Cu[:3, :3]))),
                         "LS bound att (deg)": float(np.degrees(np.sqrt(np.trace(Cu[3:, 3:]))))})
    df = pd.DataFrame(rows)
    df["pos RMS / CRLB"] = df["pos RMS (m)"] / df["CRLB pos (m)"]
    df["att RMS / CRLB"] = df["att RMS (deg)"] / df["CRLB att (deg)"]
    return df


# ---------------------------------------------------------------- beyond: budgeted selection

def _budget_trial(rng: np.random.Generator, scenario: Scenario, ks: tuple[int, ...]) -> list:
    scene = make_scene(rng, scenario, outlier_fraction=0.0)
    X, u, sig = scene.points, scene.pixels, scene.sigma
    R0, t0 = refine_pose(X, u, scene.K, *best_initial_pose(X, u, scene.K), sigma_px=sig)
    rows = []
    for k in ks:
        k = min(k, len(X))
        for method in ("D-optimal", "A-optimal", "random"):
            t_sel = time.perf_counter()
            if method == "random":
                idx = rng.choice(len(X), size=k, replace=False)
            else:
                idx = greedy_design(X, R0, t0, scene.K, k, sig, criterion=method[0])
            t_sel = time.perf_counter() - t_sel
            Rk, tk = refine_pose(X[idx], u[idx], scene.K, R0, t0, sigma_px=sig[idx])
            pos, att = pose_errors(Rk, tk, scene)
            rows.append((k, method, pos, att, t_sel))
    return rows


def budget_experiment(ks: tuple[int, ...] = (8, 12, 20, 30, 50, 80, 120, 160), n_runs: int = 30,
                      *, scenario: Scenario | None = None, runner: TrialRunner | None = None,
                      seed: int = 11, noise_unit_mm: float = 0.01) -> pd.DataFrame:
    """Best-k points by greedy D-/A-optimal design vs random k: accuracy and selection time.

    Gross errors are absent (the selection is applied after RANSAC); the design uses the ML
    pose of all points and the known σ_i; the pose from the k points is the weighted LM started
    from that all-point pose (a local analysis: no flips). ``noise_unit_mm`` defaults to the
    pixel reading (0.01 mm), where the linearised CRLB describes the errors.
    """
    sc = replace(scenario or Scenario(), noise_unit_mm=check_positive(noise_unit_mm,
                                                                       "noise_unit_mm"))
    res = run_trials(_budget_trial, check_int(n_runs, "n_runs", min_value=1), seed=seed,
                     args=(sc, tuple(ks)), runner=runner, desc="budget")
    df = pd.DataFrame([r for trial in res for r in trial],
                      columns=["k", "method", "pos", "att", "time_s"])
    return (df.groupby(["k", "method"]).agg(pos_median_m=("pos", "median"),
                                            att_median_deg=("att", "median"),
                                            select_ms=("time_s", lambda s: 1e3 * s.median()))
            .reset_index())
