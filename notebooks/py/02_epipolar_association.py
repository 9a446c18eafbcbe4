# ---
# jupyter:
#   kernelspec:
#     display_name: Python 3 (ipykernel)
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 02 · Epipolar association of space targets across distributed star sensors
#
# **Paper.** Huang Qiushi, Zhang Yasheng, Feng Fei. *Space target synchronization association
# method under distributed star sensors.* Chinese Journal of Scientific Instrument.
# [DOI 10.19650/j.cnki.cjsi.J1905157](https://doi.org/10.19650/j.cnki.cjsi.J1905157) [1]
#
# **What the paper does.** Star sensors on several satellites image the same instant; the
# featureless dots must be matched across images by the **epipolar constraint** alone: from
# known poses and intrinsics, each image pair's fundamental matrix; a dot within $L$ pixels
# of the other's epipolar line is a candidate, the nearest wins; the pairs merge into one
# table of targets, each triangulated. Experiment: four LEO
# satellites, 2°×2° sensors, nine GEO objects.
#
# ## Learning objectives
#
# After this notebook you can
# - build and check the fundamental matrix of two posed cameras (eqs. 2–5);
# - compute point-to-line distances (eq. 8) and associate points one-to-one;
# - explain how $L$ trades missed against false associations, and derive $L$ from an error
#   budget;
# - triangulate from two lines of sight and say why short baselines hurt;
# - spot when a rule (3σ rejection) or a number (10 mrad jitter) in a paper cannot be right.
#
# **Prerequisites.** Pinhole cameras, rotation matrices; notebook 01 for the Monte Carlo
# conventions. Background: Hartley–Zisserman [2].

# %%
from eotrack.notebook import lesson_header
from IPython.display import Markdown, display

lesson_header("02")  # navigation and the verdict on the central claims (recomputed below)

# %% [markdown]
# ## Setup

# %%
import warnings
from itertools import combinations

import cv2
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from eotrack.astro.twobody import MU_EARTH_KM3_S2, elements_to_state
from eotrack.exercises import check
from eotrack.experiments import epipolar as E
from eotrack.geometry import (
    associate,
    combine_estimates,
    cross_matrix,
    epipolar_distances,
    fundamental_from_poses,
    intrinsics_from_fov,
    max_z_score,
    project_points,
    rot_x,
    rot_y,
    rot_z,
    rotation_321,
    summary_table,
    triangulate_rays,
    triangulate_two_rays,
)
from eotrack.montecarlo import TrialRunner, run_trials
from eotrack.notebook import dropdown, float_slider, panel, setup_notebook, versions
from eotrack.plotting import legend_outside

setup_notebook()

# %% tags=["parameters"]
QUICK = False  # True: the reduced counts of `make repro-quick`
N_DRAWS = E.N_DRAWS[QUICK]  # scenario draws (Fig. 5, Tables 3–5); the paper: 300 groups
N_SIMS = E.N_SIMS[QUICK]  # Fig. 6 simulations; the paper: 600
N_BEYOND = 60  # draws per setting in "Beyond the paper"
N_PLACE = 100  # draws per perturbed placement (Beyond; the main run's first draws)

# %%
versions()

# %% [markdown]
# ## Notation
#
# | paper | code | meaning | unit |
# |---|---|---|---|
# | $p=(u,v,1)$ | `pts1`, `pts2` | homogeneous pixel coordinates of a centroid (u = column) | px |
# | $F_{1\text{-}2}$ | `fundamental_from_poses(K1, R1, c1, K2, R2, c2)` | fundamental matrix, $p_2^\top F p_1 = 0$ | – |
# | $M_1, M_2$ | `K1`, `K2` | intrinsic matrices (eqs. 6–7) | px |
# | $r$ | `cam.R` | reference (J2000) → camera rotation | – |
# | $Y, P, R$ | `yaw`, `pitch`, `roll` | angles of eq. (4) | rad |
# | $R_{1\text{-}2}$, $t$, $S_{1\text{-}2}$ | `relative_pose`, `cross_matrix(t)` | relative rotation, centre of camera 2 in camera-1 coordinates, $[t]_\times$ | –, km |
# | $O_1, O_2$ | `cam.c` | camera centres (satellite positions) | km |
# | $L$ | `threshold` | association gate (eq. 8) | px |
# | $\sigma_d$ | `error_budget_gate(...)[0]` | predicted spread of a true pair's distance | px |
# | $C_N^2$ | `E.PAIRS` | the map pairs (a)–(f) of Fig. 4 | – |

# %% [markdown]
# ## The method, step by step
#
# ### 1. The scene: four sensors and nine GEO objects (paper Figs. 1–2)
#
# Table 1's elements are given *at the association instant*: two-body states suffice [6]
# (check: energy $-\mu/2a$).
#
# The paper's STK scene is known only through Table 3's pixels and Table 5's two positions.
# We rebuild it: GEO1 at its Table 5 position, on its Table 3 pixel of map 4; the other
# objects where sensor 4's rays through their Table 3 pixels meet GEO1's shell; sensors 1–3
# turned to see exactly Table 3's objects. GEO5 thus follows Table 3, not Table 5 (section
# *Tables 3 and 5 disagree*).

# %%
P = E.paper_values()
t1 = P["epipolar.table1"]
r_sat, v_sat = elements_to_state(t1["a_km"], t1["e"], t1["i_deg"], t1["raan_deg"],
                                 t1["argp_deg"], t1["nu_deg"])
energy = np.einsum("ij,ij->i", v_sat, v_sat) / 2 - MU_EARTH_KM3_S2 / np.linalg.norm(r_sat, axis=1)
np.testing.assert_allclose(energy, -MU_EARTH_KM3_S2 / (2 * np.asarray(t1["a_km"])), rtol=1e-12)

scen = E.build_scenario()
assert np.allclose(scen.sat_km, r_sat) and scen.los_clear[scen.visible].all()
assert not np.any(scen.visible[1] & scen.visible[2])  # maps 2 and 3 share no object
pd.DataFrame(scen.visible.astype(int), index=[f"map {k + 1}" for k in range(4)],
             columns=scen.names)

# %% [markdown]
# Two sensors and a target span the **epipolar plane** through the baseline $O_1O_2$. Sensor
# 1's line of sight projects into image 2 onto one line, the *epipolar line*, and the
# target's image 2 must lie on it: the whole association test. At true scale:

# %%
fig = E.plot_epipolar_geometry(scen, pair=(0, 3), target=4)

# %% [markdown]
# ### 2. Frames and attitude: eq. (4)
#
# A J2000 direction reaches the sensor frame through J2000 → orbit frame (from position and
# velocity) → body (attitude angles) → sensor (mounting). The paper writes the attitude step as a product of *passive* rotations
#
# $$ r = R_z(Y)\,R_y(P)\,R_x(R)=
#   \begin{bmatrix}\cos Y&\sin Y&0\\-\sin Y&\cos Y&0\\0&0&1\end{bmatrix}
#   \begin{bmatrix}\cos P&0&-\sin P\\0&1&0\\\sin P&0&\cos P\end{bmatrix}
#   \begin{bmatrix}1&0&0\\0&\cos R&\sin R\\0&-\sin R&\cos R\end{bmatrix}
#   \qquad(4)$$
#
# Only the product enters $F$; the mounting (not in the paper) is assumed for illustration.

# %%
fig = E.plot_frame_chain(scen, 0)

# %%
# NBVAL_CHECK_OUTPUT
ch = E.frame_chain(scen, 0)
Y, Pp, Rr = 0.3, -0.4, 1.1
r = rotation_321(Y, Pp, Rr)
checks = {
    "r = Rz(Y) Ry(P) Rx(R)": np.allclose(r, rot_z(Y) @ rot_y(Pp) @ rot_x(Rr)),
    "r is a proper rotation": bool(np.allclose(r @ r.T, np.eye(3))
                                  and np.isclose(np.linalg.det(r), 1)),
    "chain product = sensor 1's camera R": np.allclose(ch.sensor, scen.cameras[0].R),
    "orbit frame z points to nadir": np.allclose(ch.orbit[2], -ch.position_km
                                                 / np.linalg.norm(ch.position_km)),
}
print(checks)
assert all(checks.values())

