# ---
# jupyter:
#   kernelspec:
#     display_name: Python 3 (ipykernel)
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 03 · Solutions — track initiation by hypothesis testing (Li et al. 2008)
#
# Worked solutions to the exercises of `03_track_init_hypothesis_testing.ipynb`. Each solution
# computes the answer, checks it with `check(...)`, then discusses it. Try the exercises first.

# %%
import math

import numpy as np
from eotrack.exercises import check
from eotrack.experiments import track_init_ht as E
from eotrack.notebook import setup_notebook
from eotrack.tracking import hypothesis as hyp
from IPython.display import Markdown, display
from scipy.optimize import brentq
from scipy.stats import binom, norm

setup_notebook()
P = E.paper_settings()

# %% [markdown]
# ## Exercise 1 — eq. (4) as a binomial tail
#
# Number the window's pixels $1,\dots,W_S$ and let $X_i = 1$ if pixel $i$ is suspicious. In a
# noise-only window the $X_i$ are independent Bernoulli($P_F$), so their sum $D$ — the count of
# eq. (3) — is Binomial($W_S$, $P_F$): $\Pr[D=t]=\binom{W_S}{t}P_F^t(1-P_F)^{W_S-t}$ (choose
# which $t$ pixels fire). The window is (falsely) flagged when $D\ge S$, so
#
# $$P_{FA}=\sum_{t=S}^{W_S}\binom{W_S}{t}P_F^t(1-P_F)^{W_S-t}=\Pr[D\ge S]=\Pr[D>S-1].$$
#
# `scipy.stats.binom.sf(k, n, p)` is $\Pr[X>k]$, hence the $S-1$. For $S=0$ it returns 1, as it
# should (every window has $D\ge0$).

# %%
def p_fa(p_f, w_s, s):
    return binom.sf(s - 1, w_s, p_f)


assert check("track_init_ht.1", p_fa)
# the explicit sum agrees
w_s, s, p = 25, 3, P["fig1_p_f"]
explicit = sum(math.comb(w_s, t) * p ** t * (1 - p) ** (w_s - t) for t in range(s, w_s + 1))
assert np.isclose(p_fa(p, w_s, s), explicit, rtol=1e-12)

# %% [markdown]
# The common mistake is `binom.sf(s, w_s, p_f)`, which is $\Pr[D > S]$ — the *printed* eq. (2).
# That the text and eq. (4) say "not fewer than $S$" is how we know eq. (2) is the erratum.
#
# ## Exercise 2 — the threshold for a required $P_{FA}$
#
# $P_{FA}$ falls with $S$, so the answer is the first $S$ at which eq. (4) drops to $10^{-6}$.

# %%
p_f, window = P["cfar_p_f"], P["window"]
s_all = np.arange(0, window * window + 1)
pfa = hyp.area_false_alarm(p_f, window, s_all)
answer = int(s_all[np.argmax(pfa <= 1e-6)])
assert answer == hyp.clustering_threshold(p_f, window, 1e-6)
assert check("track_init_ht.2", answer)
display(Markdown(
    f"S = {answer}: $P_{{FA}}$ = {pfa[answer]:.2g}. The paper's S = {P['s']} gives "
    f"$P_{{FA}}$ = {pfa[P['s']]:.2g}: enough for a requirement of $10^{{-5}}$, not $10^{{-6}}$. "
    f"In a {E.SequenceSettings().shape[0]}×{E.SequenceSettings().shape[1]} frame that is still "
    f"about {pfa[P['s']] * np.prod(E.SequenceSettings().shape):.2g} false windows per frame "
    "before the temporal test."))

# %% [markdown]
# ## Exercise 3 — how much SNR the exact count needs (the widget question)
#
# At log10 $P_F=-2.5$ the false-alarm requirement fixes the smallest admissible $S$; larger $S$
# only need more SNR. At each admissible $S$, solve exact $P_{DA}(\mathrm{SNR}) = 0.9$.

# %%
p_f3 = 10 ** -2.5
w3, ts3 = P["fig1_window"], P["fig1_target_pixels"]
s_min = hyp.clustering_threshold(p_f3, w3, 1e-4)


def snr_needed(s, pda=0.9):
    def f(snr):
        return hyp.area_detection_exact(hyp.snr_to_pd(snr, p_f3), p_f3, w3, ts3, s) - pda
    return brentq(f, 0.0, 30.0) if f(30.0) > 0 else np.inf


need = {s: snr_needed(s) for s in range(s_min, ts3 + 2)}
answer = min(need.values())
assert check("track_init_ht.3", round(answer, 1))


def snr_needed_eq7(s, pda=0.9):
    def f(snr):
        return hyp.area_detection(hyp.snr_to_pd(snr, p_f3), p_f3, w3, ts3, s) - pda
    return brentq(f, 0.0, 30.0)


