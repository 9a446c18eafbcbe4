"""Closed-form performance of spatial clustering and temporal hypothesis testing.

Li Z.Z., Peng S.J., Jin G., Dong N.L., *Track initiation for dim small moving targets based on
hypothesis testing*, Acta Photonica Sinica 37(3), 2008, eqs. (4)–(13).

Two tests act on a binary (thresholded) image sequence:

* **spatial clustering** — count the suspicious pixels ``D`` in a ``window × window`` box
  (``W_S = window²`` pixels) and flag the box when ``D ≥ S``;
* **temporal continuity** — follow a candidate through ``T`` frames in a ``gate × gate``
  association region (``M = gate²`` pixels) and accept it as a track with ``≥ T_h`` hits.

Every count here is a binomial tail, evaluated with :data:`scipy.stats.binom` (``binom.sf``), never
with a hand-written sum. All functions broadcast over array-valued probabilities and thresholds
(``p_f``, ``p_d``, ``s``, ``min_hits``) and return a ``float`` when every input is a scalar.

Conventions adopted (see the notebook's errata):

* the spatial test is ``D ≥ S`` (text and eqs. 4/7), not ``D > S`` as eq. (2) prints;
* eq. (6) ``P_1 = P_D + P_{0,W_S−T_S}`` can exceed 1; :func:`area_detection` clips it to 1
  (``p1_paper`` returns the unclipped value) and :func:`area_detection_exact` gives the exact count,
  a sum of ``Binomial(T_S, P_D)`` and ``Binomial(W_S − T_S, P_F)``;
* the SNR → P_D link the paper leaves implicit is Gaussian noise with a threshold set by P_F:
  ``P_D = Q(Q⁻¹(P_F) − SNR)`` (:func:`snr_to_pd`);
* a real spot's pixels differ: :func:`area_detection_pixels` is the exact count with one
  probability per target pixel (Poisson-binomial plus binomial).

Operating range (held-out tests in ``tests/unit/test_hypothesis.py``, ``test_cfar.py``,
``test_neighbourhood.py``, on scenes the paper did not use):

* the formulas are exact for independent pixels (Monte Carlo agreement on 5 × 5 and 7 × 7
  windows, equal and unequal target pixels);
* on CFAR-segmented images eq. (4) at the *measured* ``P_F`` holds for the first tail points
  (``S ≤ 2``); further out it holds only if the background/noise estimate is good (global or
  coarse tiles): with 16-px tiles at ``P_F`` = 0.003 the ``S = 3`` tail is about twice eq. (4),
  because the threshold errs together over a tile; correlated clutter does the same (the
  reproduction's ``P_FA`` table);
* eqs. (9), (12), (13) assume a gate that stays on its target. With the nearest-neighbour
  initiator (``TemporalContinuityInitiator``, gate centred on the last point until three hits)
  a target is followed only if it moves at most about ``n_k`` px per frame **on each axis**
  (gate ``2 n_k + 1``; the gate is square, so the limit is on ``|v_x|`` and ``|v_y|``
  separately, not on the speed): with the paper's 3 × 3 gate 1 px/frame is tracked and
  3 px/frame is lost; a 5 × 5 gate tracks (2.4, 1.8) px/frame (speed 3 along a diagonal) and
  2 px/frame along an axis, but loses 3 px/frame along an axis. Among dense false alarms (``P_F`` ≳ 0.03 in the gate) the gate is lured
  away, so the true-track rate falls below eq. (13).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.stats import binom, norm

from eotrack.validation import as_finite_array, check_int

__all__ = [
    "area_detection",
    "area_detection_exact",
    "area_detection_pixels",
    "area_false_alarm",
    "clustering_threshold",
    "p1_paper",
    "sequence_detection",
    "snr_to_pd",
    "track_detection",
    "track_false_alarm",
]


# --------------------------------------------------------------------------- validation helpers
def _prob(value: Any, name: str) -> np.ndarray:
    """``value`` as a float array of probabilities in [0, 1]."""
    if isinstance(value, bool):
        raise TypeError(f"{name} must be a real number or array of them, got bool")
    arr = as_finite_array(value, name)
    if np.any((arr < 0) | (arr > 1)):
        bad = arr[(arr < 0) | (arr > 1)].ravel()[0]
        raise ValueError(f"{name} must lie in [0, 1], got {bad!r}")
    # subnormal probabilities overflow scipy's binomial pmf; they are 0 to double precision
    return np.where(arr < 1e-290, 0.0, arr)


def _ints(value: Any, name: str, *, lo: int, hi: int | None = None,
          hi_name: str | None = None) -> np.ndarray:
    """``value`` as an integer array within ``[lo, hi]``."""
    if isinstance(value, bool):
        raise TypeError(f"{name} must be an integer or array of integers, got bool")
    arr = np.asarray(value)
    if arr.dtype.kind not in "iu":
        if arr.dtype.kind == "f" and np.all(np.isfinite(arr)) and np.all(arr == np.round(arr)):
            arr = arr.astype(int)
        else:
            raise TypeError(f"{name} must be an integer or array of integers, got {value!r}")
    if np.any(arr < lo):
        raise ValueError(f"{name} must be >= {lo}, got {arr[arr < lo].ravel()[0]}")
    if hi is not None and np.any(arr > hi):
        what = f"{hi_name} = {hi}" if hi_name else str(hi)
        raise ValueError(f"{name} must be <= {what}, got {arr[arr > hi].ravel()[0]}")
    return arr.astype(int)


def _odd_size(value: Any, name: str) -> int:
    """A positive odd window side length (``2p + 1``)."""
    v = check_int(value, name, min_value=1)
    if v % 2 == 0:
        raise ValueError(f"{name} must be a positive odd side length 2p+1 (1, 3, 5, ...), got {v}")
    return v


def _out(x: np.ndarray, *inputs: Any) -> float | np.ndarray:
    """A float if every input was a scalar, else the array."""
    if all(np.ndim(v) == 0 for v in inputs):
        return float(np.asarray(x).reshape(()))
    return np.asarray(x, dtype=float)


def _tail(k_min: np.ndarray, n: int | np.ndarray, p: np.ndarray) -> np.ndarray:
    """``P(Binomial(n, p) ≥ k_min)`` via ``binom.sf``."""
    return binom.sf(k_min - 1, n, p)


# --------------------------------------------------------------------------- SNR link
def snr_to_pd(snr: Any, p_f: Any) -> float | np.ndarray:
    """Per-pixel detection probability for a threshold set by the false-alarm rate.

    ``P_D = Q(Q⁻¹(P_F) − SNR)`` with ``Q`` the standard normal tail: Gaussian noise of unit
    variance, threshold ``Q⁻¹(P_F)``, target amplitude ``SNR`` (the link the paper leaves
    implicit; adopted in the digest).

    Parameters
    ----------
    snr
        Target amplitude over the noise standard deviation (≥ 0; scalar or array).
    p_f
        Per-pixel false-alarm probability in [0, 1].

    Returns
    -------
    float or numpy.ndarray
        ``P_D`` (broadcast over the inputs).
    """
    s = as_finite_array(snr, "snr")
    if np.any(s < 0):
        raise ValueError(f"snr must be >= 0, got {s[s < 0].ravel()[0]}")
    pf = _prob(p_f, "p_f")
    return _out(norm.sf(norm.isf(pf) - s), snr, p_f)


# --------------------------------------------------------------------------- spatial clustering
def area_false_alarm(p_f: Any, window: int, s: Any) -> float | np.ndarray:
    """Eq. (4): probability that a noise-only window holds at least ``S`` suspicious pixels.

    ``P_FA = Σ_{t=S}^{W_S} C(W_S, t) P_F^t (1 − P_F)^{W_S − t}`` with ``W_S = window²``.

    Parameters
    ----------
    p_f
        Per-pixel false-alarm probability in [0, 1].
    window
        Side ``2p + 1`` of the square neighbourhood (positive odd integer).
    s
        Count threshold ``S`` (integer, ``0 ≤ S ≤ W_S``; scalar or array).

    Returns
    -------
    float or numpy.ndarray
        ``P_FA``.
    """
    pf = _prob(p_f, "p_f")
    w = _odd_size(window, "window")
    n = w * w
    ss = _ints(s, "s", lo=0, hi=n, hi_name="W_S = window**2")
    return _out(_tail(ss, n, pf), p_f, s)


def clustering_threshold(p_f: Any, window: int, max_pfa: Any) -> int | np.ndarray:
    """Smallest clustering threshold ``S`` whose area false-alarm probability is at most ``max_pfa``.

    Inverts eq. (4): ``min {S : P(Binomial(W_S, P_F) ≥ S) ≤ max_pfa}``. ``P_FA`` falls with ``S``,
    so this is the most permissive threshold (the best detection) that meets the false-alarm
    requirement. If even ``S = W_S`` (every pixel of the window suspicious) has ``P_FA`` above
    ``max_pfa``, no threshold meets it and ``W_S + 1`` is returned (the test never fires).

    Parameters
    ----------
    p_f
        Per-pixel false-alarm probability in [0, 1] (scalar or array).
    window
        Side ``2p + 1`` of the square neighbourhood (positive odd integer).
    max_pfa
        Required area false-alarm probability in (0, 1] (scalar or array, broadcast with
        ``p_f``).

    Returns
    -------
    int or numpy.ndarray
        ``S`` (an ``int`` when both inputs are scalars).

    Examples
    --------
    >>> clustering_threshold(0.003, 5, 1e-4)
    3
    """
    pf = _prob(p_f, "p_f")
    w = _odd_size(window, "window")
    q = _prob(max_pfa, "max_pfa")
    if np.any(q <= 0):
        raise ValueError("max_pfa must be > 0 (P_FA = 0 needs S > W_S: the test never fires)")
    n = w * w
    s = np.arange(n + 1).reshape((-1,) + (1,) * np.broadcast(pf, q).ndim)
    ok = _tail(s, n, pf) <= q  # (n + 1, ...): P_FA falls with S, so ok is monotone in S
    first = np.where(ok.any(axis=0), np.argmax(ok, axis=0), n + 1)
    if np.ndim(p_f) == 0 and np.ndim(max_pfa) == 0:
        return int(first)
    return first.astype(int)


def p1_paper(p_d: Any, p_f: Any, window: int, target_pixels: int) -> float | np.ndarray:
    """Eqs. (5)–(6) as printed: ``P_1 = P_D + 1 − (1 − P_F)^{W_S − T_S}`` (may exceed 1).

    Parameters
    ----------
    p_d, p_f
        Per-pixel detection and false-alarm probabilities in [0, 1].
    window
        Side of the square neighbourhood (positive odd integer).
    target_pixels
        ``T_S``, pixels covered by the target (``1 ≤ T_S ≤ W_S``).

    Returns
    -------
    float or numpy.ndarray
        The unclipped ``P_1`` of the paper.
    """
    pd = _prob(p_d, "p_d")
    pf = _prob(p_f, "p_f")
    w = _odd_size(window, "window")
    ts = check_int(target_pixels, "target_pixels", min_value=1, max_value=w * w)
    p0 = 1.0 - (1.0 - pf) ** (w * w - ts)
    return _out(pd + p0, p_d, p_f)


def area_detection(p_d: Any, p_f: Any, window: int, target_pixels: int,
                   s: Any) -> float | np.ndarray:
    """Eqs. (5)–(7), the paper's area detection probability.

    ``P_DA = Σ_{t=S}^{W_S} C(W_S, t) P_1^t (1 − P_1)^{W_S − t}`` with
    ``P_1 = P_D + P_{0,W_S−T_S}`` (eq. 6) clipped to 1 where the printed sum exceeds 1 (see
    :func:`p1_paper`). This is the paper's heuristic: it gives every one of the ``W_S`` pixels the
    probability ``P_1``; :func:`area_detection_exact` is the exact count.

    Parameters
    ----------
    p_d, p_f
        Per-pixel detection and false-alarm probabilities in [0, 1].
    window
        Side of the square neighbourhood (positive odd integer).
    target_pixels
        ``T_S`` (``1 ≤ T_S ≤ W_S``).
    s
        Count threshold ``S`` (``0 ≤ S ≤ W_S``).

    Returns
    -------
    float or numpy.ndarray
        ``P_DA`` (eq. 7).
    """
    p1 = np.minimum(np.asarray(p1_paper(p_d, p_f, window, target_pixels)), 1.0)
    n = int(window) ** 2
    ss = _ints(s, "s", lo=0, hi=n, hi_name="W_S = window**2")
    return _out(_tail(ss, n, p1), p_d, p_f, s)


def area_detection_exact(p_d: Any, p_f: Any, window: int, target_pixels: int,
                         s: Any) -> float | np.ndarray:
    """Exact area detection probability under the paper's pixel model.

    The count in a window that holds the target is ``Binomial(T_S, P_D) + Binomial(W_S − T_S,
    P_F)`` (independent pixels), so ``P(D ≥ S) = Σ_k b(k; T_S, P_D) · P(Binomial(W_S − T_S, P_F)
    ≥ S − k)`` — a vectorised product of ``binom.pmf`` and ``binom.sf``.

    Parameters
    ----------
    p_d, p_f
        Per-pixel detection and false-alarm probabilities in [0, 1].
    window
        Side of the square neighbourhood (positive odd integer).
    target_pixels
        ``T_S`` (``1 ≤ T_S ≤ W_S``).
    s
        Count threshold ``S`` (``0 ≤ S ≤ W_S``).

    Returns
    -------
    float or numpy.ndarray
        ``P(D ≥ S)``.
    """
    pd = _prob(p_d, "p_d")
    pf = _prob(p_f, "p_f")
    w = _odd_size(window, "window")
    n = w * w
    ts = check_int(target_pixels, "target_pixels", min_value=1, max_value=n)
    ss = _ints(s, "s", lo=0, hi=n, hi_name="W_S = window**2")
    pd_b, pf_b, s_b = np.broadcast_arrays(pd, pf, ss)
    k = np.arange(ts + 1).reshape((-1,) + (1,) * pd_b.ndim)
    terms = binom.pmf(k, ts, pd_b) * _tail(s_b - k, n - ts, pf_b)
    return _out(np.clip(terms.sum(axis=0), 0.0, 1.0), p_d, p_f, s)


def area_detection_pixels(p_d_pixels: Any, p_f: Any, window: int, s: Any) -> float | np.ndarray:
    """Exact area detection probability when the target's pixels differ (a spot, not a box).

    A real spot (eq. 1) is brighter at its centre: target pixel ``i`` is suspicious with its own
    probability ``p_i``. The count is then a Poisson-binomial ``Σ_i Bernoulli(p_i)`` plus
    ``Binomial(W_S − T_S, P_F)``: the target pmf is the convolution of the ``T_S`` two-point
    pmfs (built pixel by pixel, ``T_S ≤ W_S`` steps), shifted onto the noise pmf of every distinct
    ``P_F`` at once, and the tail ``P(D ≥ S)`` is summed from the small end. With every ``p_i``
    equal it is :func:`area_detection_exact`.

    Parameters
    ----------
    p_d_pixels
        1-D sequence of the ``T_S`` target pixels' detection probabilities, each in [0, 1]
        (``1 ≤ T_S ≤ W_S``).
    p_f
        Per-pixel false-alarm probability of the noise pixels in [0, 1] (scalar or array).
    window
        Side of the square neighbourhood (positive odd integer).
    s
        Count threshold ``S`` (``0 ≤ S ≤ W_S``; scalar or array, broadcast against ``p_f``).

    Returns
    -------
    float or numpy.ndarray
        ``P(D ≥ S)``.

    Raises
    ------
    ValueError
        ``p_d_pixels`` empty, not 1-D, outside [0, 1] or longer than ``W_S``; ``s`` outside
        ``[0, W_S]``; ``window`` not a positive odd integer.
    """
    pix = _prob(p_d_pixels, "p_d_pixels")
    if pix.ndim != 1 or pix.size == 0:
        raise ValueError(f"p_d_pixels must be a non-empty 1-D sequence, got shape {pix.shape}")
    pf = _prob(p_f, "p_f")
    w = _odd_size(window, "window")
    n = w * w
    ts = pix.size
    if ts > n:
        raise ValueError(f"p_d_pixels has {ts} pixels, more than W_S = window**2 = {n}")
    ss = _ints(s, "s", lo=0, hi=n, hi_name="W_S = window**2")
    pmf = np.zeros(ts + 1)
    pmf[0] = 1.0
    for i, p in enumerate(pix):  # T_S <= W_S steps of a vectorised two-point convolution
        pmf[1:i + 2] = pmf[1:i + 2] * (1 - p) + pmf[:i + 1] * p
        pmf[0] *= 1 - p
    pf_b, s_b = np.broadcast_arrays(pf, ss)
    uniq, inv = np.unique(pf_b.ravel(), return_inverse=True)
    noise = binom.pmf(np.arange(n - ts + 1)[None, :], n - ts, uniq[:, None])  # (u, W_S-T_S+1)
    d_pmf = np.zeros((uniq.size, n + 1))
    for k in range(ts + 1):  # pmf of D = target count + noise count, one shift per k
        d_pmf[:, k:k + n - ts + 1] += pmf[k] * noise
    tail = d_pmf[:, ::-1].cumsum(axis=1)[:, ::-1]  # P(D >= j), summed from the small end
    out = tail[inv, s_b.ravel()].reshape(pf_b.shape)
    return _out(np.clip(out, 0.0, 1.0), p_f, s)


# --------------------------------------------------------------------------- temporal continuity
def _temporal_args(gate: int, frames: int, min_hits: Any) -> tuple[int, int, np.ndarray]:
    g = _odd_size(gate, "gate")
    t = check_int(frames, "frames", min_value=1)
    th = _ints(min_hits, "min_hits", lo=0, hi=t, hi_name="frames (T)")
    return g * g, t, th


def track_false_alarm(p_f: Any, gate: int, frames: int, min_hits: Any) -> float | np.ndarray:
    """Eqs. (8)–(9): probability that a noise-only track passes the temporal test.

    ``P_{0,T} = 1 − (1 − P_F)^M`` is the chance that the ``M = gate²`` association region holds a
    false alarm in one frame; ``P_FT = P(Binomial(T, P_{0,T}) ≥ T_h)``.

    Parameters
    ----------
    p_f
        Per-pixel (candidate) false-alarm probability in [0, 1].
    gate
        Side ``2 n_k + 1`` of the association region (positive odd integer).
    frames
        ``T``, number of frames in the test (≥ 1).
    min_hits
        ``T_h``, hits needed (``0 ≤ T_h ≤ T``).

    Returns
    -------
    float or numpy.ndarray
        ``P_FT``.
    """
    pf = _prob(p_f, "p_f")
    m, t, th = _temporal_args(gate, frames, min_hits)
    p0 = 1.0 - (1.0 - pf) ** m
    return _out(_tail(th, t, p0), p_f, min_hits)


def sequence_detection(p_d: Any, p_f: Any, gate: int, frames: int,
                       min_hits: Any) -> float | np.ndarray:
    """Eqs. (10)–(12): probability that a track through the target passes the temporal test.

    The gate holds something (target, or one of the other ``M − 1`` pixels a false alarm) with
    probability ``P_{1,T} = P_D + (1 − P_D)(1 − (1 − P_F)^{M−1})``;
    ``P_DS = P(Binomial(T, P_{1,T}) ≥ T_h)``.

    Parameters
    ----------
    p_d, p_f
        Per-frame target detection and per-pixel false-alarm probabilities in [0, 1].
    gate
        Side of the association region (positive odd integer).
    frames
        ``T`` (≥ 1).
    min_hits
        ``T_h`` (``0 ≤ T_h ≤ T``).

    Returns
    -------
    float or numpy.ndarray
        ``P_DS``.
    """
    pd = _prob(p_d, "p_d")
    pf = _prob(p_f, "p_f")
    m, t, th = _temporal_args(gate, frames, min_hits)
    p0 = 1.0 - (1.0 - pf) ** (m - 1)
    p1 = pd + (1.0 - pd) * p0
    return _out(_tail(th, t, p1), p_d, p_f, min_hits)


def track_detection(p_d: Any, frames: int, min_hits: Any) -> float | np.ndarray:
    """Eq. (13): probability that the target itself is detected in at least ``T_h`` of ``T`` frames.

    ``P_DT = P(Binomial(T, P_D) ≥ T_h)``.

    Parameters
    ----------
    p_d
        Per-frame target detection probability in [0, 1].
    frames
        ``T`` (≥ 1).
    min_hits
        ``T_h`` (``0 ≤ T_h ≤ T``).

    Returns
    -------
    float or numpy.ndarray
        ``P_DT``.
    """
    pd = _prob(p_d, "p_d")
    t = check_int(frames, "frames", min_value=1)
    th = _ints(min_hits, "min_hits", lo=0, hi=t, hi_name="frames (T)")
    return _out(_tail(th, t, pd), p_d, min_hits)
