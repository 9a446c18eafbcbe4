# ---
# jupyter:
#   kernelspec:
#     display_name: Python 3 (ipykernel)
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 04 · Track initiation for electro-optical tracking of space objects: logic, classic Hough and modified Hough
#
# **Paper.** Xu Zhanwei, Wang Xin. *Track initiation in electro-optical tracking of space
# objects* (空间目标光电跟踪中的航迹起始方法). Acta Astronomica Sinica **57**(2):211–218, 2016 [1],
# after the modified Hough of Lo et al. [9]. Baselines: the logic *n/m* rule [2], the
# angle-constrained logic [3], the classic Hough transform [4, 5].
#
# **What the paper does.** After star removal a frame still holds *candidates*: moving objects
# and missed stars. Track *initiation* decides which candidates of different frames are one
# object. Over a few seconds a space object moves on a straight line at constant speed, so Xu &
# Wang let *pairs* of candidates (inside a velocity gate) vote for line, speed and direction
# (ρ, θ, v, s); a cell with detections of m − 1 of the last m frames is a track (3/4 rule).
# Their 4-frame experiment finds all five objects and nothing else.
#
# **What this notebook adds.** The lost Tables 1–2 rebuilt as assumptions, the paper's
# procedure run literally, and an improved initiator (a χ² test at the noise, best fit first)
# judged on random scenes by recall, GOSPA, SIAP and the rule's analytic chance rate.
#
# ## Learning objectives
#
# After this notebook you can
#
# 1. compute a pair's Hough parameters (ρ, θ, v, s) and say how noise spreads its votes;
# 2. run the paper's voting and the logic *n/m* rule frame by frame;
# 3. replace cell counting by a χ² test and derive the **chance rate** of a 3-of-4 rule;
# 4. judge an initiator by recall, false tracks, GOSPA and SIAP on untuned scenes;
# 5. say when the angle constraint can act.
#
# **Prerequisites.** Least-squares line fits; the χ² distribution; uniform (Poisson) clutter.
#
# **Scorecard** (from `make repro`; recomputed in section 6):

# %%
import json

from eotrack.notebook import lesson_header
from eotrack.repro import papers_repro_dir
from IPython.display import Markdown, display

lesson_header("04")
_card = json.loads((papers_repro_dir() / "track_init_hough" / "scorecard.json").read_text())
display(Markdown(f"**{_card['summary']}** — " + "; ".join(
    f"`{c['claim']}`: {c['status']}" for c in _card["claims"])))

# %% [markdown]
# ## 2 · Setup

# %%
import math
from dataclasses import replace

import cv2
import numpy as np
import pandas as pd
from eotrack.exercises import check
from eotrack.experiments import track_init_hough as TH
from eotrack.montecarlo import TrialRunner
from eotrack.notebook import dropdown, panel, setup_notebook, toggle, versions
from eotrack.repro import load_claims, scorecard
from eotrack.tracking.initiation import (
    ModifiedHoughInitiator,
    cv_fit_batch,
    gated_pairs,
    hough_accumulator,
    logic_false_track_rate,
    pair_parameters,
)
from scipy.stats import chi2

setup_notebook()

# %% tags=["parameters"]
QUICK = False  # False: the counts of `make repro`; True: the test suite's (a few seconds each)
N = TH.trial_counts(quick=QUICK)  # every Monte Carlo below takes its count from N
N

# %%
versions()

# %%
claims = load_claims(TH.SLUG)
cfg = TH.xu_config()  # the paper's settings, read from claims.toml
comp_cfg = TH.ComparisonConfig()
pl_cfg = TH.PlantedConfig()
runner = TrialRunner(progress=False)
{k: v for k, v in cfg.__dict__.items() if k != "targets"}

# %% [markdown]
# ## 3 · Notation
#
# | paper | meaning | code | unit |
# |---|---|---|---|
# | $(x, y)$ | image position (x = column, y = row) | `xy[:, 0]`, `xy[:, 1]` | px |
# | $\rho, \theta$ | image line $\rho = x\cos\theta + y\sin\theta$, eq. (1), θ ∈ [0°, 180°) | `rho_px`, `theta_deg` | px, ° |
# | $v, s$ | speed and direction along the line (+ = along $(\sin\theta, -\cos\theta)$) | `speed_px_s`, `s` | px/s, ±1 |
# | $\delta\rho, \delta\theta, \delta v$ | cell sizes | `d_rho`, `d_theta_deg`, `d_v` | px, °, px/s |
# | $[v_{min}, v_{max}]$ | velocity gate (lost formula) | `v_min`, `v_max` | px/s |
# | $m$, $(m-1)/m$ | window and confirmation rule (3/4) | `m` | frames |
# | $O_k$ | candidates of frame k | `frames[k][1]` | – |
# | $S_{kj}, S_{ki}$ | cells voted by the pairs (k, k−1), (k, k−2) | – | – |
# | $P(t), Q(t)$ | votes and point set of cell t | vote mask, stored pairs | – |
# | $\sigma$ | centroid noise per axis (ours) | `sigma_px` | px |
# | $\alpha$ | false-rejection probability of the χ² test (ours) | `alpha` | – |
# | $\lambda$ | non-object detections per frame (clutter + residual stars) | `clutter_per_frame` (clutter only) plus the stars seen | 1/frame |
# | $N_f$ | detections of frame f (§4.6) | `len(xy)` | – |
# | $A$ | field area $L^2$ | `width_px**2` | px² |
# | $n/m$, $r$ | logic rule and its prediction gate | `LogicInitiator(n, m, gate_px=r)` | –, px |

# %% [markdown]
# ## 4 · The method, step by step
#
# ### 4.1 The line of a pair, eq. (1)
#
# A pair of candidates — `a` in an earlier frame, `b` in frame k — defines the image line through
# both: its normal angle θ ∈ [0°, 180°) is the pair's direction plus 90°, and
#
# $$\rho = x\cos\theta + y\sin\theta. \tag{1}$$
#
# The speed is $v = |b - a| / (t_b - t_a)$ with the *real* time difference (frames need not be
# evenly spaced), and $s = \pm 1$ says which way along the line the object moves. Check: both
# points satisfy eq. (1), and the reverse motion has the same line and the opposite s.

# %%
a, b = np.array([[120.0, 300.0]]), np.array([[161.0, 328.5]])
rho, theta, v, s = (x[0] for x in pair_parameters(a, b, 1.0))
for p in (a[0], b[0]):
    assert abs(p[0] * math.cos(theta) + p[1] * math.sin(theta) - rho) < 1e-9
assert abs(v - np.hypot(*(b - a)[0])) < 1e-12 and s == 1
assert pair_parameters(b, a, 1.0)[3][0] == -1
print(f"ρ = {rho:.3f} px, θ = {math.degrees(theta):.3f}°, v = {v:.3f} px/s, s = {s:+d}")

# %% [markdown]
# ### 4.2 The velocity gate
#
# The gate's formula is lost in our source (numbering uncertain, see Errata); its sense is
# clear: only pairs with
#
# $$v_{min} \le \frac{|b - a|}{t_b - t_a} \le v_{max}$$
#
# vote. A static star never pairs with itself (v ≈ 0); pairs of *different* stars can pass.
# Check: `gated_pairs` (one broadcast) gives the pairs of a double loop.

# %%
rng = np.random.default_rng(1)
A, B = rng.uniform(0, 512, (40, 2)), rng.uniform(0, 512, (35, 2))
ia, ib, _, _ = gated_pairs(A, B, 2.0, *cfg.v_gate_px_s)
brute = {(i, j) for i in range(len(A)) for j in range(len(B))
         if cfg.v_gate_px_s[0] <= np.hypot(*(B[j] - A[i])) / 2.0 <= cfg.v_gate_px_s[1]}
assert brute == set(zip(ia.tolist(), ib.tolist()))
display(Markdown(f"{len(brute)} of {len(A) * len(B)} pairs pass the gate at Δt = 2 s: with "
                 f"$v_{{max}}$ = {cfg.v_gate_px_s[1]:g} px/s the gate covers most of a "
                 f"{cfg.width_px} px image."))

