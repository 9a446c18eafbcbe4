# ---
# jupyter:
#   kernelspec:
#     display_name: Python 3
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
# **What the paper does.** A star sensor on a ship must keep a reference star in track while
# the waves roll, pitch and yaw the ship, clouds hide the star and sky or sea light lowers the
# contrast. The paper combines (1) a physical observation model of the star's image motion
# (Earth rotation + ship motion), (2) an *adaptive-threshold* star extraction (histogram dynamic
# range, Gaussian background removal, local mean + k·std threshold) and (3) a
# *confidence-gated adaptive Kalman filter* (Singer process noise, Sage–Husa noise estimation,
# three modes: update / update with inflated R / predict only). An ablation over four variants
# and five scenarios (Tables 1–2, Figs. 6–7) is its evidence.
#
# **Our stand-in for the paper's data.** The paper ran on "the first 200 frames of OTB100"
# (a generic visual-tracking benchmark, not star images). We simulate a shipborne star sensor
# instead: real Gaia/Hipparcos stars around a 2nd-magnitude reference star seen from a ship at
# 30°N 123°E, astropy Alt/Az for every frame, roll/pitch/yaw as sums of sinusoids, Gaussian PSF
# with motion blur, shot and read noise, 8-bit frames, with knobs for the five scenarios.
#
# **Scorecard status:** printed at the end of *Setup*; section 6 has the table. The notebook
# runs a reduced ablation (3 seeds per scenario) to stay within a minute; `make repro` runs
# 20 seeds and writes `papers_repro/akf_star/REPORT.md`.

# %% [markdown]
# ## 2 · Setup

# %%
import importlib.metadata as md

import astropy.units as u
import eotrack.astro as astro  # offline astropy first
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from eotrack import plotting
from eotrack.experiments import akf_star as A
from eotrack.geometry.shipboard import (
    OMEGA_EARTH,
    camera_from_deck,
    camera_from_level,
    deck_from_level,
    diurnal_rates,
    diurnal_rates_paper,
    enu_from_azalt,
    image_rate_projective,
    sea_state_motion,
    ship_attitude,
    star_angles_from_image,
)
from eotrack.imaging import (
    SCENARIOS,
    ExtractionConfig,
    ShipSite,
    extract_stars,
    grey_quantiles,
    scenario,
    simulate_sequence,
)
from eotrack.montecarlo import TrialRunner
from eotrack.repro import Status, load_claims, scorecard
from eotrack.tracking.kalman import (
    ConfidenceConfig,
    ConfidenceKalmanFilter,
    constant_acceleration_model,
    kalman_filter,
    nees,
    nis,
    sage_husa_update,
    sage_husa_weight,
    singer_acceleration_variance,
    singer_process_noise,
)

plotting.style()
pd.set_option("display.precision", 3)
pd.set_option("display.max_colwidth", 110)
pd.set_option("display.width", 160)

# %% tags=["parameters"]
N_SEEDS = 3       # sequences per scenario here; the paper-scale run (make repro) uses 20
N_FRAMES = 200    # the paper's 200 frames
QUICK = False

# %%
print("versions:", {p: md.version(p) for p in ("numpy", "scipy", "opencv-python-headless",
                                                "astropy", "filterpy", "eotrack")})
claims = load_claims("akf_star")
cfg = A.AblationConfig(n_seeds=N_SEEDS, n_frames=120 if QUICK else N_FRAMES)
res = A.run_ablation(cfg, runner=TrialRunner(progress=False))
rows = A.claim_results(res)
card = scorecard(rows)
print("scorecard:", {s.value: int(sum(r.status is s for r in rows)) for s in Status})

# %% [markdown]
# ## 3 · Notation
#
# | paper | code | unit |
# |---|---|---|
# | θ, φ, ψ (pitch, roll, heading) | `pitch`, `roll`, `heading` | rad |
# | α, β (optical-axis elevation, azimuth) | `cam_elevation`, `cam_azimuth` | rad |
# | R_{N→B}, R_{B→C} | `deck_from_level`, `camera_from_deck` | – |
# | S_x, S_z, f | `s_x`, `s_z`, `focal` / `SensorConfig.focal_px` | px |
# | A, h (star azimuth, altitude), ω_e | `azimuth`, `altitude`, `OMEGA_EARTH` | rad, rad/s |
# | g5, g95, R (dynamic range) | `grey_quantiles`, `dynamic_range` | grey level, – |
# | σ_b, k, r, k_b | `ExtractionConfig.sigma_b, k, r, k_b` | px, –, px, – |
# | X = [x, y, v_x, v_y, a_x, a_y] | filter state `x` | px, px/s, px/s² |
# | α (Singer), σ_w, q_a | `alpha`, `sigma_w`, `singer_acceleration_variance` | 1/s, px/s^2.5, px²/s⁴ |
# | b, d_k | `ConfidenceConfig.forgetting`, `sage_husa_weight` | – |
# | ω, η, γ, λ | `ConfidenceConfig.omega, eta, gamma, lam` | – |
# | C_img, C_motion, C_k, Ĉ_k, τ_h, τ_l | `image_confidence`, `ConfidenceKalmanFilter.confidence` | – |
# | ε (success threshold) | `AblationConfig.epsilon_px` | px |

