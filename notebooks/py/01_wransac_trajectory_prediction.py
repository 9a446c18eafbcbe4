# ---
# jupyter:
#   kernelspec:
#     display_name: Python 3 (ipykernel)
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 01 · WRANSAC: robust trajectory prediction for electro-optical tracking
#
# **Paper.** Yan L., Huang Y., Zhang Y., Tang T., Xia Y. *Research on the application of RANSAC
# algorithm in electro-optical tracking of space targets.* Opto-Electronic Engineering
# **46**(11):180540, 2019 [1]. [DOI 10.12086/oe.2019.180540](https://doi.org/10.12086/oe.2019.180540)
#
# **What the paper does.** A station tracking a high-orbit object loses it behind clouds or in
# the Earth's shadow (up to 72 min) and must steer from a *predicted* track. The paper fits the
# last 2 h of its own RA/Dec measurements with RANSAC [2], predicts 15, 30 and 72 min ahead,
# and proposes "WRANSAC" — a smooth sinusoidal loss and a refit weighted by it — which it
# reports as more stable than RANSAC, most of all at 72 min.
#
# ## Learning objectives
#
# 1. size a RANSAC run with eq. (2) and say what that number does *not* guarantee;
# 2. build RANSAC and WRANSAC step by step and check them against a library engine;
# 3. compare estimators with **common random numbers** and a **bootstrap interval**;
# 4. say what the **Gauss–Markov** and **Cramér–Rao** bounds do and do not imply, and find the
#    mechanism when a re-weighting does worse;
# 5. turn a reproduction into a measured recommendation.
#
# **Prerequisites.** Linear least squares, the Gaussian and Student-t distributions, confidence
# intervals. Notebook 06 (RANSAC for pose) builds on this one.
#
# **Scorecard** (written by `make repro`; recomputed in section 6):

# %%
import json

from eotrack.notebook import lesson_header
from eotrack.repro import papers_repro_dir

lesson_header("01")
from IPython.display import Markdown, display

_card = json.loads((papers_repro_dir() / "wransac" / "scorecard.json").read_text())
display(Markdown(f"**{_card['summary']}** — " + "; ".join(
    f"`{c['claim']}`: {c['status']}" for c in _card["claims"])))

# %% [markdown]
# ## 2 · Setup

# %%
from dataclasses import replace

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from eotrack.exercises import check, exercise_ids
from eotrack.experiments import wransac as W
from eotrack.montecarlo import TrialRunner
from eotrack.notebook import dropdown, panel, setup_notebook, toggle, versions
from eotrack.repro import load_claims, papers_repro_dir
from eotrack.robust import (
    SinusoidDrift,
    draw_samples,
    fit_linear,
    get_loss,
    min_samples,
    min_samples_real,
    msac_loss,
    predict_linear,
    ransac_linear,
    sinusoidal_loss,
    sinusoidal_loss_as_printed,
    success_probability,
    wransac_linear,
)

setup_notebook()

# %% tags=["parameters"]
QUICK = False  # True: 40 paired runs and 10 side-study runs (for a fast look; statuses may differ)
N_RUNS = 40 if QUICK else 300  # paired runs of the main experiment (the paper ran 20)
N_SIDE = 10 if QUICK else 100  # runs of the side studies (U sweep, generalisation)

# %%
print(versions())
claims = load_claims("wransac")
cfg = W.WransacConfig(n_runs=N_RUNS)
runner = TrialRunner(progress=False)
sc = W.make_scenario(cfg)
print(sc.description)

# %% [markdown]
# ## 3 · Notation
#
# | paper | code | meaning | unit |
# |---|---|---|---|
# | $P$ | `confidence` | probability that at least one minimal sample is outlier-free | – |
# | $\varepsilon$ | `outlier_ratio` | fraction of gross errors in the data | – |
# | $m$ | `sample_size` | minimal sample size (model parameters) | points |
# | $U$ | `n_hypotheses`, `n_draws` | number of random minimal samples | – |
# | $e$ | `residuals` | residual of a datum under a model | arcsec |
# | $t$ | `threshold_arcsec` | inlier threshold, $t = 3\sigma$ | arcsec |
# | $\sigma$ | `sigma_arcsec` | standard deviation of the inlier noise | arcsec |
# | $L_R, L_M, L_s$ | `zero_one_loss`, `msac_loss`, `sinusoidal_loss` | losses | – |
# | $J$ | `cost` | $\sum_d L(e_d)$ | – |
# | $w_i$ | `weights` | refit weight of an inlier, $w = 1 - L_s(e)$ (ours) | – |
# | $\theta = (a, b, c, d)$ | `params` | trajectory-model parameters | arcsec |
# | $\alpha, \delta$ | `ra`, `dec` | topocentric right ascension (minus sidereal rotation), declination | arcsec |
# | $\sigma_\text{pred}(t)$ | `gauss_markov` | Gauss–Markov prediction standard deviation | arcsec |

# %% [markdown]
# ## 4 · The method, step by step
#
# ### 4.1 Which coordinates? (§2)
#
# Azimuth/elevation tracks depend strongly on where the station is; right ascension and
# declination (the object treated like a star) barely do. The paper backs this with the
# correlation between the tracks seen from two stations. We recompute it for our
# object, from the paper's three stations.

# %%
CORR_HOURS = 24.0  # span of the correlation tracks (the paper does not state its span)
corr = W.station_correlations(cfg, duration_h=CORR_HOURS)
W.coords_table(corr, claims["wransac.coords"].paper)

# %% [markdown]
# Declination is the same track from everywhere and elevation flips sign between hemispheres,
# as in the paper; single numbers differ (the paper gives neither the object, the track length
# nor the RA wrapping — unwrapped, the RA correlation is 1).
#
# ### 4.2 How many random samples? (eqs. 1–2, Fig. 1)
#
# A minimal sample of $m$ points is outlier-free with probability $(1-\varepsilon)^m$. After
# $U$ independent samples, at least one is clean with probability
#
# $$1 - \left(1 - (1-\varepsilon)^m\right)^U = P \qquad (1)$$
#
# so the smallest sufficient number of samples is
#
# $$U = \frac{\log(1 - P)}{\log\left(1 - (1-\varepsilon)^m\right)}, \text{ rounded up.} \qquad (2)$$

# %%
U = min_samples(0.995, 0.03, 4)
print(f"P = 0.995, ε = 0.03, m = 4:  U = {min_samples_real(0.995, 0.03, 4):.3f} → {U}")