# %% [markdown]
# ### 4.3 Voting, eq. (8), and the (m − 1)/m rule — one trial by hand
#
# At frame k every candidate of $O_k$ is paired with every candidate of $O_j$ ($j = k-1$) and
# $O_i$ ($i = k-2$); the gated pairs give the cell sets $S_{kj}$, $S_{ki}$, and the pairs are
# stored in the point-set matrix $Q$ (eq. 7; eq. 9 expires what frame $k-m+1$ contributed —
# the original's step list: "根据(7)式和(8)式更新矩阵P、Q", "根据(9)式更新矩阵P、Q"). The votes are
#
# $$P(t) \leftarrow P(t) + 1 \quad \text{for } t \in S_{kj} \cup S_{ki}, \tag{8}$$
#
# a *set*: a frame adds at most one vote per cell; a cell is confirmed when $P(t) = m - 1$.
# Read literally, "+1 per current frame" gives the object seen in all four frames 3 votes only
# at frame 4, but the paper confirms it at frame 3 — what one gets when $P(t)$ counts the
# **frames whose detections are in $Q(t)$** (our reading, Errata). Check on a noise-free
# 5-object scene like the paper's: confirmations per frame 0, 0, 1, 4, as the paper says.

# %%
planted = [((60.0, 420.0), (35.0, -22.0), (0, 1, 2, 3)), ((80.0, 80.0), (40.0, 30.0), (0, 1, 3)),
           ((450.0, 100.0), (-25.0, 45.0), (0, 2, 3)), ((100.0, 300.0), (60.0, 0.0), (1, 2, 3)),
           ((60.0, 300.0), (40.0, 0.0), (1, 2, 3))]
clean = [(float(k), np.array([np.add(p, np.multiply(v_, k)) for p, v_, fs in planted if k in fs]))
         for k in range(4)]
paper_mh = ModifiedHoughInitiator(literal=True)  # the paper's procedure and cells
run = paper_mh.run(clean, log=True)
assert [e["confirmed"] for e in run.log] == [0, 0, 1, 4]
pd.DataFrame(run.log)[["frame", "candidates", "pairs", "created", "tentative", "confirmed"]]

# %% [markdown]
# **The other equations of §3**, lost in our source, rebuilt from the text:
#
# * cells $\rho_n = \lfloor \rho/\delta\rho \rfloor$, $\theta_n = \lfloor \theta/\delta\theta \rfloor$,
#   $v_n = \lfloor v/\delta v \rfloor$, $s \in \{+, -\}$;
# * the pair's line: $\Delta = b - a$, $(\cos\theta, \sin\theta) = \pm(-\Delta_y, \Delta_x)/|\Delta|$
#   with $\theta \in [0, \pi)$, ρ from eq. (1), $s = \operatorname{sign}(\Delta\cdot(\sin\theta, -\cos\theta))$;
# * $Q(t) \leftarrow Q(t) \cup \{(a, b)\}$ for every gated pair of cell $t$; after extraction the
#   votes and pairs of frame $k - m + 1$ expire;
# * neighbour test (our reading): the least-squares line through $Q(t)$ within $1.5\,\delta\rho$
#   and $1.5\,\delta\theta$ of the cell $t'$, and $P(t) + P(t') = m - 1$.
#
# ### 4.4 Drawing the (ρ, θ) voting; the 6- and 26-neighbourhoods
#
# Noise spreads one object's pairs over neighbouring cells. For a cell with $P(t) < m - 1$ the
# paper looks in the **6-neighbourhood** (±1 cell in ρ, θ *or* v, same s) for a $t'$ as above.
# An object seen in three frames has two pairs in the window; if their cells differ in *two*
# of (ρ, θ, v) they are only 26-neighbours (±1 in any combination) and the object is lost.
#
# A pair's direction error $\sigma_\theta \approx \sqrt2\,\sigma/(v\,\Delta t)$ becomes a ρ
# error of up to $|r|\,\sigma_\theta$, $r$ the distance from the **origin of ρ** (up to 724 px
# from the corner, 362 px from the centre). The figure: every gated pair of the 4-frame scene
# (left), then track 2's pairs over the cell grid, ρ from the corner (middle) and the centre
# (right).

# %%
scene = TH.make_xu_scene(cfg)
fig = TH.plot_rho_theta_votes(scene, cfg, target=1)

# %% [markdown]
# ### 4.5 What the paper's rule leaves open, and our verified initiator
#
# Cell counting (i) counts frames without checking that the detections form *one*
# constant-velocity motion (two static stars 50 px apart fill one cell for three frames), (ii)
# tolerates a cell size, not the noise, and (iii) settles conflicts in cell order. Our
# **verified** initiator (`ModifiedHoughInitiator(literal=False)`, the library default) keeps
# the 3-of-4 rule and the velocity gate and replaces cell counting by a test:
#
# * the hits $x_i$ at times $t_i$ are fitted with $x(t) = \bar x + u\,(t - \bar t)$; the
#   track passes when
#   $$\chi^2 = \frac{1}{\sigma^2}\sum_i \lVert x_i - \bar x - u\,(t_i - \bar t)\rVert^2
#   \le \chi^2_{2(n-2)}(1-\alpha)$$
#   for $n$ hits, with $v_{min} \le |u| \le v_{max}$;
# * for three hits the residual is one contrast $w^\top x$ with $\sum w_i = 0$, $\sum w_i t_i = 0$,
#   i.e. $w \propto (t_2 - t_3,\; t_3 - t_1,\; t_1 - t_2)$, and $\chi^2 = (w^\top x)^2 /
#   (\lVert w\rVert^2\sigma^2)$: given two hits, the third must lie in a **disc** of radius
#   $\sigma\sqrt{c\,\chi^2_2(1-\alpha)}$ around their prediction, $c$ a function of the
#   times (Exercise 1);
# * the triplets ending at frame k, $(k-2, k-1, k)$, $(k-3, k-2, k)$, $(k-3, k-1, k)$, are
#   extended to the window's fourth frame when it fits, ranked (more hits, then p-value) and
#   accepted best first, each detection in one track;
# * the default also searches **four-hit constant-acceleration** tracks over frames k−3…k
#   (`accel_px_s2 = 3.0`, quadratic fit, χ² with 2 d.o.f.) in the same ranking. Every "ours"
#   number of §5–§7 uses this default; §4.6's formula and its check describe the rule with the
#   search off (`accel_px_s2 = 0`);
# * on a clutter burst or accelerating tracks the default switches to a batch **growth
#   engine** (Beyond, held-out family); on the paper's scenes it does not fire, so their "ours"
#   tracks are the causal engine's — not their time: on uncrowded frames the default also runs
#   the growth engine to look for accelerating tracks in its result.
#
# The gate defaults (`v_max` = 240 px/s) are the paper's 512 px scale; a wider field needs a
# wider gate.
#
# The disc *is* the test. Check by hand on one triplet, then with the library's batch fit:

# %%
t3 = np.array([0.0, 1.0, 3.0])
w = np.array([t3[1] - t3[2], t3[2] - t3[0], t3[0] - t3[1]])
x3 = np.array([[100.0, 50.0], [130.2, 60.3], [189.8, 79.9]])  # three hits of one object
chi_contrast = np.sum((w @ x3) ** 2) / (w @ w) / cfg.sigma_px**2
_, _, _, rss = cv_fit_batch(t3[None], x3[None, :, 0], x3[None, :, 1], np.ones((1, 3), bool))
assert math.isclose(chi_contrast, rss[0] / cfg.sigma_px**2, rel_tol=1e-9)
thr = chi2.ppf(1 - pl_cfg.alpha, 2)
assert chi_contrast <= thr  # the object's triplet passes
display(Markdown(f"χ² = {chi_contrast:.2f} (threshold {thr:.2f} at α = {pl_cfg.alpha:g})."))

# %% [markdown]
# One trial by hand with the verified initiator on the rebuilt scene (its per-frame log is
# our Table 2 for it): triplets found in the χ² discs, candidate tracks passing the full test,
# conflicts lost, tracks confirmed.

# %%
ours_mh = ModifiedHoughInitiator(sigma_px=cfg.sigma_px)
run = ours_mh.run(scene.frames, log=True)
print("object → confirmation frame index:", TH.score_tracks(run.tracks, scene)["confirm_frame"])
pd.DataFrame(run.log).astype(object).fillna("–")

