"""The predictors and the paired Monte Carlo runs of the WRANSAC experiment.

Common random numbers: in every run all methods see the same noisy data and, for each
coordinate, the same minimal samples (drawn once with :func:`eotrack.robust.draw_samples`), so
differences between methods are differences of the methods, not of the draws. Variance ratios
then come with 95 % bootstrap intervals over the runs (:func:`variance_ratio`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy.optimize import least_squares

from eotrack.montecarlo import TrialRunner
from eotrack.robust import (
    LOSSES,
    Polynomial,
    SinusoidDrift,
    draw_samples,
    fit_free_sinusoid,
    fit_linear,
    irls_linear,
    predict_linear,
    ransac_linear,
)
from eotrack.validation import (
    as_finite_array,
    check_choice,
    check_generator,
    check_int,
    check_positive,
    check_same_length,
)

from .scenario import (
    COORDS,
    NOISE_MODELS,
    READINGS,
    Scenario,
    WransacConfig,
    make_scenario,
    simulate_observations,
)

__all__ = [
    "EXTRA_METHODS",
    "GENERALISATION_METHODS",
    "METHODS",
    "MODELS",
    "READING_METHODS",
    "PredictionResults",
    "budget_sweep",
    "fit_predict",
    "gauss_markov",
    "run_prediction_experiment",
    "threshold_sensitivity",
]

#: The paper's four predictors.
METHODS = ("sin", "lsq", "ransac", "wransac")
#: The three readings of WRANSAC's weights, as explicit methods.
READING_METHODS = tuple(f"wransac_{r}" for r in READINGS)
#: Baselines beyond the paper: the ideal reference, MSAC scoring, M-estimators (IRLS) started
#: from least squares (``huber``, ``soft_l1``, scipy) or from RANSAC (``*_ransac``).
EXTRA_METHODS = (*READING_METHODS, "ideal", "msac", "huber", "soft_l1", "huber_ransac", "cauchy_ransac")
ALL_METHODS = METHODS + EXTRA_METHODS
#: The methods run by the main (paired) experiment.
MAIN_METHODS = (*METHODS, "wransac_refit", "wransac_iterated", "ideal", "msac", "huber_ransac", "cauchy_ransac")
#: The methods compared on the other objects.
GENERALISATION_METHODS = ("sin", "lsq", "ransac", *READING_METHODS, "huber_ransac", "cauchy_ransac", "ideal")
MODELS = ("sinusoid_drift", "cubic", "quadratic")


def _model(name: str, t_ref: float):
    check_choice(name, "model", MODELS)
    if name == "sinusoid_drift":
        return SinusoidDrift(t_ref_s=t_ref)
    return Polynomial(degree=3 if name == "cubic" else 2, t_ref_s=t_ref)


def fit_predict(method: str, t_s: np.ndarray, y: np.ndarray, t_new_s: np.ndarray, *,
                rng: np.random.Generator, threshold: float = 9.0, n_hypotheses: int = 3,
                model: str = "sinusoid_drift", loss: str | None = None,
                weighting: str = "hypothesis", samples: np.ndarray | None = None,
                inliers: np.ndarray | None = None, return_fit: bool = False):
    """Fit one coordinate's track and predict it at new times.

    Parameters
    ----------
    method
        The paper's ``"sin"`` (free-ω sinusoid, nonlinear least squares on all data), ``"lsq"``
        (ordinary least squares of the linear model), ``"ransac"`` (0-1 loss, least-squares
        refit on the inliers), ``"wransac"`` (sinusoidal loss, refit weighted by ``1 − L_s``,
        weights per ``weighting``); beyond the paper: ``"wransac_hypothesis"``,
        ``"wransac_refit"``, ``"wransac_iterated"`` (WRANSAC with that weighting reading),
        ``"ideal"`` (ordinary least squares on the *true* inliers, given as ``inliers``),
        ``"msac"`` (linear MSAC scoring, least-squares refit), ``"huber"``/``"soft_l1"`` (scipy
        robust least squares from the LSQ fit, scale t/3), ``"huber_ransac"``/
        ``"cauchy_ransac"`` (IRLS M-estimators started from the RANSAC fit, scale t/3).
    t_s, y
        Observation times (s) and values (arcsec), shape ``(n,)``.
    t_new_s
        Prediction times (s).
    rng
        Generator for the random minimal samples (unused when ``samples`` is given).
    threshold
        Inlier threshold t (arcsec).
    n_hypotheses
        Number of minimal samples U.
    model
        Linear model: ``"sinusoid_drift"`` (the project's reading, m = 4), ``"cubic"``,
        ``"quadratic"``.
    loss
        Override the scoring loss of ``"ransac"`` (any key of ``eotrack.robust.LOSSES``).
    weighting
        WRANSAC weights from the ``"hypothesis"`` residuals, the ``"refit"`` residuals (one
        step) or ``"iterated"`` to convergence.
    samples
        Minimal samples ``(U, m)`` shared with other methods (common random numbers).
    inliers
        Boolean mask of the true inliers (``"ideal"`` only).
    return_fit
        Also return the :class:`~eotrack.robust.RansacResult` (RANSAC-type methods) or ``None``.

    Returns
    -------
    numpy.ndarray or (numpy.ndarray, RansacResult | None)
        Predictions at ``t_new_s``.
    """
    check_choice(method, "method", ALL_METHODS)
    check_generator(rng)
    tt = as_finite_array(t_s, "t_s", ndim=1)
    yy = as_finite_array(y, "y", ndim=1)
    check_same_length("t_s", tt, "y", yy)
    tn = as_finite_array(t_new_s, "t_new_s", ndim=1)
    check_positive(threshold, "threshold")
    check_choice(weighting, "weighting", tuple(READINGS))
    if loss is not None:
        check_choice(loss, "loss", tuple(LOSSES))
    mdl = _model(model, float(np.mean(tt)) if len(tt) else 0.0)
    if len(tt) < max(4, mdl.n_params):
        raise ValueError(f"need at least {max(4, mdl.n_params)} observations, got {len(tt)}")
    if method.startswith("wransac_"):
        method, weighting = "wransac", method.split("_", 1)[1]
    fit = None
    scale = threshold / 3.0
    if method == "sin":
        pred = fit_free_sinusoid(tt, yy)(tn)
    elif method == "lsq":
        pred = predict_linear(mdl, fit_linear(mdl, tt, yy), tn)
    elif method == "ideal":
        if inliers is None:
            raise ValueError("method 'ideal' needs inliers (the mask of the true inliers)")
        mask = np.asarray(inliers, dtype=bool)
        if mask.shape != tt.shape:
            raise ValueError(f"inliers must have shape {tt.shape}, got {mask.shape}")
        pred = predict_linear(mdl, fit_linear(mdl, tt, yy, weights=mask.astype(float)), tn)
    elif method in ("huber", "soft_l1"):
        a = mdl.design(tt)
        th0 = fit_linear(mdl, tt, yy)
        sol = least_squares(lambda th: a @ th - yy, th0, loss=method, f_scale=scale)
        pred = predict_linear(mdl, sol.x, tn)
    else:
        score = {"ransac": "zero_one", "wransac": "sinusoidal", "msac": "msac",
                 "huber_ransac": "zero_one", "cauchy_ransac": "zero_one"}[method]
        engine = READINGS[weighting] if method == "wransac" else "lsq"
        fit = ransac_linear(mdl, tt, yy, threshold=threshold, n_hypotheses=n_hypotheses,
                            rng=rng, loss=loss or score, weighting=engine, samples=samples)
        theta = fit.params
        if method.endswith("_ransac"):
            theta = irls_linear(mdl, tt, yy, theta, scale=scale, kind=method.split("_")[0])
        pred = predict_linear(mdl, theta, tn)
    return (pred, fit) if return_fit else pred


def student_t_efficiency(nu: float) -> float:
    """Cramér–Rao variance over OLS variance for Student-t noise with ``nu`` dof and std σ.

    The Fisher information of a location under a t_ν of scale s is ``(ν+1)/((ν+3)s²)``; with
    the same standard deviation σ (``s² = σ²(ν−2)/ν``) the bound is
    ``σ²(ν+3)(ν−2)/(ν(ν+1))`` per observation, against OLS's σ². The ratio applies to any
    linear function of the parameters, e.g. the prediction at +72 min. ν = 3 → 0.5; ν → ∞ → 1.
    """
    if isinstance(nu, bool) or not isinstance(nu, int | float | np.integer | np.floating):
        raise TypeError(f"nu must be a number, got {type(nu).__name__}")
    if not nu > 2:
        raise ValueError(f"nu must be > 2 (finite variance), got {nu}")
    return float((nu + 3.0) * (nu - 2.0) / (nu * (nu + 1.0)))


# --------------------------------------------------------------------------------------------
# the paired runs


def gauss_markov(t_obs_s: np.ndarray, t_pred_s: np.ndarray, inliers: np.ndarray,
                 sigma: float, model: str = "sinusoid_drift") -> np.ndarray:
    """Prediction standard deviation of OLS on the given inliers: ``σ √(aᵀ(AᵀA)⁻¹a)``.

    By Gauss–Markov this is the smallest standard deviation of any linear unbiased predictor
    from those points; with Gaussian noise it is also the Cramér–Rao bound for any unbiased one.

    Returns
    -------
    numpy.ndarray
        Standard deviation (arcsec) at every ``t_pred_s``.
    """
    tt = as_finite_array(t_obs_s, "t_obs_s", ndim=1)
    tp = as_finite_array(t_pred_s, "t_pred_s", ndim=1)
    mask = np.asarray(inliers, dtype=bool)
    if mask.shape != tt.shape:
        raise ValueError(f"inliers must have shape {tt.shape}, got {mask.shape}")
    check_positive(sigma, "sigma")
    mdl = _model(model, float(np.mean(tt)))
    a = mdl.design(tt[mask])
    cov = np.linalg.inv(a.T @ a)
    ap = mdl.design(tp)
    return sigma * np.sqrt(np.einsum("ij,jk,ik->i", ap, cov, ap))


def _paired_trial(rng: np.random.Generator, t_obs: np.ndarray, truth_obs: np.ndarray,
                  t_pred: np.ndarray, truth_pred: np.ndarray, cfg: WransacConfig,
                  methods: tuple[str, ...], model: str, n_hyp: int) -> dict:
    """One run: noisy data, every method on both coordinates with the same hypotheses."""
    y, bad = simulate_observations(rng, truth_obs, cfg.sigma_arcsec, cfg.outlier_fraction,
                                   cfg.gross_error_arcsec, cfg.inlier_noise, cfg.student_nu)
    n = len(t_obs)
    err = np.empty((len(methods), len(COORDS), len(t_pred)))
    hyp_err = np.full((len(COORDS), len(t_pred)), np.nan)
    shuf_err = np.full((len(COORDS), len(t_pred)), np.nan)
    gm = np.empty((len(COORDS), len(t_pred)))
    inlier_loss, inlier_weight, n_inliers = [], [], []
    mdl = _model(model, float(np.mean(t_obs)))
    for ci in range(len(COORDS)):
        idx = draw_samples(rng, n, mdl.n_params, n_hyp)
        done: dict[str, np.ndarray] = {}
        for mi, meth in enumerate(methods):
            key = f"wransac_{cfg.weighting}" if meth == "wransac" else meth
            if key in done:
                err[mi, ci] = done[key]
                continue
            pred, fit = fit_predict(meth, t_obs, y[ci], t_pred, rng=rng,
                                    threshold=cfg.threshold_arcsec, n_hypotheses=n_hyp,
                                    model=model, weighting=cfg.weighting, samples=idx,
                                    inliers=~bad[ci], return_fit=True)
            err[mi, ci] = done[key] = pred - truth_pred[ci]
            if meth == "wransac":
                inlier_loss.append(fit.losses[fit.inliers])
                inlier_weight.append(fit.weights[fit.inliers])
                n_inliers.append(fit.n_inliers)
            if key == "wransac_hypothesis":
                # the mechanism: the best hypothesis itself, and the same weights shuffled
                hyp_err[ci] = predict_linear(mdl, fit.hypothesis_params, t_pred) - truth_pred[ci]
                w = fit.weights.copy()
                inl = np.flatnonzero(fit.inliers)
                w[inl] = rng.permutation(w[inl])
                if np.count_nonzero(w) >= mdl.n_params:
                    shuf_err[ci] = predict_linear(mdl, fit_linear(mdl, t_obs, y[ci], w),
                                                  t_pred) - truth_pred[ci]
        gm[ci] = gauss_markov(t_obs, t_pred, ~bad[ci], cfg.sigma_arcsec, model)
    return {"errors": err, "n_outliers": bad.sum(axis=1), "inlier_loss": inlier_loss,
            "inlier_weight": inlier_weight, "n_inliers": n_inliers, "obs": y,
            "hyp_errors": hyp_err, "shuffled_errors": shuf_err, "gm_sd": gm}


@dataclass(frozen=True)
class PredictionResults:
    """Errors ``(runs, methods, coords, times)`` of every paired run, and what explains them.

    ``hyp_errors``/``shuffled_errors`` ``(runs, coords, times)``: the prediction errors of the
    best L_s hypothesis itself and of the weighted refit with its weights shuffled among the
    inliers; ``gm_sd`` ``(runs, coords, times)``: the Gauss–Markov standard deviation of OLS on
    that run's true inliers.
    """

    config: WransacConfig
    scenario: Scenario
    methods: tuple[str, ...]
    errors: np.ndarray
    inlier_loss: list[np.ndarray]
    inlier_weight: list[np.ndarray]
    n_inliers: np.ndarray  # (runs, coords)
    n_outliers: np.ndarray  # (runs, coords)
    first_obs: np.ndarray  # observations of run 0, (2, n)
    hyp_errors: np.ndarray | None = None
    shuffled_errors: np.ndarray | None = None
    gm_sd: np.ndarray | None = None
    n_hypotheses: int = 0

    @property
    def n_runs(self) -> int:
        """Number of runs."""
        return self.errors.shape[0]

    def window(self, horizon_min: float) -> np.ndarray:
        """Mask of prediction times within ``horizon_min`` of the last observation."""
        dt = self.scenario.t_pred_s - self.scenario.t_obs_s[-1]
        return dt <= horizon_min * 60.0 + 1e-9

    def method_errors(self, method: str, coord: str = "dec", horizon_min: float = 72
                      ) -> np.ndarray:
        """Errors ``(runs, times)`` of one method, coordinate and window."""
        check_choice(method, "method", self.methods)
        ci = COORDS.index(check_choice(coord, "coord", COORDS))
        return self.errors[:, self.methods.index(method), ci][:, self.window(horizon_min)]


def run_prediction_experiment(config: WransacConfig | None = None, *,
                              scenario: Scenario | None = None, n_runs: int | None = None,
                              methods: tuple[str, ...] = MAIN_METHODS,
                              model: str = "sinusoid_drift",
                              runner: TrialRunner | None = None, seed: int | None = None,
                              n_hypotheses: int | None = None) -> PredictionResults:
    """The repeated simulation with common random numbers: ``n_runs`` paired runs.

    Parameters
    ----------
    config
        Settings (noise model, weighting reading, budget …).
    scenario
        The true track (default: :func:`make_scenario` of ``config``).
    n_runs
        Runs (default ``config.n_runs``).
    methods
        Methods to run (names of :func:`fit_predict`).
    model
        Trajectory model.
    runner
        Where trials run.
    seed
        Root seed (default ``config.seed``).
    n_hypotheses
        Hypotheses per coordinate (default ``config.n_draws``).

    Returns
    -------
    PredictionResults
    """
    cfg = config or WransacConfig()
    sc = scenario or make_scenario(cfg)
    for m in methods:
        check_choice(m, "methods", ALL_METHODS)
    check_choice(model, "model", MODELS)
    n = cfg.n_runs if n_runs is None else check_int(n_runs, "n_runs", min_value=1)
    n_hyp = cfg.n_draws if n_hypotheses is None else check_int(n_hypotheses, "n_hypotheses",
                                                                min_value=1)
    runner = runner or TrialRunner()
    out = runner.map(_paired_trial, n, seed=cfg.seed if seed is None else seed,
                     args=(sc.t_obs_s, sc.truth_obs, sc.t_pred_s, sc.truth_pred, cfg,
                           tuple(methods), model, n_hyp), desc="wransac paired runs")
    errors = np.stack([o["errors"] for o in out])
    loss = [a for o in out for a in o["inlier_loss"]]
    weight = [a for o in out for a in o["inlier_weight"]]
    n_inl = np.array([o["n_inliers"] for o in out]) if "wransac" in methods else np.zeros((n, 0))
    return PredictionResults(cfg, sc, tuple(methods), errors, loss, weight, n_inl,
                             np.array([o["n_outliers"] for o in out]), out[0]["obs"],
                             np.stack([o["hyp_errors"] for o in out]),
                             np.stack([o["shuffled_errors"] for o in out]),
                             np.stack([o["gm_sd"] for o in out]), n_hyp)


# --------------------------------------------------------------------------------------------
# sweeps beyond the paper


#: The threshold study's columns: scoring loss (all with the OLS refit on the inliers), then
#: WRANSAC (sinusoidal scoring *and* the weighted refit) — the loss and the refit apart.
SENSITIVITY_WRANSAC = "WRANSAC (L_s + weighted refit)"


def _sensitivity_trial(rng: np.random.Generator, t_obs: np.ndarray, truth_obs: np.ndarray,
                       t_pred: np.ndarray, truth_pred: np.ndarray, cfg: WransacConfig,
                       ratios: tuple[float, ...], losses: tuple[str, ...], n_hyp: int,
                       with_wransac: bool) -> np.ndarray:
    y, _ = simulate_observations(rng, truth_obs[1], cfg.sigma_arcsec, cfg.outlier_fraction,
                                 cfg.gross_error_arcsec, cfg.inlier_noise, cfg.student_nu)
    idx = draw_samples(rng, len(t_obs), 4, n_hyp)
    cols = [("ransac", ls) for ls in losses] + ([("wransac", None)] if with_wransac else [])
    out = np.empty((len(ratios), len(cols)))
    for i, k in enumerate(ratios):
        for j, (meth, ls) in enumerate(cols):
            pred = fit_predict(meth, t_obs, y, t_pred, rng=rng, threshold=k * cfg.sigma_arcsec,
                               n_hypotheses=n_hyp, loss=ls, samples=idx,
                               weighting=cfg.weighting)
            out[i, j] = np.sqrt(np.mean((pred - truth_pred[1]) ** 2))
    return out


def threshold_sensitivity(config: WransacConfig | None = None, *, scenario: Scenario | None = None,
                          ratios: tuple[float, ...] = (1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 10.0),
                          losses: tuple[str, ...] = ("zero_one", "msac", "msac_squared",
                                                     "sinusoidal"),
                          n_runs: int = 100, n_hypotheses: int | None = None,
                          runner: TrialRunner | None = None, with_wransac: bool = True
                          ) -> pd.DataFrame:
    """RMS 72-min prediction error (Dec) versus threshold t/σ, the scoring loss and the refit apart.

    The paper argues that L_s makes RANSAC "less sensitive to the threshold". WRANSAC changes
    two things at once — the scoring loss and the refit — so each loss of ``losses`` is run
    with the *same* OLS refit on its inliers (only the choice of hypothesis differs), and, with
    ``with_wransac``, a last column :data:`SENSITIVITY_WRANSAC` adds the weighted refit.
    Every column of a run sees the same data and the same minimal samples.

    Returns
    -------
    pandas.DataFrame
        Median over runs of the RMS error (arcsec), index t/σ; columns ``"<loss> + OLS refit"``
        per loss, then :data:`SENSITIVITY_WRANSAC`.
    """
    cfg = config or WransacConfig()
    sc = scenario or make_scenario(cfg)
    for ls in losses:
        check_choice(ls, "losses", tuple(LOSSES))
    runner = runner or TrialRunner()
    n_hyp = cfg.n_draws if n_hypotheses is None else n_hypotheses
    res = runner.map(_sensitivity_trial, n_runs, seed=cfg.seed + 1,
                     args=(sc.t_obs_s, sc.truth_obs, sc.t_pred_s, sc.truth_pred, cfg,
                           tuple(ratios), tuple(losses), n_hyp, bool(with_wransac)),
                     desc="threshold sweep")
    med = np.median(np.stack(res), axis=0)
    cols = [f"{ls} + OLS refit" for ls in losses] + ([SENSITIVITY_WRANSAC] if with_wransac
                                                     else [])
    return pd.DataFrame(med, index=pd.Index(ratios, name="t/sigma"), columns=cols)


def _budget_trial(rng: np.random.Generator, t_obs: np.ndarray, truth_obs: np.ndarray,
                  t_pred: np.ndarray, truth_pred: np.ndarray, cfg: WransacConfig,
                  budgets: tuple[int, ...], methods: tuple[str, ...]) -> np.ndarray:
    y, bad = simulate_observations(rng, truth_obs[1], cfg.sigma_arcsec, cfg.outlier_fraction,
                                   cfg.gross_error_arcsec, cfg.inlier_noise, cfg.student_nu)
    # nested budgets: the first U rows of one big draw, so a larger U only adds hypotheses
    idx_all = draw_samples(rng, len(t_obs), 4, max(budgets))
    out = np.empty((len(budgets), len(methods), len(t_pred)))
    for i, n_hyp in enumerate(budgets):
        for j, meth in enumerate(methods):
            pred = fit_predict(meth, t_obs, y, t_pred, rng=rng, threshold=cfg.threshold_arcsec,
                               n_hypotheses=n_hyp, samples=idx_all[:n_hyp], inliers=~bad,
                               weighting=cfg.weighting)
            out[i, j] = pred - truth_pred[1]
    return out


def budget_sweep(config: WransacConfig | None = None, *, scenario: Scenario | None = None,
                 budgets: tuple[int, ...] = (3, 5, 10, 30, 100, 300),
                 methods: tuple[str, ...] = ("lsq", "ransac", "wransac_hypothesis",
                                             "wransac_refit", "wransac_iterated", "msac",
                                             "huber_ransac", "cauchy_ransac", "ideal"),
                 n_runs: int = 100, runner: TrialRunner | None = None) -> np.ndarray:
    """Dec prediction errors versus the number of hypotheses U, for several methods (paired).

    Eq. (2) counts the draws needed for one *outlier-free* minimal sample; it says nothing about
    whether that sample is well conditioned. This measures what the paper's U = 3 delivers.
    Hypotheses are nested: run ``r`` with budget U uses the first U samples of one draw.

    Returns
    -------
    numpy.ndarray
        Errors ``(runs, budgets, methods, times)`` (arcsec) on the scenario's prediction grid.
    """
    cfg = config or WransacConfig()
    sc = scenario or make_scenario(cfg)
    for m in methods:
        check_choice(m, "methods", ALL_METHODS)
    runner = runner or TrialRunner()
    res = runner.map(_budget_trial, n_runs, seed=cfg.seed + 2,
                     args=(sc.t_obs_s, sc.truth_obs, sc.t_pred_s, sc.truth_pred, cfg,
                           tuple(budgets), tuple(methods)), desc="budget sweep")
    return np.stack(res)


__all__ += [
    "ALL_METHODS",
    "MAIN_METHODS",
    "NOISE_MODELS",
    "SENSITIVITY_WRANSAC",
    "student_t_efficiency",
]
