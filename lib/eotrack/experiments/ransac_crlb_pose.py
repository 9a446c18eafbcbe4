"""Ning, Zhang & Zhang 2016 — RANSAC + CRLB feature selection for non-cooperative spacecraft pose.

The paper's simulation (§3): the target's centre of mass at ``[1, 1.2, 10]`` m in the camera
frame, attitude angles ``[15°, 20°, 10°]``, focal length 0.01 m; 160–180 feature points on a
plane 1 m from the target; 90 % of the points carry image noise of variance 0.02 or 0.1 (mm², as
printed), 10 % variance 3 mm² (gross errors). RANSAC (6-point DLT) removes gross errors, then the
CRLB selection (§2.4) chooses a subset of the inliers; the pose is re-estimated from the subset.

Everything the paper leaves unstated is a field of :class:`Scenario` or :class:`Settings`
(Euler sequence, plane size and placement, inlier threshold, acceptance ratio, the solver used
after selection, the reading of the selection rule).
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass, replace
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from scipy import stats
from scipy.spatial.transform import Rotation

from eotrack.montecarlo import TrialRunner, run_trials
from eotrack.plotting import get_ax
from eotrack.pose import (
    RansacConfig,
    attitude_matrix,
    best_initial_pose,
    crlb_weight_matrix,
    greedy_design,
    information_monotonicity,
    intrinsic_matrix,
    pose_crlb,
    project_points,
    projection_jacobian,
    ransac_pose_dlt,
    refine_pose,
    rotation_error_deg,
    select_features_crlb,
)
from eotrack.repro import ClaimResult, Reproduction, Status, load_claims
from eotrack.validation import check_choice, check_generator, check_int, check_positive

__all__ = [
    "READINGS",
    "SLUG",
    "TITLE",
    "Scenario",
    "Settings",
    "best_subset_gain",
    "budget_experiment",
    "efficiency_experiment",
    "error_summary",
    "explore",
    "make_scene",
    "monotonicity_curves",
    "plot_budget",
    "plot_efficiency",
    "plot_error_runs",
    "plot_monotonicity",
    "plot_selected_counts",
    "readings_table",
    "reproduce",
    "run_pose_experiment",
    "run_trial",
]

SLUG = "ransac_crlb_pose"
TITLE = ("Ning M., Zhang S., Zhang H. Robust visual navigation of non-cooperative spacecraft with "
         "active feature selection. Aerospace Shanghai 33(6):136-141, 2016. "
         "DOI 10.19328/j.cnki.1006-1630.2016.06.020")

#: Readings of the §2.4 rule: name → (score rule, start test); see eotrack.pose.selection.
READINGS: dict[str, tuple[str, str]] = {
    "as printed": ("exact", "paper"),
    "exact": ("exact", "per_point"),
    "pooled": ("pooled", "per_point"),
    "sandwich": ("sandwich", "per_point"),
    "tolerance": ("tolerance", "per_point"),
}


@dataclass(frozen=True)
class Scenario:
    """The simulated scene (§3). Defaults are the paper's settings; adopted values say so.

    Attributes
    ----------
    position_m
        Target centre of mass in the camera frame (paper).
    attitude_deg, euler_seq
        Attitude angles (paper) and their sequence (adopted: extrinsic x-y-z).
    focal_m
        Focal length (paper); image coordinates are in mm on the focal plane.
    plane_side_m
        Side of the square feature plane; the paper prints "22 m²", read as 2 m × 2 m.
    plane_offset_m
        The plane is ``Z_t = −plane_offset_m`` in the target frame (faces the camera; paper:
        "1 m from the target").
    n_points
        Inclusive range of the number of features per run (paper: 160–180).
    inlier_variances
        Per-axis noise variances of the well-matched 90 % (paper: 0.02 or 0.1, chosen at random).
    outlier_variance, outlier_fraction
        Variance of the 10 % gross errors (paper: 3).
    noise_unit_mm
        Length (mm) of the unit the variances are printed in: 1.0 = mm² as printed; 0.01 =
        px² for a 10 µm pixel (the "pixel reading", see the notebook's errata).
    """

    position_m: tuple[float, float, float] = (1.0, 1.2, 10.0)
    attitude_deg: tuple[float, float, float] = (15.0, 20.0, 10.0)
    euler_seq: str = "xyz"
    focal_m: float = 0.01
    plane_side_m: float = 2.0
    plane_offset_m: float = 1.0
    n_points: tuple[int, int] = (160, 180)
    inlier_variances: tuple[float, float] = (0.02, 0.1)
    outlier_variance: float = 3.0
    outlier_fraction: float = 0.1
    noise_unit_mm: float = 1.0

    @property
    def R(self) -> np.ndarray:
        """True rotation target → camera."""
        return attitude_matrix(self.attitude_deg, self.euler_seq)

    @property
    def t(self) -> np.ndarray:
        """True translation (m)."""
        return np.asarray(self.position_m, float)

    @property
    def K(self) -> np.ndarray:
        """Intrinsics with image coordinates in mm (``f`` in mm, principal point at 0)."""
        return intrinsic_matrix(self.focal_m * 1e3)

    def sigma_mm(self, variance: Any) -> np.ndarray:
        """Noise standard deviation (image mm) of a printed variance."""
        return np.sqrt(np.asarray(variance, float)) * self.noise_unit_mm


@dataclass(frozen=True)
class Settings:
    """Experiment settings (trial counts, RANSAC, selection reading)."""

    n_runs: int = 300            # Figs. 4–5 (paper)
    n_runs_counts: int = 80      # Fig. 6 (paper)
    reading: str = "sandwich"    # headline reading of the §2.4 rule (the one that reproduces)
    inlier_chi2: float = 0.99    # inlier threshold = χ²₂ quantile × largest inlier variance
    min_inlier_ratio: float = 0.6
    max_draws: int = 500         # RANSAC's preset number of draws (unstated)
    crlb_max_draws: int = 50     # CRLB start draws before falling back to all inliers
    tolerance: float = 0.01      # relative decrease required under the "tolerance" reading
    n_mc_efficiency: int = 200   # Monte Carlo draws per noise level (beyond the paper)
    n_runs_budget: int = 30      # scenes for the budgeted-selection study (beyond the paper)
    seed: int = 20161110
    readings: tuple[str, ...] = ("as printed", "pooled", "sandwich", "tolerance")

    def ransac_config(self, scenario: Scenario) -> RansacConfig:
        """RANSAC settings for ``scenario`` (threshold scales with the noise unit)."""
        thr = float(np.sqrt(stats.chi2.ppf(self.inlier_chi2, 2)
                            * max(scenario.inlier_variances)) * scenario.noise_unit_mm)
        return RansacConfig(inlier_threshold_px=thr, min_inlier_ratio=self.min_inlier_ratio,
                            max_draws=self.max_draws)


@dataclass(frozen=True)
class Scene:
    """One simulated image: model points, noisy image points and the truth."""

    points: np.ndarray
    pixels: np.ndarray
    sigma: np.ndarray
    gross: np.ndarray
    R: np.ndarray
    t: np.ndarray
    K: np.ndarray


def make_scene(rng: np.random.Generator, scenario: Scenario | None = None, *,
               n_points: int | None = None, outlier_fraction: float | None = None) -> Scene:
    """Simulate one image of the paper's scene (§3).

    Parameters
    ----------
    rng
        Generator.
    scenario
        :class:`Scenario` (paper defaults).
    n_points, outlier_fraction
        Override the number of points / the gross-error fraction.
    """
    rng = check_generator(rng)
    sc = scenario or Scenario()
    lo, hi = sc.n_points
    n = int(rng.integers(lo, hi + 1)) if n_points is None else check_int(n_points, "n_points",
                                                                             min_value=6)
    frac = sc.outlier_fraction if outlier_fraction is None else float(outlier_fraction)
    if not 0.0 <= frac < 1.0:
        raise ValueError(f"outlier_fraction must lie in [0, 1), got {frac}")
    half = sc.plane_side_m / 2
    X = np.column_stack([rng.uniform(-half, half, (n, 2)), np.full(n, -sc.plane_offset_m)])
    var = np.asarray(sc.inlier_variances, float)[rng.integers(0, len(sc.inlier_variances), n)]
    gross = np.zeros(n, bool)
    gross[rng.permutation(n)[:round(frac * n)]] = True
    var[gross] = sc.outlier_variance
    sigma = sc.sigma_mm(var)
    u = project_points(X, sc.R, sc.t, sc.K) + rng.normal(size=(n, 2)) * sigma[:, None]
    return Scene(X, u, sigma, gross, sc.R, sc.t, sc.K)


def _errors(R: np.ndarray, t: np.ndarray, scene: Scene) -> tuple[float, float]:
    return float(np.linalg.norm(t - scene.t)), rotation_error_deg(R, scene.R)


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
    out["pos_ransac"], out["att_ransac"] = _errors(res.R, res.t, scene)
    Rm, tm = refine_pose(X, u, scene.K, res.R, res.t, sigma_px=sig)
    out["pos_ml"], out["att_ml"] = _errors(Rm, tm, scene)
    resid = u - project_points(X, res.R, res.t, scene.K)
    # one independent stream per reading, so a reading's result does not depend on which
    # other readings are computed in the same run
    sel_seed = int(rng.integers(2**62))
    for name in settings.readings:
        rule, start = READINGS[name]
        rng_sel = np.random.default_rng([sel_seed, list(READINGS).index(name)])
        sel = select_features_crlb(X, res.R, res.t, scene.K, rng_sel, rule=rule, start=start,
                                   sigma_px=sig, residuals=resid,
                                   max_draws=settings.crlb_max_draws, tol=settings.tolerance)
        S = sel.selected
        Rs, ts = (res.R, res.t) if S.all() else refine_pose(X[S], u[S], scene.K, res.R, res.t)
        out[f"pos_{name}"], out[f"att_{name}"] = _errors(Rs, ts, scene)
        out[f"n_{name}"] = sel.n_selected
        out[f"fallback_{name}"] = sel.fallback
    return out


def run_pose_experiment(n_runs: int, *, scenario: Scenario | None = None,
                        settings: Settings | None = None, runner: TrialRunner | None = None,
                        seed: int | None = None, n_points: int | None = None,
                        outlier_fraction: float | None = None) -> pd.DataFrame:
    """``n_runs`` seeded runs of :func:`run_trial` as a DataFrame (one row per run)."""
    sc = scenario or Scenario()
    st = settings or Settings()
    n_runs = check_int(n_runs, "n_runs", min_value=1)
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


def readings_table(df: pd.DataFrame) -> pd.DataFrame:
    """Per reading: kept fraction and paired comparison with RANSAC alone (win rate, p-values)."""
    ok = df[df["success"]]
    rows = []
    for name in READINGS:
        if f"pos_{name}" not in ok:
            continue
        row = {"reading": name, "rule": READINGS[name][0], "start": READINGS[name][1],
               "kept / inliers": (ok[f"n_{name}"] / ok["n_inliers"]).mean()}
        for q in ("pos", "att"):
            a, b = ok[f"{q}_{name}"].to_numpy(), ok[f"{q}_ransac"].to_numpy()
            row[f"{q} mean ratio"] = a.mean() / b.mean()
            row[f"{q} win rate"] = float(np.mean(a < b))
            row[f"{q} p (Wilcoxon)"] = _wilcoxon_less(a, b)
        rows.append(row)
    return pd.DataFrame(rows).set_index("reading")


def _wilcoxon_less(a: np.ndarray, b: np.ndarray) -> float:
    d = a - b
    if np.all(d == 0):
        return 1.0
    return float(stats.wilcoxon(a, b, alternative="less").pvalue)


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


def plot_monotonicity(sizes: np.ndarray, scores: np.ndarray, sandwich: np.ndarray | None = None,
                      ax=None):
    """Weighted CRLB sum (and optionally the sandwich score) versus the number of points."""
    ax = get_ax(ax)
    for k, s in enumerate(scores):
        line = ax.semilogy(sizes, s, lw=1, label="exact CRLB" if k == 0 else None)[0]
        if sandwich is not None:
            ax.semilogy(sizes, sandwich[k], lw=0.8, ls=":", color=line.get_color(),
                        label="unweighted-LS covariance ('sandwich')" if k == 0 else None)
    ax.set_xlabel("number of points in the set (random order)")
    ax.set_ylabel("weighted sum of the 7 variances")
    ax.set_title("Exact CRLB never rises when a point is added")
    ax.legend()
    return ax


# ---------------------------------------------------------------- figures 4–6

def plot_error_runs(df: pd.DataFrame, quantity: str = "pos", reading: str = "sandwich", ax=None):
    """Figs. 4/5: per-run error of RANSAC alone and of RANSAC + CRLB (``reading``)."""
    check_choice(quantity, "quantity", ["pos", "att"])
    ax = get_ax(ax, figsize=(8, 3.6))
    ok = df[df["success"]]
    runs = np.arange(1, len(ok) + 1)
    ax.plot(runs, ok[f"{quantity}_ransac"], lw=0.8, label="RANSAC only")
    ax.plot(runs, ok[f"{quantity}_{reading}"], lw=0.8,
            label=f"RANSAC + CRLB ({reading} reading)")
    ax.set_yscale("log")
    ax.set_xlabel("run")
    ax.set_ylabel("position error |t̂ − t| (m)" if quantity == "pos"
                  else "attitude error (deg)")
    fig_no = "Fig. 4" if quantity == "pos" else "Fig. 5"
    a, b = ok[f"{quantity}_{reading}"].mean(), ok[f"{quantity}_ransac"].mean()
    ax.set_title(f"{fig_no} — {'position' if quantity == 'pos' else 'attitude'} error, "
                 f"{len(ok)} runs (mean {a:.3g} vs {b:.3g})")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.18), ncol=2)
    return ax


def plot_selected_counts(df: pd.DataFrame, reading: str = "sandwich",
                         paper_fraction: float = 2 / 3, ax=None):
    """Fig. 6: number of RANSAC inliers and of CRLB-selected points per run."""
    ax = get_ax(ax, figsize=(8, 3.6))
    ok = df[df["success"]]
    runs = np.arange(1, len(ok) + 1)
    ax.plot(runs, ok["n_inliers"], "o-", ms=3, lw=0.8, label="RANSAC inliers")
    ax.plot(runs, ok[f"n_{reading}"], "s-", ms=3, lw=0.8, label=f"CRLB selected ({reading})")
    ax.plot(runs, paper_fraction * ok["n_inliers"], "k--", lw=0.8,
            label=f"paper: ≈ {paper_fraction:.2f} × inliers")
    ax.set_xlabel("run")
    ax.set_ylabel("number of feature points")
    frac = (ok[f"n_{reading}"] / ok["n_inliers"]).mean()
    ax.set_title(f"Fig. 6 — points selected over {len(ok)} runs (ours: {frac:.2f} of inliers)")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.18), ncol=3)
    return ax


# ---------------------------------------------------------------- beyond: efficiency

def _efficiency_trial(rng: np.random.Generator, points: np.ndarray, sigma: np.ndarray,
                      scenario: Scenario) -> np.ndarray:
    u0 = project_points(points, scenario.R, scenario.t, scenario.K)
    u = u0 + rng.normal(size=u0.shape) * sigma[:, None]
    out = []
    for w in (sigma, None):   # ML (weighted) and unweighted least squares, from the truth
        R, t = refine_pose(points, u, scenario.K, scenario.R, scenario.t, sigma_px=w)
        dth = Rotation.from_matrix(R @ scenario.R.T).as_rotvec()
        out.append(np.concatenate([t - scenario.t, dth]))
    Rd, td = best_initial_pose(points, u, scenario.K)  # ML from a linear start (global)
    R, t = refine_pose(points, u, scenario.K, Rd, td, sigma_px=sigma)
    out.append(np.concatenate([t - scenario.t, Rotation.from_matrix(R @ scenario.R.T)
                               .as_rotvec()]))
    return np.array(out)


def efficiency_experiment(noise_units_mm: tuple[float, ...] = (1.0, 0.01), n_mc: int = 200,
                          *, scenario: Scenario | None = None, runner: TrialRunner | None = None,
                          seed: int = 7) -> pd.DataFrame:
    """Monte Carlo RMS error of the ML / unweighted / DLT-started ML pose versus the CRLB.

    One fixed geometry (the paper's scene, gross errors removed); ``n_mc`` noise draws per
    noise unit. Returns one row per (noise unit, estimator) with the RMS of the position and
    attitude errors, the CRLB's, and their ratio (efficiency ≈ 1 means the bound is attained).
    """
    sc0 = scenario or Scenario()
    rows = []
    geo = make_scene(np.random.default_rng(seed), sc0, outlier_fraction=0.0)
    for unit in noise_units_mm:
        sc = replace(sc0, noise_unit_mm=float(unit))
        sigma = geo.sigma / sc0.noise_unit_mm * unit
        C = pose_crlb(geo.points, sc.R, sc.t, sc.K, sigma)
        # unweighted LS covariance (sandwich) for the unweighted estimator's own bound
        G = projection_jacobian(geo.points, sc.R, sc.t, sc.K)
        H = np.einsum("nki,nkj->ij", G, G)
        Sg = np.einsum("nki,nkj->ij", G * sigma[:, None, None], G * sigma[:, None, None])
        Cu = np.linalg.solve(H, np.linalg.solve(H, Sg).T)
        res = np.array(run_trials(_efficiency_trial, n_mc, seed=seed, args=(geo.points, sigma, sc),
                                  runner=runner, desc="efficiency"))
        for k, name in enumerate(("ML (from truth)", "unweighted LS (from truth)",
                                  "ML (from DLT/IPPE)")):
            e = res[:, k]
            pos_rms = float(np.sqrt(np.mean(np.sum(e[:, :3] ** 2, axis=1))))
            att_rms = float(np.degrees(np.sqrt(np.mean(np.sum(e[:, 3:] ** 2, axis=1)))))
            rows.append({"noise unit (mm)": unit, "estimator": name,
                         "pos RMS (m)": pos_rms,
                         "CRLB pos (m)": float(np.sqrt(np.trace(C[:3, :3]))),
                         "att RMS (deg)": att_rms,
                         "CRLB att (deg)": float(np.degrees(np.sqrt(np.trace(C[3:, 3:])))),
                         "LS bound pos (m)": float(np.sqrt(np.trace(Cu[:3, :3]))),
                         "LS bound att (deg)": float(np.degrees(np.sqrt(np.trace(Cu[3:, 3:]))))})
    df = pd.DataFrame(rows)
    df["pos RMS / CRLB"] = df["pos RMS (m)"] / df["CRLB pos (m)"]
    df["att RMS / CRLB"] = df["att RMS (deg)"] / df["CRLB att (deg)"]
    return df


def plot_efficiency(df: pd.DataFrame, ax=None):
    """RMS error / CRLB for each estimator versus the noise unit."""
    ax = get_ax(ax)
    for j, (name, g) in enumerate(df.groupby("estimator", sort=False)):
        x = g["noise unit (mm)"].to_numpy() * 1.08 ** (j - 1)  # small offsets: no overlap
        line = ax.loglog(x, g["att RMS / CRLB"], "o-", label=f"{name}: attitude")[0]
        ax.loglog(x, g["pos RMS / CRLB"], "s--", color=line.get_color(),
                  label=f"{name}: position")
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_xlabel("noise unit (mm): 1 = variances in mm² as printed, 0.01 = px² (10 µm pixel)")
    ax.set_ylabel("RMS error / √CRLB")
    ax.legend(fontsize=7)
    ax.set_title("Estimator efficiency")
    return ax


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
            pos, att = _errors(Rk, tk, scene)
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


def plot_budget(df: pd.DataFrame, ax=None):
    """Median attitude error versus k for greedy D/A-optimal and random subsets."""
    ax = get_ax(ax)
    for method, g in df.groupby("method"):
        ax.loglog(g["k"], g["att_median_deg"], "o-", label=method)
    ax.set_xlabel("number of points k")
    ax.set_ylabel("median attitude error (deg)")
    ax.set_title("Budgeted selection: best k points vs random k (pixel reading)")
    ax.legend()
    return ax


# ---------------------------------------------------------------- claims and reproduce()

def best_subset_gain(scenario: Scenario | None = None) -> float:
    """RMS ratio (best subset / all inliers) of an unweighted solver, equal geometry assumed.

    Unweighted least squares on N points with variances σ_i² has variance ∝ mean(σ²)/N; keeping
    only the lowest-variance class (a fraction 1/len(classes)) gives ∝ σ²_min/(N/len).
    """
    v = np.asarray((scenario or Scenario()).inlier_variances, float)
    return float(np.sqrt(len(v) * v.min() / v.mean()))


def _compare_claim(claim, ok: pd.DataFrame, q: str, reading: str) -> ClaimResult:
    a, b = ok[f"{q}_{reading}"].to_numpy(), ok[f"{q}_ransac"].to_numpy()
    p = _wilcoxon_less(a, b)
    unit = "m" if q == "pos" else "deg"
    win = float(np.mean(a < b))
    boot = np.random.default_rng(0).integers(0, len(a), (2000, len(a)))
    lo, hi = np.percentile(a[boot].mean(1) / b[boot].mean(1), [2.5, 97.5])
    ours = (f"{len(ok)} runs, {reading} reading: mean {a.mean():.3g} vs {b.mean():.3g} {unit} "
            f"(ratio {a.mean() / b.mean():.2f}, 95 % CI {lo:.2f}–{hi:.2f}), median "
            f"{np.median(a):.3g} vs "
            f"{np.median(b):.3g}; CRLB better in {100 * win:.0f} % of runs, Wilcoxon p = {p:.2g}")
    if a.mean() < b.mean() and p < 0.05:
        status, note = Status.REPRODUCED, (
            "The rule as printed (exact CRLB) selects every inlier (Fisher information is "
            f"additive), so it cannot change the error; the effect comes from the '{reading}' "
            "reading (score = covariance of the unweighted pose with each point's noise "
            "variance, which the simulation knows). Weighting the points instead (ML pose) "
            "is more accurate than any selection.")
    elif a.mean() < b.mean() or p < 0.05:
        status, note = Status.PARTIAL, (
            f"Improvement is not both in the mean and significant (mean ratio "
            f"{a.mean() / b.mean():.2f}, p = {p:.2g}); the paper gives no numbers, only "
            f"'clearly improved'. With an unweighted solver the best possible subset (the "
            f"low-noise points) gains at most ≈{100 * (1 - best_subset_gain()):.0f} % in RMS "
            "here, and the planar pose ambiguity adds run-to-run scatter at the printed noise "
            "level.")
    else:
        status, note = Status.NOT_REPRODUCED, (
            f"CRLB-selected mean {a.mean():.3g} ≥ RANSAC {b.mean():.3g} {unit} (p = {p:.2g}).")
    return ClaimResult.from_claim(claim, ours=ours, status=status, note=note)


def evaluate(claims: dict, df: pd.DataFrame, df_counts: pd.DataFrame,
             reading: str) -> list[ClaimResult]:
    """One ClaimResult per claim id, decided by the computed numbers."""
    ok = df[df["success"]]
    rows = [_compare_claim(claims["ransac_crlb_pose.fig4"], ok, "pos", reading),
            _compare_claim(claims["ransac_crlb_pose.fig5"], ok, "att", reading)]
    c6 = claims["ransac_crlb_pose.fig6"]
    okc = df_counts[df_counts["success"]]
    frac = (okc[f"n_{reading}"] / okc["n_inliers"]).to_numpy()
    n_fb = int(okc[f"fallback_{reading}"].sum())
    lo, hi = c6.paper["fraction_range"]
    in_range = lo <= frac.mean() <= hi
    ours = (f"{len(okc)} runs, {reading} reading: selected / inliers = {frac.mean():.2f} "
            f"(min {frac.min():.2f}, max {frac.max():.2f}); ≥ 95 % of the inliers kept in "
            f"{int(np.sum(frac >= 0.95))} run(s); fell back to all inliers in {n_fb} run(s); "
            f"as printed (exact CRLB): {(okc['n_as printed'] / okc['n_inliers']).mean():.2f}")
    if in_range and n_fb > 0:
        status, note = Status.REPRODUCED, ""
    elif in_range:
        status, note = Status.PARTIAL, (
            f"The fraction {frac.mean():.2f} is about two thirds, but no run fell back to all "
            f"inliers (the paper saw some): with the per-point start test a 6-point start that "
            f"beats the all-inlier score is found within {Settings().crlb_max_draws} draws "
            f"every time (though {int(np.sum(frac >= 0.95))} run(s) kept ≥ 95 % of the "
            "inliers, close to the paper's 'equal counts'). The rule as printed falls back in "
            "every run.")
    else:
        status, note = Status.NOT_REPRODUCED, (
            f"Selected fraction {frac.mean():.2f} outside [{lo}, {hi}].")
    rows.append(ClaimResult.from_claim(c6, ours=ours, status=status, note=note))
    return rows


def reproduce(*, quick: bool = False, runner: TrialRunner | None = None,
              scenario: Scenario | None = None,
              settings: Settings | None = None) -> Reproduction:
    """Run Figs. 4–6 (300 / 80 runs; quick: 60 / 30) and the beyond-the-paper studies."""
    sc = scenario or Scenario()
    st = settings or Settings()
    claims = load_claims(SLUG)
    n45 = 60 if quick else st.n_runs
    n6 = 30 if quick else st.n_runs_counts
    t0 = time.perf_counter()
    df = run_pose_experiment(n45, scenario=sc, settings=st, runner=runner)
    st6 = replace(st, readings=tuple(dict.fromkeys(("as printed", "exact", st.reading))))
    df6 = run_pose_experiment(n6, scenario=sc, settings=st6, runner=runner, seed=st.seed + 1)
    t1 = time.perf_counter()
    eff = efficiency_experiment(n_mc=40 if quick else st.n_mc_efficiency, scenario=sc,
                                runner=runner)
    bud = budget_experiment(n_runs=6 if quick else st.n_runs_budget, scenario=sc, runner=runner)
    t_beyond = time.perf_counter() - t1
    sizes, scores, sandwich = monotonicity_curves(np.random.default_rng(st.seed), sc)
    rows = evaluate(claims, df, df6, st.reading)
    figs = {}
    for q, name in (("pos", "fig4_position_error"), ("att", "fig5_attitude_error")):
        fig, ax = plt.subplots(figsize=(8, 3.6))
        plot_error_runs(df, q, st.reading, ax=ax)
        figs[name] = fig
    fig, ax = plt.subplots(figsize=(8, 3.6))
    plot_selected_counts(df6, st.reading,
                         claims["ransac_crlb_pose.fig6"].paper["selected_fraction"], ax=ax)
    figs["fig6_selected_points"] = fig
    fig, ax = plt.subplots()
    plot_monotonicity(sizes, scores, sandwich, ax=ax)
    figs["monotonicity"] = fig
    fig, ax = plt.subplots()
    plot_efficiency(eff, ax=ax)
    figs["beyond_efficiency"] = fig
    fig, ax = plt.subplots()
    plot_budget(bud, ax=ax)
    figs["beyond_budget"] = fig
    tables = {
        "Figs. 4–5 — errors per method (ours; the paper gives no numbers)": error_summary(df),
        "Readings of the §2.4 rule versus RANSAC alone (paired over the runs)":
            readings_table(df),
        "Fig. 6 — points per method (80-run set)": error_summary(df6),
        "Beyond — estimator efficiency (RMS / √CRLB)": eff,
        "Beyond — budgeted selection (median errors, selection time)": bud,
    }
    text = (
        "## Setup\n\n"
        f"Scene: t = {sc.position_m} m, attitude {sc.attitude_deg}° ({sc.euler_seq}), "
        f"f = {sc.focal_m} m, {sc.n_points[0]}–{sc.n_points[1]} points on a "
        f"{sc.plane_side_m:g} m × {sc.plane_side_m:g} m plane at Z_t = −{sc.plane_offset_m:g} m; "
        f"noise variances {sc.inlier_variances} / {sc.outlier_variance} in units of "
        f"({sc.noise_unit_mm:g} mm)². RANSAC: 6-point DLT, threshold "
        f"{st.ransac_config(sc).inlier_threshold_px:.3g} mm, accept ≥ {st.min_inlier_ratio:g} "
        "inliers, refit. Pose after selection: unweighted Levenberg–Marquardt. Headline reading "
        f"of §2.4: '{st.reading}'.")
    timing = {"time_total_s": round(time.perf_counter() - t0, 1),
              "time_beyond_s": round(t_beyond, 1)}
    data = {"runs": df, "counts": df6, "efficiency": eff, "budget": bud,
            "monotonicity": (sizes, scores, sandwich), "scenario": sc, "settings": st}
    return Reproduction(slug=SLUG, title=TITLE, claims=rows, tables=tables, figures=figs,
                        text=text, data=data, settings={**asdict(sc), **asdict(st), "quick": quick,
                                             "runs_fig45": n45, "runs_fig6": n6, **timing})


def _explore_trial(rng: np.random.Generator, scenario: Scenario, settings: Settings,
                   n_points: int, outlier_fraction: float, k: int) -> dict:
    out = run_trial(rng, scenario, settings, n_points, outlier_fraction)
    if not out["success"]:
        return out
    scene = make_scene(rng, scenario, n_points=n_points, outlier_fraction=0.0)
    X, u, sig = scene.points, scene.pixels, scene.sigma
    R0, t0 = refine_pose(X, u, scene.K, *best_initial_pose(X, u, scene.K), sigma_px=sig)
    kk = min(k, len(X))
    for name, idx in (("best k", greedy_design(X, R0, t0, scene.K, kk, sig)),
                      ("random k", rng.choice(len(X), size=kk, replace=False))):
        Rk, tk = refine_pose(X[idx], u[idx], scene.K, R0, t0, sigma_px=sig[idx])
        out[f"pos_{name}"], out[f"att_{name}"] = _errors(Rk, tk, scene)
    return out


def explore(*, low_variance: float = 0.02, high_variance: float = 0.1,
            outlier_variance: float = 3.0, outlier_fraction: float = 0.1, n_points: int = 170,
            reading: str = "sandwich", noise_unit_mm: float = 1.0, k: int = 20,
            n_runs: int = 20, seed: int = 3, runner: TrialRunner | None = None):
    """Widget panel: attitude errors and points kept for ``n_runs`` runs of changed settings.

    Returns the figure (two axes: attitude error per method, points kept per method).
    """
    check_choice(reading, "reading", list(READINGS))
    for name, v in (("low_variance", low_variance), ("high_variance", high_variance),
                    ("outlier_variance", outlier_variance), ("noise_unit_mm", noise_unit_mm)):
        check_positive(v, name)
    sc = replace(Scenario(), inlier_variances=(low_variance, high_variance),
                 outlier_variance=outlier_variance, noise_unit_mm=noise_unit_mm)
    st = replace(Settings(), readings=("as printed", reading))
    rows = run_trials(_explore_trial, check_int(n_runs, "n_runs", min_value=1), seed=seed,
                      args=(sc, st, check_int(n_points, "n_points", min_value=12),
                            float(outlier_fraction), check_int(k, "k", min_value=6)),
                      runner=runner or TrialRunner(progress=False))
    df = pd.DataFrame(rows)
    ok = df[df["success"]]
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 3.6), width_ratios=[2, 1])
    if ok.empty:
        a1.text(0.5, 0.5, f"RANSAC failed in all {len(df)} runs: every image discarded",
                ha="center", va="center", transform=a1.transAxes)
        a2.set_axis_off()
        return fig
    methods = ["ransac", reading, "ml", "best k", "random k"]
    labels = ["RANSAC", f"+CRLB\n({reading})", "ML\n(weighted)", f"best {k}\n(D-opt.)",
              f"random {k}"]
    a1.boxplot([ok[f"att_{m}"] for m in methods], tick_labels=labels)
    a1.set_yscale("log")
    a1.set_ylabel("attitude error (deg)")
    a1.set_title(f"{len(ok)}/{len(df)} runs succeeded (RANSAC failures are discarded images)")
    a2.bar(["inliers", reading], [ok["n_inliers"].mean(), ok[f"n_{reading}"].mean()])
    a2.set_ylabel("points used (mean)")
    a2.set_title(f"kept {np.mean(ok[f'n_{reading}'] / ok['n_inliers']):.2f} of the inliers")
    fig.tight_layout()
    return fig


def with_changes(scenario: Scenario | None = None, **changes: Any) -> Scenario:
    """A copy of ``scenario`` (default: the paper's) with some fields changed (for widgets)."""
    check_positive(changes.get("noise_unit_mm", 1.0), "noise_unit_mm")
    return replace(scenario or Scenario(), **changes)
