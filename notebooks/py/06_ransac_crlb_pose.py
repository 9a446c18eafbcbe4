# ---
# jupyter:
#   kernelspec:
#     display_name: Python 3 (ipykernel)
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 06 · Robust pose of a non-cooperative spacecraft: RANSAC and CRLB feature selection
#
# **Paper.** Ning Mingfeng, Zhang Shijie, Zhang Hanmo. *Robust visual navigation of
# non-cooperative spacecraft with active feature selection* (基於主動特征選擇的非合作航天器魯棒視覺
# 導航方法研究). Aerospace Shanghai **33**(6):136–141, 2016.
# [DOI 10.19328/j.cnki.1006-1630.2016.06.020](https://doi.org/10.19328/j.cnki.1006-1630.2016.06.020)
#
# **What the paper does.** A chaser spacecraft estimates the pose of an unmarked target from
# one camera and feature points of known 3-D position. The paper (i) removes matching gross
# errors with RANSAC (6 random points, a linear pose, an inlier test), then (ii) scores point
# sets by the Cramér–Rao lower bound (CRLB) of the pose and keeps only the inliers that lower
# it, claiming about a third fewer points *and* a more accurate pose (Figs. 4–6).
#
# **The lesson in one line.** Fisher information only adds up, so the exact CRLB can only fall
# when a point is added: read literally, the selection keeps every inlier. Something else —
# here, a noise level estimated from the data — must be doing the work.
#
# ## Learning objectives
# After this notebook you can
# 1. write the pinhole model of a pose and its Jacobian, and derive the Fisher information and
#    CRLB of a pose from N image points (and handle the quaternion's unit-norm constraint);
# 2. run RANSAC on a pose problem by hand and recognise the planar two-fold ("flip") ambiguity;
# 3. prove, and show numerically, that adding a measurement can never raise the CRLB;
# 4. judge a paper's claim with a reading fixed *before* the run, and correct the exploratory
#    comparisons for their number (Holm).
#
# **Prerequisites.** Notebook 01 (RANSAC, the number of draws); least squares and the Gaussian
# likelihood; 3-D rotations (rotation matrix, quaternion, small-angle vector).

# %%
import json

from eotrack.notebook import lesson_footer, lesson_header
from eotrack.repro import papers_repro_dir, read_stability
from IPython.display import Markdown, display

lesson_header("06")
_card = json.loads((papers_repro_dir() / "ransac_crlb_pose" / "scorecard.json").read_text())
display(Markdown(f"**Scorecard (last `make repro`):** {_card['summary']} — recomputed below "
                 "in *Scorecard* with the same configuration."))

# %% [markdown]
# ## Setup

# %%
import time

import numpy as np
import pandas as pd
from eotrack.exercises import check, get_checker
from eotrack.experiments import ransac_crlb_pose as E
from eotrack.montecarlo import TrialRunner
from eotrack.notebook import dropdown, float_slider, panel, setup_notebook, toggle, versions
from eotrack.pose import (
    RansacConfig,
    constrained_crlb,
    dlt_pose,
    finite_difference_jacobian,
    minimal_to_quaternion_jacobian,
    pose_crlb,
    pose_fisher_information,
    pose_fisher_information_quaternion,
    project_points,
    projection_jacobian,
    quaternion_from_matrix,
    ransac_pose_dlt,
    ransac_pose_opencv,
    reprojection_errors,
    rotation_error_deg,
    scaled_crlb_weights,
    score_shares,
)
from eotrack.repro import load_claims, scorecard
from eotrack.robust import min_samples
from scipy import stats

setup_notebook()

# %% tags=["parameters"]
N_RUNS = 300         # Figs. 4-5: the paper's 300 runs (make repro: 300)
N_RUNS_COUNTS = 80   # Fig. 6: the paper's 80 runs (make repro: 80)
N_MC = 200           # efficiency Monte Carlo per noise level (make repro: 200)
N_BUDGET = 30        # scenes for budgeted selection (make repro: 30)
N_ELLIPSOID = 300    # ML draws for the CRLB ellipsoid (notebook only)
QUICK = False        # True: 60 / 30 runs, as reproduce(quick=True)

# %%
print(versions())
claims = load_claims("ransac_crlb_pose")
sc = E.Scenario()
st = E.Settings(n_runs=N_RUNS, n_runs_counts=N_RUNS_COUNTS, n_mc_efficiency=N_MC,
                n_runs_budget=N_BUDGET)
runner = TrialRunner(progress=False)

# %% [markdown]
# ## Notation
#
# | paper | code | meaning | unit |
# |---|---|---|---|
# | $r_t$ | `points`, `X` | feature point in the target body frame | m |
# | $r_c$ | `R @ X + t` | the point in the camera frame, $r_c = C_{ct}(q)\,r_t + t$ | m |
# | $C_{ct}$, $q=(q_0,\dots,q_3)$ | `R`, `quaternion_from_matrix(R)` | attitude target → camera (scalar-first) | – |
# | $t=(t_1,t_2,t_3)$ | `t` | target centre of mass in the camera frame | m |
# | $f$ | `Scenario.focal_m`, `K` | focal length; `K = diag(f, f, 1)` with $f$ in mm | m |
# | $(\mu,\nu)$ | `pixels`, `u` | image coordinates (mm on the focal plane) | mm |
# | $\sigma^2$, $\sigma_i^2$ | `sigma_px**2` | noise variance of each image coordinate (of point $i$); the library calls every image unit "px" — here the image unit is mm | mm² |
# | $N$ | `len(points)` | number of feature points | – |
# | $\theta$ | `(t, q)` (7) or `(δt, δθ)` (6) | pose parameters | m, rad |
# | $G_i$ | `projection_jacobian(...)` | $\partial u_i/\partial\theta$, 2×6 | mm/m, mm/rad |
# | $J$ | `pose_fisher_information(...)` | Fisher information (6×6, $\delta t$ then $\delta\theta$) | 1/m², 1/(m·rad), 1/rad² |
# | CRLB $=J^{-1}$ | `pose_crlb(...)`, `constrained_crlb(...)` | lower bound on the covariance | m², m·rad, rad² |
# | score | `set_score(...)` | weighted sum of the 7 CRLB values of a point set | m² + 1 (unit weights; see below) |

