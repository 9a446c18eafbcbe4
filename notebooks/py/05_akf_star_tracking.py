# ---
# jupyter:
#   kernelspec:
#     display_name: Python 3 (ipykernel)
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 05 · Adaptive anti-occlusion star tracking on a ship
#
# **Paper.** Sheng Yansong. *Adaptive anti-occlusion star tracking algorithm for ships based on
# a physical model.* Intelligent Computer and Applications **16**(4):195-202, 2026.
# [DOI 10.20169/j.issn.2095-2163.26010403](https://doi.org/10.20169/j.issn.2095-2163.26010403)
#
# **What the paper does.** A ship's star sensor must keep a reference star in track while waves
# roll, pitch and yaw the ship, clouds hide the star and sky light lowers the contrast. The
# paper combines a physical model of the star's image motion, an
# *adaptive-threshold* extraction and a *confidence-gated adaptive Kalman filter* (Singer
# process noise, Sage–Husa noise estimation, three modes), and tests them by an ablation of four
# variants in five scenarios (Tables 1–2, Figs. 6–7).
#
# **Our data.** The paper used "the first 200 frames of OTB100", a visual-tracking benchmark
# without stars. We simulate a shipborne star sensor: real Gaia/Hipparcos stars, astropy Alt/Az
# per frame, sinusoidal roll/pitch/yaw, Gaussian PSF, shot and read noise, 8-bit frames.
#
# ## Learning objectives
# After this notebook you can
# - chain the rotations level → deck → camera, predict a star's image motion and spot why the
#   paper's eq. (12) is wrong;
# - extract stars with a local threshold;
# - write the Kalman predict/update, the Singer process noise and the Sage–Husa estimator, and
#   see where Sage–Husa breaks;
# - read an ablation per scenario, with intervals, under settings fixed before the run.
#
# **Prerequisites.** Notebook 02; the basics of the Kalman filter (Labbe, chapters 4–8).
#
# **Scorecard** (computed from `papers_repro/akf_star/scorecard.json`, written by `make repro`
# from the run this notebook reads in *Reproduction*):

# %%
import json

from eotrack.notebook import lesson_header
from eotrack.repro import papers_repro_dir

lesson_header("05")
from IPython.display import Markdown, display

stored = json.loads((papers_repro_dir() / "akf_star" / "scorecard.json").read_text())
display(Markdown(f"**REPORT status: {stored['summary']}** "
                 f"({stored['settings']['n_seeds']} sequences per scenario)."))

# %% [markdown]
# ## Setup

# %%
import numpy as np
import pandas as pd
from eotrack.exercises import check
from eotrack.experiments import akf_star as A
from eotrack.geometry.shipboard import (
    camera_from_deck,
    camera_from_level,
    deck_from_level,
    enu_from_azalt,
    image_rate_projective,
    sea_state_motion,
    ship_attitude,
    star_angles_from_image,
)
from eotrack.imaging import (
    SCENARIOS,
    SensorConfig,
    clean_isolated,
    extract_stars,
    grey_quantiles,
    match_positions,
    real_sky_images,
    scenario,
    simulate_sequence,
)
from eotrack.montecarlo import TrialRunner
from eotrack.notebook import dropdown, float_slider, panel, setup_notebook, versions
from eotrack.repro import Status, load_claims, scorecard
from eotrack.tracking.kalman import (
    ConfidenceConfig,
    ConfidenceKalmanFilter,
    constant_acceleration_model,
    kalman_filter,
    sage_husa_update,
    sage_husa_weight,
    singer_acceleration_variance,
    singer_process_noise,
)

setup_notebook()
versions(("numpy", "scipy", "opencv-python-headless", "astropy", "filterpy", "sep", "eotrack"))

# %% tags=["parameters"]
QUICK = False   # True: a small live study (3 sequences × 100 frames) instead of the stored run

# %% [markdown]
# **The stored study.** The ablation (100 sequences of 200 frames) and the side studies take
# about 5 minutes, so `make repro` writes them to `papers_repro/akf_star/ablation_study.npz`,
# read here. With `QUICK = True`, or without that file, a small live study runs instead
# (3 sequences × 100 frames per scenario, 1–2 min); its statuses are not the REPORT's.

# %%
study_file = papers_repro_dir() / A.SLUG / A.STUDY_FILE
if not QUICK and study_file.exists():
    study = A.read_study(study_file)
else:
    if not QUICK:
        display(Markdown(f"**`{study_file.name}` is missing** — `python -m eotrack.repro "
                         "akf_star` (or `make repro`) writes it. Running a small live study."))
    study = A.run_study(A.small_config(), runner=TrialRunner(progress=False), n_consistency=1,
                        n_sensitivity=2, n_centroid_frames=20)
res, session, cfg = study.ablation, study.session, study.ablation.config
print(f"{study.source}: {cfg.n_seeds} sequences × {cfg.n_frames} frames per scenario")

# %% [markdown]
# ## Notation
#
# | paper | code | unit |
# |---|---|---|
# | θ, φ, ψ (pitch, roll, heading) | `pitch`, `roll`, `heading` | rad |
# | α, β (optical-axis elevation, azimuth on the deck) | `elevation`, `azimuth` | rad |
# | $R_{N\to B}$, $R_{B\to C}$ | `deck_from_level`, `camera_from_deck` | – |
# | $S_x, S_z$, f | `s_x`, `s_z`, `SensorConfig.focal_px` | px |
# | A, h (star azimuth, altitude), $\omega_e$ | `azimuth`, `altitude`, `OMEGA_EARTH` | rad, rad/s |
# | $g_5, g_{95}$, R (dynamic range) | `grey_quantiles`, `dynamic_range` | grey level, – |
# | $\sigma_b$, k, r, $k_b$ | `ExtractionConfig.sigma_b, k, r, k_b` | px, –, px, – |
# | $X=[x, y, v_x, v_y, a_x, a_y]^\top$ | filter state `x` | px, px/s, px/s² |
# | α (Singer), $\sigma_w$, $q_a$ | `alpha`, `sigma_w`, `singer_acceleration_variance` | 1/s, px/s^2.5, px²/s⁴ |
# | $R_k$, $Q_k$, b, $d_k$ | `R`, `Q`, `ConfidenceConfig.forgetting`, `sage_husa_weight` | px², –, –, – |
# | ω, η, γ, λ | `ConfidenceConfig.omega, eta, gamma, lam` | – |
# | $C_{img}, C_{motion}, C_k, \hat C_k, \tau_h, \tau_l$ | `image_confidence`, `ConfidenceKalmanFilter.confidence` | – |
# | ε (success threshold) | `AblationConfig.epsilon_px` | px |

# %% [markdown]
# ## The method, step by step
#
# ### Frames and the rotation chain (eqs. 1–5)
#
# A star's direction $\mathbf r$ in the level frame N (east-north-up at the ship) reaches the
# camera through the deck frame B:
# $$\mathbf r^{C} = R_{B\to C}\,R_{N\to B}\,\mathbf r. \tag{1}$$
# The deck turns by pitch θ about X (starboard), then roll φ about the new Y′ (bow). With the
# paper's passive matrices
#
# $$
# R_x(a)=\begin{pmatrix}1&0&0\\0&\cos a&\sin a\\0&-\sin a&\cos a\end{pmatrix},\qquad
# R_y(a)=\begin{pmatrix}\cos a&0&-\sin a\\0&1&0\\\sin a&0&\cos a\end{pmatrix}
# \tag{3}
# $$
#
# the text's sequence is $R_{N\to B}=R_y(\varphi)R_x(\theta)R_z(-\psi)$ (heading included).
# Eq. (2) prints $R_x(\varphi)R_y(\theta)$: roll about X and pitch about Y, the axes swapped —
# a first-order difference, about $|\varphi-\theta|$ (the order of the two factors alone would
# be second order, $\theta\varphi$; both checked below).
# The optical axis points at azimuth β and elevation α on the deck,
# $R_{B\to C}=R_x(\alpha)R_z(-\beta)$. The paper writes $R_y(\beta)R_x(\alpha)$ (azimuth
# about Y, its optical axis) and prints as its small-angle form the matrix $M$ with rows
# $(1, 0, \beta)$, $(0, 1, -\alpha)$, $(-\beta, \alpha, 1)$ — with the passive matrices of
# eq. (3), the expansion of the TRANSPOSE $[R_y(\beta)R_x(\alpha)]^\top$, not of the product
# (checked below). Our product's expansion (the library's form) is
#
# $$
# R_{B\to C}\approx\begin{pmatrix}1&-\beta&0\\\beta&1&\alpha\\0&-\alpha&1\end{pmatrix}
# \tag{5'}
# $$
#
# (ours, not the paper's eq. 5, which is $R_y(\beta)R_x(\alpha)\approx M$). It differs from
# $M$ at first order. The three frames, drawn from the matrices:

# %%
fig = A.plot_frames_schematic()

# %%
psi, A0, h0 = np.radians(45.0), np.radians(130.0), np.radians(42.0)
R = camera_from_level(psi, 0.0, 0.0, A0 - psi, h0)
th, ph = np.radians(1.0), np.radians(2.5)
order_effect = np.abs(deck_from_level(0, th, 0) @ deck_from_level(0, 0, ph)
                      - deck_from_level(0, 0, ph) @ deck_from_level(0, th, 0)).max()


def Rx3(a):   # eq. (3)
    return np.array([[1, 0, 0], [0, np.cos(a), np.sin(a)], [0, -np.sin(a), np.cos(a)]])


def Ry3(a):   # eq. (3)
    return np.array([[np.cos(a), 0, -np.sin(a)], [0, 1, 0], [np.sin(a), 0, np.cos(a)]])


eq2_gap = float(np.abs(Rx3(ph) @ Ry3(th) - Ry3(ph) @ Rx3(th)).max())   # printed vs the text
al, be = 0.01, 0.02                       # elevation α, azimuth β (rad)
eq5 = np.array([[1, -be, 0], [be, 1, al], [0, -al, 1]])              # eq. (5) as shown above
eq5_printed = np.array([[1, 0, be], [0, 1, -al], [-be, al, 1]])      # the paper's matrix
exact = camera_from_deck(be, al)
small = np.abs(exact - eq5)
printed_gap = float(np.abs(exact - eq5_printed).max())
paper_product = Ry3(be) @ Rx3(al)                                  # the paper's R_y(β) R_x(α)
gap_product = float(np.abs(paper_product - eq5_printed).max())
gap_transpose = float(np.abs(paper_product.T - eq5_printed).max())
assert np.allclose(camera_from_deck(be, al, small_angle=True), eq5)
checks = {"boresight on the star": bool(np.allclose(R @ enu_from_azalt(A0, h0), [0, 1, 0])),
          "R orthonormal": bool(np.allclose(R @ R.T, np.eye(3))),
          "pitch/roll order alone is a second-order effect": bool(order_effect <= 1.01 * th * ph),
          "eq. (2) as printed (axes swapped) is off at first order, ≈ |φ − θ|":
              bool(abs(eq2_gap - abs(ph - th)) < 0.05 * abs(ph - th)),
          "eq. (5') above (library form) good to 3e-4": bool(small.max() < 3e-4),
          "eq. (5) as printed off at first order (> 0.01)": bool(printed_gap > 0.01),
          "printed matrix = expansion of [R_y(β)R_x(α)]ᵀ (< 1e-3)": bool(gap_transpose < 1e-3),
          "printed matrix ≠ expansion of R_y(β)R_x(α) (> 0.01)": bool(gap_product > 0.01)}
assert all(checks.values())

# %%
# NBVAL_CHECK_OUTPUT
print(checks)
print(f"at α = {al}, β = {be}: the printed matrix is off by {round(printed_gap, 3)}, the "
      f"library's by {small.max():.0e}")
print(f"eq. (2) as printed vs the text at θ = 1°, φ = 2.5°: {eq2_gap:.4f} (|φ − θ| = "
      f"{abs(ph - th):.4f}); the factor order alone: {order_effect:.5f}")

# %% [markdown]
# ### Star angles from the image (eqs. 6–9)
#
# A star imaged at offsets $(S_x, S_z)$ from the image centre has camera-frame direction
# $\propto (S_x, f, S_z)$, so (the paper re-uses α, β here for the star's azimuth and elevation in
# the camera frame, not the optical-axis angles of eq. 5)
# $$\varphi_x=\arctan\frac{S_x}{f},\qquad \varphi_z=\arctan\frac{S_z}{f},\qquad
# \text{azimuth}=\varphi_x,\qquad \text{elevation}=\arctan(\tan\varphi_z\cos\varphi_x)
# \tag{6–9}$$
# — the right triangles of the paper's Fig. 4. Check against the direction vector:

# %%
rng = np.random.default_rng(0)
f = 700.0
sx, sz = rng.uniform(-64, 64, (2, 1000))
az, el = star_angles_from_image(sx, sz, f)
v = np.stack([sx, np.full_like(sx, f), sz], 1)
v /= np.linalg.norm(v, axis=1, keepdims=True)
err = max(np.abs(az - np.arctan2(v[:, 0], v[:, 1])).max(), np.abs(el - np.arcsin(v[:, 2])).max())
assert err < 1e-12

# %% [markdown]
# ### Image motion (eqs. 10–14) and the Earth-rotation erratum
#
# With $u=fX/Z$, $v=fY/Z$ (Z the optical axis in eq. 10's convention),
# $$\dot u=f\,\frac{\dot XZ-X\dot Z}{Z^2},\qquad \dot v=f\,\frac{\dot YZ-Y\dot Z}{Z^2}.\tag{10}$$
# The image velocity is an Earth part plus a ship part (eq. 11); for small attitude angles the
# paper writes
# $$\dot u\approx-f\omega_e\sin A\cos h+f(\dot\theta\cos\psi-\dot\varphi\sin\psi),\qquad
# \dot v\approx-f\omega_e\cos A\cos h+f(-\dot\theta\sin\psi-\dot\varphi\cos\psi),\tag{12}$$
# and integrates it to the trajectory
# $$u(t)=u_0+\int_0^t\big(\dot u_{\rm earth}+\dot u_{\rm ship}\big)\,d\tau+\varepsilon(t),
# \qquad v(t)=v_0+\int_0^t\big(\dot v_{\rm earth}+\dot v_{\rm ship}\big)\,d\tau+\varepsilon(t).
# \tag{13–14}$$
# Its Earth terms lack the observer's latitude, which a star's diurnal motion has. In azimuth A
# (from north through east) and altitude h:
# $$\dot h=\omega_e\cos\phi_{\rm lat}\sin A,\qquad
# \cos h\,\dot A=\omega_e(\sin\phi_{\rm lat}\cos h-\cos\phi_{\rm lat}\sin h\cos A),$$
# of total angular speed $\omega_e\cos\delta$. First eq. (10) by a finite difference, then both
# Earth terms against astropy for 30 bright stars over 3 minutes:

# %%
r3, rd3 = np.array([0.1, -0.2, 1.0]), np.array([0.01, 0.03, -0.02])
ud, _ = image_rate_projective(r3, rd3, 500.0)
r3b = r3 + rd3 * 1e-6
assert np.isclose(ud, 500 * (r3b[0] / r3b[2] - r3[0] / r3[2]) / 1e-6, rtol=1e-5)
diurnal = A.diurnal_check()
eq12 = {"correct form, max relative error": diurnal["rel_error_correct"].max(),
        "eq. (12), median relative error": diurnal["rel_error_paper"].median(),
        "eq. (12), max relative error": diurnal["rel_error_paper"].max(),
        "speed / (ω_e cos δ), min": diurnal["speed_over_omega_cos_dec"].min(),
        "speed / (ω_e cos δ), max": diurnal["speed_over_omega_cos_dec"].max()}