# %% [markdown]
# Eq. (1) treats each of the $m$ points of a sample as an independent draw that is an outlier
# with probability $\varepsilon$ (sampling *with* replacement). A real minimal sample is drawn
# *without* replacement from $n$ points of which $k$ are outliers, so it is clean with
# probability $\binom{n-k}{m}/\binom{n}{m}$, a little less than $(1-\varepsilon)^m$. We check
# eq. (1) by simulation where the check can fail: at the paper's setting the failure
# probability is so small that a few thousand trials cannot tell $m = 3$ from $m = 6$, so the
# check uses a high outlier ratio and more samples, where the exponent changes the answer a lot.

# %%
from math import comb

n_pts, k_out, U_chk, n_trials = 80, 24, 10, 10000
rng = np.random.default_rng(cfg.seed)
outlier = np.zeros(n_pts, bool)
outlier[:k_out] = True
samples = draw_samples(rng, n_pts, 4, U_chk * n_trials).reshape(n_trials, U_chk, 4)
fail_mc = 1 - (~outlier[samples].any(axis=2)).any(axis=1).mean()
fail_exact = (1 - comb(n_pts - k_out, 4) / comb(n_pts, 4)) ** U_chk  # without replacement
se = np.sqrt(fail_exact * (1 - fail_exact) / n_trials)
fail_eq1 = {m: 1 - success_probability(U_chk, k_out / n_pts, m) for m in (3, 4, 5, 6)}
print(f"ε = {k_out}/{n_pts}, U = {U_chk}: P(no clean sample) simulated {fail_mc:.4f} ± {se:.4f}, "
      f"exact without replacement {fail_exact:.4f}")
for m, f in fail_eq1.items():
    print(f"  eq. (1) with exponent m = {m}: {f:.4f}  ({f / fail_exact:.2f}× the exact value)")
assert abs(fail_mc - fail_exact) < 4 * se  # the simulation samples without replacement
assert abs(fail_eq1[4] / fail_exact - 1) < 0.15  # eq. (1), m = 4: a close approximation
assert all(abs(fail_eq1[m] / fail_exact - 1) > 0.5 for m in (3, 5, 6))  # wrong exponents fail
p_paper_exact = 1 - (1 - comb(77, 4) / comb(80, 4)) ** U
print(f"paper's setting (3 of 80 outliers, U = {U}): eq. (1) {success_probability(U, 3 / 80, 4):.5f}, "
      f"exact without replacement {p_paper_exact:.5f}")

# %%
# NBVAL_CHECK_OUTPUT
print(f"U = {U} hypotheses from eq. (2); we draw {cfg.n_draws}")

# %%
W.plot_min_samples(paper=claims["wransac.fig1"].paper)
plt.show()

# %% [markdown]
# ### 4.3 Losses (eqs. 3–6, Fig. 2)
#
# RANSAC picks the model $S$ minimising $J = \sum_{d\in D} L\big(E(d; S)\big)$ (3). Classic
# RANSAC uses the 0-1 loss $L_R(e) = [|e| > t]$ (4); the paper's $L_M(e) = |e|/t$ inside the
# threshold, 1 outside (5), is attributed to its ref. [11], a satellite position-prediction
# paper — MSAC is Torr and Zisserman's [3], and quadratic, $e^2/t^2$.
#
# The new loss **as printed**, $L_s(e) = \tfrac12\cos\!\big(e/(2t)\big) + \tfrac12$ inside $t$
# (6), is largest for a *perfect* fit and jumps at $|e| = t$: an erratum. The text asks for a
# loss below $L_M$ for small errors, above it for large ones inside $t$, with a continuous
# first derivative, flat near the threshold. Several functions have these properties — the
# cubic *smoothstep* $3x^2 - 2x^3$ ($x = |e|/t$) too (checked below). We adopt the raised cosine,
# the smallest edit of the printed formula (sign and argument corrected):
#
# $$L_s(e) = \tfrac12 - \tfrac12\cos\!\left(\frac{\pi e}{t}\right), \quad |e| \le t; \qquad 1
# \text{ otherwise.} \qquad (6')$$

# %%
t = 1.0
e = np.linspace(0, t, 100001)
ls, lm = sinusoidal_loss(e, t), msac_loss(e, t)
slope = np.gradient(ls, e)
printed = sinusoidal_loss_as_printed(e, t)
checks = {
    "L_s(0) = 0": ls[0] == 0,
    "L_s(t) = 1": abs(ls[-1] - 1) < 1e-12,
    "slope 0 at e = 0 and e = t": abs(slope[0]) < 1e-4 and abs(slope[-1]) < 1e-4,
    "L_s < L_M on (0, t/2)": bool(np.all(ls[(e > 0) & (e < 0.5)] < lm[(e > 0) & (e < 0.5)])),
    "L_s > L_M on (t/2, t)": bool(np.all(ls[(e > 0.5) & (e < 1)] > lm[(e > 0.5) & (e < 1)])),
    "printed form: L(0) = 1 (an erratum)": printed[0] == 1.0,
    "printed form: L(t⁻) ≈ 0.94, jump at t (an erratum)": abs(printed[-1] - 0.939) < 0.001,
}
x = e / t
smooth = 3 * x**2 - 2 * x**3  # another reading with the same properties
s_slope = np.gradient(smooth, e)
checks |= {
    "smoothstep: 0 at 0, 1 at t, flat at both ends": smooth[0] == 0 and abs(smooth[-1] - 1) < 1e-12
    and abs(s_slope[0]) < 1e-4 and abs(s_slope[-1]) < 1e-4,
    "smoothstep: < L_M on (0, t/2), > L_M on (t/2, t)":
        bool(np.all(smooth[(x > 0) & (x < 0.5)] < lm[(x > 0) & (x < 0.5)])
             and np.all(smooth[(x > 0.5) & (x < 1)] > lm[(x > 0.5) & (x < 1)])),
}
for k, v in checks.items():
    print(f"{'✔' if v else '✘'} {k}")
assert all(checks.values())
print(f"the two readings differ by at most {np.abs(ls - smooth).max():.3f} (in units of the loss)")

# %%
W.plot_losses()
plt.show()

# %% [markdown]
# ### 4.4 The trajectory model and the four predictors — the paper's unstated choices
#
# The paper calls the RA/Dec track "clearly sinusoidal" with $m = 4$ but never writes the model.
# For a geostationary object, Dec and RA minus the sidereal rotation oscillate with one sidereal
# day, so we adopt, per coordinate,
#
# $$y(t) = a\sin\omega t + b\cos\omega t + c + d\,t, \qquad \omega = \omega_\oplus
# = 7.292\,115\times10^{-5}\ \text{rad/s},$$
#
# linear in $\theta = (a, b, c, d)$. The four predictors:
#
# * **sin** — $y = A\sin(\omega' t + \varphi) + c$ with *free* $\omega'$, nonlinear least squares;
# * **LSQ** — ordinary least squares of the linear model on all data;
# * **RANSAC** — 0-1 loss, least-squares refit on the best inlier set;
# * **WRANSAC** — loss $L_s$, refit weighted by $w = 1 - L_s(e)$ (4.6).
#
# How well does the model represent the *true* track over the data and the 72 min after?