# %% [markdown]
# ## The method, step by step
#
# ### Frames and camera model (§1, eqs. 1–2)
#
# The camera frame has $z$ along the optical axis and $x, y$ along the image axes; the target
# frame sits at the target's centre of mass. A target point maps to the camera frame and the
# image as
#
# $$ r_c = C_{ct}(q)\, r_t + t \quad (1), \qquad
#    \begin{pmatrix}\mu\\ \nu\end{pmatrix} = \frac{f}{z_c}\begin{pmatrix} x_c\\ y_c
#    \end{pmatrix} \quad (2)$$
#
# i.e. $u = K r_c / z_c$. The scene of §3 is drawn below from the library's own scene object:
# camera at the origin, target 10 m away, 160–180 feature points on a 2 m × 2 m plane 1 m in
# front of the target's centre (the printed "22 m²" read as 2 m × 2 m), 10 % of them gross
# errors.

# %%
scene = E.make_scene(np.random.default_rng(1), sc)
ax = E.draw_scene_3d(scene)

# %%
n = len(scene.points)
u0 = project_points(scene.points, sc.R, sc.t, sc.K)
print(f"{n} points, {scene.gross.sum()} gross errors; image extent (mm): "
      f"{np.ptp(u0, axis=0).round(2)}; noise σ (mm): {np.unique(scene.sigma.round(3))}")
# check: with no noise the linear (DLT) pose recovers the truth exactly
R_dlt, t_dlt = dlt_pose(scene.points, u0, sc.K)
assert np.allclose(R_dlt, sc.R, atol=1e-9) and np.allclose(t_dlt, sc.t, atol=1e-9)

# %% [markdown]
# Note the scale: the whole target covers about 2 mm of the focal plane, while a variance of
# 0.02 mm² is a standard deviation of 0.14 mm. With the values as printed this is a very noisy
# problem (see *Errata*).
#
# ### RANSAC feature selection (§2.2) — one trial by hand
#
# 1. Draw 6 points at random and estimate the pose. All features lie on one plane, where the
#    3×4 DLT is rank-deficient, so the linear solution is the plane homography
#    $\hat x \sim \lambda[R e_1,\ R e_2,\ R c + t]\,(a, b, 1)^\top$ (Hartley-normalised).
# 2. Test every point: inlier if its reprojection error is below a threshold (not given; ours
#    $\sqrt{\chi^2_{2,0.99}\,\sigma^2_{\max}}$, in image mm).
# 3. Accept the model when enough points are inliers (ours: 60 %); re-estimate the pose from all
#    its inliers.
# 4. Otherwise draw again; 5. after a preset number of draws report failure — the image is
#    discarded (a result, not an exception).

# %%
rng = np.random.default_rng(2)
cfg = st.ransac_config(sc)
res = ransac_pose_dlt(scene.points, scene.pixels, sc.K, rng, cfg)
rows = {"paper: 6-point DLT RANSAC (+refit)": res}
for label, kw in (("cv2.solvePnPRansac (SQPnP) + LM", {"disambiguate": False}),
                  ("… + planar disambiguation (default)", {})):
    rows[label] = ransac_pose_opencv(scene.points, scene.pixels, sc.K,
                                     threshold_px=cfg.inlier_threshold_px, **kw)
pd.DataFrame({k: {"inliers": r.n_inliers,
                  "gross errors kept": int((r.inliers & scene.gross).sum()),
                  "position error (m)": np.linalg.norm(r.t - sc.t),
                  "attitude error (deg)": rotation_error_deg(r.R, sc.R)}
              for k, r in rows.items()}).T

# %% [markdown]
# The attitude errors can be tens of degrees, yet the data are not mis-fitted: a small plane
# seen from 10 m through this much noise has two nearly equally good poses (the planar "flip"
# ambiguity). The reprojection cost of the estimate against that of the truth, on the same
# clean inliers:

# %%
inl = res.inliers & ~scene.gross
cost = {name: np.sum(reprojection_errors(scene.points[inl], scene.pixels[inl], R, t, sc.K) ** 2)
        for name, (R, t) in (("estimate", (res.R, res.t)), ("truth", (sc.R, sc.t)))}
print({k: round(float(v), 2) for k, v in cost.items()}, "(mm²)")
# how many draws are needed? U = log(1 − P) / log(1 − (1 − ε)^6)  (notebook 01)
print("draws for a clean 6-point sample, 99 % confidence, ε = 10 %:",
      min_samples(0.99, 0.1, 6), f"(we allow {cfg.max_draws})")
junk = np.random.default_rng(3).uniform(-3, 3, scene.pixels.shape)
fail = ransac_pose_dlt(scene.points, junk, sc.K, rng,
                       RansacConfig.paper(inlier_threshold_px=0.05, max_draws=100))
print("pure-noise image:", fail.success, "—", fail.message)
assert not fail.success

# %% [markdown]
# ### The CRLB of the pose (§2.3, eqs. 3–5; eqs. 6–19 re-derived)
#
# The paper's eqs. (3)–(4): for any unbiased estimator of
# $\theta = (t_1,t_2,t_3,q_0,q_1,q_2,q_3)$ (defined in the text)
#
# $$ \mathrm{cov}(\hat\theta) \succeq J^{-1} \quad (3), \qquad
#    J = -E\!\left[\frac{\partial^2 \ln p(x;\theta)}{\partial\theta\,\partial\theta^\top}\right]
#    \quad (4),$$
#
# and eq. (5) is the likelihood $p(x;\theta)$ of white Gaussian noise $N(0,\sigma^2)$ on every
# image coordinate. In the original (6) is $\ln p$, (7) its first derivatives, (8)–(17) the
# blocks $E_{t_1t_1}, E_{t_1t_2}, \dots, E_{qq}$ and (18)–(19) the bound and $M_\theta$; they were
# images, except eq. (9), which survives as text: $E_{t_1t_2} = d_{t_1t_2} = 0$. Re-derived:
# with independent noise $N(0, \sigma_i^2)$ on both coordinates of point $i$,
# $\ln p = -\tfrac12\sum_i |u_i - \pi_i(\theta)|^2/\sigma_i^2 + $ const, so
#
# $$ J(\theta) = \sum_{i=1}^N \frac{G_i^\top G_i}{\sigma_i^2}, \qquad
#    G_i = \frac{\partial u_i}{\partial\theta}, \qquad
#    \frac{\partial u}{\partial r_c} = \frac{K_{1:2} - u\,e_3^\top}{z_c}. $$
#
# **Minimal (6-parameter) form.** Perturb $t \leftarrow t + \delta t$ and
# $R \leftarrow \exp([\delta\theta]_\times) R$: then $\partial r_c/\partial\delta t = I$ and
# $\partial r_c/\partial\delta\theta = -[R\,r_t]_\times$.
#
# **The paper's 7 parameters.** With $C = C(q/|q|)$ the information is singular along
# $(0, q)$ — scaling $q$ changes nothing. The constrained CRLB (Stoica & Ng [5]) projects onto
# the tangent space of $|q| = 1$: $C_7 = U (U^\top J_7 U)^{-1} U^\top$. It must equal the
# minimal form mapped by $\delta q = \tfrac12 (0, \delta\theta) \otimes q$:
# $C_7 = E\,C_6\,E^\top$. The cell checks the Jacobian against finite differences, the
# singular direction, and the two forms against each other.