assert eq12["correct form, max relative error"] < 0.01
assert eq12["eq. (12), median relative error"] > 0.3
pd.Series(eq12).to_frame("value")

# %%
fig = A.plot_diurnal_check(diurnal)

# %% [markdown]
# ### Ship motion and the simulated sequences
#
# Roll, pitch and yaw are sums of sinusoids (`ShipMotion`) with sea-state amplitudes and
# random phases; the *sway* scenario uses a rougher sea. The sensor and the scenario presets:

# %%
sensor = SensorConfig()
t_att = np.arange(0, 40, 0.2)
att = ship_attitude(sea_state_motion(3), t_att, np.random.default_rng(1))
fig = A.plot_ship_attitude(t_att, att, title="Sea state 3 ship attitude (one realisation)")

# %%
pd.DataFrame([scenario(s).__dict__ for s in ("nominal", *SCENARIOS)]).set_index("name").drop(
    columns=["cloud_opacity"])

# %%
fig = A.plot_example_frames(seed=1, frame=120)

# %% [markdown]
# ### The paper's adaptive-threshold extraction (eqs. 15–29)
#
# Grey histogram $H(g)$, $p(g)=H(g)/N$, CDF $C(g)=\sum_{i\le g}p(i)$, quantiles and dynamic
# range:
# $$g_5=\min\{g:C(g)\ge0.05\},\quad g_{95}=\min\{g:C(g)\ge0.95\},\quad
# R=\frac{g_{95}-g_5}{255}.\tag{15–18}$$
# Background and filtered image: $B=I*G_{\sigma_b}$, $I_f=I-B$ (eqs. 19–20). If R is below a
# preset value the search is restricted to a region of interest,
# $$T_f=\mu_f+k\sigma_f,\qquad I_f(x,y)\ge T_f,\qquad \Omega_{ROI}=\bigcup_i\Omega_i
# \tag{21–23}$$
# (the paper prints $T_f\ge I_f$ and calls $\sigma_f$ a variance). In a $(2r+1)^2$ window W a
# local threshold $T(x,y)=\mu_b+k_b\sigma_b$ (eqs. 24–27) marks star pixels $I\ge T$;
# connected regions $\Re_k$ get intensity-weighted centroids
# $$z_x=\frac{\sum x\,I}{\sum I},\qquad z_y=\frac{\sum y\,I}{\sum I}.\tag{28–29}$$
# The baseline is one global threshold $\mu+k\sigma$. One strong-light frame, by hand:

# %%
seq = simulate_sequence(np.random.default_rng(3), "strong_light", n_frames=20)
img, truth = seq.images[10], seq.truth[10]
g5, g95 = grey_quantiles(img)
ad = extract_stars(img, method="adaptive", return_info=True)
gl = extract_stars(img, method="global", return_info=True)
d_ad = np.hypot(*(ad.xy - truth).T).min() if len(ad) else np.inf
d_gl = np.hypot(*(gl.xy - truth).T).min() if len(gl) else np.inf
assert d_ad < 0.5 and not d_gl < 0.5
fig = A.plot_extraction_example(img, ad, gl, g5, g95, truth=truth)

# %%
# NBVAL_CHECK_OUTPUT
print(f"R = (g95 - g5)/255 = {round(ad.dynamic_range, 2)}; adaptive finds the reference star: "
      f"{bool(d_ad < 0.5)}; global finds it: {bool(d_gl < 0.5)}")

# %% [markdown]
# ### The Kalman filter (eqs. 30–40)
#
# State $X=[x,y,v_x,v_y,a_x,a_y]^\top$ (eq. 30); F is the constant-acceleration transition
# with the frame period ΔT. Prediction (eq. 31 wrongly adds the noise sample $W_{k-1}$ to the
# estimate; the noise enters through Q):
# $$\hat X_{k|k-1}=F\hat X_{k-1},\qquad P_{k|k-1}=FP_{k-1}F^\top+Q_{k-1}.\tag{31–32}$$
# **Eq. (33) is inconsistent with eqs. (34)–(35).** It prints $\ddot u_s=-\alpha\dot u_s+w$,
# a first-order Markov process on the *velocity*; eqs. (34)–(35) give the variance of Singer's
# process on the *acceleration*, $\dot a=-\alpha a+w(t)$ (an Ornstein–Uhlenbeck process),
# $$q_a=\sigma_a^2=\frac{\sigma_w^2}{2\alpha}\big(1-e^{-2\alpha\Delta T}\big),\qquad
# Q\approx\operatorname{diag}(0,0,0,0,q_a,q_a).\tag{34–35}$$
# **The filter runs neither:** with the constant-acceleration F the acceleration is a random
# walk whose per-frame increments have the variance $q_a$ of eq. (34); Singer's decay
# $e^{-\alpha\Delta T}$ is not in F. The Monte Carlo below checks eq. (34) only.
# Measurement and update:
# $$Z_k=HX_k+V_k,\ V_k\sim N(0,R_k)\tag{36}$$
# $$e_k=Z_k-H\hat X_{k|k-1},\tag{37}$$
# $$\hat X_k=\hat X_{k|k-1}+K_ke_k,\tag{38}$$
# $$K_k=P_{k|k-1}H^\top\big(HP_{k|k-1}H^\top+R_{k-1}\big)^{-1},\tag{39}$$
# $$P_k=(I-K_kH)P_{k|k-1}.\tag{40}$$
# Numbered as printed; eq. (39)'s $R_{k-1}$ is the previous Sage–Husa step's R (for the
# standard KF, $R_{k-1}=R$). First $q_a$ of eq. (34) against a Monte Carlo of the OU process
# over one frame:

# %%
alpha, sigma_w, dt = 0.7, 4.0, 0.2
n_mc, n_sub = 20000, 400
a = np.zeros(n_mc)
g = np.random.default_rng(2)
for _ in range(n_sub):  # Euler–Maruyama from a = 0
    a += -alpha * a * dt / n_sub + sigma_w * np.sqrt(dt / n_sub) * g.standard_normal(n_mc)
qa = singer_acceleration_variance(dt, alpha, sigma_w)
assert abs(a.var() / qa - 1) < 0.05
pd.Series({"q_a, eq. (34)": qa, "q_a, Monte Carlo": a.var()}).to_frame("px²/s⁴")

# %% [markdown]
# Eqs. (36)–(40) by hand for one step, then the library's filter against FilterPy on a
# sequence with an occlusion (prediction only while the star is hidden):

# %%
from filterpy.kalman import KalmanFilter as FPKF

F, H = constant_acceleration_model(dt)
Q = singer_process_noise(dt, alpha, sigma_w)
Rm = 0.25 * np.eye(2)
x0, P0 = np.zeros(6), np.diag([1.0, 1, 50, 50, 20, 20])
tt = np.arange(300) * dt
zs = np.c_[10 * np.sin(0.7 * tt), 5 * np.cos(0.5 * tt)] + g.normal(0, 0.5, (300, 2))
zs[100:130] = np.nan
x_pred, P_pred = F @ x0, F @ P0 @ F.T + Q                     # (31)-(32)
e1 = zs[0] - H @ x_pred                                        # (37)
K1 = P_pred @ H.T @ np.linalg.inv(H @ P_pred @ H.T + Rm)       # (39)
x1, P1 = x_pred + K1 @ e1, (np.eye(6) - K1 @ H) @ P_pred       # (38), (40)
xs, Ps = kalman_filter(zs, F, H, Q, Rm, x0, P0)
fp = FPKF(6, 2)
fp.F, fp.H, fp.Q, fp.R, fp.x, fp.P = F, H, Q, Rm, x0.copy(), P0.copy()
m_fp, c_fp, _, _ = fp.batch_filter([None if np.isnan(z[0]) else z for z in zs])
kf_checks = {"one step by hand == library": bool(np.allclose(x1, xs[0]) and np.allclose(P1, Ps[0])),
             "library == FilterPy (1e-8 px)": bool(np.abs(xs - m_fp).max() < 1e-8)}