# %% [markdown]
# ### 3. Intrinsics: eqs. (6)–(7)
#
# $$M=\begin{bmatrix}f/d_x&0&u_0\\0&f/d_y&v_0\\0&0&1\end{bmatrix},\qquad
#   \frac{f}{d_x}=\frac{N_x}{2\tan(fov_x/2)} \qquad(6,7)$$
#
# Check: a direction half the field of view (1°) off the axis lands half an image from the
# principal point.
# Table 2's sensor parameters are in the *Reproduction* section.

# %%
sensor = E.SensorConfig()
K = intrinsics_from_fov(sensor.fov_deg, sensor.fov_deg, sensor.resolution_px,
                        sensor.resolution_px, *sensor.principal_point_px)
half_fov = np.radians(sensor.fov_deg / 2)
uv = project_points([[np.tan(half_fov), 0.0, 1.0]], K, np.eye(3), np.zeros(3))
np.testing.assert_allclose(uv[0] - sensor.principal_point_px, [sensor.resolution_px / 2, 0])
display(Markdown(f"{sensor.fov_deg / 2:g}° off the axis lands {uv[0, 0] - K[0, 2]:.1f} px from "
                 f"the principal point, half the {sensor.resolution_px} px image. f/dx = "
                 f"{K[0, 0]:.0f} px, so one pixel is {206264.8 / K[0, 0]:.2f}″ and one "
                 f"arcminute is {K[0, 0] * np.radians(1 / 60):.2f} px."))

# %% [markdown]
# ### 4. The fundamental matrix from poses: eqs. (2), (3), (5)
#
# Let $r_1, r_2$ be the reference → camera rotations and $O_1, O_2$ the camera centres. A point
# $X$ has camera coordinates $P_1 = r_1(X-O_1)$ and $P_2 = r_2(X-O_2)$. With
# $R_{12} = r_2 r_1^{-1}$ (eq. 3) and $t = r_1(O_2-O_1)$ — camera 2's centre in camera-1
# coordinates — we get $P_2 = R_{12}(P_1 - t)$. Since
# $(P_1-t)^\top [t]_\times P_1 = P_1^\top (t\times P_1) - t^\top(t \times P_1) = 0$,
#
# $$P_2^\top\,R_{12}[t]_\times\,P_1 = 0 \;\Rightarrow\;
#   p_2^\top\,\underbrace{M_2^{-\top}R_{12}S_{12}M_1^{-1}}_{F_{1\text{-}2}}\,p_1 = 0,
#   \qquad S_{12} = [t]_\times \qquad(2,5)$$
#
# because $P_i \propto M_i^{-1}p_i$. Checks on the true scenario: $p_2^\top F p_1 \approx 0$
# for every object two maps share, and OpenCV's stereo convention ($x_2 = Rx_1 + T$,
# $E=[T]_\times R$) gives the same $F$ up to sign.

# %%
X = scen.objects_km
for a, b in combinations(range(4), 2):
    ca, cb = scen.cameras[a], scen.cameras[b]
    F = fundamental_from_poses(ca.K, ca.R, ca.c, cb.K, cb.R, cb.c)
    common = scen.visible[a] & scen.visible[b]
    if common.any():
        h1 = np.column_stack([ca.project(X[common]), np.ones(common.sum())])
        h2 = np.column_stack([cb.project(X[common]), np.ones(common.sum())])
        assert np.abs(np.einsum("ni,ij,nj->n", h2, F, h1)).max() < 1e-5
    F_cv = np.linalg.inv(cb.K).T @ cross_matrix(cb.R @ (ca.c - cb.c)) @ cb.R @ ca.R.T \
        @ np.linalg.inv(ca.K)
    F_cv /= np.linalg.norm(F_cv)
    assert min(np.abs(F - F_cv).max(), np.abs(F + F_cv).max()) < 1e-9
print("p2ᵀ F p1 ≈ 0 for all shared objects; F = OpenCV's [T]ₓR form up to sign")

# %% [markdown]
# ### 5. Distance to the epipolar line: eq. (8)
#
# With $Fp_1 = (a,b,c)$, $d = |p_2^\top F p_1|/\sqrt{a^2+b^2}$; $p_2$ is a candidate if
# $d < L$ (printed "$\ll L$"). `epipolar_distances(F, pts1, pts2)` returns the $(n_1, n_2)$
# matrix, matches `cv2.computeCorrespondEpilines` [3] and ignores the scale of $F$.

# %%
rng = np.random.default_rng(0)
p1, p2 = rng.uniform(0, 512, (6, 2)), rng.uniform(0, 512, (5, 2))
d = epipolar_distances(F, p1, p2)
lines = cv2.computeCorrespondEpilines(p1.reshape(-1, 1, 2), 1, F).reshape(-1, 3)
np.testing.assert_allclose(d, np.abs(lines[:, :2] @ p2.T + lines[:, 2:]), atol=1e-6)
np.testing.assert_allclose(epipolar_distances(-37.0 * F, p1, p2), d)

# %% [markdown]
# ### 6. Association (steps 4–5) and the summary table (step 6)
#
# Each point keeps its nearest candidate, each point used once: one greedy pass over all
# candidate pairs in increasing distance (errata). The global `rule="hungarian"` [4]
# maximises the number of pairs first. They differ when the nearest candidate is another
# point's only one:

# %%
# NBVAL_CHECK_OUTPUT
dist = np.array([[1.0, 2.0], [1.1, 20.0]])
print("paper rule:", associate(dist, 10.0).tolist(), "  global:",
      associate(dist, 10.0, rule="hungarian").tolist())

# %% [markdown]
# The summary (Table 3) takes the maps in order: an element joins a row if associated with
# *every* earlier element of it, else starts a row. By hand: A in all three maps, B in maps 1
# and 3, a lone point in map 3.

# %%
# NBVAL_CHECK_OUTPUT
rows = summary_table([2, 1, 3], {(0, 1): [[0, 0]], (0, 2): [[0, 0], [1, 1]], (1, 2): [[0, 0]]})
print(rows.tolist())
assert rows.tolist() == [[0, 0, 0], [1, -1, 1], [-1, -1, 2]]

# %% [markdown]
# ### 7. Triangulation and the 3σ rule (§3, paper Fig. 7)
#
# Two lines of sight rarely meet; the estimate is the midpoint of their closest-approach
# segment; $N$ lines give the least-squares point. Both exact without noise:

# %%
Xt = X[4]
rays = [cam.rays(cam.project(Xt[None]))[0] for cam in scen.cameras]
np.testing.assert_allclose(triangulate_two_rays(scen.cameras[0].c, rays[0],
                                                scen.cameras[3].c, rays[3]), Xt, atol=0.5)
np.testing.assert_allclose(triangulate_rays(np.stack([c.c for c in scen.cameras]),
                                            np.stack(rays)), Xt, atol=0.5)

# %% [markdown]
# With $N$ sensors there are $C_N^2$ pairwise estimates; the paper discards any with a
# coordinate beyond 3 standard deviations of the mean. **That rule cannot fire for
# $n \le 10$**: the largest possible $|x_i - \bar x|/s$ among $n$ samples is
# $(n-1)/\sqrt n$ ($s$ with $n-1$; Samuelson's inequality [7]; exercise 1).
# `combine_estimates(rule="mad")` (median ± k·MAD) can reject:

# %%
# NBVAL_CHECK_OUTPUT
est = np.array([[0.0, 0, 0], [2.0, 1, 0], [300.0, 0, 0]])
print("max z-score for n = 2, 3, 10:", [round(float(max_z_score(n)), 2) for n in (2, 3, 10)])
print("paper rule keeps", combine_estimates(est, rule="paper").kept.tolist(),
      "| MAD rule keeps", combine_estimates(est, rule="mad").kept.tolist())

# %% [markdown]
# ### 8. The errors injected (§2.1)
#
# * **Attitude:** uniform within ±1′ on each angle of eq. (4).
# * **Position:** uniform in a 0.2 km ball.
# * **Jitter:** printed "10 mrad" (below); we read 10 µrad, about the noise-equivalent angle.
# * **False targets:** number unstated; three per map.
# * **Distortion:** in the true projection only; the associator ignores it.

# %%
err = E.ErrorConfig()
L_PAPER = float(P["epipolar.fig4"]["threshold_px"])
sw_mrad, sw_urad = (E.run_sweep(scen, E.ErrorConfig(jitter_urad=j), [L_PAPER], 30,
                                runner=TrialRunner(progress=False)) for j in (1e4, 10.0))