# %%
X_in, s_in = scene.points[~scene.gross], scene.sigma[~scene.gross]
G = projection_jacobian(X_in, sc.R, sc.t, sc.K)
G_fd = finite_difference_jacobian(X_in, sc.R, sc.t, sc.K, step=1e-6)
assert np.allclose(G, G_fd, atol=1e-6)
J6 = pose_fisher_information(X_in, sc.R, sc.t, sc.K, s_in)
assert np.allclose(J6, np.einsum("nki,nkj->ij", G / s_in[:, None, None],
                                 G / s_in[:, None, None]))
q = quaternion_from_matrix(sc.R)
J7 = pose_fisher_information_quaternion(X_in, q, sc.t, sc.K, s_in)
assert np.allclose(J7 @ np.r_[0, 0, 0, q], 0, atol=1e-8 * np.abs(J7).max())
C7 = constrained_crlb(J7, q)
C6 = pose_crlb(X_in, sc.R, sc.t, sc.K, s_in)
Emap = minimal_to_quaternion_jacobian(q)
assert np.allclose(C7, Emap @ C6 @ Emap.T, rtol=1e-6, atol=1e-14)
# eq. (9), the one block that survives as text: E_t1t2 = 0 (exactly, for a K = diag(f, f, 1))
print("eq. (9): J6[t1, t2] =", J6[0, 1], "; J7[t1, t2] =", J7[0, 1])
assert J6[0, 1] == 0.0 and J7[0, 1] == 0.0
pd.DataFrame({"√CRLB": np.sqrt(np.diag(C7))},
             index=["t1 (m)", "t2 (m)", "t3 (m)", "q0", "q1", "q2", "q3"]).T

# %% [markdown]
# **The CRLB ellipsoid of one pose.** The bound is a covariance, so it can be drawn: the 2-σ
# ellipsoid $\{\delta\theta : \delta\theta^\top C^{-1}\delta\theta \le 4\}$ of the attitude
# block, for a fixed geometry of 170 clean points at the printed noise, with the errors of the
# maximum-likelihood (weighted Levenberg–Marquardt) pose over repeated noise draws. An
# efficient estimator puts $P(\chi^2_3 \le 4)$ of its draws inside.

# %%
ml_err, C_geo, geo = E.ml_pose_samples(N_ELLIPSOID, scenario=sc, n_points=170, runner=runner)
ax = E.plot_crlb_ellipsoid(C_geo, ml_err, block="att", n_sigma=2)

# %%
d2 = np.einsum("ni,ij,nj->n", ml_err[:, 3:], np.linalg.inv(C_geo[3:, 3:]), ml_err[:, 3:])
mc_vs_bound = np.trace(np.cov(ml_err[:, 3:].T)) / np.trace(C_geo[3:, 3:])
display(Markdown(
    f"Inside the 2-σ ellipsoid: {np.mean(d2 <= 4):.2f} of {N_ELLIPSOID} draws (efficient: "
    f"{stats.chi2.cdf(4, 3):.2f}); Monte Carlo attitude variance / CRLB = {mc_vs_bound:.2f}."))
assert 0.7 < mc_vs_bound < 1.4

# %% [markdown]
# ### CRLB-based selection (§2.4) — and why, as printed, it selects nothing
#
# The score of a point set is the weighted sum of the 7 CRLB values (weights not given; ours:
# all 1). Start like RANSAC with 6 random inliers; if their score is worse than that of all
# inliers, draw again (after a preset count, use all inliers); otherwise add the other inliers
# one at a time, keeping a point only when it lowers the score.
#
# But $J(S\cup\{i\}) = J(S) + G_i^\top G_i/\sigma_i^2$ with the added term $\succeq 0$, so
# $J(S\cup\{i\})^{-1} \preceq J(S)^{-1}$: **every CRLB, and any non-negative weighted sum of
# them, can only fall when a point is added.** Six points can never beat all inliers (the start
# test always fails), and past the start every point is kept. Below, one colour per random
# order of one scene's points: solid = the exact score, dotted = the covariance of an
# *unweighted* pose on the same sets (the "sandwich"), which can rise when a noisy point joins.
#
# **The score's units.** The translation CRLBs are in m², the quaternion CRLBs have no unit.
# With the paper's unstated weights set to 1, as here, the score adds m² to a pure number: its
# value, and which point lowers it, change if positions are in mm. The shares below: unit
# weights, and dimensionless weights $(1/|t|^2 \times 3, 1 \times 4)$ (`scaled_crlb_weights`).
# The reproduction keeps unit weights (fixed in the first claims.toml); *Beyond* compares the
# two.

# %%
shares = {"unit weights (m² + 1)": score_shares(X_in, sc.R, sc.t, sc.K, s_in),
          "scaled, L = |t| (dimensionless)": score_shares(
              X_in, sc.R, sc.t, sc.K, s_in, scaled_crlb_weights(np.linalg.norm(sc.t)))}
pd.DataFrame(shares).T.rename(columns=lambda c: f"share of the score: {c} terms")

# %%
sizes, scores, sandwich = E.monotonicity_curves(np.random.default_rng(st.seed), sc)
ax = E.plot_monotonicity(sizes, scores, sandwich)