akf = ConfidenceKalmanFilter(F, H, Q, Rm, x0, P0, ConfidenceConfig(
    omega=1.0, adaptive_noise=False, q_growth=0.0))
xa = []
for z in zs:
    akf.predict()
    akf.update(None if np.isnan(z[0]) else z, 1.0)
    xa.append(akf.x)
kf_checks["confidence filter, all trusted == standard"] = bool(
    np.abs(np.array(xa) - xs).max() < 1e-8)
assert all(kf_checks.values())

# %%
# NBVAL_CHECK_OUTPUT
print(kf_checks)

# %% [markdown]
# ### Sage–Husa noise estimation (eq. 41) and its failure
#
# With the weight $d_k=(1-b)/(1-b^{k+1})$ (the paper prints "1 − b/1 − b^k") and forgetting
# factor b,
# $$R_k=(1-d_k)R_{k-1}+d_k\big(e_ke_k^\top-HP_{k|k-1}H^\top\big),$$
# $$Q_k=(1-d_k)Q_{k-1}+d_k\big(K_ke_ke_k^\top K_k^\top+P_k-FP_{k-1}F^\top\big).\tag{41}$$
# **Why it fails.** At the first step $d_0=1$, so the old R is forgotten entirely and
# $R_0=e_0e_0^\top-HP_{0|-1}H^\top$: a rank-one matrix minus a positive definite one. For any
# $v\perp e_0$, $v^\top R_0v=-v^\top HP_{0|-1}H^\top v<0$ — in 2-D, $R_0$ is NOT positive
# semi-definite at step 0, whatever the data: indefinite when the first innovation is large
# ($e_0^\top(HP_{0|-1}H^\top)^{-1}e_0>1$), negative definite when it is small. The cell checks
# both over noise levels, priors and first measurements, then runs 60 steps with and without
# our safeguard, which clips R's eigenvalues to `ConfidenceConfig.r_bounds` and projects Q
# back onto the Singer structure with $q_a$ bounded.

# %%
step0, kind0 = [], []
for offset in (np.array([3.0, -2.0]), np.zeros(2)):   # a far and a near first measurement
    for noise in (0.05, 0.5, 5.0):
        for prior in (P0, P0 / 100):
            for _ in range(25):
                z0 = H @ (F @ x0) + offset + g.normal(0, noise, 2)
                Pp = F @ prior @ F.T + Q
                e0 = z0 - H @ (F @ x0)
                R0 = np.outer(e0, e0) - H @ Pp @ H.T            # eq. (41) with d_0 = 1
                ev = np.linalg.eigvalsh(R0)
                step0.append(ev[0])
                kind0.append("indefinite" if ev[1] > 0 else "negative definite")
step0 = np.array(step0)
assert np.all(step0 < 0)
n_kind = pd.Series(kind0).value_counts()
assert set(n_kind.index) == {"indefinite", "negative definite"}   # both cases occur

zs2 = np.c_[10 * np.sin(0.7 * tt), 5 * np.cos(0.5 * tt)] + g.normal(0, 0.05, (300, 2))
min_eig = {}
for safe in (False, True):
    x, P, Rk, Qk = x0.copy(), P0.copy(), Rm.copy(), Q.copy()
    eigs = []
    for k, z in enumerate(zs2[:60]):
        P_prev = P
        x, P = F @ x, F @ P @ F.T + Qk
        K = P @ H.T @ np.linalg.inv(H @ P @ H.T + Rk)
        e = z - H @ x
        P_prior = P
        x, P = x + K @ e, (np.eye(6) - K @ H) @ P
        Rk, Qk = sage_husa_update(Rk, Qk, e=e, K=K, H=H, F=F, P_prior=P_prior, P_post=P,
                                  P_prev=P_prev, d=sage_husa_weight(k, 0.97), safeguard=safe,
                                  q_structure=np.diag(Q) > 0,
                                  q_bounds=tuple(np.multiply(
                                      A.STATUS_CONFIDENCE.q_bounds_ratio, Q[4, 4])))
        eigs.append(np.linalg.eigvalsh(Rk)[0])
    min_eig["with safeguard" if safe else "without safeguard"] = np.array(eigs)
first_bad = int(np.argmax(min_eig["without safeguard"] <= 0))
assert min_eig["without safeguard"].min() < 0 and min_eig["with safeguard"].min() > 0
fig = A.plot_sage_husa(min_eig)

# %%
# NBVAL_CHECK_OUTPUT
print(f"R_0 not positive semi-definite at step 0 in all {len(step0)} draws (σ = 0.05-5 px, "
      f"two priors, near and far first measurements): {bool(np.all(step0 < 0))}; "
      f"both indefinite and negative definite cases occur: {len(n_kind) == 2}")
print(f"without the safeguard R is not positive definite from step {first_bad}; with it R "
      f"stays positive definite: {bool(min_eig['with safeguard'].min() > 0)}")

# %% [markdown]
# ### Confidence gating (eqs. 42–46)
#
# $$C_k=\omega C_{img}+(1-\omega)C_{motion},\qquad C_{motion}=\exp\!\big(-\eta\max(0,D_M-\gamma)\big),
# \qquad D_M=\sqrt{e_k^\top S_k^{-1}e_k},\quad S_k=HP_{k|k-1}H^\top+R_k\tag{42–43}$$
# $$\hat C_k=0.9\hat C_{k-1}+0.1C_k,\qquad \tau_h=0.85\hat C_k,\qquad \tau_l=0.35\hat C_k.\tag{44–46}$$
# Modes: $C_k\ge\tau_h$ update (and a Sage–Husa step); $\tau_l\le C_k<\tau_h$ update with
# $\lambda R$; otherwise predict only, with Q multiplied by $1+0.5\,n_{\rm missed}$ (≤ 20) while
# the star stays hidden. **$C_{img}$ is not defined by the paper**; ours is
# $C_{img}=\big(1-e^{-(SNR/8)^2}\big)\exp\!\big(-\ln^2(F/F_{ref})/(2\cdot0.7^2)\big)$ — a
# faint spot, or one much dimmer (translucent cloud) or brighter (glare, a neighbour) than the
# designated star's reference flux, is trusted less. The reproduction's first cloud sequence,
# BEAK-ST:

# %%
meas_c = session.measurements("cloud", seed=0)
tr = A.track_measurements(meas_c, cfg, variants={"BEAK-ST": A.VARIANT_PARTS["BEAK-ST"]})
tr = tr["BEAK-ST"]
fig = A.plot_confidence_trace(meas_c, tr)

# %% [markdown]
# ### Metrics (eqs. 47–50)
#
# Per-frame error, its mean over the N frames, the success flag at threshold ε and the success
# rate:
# $$e_i=\sqrt{(x_i-\hat x_i)^2+(y_i-\hat y_i)^2},\qquad E=\frac1N\sum_{i=1}^Ne_i,\tag{47–48}$$
#
# $$
# s_i=\begin{cases}1,&e_i\le\varepsilon\\0,&\text{otherwise}\end{cases},\qquad
# P_s=\frac1N\sum_{i=1}^Ns_i
# \tag{49–50}
# $$
#
# (The paper writes $S_i$ and $N_t$; we use $s_i$ and N.) The paper does not give ε; we adopt
# ε = 2 px. For the cloud track above:

# %%
e_c = np.hypot(*(tr.xs[:, :2] - meas_c.truth).T)                     # (47)
metrics_c = {"E (px)": e_c.mean(), f"P_s (ε = {cfg.epsilon_px:g} px)":
             np.mean(e_c <= cfg.epsilon_px)}                         # (48)-(50)
pd.Series(metrics_c).to_frame("BEAK-ST, one cloud sequence")

# %% [markdown]
# ## Reproduction
#
# Four variants: **Baseline** (global threshold + standard KF), **BEAK-ST-GT** (global +
# confidence AKF), **BEAK-ST-SKF** (adaptive + standard KF), **BEAK-ST** (adaptive +
# confidence AKF); every filter starts from the designated star (0.3 px error) with the same
# Singer $q_a$ (sea state 3) and R = 0.25 px².
#
# **A pre-registered confirmatory run.** No setting of this experiment had been fixed before a
# result was looked at (git shows it), so on 2026-12-02 we froze one set, the *status
# settings*, with every claim's decision rule in the `[protocol]` table of `claims.toml`,
# committed it, and only then ran it on root seeds never used before. The earlier readings stay
# in each claim's history as exploratory. Each claim is decided per scenario on 20 paired
# sequences, with t intervals Bonferroni-corrected within the claim.

# %%
protocol = A.read_protocol()
display(Markdown(
    f"**Protocol ({protocol['date']}).** γ = {protocol['gamma']:g}, R within "
    f"{protocol['r_bounds_px2']} px², q_a within {protocol['q_bounds_ratio']}× its prior, gate "
    f"cap {protocol['gate_cap']}, hold {protocol['hold_after']}; "
    f"{protocol['n_sequences_per_scenario']} sequences × {protocol['n_frames']} frames per "
    f"scenario; root seeds: {protocol['root_seeds']}. This run: k = 0, root seed "
    f"{cfg.seed} (= `A.protocol_seeds(0)`: {cfg.seed == A.protocol_seeds(0)[0]})."))
meas = A.claim_measurements(res)
claims = load_claims("akf_star")
rows = A.claim_results(res)
card = scorecard(rows)
provenance, status_by_settings, ca_tuned = A.settings_tables(res)
provenance

# %% [markdown]
# The table gives where each frozen setting came from. The first committed settings
# (9ea01e8: R ≤ 1 px², q_a ≤ 100×) and the settings tuned after inspecting track losses
# (*Exploratory settings* below) ran on the same new sequences; their statuses are
# exploratory comparisons — only the first column decides:

# %%
status_by_settings

# %%
# NBVAL_CHECK_OUTPUT
depends = [c for c in status_by_settings.index if status_by_settings.loc[c].nunique() > 1]
print("statuses that would change under another settings set:", depends)

# %% [markdown]
# ### Table 1 — mean tracking error

# %%
t1 = A.side_by_side(res.mean_error(), A.paper_table(claims["akf_star.table1"], "mean_error_px"), 2)
assert (t1.filter(like="ours") >= 0).all().all()
t1

# %% [markdown]
# ### Table 2 — success rate

# %%
t2 = A.side_by_side(res.success_rate(), A.paper_table(claims["akf_star.table2"],
                                                      "success_rate"), 3)
assert ((t2.filter(like="ours") >= 0) & (t2.filter(like="ours") <= 1)).all().all()
t2

# %% [markdown]
# The verdict behind Table 1: per scenario the five paired differences the paper's ordering
# needs (positive = the paper's side), with their Bonferroni-corrected intervals.

# %%
A.verdict_table(meas["akf_star.table1"], ["Baseline − BEAK-ST", "GT − BEAK-ST",
                                          "SKF − BEAK-ST", "Baseline − GT", "Baseline − SKF"])

# %% [markdown]
# Continuity (estimate within the gate), median error and lost tracks — robust companions of
# the means, which a single lost track can dominate:

# %%
pd.concat({"continuity": res.continuity(), "median error (px)": res.median_error(),
           "lost tracks": res.lost_fraction()}, axis=1)

# %% [markdown]
# ### Fig. 6 — mean tracking error over the frames
#
# One panel per scenario, as the claim is decided (Baseline wide and dashed under BEAK-ST-GT,
# which often has the same curve).

# %%
fig = A.plot_curves_by_scenario(res, "error")

# %% [markdown]
# ### Fig. 7 — success rate over the frames

# %%
fig = A.plot_curves_by_scenario(res, "success")

# %% [markdown]
# ## Scorecard

# %%
card[["claim", "status", "ours", "note"]]

# %%
# NBVAL_CHECK_OUTPUT
statuses = {r.claim: r.status.value for r in rows}
print(statuses)
print("summary:", {s.value: int(sum(r.status is s for r in rows)) for s in Status})

# %%
same_as_report = not QUICK and study.source.startswith("stored")
if same_as_report:
    stored_status = {c["claim"]: c["status"] for c in stored["claims"]}
    assert stored_status == statuses, (stored_status, statuses)
    # and the stored study is the protocol's run k = 0 at its counts
    assert (cfg.seed, cfg.n_seeds, cfg.n_frames) == (
        A.protocol_seeds(0)[0], protocol["n_sequences_per_scenario"], protocol["n_frames"])

# %% [markdown]
# **Stability.** The protocol's runs k = 1…5 (`--seeds 5`: new sequences, same settings and
# rules) give each claim a status of its own; a claim whose status differs on any of them is
# *fragile*. The cell checks that `stability.json` is the protocol's (full counts, run on or
# after its date) and labels it otherwise:

# %%
stab = json.loads((papers_repro_dir() / "akf_star" / "stability.json").read_text())
is_protocol = stab["date"] >= protocol["date"] and not stab["quick"]
col = "k = {}" if is_protocol else "old seed {}"
stab_tab = pd.DataFrame({"committed run (k = 0)": statuses}
                        | {col.format(k): {c: v[i] for c, v in stab["statuses"].items()}
                           for i, k in enumerate(stab["seeds"])})
stab_tab[f"same status on {len(stab['seeds'])} runs"] = [
    f"{sum(s == statuses[c] for s in stab['statuses'][c])}/{len(stab['seeds'])}"
    for c in stab_tab.index]
display(Markdown(
    f"Stability run of {stab['date']} (root seeds {stab['seeds']}): "
    + ("the protocol's runs `SeedSequence([20261202, k])`." if is_protocol else
       "**NOT the protocol's** — an earlier run on the exploratory seeds `SeedSequence(k)`, "
       "before the protocol existed; it says nothing about the confirmatory statuses.")))
stab_tab

# %% [markdown]
# **Reading** (numbers below). Where the global μ + kσ threshold, inflated by a gradient or
# glare, loses the star, the adaptive variants keep it. The confidence AKF with the status
# settings loses the star in rough seas and under clouds more often than a standard KF on the
# same centroids in the stored run (the last line below says where, for the run shown); the
# tuned (exploratory) settings repair much of this, but were chosen after seeing such failures. A lost track drifts without bound, so the means of Table 1 mix tracking
# error with **drift distance** on a 128-px frame: read them beside the median error and the
# lost tracks.

# %%
E, Ex, lost = res.mean_error(), res.extra["exploratory"].mean_error(), res.lost_fraction()
more_lost = [sc for sc in E.index if lost.loc[sc, "BEAK-ST"] > lost.loc[sc, "BEAK-ST-SKF"]]
if same_as_report:                    # what the reading says, on the confirmatory run
    assert {"ship sway", "cloud occlusion"} <= set(more_lost)
