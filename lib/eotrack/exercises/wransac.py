"""Exercises of notebook 01 (WRANSAC, Yan et al. 2019); expected values come from the library."""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from eotrack.exercises import FunctionAnswer, NumericAnswer, register


def _wls_reference(a, y, w):
    a = np.asarray(a, float)
    y = np.asarray(y, float)
    sw = np.sqrt(np.asarray(w, float))
    return np.linalg.lstsq(a * sw[:, None], y * sw, rcond=None)[0]


def _wls_inputs():
    rng = np.random.default_rng(11)
    out = []
    for n, p in ((10, 2), (40, 4), (80, 4)):
        a = rng.normal(size=(n, p))
        y = a @ rng.normal(size=p) + 0.1 * rng.normal(size=n)
        w = rng.uniform(0.0, 1.0, n)
        w[: n // 5] = 0.0
        out.append((a, y, w))
    return out


def _gm_sd_45_cloud():
    from eotrack.experiments import wransac as W

    sc = W.make_scenario()
    t = sc.t_obs_s
    inl = np.zeros(len(t), bool)
    inl[:60] = True
    return W.gauss_markov(t, np.array([t[-1] + 45 * 60.0]), inl, 3.0)[0]


#: Methods of the checker's budget sweep (a subset of ``W.BUDGET_METHODS``).
BUDGET_CHECK_METHODS = ("ransac", "wransac_hypothesis")


@lru_cache(maxsize=1)
def _budget_errors():
    from eotrack.experiments import wransac as W
    from eotrack.montecarlo import TrialRunner

    # only the methods the checker and its tests need: with common random numbers a method's
    # errors do not depend on which other methods run (tests/exercises check this)
    return W.budget_sweep(budgets=W.BUDGETS, methods=BUDGET_CHECK_METHODS,
                          runner=TrialRunner(progress=False))


def _wransac_u10_within_20():
    from eotrack.experiments import wransac as W

    return float(W.budget_table(_budget_errors(), W.BUDGETS, BUDGET_CHECK_METHODS,
                                bound_arcsec=20.0).loc[10, "wransac_hypothesis"])


@lru_cache(maxsize=1)
def _paired_ratio_72_dec() -> float:
    from eotrack.experiments import wransac as W
    from eotrack.montecarlo import TrialRunner

    res = W.run_prediction_experiment(methods=("ransac", "wransac"),
                                      runner=TrialRunner(progress=False))
    return W.variance_ratio(res, "wransac", "ransac", "dec", 72, n_boot=10)[0]


def _unpaired_reversal_probability() -> float:
    from scipy.stats import f

    return float(f.cdf(1.0 / _paired_ratio_72_dec(), 19, 19))


def _nu_at_efficiency_09() -> float:
    from scipy.optimize import brentq

    from eotrack.experiments import wransac as W

    return float(brentq(lambda nu: W.student_t_efficiency(nu) - 0.9, 2.0 + 1e-9, 1e6,
                        xtol=1e-12))


register("wransac.1", NumericAnswer(
    "Derivation. For inlier noise that is Student-t with ν degrees of freedom and standard "
    "deviation σ, derive the Cramér–Rao bound on the variance of any unbiased predictor as a "
    "fraction of the OLS (Gauss–Markov) variance, as a function of ν. At what ν (a real "
    "number, not rounded) is that fraction 0.9, i.e. could a perfect estimator cut the "
    "variance by only a tenth?",
    expected=_nu_at_efficiency_09, rtol=1e-3,
    hint="Fisher information of a t_ν location with scale s is (ν+1)/((ν+3)s²); the variance "
         "of t_ν is s²ν/(ν−2) — set it to σ². The fraction is a ratio of quadratics in ν: "
         "setting it to 0.9 gives a quadratic equation; keep the root above 2."))

register("wransac.2", NumericAnswer(
    "Computation. Clouds hide the last 20 of the 80 observations of the main scenario, so only "
    "the first 60 are inliers (σ = 3″). With eotrack.experiments.wransac.gauss_markov, compute "
    "the standard deviation (arcsec) of the OLS prediction 45 min after the last of the 80 "
    "observation times.",
    expected=_gm_sd_45_cloud, rtol=1e-2,
    hint="the inlier mask has 80 entries, the first 60 True; the prediction time is "
         "t_obs[-1] + 45 × 60 s; the function returns a standard deviation, not a variance."))

register("wransac.3", NumericAnswer(
    "Exploration. From the Explore sweep `budget_err` (errors, runs × budgets × methods × "
    "times), compute the fraction (0–1) of runs in which WRANSAC with the hypothesis weights "
    "('wransac_hypothesis'), with U = 10 hypotheses, keeps its whole 72-min Dec prediction "
    "within 20″.",
    expected=_wransac_u10_within_20, atol=0.005,
    hint="index the budget axis with W.BUDGETS.index(10) and the method axis with "
         "W.BUDGET_METHODS.index('wransac_hypothesis'); take each run's largest |error| over "
         "the times; or use W.budget_table(..., bound_arcsec=20)."))

register("wransac.4", NumericAnswer(
    "Critique. The paper ordered WRANSAC and RANSAC from 20 runs, each method on its own draws. "
    "Take the true 72-min Dec variance ratio WRANSAC/RANSAC to be the one our paired runs "
    "measure (W.variance_ratio on the main experiment), and model each method's 20-run variance "
    "estimate as σ²χ²₁₉/19, independent between the methods. With what probability do 20 "
    "unpaired runs show WRANSAC's variance *below* RANSAC's, the paper's ordering?",
    expected=_unpaired_reversal_probability, rtol=0.03,
    hint="the ratio of the two estimates over the true ratio r is F(19, 19); you need "
         "P(r·F < 1) = F.cdf(1/r, 19, 19) (scipy.stats.f)."))

register("wransac.5", FunctionAnswer(
    "Write the weighted refit: a function wls(A, y, w) returning θ that minimises "
    "Σ w_i (y_i − A_i θ)² (A: n×p design matrix, w ≥ 0, some weights zero).",
    reference=_wls_reference, inputs=_wls_inputs, rtol=1e-6, atol=1e-9,
    hint="scale each row of A and y by √w_i and solve ordinary least squares."))