# %%
# NBVAL_CHECK_OUTPUT
print("exact CRLB score non-increasing along every order:",
      bool(np.all(np.diff(scores, axis=1) <= 1e-12 * scores[:, :1])))
print("unweighted ('sandwich') score rises somewhere:", bool(np.any(np.diff(sandwich, axis=1) > 0)))

# %% [markdown]
# So the rule needs another reading to do anything. The library implements these
# (`eotrack.pose.selection`, `E.READINGS`): **as printed** (exact CRLB, the paper's start
# test); **exact** (same score, per-point start test); **pooled** — the paper's eq. (5) model
# with one $\sigma^2$ for all points, *estimated from the set's own residuals*,
# $\hat\sigma^2(S) = \sum_S |r_i|^2 / 2|S|$, so a point with a large residual raises the score;
# **sandwich** — the covariance $H^{-1}(\sum \sigma_i^2 G_i^\top G_i) H^{-1}$ of the unweighted
# pose with the simulator's true $\sigma_i$ (an oracle); **sandwich (est. σ)** — the same with
# $\hat\sigma_i^2 = |r_i|^2/2$ from each point's residual (White's heteroskedasticity-consistent
# estimate [11]); **tolerance** — exact score, but keep a point only when it lowers the score by
# more than 1 %. Each applied to this trial's inliers, then an unweighted pose on the selection:

# %%
Xi, ui, si = scene.points[res.inliers], scene.pixels[res.inliers], scene.sigma[res.inliers]
trial = {}
for name in E.READINGS:
    r = E.select_and_refit(name, Xi, ui, sc.K, res.R, res.t, si, np.random.default_rng(5), st)
    trial[name] = {"kept": int(r["selected"].sum()), "of": res.n_inliers,
                   "fell back to all": r["fallback"],
                   "attitude error (deg)": rotation_error_deg(r["R"], sc.R)}
trial_table = pd.DataFrame(trial).T
assert trial_table.loc["as printed", "kept"] == res.n_inliers
trial_table

# %% [markdown]
# ### The reading is fixed before the deciding run (not before every result)
#
# Which reading is "the paper's"? It has to be decided from the text, before looking at the
# 300 runs — otherwise we would pick the reading that happens to look best, and a 5 % test
# repeated over four readings and two metrics finds "something" far more than 5 % of the time.
# The protocol lives in `papers_repro/ransac_crlb_pose/claims.toml`:

# %%
proto = E.load_protocol()
primary = proto["primary_reading"]
display(Markdown(
    f"**Primary reading: `{primary}`** — eq. (5) gives all points one σ², nothing in §2.4 gives "
    "the selection a per-point noise level, and a constant σ² makes the rule select nothing; "
    "the only quantity of the paper's model that can make a set's score rise is σ² itself, "
    "which a real system estimates from the residuals. Exploratory: "
    f"{', '.join(proto['exploratory_readings'])} × {{position, attitude}} = "
    f"{2 * len(proto['exploratory_readings'])} comparisons, {proto['correction']}-adjusted, "
    f"α = {proto['alpha']}."))

# %% [markdown]
# **But not blind.** An earlier version used *sandwich*, chosen after seeing the results
# (withdrawn). The person who then fixed *pooled* had seen every reading's earlier results,
# pooled's included. The reasons are textual, but such a protocol is not pre-registered;
# `claims.toml` records every criterion change with its date, reason and `after_results`, and
# no claim can become `reproduced` through such a change alone.

# %%
import tomllib

_raw = tomllib.loads((papers_repro_dir() / "ransac_crlb_pose" / "claims.toml").read_text())
history = pd.DataFrame([{"claim": cid.split(".")[-1], "date": h["date"],
                         "after results": h["after_results"], "reason": h["reason"]}
                        for cid, c in _raw["claims"].items() for h in c.get("history", [])])
with pd.option_context("display.max_colwidth", None):
    display(history)

# %%
# NBVAL_CHECK_OUTPUT
print("history rows:", len(history), "— changed after results were seen:",
      int(history["after results"].sum()))

# %% [markdown]
# ## Reproduction
#
# Figs. 4–6 are lost; the text gives only directions ("more accurate") and one number (Fig. 6,
# "about two thirds"). The same 300 (Figs. 4–5) and 80 (Fig. 6) seeded runs as `make repro`:
# per run an image, RANSAC, every reading with an unweighted LM pose on its selection; `ml` is
# the pose weighted by the true σ_i (a reference, not a selection).

# %%
t0 = time.perf_counter()
runs = E.run_pose_experiment(60 if QUICK else st.n_runs, scenario=sc, settings=st,
                             runner=runner)
st6 = E.Settings(readings=("as printed", "exact", primary, "sandwich"))
counts = E.run_pose_experiment(30 if QUICK else st.n_runs_counts, scenario=sc, settings=st6,
                               runner=runner, seed=st.seed + 1)
print(f"{len(runs)} + {len(counts)} runs in {time.perf_counter() - t0:.0f} s")
ok = runs[runs["success"]]
methods = ("ransac", primary, "sandwich", "sandwich (est. σ)", "ml")
E.error_summary(runs)

# %% [markdown]
# ### Fig. 4 — position error, RANSAC alone vs RANSAC + CRLB
#
# *Paper:* "the relative position from the CRLB-selected points is more accurate than with
# RANSAC alone; accuracy clearly improved" (300 runs). Top: one box per method, each run a
# faint line joining its errors; bottom: the ECDF of each run's paired ratio to RANSAC's error
# — what the paired tests compare (the ECDFs of the errors themselves overlap).

# %%
fig = E.figure_errors(runs, "pos", methods)

# %% [markdown]
# ### Fig. 5 — attitude error, RANSAC alone vs RANSAC + CRLB
#
# *Paper:* "the relative attitude from the CRLB-selected points is more accurate" (same runs).

# %%
fig = E.figure_errors(runs, "att", methods)

# %% [markdown]
# Every reading against RANSAC alone, paired run by run: mean ratio (< 1 = better), win rate,
# one-sided Wilcoxon signed-rank p, and the Holm-adjusted p for the exploratory family. The
# primary reading's p is the protocol's test (fixed from the text after earlier results were
# seen) and is not adjusted.

# %%
readings = E.readings_table(runs, primary=primary)
readings