# %%
t_all = np.r_[sc.t_obs_s, sc.t_pred_s]
model = SinusoidDrift(t_ref_s=sc.t_obs_s.mean())
for name, ci in (("RA − sidereal", 0), ("Dec", 1)):
    y_all = np.r_[sc.truth_obs[ci], sc.truth_pred[ci]]
    resid = y_all - predict_linear(model, fit_linear(model, t_all, y_all), t_all)
    print(f"{name:14s}: model error over the {np.ptp(t_all) / 3600:.1f}-h track "
          f"{np.abs(resid).max():.3f}″ "
          f"(the track spans {np.ptp(y_all):.0f}″)")
    assert np.abs(resid).max() < 0.5

# %% [markdown]
# The model is adequate here. Over 2 h, $\omega t$ is a small fraction of a period, so the four
# columns are nearly collinear and extrapolating 72 min amplifies the noise (4.7).
#
# ### 4.5 The WRANSAC flowchart (Fig. 3)

# %%
W.plot_flowchart()
plt.show()

# %% [markdown]
# ### 4.6 One trial by hand
#
# For one noisy Dec series: (1) draw $U$ minimal samples of 4 observations; (2) solve each
# exactly for $\theta$; (3) score each on all data, $J = \sum_i L(e_i)$; (4) keep the lowest $J$
# (ties: more inliers, then smaller inlier variance); (5) refit on its inliers
# $\mathcal I = \{i : |e_i| \le t\}$.
#
# RANSAC refits by OLS on $\mathcal I$; WRANSAC by **weighted least squares**, with
# $w_i = 1 - L_s(e_i)$ on $\mathcal I$ and 0 elsewhere,
#
# $$\hat\theta_W = \arg\min_\theta \sum_i w_i\,(y_i - a_i^\top\theta)^2
# = (A^\top W A)^{-1} A^\top W y .$$
#
# The paper says only that the weights come "from the loss values of the purified inlier set".
# Which residuals? Three readings (`WransacConfig.weighting`): `"hypothesis"` — those of the
# best 4-point hypothesis (fixed before any run, used for the claims); `"refit"` — of one OLS
# refit on $\mathcal I$; `"iterated"` — that step repeated to a fixed point. Every method in a
# run gets the **same** minimal samples (common random numbers, passed as `samples`).

# %%
y, is_bad = W.simulate_observations(np.random.default_rng(cfg.seed), sc.truth_obs,
                                    cfg.sigma_arcsec, cfg.outlier_fraction,
                                    cfg.gross_error_arcsec)
t_obs, y_dec = sc.t_obs_s, y[1]
thr, n_draws = cfg.threshold_arcsec, cfg.n_draws
L_s = get_loss("sinusoidal")
idx = draw_samples(np.random.default_rng(1), len(t_obs), model.n_params, n_draws)  # step 1

A = model.design(t_obs)
best = None
for k in range(n_draws):
    theta_k = np.linalg.solve(A[idx[k]], y_dec[idx[k]])  # step 2: exact solve
    e_k = y_dec - A @ theta_k
    J = L_s(e_k, thr).sum()  # step 3
    if best is None or J < best[0]:  # step 4 (strict: the first of equal costs)
        best = (J, e_k, theta_k)
J_best, e_best, theta_hyp = best
inl = np.abs(e_best) <= thr
w = np.where(inl, 1 - L_s(e_best, thr), 0.0)  # WRANSAC weights, "hypothesis" reading
theta_w = np.linalg.solve(A.T @ (w[:, None] * A), A.T @ (w * y_dec))  # step 5, weighted

lib = wransac_linear(model, t_obs, y_dec, threshold=thr, n_hypotheses=n_draws,
                     rng=np.random.default_rng(0), samples=idx)
print(f"{is_bad[1].sum()} gross errors in this series; best cost J = {J_best:.3f}; "
      f"{inl.sum()} inliers, none a gross error: {not np.any(inl & is_bad[1])}")
np.testing.assert_allclose(lib.params, theta_w, rtol=1e-8, atol=1e-8)
print("step-by-step WRANSAC == library engine (same samples) ✔")

# %% [markdown]
# The RANSAC refit on the same data and samples, and the three predictions 72 min ahead:

# %%
ran = ransac_linear(model, t_obs, y_dec, threshold=thr, n_hypotheses=n_draws,
                    rng=np.random.default_rng(0), samples=idx)
t72 = np.array([t_obs[-1] + 72 * 60.0])
truth72 = sc.truth_pred[1][-1]
for name, th in (("best 4-point hypothesis", theta_hyp), ("RANSAC (OLS refit)", ran.params),
                 ("WRANSAC (weighted refit)", lib.params)):
    print(f"{name:26s}: Dec error at +72 min = {predict_linear(model, th, t72)[0] - truth72:+7.2f}″")

# %% [markdown]
# ### 4.7 What the theory bounds: Gauss–Markov and Cramér–Rao
#
# Without gross errors, $y = A\theta + \varepsilon$ with independent $\varepsilon_i$ of variance
# $\sigma^2$. Among *linear unbiased* predictors of $a(t)^\top\theta$, OLS on the inliers has
# the smallest variance (**Gauss–Markov** [4]),
# $\sigma^2_\text{pred}(t) = \sigma^2\, a(t)^\top (A_\mathcal{I}^\top A_\mathcal{I})^{-1} a(t)$;
# with Gaussian noise it attains the **Cramér–Rao** bound [5] for any unbiased predictor.
#
# What this covers. Gauss–Markov is about $\hat\theta = Cy$ with $C$ fixed in advance; WRANSAC's
# weights are computed from the same data, so its refit is non-linear and Gauss–Markov says
# nothing about it. Cramér–Rao does apply (its weights are even functions of the residuals, so
# with symmetric noise it is unbiased), but the bound is that of an estimator that *knows* the
# inliers — the "ideal" reference. RANSAC and WRANSAC both sit above it; which sits closer is
# an empirical question (section 5).
#
# With Student-t noise ($\nu$ dof, same $\sigma$) the bound lies *below* the OLS variance (by
# how much is exercise 1): down-weighting the tails *can* help. The extrapolation leverage:

