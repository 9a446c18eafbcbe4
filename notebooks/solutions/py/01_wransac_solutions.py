# ---
# jupyter:
#   kernelspec:
#     display_name: Python 3 (ipykernel)
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 01 · WRANSAC — worked solutions
#
# Solutions to the exercises of `01_wransac_trajectory_prediction.ipynb`. Each computes the
# answer, checks it with `eotrack.exercises.check`, then discusses it. Try the exercises first.

# %%
import numpy as np
from eotrack.exercises import check
from eotrack.experiments import wransac as W
from eotrack.montecarlo import TrialRunner
from eotrack.notebook import setup_notebook
from IPython.display import Markdown, display
from scipy import integrate, stats

setup_notebook()

# %% [markdown]
# ## Exercise 1 — the Cramér–Rao bound under Student-t noise
#
# A t variable with ν dof and scale $s$ has variance $s^2\nu/(\nu-2)$; set it to σ²:
# $s^2 = \sigma^2(\nu-2)/\nu$. The Fisher information of its location is
# $I = (\nu+1)/((\nu+3)s^2) = (\nu+1)\nu/((\nu+3)(\nu-2)\sigma^2)$ per observation. For a linear
# model the bound on any unbiased predictor is $\sigma^2_{\text{CR}} = (a^\top(A^\top A)^{-1}a)/I$
# while OLS gives $\sigma^2 a^\top(A^\top A)^{-1}a$, so the ratio is
# $(\nu+3)(\nu-2)/(\nu(\nu+1))$, independent of the design.

# %%
nu = 5.0
answer = (nu + 3) * (nu - 2) / (nu * (nu + 1))
# numeric check of the Fisher information by integration of the squared score
s = np.sqrt((nu - 2) / nu)  # σ = 1
score2 = lambda x: (stats.t.logpdf(x + 1e-6, nu, scale=s)  # noqa: E731
                    - stats.t.logpdf(x - 1e-6, nu, scale=s)) ** 2 / 4e-12
fisher = integrate.quad(lambda x: score2(x) * stats.t.pdf(x, nu, scale=s), -np.inf, np.inf)[0]
print(f"ratio by formula {answer:.4f}; 1 / Fisher information by integration {1 / fisher:.4f}")
assert abs(answer - 1 / fisher) < 1e-3
assert check("wransac.1", answer)

# %% [markdown]
# With ν = 5 a perfect estimator could cut the variance by a fifth; with ν = 3 by half, which is
# why the refit readings of WRANSAC beat RANSAC under Student-t(3) noise but cannot under
# Gaussian noise (ν → ∞, ratio → 1).
#
# ## Exercise 2 — the extrapolation leverage

# %%
sc = W.make_scenario()
t72 = np.array([sc.t_obs_s[-1] + 72 * 60.0])
answer = W.gauss_markov(sc.t_obs_s, t72, np.ones(len(sc.t_obs_s), bool), 3.0)[0]
first = W.gauss_markov(sc.t_obs_s, sc.t_obs_s[-1:], np.ones(len(sc.t_obs_s), bool), 3.0)[0]
display(Markdown(f"σ_pred(+72 min) = {answer:.2f}″, against {first:.2f}″ at the last "
                 f"observation: ×{answer / first:.0f}."))
assert check("wransac.2", answer)

# %% [markdown]
# Four nearly collinear columns over a short arc make the extrapolation ill-conditioned: the
# noise of 80 points of 3″ becomes a prediction spread several times σ after 72 min, for *any*
# linear unbiased estimator.
#
# ## Exercise 3 — what U = 3 delivers

# %%
err = W.budget_sweep(budgets=W.BUDGETS, methods=W.BUDGET_METHODS,
                     runner=TrialRunner(progress=False))
table = W.budget_table(err, W.BUDGETS, W.BUDGET_METHODS)
answer = float(table.loc[3, "ransac"])
display(table[["ransac", "wransac_hypothesis", "ideal"]])
assert check("wransac.3", answer)

# %% [markdown]
# Eq. (2) guarantees, with probability 0.995, one 4-point sample free of gross errors — not one
# whose exact fit extrapolates well. With U = 3 the best of three clean but badly spread samples
# often picks an inlier set that misses good points or keeps marginal ones; a budget of tens to
# hundreds of draws costs microseconds and removes the problem.
#
# ## Exercise 4 — why the hypothesis weights hurt

# %%
cfg = W.WransacConfig()
res = W.run_prediction_experiment(cfg, scenario=sc, n_runs=60,
                                   methods=("ransac", "wransac"),
                                   runner=TrialRunner(progress=False))
pull = W.pull_table(res)
display(pull[["slope", "corr", "shuffled_ratio", "hypothesis_weights_ratio"]])
answer = "b"
assert check("wransac.4", answer)

# %% [markdown]
# The inlier sets are the same as RANSAC's in almost every run (no gross errors get in, so not
# (a)); the corrected loss is used (not (c)); 100 draws reach RANSAC's ideal level (not (d)).
# The weighted refit moves a large fraction of the way toward the best 4-point hypothesis, and
# shuffling the same weights among the inliers costs much less than keeping them in place: the
# harm comes from weights that are *correlated* with a noisy hypothesis.
#
# ## Exercise 5 — the weighted refit

# %%
def wls(A, y, w):
    """θ minimising Σ w_i (y_i − A_i θ)²: scale rows by √w and solve least squares."""
    A, y, w = (np.asarray(v, dtype=float) for v in (A, y, w))
    sw = np.sqrt(w)
    return np.linalg.lstsq(A * sw[:, None], y * sw, rcond=None)[0]


assert check("wransac.5", wls)

# %% [markdown]
# Scaling by $\sqrt{w_i}$ turns the weighted problem into an ordinary one; points with $w_i = 0$
# drop out. Solving $(A^\top W A)\theta = A^\top W y$ directly gives the same θ but squares the
# condition number — with the nearly collinear columns of this model, `lstsq` on the scaled rows
# is the safer choice.