# %%
paper45 = pd.DataFrame(
    {q: {"paper: runs": claims[f"ransac_crlb_pose.{fig}"].paper["n_runs"],
         "paper: direction": "CRLB < RANSAC",
         "ours: runs": len(ok),
         f"ours ({primary}): mean ratio": readings.loc[(primary, q), "mean ratio"],
         "ours: p (Wilcoxon)": readings.loc[(primary, q), "p"]}
     for q, fig in (("pos", "fig4"), ("att", "fig5"))}).T
paper45

# %%
r5 = readings.loc[(primary, "att")]
lo5, hi5 = E.bootstrap_ratio_ci(ok[f"att_{primary}"], ok["att_ransac"], seed=1)
ex = readings[readings["role"] == "exploratory"]
best = ex["p (Holm)"].idxmin()
display(Markdown(
    f"**Fig. 5 decision (primary `{primary}`):** mean attitude error ratio "
    f"{r5['mean ratio']:.3f} (95 % CI {lo5:.3f}–{hi5:.3f}), CRLB better in "
    f"{100 * r5['win rate']:.0f} % of runs, one-sided Wilcoxon p = {r5['p']:.3f} "
    f"({'<' if r5['p'] < proto['alpha'] else '≥'} α = {proto['alpha']}). The smallest "
    f"exploratory Holm-adjusted p is {ex['p (Holm)'].min():.2f} ({best[0]}, {best[1]}; raw "
    f"{ex.loc[best, 'p']:.3f}). True-noise sandwich vs estimated-noise sandwich, attitude: "
    f"ratio {readings.loc[('sandwich', 'att'), 'mean ratio']:.3f} vs "
    f"{readings.loc[('sandwich (est. σ)', 'att'), 'mean ratio']:.3f}, Holm p "
    f"{readings.loc[('sandwich', 'att'), 'p (Holm)']:.2f} vs "
    f"{readings.loc[('sandwich (est. σ)', 'att'), 'p (Holm)']:.2f}."))
assert readings.loc[("as printed", "att"), "kept / inliers"] == 1.0
assert lo5 <= r5["mean ratio"] <= hi5

# %% [markdown]
# **What the criterion tests:** the whole 95 % interval of the ratio below 1 *and* p < α
# (`partial`: one of them). The direction only — not the paper's "clearly improved": with
# enough runs any gain would pass.
#
# The gains of any reading are a few per cent, not a "clear improvement". Two reasons. Even
# keeping exactly the low-noise points could lower an unweighted solver's RMS only to the ratio
# printed below; and the flip ambiguity puts some runs tens of degrees off whatever the
# selection (the long upper whiskers). Weighting every inlier by its variance (`ml`) beats every
# selection — but needs the σ_i the paper's model does not have.

# %%
print(f"best possible RMS ratio of an unweighted solver (low-noise points only): "
      f"{E.best_subset_gain(sc):.3f}")

# %% [markdown]
# ### Fig. 6 — number of selected points
#
# *Paper:* "the CRLB selection keeps only about two thirds of the RANSAC points (80 runs); in
# some runs the counts are equal — no combination qualified and all inliers were used."

# %%
c6 = claims["ransac_crlb_pose.fig6"].paper
ax = E.plot_selected_fraction(counts, (primary, "sandwich", "as printed"),
                              c6["selected_fraction"], tuple(c6["fraction_range"]))

# %%
ok6 = counts[counts["success"]]
fig6 = pd.DataFrame({r: {"paper: kept / inliers": c6["selected_fraction"],
                         "ours: kept / inliers": (ok6[f"n_{r}"] / ok6["n_inliers"]).mean(),
                         "runs falling back to all inliers": int(ok6[f"fallback_{r}"].sum())}
                     for r in (primary, "sandwich", "as printed", "exact")}).T
fig6["difference"] = fig6["ours: kept / inliers"] - fig6["paper: kept / inliers"]
fig6

# %%
frac6 = (ok6[f"n_{primary}"] / ok6["n_inliers"]).to_numpy()
ci6 = E.bootstrap_mean_ci(frac6, seed=2)
lo_b, hi_b = c6["fraction_range"]
display(Markdown(
    f"**Fig. 6 (`{primary}`):** mean kept fraction {frac6.mean():.3f}, 95 % bootstrap interval "
    f"{ci6[0]:.3f}–{ci6[1]:.3f} over {len(frac6)} runs — "
    f"{100 * (1 - frac6.mean() / c6['selected_fraction']):.0f} % below two thirds. Our band "
    f"[{lo_b}, {hi_b}] (in the first claims.toml) is asymmetric: its lower edge is "
    f"{100 * (1 - lo_b / c6['selected_fraction']):.0f} % below two thirds, its upper edge "
    f"{100 * (hi_b / c6['selected_fraction'] - 1):.0f} % above. The interval "
    f"{'contains' if ci6[0] < lo_b < ci6[1] else 'does not contain'} the lower edge: whether "
    "the point estimate falls inside the band is decided by the Monte Carlo noise, so the "
    "criterion now asks for the whole interval inside the band (history row above). The band "
    "dates from the first commit; whether it was set before Fig. 6's numbers were seen is not "
    "recorded."))

# %% [markdown]
# With the per-point start test a 6-point start that beats the all-inlier score is found in
# (almost) every run, so the readings rarely fall back to all inliers; the literal one always
# does.
#
# ## Scorecard

# %%
rows = E.evaluate(claims, runs, counts, proto)
card = scorecard(rows)
display(Markdown("\n\n".join(
    f"**`{r.claim}`** ({r.kind}{', central' if r.central else ''}) — **{r.status}**  \n"
    f"*ours:* {r.ours}  \n*note:* {r.note or '–'}" for r in rows)))

# %%
# NBVAL_CHECK_OUTPUT
for r in rows:
    print(r.claim, r.status.value)
if not QUICK:   # the same configuration as make repro: the same statuses as the REPORT
    assert {c["claim"]: c["status"] for c in _card["claims"]} == \
        {r.claim: r.status.value for r in rows}

# %% [markdown]
# ### Stability over seeds
#
# `make repro-stability` re-runs the reproduction at the same counts on five independent root
# seeds (`stability.json`); a claim whose status differs on some seed is **fragile**.

# %%
stab = read_stability(papers_repro_dir() / "ransac_crlb_pose")
committed = {c["claim"]: c["status"] for c in _card["claims"]}
if stab is None:
    display(Markdown("*No stability run stored yet (`make repro-stability`).*"))