ranges = np.linalg.norm(scen.objects_km[None] - scen.sat_km[:, None], axis=2)[scen.visible]
rng_min, rng_max = ranges.min(), ranges.max()
display(Markdown(f"In pixels: 1′ = {K[0, 0] * E.ARCMIN:.2f} px; {err.position_km:g} km seen "
                 f"from {rng_min:,.0f}–{rng_max:,.0f} km (our ranges) = "
                 f"{err.position_km / rng_max * K[0, 0]:.3f}–{err.position_km / rng_min * K[0, 0]:.3f} "
                 f"px; jitter {err.jitter_urad:g} µrad = "
                 f"{err.jitter_urad * 1e-6 * K[0, 0]:.3f} px rms. The printed 10 mrad would "
                 f"be {10e-3 * K[0, 0]:.1f} px rms — {10e-3 * K[0, 0] / L_PAPER:.0f} times "
                 f"the paper's own threshold L = {L_PAPER:g} px: in 30 draws with it, only "
                 f"{100 * sw_mrad.accuracy[0]:.0f} % of the true pairs are associated at L "
                 f"(against {100 * sw_urad.accuracy[0]:.0f} % with 10 µrad)."))

# %% [markdown]
# ### 9. One trial by hand
#
# One instant (seed 2019, shown in Figs. 3–4): draw the errors; per map pair, $F$ from the
# *measured* poses, distances, association at $L = 10$ px; then the summary.

# %%
L = float(P["epipolar.fig4"]["threshold_px"])
obs = E.draw_observation(np.random.default_rng(2019), scen, err)
by_hand = {}
for a, b in E.PAIRS:
    ca, cb = obs.cameras[a], obs.cameras[b]
    F_ab = fundamental_from_poses(ca.K, ca.R, ca.c, cb.K, cb.R, cb.c)
    by_hand[(a, b)] = associate(epipolar_distances(F_ab, obs.points[a], obs.points[b]), L)
rows_hand = summary_table([len(p) for p in obs.points], by_hand)
rows_hand = rows_hand[(rows_hand >= 0).sum(1) >= 2]  # the paper lists multi-map rows

draw = E.displayed_draw(scen, err, L)  # the same steps, as the report runs them
assert np.array_equal(rows_hand, draw.rows)
assert all(np.array_equal(by_hand[k], draw.matches[k][0]) for k in E.PAIRS)
draw.scores

# %% [markdown]
# `true`: objects both maps see; `false`: associations with a false target or wrong object.
#
# ## Reproduction
#
# The Monte Carlo behind Fig. 5 and Tables 3–5, and the Fig. 6 simulations — the
# configuration and seeds of `make repro`:

# %%
runner = TrialRunner(progress=False)
mc = E.run_scenario_draws(scen, err, E.THRESHOLDS, L, N_DRAWS, runner=runner)
res6 = E.run_fig6(N_SIMS, P["epipolar.fig6"]["threshold_px"], P["epipolar.fig6"]["n_points"],
                  runner=runner)
display(Markdown(f"{mc.n_draws} scenario draws, {mc.sweep.n_true} true pairs; "
                 f"{len(res6['overlapping'][0])} Fig. 6 simulations per variant."))

# %% [markdown]
# ### Table 1 — the sensor satellites

# %%
E.table1(scen)

# %% [markdown]
# ### Table 2 — the sensors
#
# From the configs (`E.ST_APS2_2`, `E.SensorConfig()`), with the focal length of eq. (7).

# %%
E.sensor_table()

# %% [markdown]
# ### Fig. 3 — the four star maps
#
# Gaia DR3 stars [5] to G = 10 (epoch 2019.25) plus synthetic stars to Mv 13. Objects
# circled, false targets boxed.

# %%
images = E.render_maps(scen, draw.obs, np.random.default_rng(7))
fig = E.plot_fig3(scen, draw.obs, images)

# %% [markdown]
# ### Fig. 4 — pairwise associations at L = 10 px
#
# Green: correct; red: false. Maps 2 and 3 share no object (panel d), as in the paper.

# %%
fig = E.plot_fig4(scen, draw.obs, draw.matches)

# %% [markdown]
# False targets, and objects seen by one sensor of a pair, often lie within 10 px of a
# foreign epipolar line: false associations like Fig. 4(e) are common. Some *objects* nearly
# lie on each other's lines:

# %%
pd.Series(E.closest_other_object_px(scen),
          name="closest other object to an epipolar line, noise-free (px)").to_frame()

# %% [markdown]
# How are true pairs lost: beyond $L$ (noise), or taken by a nearer wrong candidate?

# %%
true_d_all = np.concatenate([o["true_d"] for o in mc.trials])
n_missed, n_far = mc.total("missed_nominal"), int(np.sum(true_d_all >= L))
share_all = float(np.mean(mc.stack("all_true_associated")))
assert n_far == 0  # "every lost true pair was taken by a nearer wrong candidate" (Beyond)
display(Markdown(
    f"Over {mc.n_draws} draws at L = {L:g} px: {n_missed} of {len(true_d_all)} true pairs "
    f"lost — {n_far} beyond L, {n_missed - n_far} taken by a nearer wrong candidate. Every "
    f"true pair of a draw is associated (as in the paper's Fig. 4) in {100 * share_all:.0f} % "
    "of the draws."))

# %% [markdown]
# ### Table 3 — the summary table
#
# Paper's pixels beside our noise-free true pixels, and the displayed draw's rows for each
# object, each element labelled by its true identity (`false`: a false target, `·`: none).
# Map 4 matches by construction; maps 1–3 do not — by how much?

# %%
E.table3(scen, draw)

# %%
true_px = scen.true_pixels()
miss_px = np.linalg.norm(true_px - scen.paper_px, axis=2)  # NaN where Table 3 has no entry
miss = pd.DataFrame(np.round(miss_px, 1), index=[f"map {k + 1}" for k in range(4)],
                    columns=scen.names)
worst = np.unravel_index(np.nanargmax(miss_px), miss_px.shape)
display(Markdown(f"|our pixel − Table 3's| (px), noise-free. Largest: "
                 f"{miss_px[worst]:.0f} px ({scen.names[worst[1]]}, map {worst[0] + 1}); per map "
                 "the largest is " + ", ".join(f"{np.nanmax(miss_px[k]):.0f}" for k in range(4))
                 + " px."))
miss

# %% [markdown]
# Is that our fit's fault? Free each sensor's attitude entirely and find the rotation that
# best maps the object directions onto Table 3's rays (Wahba's problem [8],
# `Rotation.align_vectors`); its residuals are what no attitude can remove:

# %%
from scipy.spatial.transform import Rotation

fit = {}
for k, cam in enumerate(scen.cameras):
    idx = np.flatnonzero(scen.visible[k])
    rays_t3 = np.linalg.solve(cam.K, np.column_stack([scen.paper_px[k, idx],
                                                      np.ones(len(idx))]).T).T
    dirs = scen.objects_km[idx] - cam.c
    rot, _ = Rotation.align_vectors(rays_t3 / np.linalg.norm(rays_t3, axis=1, keepdims=True),
                                    dirs / np.linalg.norm(dirs, axis=1, keepdims=True))
    best = project_points(scen.objects_km[idx], cam.K, rot.as_matrix(), cam.c)
    res = np.linalg.norm(best - scen.paper_px[k, idx], axis=1)
    fit[f"map {k + 1}"] = {"objects": len(idx), "rms residual (px)": np.sqrt(np.mean(res**2)),
                           "max residual (px)": res.max()}
fit = pd.DataFrame(fit).T
assert fit.loc["map 4", "max residual (px)"] < 0.5  # map 4 built from its own pixels
r13 = fit.iloc[:3]
display(Markdown(
    f"Map 4's pixels are met to {fit.loc['map 4', 'max residual (px)']:.1e} px; for maps 1–3 "
    f"even the best free rotation leaves {r13['rms residual (px)'].min():.0f}–"
    f"{r13['rms residual (px)'].max():.0f} px rms (up to {r13['max residual (px)'].max():.0f} "
    "px): Table 3's four maps cannot all be views of one set of points on the GEO shell from "
    "the Table 1 positions. Our maps 1–3 keep Table 3's *visibility pattern* (which objects "
    "each map sees) — what association depends on — not its pixels."))
fit.round(1)

