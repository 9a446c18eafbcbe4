"""Monte Carlo trials of Li et al. (2008): Figs. 1–2 (pixel and gate models) and the initiator.

* :func:`fig1_monte_carlo` — windows of Gaussian pixels thresholded at ``Q⁻¹(P_F)``, counted
  (eqs. 4–7 and the exact count);
* :func:`fig2_monte_carlo` — the association-gate model of eqs. (8)–(13);
* :func:`initiator_monte_carlo` — the temporal-test initiator itself on short lattice sequences.

Each result keeps its estimates and trial count; ``result.agreement(...)`` compares them with
the closed forms by :func:`eotrack.montecarlo.mc_agreement` (binomial intervals).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from scipy.stats import norm

from eotrack.montecarlo import Agreement, TrialRunner, mc_agreement, run_trials
from eotrack.tracking import hypothesis as hyp
from eotrack.tracking.initiation.temporal import TemporalContinuityInitiator, TemporalTestConfig

from .scenario import CONFIDENCE

__all__ = [
    "Fig1Result",
    "Fig2Result",
    "fig1_monte_carlo",
    "fig2_monte_carlo",
    "initiator_monte_carlo",
]

def _fig1_trial(rng: np.random.Generator, snrs: tuple[float, ...], p_f: float, window: int,
                target_pixels: int, n_windows: int) -> np.ndarray:
    """One batch: histograms of the count D (rows: noise only, then each SNR)."""
    n_pix = window * window
    thr = norm.isf(p_f)
    out = np.zeros((len(snrs) + 1, n_pix + 1), dtype=np.int64)
    noise = rng.standard_normal((n_windows, n_pix))
    out[0] = np.bincount((noise > thr).sum(axis=1), minlength=n_pix + 1)
    for i, snr in enumerate(snrs):
        x = rng.standard_normal((n_windows, n_pix))
        x[:, :target_pixels] += snr  # uniform-amplitude target pixels (the paper's model)
        out[i + 1] = np.bincount((x > thr).sum(axis=1), minlength=n_pix + 1)
    return out


@dataclass
class Fig1Result:
    """Fig. 1 curves (formulas) and Monte Carlo estimates."""

    s: np.ndarray
    snr: list[float]
    p_d: np.ndarray
    p1: np.ndarray
    pfa: np.ndarray
    pda_paper: np.ndarray  # (n_snr, n_s)
    pda_exact: np.ndarray
    mc_pfa: np.ndarray
    mc_pda: np.ndarray
    mc_n_noise: int
    mc_n_target: int
    settings: dict = field(default_factory=dict)

    def agreement(self, which: str = "exact", *, s_max: int = 12,
                  confidence: float = CONFIDENCE, familywise: bool = False,
                  method: str = "wilson") -> Agreement:
        """Monte Carlo against a closed form for ``S ≤ s_max`` (binomial intervals).

        ``which``: ``"pfa"`` (eq. 4, noise windows), ``"exact"`` (the exact count) or
        ``"paper"`` (eq. 7), the last two over every SNR. ``familywise=True``: Bonferroni
        intervals (each at ``1 − (1 − confidence)/m``), so a correct formula fails with
        probability at most ``1 − confidence`` over all ``m`` points. ``method``: ``"wilson"``
        or ``"clopper-pearson"`` (exact coverage; the claims use it, because the Wilson lower
        bound undercovers far in the tail: one event where ``n p`` ≈ 0.03 falls outside it).
        """
        sel = self.s <= s_max
        if which == "pfa":
            mc, formula, n = self.mc_pfa[sel], self.pfa[sel], self.mc_n_noise
        elif which in ("exact", "paper"):
            formula = (self.pda_exact if which == "exact" else self.pda_paper)[:, sel]
            mc, n = self.mc_pda[:, sel], self.mc_n_target
        else:
            raise ValueError(f"which must be 'pfa', 'exact' or 'paper', got {which!r}")
        return mc_agreement(np.rint(mc * n), n, formula, confidence=confidence,
                            familywise=familywise, method=method)

    def table(self) -> pd.DataFrame:
        """Long table: S, SNR, formulas and Monte Carlo."""
        rows = []
        for j, snr in enumerate(self.snr):
            for i, s in enumerate(self.s):
                rows.append({"SNR": snr, "S": int(s), "P_FA eq.4": self.pfa[i],
                             "P_FA MC": self.mc_pfa[i], "P_DA eq.7 (paper)": self.pda_paper[j, i],
                             "P_DA exact": self.pda_exact[j, i], "P_DA MC": self.mc_pda[j, i]})
        return pd.DataFrame(rows)


def fig1_monte_carlo(*, snr: list[float], p_f: float, window: int, target_pixels: int,
                     n_noise: int, n_target: int, seed: int | np.random.SeedSequence = 1,
                     runner: TrialRunner | None = None) -> Fig1Result:
    """Fig. 1 from eqs. (4)–(7) and the exact count, with a pixel-level Monte Carlo.

    The Monte Carlo draws unit Gaussian noise in ``window²`` pixels, adds ``SNR`` to
    ``target_pixels`` of them, thresholds at ``Q⁻¹(P_F)`` and counts — so it also checks the SNR →
    P_D link. ``n_noise`` noise-only windows, ``n_target`` windows per SNR (rounded to batches).
    """
    n_pix = window * window
    s = np.arange(1, n_pix + 1)
    batch = 50_000
    n_b = max(1, int(np.ceil(max(n_noise, n_target) / batch)))
    hist = np.sum(run_trials(_fig1_trial, n_b, seed=seed, runner=runner,
                             args=(tuple(snr), p_f, window, target_pixels, batch),
                             desc="Fig. 1 Monte Carlo"), axis=0)
    n = n_b * batch
    tail = hist[:, ::-1].cumsum(axis=1)[:, ::-1][:, 1:] / n  # P(D >= S) for S = 1..n_pix
    p_d = np.asarray(hyp.snr_to_pd(np.asarray(snr), p_f))
    return Fig1Result(
        s=s, snr=list(snr), p_d=p_d,
        p1=np.asarray(hyp.p1_paper(p_d, p_f, window, target_pixels)),
        pfa=np.asarray(hyp.area_false_alarm(p_f, window, s)),
        pda_paper=np.array([hyp.area_detection(pd, p_f, window, target_pixels, s)
                            for pd in p_d]),
        pda_exact=np.array([hyp.area_detection_exact(pd, p_f, window, target_pixels, s)
                            for pd in p_d]),
        mc_pfa=tail[0], mc_pda=tail[1:], mc_n_noise=n, mc_n_target=n,
        settings={"window": window, "target_pixels": target_pixels, "p_f": p_f})


# ---------------------------------------------------------------- Fig. 2
def _fig2_trial(rng: np.random.Generator, p_f: np.ndarray, p_d: np.ndarray, gate: int,
                frames: int, n: int) -> np.ndarray:
    """One batch of the gate model: histograms of hits in T frames.

    Returns ``(3, n_pf, T + 1)``: target gate (target or any of the other M − 1 pixels), target
    only, noise-only gate (M pixels).
    """
    m = gate * gate
    out = np.zeros((3, len(p_f), frames + 1), dtype=np.int64)
    for i, (pf, pdi) in enumerate(zip(p_f, p_d)):
        tgt = rng.random((n, frames)) < pdi
        other = (rng.random((n, frames, m - 1)) < pf).any(axis=2)
        noise = (rng.random((n, frames, m)) < pf).any(axis=2)
        out[0, i] = np.bincount((tgt | other).sum(axis=1), minlength=frames + 1)
        out[1, i] = np.bincount(tgt.sum(axis=1), minlength=frames + 1)
        out[2, i] = np.bincount(noise.sum(axis=1), minlength=frames + 1)
    return out


@dataclass
class Fig2Result:
    """Fig. 2 curves (eqs. 9, 12, 13) and Monte Carlo estimates over P_F × T_h."""

    p_f: np.ndarray
    t_h: np.ndarray
    p_d: np.ndarray
    pds: np.ndarray  # (n_th, n_pf)
    pdt: np.ndarray
    pft: np.ndarray
    mc_pds: np.ndarray
    mc_pdt: np.ndarray
    mc_pft: np.ndarray
    mc_n: int
    settings: dict = field(default_factory=dict)

    def agreement(self, which: str, *, confidence: float = CONFIDENCE,
                  familywise: bool = False, method: str = "wilson") -> Agreement:
        """Monte Carlo against eq. (12) ``"pds"``, eq. (13) ``"pdt"`` or eq. (9) ``"pft"``
        (``familywise``: Bonferroni intervals over the curve's points; ``method`` as in
        :meth:`Fig1Result.agreement`)."""
        pairs = {"pds": (self.mc_pds, self.pds), "pdt": (self.mc_pdt, self.pdt),
                 "pft": (self.mc_pft, self.pft)}
        if which not in pairs:
            raise ValueError(f"which must be one of {sorted(pairs)}, got {which!r}")
        mc, formula = pairs[which]
        return mc_agreement(np.rint(mc * self.mc_n), self.mc_n, formula, confidence=confidence,
                            familywise=familywise, method=method)


def fig2_monte_carlo(*, snr: float, gate: int, frames: int, p_f: np.ndarray, n: int,
                     seed: int | np.random.SeedSequence = 2,
                     runner: TrialRunner | None = None) -> Fig2Result:
    """Fig. 2 from eqs. (8)–(13) with a Monte Carlo of the association-gate model."""
    p_f = np.asarray(p_f, dtype=float)
    p_d = np.asarray(hyp.snr_to_pd(snr, p_f))
    t_h = np.arange(1, frames + 1)
    batch = 5_000
    n_b = max(1, int(np.ceil(n / batch)))
    hist = np.sum(run_trials(_fig2_trial, n_b, seed=seed, runner=runner,
                             args=(p_f, p_d, gate, frames, batch), desc="Fig. 2 Monte Carlo"),
                  axis=0)
    nn = n_b * batch
    tail = hist[..., ::-1].cumsum(axis=2)[..., ::-1][..., 1:] / nn  # (3, n_pf, T) for T_h=1..T
    th = t_h[:, None]
    return Fig2Result(
        p_f=p_f, t_h=t_h, p_d=p_d,
        pds=np.asarray(hyp.sequence_detection(p_d[None], p_f[None], gate, frames, th)),
        pdt=np.asarray(hyp.track_detection(p_d[None], frames, th)),
        pft=np.asarray(hyp.track_false_alarm(p_f[None], gate, frames, th)),
        mc_pds=tail[0].T, mc_pdt=tail[1].T, mc_pft=tail[2].T, mc_n=nn,
        settings={"snr": snr, "gate": gate, "frames": frames})


# ---------------------------------------------------------------- initiator vs formulas
def _initiator_trial(rng: np.random.Generator, p_d: float, p_f: float, gate: int, frames: int,
                     min_hits: int, n_seq: int, region: int) -> np.ndarray:
    """Batch of short sequences for :func:`initiator_monte_carlo`: counts (containing, pure)."""
    ini = TemporalContinuityInitiator(TemporalTestConfig(gate=gate, frames=frames,
                                                         min_hits=min_hits, predict="last"))
    c = region // 2
    out = np.zeros(2, dtype=np.int64)
    for _ in range(n_seq):
        fa = rng.random((frames, region, region)) < p_f
        det = rng.random(frames) < p_d
        fa[:, c, c] = False  # the target pixel holds the target or nothing
        seq, is_tgt = [], []
        for k in range(frames):
            yy, xx = np.nonzero(fa[k])
            xy = np.column_stack([xx, yy]).astype(float)
            flag = np.zeros(len(xy), dtype=bool)
            if det[k]:
                xy = np.vstack([xy, [c, c]])
                flag = np.append(flag, True)
            seq.append((float(k), xy))
            is_tgt.append(flag)
        tracks = ini.initiate(seq)
        on = [[is_tgt[f][d] for f, d in tr.hits] for tr in tracks]
        out[0] += any(any(h) for h in on)
        out[1] += any(sum(h) >= min_hits for h in on)
    return out


def initiator_monte_carlo(*, snr: float, p_f: np.ndarray, gate: int, frames: int,
                          min_hits: int, n: int, region: int = 15,
                          seed: int | np.random.SeedSequence = 5,
                          runner: TrialRunner | None = None) -> pd.DataFrame:
    """The temporal-test initiator itself against eqs. (12)–(13).

    ``n`` sequences of ``T`` frames per ``P_F``: a stationary target at the centre of a
    ``region × region`` lattice, detected with ``P_D`` (SNR link) per frame, Bernoulli false
    alarms with ``P_F`` on the other pixels. Measured: the probability that a confirmed track
    contains the target (compare ``P_DS``) and that one holds ``≥ T_h`` target points (compare
    ``P_DT``). With nothing but the target, both equal ``P_DT`` exactly; false alarms in the gate
    can both complete a target track (``P_DS``) and lure the gate away from the target.
    """
    rows = []
    batch = 100
    n_b = max(1, int(np.ceil(n / batch)))
    for i, pf in enumerate(np.asarray(p_f, dtype=float)):
        pdv = float(hyp.snr_to_pd(snr, pf))
        sub = (seed + 100 * i if not isinstance(seed, np.random.SeedSequence) else
               np.random.SeedSequence(seed.entropy, spawn_key=(*seed.spawn_key, i)))
        cnt = np.sum(run_trials(_initiator_trial, n_b, seed=sub, runner=runner,
                                args=(pdv, float(pf), gate, frames, min_hits, batch, region),
                                desc=f"initiator P_F {pf:g}"), axis=0)
        nn = n_b * batch
        rows.append({"P_F": float(pf), "P_D": pdv,
                     "track containing the target": cnt[0] / nn,
                     "P_DS eq.12": float(hyp.sequence_detection(pdv, pf, gate, frames, min_hits)),
                     "track with >= T_h target points": cnt[1] / nn,
                     "P_DT eq.13": float(hyp.track_detection(pdv, frames, min_hits)),
                     "sequences": nn})
    return pd.DataFrame(rows)