else:
    display(pd.DataFrame({cid: {"committed status": committed[cid],
                                "seeds": stab.cell(cid, committed[cid]).replace("**", ""),
                                "per seed": ", ".join(stab.statuses.get(cid, ()))}
                          for cid in committed}).T)

# %% [markdown]
# **Exploratory: more runs.** Pooling the default and the five seeds' runs (6 × 300 paired
# runs; decided after seeing the table, so it cannot change a status) narrows the interval on
# the size of the effect. They take about 90 s, so `make repro` computes them
# (`E.pooled_seed_runs`, summarised by `E.pooled_summary`) into
# `papers_repro/ransac_crlb_pose/pooled_seed_runs.json`, read here:

# %%
pooled = E.read_pooled_study()
assert pooled is not None and pooled["reading"] == primary, "run make repro first"
display(pd.DataFrame({q: {"runs": pooled[q]["runs"],
                          "mean ratio CRLB / RANSAC": pooled[q]["mean_ratio"],
                          "95 % CI": "{:.3f}–{:.3f}".format(*pooled[q]["ci"]),
                          "one-sided Wilcoxon p": pooled[q]["p_less"]}
                      for q in ("pos", "att")}).T)
kf = pooled["kept_fraction"]
two3 = c6["selected_fraction"]
display(Markdown(
    f"**Fig. 6 over {pooled['runs']} runs:** kept fraction {kf['mean']:.3f} (95 % CI "
    f"{kf['ci'][0]:.3f}–{kf['ci'][1]:.3f}), {100 * (1 - kf['mean'] / two3):.0f} % below two "
    f"thirds and {kf['mean'] - lo_b:.3f} "
    f"{'inside' if kf['ci'][0] > lo_b else 'from'} our band's lower edge {lo_b}. The verdict "
    f"is a band-edge call; the finding is ≈ {kf['mean']:.2f}, not two thirds. Figs. 4–5: "
    f"gains of {100 * (1 - pooled['pos']['mean_ratio']):.1f} % (position) and "
    f"{100 * (1 - pooled['att']['mean_ratio']):.1f} % (attitude) — set them beside the paper's "
    "\"clearly improved\"."))
assert kf["ci"][0] <= kf["mean"] <= kf["ci"][1]

# %% [markdown]
# Read the seeds before the statuses: with gains of a few per cent, one seed's verdict is
# chance; Fig. 6's status would change with the run count.
#
# **How the statuses moved.** Fig. 5 was once `reproduced` through *sandwich* (chosen after
# seeing results); Fig. 6 `partial` on a point estimate at the band's edge. Fig. 6 and the
# "lower" leg of Figs. 4–5 are now decided on intervals.
#
# ## Explore
#
# Points dropped and attitude error per reading, at the printed noise (1 mm) and the pixel
# reading (0.01 mm, no flips); a few dozen cached runs per setting (`E.EXPLORE_RUNS`).

# %%
n_cached = E.warm_explore_cache()   # every setting the controls can reach: a change only draws
uses_tolerance = [name for name, spec in E.READINGS.items() if spec[0] == "tolerance"]
explore = panel(
    E.explore_figure,
    tight=False,  # fixed margins
    reading=dropdown("selection reading", list(E.READINGS), primary),
    noise_unit_mm=dropdown("noise unit", E.NOISE_UNITS, 1.0),
    tolerance_pct=float_slider("tolerance reading: min. decrease (%)", *E.TOLERANCE_PCT),
    show_ml=toggle("show ML (weighted) reference", True),
    enabled_when={"tolerance_pct": ("reading", uses_tolerance)},
)

# %%
# NBVAL_CHECK_OUTPUT
print("settings cached for the panel:", n_cached)

# %% [markdown]
# ## Errata and deviations
#
# * **Equations lost; labels are readings.** Eqs. (1)–(19) were images except (9), text
#   ($E_{t_1t_2} = 0$, checked). Eq. (1) is in quaternion form; $C_{ct}(q)\,r_t + t$ is our
#   reading. Eq. (2) has its origin top-left (§1); we drop the principal-point offset.
# * **The selection rule as printed cannot select** (additivity). The primary reading
#   (*pooled*) was fixed from the text, after earlier results had been seen (history above);
#   the other four readings are exploratory (Holm).
# * **Units of the noise.** "Variance 0.02 / 0.1 / 3 mm²" on a 10 mm focal length puts
#   σ = 0.14–0.32 mm on a target image ≈ 2 mm wide. We keep the printed values
#   (`noise_unit_mm = 1`). If the authors meant px² with a ≈ 10 µm pixel, all errors shrink
#   100× and the flip ambiguity disappears (Explore: noise unit).
# * **"22 m²" plane.** Read as 2 m × 2 m, at $Z_t = -1$ m, facing the camera.
# * **Unstated settings (ours):** Euler sequence x-y-z; inlier threshold
#   $\sqrt{\chi^2_{2,0.99}\cdot 0.1}$ mm; acceptance 60 %; 500 RANSAC draws; 50 CRLB start
#   draws; CRLB weights all 1; random order of adding points; unweighted LM after selection.
# * **RANSAC refit.** The accepted pose is re-estimated from all inliers (best of DLT and both
#   IPPE solutions, LM-refined) and the inlier test repeated once.
# * **OpenCV on this target** lands on the mirrored planar pose in most scenes (SQPnP/EPnP);
#   `ransac_pose_opencv` disambiguates (benchmark).

# %% [markdown]
# ## Beyond the paper
#
# ### Estimator efficiency: Monte Carlo covariance vs the CRLB
#
# Fixed geometry (the paper's scene, gross errors removed), noise at the printed level and
# 100× smaller. *ML* = weighted Levenberg–Marquardt; *unweighted LS* is bounded not by the
# CRLB but by its own sandwich covariance ("LS bound").

# %%
eff = E.efficiency_experiment(n_mc=40 if QUICK else st.n_mc_efficiency, scenario=sc,
                              runner=runner)
ax = E.plot_efficiency(eff)
eff

# %%
ml_lin = eff[(eff["noise unit (mm)"] == 0.01) & (eff["estimator"] == "ML (from truth)")].iloc[0]
assert 0.75 < ml_lin["att RMS / CRLB"] < 1.25 and 0.75 < ml_lin["pos RMS / CRLB"] < 1.25