# %%
rec = mc.stack("objects_recovered")
n_obj = len(scen.names)
display(Markdown(
    f"Displayed draw: {E.objects_recovered(draw.obs, draw.rows, scen)}/{n_obj} objects "
    f"recovered exactly. Over {mc.n_draws} draws: {rec.mean():.1f}/{n_obj} on average, all "
    f"nine in {100 * np.mean(rec == n_obj):.0f} % of draws."))

# %% [markdown]
# The summary rule is unforgiving: one wrong pairwise association splits an object's row.
#
# ### Table 4 — mean distance to the epipolar line

# %%
t4 = E.table4(draw, mc)
t4

# %% [markdown]
# The claim is an ordering, so it is decided over all draws: each draw has a noise-free twin
# with the *same* false targets (common random numbers); the paired difference per map pair
# gets a t interval at family-wise 95 % (Bonferroni [11] over the five pairs sharing objects):

# %%
t4p = E.table4_paired(scen, mc)
t4p_show = t4p.assign(pair=[f"{a + 1}-{b + 1}" for a, b in t4p["pair"]]).round(3)
assert (t4p["n_draws"] >= 20).all()
assert (t4p["ci_low"] > 0).all()  # the prose below relies on it
t4p_show

# %% [markdown]
# Every interval lies above zero: noise does push associated points away from their lines.
# The *levels* do not match, and the error budget (Beyond) says why: a true pair's signed
# distance is roughly Gaussian with the pair's σ_d, so its mean |d| is σ_d√(2/π).

# %%
p4 = P["epipolar.table4"]
sig_pair = E.distance_sigma_px(scen, err).groupby("pair")["sigma_px"].mean()
paper_noisy = pd.Series(p4["mean_distance_noisy_px"], index=p4["pairs"])
with warnings.catch_warnings():
    warnings.simplefilter("ignore", RuntimeWarning)  # pair (d) has no correct pairs
    ours_true = pd.Series(np.nanmean(mc.stack("mean_d_true"), 0), index=p4["pairs"])
levels = pd.DataFrame({"σ_d (px)": sig_pair,
                       "σ_d√(2/π) (px)": sig_pair * np.sqrt(2 / np.pi),
                       "ours noisy, correct pairs (px)": ours_true,
                       "paper noisy (px)": paper_noisy,
                       "σ_d the paper's mean needs (px)": paper_noisy / np.sqrt(2 / np.pi)})
levels["needed / our σ_d"] = levels.iloc[:, 4] / levels.iloc[:, 0]
levels = levels.dropna(subset=["σ_d (px)"])
# the earlier criteria (claims.toml history): the displayed draw's noisy means in 1–10 px
# (first), then all intervals above 0 and the over-draw noisy means in 1–10 px (second)
disp_noisy = draw.scores.set_index("pair")["mean_distance_px"]
old_fail = disp_noisy[(disp_noisy <= 1) | (disp_noisy >= 10)]
assert len(old_fail) >= 1  # the prose below relies on it
second_ok = bool((t4p["ci_low"] > 0).all() and t4p["noisy mean (px)"].between(1, 10).all())
md_all = mc.stack("mean_d")  # per draw and pair: noisy mean of all associated points


def share_reaching(k, v):
    col = md_all[:, list(p4["pairs"]).index(k)]
    return float(np.mean(col[np.isfinite(col)] >= v)) if np.isfinite(v) else np.nan


levels["share of draws ≥ paper's"] = [share_reaching(k, v)
                                      for k, v in levels["paper noisy (px)"].items()]
display(Markdown(
    f"The prediction meets our correct pairs to within "
    f"{100 * np.nanmax(np.abs(levels.iloc[:, 2] / levels.iloc[:, 1] - 1)):.0f} %. The "
    f"paper's noisy means would need σ_d "
    f"{levels['needed / our σ_d'].min():.1f}–{levels['needed / our σ_d'].max():.1f} times "
    f"ours — larger errors than a uniform ±1′ (even read as rms, the attitude term grows "
    f"only √3 = {3**0.5:.2f}×). So the claim is scored **partial**: ordering yes, level no "
    f"(the criterion asks 0.5–2 times the paper's). The paper's values are one run: the last "
    f"column is the share of our single draws whose noisy mean reaches it. That level band "
    f"was set after results (history): under the first, one-draw criterion the displayed "
    f"draw's {old_fail.index[0]} noisy mean {old_fail.iloc[0]:.3f} px lies outside its "
    f"1–10 px (not reproduced); under the second (over-draw means in 1–10 px) the claim "
    f"{'would be reproduced' if second_ok else 'would not be reproduced either'} — a band "
    "far wider than the gap to the paper, so it was tightened."))
levels.round(3)

# %% [markdown]
# Noise-free, our correct pairs sit at ≈ 0 px (only the ignored lens distortion): our
# noise-free means come from false associations. The paper's 0.2–3.9 px need an unstated
# error (it reports one false association, in 4(e)); whole-pixel centroids explain a few
# tenths of a pixel (*Beyond*). Not scored.

# %%
with warnings.catch_warnings():
    warnings.simplefilter("ignore", RuntimeWarning)
    assert np.nanmax(np.nanmean(mc.stack("mean_d0_true"), 0)) < 0.05  # prose above

# %% [markdown]
# **Row 4(a)** holds a single number, 1.387, of unknown column. By size it fits the
# noise-free column:

# %%
lone = p4["row_a_unplaced_px"]
free_rng = np.nanmin(p4["mean_distance_noise_free_px"]), np.nanmax(p4["mean_distance_noise_free_px"])
noisy_rng = np.nanmin(p4["mean_distance_noisy_px"]), np.nanmax(p4["mean_distance_noisy_px"])
display(Markdown(f"1.387 px against the other rows: noise-free {free_rng[0]:.3f}–"
                 f"{free_rng[1]:.3f} px (inside: {free_rng[0] <= lone <= free_rng[1]}), noisy "
                 f"{noisy_rng[0]:.3f}–{noisy_rng[1]:.3f} px (inside: "
                 f"{noisy_rng[0] <= lone <= noisy_rng[1]}). We leave it unplaced (NaN in both "
                 "columns of claims.toml) and compare no number with it."))

# %% [markdown]
# ### Fig. 5 — threshold versus error rate

# %%
sw = mc.sweep
ax = E.plot_fig5(sw.thresholds, sw.accuracy, sw.false_rate, sw.miss_rate, sw.error_rate,
                 paper=P["epipolar.fig5"])

# %% [markdown]
# What is "≈ 90 % correct"? The paper counts falsely associated pairs (误判率, Fig. 5's
# axis) among the 1,032 pairs it **associated**: read so, its 90 % is correct *of the
# associated pairs*. Our first criterion
# used correct *of the true pairs*, the reading that favours the paper; the criterion (set
# after results) now requires both. Bootstrap [10] intervals over the draws (2,000 resamples,
# family-wise 95 %) for the best threshold and each reading's best in-band rate:

# %%
boot5 = E.fig5_bootstrap(mc, tuple(P["epipolar.fig5"]["best_threshold_px"]),
                         confidence=1 - 0.05 / 3)
f5 = E.fig5_summary(sw, boot5)
assert 0.80 < f5.loc[0, "ours"] < 0.95  # Monte Carlo: checked with a tolerance
assert boot5["prec_ci"][1] < 0.85  # the prose below relies on it
assert boot5["best_L_ci"][1] < P["epipolar.fig5"]["best_threshold_px"][0]  # prose below
n_assoc = float(sw.n_associated[sw.thresholds == L][0])
display(Markdown(
    f"Per group: the paper's {P['epipolar.fig5']['n_associated_pairs']} associated pairs over "
    f"{P['epipolar.fig5']['n_groups']} groups are "
    f"{P['epipolar.fig5']['n_associated_pairs'] / P['epipolar.fig5']['n_groups']:.2f} per "
    f"group; ours at L = {L:g} px are {n_assoc / mc.n_draws:.1f} per four-map draw and "
    f"{n_assoc / mc.n_draws / len(E.PAIRS):.2f} per map pair."))
f5