Emed = res.median_error()
lines = [f"- **{sc}**: lowest mean error {E.loc[sc].idxmin()} ({E.loc[sc].min():.2f} px; lowest "
         f"median {Emed.loc[sc].idxmin()}, {Emed.loc[sc].min():.2f} px — orderings only where the "
         "verdict table's intervals exclude 0); "
         f"BEAK-ST {E.loc[sc, 'BEAK-ST']:.2f} px (lost {100 * lost.loc[sc, 'BEAK-ST']:.0f} % of "
         f"tracks), exploratory BEAK-ST {Ex.loc[sc, 'BEAK-ST']:.2f} px; paper's BEAK-ST "
         f"{t1.loc[sc, 'BEAK-ST paper']:.2f} px" for sc in E.index]
over = int((E > 128).sum().sum())      # the simulated sensor is 128×128 px
lines.append(f"- means above the frame width (128 px, i.e. drift of lost tracks): {over} of "
             f"{E.size} scenario × variant cells")
lines.append("- BEAK-ST lost more tracks than BEAK-ST-SKF under: "
             + (", ".join(more_lost) or "no scenario"))
display(Markdown("\n".join(lines)))

# %% [markdown]
# ## Explore
#
# How much the confidence filter trusts a measurement that disagrees with its prediction
# (γ, η, λ) against how fast it adapts its noise (b), on single sequences: the first three of
# each scenario in *Reproduction*. **Occlusion** (cloud only): a 25-frame occlusion is a new
# simulation (same ship motion, noise and cloud shapes, slower clouds), stored with the study;
# **b, λ, γ, η** re-run only BEAK-ST on the stored centroids.

# %%
from dataclasses import replace

EXPLORE_SEEDS, OCCLUSIONS = A.EXPLORE_SEEDS, A.EXPLORE_OCCLUSIONS   # (0, 1, 2), (10, 25)
n_before = session.n_simulated
assert session.precompute(seeds=EXPLORE_SEEDS, occlusions=OCCLUSIONS) == 0   # all stored
SHOWN = ("Baseline", "BEAK-ST-SKF", "BEAK-ST")   # BEAK-ST-GT left out (often = Baseline)
# the panel's sequences are the reproduction's: BEAK-ST re-run by this code gives its errors
same = session.errors("cloud", seed=0, variants=("BEAK-ST",))["BEAK-ST"]
stored_errors = res.errors[res.scenarios.index("cloud"), 0, A.VARIANTS.index("BEAK-ST")]
assert np.allclose(same, stored_errors, atol=1e-4)   # stored as float32


def draw(scenario_name, seed, occlusion_frames, b, lam, gamma, eta):
    errs = session.errors(scenario_name, seed=seed, occlusion_frames=occlusion_frames,
                          confidence=replace(cfg.confidence, forgetting=b, lam=lam,
                                             gamma=gamma, eta=eta), variants=SHOWN)
    occ = (f"{occlusion_frames}-frame occlusions" if scenario_name == "cloud"
           else "no clouds")
    # the filter's setting in the title: a move that changes no estimate still shows
    return A.plot_explore_errors(
        errs, f"{A.SCENARIO_LABELS.get(scenario_name, scenario_name)}, sequence {seed}, {occ} "
        f"(one sequence, not the Monte Carlo)\nconfidence filter: b = {b:.3f}, "
        f"λ = {lam:.0f}, γ = {gamma:.1f}, η = {eta:.1f}", gate_px=cfg.gate_px)


explore = panel(draw,
                scenario_name=dropdown("scenario", list(SCENARIOS), "cloud"),
                seed=dropdown("seed (reproduction sequence)", list(EXPLORE_SEEDS), 0),
                occlusion_frames=dropdown("occlusion (frames, cloud)", list(OCCLUSIONS), 10),
                b=float_slider("forgetting b", 0.90, 0.995, 0.005, 0.97),
                lam=float_slider("λ (R inflation)", 1.0, 50.0, 1.0, 10.0),
                gamma=float_slider("γ (D_M tolerance)", 1.0, 10.0, 0.5, cfg.confidence.gamma),
                eta=float_slider("η (1/σ)", 0.2, 5.0, 0.2, 1.0),
                enabled_when={"occlusion_frames": ("scenario_name", ["cloud"])})

# %% [markdown]
# Longer occlusions, counted on the panel's cloud sequences (default filter settings): a track
# is *lost* when its final estimate is farther than the gate from the star.

# %%
lost = pd.DataFrame({f"{occ}-frame occlusions": {
    v: sum(session.errors("cloud", seed=s, occlusion_frames=occ, variants=(v,))[v][-1]
           > cfg.gate_px for s in EXPLORE_SEEDS) for v in SHOWN} for occ in OCCLUSIONS})
lost.index.name = f"tracks lost (of {len(EXPLORE_SEEDS)} sequences)"
assert session.n_simulated == n_before   # the panel and this table simulated nothing
lost

# %% [markdown]
# ## Errata and deviations
#
# | where | paper | adopted |
# |---|---|---|
# | eq. (2) | $R_x(\varphi)R_y(\theta)$: axes swapped | $R_y(\varphi)R_x(\theta)$, the text's pitch about X then roll about Y′ (differs at first order) |
# | eq. (5) | $R_y(\beta)R_x(\alpha)$, azimuth about the optical axis; the printed matrix expands $[R_y(\beta)R_x(\alpha)]^\top$ | $R_x(\alpha)R_z(-\beta)$, small-angle form above |
# | eq. (10) | Z the optical axis | Y′ (Fig. 3); eq. (10) checked as printed |
# | eq. (12) | Earth term without latitude | the diurnal rates (next cell) |
# | eqs. (21)–(22) | σ_f a "variance"; $T_f\ge I_f$ | standard deviation; $I_f\ge T_f$ |
# | eq. (18) | R divided by 255 | other data: quantiles over the data's range |
# | eqs. (28)–(29) | weights I over the thresholded region | weights $I-B$, region grown by 2 px (*Beyond*) |
# | eq. (31) | noise sample added to the prediction | mean predicted; noise through Q |
# | eq. (33) | $\ddot u_s=-\alpha\dot u_s+w$, inconsistent with eqs. (34)–(35) | constant acceleration (random-walk a) with the Q of eqs. (34)–(35) |
# | eq. (41) | $d_k = 1-b/1-b^k$ | $d_k=(1-b)/(1-b^{k+1})$; R and Q bounded |
# | eq. (42) | $C_{img}$ undefined | SNR × flux consistency |
# | eq. (46) | "Q increased" in occlusion, no law | Q × (1 + 0.5 n_missed), at most × 20 |
# | §2 | OTB100; ε, ω, η, γ, λ, b, k, k_b, r, σ_b not given | simulated sequences; values in `AblationConfig`, `ConfidenceConfig`, `ExtractionConfig` |
# | abstract | 40 % lower error, continuity > 95 % | Table 1 gives more (exercise 5); continuity = estimate within the gate |

# %%
display(Markdown(
    f"**Eq. (12), measured.** Against astropy for {len(diurnal)} stars, the printed "
    f"Earth-rotation rates are off by a median relative error of "
    f"{diurnal['rel_error_paper'].median():.2f} (maximum "
    f"{diurnal['rel_error_paper'].max():.3g}: for stars near the meridian the true rate "
    f"is small and the printed one is not), while the corrected form stays within "
    f"{100 * diurnal['rel_error_correct'].max():.2g} % — the printed term is wrong by about "
    f"its own size, not by a few per cent."))

# %% [markdown]
# **Exploratory settings**, chosen after looking at track losses on the earlier seeds; they run
# on the protocol's sequences beside the status settings and never decide a status. The
# scenario presets were also set with results in view; they are part of the frozen protocol.
#
# | setting | value | what was seen with the alternative (earlier seeds) |
# |---|---|---|
# | γ | 5 | γ = 3 lost the star in rough seas (*Beyond*) |
# | R upper bound | 1 px² | at 25 px² BEAK-ST diverged under sway |
# | $q_a$ range | [1, 16] × prior | over-confident before sway peaks; estimates dropped at low SNR |
# | gate cap | 30 px | at 60 px a coasting track took a neighbour |
# | hold after 5 missed frames | v, a zeroed | the CA extrapolation ran away |