# %% [markdown]
# ## 4 · The method, step by step
#
# ### 4.1 Rotation chain (eqs. 1–5)
#
# $\mathbf r^{C} = R_{B\to C}\,R_{N\to B}\,\mathbf r$. The level frame N is east-north-up. The
# text turns the deck by pitch θ about X (starboard) and then by roll φ about the new Y′ (bow);
# with the paper's passive matrices
# $R_x(a)=\begin{pmatrix}1&0&0\\0&\cos a&\sin a\\0&-\sin a&\cos a\end{pmatrix}$,
# $R_y(a)=\begin{pmatrix}\cos a&0&-\sin a\\0&1&0\\\sin a&0&\cos a\end{pmatrix}$
# that is $R_{N\to B}=R_y(\varphi)R_x(\theta)R_z(-\psi)$ (heading included). Eq. (2) prints
# $R_x(\varphi)R_y(\theta)$ — angle symbols swapped and factors reversed; for sea-state angles
# the difference is second order. The camera looks at azimuth β, elevation α on the deck:
# $R_{B\to C}=R_x(\alpha)R_z(-\beta)$ (eq. 5 rotates the azimuth about Y, the optical axis, and
# prints the transpose of the small-angle product).

# %%
psi, A0, h0 = np.radians(45.0), np.radians(130.0), np.radians(42.0)
R = camera_from_level(psi, 0.0, 0.0, A0 - psi, h0)
assert np.allclose(R @ enu_from_azalt(A0, h0), [0, 1, 0])          # boresight on the star
assert np.allclose(R @ R.T, np.eye(3))
th, ph = np.radians(1.0), np.radians(2.5)
Rx = deck_from_level(0.0, th, 0.0)
Ry = deck_from_level(0.0, 0.0, ph)
printed_minus_text = np.abs(Rx @ Ry - Ry @ Rx).max()
print(f"order of pitch/roll matters only at second order: {printed_minus_text:.2e} "
      f"(θφ = {th * ph:.2e})")
assert printed_minus_text <= 1.01 * th * ph
small = np.abs(camera_from_deck(0.01, 0.02) - camera_from_deck(0.01, 0.02, small_angle=True))
assert small.max() < 3e-4

# %% [markdown]
# ### 4.2 Star angles from the image (eqs. 6–9)
#
# A star imaged at offsets $(S_x, S_z)$ has camera-frame direction $\propto (S_x, f, S_z)$, so
# its azimuth is $\varphi_x=\arctan(S_x/f)$ and its elevation
# $\arctan\big(S_z/\sqrt{S_x^2+f^2}\big)=\arctan(\tan\varphi_z\cos\varphi_x)$ — the right
# triangles of Fig. 4.

# %%
rng = np.random.default_rng(0)
f = 700.0
sx, sz = rng.uniform(-64, 64, (2, 1000))
az, el = star_angles_from_image(sx, sz, f)
v = np.stack([sx, np.full_like(sx, f), sz], 1)
v /= np.linalg.norm(v, axis=1, keepdims=True)
err = max(np.abs(az - np.arctan2(v[:, 0], v[:, 1])).max(), np.abs(el - np.arcsin(v[:, 2])).max())
print(f"eqs. (6)-(9) vs the direction vector: max difference {err:.1e} rad")
assert err < 1e-12

# %% [markdown]
# ### 4.3 Image motion (eqs. 10–12) and the Earth-rotation erratum
#
# Eq. (10), $\dot u=f(\dot X Z-X\dot Z)/Z^2$, is the derivative of $u=fX/Z$ (checked by a finite
# difference below). Eq. (12) writes the Earth-rotation part as
# $\dot u\approx-f\omega_e\sin A\cos h$, $\dot v\approx-f\omega_e\cos A\cos h$ — without the
# observer's latitude. A star's diurnal motion in azimuth A (from north through east) and
# altitude h is
# $$\dot h=\omega_e\cos\phi_{\rm lat}\sin A,\qquad
# \cos h\,\dot A=\omega_e(\sin\phi_{\rm lat}\cos h-\cos\phi_{\rm lat}\sin h\cos A),$$
# of total angular speed $\omega_e\cos\delta$. We compare both forms with astropy's Alt/Az of
# the 30 brightest stars above 15° seen from the ship, over 3 minutes (no refraction).