# %% [markdown]
# Small thresholds miss true pairs, large ones admit false pairs, as the paper says. In its
# reading our best in-band rate stays below 85 % (interval), and the best threshold's
# interval excludes 8–12 px: not reproduced. The paper's "group" matches our *map pair*
# (pairs per group, above); pooled rates do not depend on the grouping.
#
# ### Fig. 6 — the Monte Carlo bound on false association
#
# Our setting is stated: 512×512 images, 100 uniform points each, a point with more than one
# candidate counts as wrong; F drawn **at random** (the paper's words; i.i.d. normal
# entries, rank 2) or from **overlapping views** (ours, the scene's geometry). Dashed: the expectation $P(N\ge2)$,
# $N\sim\mathrm{Bin}(100,\,2L\ell/512^2)$, ℓ the line's length inside the image.

# %%
L6 = np.asarray(P["epipolar.fig6"]["threshold_px"], float)
fig, axs = plt.subplots(1, 2, figsize=(7.2, 4.2), sharey=True, layout="constrained")
for ax, mode, title in ((axs[0], "random_f", "Fig. 6 — random F (paper's wording)"),
                        (axs[1], "overlapping", "overlapping views (ours)")):
    run, an, _ = res6[mode]
    E.plot_fig6({Lv: run[:, i] for i, Lv in enumerate(L6)},
                {Lv: an[i] for i, Lv in enumerate(L6)}, P["epipolar.fig6"], ax=ax, title=title,
                legend=False)
leg = legend_outside(fig, where="below", ncol=5)

# %%
f6 = E.fig6_table(res6)
assert np.allclose(f6["ours MC (overlapping views)"], f6["binomial (overlapping)"], atol=0.02)
assert np.allclose(f6["ours MC (random F)"], f6["binomial (random F)"], atol=0.02)
n6, w6 = int(P["epipolar.fig6"]["n_points"]), sensor.resolution_px
display(Markdown(f"A {L6[0]:g} px band around a line crossing a {w6}×{w6} image (ℓ = {w6} px, "
                 f"a horizontal line) holds 2·L·ℓ·n/{w6}² = {2 * L6[0] * w6 * n6 / w6**2:.1f} "
                 f"of the other image's n = {n6} points on average; two or more make the "
                 "point count as wrong."))
f6

# %% [markdown]
# Both simulations agree with their expectation; neither comes near the paper (band count
# above the table).
#
# ### Table 5 — triangulation of GEO1 and GEO5 (J2000, km)

# %%
t5, estimates = E.table5(scen, draw)
t5

# %% [markdown]
# Under Table 3 only sensors 1 and 4 see GEO1: one estimate. Our errors are far above 3 km:
# two nearly parallel lines of sight, each off by up to 1′ per angle, whose midpoint slides
# far along them (numbers below).

# %%
ax = E.plot_triangulation(scen, draw.obs, pair=(0, 3), target=4)

# %%
tri = mc.stack("tri_err_km")
base = [np.linalg.norm(scen.sat_km[a] - scen.sat_km[b]) for a, b in E.PAIRS]
rng_km = np.linalg.norm(scen.objects_km[4] - scen.sat_km[3])
has_row = np.isfinite(tri).mean(0)
display(Markdown(f"Over {mc.n_draws} draws, the median largest coordinate error of the "
                 f"combined estimate is {np.nanmedian(tri[:, 0]):.0f} km (GEO1) and "
                 f"{np.nanmedian(tri[:, 1]):.0f} km (GEO5), over the {100 * has_row[0]:.0f} % "
                 f"and {100 * has_row[1]:.0f} % of draws in which the object has a row. At a range of {rng_km:,.0f} km "
                 f"an error of {err.attitude_arcmin:g}′ moves a line of sight by "
                 f"{rng_km * err.attitude_arcmin * E.ARCMIN:.1f} km; the baselines are only "
                 f"{min(base):,.0f}–{max(base):,.0f} km."))

# %% [markdown]
# ### Fig. 8 — the two objects in J2000

# %%
ax = E.plot_fig8(scen, estimates, paper=P["epipolar.table5"])  # diamonds: the paper's

# %% [markdown]
# ### Tables 3 and 5 disagree — which table each object follows, and what the other choice changes
#
# Table 5 gives true positions for GEO1 and GEO5; Table 3 gives their pixels in map 4. The two
# cannot both hold:

# %%
t5p = P["epipolar.table5"]
geo1_t5, geo5_t5 = np.asarray(t5p["geo1_km"][-1]), np.asarray(t5p["geo5_km"][-1])
cam4, sat4 = scen.cameras[3], scen.sat_km[3]


def seen_angle_deg(x1, x2, c):
    u, w = x1 - c, x2 - c
    return float(np.degrees(np.arccos(u @ w / np.linalg.norm(u) / np.linalg.norm(w))))


sep = {"ours": float(np.linalg.norm(scen.objects_km[0] - scen.objects_km[4])),
       "t5": float(np.linalg.norm(geo1_t5 - geo5_t5))}
ang = {"ours": seen_angle_deg(scen.objects_km[0], scen.objects_km[4], sat4),
       "t5": seen_angle_deg(geo1_t5, geo5_t5, sat4)}
uv5_t5 = cam4.project(geo5_t5[None])[0]
sees_t5 = [bool(c.sees(geo5_t5[None])[0]) for c in scen.cameras]
contradiction = pd.DataFrame({
    "Table 3 (our scene)": [f"{scen.objects_km[4, 2]:.2f}", f"{sep['ours']:.0f}",
                            f"{ang['ours']:.3f}",
                            f"{np.linalg.norm(scen.paper_px[3, 0] - scen.paper_px[3, 4]):.0f}",
                            "({:.0f}, {:.0f})".format(*scen.paper_px[3, 4]),
                            ", ".join(str(k + 1) for k in np.flatnonzero(scen.visible[:, 4]))],
    "Table 5": [f"{geo5_t5[2]:.2f}", f"{sep['t5']:.0f}", f"{ang['t5']:.3f}",
                f"{np.radians(ang['t5']) * cam4.K[0, 0]:.0f}",
                "({:.0f}, {:.0f})".format(*uv5_t5),
                ", ".join(str(k + 1) for k, v in enumerate(sees_t5) if v) or "none"]},
    index=["GEO5 Z (km)", "GEO1–GEO5 separation (km)", "GEO1–GEO5 seen from Sat4 (°)",
           "GEO1–GEO5 in map 4 (px)", "GEO5 pixel in map 4 (u, v)",
           "maps that see GEO5 (our pointings)"])
assert uv5_t5[1] > cam4.size[1] and not sees_t5[3]  # Table 5's GEO5 falls outside image 4
assert sees_t5 == [True, False, False, False]  # the prose below relies on it
display(Markdown(f"Our GEO5 is {np.linalg.norm(scen.objects_km[4] - geo5_t5):.0f} km from "
                 f"Table 5's; seen from Sat4, Table 5's GEO1–GEO5 angle is "
                 f"{np.radians(ang['t5']) * cam4.K[0, 0]:.0f} px, but Table 3 puts them "
                 f"{np.linalg.norm(scen.paper_px[3, 0] - scen.paper_px[3, 4]):.0f} px apart."))
contradiction

# %% [markdown]
# **Which table each object follows.** GEO1 both (Table 5's position, Table 3's map-4
# pixel); GEO2–GEO9, GEO5 included, Table 3's map 4: Table 3 fixes who sees whom, which is
# what association tests; Table 5 is an output. At its Table 5 position GEO5 leaves image 4.
#
# **What the other choice changes.** Put GEO5 there, re-point the sensors that lose it just
# enough to keep Table 3's visibility (`E.repointed_scenario`; map 4 then no longer meets
# Table 3's pixels exactly), and re-run Table 3, Fig. 5 and the triangulation behind Fig. 8
# on both scenes with the same draws (Wilson [9] and bootstrap [10] intervals):

# %%
X_t5 = scen.objects_km.copy()
X_t5[4] = geo5_t5
scen_t5 = E.repointed_scenario(scen, X_t5)
moved = [k + 1 for k, (c0, c1) in enumerate(zip(scen.cameras, scen_t5.cameras))
         if not np.array_equal(c0.R, c1.R)]
shift = np.linalg.norm(scen_t5.true_pixels() - scen.true_pixels(), axis=2)
others = np.delete(np.arange(len(scen.names)), 4)
shift_o = np.where(scen.visible[:, others], shift[:, others], np.nan)
assert scen_t5.los_clear[scen_t5.visible].all() and np.array_equal(scen_t5.visible, scen.visible)
pl_t5 = E.placement_study({"GEO5 from Table 3 (ours)": scen, "GEO5 from Table 5": scen_t5},
                          err, E.THRESHOLDS, L, mc.n_draws, runner=runner)  # mc's seed
