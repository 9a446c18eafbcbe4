# ---
# jupyter:
#   kernelspec:
#     display_name: Python 3 (ipykernel)
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 07 · Capstone — worked solutions
#
# [← the lesson: 07 · Capstone](../07_capstone_geo_surveillance.ipynb) ·
# [index](../00_index.ipynb)
#
# Solutions to the exercises of `07_capstone_geo_surveillance.ipynb`. Each computes the
# answer, checks it with `eotrack.exercises.check`, then discusses it. Try the exercises first.

# %%
import numpy as np
from eotrack.exercises import check
from eotrack.experiments import capstone as C
from eotrack.notebook import setup_notebook

setup_notebook()
ARCSEC = 180 / np.pi * 3600

# %% [markdown]
# ## Exercise 1 — range error of a two-station triangulation (derivation)
#
# Put station A at the origin and the object at range $R$ along A's line of sight; station B
# sits a baseline $B$ away, perpendicular to that line, so B sees the object under the
# parallax angle $\gamma \approx B/R$. Rotate B's line of sight by a small error
# $\sigma_\theta$: at the object's distance from B ($\approx R$) it moves sideways by
# $R\,\sigma_\theta$. Along A's line the intersection then slides by
# $R\sigma_\theta/\sin\gamma \approx R\sigma_\theta \cdot R/B$:
#
# $$ \sigma_R \approx \frac{R^2\,\sigma_\theta}{B}. $$

# %%
answer = 37_000.0 ** 2 * (1.0 / ARCSEC) / 4_900.0
assert check("capstone.1", answer)
print(f"answer = {answer:.3f}")

# %% [markdown]
# About 1.4 km per arcsecond. Our centroids are good to ≈ 0.2 px = 3″, which gives ≈ 4 km;
# the budget's median range error is somewhat smaller because several frames' errors partly
# average and the baseline's component perpendicular to the lines of sight varies.

# %% [markdown]
# ## Exercise 2 — the sidereal drift in pixels (computation)

# %%
cfg = C.CapstoneConfig()
answer = 7.292115e-5 * cfg.frame_interval_s * ARCSEC * np.cos(np.radians(-5.0)) \
    / cfg.pixel_scale_arcsec
assert check("capstone.2", answer)
assert np.isclose(answer, C.sidereal_drift_px(cfg, dec_deg=-5.0))
print(f"answer = {answer:.3f}")

# %% [markdown]
# Twenty pixels per frame step against a GEO target's fraction of a pixel: the motion test
# has a wide margin. It also explains the velocity gate of the initiator (0–0.5 px/s): a
# star left in the candidates moves 1 px/s and is rejected by the gate.

# %% [markdown]
# ## Exercise 3 — the target's signal-to-noise ratio where initiation halves (exploration)

# %%
c = C.with_changes(sky_e=6400.0)
flux = 10 ** (-0.4 * (c.target_mag - c.zero_point_mag))
answer = flux / (2 * np.pi * c.psf_sigma_px ** 2) / np.sqrt(c.sky_e + c.read_noise_e ** 2)
assert check("capstone.3", answer)
print(f"answer = {answer:.3f}")

# %% [markdown]
# A peak S/N near 5 against a 4σ extraction threshold: about half the frames lift the target
# above threshold, and a tracklet needs at least three of the five — so initiation recall
# halves. The extractor is not "broken" here; the photons are simply too few.

# %% [markdown]
# ## Exercise 4 — why the predictor fails first (critique)

# %%
answer = "B"
assert check("capstone.4", answer)

# %% [markdown]
# The chain labels tracklets by the field in which they were found: every false track in an
# object's field joins that object's RA/Dec series. Notebook 01's predictors were tuned for
# 3 % outliers of 30–300″; here false tracklets can be a quarter of the series and thousands
# of arcseconds off, beyond what RANSAC with a few hundred hypotheses on 8 points can reject.
# Association, in contrast, passes only pairs on each other's epipolar lines, so the pairs it
# triangulates stay right. A (shadow length) is geometry, independent of the sky; C fails
# because the same two hours work at 400 e⁻/px; D confuses stages — prediction uses the
# angles, not the triangulated positions.

# %% [markdown]
# [← the lesson: 07 · Capstone](../07_capstone_geo_surveillance.ipynb) ·
# [index](../00_index.ipynb)