# %%
r3, rd3 = np.array([0.1, -0.2, 1.0]), np.array([0.01, 0.03, -0.02])
ud, vd = image_rate_projective(r3, rd3, 500.0)
eps_t = 1e-6
r3b = r3 + rd3 * eps_t
assert np.isclose(ud, 500 * (r3b[0] / r3b[2] - r3[0] / r3[2]) / eps_t, rtol=1e-5)

from astropy.coordinates import AltAz, EarthLocation, SkyCoord
from astropy.time import Time

site = ShipSite()
loc = EarthLocation.from_geodetic(site.lon_deg * u.deg, site.lat_deg * u.deg, 0 * u.m)
t0 = Time(site.start_utc)
cat = astro.load_catalog().select(slice(0, 400))
times = t0 + np.array([0.0, 90.0, 180.0]) * u.s
aa = SkyCoord(cat.ra_deg[:, None] * u.deg, cat.dec_deg[:, None] * u.deg).transform_to(
    AltAz(obstime=times[None, :], location=loc, pressure=0 * u.hPa))
Az, Alt = np.radians(aa.az.deg), np.radians(aa.alt.deg)
up = np.flatnonzero(Alt[:, 1] > np.radians(15))[:30]
dA = np.angle(np.exp(1j * (Az[up, 2] - Az[up, 0]))) / 180.0
dh = (Alt[up, 2] - Alt[up, 0]) / 180.0
obs = np.c_[np.cos(Alt[up, 1]) * dA, dh]                    # (cos h Ȧ, ḣ) from astropy
good = np.c_[diurnal_rates(Az[up, 1], Alt[up, 1], np.radians(site.lat_deg))]
paper = np.c_[diurnal_rates_paper(Az[up, 1], Alt[up, 1])]
rel_good = np.linalg.norm(good - obs, axis=1) / np.linalg.norm(obs, axis=1)
rel_paper = np.linalg.norm(paper - obs, axis=1) / np.linalg.norm(obs, axis=1)
dec = np.radians(cat.dec_deg[up])
speed = np.linalg.norm(obs, axis=1) / (OMEGA_EARTH * np.cos(dec))
print(f"correct form vs astropy: median relative error {np.median(rel_good):.1e}, max "
      f"{rel_good.max():.1e}; total speed / (ω_e cos δ) = {speed.min():.4f}…{speed.max():.4f}")
print(f"eq. (12) as printed vs astropy: median relative error {np.median(rel_paper):.2f}, max "
      f"{rel_paper.max():.2f}")
assert rel_good.max() < 0.01 and np.median(rel_paper) > 0.3

# %%
fig, ax = plt.subplots(figsize=(6.4, 3.6))
sc_ = 206264.8
ax.plot(obs[:, 1] * sc_, good[:, 1] * sc_, "o", label="correct form")
ax.plot(obs[:, 1] * sc_, paper[:, 1] * sc_, "x", label="eq. (12) as printed")
lim = np.abs(obs[:, 1]).max() * sc_ * 1.1
ax.plot([-lim, lim], [-lim, lim], "k:", lw=0.8)
ax.set_xlabel("astropy ḣ (arcsec/s)")
ax.set_ylabel("model ḣ (arcsec/s)")
ax.set_title("Altitude rate of 30 real stars, 30°N, 3 min")
ax.legend()
plt.show()

# %% [markdown]
# ### 4.4 Ship motion and the simulated sequences
#
# Roll, pitch and yaw are sums of sinusoids (`ShipMotion`) with indicative sea-state
# amplitudes (sea state 3: roll 1.2°, pitch 0.6°; the *sway* scenario uses sea state 5); the
# phases are random per sequence. Sensor: 128×128 px, 10° field (≈ 281″/px), 5 Hz, 0.1 s
# exposure, σ_PSF = 1 px. The scenario knobs are `Scenario` fields:

# %%
att = ship_attitude(sea_state_motion(3), np.arange(0, 40, 0.2), np.random.default_rng(1))
print(pd.DataFrame([scenario(s).__dict__ for s in ("nominal", *SCENARIOS)]).set_index("name")
      .drop(columns=["cloud_opacity"]))
fig, ax = plt.subplots(figsize=(6.4, 3.0))
for k in ("roll", "pitch", "heading"):
    a = np.degrees(att[k] - (np.radians(45) if k == "heading" else 0))
    ax.plot(np.arange(0, 40, 0.2), a, label=k if k != "heading" else "yaw")
ax.set_xlabel("t (s)")
ax.set_ylabel("angle (deg)")
ax.set_title("Sea state 3 ship attitude (one realisation)")
ax.legend()
plt.show()
A.plot_example_frames(seed=1, frame=120)
plt.show()