# %% [markdown]
# ## Beyond the paper
#
# **Centroid accuracy.** Eqs. (28)–(29) weight only the pixels above the local threshold, so
# the PSF wings are cut and the centroid is pulled towards the brightest pixel ("pixel
# locking"). Growing each region by two pixels (the library default) removes most of the bias,
# as does the sky extractor's windowed centroid (nominal sequence, 60 frames):

# %%
centroids = study.tables["centroid_bias"]
centroids.round(4)

# %% [markdown]
# **Constant-velocity and re-tuned constant-acceleration filters.** The ablation's adaptive
# centroids, on the protocol's sequences, through a plain constant-velocity KF
# (white-acceleration density q = 400 px²/s³) and through the standard CA filter with its
# process noise ×100 or with a small R:

# %%
E, Ex = res.mean_error(), res.extra["exploratory"].mean_error()
grown = centroids.loc["grown region (grow 2, default)"]
display(Markdown(
    f"The small R is a setting, R = {A.CA_TRUE_R_PX2:g} px² "
    f"({np.sqrt(A.CA_TRUE_R_PX2):.2f} px per axis), of the order of the adaptive centroids' "
    f"error measured above (median {grown['median error (px)']:.3f} px, 90th percentile "
    f"{grown['90th percentile (px)']:.3f} px); the status filters use R = {cfg.r_px2:g} px²."))
cv = res.extra["CV baseline"].mean_error()["CV KF"]
cv_lost = res.extra["CV baseline"].lost_fraction()["CV KF"]
tuned_cols = [c for c in ca_tuned.columns if c.startswith("CA KF, ")]
tab = ca_tuned.assign(**{"BEAK-ST": E["BEAK-ST"], "BEAK-ST (exploratory)": Ex["BEAK-ST"]})
display(tab.round(3))
sway = "ship sway"
best_ca = ca_tuned.loc[sway, tuned_cols].min()
singer = ca_tuned.loc[sway, "CA KF (Singer Q, R = 0.25 px²)"]
# the lever is Q/R: a re-tuned CA filter matches or beats the CV one under sway ...
assert best_ca <= 1.1 * cv[sway] and singer > 3 * best_ca
worst = ca_tuned[tuned_cols].max(axis=1)
w = worst.idxmax()
display(Markdown(
    f"Under sway the CA filter with the Singer prior errs by {singer:.2f} px, the CV filter by "
    f"{cv[sway]:.3f} px and the re-tuned CA filter by {best_ca:.3f} px: the sway error is "
    "**lag from the noise setting** (Q too small for the sway, R large), not constant "
    "acceleration against constant velocity. The same re-tuning fails elsewhere: its worst "
    f"mean error is {worst.max():.0f} px ({w}), where the Singer prior gives "
    f"{ca_tuned.loc[w, 'CA KF (Singer Q, R = 0.25 px²)']:.2f} px and BEAK-ST "
    f"{E.loc[w, 'BEAK-ST']:.2f} px — but BEAK-ST errs by {E.loc[sway, 'BEAK-ST']:.0f} px under "
    "sway. No single re-tuning of the CA filter suits every scenario; on these 20 sequences "
    f"the CV filter with one fixed q does: mean error at most {cv.max():.2f} px ({cv.idxmax()}), "
    f"{(cv_lost * cfg.n_seeds).sum():.0f} of {cv_lost.size * cfg.n_seeds} tracks lost "
    f"({', '.join(cv_lost.index[cv_lost > 0]) or 'none'})."))

# %% [markdown]
# **Which part of the confidence AKF loses the sway tracks?** BEAK-ST re-filtered on the three
# stored sway sequences with each of its two mechanisms switched off — the Sage–Husa
# adaptation (`adaptive_noise`) and the motion gating (η = 0 makes $C_{motion}\equiv1$):

# %%
iso = A.isolate_confidence(session, "sway", EXPLORE_SEEDS)
kept = [f"Sage–Husa {a}, gating {b}" for (a, b), r in iso.iterrows() if r.iloc[0] == 0]
display(iso.round(2))
display(Markdown("Sequences kept in every one of the three: "
                 + ("; ".join(kept) or "no combination") + "."))

# %% [markdown]
# **Filter consistency.** On two other sequences per scenario (simulation seeds 100 and 101),
# the CA filter, a CV filter and BEAK-ST. NEES uses the position block of P against the true
# position, NIS the innovations; both have mean 2 for a consistent filter (2 degrees of
# freedom; Bar-Shalom et al. 2001, §5.4): far above 2 is over-confident, far below
# over-cautious.

# %%
cons = study.tables["consistency"]
display(cons.round(3))
nees_max = cons["mean NEES"].groupby(level="filter").agg(["max", "idxmax"])
display(Markdown("Largest mean NEES per filter (2 = consistent): " + "; ".join(
    f"{f} {r['max']:.3g} ({r['idxmax'][0]})" for f, r in nees_max.iterrows())
    + ". A NEES in the hundreds is a lost track with a small P (over-confident): on these two "
    "other sequences per scenario even the CV filter can lose a track the ablation kept."))

# %% [markdown]
# **Sensitivity of BEAK-ST in a rough sea (exploratory).** Sea state 5, six sequences; "lost"
# is the share of sequences whose final estimate is farther than the gate from the star; every
# row uses the tuned bounds on R and q_a. This study led to γ = 5: exploratory evidence only.

# %%
study.tables["sensitivity"].round(3)

# %% [markdown]
# **Extraction on real skies.** The paper's procedure suits 8-bit frames (R assumes 0…255,
# touching stars merge). The library's default, `extract_stars(img)` (method `"sky"`), thresholds
# over the *local* noise of sigma-clipped meshes for at most one false detection per 10⁶ px of
# noise (integer frames included), deblends, and flags cosmic rays and hot pixels as DAOFIND and
# SEP do. On M13 (astropy's test data) both recover SEP's 40 brightest clean, isolated stars —
# a sanity check; the comparison is in the benchmark records of the closing note:

# %%
import sep

m13 = real_sky_images()["m13"]
data = np.ascontiguousarray(m13, dtype=np.float64)
bkg = sep.Background(data)
ref = sep.extract(data - bkg, 5.0, err=bkg.rms(), minarea=3)
ref_xy = np.c_[ref["x"], ref["y"]]
idx = clean_isolated(ref_xy, ref["flux"], ref["flag"], m13.shape, a=ref["a"], b=ref["b"], n=40)
sky = extract_stars(m13, return_info=True)
found, _, offset = match_positions(sky.xy, ref_xy[idx], 1.0)
paper_way = extract_stars(m13, method="adaptive")
found_paper, _, _ = match_positions(paper_way.xy, ref_xy[idx], 1.0)
assert found.mean() >= 0.95
fig = A.plot_real_sky(m13, sky.xy, reference=ref_xy[idx],
                title="M13 (astropy test data): sky extractor and SEP's clean isolated stars")

# %%
# NBVAL_CHECK_OUTPUT
print(f"SEP's clean isolated stars found within 1 px — sky extractor: {round(found.mean(), 1)}, "
      f"paper's adaptive method: {round(found_paper.mean(), 1)}")

# %% [markdown]
# **Recommendation.** A local-background extractor, a Kalman filter whose Q and R match the
# centroid noise and the sway (checked per condition), track maintenance for occlusions, and a
# bounded Sage–Husa if any.