# %% [markdown]
# ### 4.6 The chance rate of the 3-of-4 rule
#
# How many false tracks must any initiator applying this test make? Let the non-object
# detections be uniform in the field of area $A$, $N_f$ in frame f. Three of them, in frames
# $t_1 < t_2 < t_3$, pass when the outer two are a gated distance apart and the middle one falls
# in its disc:
#
# $$P_3(t_1,t_2,t_3) = D(t_3 - t_1)\;\frac{\pi\,\chi^2_2(1-\alpha)\,\sigma^2\,c}{A},\qquad
#   c = 1 + \tau^2 + (1-\tau)^2,\quad \tau = \frac{t_2 - t_1}{t_3 - t_1},$$
#
# with $D(T)$ the probability that two uniform points of the square are between $v_{min}T$ and
# $v_{max}T$ apart (closed form, `distance_cdf_square`). Summing $N_{f_1}N_{f_2}N_{f_3}\,P_3$
# over the triplet shapes of every frame (`triplet_shapes`) gives the expected number of
# passing triples, an upper bound. `chi2_chance_tracks` corrects it three ways: a residual star
# cannot pair with itself (inclusion–exclusion); passing triples of one frame that share a
# detection are confirmed once (**conflicts**: with $E_f$ the expected passing triples ending
# at frame k that use frame f and $N_f$ its depleted count, $\sum_f E_f^2/2N_f$ fewer tracks,
# capped at half of frame k's triples); and a confirmed chance track uses up its detections
# (**depletion**, frame by frame, mean-field). Without the conflict term the count is too high
# (§5 checks it on clutter-only scenes). The conflict term was added after that check had been
# seen, and it is validated only on the densities of that check (§5); at higher densities it
# over-corrects (independent review, issue 27), so do not use it beyond them. Check $P_3$
# against brute force (the tolerance is about 3 standard errors of the pass count, printed):

# %%
rng = np.random.default_rng(0)
n_mc, L, sig_big = 400_000, 100.0, 2.0
pts = rng.uniform(0, L, (n_mc, 3, 2))
_, _, u_fit, rss = cv_fit_batch(np.broadcast_to(t3, (n_mc, 3)), pts[..., 0], pts[..., 1],
                                np.ones((n_mc, 3), bool))
speed = np.hypot(*u_fit.T)
passed = (rss / sig_big**2 <= chi2.ppf(0.99, 2)) & (speed >= 3) & (speed <= 20)
p_formula = TH.triplet_chance_probability(*t3, width=L, v_min=3, v_max=20, sigma_px=sig_big,
                                          alpha=0.01)
assert abs(passed.mean() / p_formula - 1) < 0.05
display(Markdown(f"$P_3$: formula {p_formula:.3g}, brute force {passed.mean():.3g} "
                 f"({n_mc} random triples, {int(passed.sum())} pass: 5 % is "
                 f"{0.05 * math.sqrt(passed.sum()):.1f} standard errors)."))

# %% [markdown]
# ### 4.7 The logic n/m rule and the angle constraint
#
# Every candidate opens a *head*, paired with every gated candidate of a later frame of its
# window; a tentative track takes the nearest candidate within $r$ of its constant-velocity
# prediction and is confirmed with n detections in m frames. The **angle-constrained** variant
# [3] also rejects a point whose angle at the middle of the last three is ≤ 90°. With $r$ =
# 10 px and $v_{min}$ = 10 px/s the prediction lies ≥ 10 px ahead of the last point, so no
# point of the gate makes an angle ≤ 90°: the constraint acts only when $r > v_{min}\Delta t$.
# *Our approximation* (not validated; Beyond compares it with the measurement) of the logic
# rule's chance rate in uniform clutter is
#
# $$ R = N_c \sum_{\Delta=1}^{m-1} N_c\, p_\Delta \;
#   \Pr\Big[\sum_{j=1}^{m-1-\Delta} B_j \ge n-2\Big],\qquad
#   B_j \sim \mathrm{Bernoulli}\big(q_{\Delta j}\,(1-e^{-N_c \pi r^2/A})\big), $$
#
# with $p_\Delta = D(\Delta)$ and $q_{\Delta j}$ the probability that the prediction stays in the
# field. Check: the 2/3 special case $R = N_c^2(p_1 + p_2)$.

# %%
pp = [float(TH.distance_cdf_square(240 * g, 512) - TH.distance_cdf_square(10 * g, 512))
      for g in (1, 2, 3)]
assert math.isclose(logic_false_track_rate(2, 3, 3.0, pp, 0.001), 9 * (pp[0] + pp[1]))
print("p_Δ for Δ = 1, 2, 3:", np.round(pp, 4))

# %% [markdown]
# ### 4.8 The classic Hough accumulator
#
# Every point of a batch of frames votes once per θ column in the cell of
# $\rho = x\cos\theta + y\sin\theta$ [4]; a peak of n votes from n distinct frames is a track.
# It knows nothing of time or speed. Check against OpenCV's `HoughLinesPointSet` [5]. The two
# follow different conventions: ours samples θ at column centres $(i + \frac12)\delta\theta$ and
# reports a ρ bin by its centre; OpenCV samples θ at $i\,\delta\theta$ and reports a ρ bin by its
# lower edge. So on this line the printed θ differ by −½ bin and ρ by +½ bin; the assert pins
# these reporting conventions. The bins themselves are compared with OpenCV's bin for bin by the
# unit test `test_accumulator_equals_opencv_bin_for_bin` (a half-bin shift of the ρ bins that
# keeps the reported centres passes this cell but fails that test).

# %%
line = np.array([[x, 2 * x / 3 + 5] for x in range(0, 60, 3)], float)
acc = hough_accumulator(line, d_rho=1.0, d_theta_deg=1.0, rho_max=100.0)
r_pk, t_pk, votes = acc.peak()
cv_best = cv2.HoughLinesPointSet(line.astype(np.float32).reshape(-1, 1, 2), 1, 3, -100, 100,
                                 1.0, 0.0, math.pi, math.radians(1.0)).reshape(-1, 3)[0]
assert votes == int(cv_best[0])
assert math.isclose(math.degrees(t_pk - cv_best[2]), -0.5, abs_tol=1e-4)  # half a 1° column
assert math.isclose(r_pk - cv_best[1], 0.5, abs_tol=1e-6)  # half a 1 px bin
print(f"ours: ρ = {r_pk:.1f} px, θ = {math.degrees(t_pk):.1f}°, {votes} votes | OpenCV: "
      f"ρ = {cv_best[1]:.1f}, θ = {math.degrees(cv_best[2]):.1f}°, {int(cv_best[0])} votes")

# %% [markdown]
# ## 5 · Reproduction
#
# ### Table 1 — the planted objects (ours: the paper's numbers are lost)
#
# A stated assumption, not a result: five constant-velocity objects satisfying the text (one in
# all frames, two missing frame 3 and frame 2, two nearly overlapping ones missing frame 1);
# positions at the first frame's time.

# %%
pd.DataFrame([{"track": i + 1, "name": t.name, "x0 (px)": t.xy0_px[0], "y0 (px)": t.xy0_px[1],
               "vx (px/s)": t.v_px_s[0], "vy (px/s)": t.v_px_s[1],
               "frames seen": ",".join(str(f + 1) for f in t.frames)}
              for i, t in enumerate(cfg.targets)])

# %% [markdown]
# ### Fig. 2 — the candidates of the four frames
#
# Gaia DR3 stars around RA 100°, Dec 0°, projected onto the 512 px, 0.7° field; the telescope
# tracks the stars, and star removal leaves each in a frame with probability
# `residual_fraction` (our assumption).

# %%
ax = TH.plot_xu_frames(scene)

# %% [markdown]
# ### Table 2 — per-frame log (the paper's counts are lost)
#
# What the text keeps are the confirmation frames (claims.toml); the counts are ours, with the
# paper's literal procedure (6- and 26-neighbourhood) and with our verified initiator. They are
# counted after the hand-off: detections claimed by a confirmed track leave the candidate sets
# (so a frame can list fewer candidates than Fig. 2 shows).

# %%
t2 = {nb: TH.xu_table2(cfg, scene, nb) for nb in (6, 26)}
t2["ours"] = TH.xu_table2(cfg, scene, literal=False)
p2 = claims["track_init.xu_table2"].paper
want = {1: p2["confirm_frame_track1"], 2: p2["confirm_frame_track2"],
        3: p2["confirm_frame_track3"], 4: cfg.n_frames, 5: cfg.n_frames}