# %% [markdown]
# ### 4.5 Adaptive-threshold extraction (eqs. 15–29)
#
# Histogram quantiles $g_5, g_{95}$ and dynamic range $R=(g_{95}-g_5)/255$; background
# $B=I*G_{\sigma_b}$; $I_f=I-B$; ROI from $I_f\ge T_f=\mu_f+k\sigma_f$ (the paper prints the
# comparison reversed and calls σ_f a variance) when R is small; local threshold
# $T=\mu_b+k_b\sigma_b$ over a $(2r+1)^2$ window (box filters); connected components; weighted
# centroids. The baseline is one global threshold $\mu+k\sigma$. On a strong-light frame:

# %%
seq = simulate_sequence(np.random.default_rng(3), "strong_light", n_frames=20)
img = seq.images[10]
g5, g95 = grey_quantiles(img)
ad = extract_stars(img, return_info=True)
gl = extract_stars(img, method="global", return_info=True)
d_ad = np.hypot(*(ad.xy - seq.truth[10]).T).min() if len(ad) else np.inf
d_gl = np.hypot(*(gl.xy - seq.truth[10]).T).min() if len(gl) else np.inf
print(f"g5 = {g5}, g95 = {g95}, R = {ad.dynamic_range:.3f}; adaptive: {len(ad)} stars, "
      f"reference star found {d_ad:.2f} px from the truth; global: {len(gl)} stars")
assert d_ad < 0.5 and not d_gl < 0.5
fig, axs = plt.subplots(1, 2, figsize=(8, 3.6))
axs[0].bar(np.arange(256), np.bincount(img.ravel(), minlength=256), width=1)
axs[0].axvline(g5, color="k", ls=":")
axs[0].axvline(g95, color="k", ls=":")
axs[0].set_title("grey histogram, g5 and g95")
axs[1].imshow(img, cmap="gray")
axs[1].plot(*ad.xy.T, "+", color="lime", label="adaptive")
if len(gl):
    axs[1].plot(*gl.xy.T, "x", color="r", label="global")
axs[1].set_title("strong light: detections")
axs[1].grid(False)
plt.show()

# %% [markdown]
# ### 4.6 Kalman filters (eqs. 30–46)
#
# Constant-acceleration state, prediction $X_{k|k-1}=FX_{k-1}$ (eq. 31 wrongly adds the noise
# sample $W_{k-1}$ to the estimate), $P_{k|k-1}=FPF^\top+Q$. Singer: $\dot a=-\alpha a+w$,
# $q_a=\frac{\sigma_w^2}{2\alpha}(1-e^{-2\alpha\Delta T})$ is the variance the
# Ornstein–Uhlenbeck process adds over one frame — checked by Monte Carlo:

# %%
alpha, sigma_w, dt = 0.7, 4.0, 0.2
n_mc, n_sub = 20000, 400
a = np.zeros(n_mc)
h_ = dt / n_sub
g = np.random.default_rng(2)
for _ in range(n_sub):  # Euler–Maruyama from a = 0
    a += -alpha * a * h_ + sigma_w * np.sqrt(h_) * g.standard_normal(n_mc)
qa = singer_acceleration_variance(dt, alpha, sigma_w)
print(f"q_a closed form {qa:.4f}, Monte Carlo {a.var():.4f}")
assert abs(a.var() / qa - 1) < 0.05

# %% [markdown]
# Our standard filter against FilterPy on the same data (identical estimates), and the
# confidence filter with every observation trusted (ω = 1, C_img = 1, no Sage–Husa, no Q growth
# during the gap) against the standard filter:

# %%
from filterpy.kalman import KalmanFilter as FPKF

F, H = constant_acceleration_model(dt)
Q = singer_process_noise(dt, alpha, sigma_w)
Rm = 0.25 * np.eye(2)
x0, P0 = np.zeros(6), np.diag([1.0, 1, 50, 50, 20, 20])
tt = np.arange(300) * dt
zs = np.c_[10 * np.sin(0.7 * tt), 5 * np.cos(0.5 * tt)] + g.normal(0, 0.5, (300, 2))
zs[100:130] = np.nan  # an occlusion: predict only
xs, Ps = kalman_filter(zs, F, H, Q, Rm, x0, P0)
fp = FPKF(6, 2)
fp.F, fp.H, fp.Q, fp.R, fp.x, fp.P = F, H, Q, Rm, x0.copy(), P0.copy()
m_fp, c_fp, _, _ = fp.batch_filter([None if np.isnan(z[0]) else z for z in zs])
print(f"ours vs FilterPy: max |Δx| = {np.abs(xs - m_fp).max():.1e}, "
      f"max |ΔP| = {np.abs(Ps - c_fp).max():.1e}")
assert np.abs(xs - m_fp).max() < 1e-8
# q_growth = 0: no extra process noise during the occlusion, which the standard filter lacks
akf = ConfidenceKalmanFilter(F, H, Q, Rm, x0, P0, ConfidenceConfig(
    omega=1.0, adaptive_noise=False, q_growth=0.0))
xa = []
for z in zs:
    akf.predict()
    akf.update(None if np.isnan(z[0]) else z, 1.0)
    xa.append(akf.x)