# %%
all_in = np.ones(len(t_obs), bool)
gm = W.gauss_markov(t_obs, np.r_[t_obs[-1], sc.t_pred_s], all_in, cfg.sigma_arcsec)
eff3 = W.student_t_efficiency(cfg.student_nu)
display(Markdown(
    f"With all {len(t_obs)} points inliers and σ = {cfg.sigma_arcsec:g}″, the OLS prediction "
    f"spread is {gm[0]:.2f}″ at the last observation and {gm[-1]:.1f}″ at +72 min: the noise "
    f"is amplified {gm[-1] / gm[0]:.0f}× by extrapolation, so any information a weighting "
    f"throws away is amplified as much. For Student-t noise with ν = {cfg.student_nu:g}, the "
    f"Cramér–Rao bound is {eff3:.2f}× the OLS variance."))
assert 10 < gm[-1] / gm[0] < 30

# %% [markdown]
# ## 5 · Reproduction
#
# We run the experiment with `N_RUNS` **paired runs**: in every run, every method sees the same
# noisy data and the same minimal samples, so a difference between two methods is a difference
# of the methods. A second set of paired runs uses Student-t inlier noise (same σ) for the
# reading × noise table. The counts of this execution:

# %%
display(Markdown(
    f"{cfg.n_runs} paired runs (the paper ran {cfg.paper_runs}); the paper's \"max over its "
    f"{cfg.paper_runs} runs\" is judged as the median over the {cfg.n_runs // cfg.paper_runs} "
    f"disjoint blocks of {cfg.paper_runs} runs; Student-t noise with ν = {cfg.student_nu:g}; "
    f"{cfg.n_draws} hypotheses drawn per fit (U = {cfg.n_hypotheses} from eq. 2 is the minimum)."
    + (" **QUICK is on: fewer runs than `make repro`, statuses may differ.**" if QUICK else "")))

# %%
res = W.run_prediction_experiment(cfg, scenario=sc, runner=runner)
res_t = W.run_prediction_experiment(replace(cfg, inlier_noise="student_t"), scenario=sc,
                                    methods=W.STUDENT_METHODS, runner=runner)
print(f"{res.n_runs} paired runs × {len(res.methods)} methods; {res_t.n_runs} Student-t runs")

# %% [markdown]
# ### Table 1 — prediction errors, the paper's beside ours
#
# Statistics pool every prediction time within the horizon (30-s grid) over all runs; the last
# column is the reference line **ideal: OLS on the true inliers with the true model**. The paper
# does not say which coordinate Table 1 is; declination first, RA below. The paper's loop runs
# to an unstated maximum number of hypotheses; we draw the number printed above (see Explore).

# %%
T1 = ("sin", "lsq", "ransac", "wransac", "ideal")
table_paper = claims["wransac.table1"].paper["values"]
t1_dec = W.error_table(res, "dec", table_paper, T1)
t1_dec

# %%
W.error_table(res, "ra", table_paper, T1)

# %%
v72 = t1_dec.loc[(72, "variance")]
assert v72["lsq (ours)"] > 20 * v72["ransac (ours)"]
assert v72["ideal (ours)"] <= v72["ransac (ours)"] < 1.3 * v72["ideal (ours)"]
display(Markdown(
    f"**Reading.** As in the paper, least squares and the free sinusoid are thrown off by the "
    f"gross errors (72-min Dec variance {v72['lsq (ours)']:.0f} and {v72['sin (ours)']:.0f} ″²) "
    f"while RANSAC stays at {v72['ransac (ours)']:.0f} ″², close to the ideal reference "
    f"({v72['ideal (ours)']:.0f} ″²). Unlike the paper, WRANSAC's weighted refit is *less* "
    f"stable than RANSAC's ({v72['wransac (ours)']:.0f} ″²). Section 5's last two tables say "
    "why, and when the paper's ordering does appear."))

# %% [markdown]
# **Which noise level?** The paper adds "幅值为3″的高斯白噪声", Gaussian white noise of
# *amplitude* 3″. We read σ = 3″ (the claims use it). "Amplitude" could also mean the 3σ extent
# of the noise, σ = 1″. Both readings are measured here, on the same scenario, with the
# threshold kept at 3σ, at both of the paper's horizons (15 and 72 min), beside its RANSAC
# variances.

# %%
res_amp = W.run_prediction_experiment(replace(cfg, sigma_arcsec=cfg.sigma_arcsec / 3),
                                      scenario=sc, n_runs=N_SIDE,
                                      methods=("ransac", "wransac", "ideal"), runner=runner)
paper_v = {h: claims["wransac.table1"].paper["values"][str(h)]["variance"][T1.index("ransac")]
           for h in (15, 72)}
readings = {f"σ = {cfg.sigma_arcsec:g}″ (ours)": res,
            f"σ = {cfg.sigma_arcsec / 3:g}″ (3σ = 3″)": res_amp}
noise_tab = pd.DataFrame({
    name: {f"{co} {h} min": float(np.var(r.method_errors("ransac", co, h)))
           for h in (15, 72) for co in ("dec", "ra")} for name, r in readings.items()})
noise_tab["paper (coordinate unstated)"] = [paper_v[int(k.split()[1])] for k in noise_tab.index]
r_amp = W.variance_ratio(res_amp, "wransac", "ransac", "dec", 72)
grow_paper = paper_v[72] / paper_v[15]
grow_ours = noise_tab.loc["dec 72 min"].iloc[0] / noise_tab.loc["dec 15 min"].iloc[0]
sigma_match = {h: cfg.sigma_arcsec * np.sqrt(paper_v[h] / noise_tab.loc[f"dec {h} min"].iloc[0])
               for h in (15, 72)}
display(noise_tab.round(2))
display(Markdown(
    f"RANSAC's variance, ″². Matching the paper at 15 min would take σ ≈ {sigma_match[15]:.0f}″, "
    f"at 72 min σ ≈ {sigma_match[72]:.1f}″ — our σ = {cfg.sigma_arcsec:g}″ already matches the "
    f"72-min value. From 15 to 72 min the paper's variance grows ×{grow_paper:.1f}, white noise "
    f"extrapolated by our model ×{grow_ours:.0f}: no single σ matches both horizons, so the "
    "paper's short-horizon errors are not extrapolated white noise (its data or model must "
    "carry another error that does not grow with the horizon). The ordering does not depend "
    f"on the reading: at σ = {cfg.sigma_arcsec / 3:g}″ the 72-min WRANSAC/RANSAC ratio is "
    f"{r_amp[0]:.2f} [{r_amp[1]:.2f}, {r_amp[2]:.2f}] ({res_amp.n_runs} paired runs): the inlier "
    "noise, the threshold and so both refits scale with σ, while the gross errors stay far "
    "outside the threshold."))
assert noise_tab.loc["dec 15 min"].iloc[1] < noise_tab.loc["dec 15 min"].iloc[0] < paper_v[15]
assert grow_ours > 3 * grow_paper

# %% [markdown]
# ### Figs. 4–5 — the inliers' loss values and weights