t5_effect = pl_t5.drop(columns=["mean, 95 % t"])
ours_ = t5_effect.iloc[0]
assert np.isclose(ours_["objects recovered (mean)"], rec.mean())  # the same draws as mc
assert np.isclose(ours_["GEO1 median max|Δ| (km)"], np.nanmedian(mc.stack("tri_err_km")[:, 0]))
f8 = t5_effect["Fig. 8: both below separation/10"].astype(float)
lo_hi = [tuple(float(x) for x in s_.split("–")) for s_ in t5_effect["Fig. 8, 95 % Wilson"]]
assert all(hi < 0.5 for _, hi in lo_hi)  # Fig. 8 "not reproduced" on both scenes (prose)
assert t5_effect["Table 3 status"].nunique() == 1  # prose: no status changes
assert (t5_effect.iloc[:, 3].astype(float) < 0.85).all() \
    and (t5_effect["best L (px)"].astype(float) < P["epipolar.fig5"]["best_threshold_px"][0]).all()
assert (t5_effect[["GEO1 median max|Δ| (km)", "GEO5 median max|Δ| (km)"]].astype(float)
        > 3).all().all()  # Table 5: medians far above 3 km on both scenes
display(Markdown(
    f"Sensor(s) {', '.join(map(str, moved))} re-pointed; the other objects move by up to "
    f"{np.nanmax(shift_o):.0f} px in their images. {mc.n_draws} draws per scene, the main "
    f"run's (first column = the numbers above). Table 3's status on the two scenes: "
    + " / ".join(t5_effect["Table 3 status"]) + f"; Fig. 8's share of draws resolving both "
    f"objects rises from {f8.iloc[0]:.2f} to {f8.iloc[1]:.2f} (the separation grows "
    f"{sep['t5'] / sep['ours']:.1f}×), both intervals below 0.5. Triangulation medians are "
    "over the draws in which the object has a row (shares in the table)."))
t5_effect.T.map(lambda v: f"{v:.3g}" if isinstance(v, float) else v)

# %% [markdown]
# Following Table 5 for GEO5 changes none of the verdicts of Table 3, Fig. 5, Table 5 or
# Fig. 8; only Fig. 8's criterion (a tenth of the separation) grows easier.
#
# ## Scorecard
#
# The claims, scored from the results above (no new trials) with the criteria fixed in
# `papers_repro/epipolar/claims.toml`:

# %%
rep = E.score(scen, draw, mc, res6, errors=err, settings={"quick": QUICK})

# %%
# NBVAL_CHECK_OUTPUT
for row in rep.claims:  # checks verify our construction: pass / fail
    shown = ("pass" if row.status == "reproduced" else "fail") if row.kind == "check" \
        else str(row.status)
    print(f"{row.claim:18s} {row.kind:7s} {shown}")
print(rep.status_summary())
rep_t3 = next(str(r.status) for r in rep.claims if r.claim == "epipolar.table3")

# %%
rep.scorecard[["claim", "paper", "ours", "status", "note"]]

# %% [markdown]
# ## Explore
#
# **The key trade-off: the threshold $L$.** Left: missed and false associations per true
# pair against $L$, with the error-budget gate (green, *Beyond*). Right: distances of the
# accepted pairs. Where does the total error bottom out? With doubled attitude error, or no
# false targets? Each setting is simulated once (60 draws); moving $L$ only re-counts.

# %%
ATTITUDES = {"±0.5′": 0.5, "±1′ (paper)": 1.0, "±2′": 2.0}
N_FALSE = {"0": 0, "3 (ours)": 3, "6": 6}
view = E.TradeoffView(E.threshold_study)
for att in ATTITUDES.values():  # simulate and draw every setting once (cached)
    for nf in N_FALSE.values():
        view(threshold=10.0, attitude_arcmin=att, n_false=nf)

explore = panel(view,  # a change only re-counts the stored distances and redraws
                threshold=float_slider("L (px)", 0.5, 30.0, 0.5, 10.0),
                attitude_arcmin=dropdown("attitude error", ATTITUDES, 1.0),
                n_false=dropdown("false targets / map", N_FALSE, 3))

# %% [markdown]
# ## Errata and deviations
#
# | where | the paper | what we do |
# |---|---|---|
# | eq. (8) | "$\ll L$" | $< L$ |
# | eq. (4) | called 3-2-1 | the printed passive product turns the frame about x first; kept (`rotation_321`), no effect |
# | Table 1 | eccentricity "/(°)" | dimensionless |
# | §2.1 | jitter "10 mrad" (section 8) | 10 µrad |
# | §2.1 | attitude, position "upper bounds" 1′, 0.2 km | uniform within ±1′; uniform in a 0.2 km ball |
# | §2.1 | "random false targets" | 3 per map, uniform |
# | Table 2 | distortion coefficients without units | OpenCV model, normalised coordinates |
# | Tables 3/5 | positions not given; maps 1–3 fit no attitude | built from GEO1 (Table 5) and map 4 (Table 3) |
# | Tables 3/5 | GEO5's position vs its pixels; GEO1's pairs 1&2, 2&4 | Table 3 followed; the other choice measured |
# | Table 4 | row 4(a): one value, column lost | unplaced |
# | Table 5 | GEO1 2&4 X = +39,365.25 | −39,365.25 (the printed mean needs it) |
# | §3 | 3σ rejection | cannot fire with ≤ 10 estimates |
# | Fig. 6 | image size, F and points unstated | stated; two variants |
# | Fig. 5 | "error rate" undefined; 90 % of 1,032 *associated* pairs | both readings, ≥ 85 % each (set after results) |
# | step 5 | nearest candidate per point (order-dependent) | one greedy pass in increasing distance |
# | epoch | time scale unstated | UTC; J2000 ≈ GCRS |
#
# ## Beyond the paper
#
# ### A threshold from the error budget
#
# Instead of guessing $L$, propagate the error model to the distance of a true pair:
# linearise the distance with respect to the 12 pose parameters of two sensors and the 4
# centroid coordinates, and add the variances (uniform ±α: α²/3; ball of radius ρ: ρ²/5 per
# axis; jitter σ²). The signed distance is roughly Gaussian, so a gate at probability $p$ is
# $L = \sigma_d\sqrt{\chi^2_1(p)}$. Check: the Monte Carlo distances of true pairs follow the
# predicted half-normal.

# %%
sig_rms, gate99 = E.error_budget_gate(scen, err)
true_d = np.concatenate([o["true_d"] for o in mc.trials])
mc_rms = float(np.sqrt(np.mean(true_d**2)))
assert abs(mc_rms / sig_rms - 1) < 0.15
display(Markdown(f"Predicted σ_d = {sig_rms:.2f} px, Monte Carlo rms {mc_rms:.2f} px; "
                 f"99 % gate {gate99:.1f} px."))
ax = E.plot_distance_check(true_d, sig_rms)

# %% [markdown]
# This gate is the library's default: `associate(dist, sigma_px=σ)` gates at
# $\sigma\sqrt{\chi^2_1(0.99)}$ (`chi2_gate`), and an explicit threshold overrides it.

# %%
from eotrack.geometry import chi2_gate

d_ex = E.pair_distances(draw.obs, 0, 3)
assert np.array_equal(associate(d_ex, sigma_px=sig_rms), associate(d_ex, chi2_gate(sig_rms)))
assert np.isclose(chi2_gate(sig_rms), gate99)

# %% [markdown]
# A pooled σ_d gives one gate for all map pairs, but σ_d differs per pair: "outside with
# probability 1 − p" holds only on average. Miss probability per pair at the pooled gate, and
# each pair's own gate (`associate(d, sigma_px=σ_pair)`):

# %%
from scipy.stats import norm

sig_tab = E.distance_sigma_px(scen, err)
sig_tab["miss at pooled gate"] = 2 * norm.sf(gate99 / sig_tab["sigma_px"])
per_pair = sig_tab.groupby("pair").agg(sigma_min=("sigma_px", "min"),
                                       sigma_max=("sigma_px", "max"),
                                       miss_at_pooled=("miss at pooled gate", "mean"))