assert np.abs(np.array(xa) - xs).max() < 1e-8
print("confidence filter with all observations trusted == standard filter")

# %% [markdown]
# **Sage–Husa (eq. 41)** with $d_k=(1-b)/(1-b^{k+1})$: $R_k=(1-d_k)R_{k-1}+d_k(e_ke_k^\top-HP_{k|k-1}H^\top)$.
# When the innovations are small compared with the predicted covariance the bracket is
# negative definite and the estimate of R loses positive definiteness. Run on accurate
# centroids (σ = 0.05 px) with a generous prior P: without the safeguard R becomes indefinite
# within a few steps; our safeguard symmetrises R and clips its eigenvalues to
# `ConfidenceConfig.r_bounds`, and projects Q back onto the Singer structure
# (a bounded q_a).

# %%
zs2 = np.c_[10 * np.sin(0.7 * tt), 5 * np.cos(0.5 * tt)] + g.normal(0, 0.05, (300, 2))
out = {}
for safe in (False, True):
    x, P, Rk, Qk = x0.copy(), P0.copy(), Rm.copy(), Q.copy()
    min_eig = []
    for k, z in enumerate(zs2[:60]):
        P_prev = P
        x, P = F @ x, F @ P @ F.T + Qk
        S = H @ P @ H.T + Rk
        K = P @ H.T @ np.linalg.inv(S)
        e = z - H @ x
        P_prior = P
        x, P = x + K @ e, (np.eye(6) - K @ H) @ P
        Rk, Qk = sage_husa_update(Rk, Qk, e=e, K=K, H=H, F=F, P_prior=P_prior, P_post=P,
                                  P_prev=P_prev, d=sage_husa_weight(k, 0.97), safeguard=safe,
                                  q_structure=np.diag(Q) > 0, q_bounds=(0.25 * Q[4, 4],
                                                                        100 * Q[4, 4]))
        min_eig.append(np.linalg.eigvalsh(Rk)[0])
    out["with safeguard" if safe else "without safeguard"] = np.array(min_eig)
first_bad = int(np.argmax(out["without safeguard"] <= 0))
print(f"without safeguard: R indefinite from step {first_bad}; with safeguard min eigenvalue "
      f"{out['with safeguard'].min():.3f} px²")
assert out["without safeguard"].min() < 0 and out["with safeguard"].min() > 0
fig, ax = plt.subplots(figsize=(6.4, 3.0))
for k, vv in out.items():
    ax.plot(vv, label=k)
ax.axhline(0, color="k", lw=0.8)
ax.set_xlabel("step")
ax.set_ylabel("smallest eigenvalue of R (px²)")
ax.set_title("Sage–Husa R estimate: the failure and the safeguard")
ax.legend()
plt.show()

# %% [markdown]
# **Confidence gating (eqs. 42–46).** $C_k=\omega C_{img}+(1-\omega)C_{motion}$,
# $C_{motion}=\exp(-\eta\max(0,D_M-\gamma))$, $D_M=\sqrt{e^\top S^{-1}e}$,
# $\hat C_k=0.9\hat C_{k-1}+0.1C_k$, $\tau_h=0.85\hat C_k$, $\tau_l=0.35\hat C_k$. Modes:
# $C_k\ge\tau_h$ update (and a Sage–Husa step); $\tau_l\le C_k<\tau_h$ update with $\lambda R$;
# otherwise predict only, with Q multiplied by $1+0.5\,n_{missed}$ (≤ 20) while the star stays
# hidden (the tracking driver also holds the last position after 5 missed frames — our track
# maintenance, applied to every variant). **$C_{img}$ is not defined by the paper**; ours is
# $C_{img}=\big(1-e^{-(SNR/8)^2}\big)\exp\!\big(-\ln^2(F/F_{ref})/(2\cdot0.7^2)\big)$ — a faint
# spot, or one much dimmer (translucent cloud) or brighter (glare, a neighbour) than the
# designated star's reference flux, is trusted less. Our defaults: ω = 0.5, η = 1, γ = 5,
# λ = 10, b = 0.97 (γ = 5 rather than the 99 % χ² gate γ = 3: see the sensitivity study in
# section 9 — this choice was made after seeing it, and is reported as such). One cloud
# sequence, BEAK-ST:

# %%
seq_c = simulate_sequence(np.random.default_rng(2), "cloud", n_frames=N_FRAMES)
tr = A.track_sequence(seq_c, cfg, np.random.default_rng(2))["BEAK-ST"]
e_c = np.hypot(*(tr.xs[:, :2] - seq_c.truth).T)
fig, axs = plt.subplots(2, 1, figsize=(7, 4.5), sharex=True)
axs[0].plot(seq_c.visible, label="cloud transmission at the star")
axs[0].plot(tr.confidence, ".", ms=3, label="C_k")
axs[0].scatter(np.arange(N_FRAMES), np.full(N_FRAMES, -0.1), c=tr.modes, cmap="viridis",
               marker="|", s=60)