display(Markdown(
    f"Smallest admissible S = {s_min}; SNR needed for exact $P_{{DA}}$ ≥ 0.9: " + ", ".join(
        f"S = {s}: {v:.2f}" for s, v in need.items()) + f". Answer: SNR ≈ {answer:.1f}. "
    f"Eq. (7) would claim SNR {snr_needed_eq7(s_min):.2f} suffices at the same S — the "
    "paper's 'SNR 2 works' comes from there."))

# %%
pd_need = brentq(lambda q: binom.sf(s_min - 1, ts3, q) - 0.9, 1e-9, 1 - 1e-12)
display(Markdown(
    f"Why: with $T_S$ = {ts3} target pixels and S = {s_min}, at least {s_min} target pixels must "
    f"fire (noise pixels rarely help at this $P_F$): $\\Pr[\\mathrm{{Bin}}({ts3},P_D)\\ge{s_min}]"
    f"\\ge0.9$ needs $P_D$ ≈ {pd_need:.2f} per pixel, i.e. SNR = $Q^{{-1}}(P_F)-Q^{{-1}}(P_D)$ = "
    f"{norm.isf(p_f3) - norm.isf(pd_need):.2f}."))

# %% [markdown]
# ## Exercise 4 — why eq. (7) overstates $P_{DA}$
#
# Condition on $k$, the number of detected target pixels, $k\sim\mathrm{Bin}(T_S,P_D)$; the
# $W_S-T_S$ noise pixels must supply at least $S-k$ more.

# %%
p_f4 = P["fig1_p_f"]
p_d4 = float(hyp.snr_to_pd(2.0, p_f4))
w4, ts4 = P["fig1_window"], P["fig1_target_pixels"]
s4 = ts4
k = np.arange(ts4 + 1)
terms = binom.pmf(k, ts4, p_d4) * binom.sf(s4 - k - 1, w4 * w4 - ts4, p_f4)
answer = float(terms.sum())
assert check("track_init_ht.4", answer)
eq7 = hyp.area_detection(p_d4, p_f4, w4, ts4, s4)
p1 = hyp.p1_paper(p_d4, p_f4, w4, ts4)
display(Markdown(
    f"Exact $P_{{DA}}$ = {answer:.3g}; eq. (7) = {eq7:.3f}. The term $k = T_S$ (all four target "
    f"pixels detected, $P_D^4$ = {p_d4 ** 4:.3g}) is {terms[-1] / answer:.0%} of the exact "
    f"value. Eq. (7) instead gives **every one of the {w4 * w4} pixels** the probability "
    f"$P_1$ = {p1:.3f}, so it expects {w4 * w4 * p1:.1f} suspicious pixels per window, while the "
    f"model's mean is $T_S P_D + (W_S - T_S) P_F$ = {ts4 * p_d4 + (w4 * w4 - ts4) * p_f4:.2f}."))

# %% [markdown]
# The error is structural: $P_{0,W_S-T_S}$ is the probability that *at least one* of the
# $W_S-T_S$ noise pixels fires — a per-window quantity — added to a per-pixel $P_D$ and then
# used as a per-pixel probability for all $W_S$ pixels. The Monte Carlo of Fig. 1 in the
# notebook follows the exact count at every checked point.
#
# ## Exercise 5 — when eq. (6) leaves [0, 1]
#
# $P_1 = P_D + P_0$ with $P_0 = 1-(1-P_F)^{W_S-T_S}$, so $P_1>1 \iff P_D > (1-P_F)^{W_S-T_S}$.

# %%
p_f5, w5, ts5 = P["cfar_p_f"], P["window"], P["curved_size_px"] ** 2
answer = (1 - p_f5) ** (w5 * w5 - ts5)
assert check("track_init_ht.5", answer)
display(Markdown(
    f"$P_1 > 1$ for $P_D >$ {answer:.3f}. The paper's own experiment states $P_D$ = "
    f"{P['cfar_p_d']:g}, where eq. (6) gives $P_1$ = "
    f"{hyp.p1_paper(P['cfar_p_d'], p_f5, w5, ts5):.2f}: eq. (7) is then undefined (the library "
    "clips $P_1$ to 1, making $P_{DA}$ = 1 for every S)."))

# %%
display(Markdown(
    f"A per-window probability (\"some noise pixel fires\") is large even when each pixel's "
    f"$P_F$ is small: with {w5 * w5 - ts5} noise pixels at $P_F$ = {p_f5:g} it is "
    f"{1 - answer:.2f}. Adding it to a per-pixel probability has no meaning; the exact count "
    "needs no such step."))