# %% [markdown]
# At small noise ML attains the CRLB and unweighted LS its own, larger bound — the gap
# weighting closes. At the printed noise ML often lands in the mirrored planar solution, and
# the CRLB says little about the actual error.
#
# ### Budgeted selection: best k points vs random k
#
# If only k points can be used, which k? Greedy design on the Fisher information (D-optimal:
# max $\log\det J(S)$; A-optimal: min the weighted CRLB sum), pixel reading, weighted LM.

# %%
bud = E.budget_experiment(n_runs=6 if QUICK else st.n_runs_budget, scenario=sc, runner=runner)
ax = E.plot_budget(bud)
bud.pivot(index="k", columns="method", values="att_median_deg")

# %% [markdown]
# With a *budget*, "which points?" has a real answer: over these scenes (medians, no
# interval) designed subsets look better than random ones at small k; from about a hundred
# points on the choice hardly matters.

# %% [markdown]
# ### The score's units: unit weights versus dimensionless weights
#
# The same images and RANSAC inliers, the *pooled* reading from the same random start stream,
# once with unit weights (the reproduction's) and once with `scaled_crlb_weights(|t̂|)`;
# paired ratios of the mean errors (scaled / unit) with 95 % paired-bootstrap intervals.

# %%
wst = E.weights_study(30 if QUICK else st.n_runs_counts, scenario=sc, runner=runner)
wrows = {}
for q, unit in (("pos", "m"), ("att", "deg")):
    lo_w, hi_w = E.bootstrap_ratio_ci(wst[f"{q}_scaled"], wst[f"{q}_unit"])
    wrows[q] = {"mean, unit weights": wst[f"{q}_unit"].mean(),
                "mean, scaled weights": wst[f"{q}_scaled"].mean(), "unit": unit,
                "ratio scaled / unit": wst[f"{q}_scaled"].mean() / wst[f"{q}_unit"].mean(),
                "95 % CI": f"{lo_w:.3f}–{hi_w:.3f}"}
display(pd.DataFrame(wrows).T)
print(f"{len(wst)} runs; kept fraction: unit weights {wst['frac_unit'].mean():.3f}, "
      f"scaled {wst['frac_scaled'].mean():.3f}")

# %% [markdown]
# On these runs the weights change neither the kept fraction nor the errors measurably (why
# was not isolated).
#
# ### Robust pose on a user's scene
#
# Scenes unlike the paper's (`eotrack.pose.random_pnp_scene`): 60 non-planar points, a pixel
# camera with an off-centre principal point, 8–15 m, noise 0.3–1.5 px, 30 % mismatches.
# `ransac_pose` defaults: P3P hypotheses, a **scale-aware** inlier threshold
# $\tau = k\hat\sigma$ ($\hat\sigma$ from the best hypothesis' residuals: any image unit),
# the Fischler–Bolles draw count (notebook 01, its eq. 2), local optimisation of the *final*
# best hypothesis (once, not on every new best as in LO-RANSAC [13]) and a Cauchy refinement.
# **In-sample:** $k = 4$ was chosen on this family (benchmark seed), so the first table is the
# tuning family; the second is out of family (noisier, 20 points / 50 % mismatches at
# f = 400 px, millimetres). OpenCV: `solvePnPRansac` + `solvePnPRefineLM`, 8 px (in mm for the
# mm row). Both tables come from `E.pose_family_comparison` and `E.family_table`, the call the
# benchmark makes.

# %%
from eotrack.pose import random_pnp_scene

rng_f = np.random.default_rng(606)
family = [random_pnp_scene(rng_f) for _ in range(40)]
fam_table = E.family_table(E.pose_family_comparison(family, cv_threshold=8.0))
fam_table

# %%
assert fam_table.loc[E.OURS, "found (< 5°)"] >= 0.95 * len(family)

# %%
from dataclasses import replace as _replace

rng_h = np.random.default_rng(707)
_mm = np.diag([0.005, 0.005, 1.0])
held = {"σ 2–4 px": ([random_pnp_scene(rng_h, sigma_px=(2.0, 4.0)) for _ in range(30)], 8.0),
        "20 points, 50 % out, f = 400 px": (
            [random_pnp_scene(rng_h, n_points=20, outlier_fraction=0.5, focal_px=400.0)
             for _ in range(30)], 8.0),
        "design family in mm (5 µm pixels)": (
            [_replace(s, pixels=0.005 * s.pixels, K=_mm @ s.K) for s in family[:30]], 0.04)}
held_table = pd.concat({fam_name: E.family_table(
    E.pose_family_comparison(scenes, cv_threshold=thr_cv, methods=(E.OURS, E.OPENCV)),
    timing=False) for fam_name, (scenes, thr_cv) in held.items()})
held_table

# %%
_ours_rows = held_table.xs(E.OURS, level=1)
assert (_ours_rows["found (< 5°)"] >= 0.9 * _ours_rows["of"]).all()

# %% [markdown]
# Timings and six held-out families: `benchmarks/bench_ransac_crlb_pose.py` (`make bench`;
# one family failed at first, the threshold's sanity cap was changed, two fresh families
# checked it).
#
# ## Key points
#
#
# * The Fisher information of a pose from N points is $\sum_i G_i^\top G_i/\sigma_i^2$; its
#   inverse bounds the covariance of any unbiased pose, and the ML pose attains it at small
#   noise.
# * Information is additive, so adding a point never raises any CRLB: a rule "keep a point if
#   it lowers the CRLB" keeps everything.
# * A selection rule can only drop points through something the CRLB does not contain: an
#   estimated noise level, an unweighted solver, or a budget/stopping rule.
# * If per-point noise is known, weight the points (ML) rather than dropping them.
# * A small, distant plane has two nearly equally good poses: check solvers for the flip.
# * Fix the reading and the test before the run; Holm-correct exploratory comparisons.
#
# ## Exercises
#
# **1 (derivation).** Derive $J_1 = G_1^\top G_1/\sigma^2$ for one point in the 6-parameter
# form and evaluate it for the point, pose (a rotated target, $R \ne I$) and noise given in the
# question below. Mind the perturbation: $R \leftarrow \exp([\delta\theta]_\times) R$ is a
# camera-frame rotation. Why is its rank 2?