# %%
W.plot_inlier_histograms(res)
plt.show()

# %% [markdown]
# ### Fig. 6 — the 72-min prediction against the true track (run 0)

# %%
W.plot_prediction(res, coord="dec")
plt.show()

# %% [markdown]
# ### Fig. 7 — prediction error over the 72 min (all runs)

# %%
W.plot_error_distribution(res, coord="dec", bound=claims["wransac.fig7"].paper["bound_arcsec"])
plt.show()

# %% [markdown]
# ### The central finding: reading × noise, paired variance ratios to RANSAC
#
# Ratio of pooled 72-min variances, WRANSAC (each reading) over RANSAC, with 95 % bootstrap
# intervals (runs resampled with replacement, the same resample for both methods). A ratio
# below 1 with its interval below 1 is the paper's ordering. The claims use the reading fixed
# beforehand (hypothesis weights, Gaussian noise); the other **five** cells are exploratory.

# %%
ratios = W.ratio_table({"gaussian": res, f"student_t ν={cfg.student_nu:g}": res_t})
ratios

# %%
W.plot_ratio_table(ratios, "dec")
plt.show()
flat = ratios.reset_index()
g = flat[(flat["noise"] == "gaussian") & (flat["coordinate"] == "dec")].set_index("method")
assert g.loc["WRANSAC, weights from hypothesis", "95 % lo"] > 1.0
paper_order = ratios[ratios["verdict"].str.startswith("paper")]
display(Markdown(
    "Cells with the paper's ordering (interval below 1): "
    + ("; ".join(f"{n}, {c}: {m}" for n, c, m in paper_order.index) or "none")
    + ". With Gaussian noise every reading is less stable than RANSAC — measured, not implied "
    "by the theory, which bounds both from below (4.7); with heavy-tailed noise the refit "
    "readings beat RANSAC. Note the ideal "
    "reference under Student-t noise: OLS on *all* true inliers is then not ideal, because "
    "RANSAC's threshold also trims the heaviest tails."))

# %% [markdown]
# ### The mechanism: the pull toward the hypothesis
#
# The "hypothesis" weights come from the residuals of the best 4-point fit, whose own 72-min
# prediction scatters widely; points agreeing with it get larger weights, so the refit leans
# toward it. Each dot is one run: hypothesis minus RANSAC (x), WRANSAC minus RANSAC (y), +72 min.

# %%
W.plot_pull(res)
plt.show()
pull = W.pull_table(res)
pull

# %%
p = pull.loc["dec"]
assert 0.3 < p["slope"] < 0.7 and p["corr"] > 0.8
display(Markdown(
    f"At +72 min the refit moves {100 * p['slope']:.0f} % of the way toward the hypothesis "
    f"(correlation {p['corr']:.2f}), whose own error spread is {p['hyp_sd']:.0f}″ against "
    f"RANSAC's {p['ransac_sd']:.0f}″. The same weights *shuffled* among the inliers cost "
    f"×{p['shuffled_ratio']:.2f} in variance; in place, ×{p['hypothesis_weights_ratio']:.2f}: "
    "most of the loss is the link between weights and hypothesis, not unequal weights as such."))

# %% [markdown]
# The bound and the measured variances side by side (72-min window, pooled; the bound uses each
# run's true inlier set), and the leverage curve:

# %%
gmt = W.gauss_markov_table(res)
r_ideal = W.variance_ratio(res, "ideal", "ransac", "dec", 72)
display(Markdown(
    f"Dec: bound {gmt.loc['dec', 'bound: mean σ_pred² (″²)']:.0f} ″², RANSAC "
    f"{gmt.loc['dec', 'ransac variance (″²)']:.1f} ″², WRANSAC "
    f"{gmt.loc['dec', 'wransac variance (″²)']:.0f} ″²; ideal/RANSAC variance ratio "
    f"{r_ideal[0]:.2f} [{r_ideal[1]:.2f}, {r_ideal[2]:.2f}]. RANSAC's refit is close to the "
    "bound but not at it (its inlier set is a random estimate of the true one); WRANSAC is far "
    "above it. The bound is the floor of both, not a ranking of the two."))
gmt

# %%
W.plot_leverage(res)
plt.show()

# %% [markdown]
# ### Is the 72-min window an Earth-shadow window?
#
# The paper quotes 72 min as the longest time in the Earth's shadow. Our window ends at the
# entry into the object's longest shadow pass of the season (conical shadow model [6]):

# %%
display(Markdown(
    f"Longest shadow pass: {sc.eclipse_min:.0f} min; {100 * np.mean(sc.shadow_pred > 0):.0f} % "
    "of the 72-min prediction window is in the Earth's shadow."))
W.plot_eclipse_season(sc)
plt.show()

# %% [markdown]
# ## 6 · Scorecard
#
# Each claim is judged by its criterion in `claims.toml`, whose history shows which criteria
# changed after results were seen (none of those changes can make a claim reproduced). *Checks*
# (a formula, our construction) pass or fail; *results* are the paper's findings. A central
# claim is scored *contradicted* if the family-wise paired interval of the WRANSAC/RANSAC
# variance ratio lies above 1 in both coordinates.

# %%
rows = W.evaluate(claims, res, corr)
scorecard = pd.DataFrame([r.to_dict() for r in rows])
scorecard[["claim", "kind", "central", "status", "ours", "note"]]

# %%
# NBVAL_CHECK_OUTPUT
for r in rows:
    print(f"{r.claim:22s} {r.kind:6s} {r.verdict}")

# %% [markdown]
# ## 7 · Explore
#
# Eq. (2) gives the minimum U — enough for *one* outlier-free 4-point sample, not for a
# *well-conditioned* one. The panel shows, for the chosen U, each run's worst 72-min Dec error
# for the methods you switch on, filtered from a precomputed sweep (the same draws for every U
# and method; `N_SIDE` runs per cell).

# %%
budget_err = W.budget_sweep(cfg, scenario=sc, budgets=W.BUDGETS, methods=W.BUDGET_METHODS,
                            n_runs=N_SIDE, runner=runner)
GROUPS = {"ransac": ("ransac", "msac"),
          "readings": ("wransac_hypothesis", "wransac_refit", "wransac_iterated"),
          "mest": ("huber_ransac", "cauchy_ransac"), "refs": ("lsq", "ideal")}


def draw_budget(U, ransac, readings, mest, refs):
    show = tuple(m for key, on in (("ransac", ransac), ("readings", readings), ("mest", mest),
                                   ("refs", refs)) if on for m in GROUPS[key])
    fig, ax = plt.subplots(figsize=(8, 4.5))
    fig.subplots_adjust(left=0.11, right=0.95, bottom=0.2, top=0.93)  # room for the labels
    W.plot_budget(budget_err, W.BUDGETS, W.BUDGET_METHODS, U, show, ax=ax)
    return fig


