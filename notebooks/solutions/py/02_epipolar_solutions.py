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
# ## Exercise 1 — when can a 2.5σ rule reject? (derivation)
#
# Shift and scale so that $\bar x = 0$ and $\sum x_i^2 = n-1$ (then $s = 1$). To make one
# sample $x_1$ as large as possible, the other $n-1$ must be equal (any spread among them
# uses up the fixed sum of squares): $x_j = -x_1/(n-1)$. Then
#
# $$ x_1^2 + (n-1)\frac{x_1^2}{(n-1)^2} = n-1 \;\Rightarrow\; x_1^2\,\frac{n}{n-1} = n-1
#    \;\Rightarrow\; \max\frac{|x_i-\bar x|}{s} = \frac{n-1}{\sqrt n}. $$
#
# This is Samuelson's inequality (Samuelson 1968, *JASA* 63, 1522). A $k\sigma$ rule can fire
# only if $(n-1)/\sqrt n > k$, i.e. $n^2 - (2 + k^2)n + 1 > 0$. For $k = 2.5$: $n > 8.1$;
# for the paper's $k = 3$: $n > 10.9$.

# %%
def smallest_n(k):
    n = 2
    while (n - 1) / np.sqrt(n) <= k:
        n += 1
    return n


n = smallest_n(2.5)
x = np.r_[np.zeros(n - 1), 1.0]  # the extreme configuration
assert np.isclose(np.abs(x - x.mean()).max() / x.std(ddof=1), max_z_score(n))
assert check("epipolar.1", n)
assert not check("epipolar.1", smallest_n(3.0))  # the paper's 3σ rule: another question
print(f"2.5σ: n ≥ {n}; 3σ: n ≥ {smallest_n(3.0)}")

# %% [markdown]
# With 2–6 pairwise estimates (2–4 sensors), even a 2.5σ rule never removes anything, and the
# paper's "3σ-filtered mean" is the plain mean. (With the population $s$, $\sqrt{n-1}$
# replaces $(n-1)/\sqrt n$ and the answer shifts by one — the checker rejects it.) A
# median/MAD rule or a distance gate from the error budget can reject.
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
assert not check("epipolar.2", epipolar_distances)  # numpy only: the library is rejected

# %% [markdown]
# Normalising the line makes the result a distance in pixels and independent of the scale
# of $F$. The algebraic residual $|p_2^\top F p_1|$ alone would depend on both.
#
# ## Exercise 3 — the best threshold in the widget (exploration)
#
# The panel's curves come from `E.threshold_study(attitude, n_false)` (60 draws); the slider
# moves in 0.5 px steps, so the answer is read on that grid. With 6 false targets per map,
# and with 3 for comparison:

# %%
grid = np.arange(0.5, 30.01, 0.5)  # the slider's values
best = {}
for nf in (6, 3):
    rates = E.threshold_study(1.0, nf).rates(grid)
    best[nf] = float(grid[np.argmin(rates["total"])])
assert check("epipolar.3", best[6])
assert not check("epipolar.3", best[6] + 0.5)  # one slider step off is wrong
assert best[6] < best[3]
print(f"best L: {best[6]:g} px with 6 false targets, {best[3]:g} px with 3; χ² 99 % gate "
      f"{E.threshold_study(1.0, 6).gate_px:.1f} px (the same for both)")

# %% [markdown]
# More false targets put more foreign points in every band, so false associations grow
# faster with $L$ and the optimum moves *down*; the error-budget gate does not move (it knows
# only the true pairs' spread). Both stay well below the paper's 8–12 px.
#
# ## Exercise 4 — "10 mrad" in pixels (critique)

# %%
K_ref = E.ST_APS2_2.K  # 20°, 1024 px: f/dx = 1024 / (2 tan 10°)
jitter_ref = 10e-3 * K_ref[0, 0]
jitter_exp = 10e-3 * E.SensorConfig().K[0, 0]
assert check("epipolar.4", jitter_ref)
assert not check("epipolar.4", jitter_exp)  # the experiment's sensor: section 8's number
print(f"10 mrad = {jitter_ref:.1f} px on ST-APS2-2 ({jitter_exp:.1f} px on the 2° sensor; "
      f"L = 10 px): the wide-field pixel is {jitter_exp / jitter_ref:.2f} times coarser "
      "(10× the field over 2× the pixels)")

# %% [markdown]
# Even on the wide-field sensor, about five times coarser per pixel (printed above), 10 mrad
# rms stays well above the 10 px threshold: no reading of the sensors saves "10 mrad". It is also far above both
# sensors' stated 6″ accuracy. 10 µrad (≈ 2″, about the noise-equivalent angle) is the
# sensible reading.
#
# ## Exercise 5 — the error-budget gate with 1′ rms and 100 µrad jitter (computation)

# %%
scen = E.build_scenario()
rms = E.ErrorConfig(attitude_arcmin=np.sqrt(3.0), jitter_urad=100.0)  # bound √3′ ⇔ rms 1′
sigma, gate90 = E.error_budget_gate(scen, rms, p=0.90)
sigma10, gate90_10 = E.error_budget_gate(scen, E.ErrorConfig(attitude_arcmin=np.sqrt(3.0)),
                                         p=0.90)
assert check("epipolar.5", gate90)
assert not check("epipolar.5", gate90_10)  # the jitter forgotten
print(f"σ_d = {sigma:.2f} px (with 10 µrad: {sigma10:.2f} px); 90 % gate = {gate90:.2f} px "
      f"(= {gate90 / sigma:.3f} σ_d); 100 µrad = {100e-6 * E.SensorConfig().K[0, 0]:.2f} px")

# %% [markdown]
# The gate is $\sigma_d\sqrt{\chi^2_1(p)}$: 1.645 σ at 90 %. The jitter enters σ_d in
# quadrature through the centroids of both images: 100 µrad is over a pixel (printed), so it
# matters beside the attitude term, while the default 10 µrad does not. The rms reading is
# exploratory (chosen after seeing Fig. 5); it changes no claim's status.
