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
from eotrack.experiments.capstone import stored as S
from eotrack.notebook import setup_notebook
from eotrack.repro import papers_repro_dir
from scipy.stats import chi2, norm

setup_notebook()
ARCSEC = 180 / np.pi * 3600

# %% [markdown]
# ## Exercise 1 — range error of a two-station triangulation (derivation)
#
# Put station A at the origin and the object at range $R$ along A's line of sight; station B
# sits a baseline $B$ away, perpendicular to that line, so the two rays meet under the
# parallax angle $\gamma \approx B/R$. Rotate B's ray by a small error $\sigma_\theta$ in the
# plane of the two rays (the epipolar plane): at the object's distance from B ($\approx R$) it
# moves sideways by $R\,\sigma_\theta$, and the intersection slides along A's ray by
# $R\sigma_\theta/\sin\gamma \approx R\sigma_\theta \cdot R/B$:
#
# $$ \sigma_R \approx \frac{R^2\,\sigma_\theta}{B}. $$

# %%
answer = 37_000.0 ** 2 * (1.0 / ARCSEC) / 4_900.0
assert check("capstone.1", answer)
print(f"answer = {answer:.3f}")

# %% [markdown]
# That is the range error per arcsecond of one ray (printed above). Two corrections make it the capstone's measured number: both
# rays have errors, and they add in quadrature, $\sqrt{\sigma_{\theta,a}^2+\sigma_{\theta,b}^2}$;
# and only the baseline's component perpendicular to the line of sight, $B_\perp$, makes
# parallax — it is smaller than $B$, so the error is *larger*. The triangulation uses one
# frame's hit of each tracklet, so nothing is averaged over frames. Only the error component
# in the epipolar plane counts; the out-of-plane part makes the rays miss each other (the
# `gap_km` column) without moving the range much. With the measured in-plane errors the
# notebook's formula matches its measured RMS range error.

# %% [markdown]
# ## Exercise 2 — the sidereal drift in pixels (computation)

# %%
cfg = C.CapstoneConfig()
answer = 7.292115e-5 * cfg.frame_interval_s * ARCSEC * np.cos(np.radians(30.0)) \
    / cfg.pixel_scale_arcsec
assert check("capstone.2", answer)
assert np.isclose(answer, C.sidereal_drift_px(cfg, dec_deg=30.0))
print(f"answer = {answer:.3f}")

# %% [markdown]
# Many pixels per frame step (printed above) against a GEO target's fraction of a pixel: the
# motion test has a wide margin. The star/target separation compares RA/Dec from the plate solutions of
# neighbouring frames, so it does not even need the drift — a star is simply fixed on the sky.

# %% [markdown]
# ## Exercise 3 — the target's signal-to-noise ratio where initiation fails (exploration)

# %%
c = C.with_changes(sky_e=6400.0)
flux = 10 ** (-0.4 * (c.target_mag - c.zero_point_mag))
answer = flux / (2 * np.pi * c.psf_sigma_px ** 2) / np.sqrt(c.sky_e + c.read_noise_e ** 2)
assert check("capstone.3", answer)
print(f"answer = {answer:.3f}")
print(f"expected completeness there {C.expected_completeness(c):.2f}, expected recall "
      f"{C.expected_recall(c):.2f}")
st, _ = S.read_stored(papers_repro_dir() / "capstone" / S.STORED_FILE)
if st:
    sw = S.sweep_from(st)
    comp = sw.loc["extraction · target completeness (sunlit frames)", c.sky_e]
    rec = sw.loc["initiation · recall (object-bursts with ≥ 3 sunlit frames)", c.sky_e]
    print(f"measured in the sweep (QUICK night): completeness {comp:.3f}, recall {rec:.3f}; "
          f"expected recall from the measured completeness "
          f"{C.expected_recall(c, completeness=comp):.3f}")

