"""Exercises of notebook 03 (Li et al. 2008, track initiation by hypothesis testing).

Expected values are computed with the library on first use; nothing is typed in.

1. derivation — eq. (4) as a binomial tail (a function);
2. computation — the clustering threshold S for a required P_FA;
3. exploration — the smallest SNR at which the exact count allows low P_FA and high P_DA;
4. critique — eq. (7) against the exact count at Fig. 1's operating point;
5. critique — the P_D above which eq. (6) gives P_1 > 1.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from eotrack.exercises import FunctionAnswer, NumericAnswer, register
from eotrack.tracking import hypothesis as hyp

__all__: list[str] = []

#: Exercise 3's requirement (the claim's criterion constants).
_EX3_MAX_PFA = 1e-4
_EX3_MIN_PDA = 0.9
_EX3_LOG10_PF = -2.5
_EX3_TS = 4


def _settings() -> dict:
    from eotrack.experiments.track_init_ht import paper_settings

    return paper_settings()


def _p_fa_reference(p_f: float, w_s: int, s: int) -> float:
    """Eq. (4) with the window given as its number of pixels ``W_S`` (a square of an odd side)."""
    return float(hyp.area_false_alarm(p_f, math.isqrt(int(w_s)), s))


def _ex1_inputs() -> list[tuple]:
    return [(0.003, 25, 3), (0.03, 25, 7), (0.01, 9, 2), (0.2, 49, 10), (0.5, 1, 1),
            (0.05, 25, 0), (0.001, 121, 4)]


def _ex3_expected() -> float:
    """Smallest SNR at which some S has P_FA <= 1e-4 and exact P_DA >= 0.9 (5x5, T_S = 4)."""
    p_f = 10.0 ** _EX3_LOG10_PF
    window = _settings()["fig1_window"]
    s_min = hyp.clustering_threshold(p_f, window, _EX3_MAX_PFA)

    def need(s: int) -> float:
        f = lambda snr: hyp.area_detection_exact(hyp.snr_to_pd(snr, p_f), p_f, window,  # noqa: E731
                                                 _EX3_TS, s) - _EX3_MIN_PDA
        return brentq(f, 0.0, 30.0) if f(30.0) > 0 else np.inf

    return float(min(need(s) for s in range(s_min, window * window + 1)))


def _ex4_expected() -> float:
    ps = _settings()
    p_f = ps["fig1_p_f"]
    return float(hyp.area_detection_exact(hyp.snr_to_pd(2.0, p_f), p_f, ps["fig1_window"],
                                          ps["fig1_target_pixels"], ps["fig1_target_pixels"]))


def _ex5_expected() -> float:
    ps = _settings()
    # P_1 = P_D + P_0 exceeds 1 when P_D > 1 - P_0, and P_0 is P_1 at P_D = 0
    return 1.0 - float(hyp.p1_paper(0.0, ps["cfar_p_f"], ps["window"], ps["curved_size_px"] ** 2))


register("track_init_ht.1", FunctionAnswer(
    "Derivation: in a window of W_S noise pixels, each suspicious with probability P_F "
    "independently, show that the area false-alarm probability of eq. (4) is the tail "
    "P(Bin(W_S, P_F) >= S). Write p_fa(p_f, w_s, s) returning it (w_s = number of pixels).",
    reference=_p_fa_reference, inputs=_ex1_inputs, rtol=1e-6, atol=1e-15,
    hint="the count of suspicious pixels is a sum of W_S independent Bernoulli(P_F); "
         "scipy.stats.binom.sf(k, n, p) is P(X > k) — mind the off-by-one for '>= S', "
         "and S = 0 must give 1."))

register("track_init_ht.2", NumericAnswer(
    "Computation: the experiment segments at P_F = 0.03 (claims.toml) and clusters in a 5x5 "
    "window. What is the smallest threshold S whose area false-alarm probability P_FA (eq. 4) "
    "is at most 1e-6?",
    expected=lambda: hyp.clustering_threshold(_settings()["cfar_p_f"], _settings()["window"],
                                              1e-6),
    rtol=0.0, atol=1e-9,
    hint="P_FA falls as S grows: evaluate eq. (4) for S = 1, 2, ... (area_false_alarm takes an "
         "array of S) and take the first S at or below the requirement.",
    expects="an integer S"))

register("track_init_ht.3", NumericAnswer(
    "Exploration: in the Explore panel set log10 P_F = -2.5, window 5x5, T_S = 4. Raise the "
    "SNR: what is the smallest SNR (to 0.1) at which some S gives P_FA <= 1e-4 and an EXACT "
    "P_DA >= 0.9?",
    expected=_ex3_expected, rtol=0.0, atol=0.1,
    hint="P_FA <= 1e-4 fixes the smallest admissible S (left panel, black curve); at that S "
         "move the SNR slider until the solid blue (exact) curve reaches 0.9 — larger S only "
         "needs more SNR.",
    expects="an SNR (a number)"))

register("track_init_ht.4", NumericAnswer(
    "Critique (eq. 7): at Fig. 1's setting (W_S = 25, T_S = 4, P_F = 0.003) and SNR 2, eq. (7) "
    "gives P_DA of about 0.96 at S = 4. Compute the exact P_DA at S = 4 (the count is "
    "Bin(T_S, P_D) + Bin(W_S - T_S, P_F)).",
    expected=_ex4_expected, rtol=0.02,
    hint="condition on k, the number of detected target pixels: the noise pixels must supply "
         "at least S - k; area_detection_exact does the sum, or convolve the two binomial pmfs.",
    expects="a probability"))

register("track_init_ht.5", NumericAnswer(
    "Critique (eq. 6): with the experiment's settings (P_F = 0.03, a 5x5 window, a 3x3 target "
    "so T_S = 9), above which per-pixel detection probability P_D does eq. (6), "
    "P_1 = P_D + 1 - (1 - P_F)^(W_S - T_S), exceed 1?",
    expected=_ex5_expected, rtol=5e-3,
    hint="set P_1 = 1 in eq. (6) and solve for P_D; (1 - P_F)^(W_S - T_S) is the chance that "
         "none of the W_S - T_S noise pixels fires.",
    expects="a probability"))