axs[0].set_ylim(-0.2, 1.05)
axs[0].legend(fontsize=8)
axs[0].set_title("BEAK-ST through clouds (mode strip: update / inflated / predict)")
axs[1].semilogy(e_c + 1e-3)
axs[1].set_ylabel("error (px)")
axs[1].set_xlabel("frame")
plt.show()

# %% [markdown]
# ## 5 · Tables 1–2 and Figs. 6–7
#
# Four variants: **Baseline** (global threshold + standard KF), **BEAK-ST-GT** (global +
# confidence AKF), **BEAK-ST-SKF** (adaptive + standard KF), **BEAK-ST** (adaptive +
# confidence AKF); every filter starts from the designated star (0.3 px error) with the same
# Singer q_a (sea state 3) and R = 0.25 px². ε = 2 px (the paper does not give it). Here
# `N_SEEDS` sequences per scenario; `make repro` uses 20.

# %%
def side_by_side(ours, key, digits):
    return A._side_by_side(ours, A._paper_table(claims[f"akf_star.{key}"],
                                                 "mean_error_px" if key == "table1"
                                                 else "success_rate"), digits)


print("Table 1 — mean tracking error (px), paper vs ours")
side_by_side(res.mean_error(), "table1", 2)

# %%
print(f"Table 2 — success rate (e ≤ {cfg.epsilon_px:g} px), paper vs ours")
side_by_side(res.success_rate(), "table2", 3)

# %%
print(f"Continuity (estimate within {cfg.gate_px:g} px), median error (px) and lost tracks")
pd.concat({"continuity": res.continuity(), "median error": res.median_error(),
           "lost tracks": res.lost_fraction()}, axis=1)

# %%
fig, axs = plt.subplots(1, 2, figsize=(12, 4))
A.plot_error_curves(res, ax=axs[0])
A.plot_success_curves(res, ax=axs[1])
plt.show()

# %% [markdown]
# ## 6 · Scorecard

# %%
card[["claim", "status", "ours", "note"]]

# %% [markdown]
# **Reading.** The adaptive threshold is what matters most on our sequences: under strong
# light and stray light the global μ + kσ threshold, inflated by the sky gradient or the glare,
# loses the star almost always, while the adaptive method keeps it (errors of a few tenths of a
# pixel). The confidence AKF pays off under sway, where its Sage–Husa q_a adapts to a rougher
# sea than the filter was initialised for, and it helps a little under cloud. At low SNR it
# brings nothing: with faint, often missing centroids its confidence is low and its adapted
# noise noisy — in the 20-seed run (`make repro`, `papers_repro/akf_star/REPORT.md`) BEAK-ST
# loses the star in a few low-SNR sequences and ends behind BEAK-ST-SKF there.
# It is also *fragile*: when the constant-acceleration prediction lags a sway peak the
# motion-consistency term treats the genuine star as an outlier, the λR update widens the lag
# and the star can leave the gate; the γ sensitivity in section 9 shows how close to this edge
# the filter works. Compare mean and median errors and the *lost tracks* table. Our absolute errors are far below the paper's (a few tenths of a
# pixel against 1.6–3.9 px) because our centroids are accurate and our success threshold is
# ε = 2 px; the paper's OTB100 data and ε are unknown.

# %% [markdown]
# ## 7 · Explore
#
# Static figure with the default parameters (cloud scenario, one sequence), then the
# interactive version: scenario, forgetting factor b, λ, η, γ, ω, the thresholds k and k_b and
# the occlusion length.

# %%
def explore(scenario_name="cloud", b=0.97, lam=10.0, eta=1.0, gamma=5.0, omega=0.5, k=4.0,
            k_b=3.0, occlusion_frames=10, seed=0):
    """Track one sequence with BEAK-ST and Baseline and plot their errors."""
    sc = scenario(scenario_name, occlusion_frames=int(occlusion_frames))
    c = A.AblationConfig(confidence=ConfidenceConfig(forgetting=b, lam=lam, eta=eta,
                                                     gamma=gamma, omega=omega),
                         extraction=ExtractionConfig(k=k, k_b=k_b))
    s = simulate_sequence(np.random.default_rng(seed), sc, n_frames=N_FRAMES)
    out_ = A.track_sequence(s, c, np.random.default_rng(seed))
    fig_, ax_ = plt.subplots(figsize=(7, 3.2))
    for name, r in out_.items():
        ax_.semilogy(np.hypot(*(r.xs[:, :2] - s.truth).T) + 1e-3, label=name, lw=0.9)
    ax_.set_xlabel("frame")
    ax_.set_ylabel("error (px)")
    ax_.set_title(f"{scenario_name}: tracking error of the four variants")
    ax_.legend(fontsize=8)
    return fig_