nominal = {}
for key, (_, tracks) in t2.items():
    nominal[key] = TH.score_tracks(tracks, scene, n=cfg.rule_m - 1, m=cfg.rule_m)
    nominal[key]["n_tracks"] = len(tracks)
frames_cmp = pd.DataFrame({"track": list(want), "paper (frame)": list(want.values())})
for key, name in ((6, "paper's rule, 6-nbhd"), (26, "26-nbhd"), ("ours", "ours")):
    got = {i + 1: f + 1 for i, f in nominal[key]["confirm_frame"].items()}
    frames_cmp[name] = [got.get(i, np.nan) for i in want]
    frames_cmp[f"Δ {name}"] = frames_cmp[name] - frames_cmp["paper (frame)"]
frames_cmp

# %%
t2[6][0]

# %%
t2["ours"][0]

# %%
# NBVAL_CHECK_OUTPUT
print("confirmed per frame, paper's procedure (6-nbhd):", t2[6][0]["tracks confirmed"].tolist())
print("confirmed per frame, 26-nbhd:", t2[26][0]["tracks confirmed"].tolist())
print("confirmed per frame, verified:", t2["ours"][0]["tracks confirmed"].tolist())
print("tracks found (6 / 26 / verified):", [nominal[key]["correct"] for key in (6, 26, "ours")])

# %% [markdown]
# ### Fig. 3 — the extracted tracks
#
# Left: the paper's procedure (6-neighbourhood); right: our verified initiator. Then the same on
# `N["redraws"]` redraws of the residual stars and the centroid noise.

# %%
fig = TH.plot_fig3_pair(scene, t2[6][1], t2["ours"][1],
                        titles=("paper (6-neighbourhood)", "verified initiator"),
                        suptitle="Fig. 3 — extracted tracks")

# %%
redraws = TH.xu_redraws(cfg, N["redraws"], runner=runner)
red = redraws.groupby("initiator", sort=False)[["exact", "false"]].mean()
assert red.loc["ours (verified)", "exact"] >= red.loc["paper (6-nbhd)", "exact"]
red.rename(columns={"exact": "fraction exact", "false": "mean false tracks"})

# %% [markdown]
# ### Method comparison (Monte Carlo)
#
# Four objects at 15–70 px/s, six frames at 1 Hz, uniform Poisson clutter, each object detected
# with probability $P_D$, the paper's gate and cells. *Correct*: a track whose detections up to
# confirmation come from one object (first per object); any other track is false. The digest's
# criterion for the angle constraint is *fewer* false tracks at equal initiation probability.

# %%
comp, comp_trials = TH.run_comparison(comp_cfg, n_trials=N["comparison"], runner=runner,
                                      xu=cfg, per_trial=True)
fig = TH.plot_comparison_grid(comp)

# %%
comp.pivot_table(index=["sweep", "clutter", "p_detect"], columns="method",
                 values="false_per_frame", sort=False)

# %% [markdown]
# Where does the angle constraint act? Wider prediction gates and denser clutter:

# %%
angle = TH.angle_constraint_table(comp_cfg, n_trials=N["aux"], runner=runner, xu=cfg)
ax = TH.plot_angle_constraint(angle)
angle.pivot_table(index=["clutter", "gate_px"], columns="method",
                  values=["false_per_frame", "p_correct"])

# %% [markdown]
# ### Planted scenes — scenes the initiators were not tuned to
#
# The paper's claim — several objects initiated in a few frames, residual stars no obstacle — on
# `N["planted"]` random scenes (criterion fixed in claims.toml before the run): 2–8 objects at 5–150 px/s in random directions, each detection missed with
# probability 0.1, 10–40 static residual stars, uniform clutter of 5–50 per frame, σ = 0.3 px;
# every initiator gets the gate [3, 240] px/s. First the chance rate of §4.6 against clutter-only
# scenes (acceleration search off, the rule the formula describes); the planted criterion
# multiplies the formula by the pooled measured/analytic ratio. Chance tracks are rare at low
# density, so the check runs more scenes there (standard errors below, with what 100 scenes
# per level would give). This cell reads `make repro`'s `chance_rate_check.csv`; with
# `QUICK = True`, or without it, it runs 10 scenes per level.

# %%
_chance_file = papers_repro_dir() / TH.SLUG / TH.CHANCE_CHECK_FILE
if not QUICK and _chance_file.exists():
    chance = pd.read_csv(_chance_file)
else:
    chance = TH.chance_rate_check(pl_cfg, n_trials=N["chance"], runner=runner)
ax = TH.plot_chance_check(chance)
k_chance = TH.calibrated_chance_factor(chance)
display(Markdown("measured/analytic: " + ", ".join(
    f"{c:g}/frame {r:.3f} ± {e:.3f} ({n} scenes; 100 scenes: ± {e * math.sqrt(n / 100):.3f})"
    for c, r, e, n in zip(chance["clutter"], chance["ratio"], chance["ratio s.e."],
                          chance["scenes"]))
    + f"; pooled **{k_chance:.3f}**."))
chance

# %%
planted_df = TH.run_planted(pl_cfg, n_scenes=N["planted"], runner=runner, xu=cfg)
summary = TH.summarise_planted(planted_df)
p_pl = claims["track_init.planted_scenes"].paper
fig = TH.plot_planted_summary(summary, recall_min=p_pl["recall_min"],
                              ratio_max=p_pl["false_over_chance_max"], chance_factor=k_chance)
summary

# %%
s_idx = summary.set_index("method")
lit_row, ours_row = s_idx.loc["modified Hough 3/4 (paper)"], s_idx.loc["modified Hough 3/4 (ours)"]
assert ours_row["recall"] > s_idx.loc["logic 3/4", "recall"]
display(Markdown(
    f"The paper's procedure: recall **{lit_row['recall']:.3f}** (criterion ≥ "
    f"{p_pl['recall_min']}), {lit_row['false per scene'] / (k_chance * lit_row['chance per scene']):.2f}"
    f" × the calibrated chance rate (criterion ≤ {p_pl['false_over_chance_max']}) — this sets the "
    f"status. Our verified variant, beside it: recall {ours_row['recall']:.3f}, "
    f"{ours_row['false per scene'] / (k_chance * ours_row['chance per scene']):.2f} × chance."))

# %% [markdown]
# The same runs scored by the community's measures [6, 10, 11], computed by Stone Soup
# (`eotrack.tracking.metrics`, hand-checked in its tests): GOSPA ($c$ = 10 px, $p$ = 1; the
# mean over the scored frames 3–6 of each scene, then over scenes; *missed* and *false* parts $c/2$ per missed object or false track,
# *localisation* the summed distances), SIAP completeness (object-frames covered by a track)
# and spuriousness (track-frames on no object).

# %%
metrics = TH.summarise_metrics(planted_df)
assert metrics.loc["modified Hough 3/4 (ours)", "gospa"] == metrics["gospa"].min()
metrics.round(3)

# %% [markdown]
# **Why logic 2/3 and the classic Hough lose almost every object.** Not a bug: the rules.
# The same objects with the clutter, the residual stars or both removed (paired scenes); *mixing*
# counts false tracks holding an object's detection:

# %%
abl = TH.recall_ablation(pl_cfg, n_scenes=max(10, N["planted"] // 4), runner=runner)
abl_r = abl.pivot(index="method", columns="condition", values="recall")
abl_m = abl.pivot(index="method", columns="condition", values="mixing per scene")
assert abl_r.loc["logic 2/3", "objects only"] > abl_r.loc["logic 2/3", "as planted"]
display(abl_r.round(3), abl_m.round(2))
_h = abl[abl["method"] == "classic Hough 3/4"].set_index("condition")
_dz = ((_h.loc["as planted", "recall"] - _h.loc["no residual stars", "recall"])
       / np.hypot(_h.loc["as planted", "recall s.e."], _h.loc["no residual stars", "recall s.e."]))
display(Markdown(f"(About {int(abl['eligible'].mean())} objects per condition: the classic "
                 f"Hough's recall as planted minus without residual stars is {_dz:.1f} binomial "
                 "s.e. — " + ("within noise" if abs(_dz) < 2 else "beyond noise")
                 + "; read only the large differences.)"))
gate_share = float(TH.distance_cdf_square(240.0, 512) - TH.distance_cdf_square(3.0, 512))
rng_h = np.random.default_rng(3)
chance_peak = []  # highest classic-Hough cell of the non-object detections of 4 frames
for _ in range(8):
    sc_h = TH.planted_scene(rng_h, pl_cfg)
    pts_h = np.concatenate([xy[lab < 0] for (_, xy), lab in zip(sc_h.frames[:4], sc_h.labels[:4])])
    chance_peak.append(int(hough_accumulator(pts_h, 5.0, 1.0, rho_max=730.0).votes.max()))
assert min(chance_peak) > 4
display(Markdown(
    f"A 2/3 track is confirmed by **any two** detections inside the velocity gate, which at "
    f"[3, 240] px/s covers {100 * gate_share:.0f} % of the field: each object detection has "
    f"about {gate_share * abl['detections per frame'].iloc[0]:.0f} gated partners per frame and "
    "two points carry no consistency test, so the confirmed pair is seldom the object's own "
    f"(recall {abl_r.loc['logic 2/3', 'as planted']:.2f} as planted, "
    f"{abl_r.loc['logic 2/3', 'no clutter']:.2f} without clutter, "
    f"{abl_r.loc['logic 2/3', 'objects only']:.2f} with objects only, where the other objects "
    "are the wrong partners). The classic Hough's cell (5 px × 1°, no time or speed) "
    "collects points of any order and speed; in clutter the highest cells are chance lines "
    f"(the non-object detections of 4 frames alone fill cells with {min(chance_peak)}–"
    f"{max(chance_peak)} votes, an object gives 4), confirmed first, and each takes the "
    "detection closest to its line in every frame — often the object's "
    f"(recall {abl_r.loc['classic Hough 3/4', 'as planted']:.2f} as planted, "
    f"{abl_r.loc['classic Hough 3/4', 'objects only']:.2f} objects only). The 3/4 rules with "
    "a prediction gate or a χ² test suffer it less (the table above)."))

# %% [markdown]
# ## 6 · Scorecard

# %%
rows = TH.evaluate(claims, cfg, t2[6][0], nominal, redraws, comp, angle, planted_df, chance,
                  comp_trials=comp_trials, n_frames_comp=comp_cfg.n_frames,
                  planted_metrics=metrics)
if QUICK:
    display(Markdown("**QUICK (reduced) run — these statuses are not the REPORT's.**"))
scorecard(rows)[["claim", "kind", "status", "ours", "variant", "note"]]

# %%
# NBVAL_CHECK_OUTPUT
for c in rows:
    print(f"{c.claim}: {c.status}")
if not QUICK:  # the full configuration is make repro's: the REPORT must say the same
    assert [str(c.status) for c in rows] == [c["status"] for c in _card["claims"]]

# %% [markdown]
# ## 7 · Explore
#
# The paper's choices (6- or 26-neighbourhood, origin of ρ) as clutter grows, against the
# verified initiator, on the same seeded planted scenes (the title says how many). Left: recall
# and false tracks against the chance rate; right: the first scene. All settings are computed
# once below; a change only redraws.

# %%
for lam in TH.EXPLORE_CLUTTER:
    for nb in (6, 26):
        for centred in (False, True):
            TH.explore_results(lam, nb, centred, False)
    TH.explore_results(lam, 6, False, True)


def draw(clutter, neighbourhood, centred, verified):
    return TH.plot_explore(clutter=clutter, neighbourhood=26 if neighbourhood else 6,
                           centred=centred, verified=verified)


explore = panel(draw, tight=False,
                clutter=dropdown("clutter (points/frame)", list(TH.EXPLORE_CLUTTER),
                                 20.0),
                neighbourhood=toggle("26-neighbourhood", False),
                centred=toggle("ρ from the image centre", False),
                verified=toggle("verified initiator (ours)", False))

# %% [markdown]
# ## 8 · Errata and deviations
#
# * **Tables 1 and 2 are lost.** Table 1 is ours, changed twice after seeing results (in the
#   claim's history); its redraws vary only stars and noise (Beyond redraws the table). Table 2
#   is reproduced in form only; the residual-star fraction is assumed.
# * **Eq. (8)** read as "+1 per current frame" contradicts the paper's confirmation frames; we
#   count distinct frames in Q(t) (§4.3). The lost formulas are rebuilt in §4.3 (numbering
#   uncertain).
# * **Direction s**: + along $(\sin\theta, -\cos\theta)$ (ours; the paper's "x and y
#   increasing" disagrees at θ = 0). **Origin of ρ**: the corner (unstated).
# * **Constant-velocity check** (ours): a confirmed cell must give one detection per frame on a
#   constant-velocity track of the cell (residual ≤ δρ/2). Every "paper" row includes it;
#   Beyond runs the bare procedure.
# * **Variants** (26-neighbourhood, verified initiator) cannot make the paper's claim
#   reproduced.
# * **Planted yardstick**: the chance rate is our χ² rule's, not that of the paper's cell.
# * **Logic details** left open: heads stay open for their window, a 10 px gate, conflicts to
#   the track with more points. At that gate the angle constraint cannot act (§4.7).
# * **Hand-off**: a confirmed track claims its later detections within 5 px of its prediction.
# * **Reviews**: the closing note below the exercises gives the counts.

# %% [markdown]
# ## 9 · Beyond the paper
#
# ### The logic rule's analytic false-track rate beside the measured one
#
# Clutter only, 20 frames per run; the measured rate over the formula of §4.7, with the
# prediction-inside factor $q$ and without it:

# %%
lf = TH.logic_false_track_table(comp_cfg, n_trials=N["aux"], runner=runner, xu=cfg)
ax = TH.plot_logic_false_tracks(lf)
lf = lf.assign(**{"measured / analytic": lf["measured"] / lf["analytic"],
                  "measured / edges ignored": lf["measured"] / lf["analytic, edges ignored"]})
l34 = lf[lf["method"] == "logic 3/4"]
ratio_ok = l34["measured / analytic"].between(0.8, 1.25)
display(Markdown(
    "Logic 3/4, measured / formula: " + ", ".join(
        f"{c:g}/frame {r:.2f} ({n} tracks)" for c, r, n in
        zip(l34["clutter"], l34["measured / analytic"], l34["false"]))
    + "; without the edge factor: " + ", ".join(
        f"{r:.2f}" for r in l34["measured / edges ignored"])
    + f". The formula is within 25 % of the measurement at {int(ratio_ok.sum())} of "
    f"{len(l34)} densities: it does not follow it. The edges-ignored version is within 25 % at "
    f"{int(l34['measured / edges ignored'].between(0.8, 1.25).sum())} of {len(l34)} (counts of "
    "a few tracks carry Poisson errors of tens of %). We have not found the missing terms; the "
    "formula is shown, not used. For 2/3 it is a gross upper bound (detections are used up)."))
lf

# %% [markdown]
# ### Stone Soup's `MultiMeasurementInitiator`
#
# The same seeded scenes given to Stone Soup [6] (constant-velocity Kalman model, wide velocity
# prior, Mahalanobis gate, global nearest neighbour, confirmation at 3 updates); the cell after
# the table looks at the objects it loses.

# %%
try:
    stone = TH.stonesoup_comparison(comp_cfg, n_trials=N["aux"], runner=runner, xu=cfg)
except ImportError as exc:  # optional baseline
    stone = pd.DataFrame({"note": [f"Stone Soup unavailable: {exc}"]})
stone

# %%
rng_ss = np.random.default_rng(3)
ss_lost = ss_elig = ss_mixed = ss_false = 0
for _ in range(6):
    sc_ss = TH.comparison_scene(rng_ss, comp_cfg, 10.0, comp_cfg.p_detect_nominal)
    tr_ss = TH.StoneSoupInitiator().initiate(sc_ss.frames)
    r_ss = TH.score_tracks(tr_ss, sc_ss)
    ss_elig += r_ss["eligible"]
    ss_lost += r_ss["eligible"] - r_ss["correct"]
    ss_false += r_ss["false"]
    ss_mixed += sum(1 for t in tr_ss if len({int(sc_ss.labels[f][d]) for f, d in t.hits
                                             if f <= t.confirmed_at}) > 1)
display(Markdown(
    f"Stone Soup, 6 scenes at 10 clutter points per frame: {ss_lost} of {ss_elig} objects lost, "
    f"{ss_false} false tracks, {ss_mixed} confirmed tracks mixing sources. A likely cause of "
    "the losses (not traced here) is its start from one detection with the wide zero-mean "
    "velocity prior: the first gate holds every point the speed allows, so clutter competes "
    "for each update under global nearest neighbour."))

# %% [markdown]
# ### Table 1 redrawn at random
#
# The statuses of §5 rest on *our* Table 1. Here the table itself is redrawn: the same frame
# patterns, random starts and velocities (speeds uniform in 20–80 px/s, every object inside the
# field), stars and noise as before. Share of redraws in which each initiator finds exactly the
# five objects and nothing else:

# %%
rand_tab = TH.xu_random_tables(cfg, max(4, N["aux"]), runner=runner)
rand_tab.groupby("initiator", sort=False)[["exact", "correct", "false"]].mean().round(3)

# %% [markdown]
# ### The paper's procedure without our constant-velocity check
#
# Errata: every "paper" row above includes our check of a confirmed cell. The bare procedure
# (`cv_check=False`: the cell's points, one per frame) on the planted scenes:

# %%
bare_rows = []
_lit_kw = {"d_rho": cfg.cell_rho_px, "d_theta_deg": cfg.cell_theta_deg, "d_v": cfg.cell_v_px_s,
           "v_min": pl_cfg.v_gate_px_s[0], "v_max": pl_cfg.v_gate_px_s[1], "literal": True}
_bare_rng = np.random.default_rng(pl_cfg.seed + 1)
_bare_scenes = [TH.planted_scene(_bare_rng, pl_cfg) for _ in range(max(3, N["aux"] // 2))]
for name, chk in (("paper + our check", True), ("paper, bare", False)):
    ini = ModifiedHoughInitiator(**_lit_kw, cv_check=chk)
    res = [TH.score_tracks(ini.initiate(sc.frames), sc) for sc in _bare_scenes]
    bare_rows.append({"procedure": name, "scenes": len(res),
                      "recall": sum(r["correct"] for r in res) / max(sum(r["eligible"] for r in res), 1),
                      "false per scene": np.mean([r["false"] for r in res])})
bare = pd.DataFrame(bare_rows).set_index("procedure")
display(Markdown(
    f"Without the check: recall {bare.loc['paper, bare', 'recall']:.3f} (with it "
    f"{bare.loc['paper + our check', 'recall']:.3f}; the planted criterion asks ≥ "
    f"{p_pl['recall_min']}), {bare.loc['paper, bare', 'false per scene']:.1f} false tracks per "
    f"scene (with it {bare.loc['paper + our check', 'false per scene']:.1f})."))
bare.round(3)

# %% [markdown]
# ### A held-out family (issue 27's "Generalise" target)
#
# Scenes the paper never had, drawn by `TH.heldout_scene` from `TH.HeldOutConfig()` (its
# settings are printed below). The targets (`TH.HELDOUT_TARGETS`) and each decisive seed were
# fixed before that seed was drawn, and a seed is decisive for one code only.
#
# The default initiator has a **growth engine** (`grow=True`): acceleration-widened 3-of-4
# seeds are grown over the whole sequence with a least-squares constant-acceleration fit
# (irregular intervals and gaps allowed, discs cut by each frame's own clutter density), and one
# best-first selection over the sequence prefers longer tracks, so a chance triplet cannot take
# the detections of a longer track. It is a **batch** (offline) decision: a track confirmed at
# frame k can depend on later frames, unlike the paper's real-time loop and logic 3/4. It runs
# only when the data call for it: a clutter burst (a frame with more than `grow_burst` = 3 times
# the median frame's detections and at least 50 more), or an accelerating track — more than m
# hits, explained by a constant-acceleration fit but not by a constant-velocity one — in the
# causal engine's result or in its own. Otherwise the causal engine's tracks are returned.

# %%
hcfg = TH.HeldOutConfig()
display(Markdown(
    f"The family: {hcfg.n_frames} frames at intervals drawn in {hcfg.dt_s[0]:g}–{hcfg.dt_s[1]:g} s, "
    f"{hcfg.n_objects[0]}–{hcfg.n_objects[1]} objects at {hcfg.speed_px_s[0]:g}–"
    f"{hcfg.speed_px_s[1]:g} px/s accelerating by up to ±{hcfg.accel_px_s2:g} px/s² along and "
    f"across, $P_D$ = {hcfg.p_detect:g}, uniform clutter {hcfg.clutter_per_frame[0]:g}–"
    f"{hcfg.clutter_per_frame[1]:g} per frame plus a burst of {hcfg.burst} false alarms in one "
    f"frame, {hcfg.n_stars[0]}–{hcfg.n_stars[1]} residual stars (each seen with probability "
    f"{hcfg.star_residual:g}), σ = {hcfg.sigma_px:g} px, a {hcfg.width_px} px field. Targets: "
    f"recall ≥ {TH.HELDOUT_TARGETS['recall']:g}, no more false tracks than logic 3/4, ≤ "
    f"{TH.HELDOUT_TARGETS['ms per frame at 200']:g} / "
    f"{TH.HELDOUT_TARGETS['ms per frame at 1000']:g} ms per frame at 200 / 1,000 uniform "
    "candidates (at load < 2.5)."))

# %% [markdown]
# Every decisive run so far, one seed per code version — the code was revised after each
# failure, so the last success must be read against this count. The first two from
# `TH.HELDOUT_EARLY_RUNS`, the others from the stored records of
# `benchmarks/bench_track_init_hough.py --record` (60 scenes per seed; the default
# `ModifiedHoughInitiator(v_min=3, v_max=240)` against logic 3/4 on the same scenes):

# %%
_dir = papers_repro_dir() / TH.SLUG
hist_rows, rec = [], None
for _e in TH.HELDOUT_EARLY_RUNS:  # recorded before the JSON records existed
    _rm = _e["recall"] >= TH.HELDOUT_TARGETS["recall"]
    _fm = (None if _e["logic 3/4 false"] is None
           else _e["false per scene"] <= _e["logic 3/4 false"])
    hist_rows.append({**_e, "recall met": _rm, "false met": _fm,
                      "criterion met": bool(_rm and _fm)})
for _code, _fname in (("1fbbc7c", "heldout_benchmark_1fbbc7c.json"),
                      ("64e5a2f", "heldout_benchmark_64e5a2f.json"),
                      (TH.HELDOUT_CODE, "heldout_benchmark.json")):
    if not (_dir / _fname).exists():
        continue
    _r = json.loads((_dir / _fname).read_text())
    if _fname == "heldout_benchmark.json":
        rec = _r
    _seed = next(s for s, v in _r["seeds"].items() if v["role"] == "decisive")
    _ini = _r["seeds"][_seed]["initiators"]
    _d, _lg = _ini["modified Hough (ours, default)"], _ini["logic 3/4"]
    _pf = {(x["initiator"], x["candidates/frame"]): x["CPU ms/frame"] for x in _r["per frame"]}
    _t200, _t1000 = _pf[("modified Hough (ours)", 200)], _pf[("modified Hough (ours)", 1000)]
    _tg = _r["targets"]
    _ok = {"recall": _d["recall"] >= _tg["recall"],
           "false": _d["false per scene"] <= _lg["false per scene"],
           "time": (_t200 <= _tg["ms per frame at 200"] and _t1000 <= _tg["ms per frame at 1000"]
                    and _r["load average at start"] < 2.5)}
    _causal200 = _pf[("modified Hough (ours, causal: grow=False)", 200)]
    hist_rows.append({"code": _code, "decisive seed": int(_seed), "recorded": _r["date"],
                      "load": f"{_r['load average at start']:.1f}",
                      "recall": _d["recall"], "false per scene": _d["false per scene"],
                      "logic 3/4 recall": _lg["recall"],
                      "logic 3/4 false": _lg["false per scene"],
                      "ms/frame at 200": _t200, "ms/frame at 1000": _t1000,
                      "causal ms/frame at 200": _causal200,
                      "recall met": _ok["recall"], "false met": _ok["false"],
                      "time met (load < 2.5)": _ok["time"], "criterion met": all(_ok.values())})
hist = pd.DataFrame(hist_rows)
if rec is not None:
    dec = rec["seeds"][str(TH.HELDOUT_SEED)]["initiators"]
    d, lg = dec["modified Hough (ours, default)"], dec["logic 3/4"]
    cz = dec["modified Hough (ours, causal: grow=False)"]
    pf = {(x["initiator"], x["candidates/frame"]): x["CPU ms/frame"] for x in rec["per frame"]}
    ho = {x["initiator"]: x for x in rec["per frame on held-out scenes"]}
    last = hist.iloc[-1]
    verdict = "met" if last["criterion met"] else "**not met**"
    parts = [k for k, col in (("recall", "recall met"), ("false tracks", "false met"),
                              ("time per frame", "time met (load < 2.5)")) if not last[col]]
    display(Markdown(
        f"Code {TH.HELDOUT_CODE} on seed {TH.HELDOUT_SEED}, recorded {rec['date']} at load "
        f"{rec['load average at start']:.2f} → {rec['load average at end']:.2f}: recall "
        f"{d['recall']:.3f} with {d['false per scene']:.2f} false tracks per scene (logic 3/4: "
        f"{lg['recall']:.3f}, {lg['false per scene']:.2f}; the causal engine alone: "
        f"{cz['recall']:.3f}, {cz['false per scene']:.2f}); GOSPA {d['gospa']:.1f} (missed "
        f"{d['gospa missed']:.1f}, false {d['gospa false']:.1f}) vs logic 3/4's {lg['gospa']:.1f}; "
        f"SIAP completeness {d['siap completeness']:.3f} vs {lg['siap completeness']:.3f}. "
        f"The criterion is {verdict}"
        + (f" (missed: {', '.join(parts)})" if parts else "") + ". "
        f"CPU per frame at 200 uniform candidates: default "
        f"{pf[('modified Hough (ours)', 200)]:.2f} ms, the causal engine it runs there "
        f"(crowded frames) {pf[('modified Hough (ours, causal: grow=False)', 200)]:.2f} ms; at "
        f"1,000: {pf[('modified Hough (ours)', 1000)]:.1f} ms; growth forced "
        f"{pf[('modified Hough (ours, growth forced)', 200)]:.1f} / "
        f"{pf[('modified Hough (ours, growth forced)', 1000)]:.0f} ms. On held-out scenes, where "
        f"the growth runs ({ho['modified Hough (ours, default)']['mean detections/frame']:.0f} "
        f"detections per frame, "
        f"{ho['modified Hough (ours, default)']['burst frame detections']:.0f} in the burst "
        f"frame): {ho['modified Hough (ours, default)']['CPU ms/frame']:.1f} ms per frame "
        f"(causal {ho['modified Hough (ours, causal: grow=False)']['CPU ms/frame']:.1f}, logic "
        f"3/4 {ho['logic 3/4']['CPU ms/frame']:.1f})."))
hist.round(3)

# %%
_c200 = hist["causal ms/frame at 200"].dropna() if "causal ms/frame at 200" in hist else []
if len(_c200) >= 2:
    display(Markdown(
        f"At 200 uniform candidates the frames are crowded, so the default runs the causal "
        f"engine, whose code is the same in all {len(_c200)} records: it took "
        f"{_c200.min():.2f}–{_c200.max():.2f} ms per frame across them. So the run-to-run spread "
        "of this machine spans the 5 ms target, and the load rule does not make that part "
        "decidable; the criterion counts the measurement as it was made (cause of the spread "
        "not traced)."))

# %% [markdown]
# Earlier codes: 1fbbc7c (growth always on) changed the paper's scenes; 64e5a2f ran the growth
# only when the causal result held an accelerating track, and on the development seeds (listed
# in commit 1b1c4c2) every scene it lost against growth-always-on was one whose causal result
# held none: the causal engine had lost the very objects that would have shown the need. The
# burst and own-result triggers close that gap.
#
# The paper's scenes keep the causal engine: on planted scenes (constant-velocity objects,
# no burst) the default's tracks equal `grow=False`'s —

# %%
_pl_rng = np.random.default_rng(2029)  # an illustration seed, neither decisive nor tuning
_pl_ini = TH.planted_initiators(pl_cfg)["modified Hough 3/4 (ours)"]
_n_pl = max(5, N["aux"])
_same = sum([t.hits for t in _pl_ini.initiate(sc.frames)]
            == [t.hits for t in replace(_pl_ini, grow=False).initiate(sc.frames)]
            for sc in (TH.planted_scene(_pl_rng, pl_cfg) for _ in range(_n_pl)))
display(Markdown(f"— in {_same} of {_n_pl} planted scenes here."))

# %% [markdown]
# The same family on a few fresh scenes here (seed 2027: neither decisive nor used for
# tuning), with the default's misses sorted by cause:

# %%
from eotrack.tracking.initiation import LogicInitiator

held_inits = {"ours (default)": ModifiedHoughInitiator(v_min=3, v_max=240),
              "ours, causal (grow=False)": ModifiedHoughInitiator(v_min=3, v_max=240, grow=False),
              "logic 3/4": LogicInitiator(n=3, m=4, v_min=3, v_max=240, gate_px=10.0)}
miss = {"missed": 0, "stolen": 0, "seen 3 times": 0}  # the default's misses
h_rng = np.random.default_rng(2027)
tot = {k: np.zeros(3) for k in held_inits}
n_held = max(2, N["aux"])
for _ in range(n_held):
    h_sc = TH.heldout_scene(h_rng, hcfg)
    for name, ini in held_inits.items():
        h_tr = ini.initiate(h_sc.frames)
        r = TH.score_tracks(h_tr, h_sc)
        tot[name] += (r["correct"], r["eligible"], r["false"])
        if name != "ours (default)":
            continue
        used = {(f, d) for t in h_tr for f, d in t.hits if f <= t.confirmed_at}
        for i in range(h_sc.n_targets):
            dets = [(f, int(d)) for f, lab in enumerate(h_sc.labels)
                    for d in np.flatnonzero(lab == i)]
            seen = np.array([np.any(lab == i) for lab in h_sc.labels], int)
            if np.convolve(seen, np.ones(4, int), "valid").max() < 3 or i in r["confirm_frame"]:
                continue
            miss["missed"] += 1
            miss["stolen"] += any(x in used for x in dets)
            miss["seen 3 times"] += len(dets) == 3
held = pd.DataFrame([{"initiator": k, "scenes": n_held, "eligible objects": int(e),
                      "recall": c / max(e, 1), "false per scene": f / n_held}
                     for k, (c, e, f) in tot.items()])
_m = miss["missed"]
display(Markdown(
    f"The default missed {_m} of {int(tot['ours (default)'][1])} eligible objects here"
    + (f"; of those, {miss['stolen']} of {_m} lost a detection to another track and "
       f"{miss['seen 3 times']} of {_m} were seen only three times" if _m else "")
    + (": three hits of an accelerating object fit a chance triplet as well, so no longer track "
       "vouches for them." if _m and miss["seen 3 times"] * 2 > _m else ".")))
held.round(3)

# %% [markdown]
# ### Speed
#
# The engine is built from array operations: the third detection looked up for every seed
# pair at once (an occupancy image in cells proportional to the disc, so wide acceleration
# discs cost no more, then a spatial grid inside the χ² disc), fits in batch, conflicts in
# parallel rounds. The benchmark
# (`benchmarks/bench_track_init_hough.py`) times it per frame against uniform candidates; here
# one small measurement (machine-dependent, not part of any claim):

# %%
import time

rng = np.random.default_rng(1)
bench = [(float(k), rng.uniform(0, 512, (200, 2))) for k in range(6)]
fast = ModifiedHoughInitiator()


def cpu_s(frames, repeat=3):
    out = []
    for _ in range(repeat):
        t0 = time.process_time()
        fast.initiate(frames)
        out.append(time.process_time() - t0)
    return min(out)


n_tr = len(fast.initiate(bench))  # warm-up
steady_ms = 1e3 * (cpu_s(bench) - cpu_s(bench[:2])) / (len(bench) - 2)
display(Markdown(f"Verified initiator, 200 uniform candidates per frame: {steady_ms:.1f} ms CPU "
                 f"per frame in steady state ({n_tr} chance tracks in 6 frames — 200 uniform "
                 "points per frame are mostly chance triplets)."))

# %% [markdown]
# ## 10 · Key points
#
# * Pairs vote for line, speed and direction; cells quantise what noise spreads, more so far
#   from ρ's origin.
# * A χ² test at the noise is the same 3-of-4 rule with the right tolerance; best fit first
#   keeps most objects' detections from chance tracks at the planted densities (a clutter burst
#   still takes some: Beyond).
# * A 3-of-4 rule's chance rate starts as λ³σ²/A (§4.6's first term) and grows more slowly once
#   chance triplets share detections: compute it before judging false tracks.
# * Two hits carry no test (2/3), a line cell knows no time (classic Hough): both fail in
#   clutter.
# * Judge initiators on many random scenes by recall, false tracks, GOSPA and SIAP.

# %% [markdown]
# ## 11 · Exercises
#
# Check an answer with `check("track_init_hough.k", answer)`; it says right or wrong and gives a
# hint, never the solution. Worked solutions:
# `notebooks/solutions/04_track_init_hough_solutions.ipynb`.
#
# **Exercise 1 (derivation).** Three hits at $t_1 < t_2 < t_3$ pass the χ² test when the hit you
# look up lies in a disc of area $\pi\chi^2_2(1-\alpha)\sigma^2 c$ around the point predicted
# from the other two (§4.5). §4.6 states $c$ for the middle hit only; derive it for any hit and
# write `disc_factor(t1, t2, t3, which)` returning it for the hit `which` ∈ {0, 1, 2}.

# %%
def disc_factor(t1, t2, t3, which):
    return None  # your code here


if disc_factor(0.0, 1.0, 2.0, 1) is not None:
    check("track_init_hough.1", disc_factor)

# %% [markdown]
# **Exercise 2 (computation).** Draw the clutter-only scene
# `TH.planted_scene(np.random.default_rng(2016), pl_cfg, clutter_per_frame=30, n_objects=0,
# n_stars=0)` and compute the number of passing triples $\sum N_1N_2N_3P_3$ over the frame
# triples of `triplet_shapes` — §4.6's first step, every detection counted as available, before
# depletion and conflicts (the planted scenes' gate, σ, α).

# %%
answer = None  # your answer here
if answer is not None:
    check("track_init_hough.2", answer)

# %% [markdown]
# **Exercise 3 (exploration).** The Explore panel offers 5, 20 and 50 clutter points per frame.
# Run the paper's procedure (6-neighbourhood, ρ from the corner) on its scenes at 35 per frame,
# `TH.explore_results(35.0, 6, False, False)`: what is the mean number of false tracks per
# scene? Compare it with the chance rate and with the verified initiator.

# %%
answer = None  # your answer here
if answer is not None:
    check("track_init_hough.3", answer)

# %% [markdown]
# **Exercise 4 (critique).** The paper's 6-neighbourhood loses track 2 of the nominal scene
# (seen in frames 1, 2, 4). Would finer cells save it? With δρ = 3 px, δθ = 3°, δv = 3 px/s
# (ρ from the corner), compute the cells $(\lfloor\rho/\delta\rho\rfloor,
# \lfloor\theta/\delta\theta\rfloor, \lfloor v/\delta v\rfloor)$ of track 2's pairs 1→2 and
# 2→4 (label 1 in `scene.labels`) and give the number of indices in which they differ.

# %%
answer = None  # your answer here (a number)
if answer is not None:
    check("track_init_hough.4", answer)

# %% [markdown]
# **Exercise 5 (critique).** The angle-constrained logic rejects a candidate X when the angle at
# the last point P between the previous point and X is ≤ 90°. Take $v_{min}$ = 15 px/s,
# Δt = 1 s and a gate of radius r = 20 px around a prediction exactly $v_{min}\Delta t$ ahead of
# P. What fraction of the gate's area holds candidates that the constraint rejects?

# %%
answer = None  # a number in [0, 1]
if answer is not None:
    check("track_init_hough.5", answer)

# %% [markdown]
# ## 12 · Closing note
#
# **Reviews.** Round 1 (issue 27): 18 findings, 15 fixed or answered, 3 left (two now in
# Beyond). Round 2: 14 findings, 13 fixed, 1 left (the 5-seed stability, since re-run: 5/5 in
# the header). Round 3 (independent, this session, two passes): 29 findings (3 high, 6 medium,
# 20 low): 20 fixed, 2 in part (the chance formula's range, the word count), 2 answered (the
# growth engine documented as offline; the capstone's SIAP is the capstone's), 5 left (held-out
# variants, Fig. 3 colours, the five methods' timing table, prose length, an exploratory label on
# the chance-rate claim).
# **Held-out target** (Beyond, from the stored records):

# %%
if len(hist):
    _last = hist.iloc[-1]
    display(Markdown(
        f"code {_last['code']}, decisive seed {_last['decisive seed']}: recall "
        f"{_last['recall']:.3f} ({'met' if _last['recall met'] else 'not met'}), false tracks "
        f"{_last['false per scene']:.2f} vs logic 3/4's {_last['logic 3/4 false']:.2f} "
        f"({'met' if _last['false met'] else 'not met'}), time per frame "
        f"({'met' if _last['time met (load < 2.5)'] else 'not met'}); criterion "
        f"{'met' if _last['criterion met'] else '**not met**'}. Earlier decisive runs: "
        + "; ".join(f"{r['code']} {'met' if r['criterion met'] else 'not met'}"
                    for _, r in hist.iloc[:-1].iterrows())
        + f" — {len(hist)} decisive seeds for {len(hist)} code versions (1fbbc7c's growth was "
        "always on and changed the paper's scenes)."))

# %% [markdown]
# ## 13 · References
#
# 1. Xu Z.W., Wang X. Track initiation in electro-optical tracking of space objects. *Acta
#    Astronomica Sinica* 57(2):211–218, 2016 (CNKI; no DOI printed).
# 2. He You, Xiu J.J., Guan X. et al. *Radar Data Processing with Applications* (雷达数据处理及应用),
#    3rd ed. Publishing House of Electronics Industry, 2009 (ref. [13] of Xu & Wang: the logic
#    n/m rule). Also: Bar-Shalom Y., Willett P.K., Tian X. *Tracking and Data Fusion: A Handbook of Algorithms.*
#    YBS Publishing, 2011. ISBN 978-0-9648312-7-8.
# 3. Yuan G., Sheng F. et al. Angle-constrained logic track initiation. *Ship Electronic
#    Engineering* 30(5), 2010 (CNKI; no DOI).
# 4. Duda R.O., Hart P.E. Use of the Hough transformation to detect lines and curves in
#    pictures. *Commun. ACM* 15(1):11–15, 1972. doi:10.1145/361237.361242
# 5. Bradski G. The OpenCV library. *Dr. Dobb's Journal of Software Tools*, 2000
#    (`cv2.HoughLinesPointSet`).
# 6. Barr J., Harrald O., Hiscocks S. et al. Stone Soup: announcement of beta release of an
#    open-source framework for tracking and state estimation. *Proc. SPIE* 11018, 2019.
#    doi:10.1117/12.2518514
# 7. Gaia Collaboration, Vallenari A. et al. Gaia Data Release 3: summary of the content and
#    survey properties. *Astron. Astrophys.* 674:A1, 2023. doi:10.1051/0004-6361/202243940
# 8. Carlson B.D., Evans E.D., Wilson S.L. Search radar detection and track with the Hough
#    transform. *IEEE Trans. Aerosp. Electron. Syst.* 30(1):102–108, 1994. doi:10.1109/7.250410
# 9. Lo T., Leung H., Bridgewater A.W. et al. (modified Hough track initiation), *AGARD
#    Conference Proceedings* 539:25.1, 1994 (ref. [11] of Xu & Wang).
# 10. Rahmathullah A.S., García-Fernández Á.F., Svensson L. Generalized optimal sub-pattern
#    assignment metric. *Proc. FUSION* 2017. doi:10.23919/ICIF.2017.8009645
# 11. Votruba P., Nisley R., Rothrock R., Zombro B. *Single Integrated Air Picture (SIAP)
#    Metrics Implementation.* SIAP SE Task Force TR 2001-003, 2001.
# 12. Yang J.Y. (track initiation methods: classic Hough and the modified Hough over three
#    scans). *科技创新与应用* (Technology Innovation and Application) 2019(6):12–13 (CNKI; the
#    collection's source of the classic Hough and logic baselines, claims.toml "Yang 2019 §2-3").

# %%
from eotrack.notebook import lesson_footer

_ = lesson_footer("04")
