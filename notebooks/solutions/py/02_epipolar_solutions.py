# ---
# jupyter:
#   kernelspec:
#     display_name: Python 3 (ipykernel)
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 02 · Epipolar association — worked solutions
#
# Solutions to the exercises of `02_epipolar_association.ipynb`. Each computes the answer,
# checks it with `eotrack.exercises.check`, then discusses it. Try the exercises first.

# %%
import numpy as np
from eotrack.exercises import check
from eotrack.experiments import epipolar as E
from eotrack.geometry import epipolar_distances, max_z_score
from eotrack.notebook import setup_notebook

setup_notebook()

# %% [markdown]
# ## Exercise 1 — when can a 3σ rule reject? (derivation)
#
# Shift and scale so that $\bar x = 0$ and $\sum x_i^2 = n-1$ (then $s = 1$). To make one
# sample $x_1$ as large as possible, the other $n-1$ must be equal (any spread among them
# uses up the fixed sum of squares): $x_j = -x_1/(n-1)$. Then
#
# $$ x_1^2 + (n-1)\frac{x_1^2}{(n-1)^2} = n-1 \;\Rightarrow\; x_1^2\,\frac{n}{n-1} = n-1
#    \;\Rightarrow\; \max\frac{|x_i-\bar x|}{s} = \frac{n-1}{\sqrt n}. $$
#
# The rule can fire only if $(n-1)/\sqrt n > 3$, i.e. $n^2 - 11n + 1 > 0$, $n > 10.9$:

# %%
n = 2
while (n - 1) / np.sqrt(n) <= 3:
    n += 1
x = np.r_[np.zeros(n - 1), 1.0]  # the extreme configuration
assert np.isclose(np.abs(x - x.mean()).max() / x.std(ddof=1), max_z_score(n))
assert check("epipolar.1", n)

# %% [markdown]
# With 2–6 pairwise estimates (2–4 sensors), the paper's rejection step never removes
# anything: its "3σ-filtered mean" is the plain mean. A median/MAD rule or a distance gate
# from the error budget can reject.
#
# ## Exercise 2 — eq. (8) as a function (computation)

# %%
def dist(F, p1, p2):
    F = np.asarray(F, float)
    h1 = np.column_stack([p1, np.ones(len(p1))])
    h2 = np.column_stack([p2, np.ones(len(p2))])
    lines = h1 @ F.T  # row i: (a, b, c) = F p1_i
    lines /= np.hypot(lines[:, 0], lines[:, 1])[:, None]
    return np.abs(lines @ h2.T)  # (n1, n2)


rng = np.random.default_rng(0)
F = rng.normal(size=(3, 3))
p1, p2 = rng.uniform(0, 512, (4, 2)), rng.uniform(0, 512, (3, 2))
np.testing.assert_allclose(dist(F, p1, p2), epipolar_distances(F, p1, p2))
assert check("epipolar.2", dist)

# %% [markdown]
# Normalising the line makes the result a distance in pixels and independent of the scale
# of $F$. The algebraic residual $|p_2^\top F p_1|$ alone would depend on both.
#
# ## Exercise 3 — the best threshold in the widget (exploration)
#
# The panel's curves come from `E.threshold_study()` (60 draws). Its total error is smallest
# at:

# %%
study = E.threshold_study(1.0, 3)
th, rates = study.curves()
best = float(th[np.argmin(rates["total"])])
assert check("epipolar.3", best)
print(f"best L = {best:g} px; χ² 99 % gate = {study.gate_px:.1f} px")

# %% [markdown]
# The optimum sits well below the paper's 8–12 px, near the error-budget gate: it follows the
# spread of true-pair distances that the ±1′ attitude error produces. With 300 draws (Fig. 5)
# the same answer comes out to within the sweep's step.
#
# ## Exercise 4 — "10 mrad" in pixels (critique)

# %%
K = E.SensorConfig().K
jitter_px = 10e-3 * K[0, 0]
assert check("epipolar.4", jitter_px)
print(f"10 mrad = {jitter_px:.0f} px (L = 10 px; the image is 512 px wide)")

# %% [markdown]
# A jitter of that size would throw every centroid far outside a 10 px band (and often off
# the image): no association could work. It is also hundreds of times the sensor's stated
# 6″ accuracy. 10 µrad (≈ 2″, about the noise-equivalent angle) is the sensible reading.
#
# ## Exercise 5 — the error-budget gate with 1′ rms (computation)

# %%
scen = E.build_scenario()
sigma, gate = E.error_budget_gate(scen, E.ErrorConfig(attitude_arcmin=np.sqrt(3.0)))
assert check("epipolar.5", gate)
print(f"σ_d = {sigma:.2f} px, 99 % gate = {gate:.1f} px")

# %% [markdown]
# Read as an rms error, the paper's 1′ puts the gate inside its recommended 8–12 px — a
# plausible origin of that range. The reading is exploratory (chosen after seeing Fig. 5), so
# it does not change the Fig. 5 claim's status.
