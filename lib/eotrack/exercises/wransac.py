"""Exercises of notebook 01 (WRANSAC, Yan et al. 2019); expected values come from the library."""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from eotrack.exercises import Choice, FunctionAnswer, NumericAnswer, register


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


def _gm_sd_72():
    from eotrack.experiments import wransac as W

    sc = W.make_scenario()
    t72 = np.array([sc.t_obs_s[-1] + 72 * 60.0])
    return W.gauss_markov(sc.t_obs_s, t72, np.ones(len(sc.t_obs_s), bool), 3.0)[0]


@lru_cache(maxsize=1)
def _budget():
    from eotrack.experiments import wransac as W
    from eotrack.montecarlo import TrialRunner

    err = W.budget_sweep(budgets=W.BUDGETS, methods=W.BUDGET_METHODS,
                         runner=TrialRunner(progress=False))
    return W.budget_table(err, W.BUDGETS, W.BUDGET_METHODS)


def _student_efficiency_5():
    from eotrack.experiments import wransac as W

    return W.student_t_efficiency(5.0)


register("wransac.1", NumericAnswer(
    "Derivation. For inlier noise that is Student-t with ν = 5 degrees of freedom and standard "
    "deviation σ, derive the Cramér–Rao bound on the variance of any unbiased predictor as a "
    "fraction of the OLS (Gauss–Markov) variance. Give the fraction.",
    expected=_student_efficiency_5, rtol=1e-3,
    hint="Fisher information of a t_ν location with scale s is (ν+1)/((ν+3)s²); the variance "
         "of t_ν is s²ν/(ν−2) — set it to σ²."))

register("wransac.2", NumericAnswer(
    "Computation. With eotrack.experiments.wransac.gauss_markov, compute the standard deviation "
    "(arcsec) of the OLS prediction 72 min after the last observation when all 80 observations "
    "of the main scenario are inliers with σ = 3″.",
    expected=_gm_sd_72, rtol=1e-2,
    hint="t_pred is one time: the last observation time plus 72 × 60 s; the inlier mask is all "
         "True."))

register("wransac.3", NumericAnswer(
    "Exploration. In the Explore panel, set U = 3 (the paper's eq. 2 value) and show RANSAC: "
    "what fraction of the runs keep the whole 72-min Dec prediction within 27″? (0–1)",
    expected=lambda: float(_budget().loc[3, "ransac"]), atol=0.015,
    hint="read the percentage printed under the RANSAC box and divide by 100."))

register("wransac.4", Choice(
    "Critique. Under Gaussian noise, WRANSAC with weights from the best hypothesis's residuals "
    "has a larger 72-min variance than RANSAC. Which is the main cause? "
    "(a) the sinusoidal loss selects inlier sets that contain gross errors; "
    "(b) the weights come from the residuals of a noisy 4-point hypothesis, so the refit is "
    "pulled toward that hypothesis; (c) eq. (6) as printed is used; "
    "(d) 100 hypotheses are too few.",
    options=["a", "b", "c", "d"], answer="b",
    hint="compare the shuffled-weights control with the hypothesis-weights refit, and look at "
         "the pull plot."))

register("wransac.5", FunctionAnswer(
    "Write the weighted refit: a function wls(A, y, w) returning θ that minimises "
    "Σ w_i (y_i − A_i θ)² (A: n×p design matrix, w ≥ 0, some weights zero).",
    reference=_wls_reference, inputs=_wls_inputs, rtol=1e-6, atol=1e-9,
    hint="scale each row of A and y by √w_i and solve ordinary least squares."))