explore = panel(draw_budget, tight=False, U=dropdown("hypotheses U", list(W.BUDGETS), 3),
                ransac=toggle("RANSAC, MSAC", True), readings=toggle("WRANSAC readings", True),
                mest=toggle("M-estimators from RANSAC", False),
                refs=toggle("LSQ, ideal", True))

# %%
bt = W.budget_table(budget_err, W.BUDGETS, W.BUDGET_METHODS)
display(Markdown(
    f"With U = 3, RANSAC keeps the whole 72-min Dec prediction within 27″ in "
    f"{100 * bt.loc[3, 'ransac']:.0f} % of the runs; with U = 100, in "
    f"{100 * bt.loc[100, 'ransac']:.0f} %. The table gives every method and budget:"))
bt

# %% [markdown]
# ## 8 · Errata and deviations

# %%
lo_g, hi_g = cfg.gross_error_arcsec
errata = [
    ("eq. (6)", "$L_s = \\tfrac12\\cos(e/2t) + \\tfrac12$",
     "$\\tfrac12 - \\tfrac12\\cos(\\pi e/t)$: one of several readings with the stated properties "
     "(smoothstep is another, 4.3); the smallest edit of the printed form"),
    ("eq. (5), ref. [11]", "$L_M = \\lvert e\\rvert/t$, MSAC cited to a prediction paper",
     "kept as printed; MSAC is Torr & Zisserman [3], squared (`msac_squared`)"),
    ("eq. (1)", "independent draws (with replacement)",
     f"samples drawn without replacement; exact {p_paper_exact:.5f} vs eq. (1) "
     f"{success_probability(U, 3 / 80, 4):.5f} at the paper's setting (4.2)"),
    ("§3.3", "weights \"from the loss of the purified inlier set\", no formula",
     "$w = 1 - L_s(e)$, three readings of $e$ (4.6); the claims use the hypothesis residuals"),
    ("§4", "model with $m = 4$, never written", "$a\\sin\\omega t + b\\cos\\omega t + c + dt$, ω sidereal"),
    ("§4", f"U = {cfg.n_hypotheses} from eq. (2); loop to an unstated maximum",
     f"{cfg.n_draws} draws; U = {cfg.n_hypotheses} breaks down in many runs (Explore)"),
    ("§4", "\"an arbitrary space object\", real station data",
     f"NORAD {cfg.norad_id} from a real TLE, SGP4, the paper's station"),
    ("§4", "noise of \"amplitude 3″\"",
     f"σ = {cfg.sigma_arcsec:g}″; the 3σ = 3″ reading measured in section 5 (ordering unchanged)"),
    ("§4", f"ε = {cfg.outlier_ratio} outliers, magnitude unstated",
     f"{100 * cfg.outlier_fraction:g} % of points get ±[{lo_g:g}, {hi_g:g}]″ gross errors"),
    ("§4", f"{cfg.paper_runs} runs, methods compared on different draws",
     f"{cfg.n_runs} paired runs (common random numbers), bootstrap intervals"),
    ("Table 1", "coordinate unstated", "Dec and RA (RA as drift against the sidereal rotation)"),
    ("§4", "a stability gain of WRANSAC over RANSAC",
     "not implied by the theory (4.7) and measured with the opposite sign (section 5)"),
    ("§2", "correlations for an unstated object and span",
     f"{CORR_HOURS:g} h of our object; RA wrapped to [0, 360)"),
]
display(Markdown("| where | the paper | what we do, and the measured consequence |\n|---|---|---|\n"
                 + "\n".join(f"| {a} | {b} | {c} |" for a, b, c in errata)))

# %% [markdown]
# ## 9 · Beyond the paper
#
# ### Threshold sensitivity
#
# The paper argues that $L_s$ makes RANSAC less sensitive to the threshold. WRANSAC changes the
# scoring loss *and* the refit, so the study keeps them apart: each loss picks its hypothesis
# and is refitted by the same OLS; the last column adds WRANSAC's weighted refit. Median RMS
# 72-min Dec error versus $t/\sigma$ (paired draws):