# %% [markdown]
# A peak S/N near 5 against a 4σ extraction threshold: the target is above threshold in only
# part of the frames (the sub-pixel phase lowers the peak pixel). Recall is **not** bounded by
# the per-frame completeness: the initiator confirms a tracklet with 3 hits in some window of
# 4 consecutive frames, so a burst of 5 frames survives a missed frame, and at a completeness
# near 0.67 the expected recall is about 0.70 — what the sweep measures (printed above). At
# lower completeness recall falls faster than completeness (it needs three hits), which is why
# the recall criterion fails first as the sky brightens. The extractor is not "broken" here;
# the photons are simply too few.

# %% [markdown]
# ## Exercise 4 — why the curve predictors fail on a mixed series (critique)

# %%
answer = "B"
assert check("capstone.4", answer)

# %% [markdown]
# The old chain put every tracklet of an object's field into its RA/Dec series; in the
# cluster's field two thirds of them are the companions', taken at the same instants as the
# object's own. The isolation table separates the effects. One companion alone is a consistent
# wrong track: the predictors follow it, and the error is about the companions' separation.
# Mixed series are different: a minimal sample that takes points from two tracks is fitted by
# a strongly curved sinusoid-plus-drift (or, with two points at one instant, is degenerate — the
# prediction table's `note` column), which extrapolates far through an hour of eclipse; with only a handful of
# points per track no sample's consensus clearly beats the others, so RANSAC and WRANSAC can
# keep such a fit, while least squares averages all points into one smooth compromise whose
# error stays of the order of the separations. A is geometry, independent of the sky; C fails
# because the same two hours of the object's own tracklets predict to a few arcseconds; D
# confuses stages — the curve predictors use the angles, not the triangulated positions.

# %% [markdown]
# ## Exercise 5 — a wrong partner inside the epipolar gate (derivation)
#
# The gate is $g = \sigma_e\sqrt{\chi^2_1(0.99)}$ with $\sigma_e = \sqrt2 \times 0.3$ px. The
# measured epipolar distance of the wrong pair is $d_0 + \varepsilon$,
# $\varepsilon \sim N(0, \sigma_e^2)$; it is inside the gate when $-g < d_0 + \varepsilon < g$.

# %%
se = np.sqrt(2) * 0.3
g = se * np.sqrt(chi2.ppf(0.99, 1))
answer = norm.cdf((g - 0.5) / se) - norm.cdf((-g - 0.5) / se)
assert check("capstone.5", answer)
assert np.isclose(g, C.epipolar_gate_px())
print(f"g = {g:.3f} px, answer = {answer:.3f}")

# %% [markdown]
# Most of the time (the probability printed above) the wrong partner passes the gate: a gate
# only separates objects whose epipolar distance exceeds it by a few σ. The assignment then prefers the nearer
# candidate, so what matters is whether the wrong one is *nearer* than the true one — far less
# likely when the measured noise is, as here, smaller than the gate's conservative 0.3 px.

# %% [markdown]
# ## Exercise 6 — the velocity gate at 5″ pixels (computation)

# %%
rates = C.expected_rates(cfg)
span = (cfg.burst_frames - 1) * cfg.frame_interval_s
answer = max(1.5 * float(rates.to_numpy().max()) / 5.0, 2.0 / span)
assert check("capstone.6", answer)
assert np.isclose(answer, C.velocity_gate(C.with_changes(cfg, pixel_scale_arcsec=5.0)))
print(f"fastest rate {rates.to_numpy().max():.2f}″/s = {rates.to_numpy().max() / 5.0:.2f} px/s at "
      f"5″/px → answer = {answer:.3f} px/s")

# %% [markdown]
# Three times the 15″/px gate: the inclined 14128's rate in the staring frame (printed above)
# is beyond the old fixed 0.5 px/s at 5″ pixels, which is why its recall silently fell there.
# The rate is a property of the object, the gate in pixels a property of the camera.

# %% [markdown]
# [← the lesson: 07 · Capstone](../07_capstone_geo_surveillance.ipynb) ·
# [index](../00_index.ipynb)