# %% [markdown]
# ## Key points
#
# - A star's image motion is Earth rotation plus ship motion; the Earth part depends on the
#   observer's latitude, which the paper's eq. (12) drops.
# - A threshold must be local: a global μ + kσ fails under gradients and glare.
# - The Kalman update is a few lines; the modelling lives in F, Q and R. The sway error of the
#   CA filters is lag from a small Q and a large R.
# - Sage–Husa with $d_0=1$ starts from $ee^\top-HPH^\top$, never positive semi-definite in
#   2-D: bound it.
# - With the frozen settings the confidence AKF lost the star under sway and clouds more often
#   than a standard KF on the same centroids; under sway its bounded Sage–Husa adaptation and
#   its motion gating each lose it on their own (*Beyond*).
# - A status is a test only if settings and rule were fixed before the data (here: frozen in
#   `claims.toml`, run on new seeds).

# %% [markdown]
# ## Exercises
#
# Check an answer with `check("akf_star.N", answer)`; worked solutions are in
# `notebooks/solutions/05_akf_star_solutions.ipynb`.
#
# **1 (derivation, eq. 34).** The Singer acceleration obeys $da=-\alpha a\,dt+\sigma_w dW$.
# Starting from $a=0$, derive the variance after one frame ΔT and evaluate it for a slower
# camera and a livelier sea than above: α = 1.5 s⁻¹, σ_w = 3, ΔT = 0.5 s.

# %%
answer = None  # your answer here (px²/s⁴)
if answer is not None:
    check("akf_star.1", answer)

# %% [markdown]
# **2 (derivation, eq. 41).** Write `d(k, b)`, the Sage–Husa weight of step k, such that the
# weights $d_k b^{k-j}$ of the past steps j = 0…k sum to one.

# %%
d = None  # your function here: def d(k, b): ...
if d is not None:
    check("akf_star.2", d)

# %% [markdown]
# **3 (computation).** Take `A.diurnal_check(n_stars=60, min_alt_deg=30)` — 60 stars above
# 30°, not the 30 above 15° shown earlier — and keep only the columns `azimuth_deg`,
# `altitude_deg`, `astropy_cosh_Adot` and `astropy_hdot`. From A and h build eq. (12)'s
# Earth-rotation rates yourself (ω_e = 7.292115·10⁻⁵ rad/s) and find their median relative
# error against astropy. The mapping: eq. (12)'s $(\dot u,\dot v)/f$ is read as
# $(\cos h\,\dot A,\ \dot h)$, i.e. $-\omega_e\sin A\cos h$ is the azimuthal rate and
# $-\omega_e\cos A\cos h$ the altitude rate; a star's relative error is
# $|r_{\rm paper}-r_{\rm astropy}|/|r_{\rm astropy}|$ of that 2-vector.

# %%
answer = None
if answer is not None:
    check("akf_star.3", answer)

# %% [markdown]
# **4 (exploration).** In *Explore*: cloud scenario, seed 0, 25-frame occlusion, the session's
# default filter settings (the status settings, γ = 3 — not the tuned ones). What is BEAK-ST's
# mean error over the 200 frames (px)? (`session.errors(...)` reads it exactly.) Then move γ
# and λ: which settings lose the star?

# %%
answer = None
if answer is not None:
    check("akf_star.4", answer)

# %% [markdown]
# **5 (critique).** The abstract claims about 40 % lower error. From the paper's Table 1
# (`claims["akf_star.table1"].paper`), compute per scenario by how many per cent BEAK-ST's mean
# error is below Baseline's, and give the median of the five reductions. Does it support
# "about 40 %"?

# %%
answer = None
if answer is not None:
    check("akf_star.5", answer)

# %% [markdown]
# **6 (critique).** For which observer are eq. (12)'s Earth-rotation terms exact for every star?
# (a) at the equator, (b) at a pole, (c) at 45° latitude, (d) for no observer. Answer with
# the letter.

# %%
answer = None  # "a", "b", "c" or "d"
if answer is not None:
    check("akf_star.6", answer)

# %% [markdown]
# ## Closing note (issue 28)
#
# The reviews of this notebook and how each finding was fixed or answered are in the issue's
# closing notes. This version: verdicts from a pre-registered confirmatory run with its
# stability over the runs k = 1…5; side studies in *Beyond*; an extractor whose false-alarm
# rate holds on integer frames. Each target of the benchmark records
# (`papers_repro/akf_star/bench_*.txt`, written by `--out` of the two scripts), read from them:

# %%
import re

target = re.compile(r"([-+]?\d+(?:\.\d+)?)[^\d(]*\(target ([<>]=) ([-+]?\d+(?:\.\d+)?)")
verdicts = []
for name in ("bench_akf_star.txt", "bench_extraction.txt"):
    rec = papers_repro_dir() / "akf_star" / name
    text = rec.read_text() if rec.exists() else f"{name}: not recorded yet\n"
    for line in text.splitlines():
        m = target.search(line)
        if m:
            v, op, b = float(m[1]), m[2], float(m[3])
            ok = v <= b if op == "<=" else v >= b
            verdicts.append({"record": name, "measurement": line.split("]")[0].lstrip("[ "),
                             "value": v, "target": f"{op} {b:g}",
                             "met": "met" if ok else "MISSED"})
pd.DataFrame(verdicts)

# %% [markdown]
# ## References
#
# 1. Sheng Y.S. Adaptive anti-occlusion star tracking algorithm for ships based on a physical
#    model. *Intelligent Computer and Applications* 16(4):195–202, 2026.
#    [doi:10.20169/j.issn.2095-2163.26010403](https://doi.org/10.20169/j.issn.2095-2163.26010403)
# 2. Kalman R.E. A new approach to linear filtering and prediction problems. *J. Basic Eng.*
#    82(1):35–45, 1960. [doi:10.1115/1.3662552](https://doi.org/10.1115/1.3662552)
# 3. Singer R.A. Estimating optimal tracking filter performance for manned maneuvering targets.
#    *IEEE Trans. Aerospace and Electronic Systems* AES-6(4):473–483, 1970.
#    [doi:10.1109/TAES.1970.310128](https://doi.org/10.1109/TAES.1970.310128)
# 4. Sage A.P., Husa G.W. Adaptive filtering with unknown prior statistics. *Proc. Joint
#    Automatic Control Conference*, 760–769, 1969.
# 5. Bertin E., Arnouts S. SExtractor: software for source extraction. *A&A Suppl.*
#    117:393–404, 1996. [doi:10.1051/aas:1996164](https://doi.org/10.1051/aas:1996164)
# 6. Barbary K. SEP: Source Extractor as a library. *JOSS* 1(6):58, 2016.
#    [doi:10.21105/joss.00058](https://doi.org/10.21105/joss.00058)
# 7. Gaia Collaboration, Vallenari A. et al. Gaia Data Release 3. *A&A* 674:A1, 2023.
#    [doi:10.1051/0004-6361/202243940](https://doi.org/10.1051/0004-6361/202243940)
# 8. Astropy Collaboration. The Astropy Project: sustaining and growing a community-oriented
#    Python package. *ApJ* 935:167, 2022.
#    [doi:10.3847/1538-4357/ac7c74](https://doi.org/10.3847/1538-4357/ac7c74)
# 9. Wu Y., Lim J., Yang M.-H. Object tracking benchmark (OTB100). *IEEE TPAMI*
#    37(9):1834–1848, 2015. [doi:10.1109/TPAMI.2014.2388226](https://doi.org/10.1109/TPAMI.2014.2388226)
# 10. Labbe R. *Kalman and Bayesian Filters in Python*, 2020.
#     <https://github.com/rlabbe/Kalman-and-Bayesian-Filters-in-Python>
# 11. Bar-Shalom Y., Li X.R., Kirubarajan T. *Estimation with Applications to Tracking and
#     Navigation.* Wiley, 2001 (NEES and NIS, §5.4).
#     [doi:10.1002/0471221279](https://doi.org/10.1002/0471221279)
# 12. Labbe R. *FilterPy* (the reference Kalman filter our library is tested against).
#     <https://github.com/rlabbe/filterpy>

# %%
from eotrack.notebook import lesson_footer

lesson_footer("05")