# %%
print(get_checker("ransac_crlb_pose.1").question)
answer = None  # your 6×6 array here
if answer is not None:
    display(check("ransac_crlb_pose.1", answer))

# %% [markdown]
# **2 (computation).** A ratio of scores is unit-free only if the score is. With the
# dimensionless weights of `scaled_crlb_weights`, compute score$(S_6)$ / score$(S_{all})$ for
# the scene named in the question; then show that this score never rises along the nested
# sets $S_6 \subset S_7 \subset \dots$ (hint: `information_monotonicity(..., weights=...)`).

# %%
print(get_checker("ransac_crlb_pose.2").question)
answer = None  # your number here
if answer is not None:
    display(check("ransac_crlb_pose.2", answer))

# %% [markdown]
# **3 (design).** Design a selection rule that *can* drop points: add points in a given order
# and stop when exercise 2's dimensionless score is within a fraction `frac` of the all-point
# score. Write
# `points_needed(points, R, t, K, sigma, frac)`, then test it: how many points does it keep for
# `frac = 0.1`, and is the pose from them worse than from all points?

# %%
def points_needed(points, R, t, K, sigma, frac):
    """Your rule: the fewest leading points within (1 + frac) of the all-point score."""
    return None


if points_needed(*[None] * 6) is not None:
    display(check("ransac_crlb_pose.3", points_needed))

# %% [markdown]
# **4 (exploration).** The Explore panel's titles give one mean ratio per setting, from a few
# dozen runs. Is the ratio at the pixel reading (0.01 mm) different from the one at 1 mm, or
# from 1? Compute the 95 % paired-bootstrap interval asked for below, then the same at 1 mm,
# and decide what so few runs can show.

# %%
print(get_checker("ransac_crlb_pose.4").question)
answer = None  # (lo, hi)
if answer is not None:
    display(check("ransac_crlb_pose.4", answer))

# %% [markdown]
# **5 (transfer).** If every point's σ_i were known, could the exact CRLB rule drop a noisy
# point? **6 (critique).** If eq. (5) had per-point σ_i, which reading would the protocol's
# textual argument pick? Answer with a letter; the options are in the questions.

# %%
for k in (5, 6):
    print(f"{k}.", get_checker(f"ransac_crlb_pose.{k}").question)
answer5 = None  # "a", "b", "c" or "d"
answer6 = None
if answer5 is not None:
    display(check("ransac_crlb_pose.5", answer5))
if answer6 is not None:
    display(check("ransac_crlb_pose.6", answer6))

# %% [markdown]
# Worked solutions: `notebooks/solutions/06_ransac_crlb_pose_solutions.ipynb`.
#
# ## Closing note: independent review
#
# An independent review (issue 29) found **14** defects (1 high, 5 medium, 8 low): **fixed
# 14, left 0**.
#
# ## References
#
# 1. Ning M., Zhang S., Zhang H. Robust visual navigation of non-cooperative spacecraft with
#    active feature selection. *Aerospace Shanghai* 33(6):136–141, 2016.
#    DOI [10.19328/j.cnki.1006-1630.2016.06.020](https://doi.org/10.19328/j.cnki.1006-1630.2016.06.020)
# 2. Fischler M. A., Bolles R. C. Random sample consensus. *Commun. ACM* 24(6):381–395, 1981.
#    DOI [10.1145/358669.358692](https://doi.org/10.1145/358669.358692)
# 3. Hartley R., Zisserman A. *Multiple View Geometry in Computer Vision*, 2nd ed. Cambridge
#    University Press, 2004. DOI [10.1017/CBO9780511811685](https://doi.org/10.1017/CBO9780511811685)
# 4. Kay S. M. *Fundamentals of Statistical Signal Processing: Estimation Theory*. Prentice
#    Hall, 1993 (ch. 3, the CRLB).
# 5. Stoica P., Ng B. C. On the Cramér–Rao bound under parametric constraints. *IEEE Signal
#    Process. Lett.* 5(7):177–179, 1998. DOI [10.1109/97.700921](https://doi.org/10.1109/97.700921)
# 6. Terzakis G., Lourakis M. A consistently fast and globally optimal solution to the
#    perspective-n-point problem (SQPnP). *ECCV* 2020.
#    DOI [10.1007/978-3-030-58452-8_28](https://doi.org/10.1007/978-3-030-58452-8_28)
# 7. Collins T., Bartoli A. Infinitesimal plane-based pose estimation (IPPE). *Int. J. Comput.
#    Vis.* 109:252–286, 2014. DOI [10.1007/s11263-014-0725-5](https://doi.org/10.1007/s11263-014-0725-5)
# 8. Lepetit V., Moreno-Noguer F., Fua P. EPnP: an accurate O(n) solution to the PnP problem.
#    *Int. J. Comput. Vis.* 81:155–166, 2009. DOI [10.1007/s11263-008-0152-6](https://doi.org/10.1007/s11263-008-0152-6)
# 9. Holm S. A simple sequentially rejective multiple test procedure. *Scand. J. Stat.*
#    6(2):65–70, 1979 (JSTOR 4615733).
# 10. Wilcoxon F. Individual comparisons by ranking methods. *Biometrics Bulletin*
#     1(6):80–83, 1945. DOI [10.2307/3001968](https://doi.org/10.2307/3001968)
# 11. White H. A heteroskedasticity-consistent covariance matrix estimator and a direct test for
#     heteroskedasticity. *Econometrica* 48(4):817–838, 1980.
#     DOI [10.2307/1912934](https://doi.org/10.2307/1912934)
# 12. Pukelsheim F. *Optimal Design of Experiments*. SIAM, 2006.
#     DOI [10.1137/1.9780898719109](https://doi.org/10.1137/1.9780898719109)
# 13. Chum O., Matas J., Kittler J. Locally optimized RANSAC. *DAGM* 2003.
#     DOI [10.1007/978-3-540-45243-0_31](https://doi.org/10.1007/978-3-540-45243-0_31)
# 14. Gao X.-S., Hou X.-R., Tang J., Cheng H.-F. Complete solution classification for the
#     perspective-three-point problem. *IEEE TPAMI* 25(8):930–943, 2003.
#     DOI [10.1109/TPAMI.2003.1217599](https://doi.org/10.1109/TPAMI.2003.1217599)

# %%
lesson_footer("06")
