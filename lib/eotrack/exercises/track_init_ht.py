"""Exercises of notebook 03 (Li et al. 2008, track initiation by hypothesis testing).

Expected values are computed with the library on first use; nothing is typed in.

1. derivation — the exact P_DA when the target's pixels have different P_D (a function);
2. computation — the clustering threshold S for a required P_FA, on a 7 × 7 window;
3. exploration — the smallest SNR (on the 0.1 grid) at which the exact count allows low P_FA
   and high P_DA, for a 6-pixel target (the notebook prints the P_D that Fig. 1's T_S = 4
   needs, so the question is posed on another T_S);
4. critique — eq. (7) against the exact count for a 3 × 3 target (T_S = 9);
5. critique — the P_D above which eq. (6) gives P_1 > 1 (on a 7 × 7 window).

None of the answers is printed in the notebook: the notebook shows eq. (4), the equal-P_D exact
count and Fig. 1 for T_S = 4; the exercises ask for other settings.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from eotrack.exercises import FunctionAnswer, NumericAnswer, register
from eotrack.tracking import hypothesis as hyp

__all__: list[str] = []

#: Exercise 2's setting (not the notebook's: a 7 x 7 window at P_F = 0.01).
_EX2_WINDOW = 7
_EX2_PF = 0.01
_EX2_MAX_PFA = 1e-8
#: Exercise 4's setting: Fig. 1's window and P_F, SNR 2, a 3 x 3 target, S = 6.
_EX4_TS = 9
_EX4_S = 6
_EX4_SNR = 2.0
#: Exercise 3's requirement (the claim's criterion constants).
_EX3_MAX_PFA = 1e-4
_EX3_MIN_PDA = 0.9
_EX3_LOG10_PF = -2.5
_EX3_TS = 6  # not Fig. 1's T_S = 4, whose needed P_D the notebook prints


def _settings() -> dict:
    from eotrack.experiments.track_init_ht import paper_settings

    return paper_settings()


def _p_da_reference(p_d_pixels, p_f: float, w_s: int, s: int) -> float:
    """Exact P_DA with per-pixel target probabilities (``w_s`` = number of window pixels)."""
    return float(hyp.area_detection_pixels(np.asarray(p_d_pixels, dtype=float), p_f,
                                           math.isqrt(int(w_s)), s))


def _ex1_inputs() -> list[tuple]:
    # unequal pixels (a binomial with their mean is wrong), one equal case, the edge cases
    # S = 1 and S above the target's pixel count, a 3 x 3 window (S >= 1, the question's domain)
    return [((0.9, 0.5, 0.5, 0.2), 0.003, 25, 3), ((0.98, 0.6, 0.6, 0.6, 0.6, 0.2, 0.2, 0.2,
                                                     0.2), 0.03, 25, 7),
            ((0.3, 0.3, 0.3, 0.3), 0.003, 25, 2), ((0.7, 0.1), 0.05, 9, 3),
            ((0.99, 0.01, 0.5), 0.01, 25, 1), ((0.8, 0.4, 0.4), 0.02, 25, 5),
            ((1.0, 0.0, 0.5, 0.25, 0.75), 0.1, 49, 4)]


def _ex2_expected() -> int:
    return int(hyp.clustering_threshold(_EX2_PF, _EX2_WINDOW, _EX2_MAX_PFA))


def _ex3_expected() -> float:
    """Smallest SNR at which some S has P_FA <= 1e-4 and exact P_DA >= 0.9 (5x5, T_S = 6)."""
    p_f = 10.0 ** _EX3_LOG10_PF
    window = _settings()["fig1_window"]
    s_min = hyp.clustering_threshold(p_f, window, _EX3_MAX_PFA)

    def need(s: int) -> float:
        f = lambda snr: hyp.area_detection_exact(hyp.snr_to_pd(snr, p_f), p_f, window,  # noqa: E731
                                                 _EX3_TS, s) - _EX3_MIN_PDA
        return brentq(f, 0.0, 30.0) if f(30.0) > 0 else np.inf

    return float(min(need(s) for s in range(s_min, window * window + 1)))


def _ex3_grid() -> float:
    """The answer on the panel's 0.1 SNR grid: the smallest grid value that meets the
    requirement (rounding the exact SNR down would give a value that does not)."""
    return math.ceil(round(_ex3_expected() * 10, 9)) / 10


def _ex4_expected() -> float:
    ps = _settings()
    p_f = ps["fig1_p_f"]
    return float(hyp.area_detection_exact(hyp.snr_to_pd(_EX4_SNR, p_f), p_f, ps["fig1_window"],
                                          _EX4_TS, _EX4_S))


#: Exercise 5's setting (not the notebook's 5 x 5 window, whose P_1 is printed): a 7 x 7 window.
_EX5_WINDOW = 7


def _ex5_expected() -> float:
    ps = _settings()
    # P_1 = P_D + P_0 exceeds 1 when P_D > 1 - P_0, and P_0 is P_1 at P_D = 0
    return 1.0 - float(hyp.p1_paper(0.0, ps["cfar_p_f"], _EX5_WINDOW, ps["curved_size_px"] ** 2))


register("track_init_ht.1", FunctionAnswer(
    "Derivation: a real spot is brighter at its centre, so target pixel i is suspicious with its "
    "own probability p_i. Show that the count D in a window is then a Poisson-binomial "
    "sum of Bernoulli(p_i) plus Bin(W_S - T_S, P_F), and write p_da(p_d_pixels, p_f, w_s, s) "
    "returning the exact P(D >= S) for S >= 1 (p_d_pixels: the T_S probabilities; w_s = number of pixels).",
    reference=_p_da_reference, inputs=_ex1_inputs, rtol=1e-6, atol=1e-12,
    hint="build the pmf of the target count pixel by pixel (np.convolve with [1 - p_i, p_i]), "
         "then condition on it: the W_S - T_S noise pixels must supply at least S - k "
         "(binom.sf(S - k - 1, ...)). A binomial with the mean p_i is not the same count.",
    expects="a function p_da(p_d_pixels, p_f, w_s, s)"))

register("track_init_ht.2", NumericAnswer(
    f"Computation: a sensor segments at P_F = {_EX2_PF:g} and clusters in a "
    f"{_EX2_WINDOW}x{_EX2_WINDOW} window. What is the smallest threshold S whose area "
    f"false-alarm probability P_FA (eq. 4, D >= S) is at most {_EX2_MAX_PFA:g}?",
    expected=_ex2_expected, rtol=0.0, atol=1e-9,
    hint="the window has W_S = side**2 pixels; P_FA falls as S grows: evaluate eq. (4) for "
         "S = 1, 2, ... and take the first S at or below the requirement (D >= S, not D > S).",
    expects="an integer S"))

#: Rounding slack below the exact threshold SNR (3.148 for 3.1477 is a rounding, 3.145 is wrong).
_EX3_ROUND_SLACK = 5e-4


class _SnrThresholdAnswer(NumericAnswer):
    """Right if the SNR meets the requirement and is not above the grid answer: the grid value
    itself, or an off-grid value in [exact threshold, grid value] (rounding slack below)."""

    def judge(self, answer: float) -> bool:
        exact, grid = _ex3_expected(), _ex3_grid()
        return bool(exact - _EX3_ROUND_SLACK <= answer <= grid + 1e-9)


register("track_init_ht.3", _SnrThresholdAnswer(
    f"Exploration: in the Explore panel set log10 P_F = -2.5, window 5x5, T_S = {_EX3_TS}. Raise the "
    "SNR in steps of 0.1: what is the smallest SNR on that grid at which some S gives "
    "P_FA <= 1e-4 and an EXACT P_DA >= 0.9?",
    expected=_ex3_grid, rtol=0.0, atol=0.0,
    hint="P_FA <= 1e-4 fixes the smallest admissible S (left panel, black curve); at that S "
         "move the SNR slider until the exact curve reaches 0.9 at that S — read the title's "
         "'exact P_DA' and check it is really >= 0.9, not just close.",
    expects="an SNR (a number)"))

register("track_init_ht.4", NumericAnswer(
    f"Critique (eq. 7): at Fig. 1's window and P_F (W_S = 25, P_F = 0.003) and SNR "
    f"{_EX4_SNR:g}, take a 3x3 target (T_S = {_EX4_TS}) and S = {_EX4_S}. Compute the exact "
    "P_DA (the count is Bin(T_S, P_D) + Bin(W_S - T_S, P_F)) and compare it with eq. (7).",
    expected=_ex4_expected, rtol=0.02,
    hint="P_D from the SNR link Q(Q^-1(P_F) - SNR); condition on k, the number of detected "
         "target pixels: the noise pixels must supply at least S - k. Eq. (7) is far larger.",
    expects="a probability"))

register("track_init_ht.5", NumericAnswer(
    f"Critique (eq. 6): with the experiment's P_F = 0.03 and 3x3 target (T_S = 9) but a "
    f"{_EX5_WINDOW}x{_EX5_WINDOW} window (not the notebook's 5x5), above which per-pixel detection probability P_D does eq. (6), "
    "P_1 = P_D + 1 - (1 - P_F)^(W_S - T_S), exceed 1?",
    expected=_ex5_expected, rtol=5e-3,
    hint="set P_1 = 1 in eq. (6) and solve for P_D; (1 - P_F)^(W_S - T_S) is the chance that "
         "none of the W_S - T_S noise pixels fires.",
    expects="a probability"))