# %%
sens = W.threshold_sensitivity(cfg, scenario=sc, n_runs=N_SIDE // 2, runner=runner)
W.plot_threshold_sensitivity(sens)
plt.show()
sens

# %%
k3 = cfg.threshold_sigmas
row = sens.loc[k3]
zo, ls_ols, wr = row["zero_one + OLS refit"], row["sinusoidal + OLS refit"], row[W.SENSITIVITY_WRANSAC]
spread = sens.max() / sens.min()
low = sens.loc[sens.index <= 4]
best_low = low[[c for c in low.columns if "OLS" in c]].idxmin(axis=1)
display(Markdown(
    f"**Reading.** At t = {k3:g}σ the 0-1 loss gives {zo:.2f}″, the sinusoidal loss with the "
    f"same OLS refit {ls_ols:.2f}″ and WRANSAC (sinusoidal loss + weighted refit) {wr:.2f}″: of "
    f"WRANSAC's gap of {wr - zo:.2f}″ to RANSAC, {ls_ols - zo:.2f}″ comes from the scoring loss "
    f"and {wr - ls_ols:.2f}″ from the weighted refit. Smallest error with an OLS refit, per "
    "t/σ ≤ 4: " + ", ".join(f"{k:g}σ {c.split(' +')[0]}" for k, c in best_low.items())
    + f"; WRANSAC is the worst column at {int((low.idxmax(axis=1) == W.SENSITIVITY_WRANSAC).sum())} "
    f"of these {len(low)} thresholds. "
    "Sensitivity to the threshold (largest over smallest median error across t/σ): "
    + ", ".join(f"{c} ×{v:.1f}" for c, v in spread.items())
    + ". The paper's argument — the smooth loss makes RANSAC less sensitive to t — is "
    + ("supported" if spread["sinusoidal + OLS refit"] < 0.9 * spread["zero_one + OLS refit"]
       else "not supported (within 10 %, indistinguishable)"
       if spread["sinusoidal + OLS refit"] <= 1.1 * spread["zero_one + OLS refit"]
       else "contradicted") + " by the scoring loss alone in this scenario, and WRANSAC's "
    "weighted refit adds error at every threshold."
    if (low[W.SENSITIVITY_WRANSAC] > low["sinusoidal + OLS refit"]).all() else "."))

# %% [markdown]
# ### Generalisation: other objects, other stations
#
# More objects from the `sgp4` verification TLEs [7], each seen from a station that has it well
# above the horizon up to its longest shadow pass — geostationary, inclined geostationary and
# drifting — with M-estimators (Huber, Cauchy [8]) started from the RANSAC fit. The table gives
# the worst |error| (RA or Dec) within 72 min over the runs and the median over runs of each
# run's worst error; each case has a seed of its own.

# %%
gen = W.generalisation(cfg, n_runs=N_SIDE, runner=runner)
gen[f"NORAD {cfg.norad_id} (main), {cfg.station[0]:g}°, {cfg.station[1]:g}°E"] = res
worst = W.worst_error_table(gen)
cols = [m for m in W.GENERALISATION_METHODS if m in worst["worst"].columns]
worst = worst.loc[:, [(s, m) for s in ("worst", "median run") for m in cols]]
worst

# %%
W.plot_generalisation(worst)
plt.show()
display(Markdown("**Recommendation.** " + W.recommendation(worst)))

# %% [markdown]
# ### The model, not the estimator: predicting from a fitted orbit
#
# For the drifting objects the worst error above is the sinusoid model's, whatever the
# estimator. The alternative the paper never tries: fit a **physical orbit** to the same 2 h of
# angles. `eotrack.astro.fit_orbit` starts from Gauss's angles-only initial orbit [10] on a few
# triplets spread over the arc (the one of least robust cost on all data is kept, so a gross
# error in one triplet does not spoil the start), then fits the state vector to all angles by
# least squares with a Cauchy loss, two-body dynamics (J2: `dynamics="j2"`). In every run the
# orbit fit and the sinusoid predictors see the *same* angles and gross errors.
#
# **Criterion, written and committed before the first run** (`W.ORBIT_CRITERION`). The
# comparison and the same criterion over the five independent root seeds of `--seeds 5` take
# about two minutes, so `make repro` computes them (`W.orbit_comparison`,
# `W.orbit_seed_study`) into `papers_repro/wransac/orbit_study.json` and this notebook reads
# that file — the numbers below are the committed full run's, whatever `QUICK` says.

# %%
display(Markdown(f"> {W.ORBIT_CRITERION}"))
orbit, orbit_seeds, orbit_runs = W.read_orbit_study(papers_repro_dir() / "wransac"
                                                    / W.ORBIT_STUDY_FILE)
orbit_ok, orbit_crit = W.orbit_criterion(orbit)
print(f"{orbit_runs} paired runs per case (committed run); seed study: "
      f"{orbit_seeds['root seed'].nunique()} root seeds × {orbit_seeds['case'].nunique()} "
      "drifting cases")
orbit.drop(columns=["p90 run"], level=0).round(1)

# %%
W.plot_generalisation(orbit, title="Orbit fit vs sinusoid predictors")
plt.show()
display(Markdown(W.orbit_text(orbit, orbit_seeds, sigma_arcsec=cfg.sigma_arcsec)))
orbit_crit.round(2)

# %% [markdown]
# The criterion over the independent root seeds (each row: one seed's 50-run comparison on a
# drifting case):

# %%
orbit_seeds.round(2)

# %%
# NBVAL_CHECK_OUTPUT
print("orbit-fit criterion (drifting cases, ≥ 5× better), committed run:",
      "met" if orbit_ok else "not met")
print("seeds meeting it, per drifting case:", {k.split(" (")[0]: f"{int(g.sum())}/{len(g)}"
                                              for k, g in orbit_seeds.groupby("case")["met"]})

# %% [markdown]
# Why: on noise-free angles, which model limits the prediction? On the two drifting cases, the
# same orbit fit and the sinusoid model (least squares on the same noise-free 2 h, the "ideal"
# reference without noise) against the SGP4 track over the 72 min:

# %%
from eotrack.astro import fit_orbit


def noise_free_errors(changes: dict) -> dict:
    """Worst 72-min |error| (″) of the orbit fit and of the sinusoid model on noise-free angles."""
    c = replace(cfg, **changes)
    s_c = W.make_scenario(c)
    inp = W.orbit_inputs(s_c, c.station)
    f0 = fit_orbit(s_c.t_obs_s, W.absolute_ra(s_c.truth_obs[0], s_c.t_obs_s, inp["ra0_deg"]),
                   s_c.truth_obs[1] / 3600, inp["site_obs"], sigma_arcsec=c.sigma_arcsec)
    ra_p, dec_p = f0.predict(s_c.t_pred_s, inp["site_pred"])
    ra_true = W.absolute_ra(s_c.truth_pred[0], s_c.t_pred_s, inp["ra0_deg"])
    orbit_err = max(np.abs(((ra_p - ra_true + 180) % 360 - 180) * 3600).max(),
                    np.abs(dec_p * 3600 - s_c.truth_pred[1]).max())
    m = SinusoidDrift(t_ref_s=s_c.t_obs_s.mean())
    sin_err = max(np.abs(predict_linear(m, fit_linear(m, s_c.t_obs_s, s_c.truth_obs[ci]),
                                        s_c.t_pred_s) - s_c.truth_pred[ci]).max()
                  for ci in range(2))
    return {"orbit fit (″)": orbit_err, "sinusoid model (″)": sin_err}


drift_cases = {k: v for k, v in W.GENERALISATION_CASES.items() if "drifting" in k}
noise_free = pd.DataFrame({k.split(" (")[0]: noise_free_errors(v)
                           for k, v in drift_cases.items()}).T
display(noise_free.round(2))
med_orbit = orbit.loc[list(drift_cases), ("median run", "orbit")]
display(Markdown(
    "Noise-free, the orbit fit predicts the SGP4 track of the drifting objects to "
    + " and ".join(f"{v:.2f}″" for v in noise_free["orbit fit (″)"])
    + " over 72 min, while the sinusoid model is off by "
    + " and ".join(f"{v:.0f}″" for v in noise_free["sinusoid model (″)"])
    + f" even without noise: the sinusoid model fails on a drifting object, the orbit does "
    f"not. With σ = {cfg.sigma_arcsec:g}″ the orbit fit's median worst error is "
    + " and ".join(f"{v:.0f}″" for v in med_orbit)
    + ": what remains is the noise propagated through an angles-only fit of a short arc (the "
    "range is seen only through the station's parallax)."))
assert (noise_free["orbit fit (″)"] < 2.0).all()
assert (noise_free["sinusoid model (″)"] > 10 * noise_free["orbit fit (″)"]).all()

# %% [markdown]
# **For a practitioner**: predict from a robustly fitted orbit. With a sinusoid model, spend the
# hypothesis budget, refit by least squares on the inliers, polish with an M-estimator from
# RANSAC; down-weight only for heavy-tailed noise, never with 4-point-hypothesis weights.

# %% [markdown]
# ## 10 · Key points
#
# * Eq. (2) sizes RANSAC for one *outlier-free* sample, not a *usable* one: budget tens to
#   hundreds of hypotheses.
# * Compare estimators on common random numbers, with intervals; 20 unpaired runs can order two
#   methods either way.
# * OLS on the *true* inliers attains the Cramér–Rao bound under Gaussian noise — a floor under
#   every unbiased predictor; no theorem here orders RANSAC and WRANSAC, the ordering is measured.
# * WRANSAC's hypothesis weights pull the refit toward a noisy 4-point fit; extrapolation
#   amplifies the pull.
# * Down-weighting pays off only with heavy-tailed inlier noise.
# * The printed loss (6) is an erratum; several smooth readings have the stated properties.
# * For a drifting object the model, not the estimator, limits prediction; a robustly fitted
#   orbit removes that limit and leaves the noise.

# %% [markdown]
# ## 11 · Exercises
#
# Check an answer with `check("wransac.k", answer)`; worked solutions are in
# `notebooks/solutions/01_wransac_solutions.ipynb`.

# %%
# NBVAL_CHECK_OUTPUT
print(exercise_ids("wransac"))

# %% [markdown]
# **Exercise 1 (derivation).** For Student-t inlier noise with ν degrees of freedom and
# standard deviation σ, derive the Cramér–Rao bound on the variance of an unbiased predictor as
# a fraction of the OLS (Gauss–Markov) variance, as a function of ν (4.7 prints only its value
# at ν = 3). At what ν — a real number, not rounded — is the fraction 0.9? (Fisher information
# of a t location with scale $s$: $(\nu+1)/((\nu+3)s^2)$.)

# %%
answer = None  # your ν here
if answer is not None:
    display(check("wransac.1", answer))

# %% [markdown]
# **Exercise 2 (computation).** Clouds hide the last 20 of the 80 observations of the main
# scenario: only the first 60 are inliers (σ = 3″). With `W.gauss_markov`, compute the standard
# deviation (″) of the OLS prediction 45 min after the last of the 80 observation times.

# %%
answer = None  # e.g. W.gauss_markov(sc.t_obs_s, ..., ..., 3.0)[0]
if answer is not None:
    display(check("wransac.2", answer))

# %% [markdown]
# **Exercise 3 (exploration).** With `QUICK = False` (the checker uses the full sweep of
# 100 runs), from the Explore sweep `budget_err` (runs × budgets × methods × times), compute the fraction (0–1) of runs in which WRANSAC with the hypothesis weights
# (`"wransac_hypothesis"`), with U = 10, keeps its whole 72-min Dec prediction within **20″**.

# %%
answer = None  # a fraction between 0 and 1
if answer is not None:
    display(check("wransac.3", answer))

# %% [markdown]
# **Exercise 4 (critique).** The paper ordered WRANSAC and RANSAC from 20 runs, each method on
# its own draws. Take the true 72-min Dec variance ratio WRANSAC/RANSAC to be the one our paired
# runs measure (`W.variance_ratio(res, "wransac", "ransac", "dec", 72)`, with `QUICK = False`:
# the checker uses the 300 paired runs), and model each
# method's 20-run variance estimate as $\sigma^2\chi^2_{19}/19$, independent between the two.
# With what probability do 20 unpaired runs show WRANSAC's variance *below* RANSAC's?

# %%
answer = None  # a probability
if answer is not None:
    display(check("wransac.4", answer))

# %% [markdown]
# **Exercise 5 (the weighted refit).** Write `wls(A, y, w)` returning the θ that minimises
# $\sum_i w_i (y_i - A_i\theta)^2$ (some $w_i$ are zero).

# %%
wls = None  # def wls(A, y, w): ...
if wls is not None:
    display(check("wransac.5", wls))

# %% [markdown]
# ## Closing note (issue 24)
#
# The expert review found 8 defects (a confounded threshold study, an overclaimed bound, a
# false "only reading", an eq. (1) check that could not fail, unflagged readings, hand-typed
# numbers, three exercises answered above them, prose over length): all 8 fixed. The
# independent review of that version found **12** (0 high, 7 medium, 5 low): **12 fixed, 0
# left** — the orbit text's explanation replaced by the measured tail, bias and paired
# per-run ratio (1); the criterion over five root seeds, fragile cases marked (2); the
# noise-free check on the drifting cases (3) and "about 2×" on the others (4); the J2 fit's
# crash and silent unit errors (5, 6: library and tests); exercise 1 re-posed (7); exercises
# 3–4 need `QUICK = False` (8); both horizons of the noise level (9); the orbit figures (10);
# time per fit as a ratio (11); the J2 pole and Gauss start stated (12).

# %% [markdown]
# ## 12 · References
#
# 1. Yan L. et al. *Opto-Electronic Engineering* 46(11):180540, 2019. doi:10.12086/oe.2019.180540
# 2. Fischler M. A., Bolles R. C. Random sample consensus. *Comm. ACM* 24(6):381–395, 1981.
#    doi:10.1145/358669.358692
# 3. Torr P. H. S., Zisserman A. MLESAC. *Computer Vision and Image Understanding* 78(1):138–156,
#    2000. doi:10.1006/cviu.1999.0832
# 4. Kariya T., Kurata H. *Generalized Least Squares*, ch. 2. Wiley, 2004. doi:10.1002/0470866993
# 5. Kay S. M. *Fundamentals of Statistical Signal Processing I: Estimation Theory*, ch. 3–4.
#    Prentice Hall, 1993.
# 6. Montenbruck O., Gill E. *Satellite Orbits*, §3.4.2. Springer, 2000. doi:10.1007/978-3-642-58351-3
# 7. Vallado D. A. et al. Revisiting Spacetrack Report #3. AIAA 2006-6753. doi:10.2514/6.2006-6753
# 8. Huber P. J. *Ann. Math. Stat.* 35(1):73–101, 1964. doi:10.1214/aoms/1177703732; Holland P. W.,
#    Welsch R. E. *Comm. Stat. Theory Methods* 6(9):813–827, 1977. doi:10.1080/03610927708827533
# 9. Efron B., Tibshirani R. J. *An Introduction to the Bootstrap*. Chapman & Hall, 1993.
# 10. Curtis H. D. *Orbital Mechanics for Engineering Students*, 3rd ed., Algorithms 3.3–3.4, 5.5.
#     Butterworth-Heinemann, 2014; Vallado D. A. *Fundamentals of Astrodynamics and
#     Applications*, 4th ed., Algorithm 52. Microcosm, 2013.
# 11. Cen M. et al. Position prediction method for satellite tracking based on error-space
#     estimate. *Opto-Electronic Engineering* 34(6):15–19, 2007 (the paper's ref. [11]).

# %%
from eotrack.notebook import lesson_footer

lesson_footer("01")