explore()
plt.show()

# %% tags=["nbval-ignore-output"]
from ipywidgets import FloatSlider, IntSlider, interact


def _slider(cls, v, lo, hi, step):
    return cls(value=v, min=lo, max=hi, step=step, continuous_update=False)


interact(lambda **kw: (explore(**kw), plt.show()), scenario_name=list(SCENARIOS),
         b=_slider(FloatSlider, 0.97, 0.9, 0.999, 0.005),
         lam=_slider(FloatSlider, 10, 1, 100, 1), eta=_slider(FloatSlider, 1, 0, 5, 0.1),
         gamma=_slider(FloatSlider, 5, 0, 10, 0.5), omega=_slider(FloatSlider, 0.5, 0, 1, 0.05),
         k=_slider(FloatSlider, 4, 2, 6, 0.5), k_b=_slider(FloatSlider, 3, 1, 6, 0.5),
         occlusion_frames=_slider(IntSlider, 10, 2, 60, 1), seed=_slider(IntSlider, 0, 0, 20, 1))

# %% [markdown]
# ## 8 · Errata and deviations
#
# | where | paper | adopted |
# |---|---|---|
# | eq. (2) | $R_x(\varphi)R_y(\theta)$ | $R_y(\varphi)R_x(\theta)$ (the text's pitch-then-roll; difference is second order) |
# | eq. (5) | azimuth about Y (the optical axis); small-angle matrix = transpose of the product | azimuth about the vertical: $R_x(\alpha)R_z(-\beta)$ |
# | eq. (10) | Z as the optical axis | Y′ is the optical axis (Fig. 3); eq. (10) checked in its own convention |
# | eq. (12) | Earth term $-f\omega_e\sin A\cos h$, $-f\omega_e\cos A\cos h$, no latitude | the diurnal rates above (checked against astropy: < 1 % vs ≈ tens of % error) |
# | eq. (21)–(22) | σ_f called a variance; $T_f\ge I_f$ | standard deviation; $I_f\ge T_f$ |
# | eqs. (28)–(29) | weights I | weights $I-B$ (background-subtracted); the region ℜ_k as in the paper (optionally grown, section 9) |
# | eq. (31) | adds the noise sample to the prediction | prediction uses the mean; noise enters through Q |
# | eq. (41) | $d_k = 1-b/1-b^k$ | $d_k=(1-b)/(1-b^{k+1})$; safeguard: R eigenvalues clipped to [0.01, 1] px², Q projected on the Singer structure with q_a ∈ [1, 16]·q_a,0 (never below the sea-state prior, at most about two sea states rougher) |
# | eq. (42) | $C_{img}$ undefined | SNR × flux consistency (section 4.6) |
# | eq. (46) | "Q increased" during occlusion, no law | Q × (1 + 0.5 n_missed), at most × 20; Ĉ held while no star is seen |
# | §2 | OTB100 frames | simulated real-sky ship sequences (128×128 px, 10°, 5 Hz) |
# | §1.4 | no track maintenance after a loss | after 5 frames (1 s) without a measurement the velocity and acceleration are zeroed (hold the last position) so the star can be re-acquired; the same for every variant |
# | §2 | ε, ω, η, γ, λ, b, k, k_b, r, σ_b not given | ε = 2 px, ω = 0.5, η = 1, γ = 5, λ = 10, b = 0.97, k = 4, k_b = 3, r = 7, σ_b = 6 px; association gate min(30 px, max(10 px, 4σ)) |
# | abstract | 40 % error reduction, continuity > 95 % | Table 1 gives 52 %; no Table 2 rate reaches 0.95; continuity defined as "estimate within the gate" |
#
# **Choices made after looking at results** (none towards the paper's numbers, all towards a
# filter that does not lose the star for avoidable reasons): the R upper bound of 1 px² (at
# 25 px² the Sage–Husa R absorbed the prediction lag under sway and BEAK-ST diverged in most
# sway sequences); the q_a floor at the sea-state prior (a lower floor let q_a shrink in calm
# stretches and made the filter over-confident before the next sway peak) and its ceiling of
# 16× (at 100× the estimate, driven by centroid noise at low SNR, grew so large that a few
# frames of prediction threw the estimate tens of pixels away); the 30 px cap of the
# association gate (with 60 px a coasting track grabbed a neighbour star 58 px away); holding
# the position after 5 missed frames (without it the constant-acceleration extrapolation ran
# away to hundreds or thousands of pixels); γ = 5 instead of 3 (section 9). The scenario presets (sky levels, cloud sizes, 10-frame occlusions, sea state 5,
# glare strength, haze) were set so that each scenario stresses its part of the pipeline; with
# 25-frame occlusions every variant loses the star behind the clouds (try it in *Explore*).