per_pair["own 99 % gate (px)"] = [chi2_gate(v) for v in sig_tab.groupby("pair")["sigma_px"].max()]
display(Markdown(f"Pooled gate {gate99:.2f} px: mean miss probability over the true pairs "
                 f"{100 * sig_tab['miss at pooled gate'].mean():.1f} % (not 1 %), from "
                 f"{100 * per_pair['miss_at_pooled'].min():.2f} % to "
                 f"{100 * per_pair['miss_at_pooled'].max():.1f} % per pair."))
per_pair.round(4)

# %% [markdown]
# Gate against the sweep's best threshold, attitude read as a uniform bound (left) or rms
# (right):

# %%
gs_bound = E.gate_study(scen, (0.5, 1.0, 2.0), n_draws=N_BEYOND, runner=runner)
gs_rms = E.gate_study(scen, (0.5, 1.0, 1.5), gaussian=True, n_draws=N_BEYOND, runner=runner)
fig, axs = plt.subplots(1, 2, figsize=(7.2, 3.8), sharey=True, layout="constrained")
E.plot_gate_study(gs_bound, ax=axs[0], legend=False)  # titles and x labels say which reading
E.plot_gate_study(gs_rms, ax=axs[1], legend=False)
leg = legend_outside(fig, where="below", ncol=3)
gap = (gs_bound["gate χ²₁ 99 % (px)"] - gs_bound["best L (px)"]).to_numpy()
assert abs(gap[0]) < 1 and gap[-1] > 3  # prose: coincide for small errors, gate above later
gate_rms_1 = float(gs_rms.loc[gs_rms["attitude (′)"] == 1.0, "gate χ²₁ 99 % (px)"].iloc[0])
lo5, hi5 = P["epipolar.fig5"]["best_threshold_px"]
assert lo5 <= gate_rms_1 <= hi5  # prose: read as rms, 1′ gives a gate inside the band
pd.concat({"attitude read as a uniform bound": gs_bound, "attitude read as rms": gs_rms})

# %% [markdown]
# For small attitude errors gate and optimum roughly coincide; as errors grow, false
# associations pull the optimum below the gate. Read as rms, 1′ gives a gate inside 8–12 px,
# a plausible origin of the paper's threshold (*exploratory*, not scored).
#
# ### Where the lost true pairs come from
#
# Every lost true pair was taken by a nearer wrong candidate. Noise-free, which epipolar
# lines pass within 5 px of another object's image?

# %%
X0 = scen.true_pixels()
near = []
for a, b in E.PAIRS:
    ca, cb = scen.cameras[a], scen.cameras[b]
    both = np.flatnonzero(scen.visible[a] & scen.visible[b])
    if len(both) < 2:
        continue
    F_ab = fundamental_from_poses(ca.K, ca.R, ca.c, cb.K, cb.R, cb.c)
    d_ab = epipolar_distances(F_ab, X0[a, both], X0[b, both])
    for i, j in zip(*np.nonzero((d_ab < 5) & ~np.eye(len(both), dtype=bool))):
        near.append({"pair": f"{a + 1}-{b + 1}", "line of": scen.names[both[i]],
                     "passes near": scen.names[both[j]], "distance (px)": d_ab[i, j]})
near = pd.DataFrame(near)
assert "GEO5" in set(near["line of"]) | set(near["passes near"])  # the prose relies on it
near.round(2)

# %% [markdown]
# Are they an accident of our construction (objects on the GEO shell along map 4's rays)?
# Move GEO2–GEO9 by up to ±15 km per axis, sensors fixed, every map still seeing its Table 3
# objects (`E.perturbed_scenario`): closest other object to a line per pair, then Figs. 4–5
# and Table 3 with the main run's first `N_PLACE` draws:

# %%
rng_p = np.random.default_rng(11)
scenes_p = {"ours": scen, **{f"perturbed {i + 1}": E.perturbed_scenario(scen, rng_p)
                             for i in range(3)}}
near_p = pd.DataFrame({k: E.closest_other_object_px(v) for k, v in scenes_p.items()})
n_keep = int(np.sum(near_p.drop(columns="ours").min() < 5))
assert n_keep >= 2  # the prose below relies on it
display(Markdown(f"{n_keep} of {len(scenes_p) - 1} perturbed placements keep an object within "
                 "5 px of another object's epipolar line (px, noise-free):"))
display(near_p.round(2))
placements = E.placement_study(scenes_p, err, E.THRESHOLDS, L, N_PLACE, runner=runner)
pr_, rc_ = placements.iloc[:, 1].astype(float), placements.iloc[:, 0].astype(float)
best_ = placements["best L (px)"].astype(float)
lo_band = P["epipolar.fig5"]["best_threshold_px"][0]
assert placements.iloc[:, 3].astype(float).max() < 0.85  # in-band, paper's reading
assert best_.max() < lo_band  # so Fig. 5 fails both conditions on every placement
assert (placements["Table 3 status"] == rep_t3).all()  # the prose below relies on it
display(Markdown(f"Across the placements the recall at L = {L:g} px spans {rc_.min():.3f}–"
                 f"{rc_.max():.3f}, the paper's reading {pr_.min():.3f}–{pr_.max():.3f}, the "
                 f"best L {best_.min():g}–{best_.max():g} px, the objects recovered "
                 f"{placements['objects recovered (mean)'].astype(float).min():.2f}–"
                 f"{placements['objects recovered (mean)'].astype(float).max():.2f} of "
                 f"{len(scen.names)}; Table 3 is *{rep_t3}* on every placement."))
placements.iloc[:, :10].T.map(lambda v: f"{v:.3g}" if isinstance(v, float) else v)

# %% [markdown]
# Near-coincident lines survive the perturbations (count above): with nine objects in one
# 2° field they are common in this geometry, not an artefact of our placement. The rates move by several points, but no placement
# changes the verdict of Table 3 or Fig. 5.
#
# ### Whole-pixel centroids and Table 4's noise-free level
#
# Table 3 prints whole pixels; rounding moves a point by ±0.5 px per axis. Noise-free draws
# with rounded centroids:

# %%
mc_q = E.run_scenario_draws(scen, E.ErrorConfig(quantize=True), E.THRESHOLDS, L,
                            N_BEYOND, runner=runner)
paper_free = np.asarray(P["epipolar.table4"]["mean_distance_noise_free_px"])
with warnings.catch_warnings():
    warnings.simplefilter("ignore", RuntimeWarning)  # pair (d) has no correct pairs
    noise_free_cmp = pd.DataFrame({
        "pair": P["epipolar.table4"]["pairs"], "paper noise-free (px)": paper_free,
        "ours, correct pairs (px)": np.nanmean(mc.stack("mean_d0_true"), 0),
        "ours, correct pairs, rounded (px)": np.nanmean(mc_q.stack("mean_d0_true"), 0),
        "ours, all associated, rounded (px)": np.nanmean(mc_q.stack("mean_d0"), 0)})
rounded = noise_free_cmp["ours, correct pairs, rounded (px)"]
assert np.nanmax(rounded) < 0.6 < np.nanmax(paper_free)  # the prose below relies on it
noise_free_cmp.round(3)

# %% [markdown]
# Rounding explains a few tenths of a pixel (the paper's 4(f), 0.237 px), not 1–4 px.
#
# ### Fewer false associations: global assignment and a three-view check
#
# **Three-view check** (ours, not scored): triangulate a pair, project the point
# into every other map; if it lands inside that image with no detection within 1.5 L, the pair
# is false. The paper spots Fig. 4(e) by inconsistent summary rows. Over all draws at
# L = 10 px:

# %%
rules = E.rules_table(mc).set_index("rule")
r_f, r_m = rules["false associations"], rules["missed true pairs"]
assert r_f.iloc[2] < 0.5 * r_f.iloc[0] and r_m.iloc[2] < 1.05 * r_m.iloc[0]  # prose below
assert r_m.iloc[1] < r_m.iloc[0]  # prose below: the global assignment misses fewer
rules

# %% [markdown]
# The three-view check removes most false associations at almost no cost in true pairs; a
# pair whose point lands in no third image cannot be checked (GEO2, GEO6 and GEO9 are seen
# by maps 2 and 4 only). The global assignment misses fewer true pairs.
#
# ### What attitude accuracy a 3 km triangulation needs
#
# The sensor's stated accuracy is 6″ (0.1′), ten times the injected 1′:

# %%
SETTINGS_TRI = ((1.0, 0.2, 10.0), (0.1, 0.2, 10.0), (0.03, 0.2, 10.0), (0.03, 0.02, 10.0),
                (0.03, 0.2, 1.0))
out_tri = {}
for att, pos, jit in SETTINGS_TRI:  # same seed: the same random numbers, scaled (paired)
    t = np.stack(run_trials(E.triangulation_trial, N_DRAWS, seed=5, runner=runner,
                            args=(scen, E.ErrorConfig(attitude_arcmin=att, position_km=pos,
                                                      jitter_urad=jit), L)))
    out_tri[f"±{att:g}′, {pos:g} km, {jit:g} µrad"] = {
        "GEO1 has a row": np.mean(np.isfinite(t[:, 0])),
        "GEO1 median max|Δ| (km)": np.nanmedian(t[:, 0]),
        "GEO5 median max|Δ| (km)": np.nanmedian(t[:, 1]),
        "both within 3 km": np.mean(np.all(t <= 3, axis=1))}
tri_tab = pd.DataFrame(out_tri).T
g1 = tri_tab["GEO1 median max|Δ| (km)"].to_numpy()
both3 = tri_tab["both within 3 km"].to_numpy()
a_, p_, j_ = np.array(SETTINGS_TRI).T
assert abs(g1[3] / g1[2] - 1) < 0.25 and g1[4] < 0.7 * g1[2]  # the prose below relies on it
display(Markdown(
    f"{N_DRAWS} paired draws per setting (other draws than the main run's: its GEO1 median "
    f"is {np.nanmedian(mc.stack('tri_err_km')[:, 0]):.0f} km); medians over the draws in which "
    f"GEO1 has a row. GEO1's error shrinks "
    f"{g1[0] / g1[1]:.1f}× from ±{a_[0]:g}′ to ±{a_[1]:g}′ (the attitude error shrinks "
    f"{a_[0] / a_[1]:.0f}×) but only {g1[1] / g1[2]:.1f}× more to ±{a_[2]:g}′ "
    f"({a_[1] / a_[2]:.1f}×). There, a {p_[2] / p_[3]:.0f} times smaller position error "
    f"leaves GEO1 at {g1[3]:.1f} km; a {j_[2] / j_[4]:.0f} times smaller jitter brings it to "
    f"{g1[4]:.1f} km (both within 3 km in {100 * both3[4]:.0f} % of the draws)."))
tri_tab

# %% [markdown]
# Down to the sensor's 0.1′ the error roughly follows the attitude error; below it the 10 µrad
# jitter, stretched along the line of sight by the short baselines, sets a floor of a few km,
# not the position error. The paper's 3 km needs arcsecond attitude errors *and* a jitter
# well below 10 µrad.
#
# ## Key points
#
# - With known poses, $F = M_2^{-\top}R_{12}[t]_\times M_1^{-1}$; association needs only the
#   distance of a dot from an epipolar line.
# - $L$ trades missed against false associations. The best $L$ follows the true-pair spread
#   only while false candidates are rare; with several per band they pull it below the
#   error-budget gate $\sigma_d\sqrt{\chi^2_1(p)}$.
# - Foreign points in a band cause false associations; a third view removes most.
# - Short baselines turn small angular errors into large range errors.
# - A 3σ rejection rule cannot reject anything among ≤ 10 samples.
#
# ## Exercises
#
# Check an answer with `check("epipolar.N", answer)`; it says right or wrong with a hint.
# Worked solutions: `notebooks/solutions/02_epipolar_solutions.ipynb`.
#
# **1 (derivation).** Show that among $n$ samples the largest possible
# $|x_i-\bar x|/s$ ($s$ with $n-1$ in the denominator) is $(n-1)/\sqrt n$. A looser rule
# rejects beyond 2.5σ: what is the smallest $n$ for which it can reject an estimate?

# %%
answer = None  # your answer here (an integer)
if answer is not None:
    check("epipolar.1", answer)

# %% [markdown]
# **2 (computation).** Write `dist(F, p1, p2)` returning eq. (8)'s $(n_1, n_2)$ matrix with
# numpy only (the checker rejects eotrack and OpenCV). It runs on hidden inputs, including
# scaled and sign-flipped $F$.

# %%
dist_fn = None  # your function here


if dist_fn is not None:
    check("epipolar.2", dist_fn)

# %% [markdown]
# **3 (exploration).** In the *Explore* panel, with the paper's ±1′ attitude error but **6**
# false targets per map, at which threshold $L$ (px) is the total error smallest? (To 0.5 px.)
# Is it above or below the optimum with 3 false targets, and why?

# %%
answer = None  # your answer here (px)
if answer is not None:
    check("epipolar.3", answer)

# %% [markdown]
# **4 (critique).** Would the "10 mrad" reading be saved on Table 2's wide-field reference
# sensor (ST-APS2-2, 20°×20°, 1024×1024 px)? How many of *its* pixels is 10 mrad?

# %%
answer = None  # your answer here (px)
if answer is not None:
    check("epipolar.4", answer)

# %% [markdown]
# **5 (computation, error budget).** Read the paper's 1′ as an rms attitude error (uniform
# noise of bound $\sqrt3$′ has that rms) and the jitter as **100 µrad** rms. What **90 %**
# gate (px) does the error budget give? Use `E.error_budget_gate`.

# %%
answer = None  # your answer here (px)
if answer is not None:
    check("epipolar.5", answer)

# %% [markdown]
# ## References
#
# 1. Huang Q., Zhang Y., Feng F. Space target synchronization association method under
#    distributed star sensors. *Chinese Journal of Scientific Instrument*.
#    [doi:10.19650/j.cnki.cjsi.J1905157](https://doi.org/10.19650/j.cnki.cjsi.J1905157)
# 2. Hartley R., Zisserman A. *Multiple View Geometry in Computer Vision*, 2nd ed.,
#    Cambridge University Press, 2004.
#    [doi:10.1017/CBO9780511811685](https://doi.org/10.1017/CBO9780511811685)
# 3. Bradski G. The OpenCV Library. *Dr. Dobb's Journal of Software Tools*, 2000.
# 4. Kuhn H. W. The Hungarian method for the assignment problem. *Naval Research Logistics
#    Quarterly* 2, 83–97, 1955. [doi:10.1002/nav.3800020109](https://doi.org/10.1002/nav.3800020109)
# 5. Gaia Collaboration, Vallenari A. et al. Gaia Data Release 3. *Astronomy & Astrophysics*
#    674, A1, 2023. [doi:10.1051/0004-6361/202243940](https://doi.org/10.1051/0004-6361/202243940)
# 6. Vallado D. A. *Fundamentals of Astrodynamics and Applications*, 4th ed., Microcosm Press,
#    2013 (two-body states from elements).
# 7. Samuelson P. A. How deviant can you be? *Journal of the American Statistical
#    Association* 63(324), 1522–1525, 1968.
#    [doi:10.1080/01621459.1968.10480944](https://doi.org/10.1080/01621459.1968.10480944)
# 8. Wahba G. A least squares estimate of satellite attitude. *SIAM Review* 7(3), 409, 1965.
#    [doi:10.1137/1007077](https://doi.org/10.1137/1007077)
# 9. Wilson E. B. Probable inference, the law of succession, and statistical inference.
#    *JASA* 22(158), 209–212, 1927. [doi:10.1080/01621459.1927.10502953](https://doi.org/10.1080/01621459.1927.10502953)
# 10. Efron B. Bootstrap methods: another look at the jackknife. *Annals of Statistics* 7(1),
#     1–26, 1979. [doi:10.1214/aos/1176344552](https://doi.org/10.1214/aos/1176344552)
# 11. Dunn O. J. Multiple comparisons among means. *JASA* 56(293), 52–64, 1961.
#     [doi:10.1080/01621459.1961.10482090](https://doi.org/10.1080/01621459.1961.10482090)
#
# ## Closing note: review
#
# Earlier rounds: 15 and 21 findings; the two left partly done (Table 3 on other placements,
# prose length) are closed here. Third, independent review of this revision
# (`../shared/REVIEW.md`): **17 found** (6 medium, 11 low), **15 fixed**, 2 handed to the
# lead because the files are not this paper's (exercise 5's hint; the figure lint's xfail
# key), **none left**.

# %%
from eotrack.notebook import lesson_footer

lesson_footer("02")