# %% [markdown]
# ## 9 · Beyond the paper
#
# **A constant-velocity KF and NEES/NIS.** On sway sequences (adaptive extraction) we compare
# the standard CA filter, a CV filter and BEAK-ST. NEES uses the position block of P against
# the true position (2 degrees of freedom, mean 2 if consistent); NIS the innovations
# (mean 2).

# %%
variants_b = {"CA KF": ("adaptive", "kf"), "CV KF": ("adaptive", "cv"),
              "BEAK-ST": ("adaptive", "akf")}
rows_b = []
for sc_name in ("sway", "cloud", "low_snr"):
    for seed in range(2):
        s = simulate_sequence(np.random.default_rng(100 + seed), sc_name, n_frames=N_FRAMES)
        out_b = A.track_sequence(s, cfg, np.random.default_rng(seed), variants=variants_b)
        for name, r in out_b.items():
            err_b = r.xs[:, :2] - s.truth
            ne = nees(err_b, r.Ps[:, :2, :2])
            ni = nis(r.innovations, r.S)
            rows_b.append({"scenario": sc_name, "filter": name,
                           "mean error (px)": np.hypot(*err_b.T).mean(),
                           "mean NEES": np.nanmean(ne), "mean NIS": np.nanmean(ni)})
beyond = pd.DataFrame(rows_b).groupby(["scenario", "filter"]).mean()
beyond

# %% [markdown]
# **Sensitivity of BEAK-ST in a rough sea** (sea state 5, 6 sequences): the Mahalanobis
# tolerance γ, the Sage–Husa adaptation and ω. "lost" is the fraction of sequences whose final
# estimate is more than 10 px from the star.

# %%
seqs_s = [simulate_sequence(np.random.default_rng(200 + i), "sway", n_frames=N_FRAMES)
          for i in range(6)]
rows_s = []
for label, cc in [("γ = 5 (default)", ConfidenceConfig()),
                  ("γ = 3", ConfidenceConfig(gamma=3.0)),
                  ("no Sage–Husa", ConfidenceConfig(adaptive_noise=False)),
                  ("ω = 0.8", ConfidenceConfig(omega=0.8)),
                  ("b = 0.95", ConfidenceConfig(forgetting=0.95))]:
    c_s = A.AblationConfig(confidence=cc)
    errs_s = np.array([np.hypot(*(A.track_sequence(q, c_s, np.random.default_rng(i),
                                                   variants={"b": ("adaptive", "akf")})["b"]
                                  .xs[:, :2] - q.truth).T) for i, q in enumerate(seqs_s)])
    rows_s.append({"setting": label, "lost": np.mean(errs_s[:, -1] > 10),
                   "median error (px)": np.median(errs_s),
                   "success (ε = 2 px)": np.mean(errs_s <= 2)})
sens = pd.DataFrame(rows_s).set_index("setting")
sens

# %% [markdown]
# A consistent filter has mean NEES and NIS near 2. Values far above 2 mean the filter is
# over-confident (its covariance is too small for its actual errors) — the signature of the
# model mismatch (constant acceleration against oscillating sway) discussed above; values far
# below 2 mean it is too cautious. The standard CA filter initialised for sea state 3 is
# over-confident in the sea-state-5 sway (NEES ≈ 6, NIS ≈ 11); the adaptive q_a of BEAK-ST
# brings both near 2 there. A plain constant-velocity filter with a generous white-acceleration
# density (`AblationConfig.cv_q`) is very cautious (NEES ≪ 2) and, precisely because it follows
# the measurements closely, has the smallest errors with bright stars — but it loses the star
# at low SNR, where following every faint centroid is the wrong thing to do. The extra
# structure of the paper's filter pays off only where measurements are unreliable.

# %% [markdown]
# **Centroid accuracy of the thresholded centre of gravity.** Eqs. (28)–(29) weight only the
# pixels above the local threshold, so the PSF wings are cut and the centroid is pulled towards
# the brightest pixel ("pixel locking"). Growing each region by two pixels before weighting
# (`ExtractionConfig(centroid_grow=2)`, not the paper's method) removes most of that bias — on
# the nominal sequence:

# %%
seq_n = simulate_sequence(np.random.default_rng(7), "nominal", n_frames=60)
cent = {}
for grow in (0, 2):
    c_e = ExtractionConfig(centroid_grow=grow)
    d_e = [np.hypot(*(extract_stars(im, config=c_e).xy - t).T).min()
           for im, t in zip(seq_n.images, seq_n.truth)]
    cent[f"centroid_grow={grow}"] = {"median error (px)": np.median(d_e),
                                     "90th percentile (px)": np.percentile(d_e, 90)}
pd.DataFrame(cent).T

# %% [markdown]
# **FilterPy cross-check** is in section 4.6 (identical estimates to 1e-8). The benchmark
# `benchmarks/bench_akf_star.py` times one filter step against FilterPy, the batched filter,
# and our extraction against SEP.
