"""Li et al. (2008): track initiation for dim small targets by spatial clustering and temporal
hypothesis testing — Figs. 1–2 from the closed forms with Monte Carlo checks, and the
image-sequence experiment (Figs. 3–7) on simulated deep-space sequences.

The paper's settings are read from ``papers_repro/track_init_ht/claims.toml``; everything else
is computed. Entry point: :func:`reproduce`.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from scipy.stats import norm

from eotrack.imaging.dim_targets import (
    DimSequence,
    DimSequenceConfig,
    DimTarget,
    curved_path,
    fwhm_to_sigma,
    peak_snr_for_pixel_pd,
    simulate_dim_sequence,
    straight_path,
)
from eotrack.imaging.neighbourhood import candidate_frames, neighbourhood_count
from eotrack.montecarlo import TrialRunner, run_trials
from eotrack.plotting import get_ax
from eotrack.repro import ClaimResult, Reproduction, Status, load_claims
from eotrack.tracking import hypothesis as hyp
from eotrack.tracking.initiation.base import Frame, Track
from eotrack.tracking.initiation.temporal import TemporalContinuityInitiator, TemporalTestConfig

__all__ = [
    "SLUG",
    "TITLE",
    "Fig1Result",
    "Fig2Result",
    "SequenceSettings",
    "fig1_monte_carlo",
    "fig2_monte_carlo",
    "initiator_monte_carlo",
    "match_tracks",
    "paper_settings",
    "plot_fig1",
    "plot_fig2",
    "plot_initiator_vs_formulas",
    "plot_measured_vs_formula",
    "plot_sequence_panels",
    "plot_snr_sweep",
    "reproduce",
    "run_sequence",
    "sequence_experiment",
    "snr_sweep",
    "wilson_interval",
]

SLUG = "track_init_ht"
TITLE = ("Li Z.Z., Peng S.J., Jin G., Dong N.L., *Track initiation for dim small moving targets "
         "based on hypothesis testing*, Acta Photonica Sinica 37(3):613–616, 2008")

#: Criterion constants of ``track_init.li_fig1`` (ours, stated in claims.toml's criterion).
LOW_PFA = 1e-4
HIGH_PDA = 0.9
FAIL_PDA = 0.5
#: Two-sided z of the 99.9 % Monte Carlo interval.
Z_999 = float(norm.isf(0.0005))


def paper_settings() -> dict[str, Any]:
    """The paper's settings, from claims.toml (single source of the paper's numbers)."""
    c = load_claims(SLUG)
    f1 = c["track_init.li_fig1"].paper
    f2 = c["track_init.li_fig2"].paper
    ex = c["track_init.li_experiment"].paper
    return {
        "fig1_window": round(float(np.sqrt(f1["window_pixels_W_S"]))),
        "fig1_target_pixels": int(f1["target_pixels_T_S"]),
        "fig1_p_f": float(f1["p_f"]),
        "fig1_snr": [float(s) for s in f1["snr"]],
        "fig2_snr": float(f2["snr"]),
        "fig2_gate": int(f2["gate_M"][0]),
        "frames_T": int(ex["frames_T"]),
        "min_hits_T_h": int(ex["min_hits_T_h"]),
        "n_frames": int(ex["n_frames"]),
        "cfar_p_f": float(ex["cfar_p_f"]),
        "cfar_p_d": float(ex["cfar_p_d"]),
        "window": int(ex["window_W_S"][0]),
        "s": int(ex["threshold_S"]),
        "gate": int(ex["gate_M"][0]),
        "curved_snr": float(ex["curved_target_snr"]),
        "curved_size_px": int(ex["curved_target_size_px"][0]),
        "curved_frames": int(ex["curved_target_frames"]),
    }


def wilson_interval(k: np.ndarray, n: np.ndarray | int, z: float = Z_999) -> tuple[np.ndarray,
                                                                                   np.ndarray]:
    """Wilson score interval of a binomial proportion ``k / n`` (vectorised)."""
    k = np.asarray(k, dtype=float)
    n = np.asarray(n, dtype=float)
    p = k / n
    den = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / den
    half = z * np.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / den
    return np.clip(centre - half, 0, 1), np.clip(centre + half, 0, 1)


# =============================================================================== Fig. 1
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
                     n_noise: int, n_target: int, seed: int = 1,
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


def plot_fig1(res: Fig1Result, *, s_max: int = 12, ax: plt.Axes | None = None) -> plt.Axes:
    """Fig. 1: P_FA and P_DA versus S (lines: formulas; markers: Monte Carlo)."""
    ax = get_ax(ax, figsize=(7.5, 4.6))
    sel = res.s <= s_max
    s = res.s[sel]
    ax.semilogy(s, res.pfa[sel], "k-", lw=2, label="$P_{FA}$ eq. (4)")
    ok = res.mc_pfa[sel] > 0
    ax.plot(s[ok], res.mc_pfa[sel][ok], "kx", ms=7, label="$P_{FA}$ Monte Carlo")
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for j, snr in enumerate(res.snr):
        c = colors[j % len(colors)]
        ax.semilogy(s, res.pda_paper[j, sel], "-", color=c,
                    label=f"$P_{{DA}}$ eq. (7), SNR {snr:g}")
        ax.semilogy(s, res.pda_exact[j, sel], "--", color=c, label=f"exact count, SNR {snr:g}")
        ok = res.mc_pda[j, sel] > 0
        ax.plot(s[ok], res.mc_pda[j, sel][ok], "o", mfc="none", color=c, ms=5)
    ax.plot([], [], "o", mfc="none", color="gray", label="Monte Carlo (pixels)")
    ax.set_ylim(1e-9, 2)
    ax.set_xlabel("clustering threshold S")
    ax.set_ylabel("probability")
    w = res.settings
    ax.set_title(f"Fig. 1 — W_S = {w['window'] ** 2}, T_S = {w['target_pixels']}, "
                 f"P_F = {w['p_f']:g}")
    ax.legend(fontsize=7, ncol=2, loc="lower left")
    return ax


def _fig1_readings(res: Fig1Result, pda: np.ndarray) -> dict[str, Any]:
    """The paper's readings of Fig. 1 evaluated on one family of P_DA curves."""
    pfa = res.pfa
    ok_s = pfa <= LOW_PFA
    best = [float(pda[j, ok_s].max()) if ok_s.any() else 0.0 for j in range(len(res.snr))]
    return {
        "pfa_decreasing": bool(np.all(np.diff(pfa) < 0) or np.all(np.diff(pfa[pfa > 0]) < 0)),
        "pda_nonincreasing_in_S": bool(np.all(np.diff(pda, axis=1) <= 1e-15)),
        "pda_increasing_in_snr": bool(np.all(np.diff(pda, axis=0) >= -1e-15)),
        "pda_ge_pfa": bool(np.all(pda >= pfa - 1e-15)),
        "best_pda_at_low_pfa": best,
    }


# =============================================================================== Fig. 2
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


def fig2_monte_carlo(*, snr: float, gate: int, frames: int, p_f: np.ndarray, n: int,
                     seed: int = 2, runner: TrialRunner | None = None) -> Fig2Result:
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


def plot_fig2(res: Fig2Result, *, t_h: tuple[int, ...] = (3, 4, 5, 6),
              ax: plt.Axes | None = None) -> plt.Axes:
    """Fig. 2: P_DS (solid) and P_DT (dashed) versus P_F for several T_h; markers Monte Carlo."""
    ax = get_ax(ax, figsize=(7.0, 4.4))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for c, th in zip(colors, t_h):
        i = int(th) - 1
        ax.semilogx(res.p_f, res.pds[i], "-", color=c, label=f"$P_{{DS}}$, $T_h$ = {th}")
        ax.semilogx(res.p_f, res.pdt[i], "--", color=c, label=f"$P_{{DT}}$, $T_h$ = {th}")
        ax.plot(res.p_f, res.mc_pds[i], "o", mfc="none", color=c, ms=4)
        ax.plot(res.p_f, res.mc_pdt[i], "s", mfc="none", color=c, ms=4)
    ax.plot([], [], "o", mfc="none", color="gray", label="Monte Carlo")
    st = res.settings
    ax.set_xlabel("single-frame false-alarm probability $P_F$")
    ax.set_ylabel("probability")
    ax.set_title(f"Fig. 2 — SNR {st['snr']:g}, M = {st['gate']}×{st['gate']}, "
                 f"T = {st['frames']}")
    ax.legend(fontsize=7, ncol=2)
    return ax


def _mc_agrees(mc: np.ndarray, formula: np.ndarray, n: int) -> tuple[bool, float]:
    """Whether every formula value lies in the 99.9 % Wilson interval of its estimate."""
    lo, hi = wilson_interval(np.asarray(mc) * n, n)
    inside = (formula >= lo - 1e-12) & (formula <= hi + 1e-12)
    return bool(np.all(inside)), float(np.mean(inside))


# =============================================================================== initiator vs formulas
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
                          min_hits: int, n: int, region: int = 15, seed: int = 5,
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
        cnt = np.sum(run_trials(_initiator_trial, n_b, seed=seed + 100 * i, runner=runner,
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


def plot_initiator_vs_formulas(df: pd.DataFrame, *, ax: plt.Axes | None = None) -> plt.Axes:
    """The initiator's measured track probabilities beside eqs. (12)–(13)."""
    ax = get_ax(ax, figsize=(6.0, 3.8))
    ax.semilogx(df["P_F"], df["P_DS eq.12"], "C1-", label="$P_{DS}$ eq. (12)")
    ax.semilogx(df["P_F"], df["track containing the target"], "C1o", mfc="none",
                label="initiator: a track contains the target")
    ax.semilogx(df["P_F"], df["P_DT eq.13"], "C2--", label="$P_{DT}$ eq. (13)")
    ax.semilogx(df["P_F"], df["track with >= T_h target points"], "C2s", mfc="none",
                label="initiator: a track holds $\\geq T_h$ target points")
    ax.set_xlabel("single-frame $P_F$")
    ax.set_ylabel("probability")
    ax.set_title("The temporal-test initiator against eqs. (12)-(13)")
    ax.legend(fontsize=7)
    return ax


# =============================================================================== sequences
@dataclass(frozen=True)
class SequenceSettings:
    """The image-sequence experiment (paper values from claims.toml; scene ours, see notes).

    The paper gives neither its scene nor the main target's SNR and size: we adopt a 256 × 256
    sequence with a fluctuating background (clutter 3× the white noise), a main target of 3 × 3
    pixels (FWHM 3 px) whose peak SNR is solved so that CFAR detects its 3 × 3 core with the
    paper's ``P_D = 0.98``, moving on a straight line, and the curved target of SNR 2, 3 × 3
    pixels, over 30 frames.
    """

    shape: tuple[int, int] = (256, 256)
    n_frames: int = 50
    p_f: float = 0.03
    p_d: float = 0.98
    window: int = 5
    s: int = 7
    gate: int = 3
    frames: int = 7
    min_hits: int = 5
    size_px: int = 3
    curved_snr: float = 2.0
    curved_frames: int = 30
    curved_first: int = 10
    main_start: tuple[float, float] = (50.0, 70.0)
    main_velocity: tuple[float, float] = (0.6, 0.35)
    curved_centre: tuple[float, float] = (170.0, 150.0)
    curved_radius: float = 45.0
    curved_phase: float = -1.2
    curved_rate: float = 0.035
    noise_sigma: float = 10.0
    clutter_sigma: float = 30.0
    clutter_scale_px: float = 24.0
    jitter_px: float = 0.25
    include_main: bool = True
    tile: int = 16

    @property
    def sigma_px(self) -> float:
        """Spot width δ of a target whose FWHM is ``size_px``."""
        return fwhm_to_sigma(self.size_px)

    @property
    def main_snr(self) -> float:
        """Peak SNR of the main target (3 × 3 core detected with mean rate ``p_d``)."""
        return peak_snr_for_pixel_pd(self.p_d, self.p_f, self.sigma_px, self.size_px)

    def scene(self) -> DimSequenceConfig:
        """The scene of one run."""
        targets = []
        if self.include_main:
            targets.append(DimTarget(straight_path(self.main_start, self.main_velocity,
                                                   self.n_frames),
                                     snr=self.main_snr, sigma_px=self.sigma_px))
        n_c = min(self.curved_frames, self.n_frames - self.curved_first)
        if n_c > 0:
            targets.append(DimTarget(curved_path(self.curved_centre, self.curved_radius,
                                                 self.curved_phase, self.curved_rate, n_c),
                                     snr=self.curved_snr, sigma_px=self.sigma_px,
                                     first_frame=self.curved_first))
        return DimSequenceConfig(shape=self.shape, n_frames=self.n_frames,
                                 noise_sigma=self.noise_sigma, clutter_sigma=self.clutter_sigma,
                                 clutter_scale_px=self.clutter_scale_px,
                                 jitter_px=self.jitter_px, targets=tuple(targets))

    def temporal(self) -> TemporalTestConfig:
        """The temporal-test configuration."""
        return TemporalTestConfig(gate=self.gate, frames=self.frames, min_hits=self.min_hits)


def match_tracks(tracks: list[Track], frames: list[tuple[float, np.ndarray]],
                 truth_xy: np.ndarray, radius_px: float = 2.5
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Assign tracks to targets.

    A track belongs to target ``i`` if at least half its hits lie within ``radius_px`` of the
    target's true position in their frame.

    Returns
    -------
    owner : numpy.ndarray
        ``(n_tracks,)`` target index or −1 (false track).
    coverage : numpy.ndarray
        ``(n_targets,)`` fraction of each target's frames with a matching hit in one of its tracks
        (a track broken into segments still covers its frames).
    segments : numpy.ndarray
        ``(n_targets,)`` number of tracks assigned to each target.
    """
    n_t = truth_xy.shape[0]
    owner = np.full(len(tracks), -1)
    covered = np.zeros(truth_xy.shape[:2], dtype=bool)
    alive = np.isfinite(truth_xy[..., 0]).sum(axis=1)
    for ti, tr in enumerate(tracks):
        f = np.array(tr.frame_indices)
        p = np.array([frames[a][1][b] for a, b in tr.hits]).reshape(-1, 2)
        d = np.linalg.norm(p[None] - truth_xy[:, f], axis=2)  # (n_targets, n_hits)
        close = np.nan_to_num(d, nan=np.inf) <= radius_px
        frac = close.mean(axis=1)
        best = int(np.argmax(frac))
        if frac[best] >= 0.5:
            owner[ti] = best
            covered[best, f[close[best]]] = True
    coverage = covered.sum(axis=1) / np.maximum(alive, 1)
    segments = np.bincount(owner[owner >= 0], minlength=n_t)
    return owner, coverage, segments


def run_sequence(rng: np.random.Generator, st: SequenceSettings, keep: bool = False
                 ) -> dict[str, Any]:
    """One run of the image-sequence experiment: simulate, segment, cluster, test; measure.

    Returns a dict of counts (for pooled probabilities) and track outcomes; with ``keep`` also
    the sequence, the binary and clustered stacks, candidate frames and tracks.
    """
    seq: DimSequence = simulate_dim_sequence(st.scene(), rng)
    frames, g, clus = candidate_frames(seq.images, seq.times_s, st.p_f, st.window, st.s,
                                       tile=st.tile, keep_masks=True)
    ini = TemporalContinuityInitiator(st.temporal())
    tracks = ini.initiate(frames)
    truth = seq.truth_xy
    n_tg, n_fr = truth.shape[:2]
    h, w = st.shape
    yy, xx = np.mgrid[0:h, 0:w]
    # pixels far (> 6 px) from every target in each frame, and inside the border
    p = st.window // 2
    bg = np.zeros((n_fr, h, w), dtype=bool)
    bg[:, p:h - p, p:w - p] = True
    near_path = np.zeros((h, w), dtype=bool)
    for k in range(n_fr):
        for i in range(n_tg):
            if np.isfinite(truth[i, k, 0]):
                near = (np.abs(xx - truth[i, k, 0]) <= 6) & (np.abs(yy - truth[i, k, 1]) <= 6)
                bg[k] &= ~near
                near_path |= near
    d = neighbourhood_count(g, st.window)
    n_pix = st.window ** 2
    out: dict[str, Any] = {
        "bg_pixels": int(bg.sum()), "bg_detected": int(g[bg].sum()),
        "bg_clustered": int(clus[bg].sum()),
        "d_hist": np.bincount(d[bg], minlength=n_pix + 1),
    }
    # --- per target: pixel P_D over the 3x3 core, P_DA at the true pixel, candidate hits
    cand_hit = np.zeros((n_tg, n_fr), dtype=bool)
    any_in_gate = np.zeros((n_tg, n_fr), dtype=bool)
    alive = np.isfinite(truth[..., 0])
    core = np.arange(st.size_px) - st.size_px // 2
    pix_det = np.zeros(n_tg)
    pix_n = np.zeros(n_tg)
    area_det = np.zeros(n_tg)
    half = st.gate // 2 + 0.5
    for i in range(n_tg):
        for k in np.flatnonzero(alive[i]):
            cx, cy = np.rint(truth[i, k]).astype(int)
            if not (p <= cx < w - p and p <= cy < h - p):
                continue
            pix_det[i] += g[k][np.ix_(cy + core, cx + core)].sum()
            pix_n[i] += st.size_px ** 2
            area_det[i] += d[k, cy, cx] >= st.s
            xy = frames[k][1]
            if len(xy):
                dd = np.abs(xy - truth[i, k])
                cand_hit[i, k] = bool(np.any(np.hypot(*dd.T) <= 1.5))
                gate_c = np.array([cx, cy])
                any_in_gate[i, k] = bool(np.any((np.abs(xy - gate_c) <= half).all(axis=1)))
    out["target_pix_det"] = pix_det
    out["target_pix_n"] = pix_n
    out["target_area_det"] = area_det
    out["target_frames"] = alive.sum(axis=1)
    out["target_cand_hits"] = cand_hit.sum(axis=1)
    # sliding windows of T frames over each target's life: hits >= T_h ?
    win = st.frames
    hist_t = np.zeros((n_tg, win + 1), dtype=np.int64)
    hist_s = np.zeros((n_tg, win + 1), dtype=np.int64)
    for i in range(n_tg):
        idx = np.flatnonzero(alive[i])
        if len(idx) >= win:
            c = np.convolve(cand_hit[i, idx].astype(int), np.ones(win, int), "valid")
            hist_t[i] = np.bincount(c, minlength=win + 1)
            c = np.convolve(any_in_gate[i, idx].astype(int), np.ones(win, int), "valid")
            hist_s[i] = np.bincount(c, minlength=win + 1)
    out["pdt_hist"] = hist_t
    out["pds_hist"] = hist_s
    # --- fixed-gate temporal test on the candidate maps away from the targets (eq. 9)
    cmap = np.zeros((n_fr, h, w), dtype=np.uint8)
    for k, (_, xy) in enumerate(frames):
        if len(xy):
            r = np.clip(np.rint(xy).astype(int), 0, [w - 1, h - 1])
            cmap[k, r[:, 1], r[:, 0]] = 1
    far = ~near_path
    far[:p] = far[h - p:] = False
    far[:, :p] = far[:, w - p:] = False
    out["cand_pixels"] = int(far.sum() * n_fr)
    out["cand_false"] = int(cmap[:, far].sum())
    gate_hit = neighbourhood_count(cmap, st.gate)[:, far] > 0  # (T, n_far)
    cs = np.concatenate([np.zeros((1, gate_hit.shape[1]), int), gate_hit.cumsum(axis=0)])
    counts = cs[win:] - cs[:-win]  # (n_windows, n_far)
    out["pft_hist"] = np.bincount(counts.ravel(), minlength=win + 1)
    # --- the initiator's tracks
    owner, coverage, segments = match_tracks(tracks, frames, truth)
    out["coverage"] = coverage
    out["segments"] = segments
    out["n_false_tracks"] = int(np.sum(owner < 0))
    out["n_tracks"] = len(tracks)
    out["confirmed_at"] = [int(tr.confirmed_at) for tr in tracks]
    out["owner"] = owner
    out["hypotheses"] = ini.stats["hypotheses"]
    out["candidates_per_frame"] = float(np.mean([len(xy) for _, xy in frames]))
    if keep:
        out.update(seq=seq, binary=g, clustered=clus, frames=frames, tracks=tracks)
    return out


def _sequence_trial(rng: np.random.Generator, st: SequenceSettings) -> dict[str, Any]:
    return run_sequence(rng, st, keep=False)


def sequence_experiment(st: SequenceSettings, n_runs: int, *, seed: int = 3,
                        runner: TrialRunner | None = None) -> dict[str, Any]:
    """Run ``n_runs`` sequences and pool the measurements against eqs. (4), (7), (9), (12), (13).

    Returns
    -------
    dict
        ``runs`` (per-run dicts), ``table`` (measured vs formula), ``pfa_table``, ``pft_table``,
        and the summary numbers used by the scorecard.
    """
    runs = run_trials(_sequence_trial, n_runs, seed=seed, runner=runner, args=(st,),
                      desc="image sequences")
    n_pix = st.window ** 2
    p_f = sum(r["bg_detected"] for r in runs) / sum(r["bg_pixels"] for r in runs)
    removed = 1 - sum(r["bg_clustered"] for r in runs) / max(1, sum(r["bg_detected"]
                                                                     for r in runs))
    d_hist = np.sum([r["d_hist"] for r in runs], axis=0)
    n_bg = d_hist.sum()
    s_all = np.arange(1, n_pix + 1)
    pfa_meas = d_hist[::-1].cumsum()[::-1][1:] / n_bg
    pfa_tab = pd.DataFrame({"S": s_all, "P_FA measured": pfa_meas,
                            "P_FA eq.4 (measured P_F)": hyp.area_false_alarm(p_f, st.window,
                                                                           s_all)})
    pfa_tab = pfa_tab[pfa_tab["S"] <= st.s + 2].reset_index(drop=True)
    # target rows (0 = main, 1 = curved when include_main)
    names = (["main (straight)"] if st.include_main else []) + [f"curved, SNR {st.curved_snr:g}"]
    pix_pd = np.sum([r["target_pix_det"] for r in runs], axis=0) / np.maximum(
        np.sum([r["target_pix_n"] for r in runs], axis=0), 1)
    pda = np.sum([r["target_area_det"] for r in runs], axis=0) / np.maximum(
        np.sum([r["target_frames"] for r in runs], axis=0), 1)
    cand_pd = np.sum([r["target_cand_hits"] for r in runs], axis=0) / np.maximum(
        np.sum([r["target_frames"] for r in runs], axis=0), 1)
    pdt_hist = np.sum([r["pdt_hist"] for r in runs], axis=0)
    pds_hist = np.sum([r["pds_hist"] for r in runs], axis=0)
    p_cand = sum(r["cand_false"] for r in runs) / sum(r["cand_pixels"] for r in runs)
    pft_hist = np.sum([r["pft_hist"] for r in runs], axis=0)
    t_h = np.arange(1, st.frames + 1)
    pft_meas = pft_hist[::-1].cumsum()[::-1][1:] / pft_hist.sum()
    pft_tab = pd.DataFrame({"T_h": t_h, "P_FT measured (fixed gate)": pft_meas,
                            "P_FT eq.9 (measured candidate P_F)":
                                hyp.track_false_alarm(p_cand, st.gate, st.frames, t_h)})
    ts = st.size_px ** 2
    rows = []
    for i, name in enumerate(names):
        tot = pdt_hist[i].sum()
        pdt_m = pdt_hist[i, st.min_hits:].sum() / tot if tot else np.nan
        pds_m = pds_hist[i, st.min_hits:].sum() / tot if tot else np.nan
        rows.append({
            "target": name,
            "pixel P_D (3x3 core)": pix_pd[i],
            "P_DA measured": pda[i],
            "P_DA eq.7 (paper)": hyp.area_detection(pix_pd[i], p_f, st.window, ts, st.s),
            "P_DA exact": hyp.area_detection_exact(pix_pd[i], p_f, st.window, ts, st.s),
            "candidate P_D": cand_pd[i],
            "P_DT measured": pdt_m,
            "P_DT eq.13": hyp.track_detection(cand_pd[i], st.frames, st.min_hits),
            "P_DS measured": pds_m,
            "P_DS eq.12": hyp.sequence_detection(cand_pd[i], p_cand, st.gate, st.frames,
                                                 st.min_hits),
            "recovered runs": float(np.mean([r["coverage"][i] >= 0.5 for r in runs])),
            "mean coverage": float(np.mean([r["coverage"][i] for r in runs])),
            "tracks per target": float(np.mean([r["segments"][i] for r in runs])),
        })
    return {
        "runs": runs, "p_f": p_f, "removed": removed, "p_cand": p_cand,
        "table": pd.DataFrame(rows), "pfa_table": pfa_tab, "pft_table": pft_tab,
        "false_tracks": [r["n_false_tracks"] for r in runs],
        "candidates_per_frame": float(np.mean([r["candidates_per_frame"] for r in runs])),
        "main_snr": st.main_snr,
    }


def snr_sweep(st: SequenceSettings, snrs: list[float], n_runs: int, *, seed: int = 4,
              runner: TrialRunner | None = None) -> pd.DataFrame:
    """Recovery of the curved target versus its SNR (curved target alone, 128 × 128 crop)."""
    rows = []
    for j, snr in enumerate(snrs):
        sub = replace(st, shape=(128, 128), include_main=False, curved_snr=float(snr),
                      n_frames=st.curved_first + st.curved_frames,
                      curved_centre=(st.curved_centre[0] - 110, st.curved_centre[1] - 85))
        runs = run_trials(_sequence_trial, n_runs, seed=seed + 1000 * j, runner=runner,
                          args=(sub,), desc=f"SNR {snr:g}")
        cov = np.array([r["coverage"][0] for r in runs])
        fr = np.array([r["target_frames"][0] for r in runs])
        rows.append({"SNR": float(snr),
                     "P_DA measured": float(np.sum([r["target_area_det"][0] for r in runs])
                                            / fr.sum()),
                     "recovered (coverage >= 0.5)": float(np.mean(cov >= 0.5)),
                     "mean coverage": float(cov.mean()),
                     "false tracks / run": float(np.mean([r["n_false_tracks"] for r in runs])),
                     "runs": n_runs})
    return pd.DataFrame(rows)


# =============================================================================== plots
def plot_sequence_panels(run: dict[str, Any], frame: int, *, fig: plt.Figure | None = None
                         ) -> plt.Figure:
    """Figs. 3–6 and 7: raw frame, CFAR segmentation, clustering, track image, curved track."""
    seq: DimSequence = run["seq"]
    fig = fig or plt.figure(figsize=(13, 8.2))
    axs = fig.subplots(2, 3)
    truth = seq.truth_xy
    im = seq.images[frame]
    lo, hi = np.percentile(im, [1, 99.5])
    axs[0, 0].imshow(im, vmin=lo, vmax=hi)
    for i in range(truth.shape[0]):
        if np.isfinite(truth[i, frame, 0]):
            axs[0, 0].add_patch(plt.Circle(truth[i, frame], 7, fill=False, ec="w"))
    axs[0, 0].set_title(f"Fig. 3 — frame {frame} (targets circled)")
    axs[0, 1].imshow(run["binary"][frame], interpolation="nearest")
    axs[0, 1].set_title(f"Fig. 4 — CFAR segmentation ({int(run['binary'][frame].sum())} px)")
    axs[0, 2].imshow(run["clustered"][frame], interpolation="nearest")
    axs[0, 2].set_title(f"Fig. 5 — clustered ({int(run['clustered'][frame].sum())} px)")
    acc = run["clustered"].max(axis=0)
    fr_objs = [Frame(t, xy) for t, xy in run["frames"]]
    axs[1, 0].imshow(acc, interpolation="nearest")
    axs[1, 0].set_title("clustered points, all frames")
    ax = axs[1, 1]
    ax.imshow(np.zeros_like(acc), vmin=0, vmax=1)
    owner = run["owner"]
    for tr, o in zip(run["tracks"], owner):
        p = tr.positions(fr_objs)
        ax.plot(p[:, 0], p[:, 1], "-", lw=1.5, color="w" if o >= 0 else "r")
    ax.set_xlim(0, acc.shape[1])
    ax.set_ylim(acc.shape[0], 0)
    ax.set_title(f"Fig. 6 — confirmed tracks ({int(np.sum(owner >= 0))} target, "
                 f"{int(np.sum(owner < 0))} false in red)")
    ax = axs[1, 2]
    for i in range(truth.shape[0]):
        ax.plot(truth[i, :, 0], truth[i, :, 1], ":", color="gray", lw=1)
    for tr, o in zip(run["tracks"], owner):
        p = tr.positions(fr_objs)
        ax.plot(p[:, 0], p[:, 1], ".-", ms=3, label=f"track of target {o}" if o >= 0
                else "false track")
    ax.set_xlim(0, acc.shape[1])
    ax.set_ylim(acc.shape[0], 0)
    ax.set_aspect("equal")
    ax.set_title("Fig. 7 — tracks (dotted: truth)")
    ax.legend(fontsize=7)
    for a in axs.ravel():
        a.set_xticks([])
        a.set_yticks([])
    fig.tight_layout()
    return fig


def plot_measured_vs_formula(exp: dict[str, Any], *, ax: plt.Axes | None = None) -> plt.Axes:
    """Measured P_FA(S) and P_FT(T_h) on the sequences beside eqs. (4) and (9)."""
    ax = get_ax(ax, figsize=(6.4, 4.0))
    t = exp["pfa_table"]
    ax.semilogy(t["S"], t["P_FA eq.4 (measured P_F)"], "k-", label="$P_{FA}$ eq. (4) vs S")
    m = t["P_FA measured"] > 0
    ax.semilogy(t["S"][m], t["P_FA measured"][m], "ko", mfc="none", label="measured vs S")
    f = exp["pft_table"]
    ax.semilogy(f["T_h"], f["P_FT eq.9 (measured candidate P_F)"], "C3-",
                label="$P_{FT}$ eq. (9) vs $T_h$")
    m = f["P_FT measured (fixed gate)"] > 0
    ax.semilogy(f["T_h"][m], f["P_FT measured (fixed gate)"][m], "C3s", mfc="none",
                label="measured vs $T_h$")
    ax.set_ylim(1e-12, 1.5)
    ax.set_xlabel("S (clustering) or $T_h$ (temporal)")
    ax.set_ylabel("probability")
    ax.set_title("Sequences: measured false-alarm rates vs formulas")
    ax.legend(fontsize=7)
    return ax


def plot_snr_sweep(df: pd.DataFrame, *, ax: plt.Axes | None = None) -> plt.Axes:
    """Recovery of the curved target versus SNR."""
    ax = get_ax(ax, figsize=(5.5, 3.6))
    ax.plot(df["SNR"], df["recovered (coverage >= 0.5)"], "o-", label="recovered runs")
    ax.plot(df["SNR"], df["P_DA measured"], "s--", label="per-frame $P_{DA}$")
    ax.set_xlabel("peak SNR of the curved 3×3 target")
    ax.set_ylabel("fraction")
    ax.set_ylim(-0.03, 1.03)
    ax.set_title("Fig. 7 target: recovery versus SNR")
    ax.legend(fontsize=8)
    return ax


# =============================================================================== reproduce
def reproduce(*, quick: bool = False, runner: TrialRunner | None = None) -> Reproduction:
    """Run Figs. 1–2 and the sequence experiment; score the three claims."""
    ps = paper_settings()
    claims = load_claims(SLUG)
    n_noise = 200_000 if quick else 2_000_000
    n_target = n_noise
    n_fig2 = 10_000 if quick else 100_000
    n_seq = 2 if quick else 8
    n_sweep = 3 if quick else 8
    n_init = 200 if quick else 2000
    # ---------------------------------------------------------------- Fig. 1
    f1 = fig1_monte_carlo(snr=ps["fig1_snr"], p_f=ps["fig1_p_f"], window=ps["fig1_window"],
                          target_pixels=ps["fig1_target_pixels"], n_noise=n_noise,
                          n_target=n_target, runner=runner)
    r_paper = _fig1_readings(f1, f1.pda_paper)
    r_exact = _fig1_readings(f1, f1.pda_exact)
    s_chk = f1.s <= 12
    ok_exact, frac_exact = _mc_agrees(f1.mc_pda[:, s_chk], f1.pda_exact[:, s_chk], f1.mc_n_target)
    ok_pfa, _ = _mc_agrees(f1.mc_pfa[s_chk], f1.pfa[s_chk], f1.mc_n_noise)
    _, frac_paper = _mc_agrees(f1.mc_pda[:, s_chk], f1.pda_paper[:, s_chk],
                                      f1.mc_n_target)

    def readings_hold(r: dict) -> bool:
        b = r["best_pda_at_low_pfa"]
        snr = ps["fig1_snr"]
        good = all(b[j] >= HIGH_PDA for j, s in enumerate(snr) if s >= 2)
        bad = all(b[j] < FAIL_PDA for j, s in enumerate(snr) if s < 2)
        return (r["pfa_decreasing"] and r["pda_nonincreasing_in_S"]
                and r["pda_increasing_in_snr"] and r["pda_ge_pfa"] and good and bad)

    hold_paper, hold_exact = readings_hold(r_paper), readings_hold(r_exact)
    bp = ", ".join(f"SNR {s:g}: {v:.3f}" for s, v in zip(ps["fig1_snr"],
                                                         r_paper["best_pda_at_low_pfa"]))
    be = ", ".join(f"SNR {s:g}: {v:.3g}" for s, v in zip(ps["fig1_snr"],
                                                         r_exact["best_pda_at_low_pfa"]))
    ours1 = (f"eqs. (4)/(7) readings hold: {hold_paper}; best P_DA with P_FA <= {LOW_PFA:g}: "
             f"{bp}. Exact count: {be}. Monte Carlo ({f1.mc_n_target:,} windows per SNR) agrees "
             f"with the exact count at {frac_exact:.0%} of S<=12 points (P_FA: {ok_pfa}) and with "
             f"eq. (7) at {frac_paper:.0%}")
    if hold_paper and hold_exact and ok_exact and ok_pfa:
        st1, note1 = Status.REPRODUCED, ""
    elif hold_paper and ok_exact and ok_pfa:
        st1 = Status.PARTIAL
        note1 = (f"Fig. 1 as printed (eqs. 4, 7) shows every reading. But eq. (6) gives all "
                 f"W_S pixels the probability P_1 = P_D + P_0 (P_1 = "
                 f"{', '.join(f'{v:.3f}' for v in f1.p1)}), and the Monte Carlo of the stated "
                 f"pixel model follows the exact count, not eq. (7): with T_S = 4 target pixels "
                 f"the best P_DA at P_FA <= {LOW_PFA:g} is only {be} — the 'SNR 2-3 works' "
                 f"reading does not survive the exact count.")
    else:
        st1 = Status.NOT_REPRODUCED
        note1 = (f"readings (paper formulas) hold: {hold_paper}; Monte Carlo agrees with exact: "
                 f"{ok_exact}, P_FA: {ok_pfa}")
    res1 = ClaimResult.from_claim(claims["track_init.li_fig1"], ours=ours1, status=st1,
                                  note=note1)
    # ---------------------------------------------------------------- Fig. 2
    p_f_grid = np.logspace(-4, -1, 13)
    f2 = fig2_monte_carlo(snr=ps["fig2_snr"], gate=ps["fig2_gate"], frames=ps["frames_T"],
                          p_f=p_f_grid, n=n_fig2, runner=runner)
    ge = bool(np.all(f2.pds >= f2.pdt - 1e-15))
    gap = f2.pds - f2.pdt  # (T_h, P_F)
    closes = bool(np.all(np.diff(gap, axis=1) >= -1e-12))
    peak_pf = f2.p_f[np.argmax(gap, axis=1)]
    gap_low = float(gap[:, 0].max())
    ok_ds, fr_ds = _mc_agrees(f2.mc_pds, f2.pds, f2.mc_n)
    ok_dt, fr_dt = _mc_agrees(f2.mc_pdt, f2.pdt, f2.mc_n)
    ok_ft, fr_ft = _mc_agrees(f2.mc_pft, f2.pft, f2.mc_n)
    i_th = ps["min_hits_T_h"] - 1
    ours2 = (f"P_DS >= P_DT everywhere: {ge}; gap P_DS - P_DT at T_h = {ps['min_hits_T_h']}: "
             f"{gap[i_th, -1]:.3f} at P_F = {p_f_grid[-1]:g}, peak {gap[i_th].max():.3f} at "
             f"P_F = {peak_pf[i_th]:.2g}, {gap[i_th, 0]:.1e} at P_F = {p_f_grid[0]:g} (largest "
             f"over T_h at P_F = {p_f_grid[0]:g}: {gap_low:.1e}); monotone in P_F for every T_h: "
             f"{closes}; Monte Carlo ({f2.mc_n:,} tracks per P_F) inside the 99.9 % interval of "
             f"eqs. (12)/(13)/(9) at {fr_ds:.0%}/{fr_dt:.0%}/{fr_ft:.0%} of points")
    if ge and closes and ok_ds and ok_dt and ok_ft:
        st2, note2 = Status.REPRODUCED, ""
    elif ge and ok_ds and ok_dt and ok_ft and gap_low < 0.01:
        st2 = Status.PARTIAL
        note2 = ("P_DS >= P_DT holds everywhere and the gap vanishes as P_F falls "
                 f"(<= {gap_low:.1e} at P_F = {p_f_grid[0]:g}), but not monotonically over "
                 f"[{p_f_grid[0]:g}, {p_f_grid[-1]:g}]: at SNR {ps['fig2_snr']:g} the link makes "
                 "P_D rise with P_F, so for large P_F both probabilities saturate and the gap "
                 "shrinks again; it peaks at P_F = "
                 + ", ".join(f"{v:.2g}" for v in peak_pf) + " for T_h = 1..7. The paper's "
                 "P_F range is not stated.")
    else:
        st2 = Status.NOT_REPRODUCED
        note2 = (f"P_DS >= P_DT: {ge}, gap at smallest P_F {gap_low:.2e}, MC agreement "
                 f"{fr_ds:.0%}/{fr_dt:.0%}/{fr_ft:.0%}")
    res2 = ClaimResult.from_claim(claims["track_init.li_fig2"], ours=ours2, status=st2,
                                  note=note2)
    ini_mc = initiator_monte_carlo(snr=ps["fig2_snr"], p_f=np.array([1e-3, 3e-3, 1e-2, 3e-2, 1e-1]),
                                   gate=ps["fig2_gate"], frames=ps["frames_T"],
                                   min_hits=ps["min_hits_T_h"], n=n_init, runner=runner)
    # ---------------------------------------------------------------- sequences
    st = SequenceSettings(n_frames=ps["n_frames"], p_f=ps["cfar_p_f"], p_d=ps["cfar_p_d"],
                          window=ps["window"], s=ps["s"], gate=ps["gate"],
                          frames=ps["frames_T"], min_hits=ps["min_hits_T_h"],
                          size_px=ps["curved_size_px"], curved_snr=ps["curved_snr"],
                          curved_frames=ps["curved_frames"])
    ex = sequence_experiment(st, n_seq, runner=runner)
    sweep = snr_sweep(st, [ps["curved_snr"], 3.0, 4.0, 5.0, 6.0], n_sweep, runner=runner)
    runs = ex["runs"]
    main_ok = np.array([r["coverage"][0] >= 0.9 and r["n_false_tracks"] <= 1 for r in runs])
    curved_rec = float(np.mean([r["coverage"][1] >= 0.5 for r in runs]))
    tab = ex["table"]
    ok_removed = ex["removed"] >= 0.9
    ok_main = main_ok.mean() >= 0.9
    ok_curved = curved_rec >= 0.5
    rec_snr = sweep.loc[sweep["recovered (coverage >= 0.5)"] >= 0.5, "SNR"]
    snr50 = f"{rec_snr.min():g}" if len(rec_snr) else f"> {sweep['SNR'].max():g}"
    ours3 = (f"{n_seq} simulated 256x256x{st.n_frames} sequences: CFAR P_F measured "
             f"{ex['p_f']:.4f}; clustering removes {ex['removed']:.1%} of false pixels "
             f"({ex['candidates_per_frame']:.1f} candidates/frame left); main target (peak SNR "
             f"{st.main_snr:.2f}) confirmed with >= 90 % coverage and <= 1 false track in "
             f"{main_ok.mean():.0%} of runs (false tracks/run {np.mean(ex['false_tracks']):.2f});"
             f" curved SNR-{st.curved_snr:g} target recovered in {curved_rec:.0%} of runs "
             f"(per-frame P_DA {tab['P_DA measured'].iloc[1]:.2f}; eq. (7) predicts "
             f"{tab['P_DA eq.7 (paper)'].iloc[1]:.2f}, exact count "
             f"{tab['P_DA exact'].iloc[1]:.2f}); recovered in >= 50 % of runs from SNR {snr50}")
    if ok_removed and ok_main and ok_curved:
        st3, note3 = Status.REPRODUCED, ""
    elif ok_removed and ok_main:
        st3 = Status.PARTIAL
        note3 = (f"The main target is separated as in Figs. 4-6, but the SNR-2, 3x3 curved "
                 f"target of Fig. 7 is recovered in only {curved_rec:.0%} of runs: with P_F = "
                 f"{st.p_f:g} its pixels are detected with P_D = "
                 f"{tab['pixel P_D (3x3 core)'].iloc[1]:.2f}, so the 5x5 window reaches S = "
                 f"{st.s} in {tab['P_DA measured'].iloc[1]:.0%} of frames (exact count "
                 f"{tab['P_DA exact'].iloc[1]:.2f}) and T_h = {st.min_hits} of T = {st.frames} "
                 f"is rarely met. The paper's own eq. (7) would predict P_DA = "
                 f"{tab['P_DA eq.7 (paper)'].iloc[1]:.2f}. Our target reaches 50 % recovery at "
                 f"SNR {snr50}. The paper's SNR definition and scene are not given.")
    else:
        st3 = Status.NOT_REPRODUCED
        note3 = (f"clustering removed {ex['removed']:.1%} (need 90 %), main target runs OK "
                 f"{main_ok.mean():.0%} (need 90 %)")
    res3 = ClaimResult.from_claim(claims["track_init.li_experiment"], ours=ours3, status=st3,
                                  note=note3)
    # ---------------------------------------------------------------- report
    demo = run_sequence(np.random.default_rng(2008), st, keep=True)
    figs = {}
    figs["fig1_area_probabilities"] = plot_fig1(f1).figure
    figs["fig2_sequence_track_detection"] = plot_fig2(f2).figure
    figs["beyond_initiator_vs_eq12_13"] = plot_initiator_vs_formulas(ini_mc).figure
    figs["fig3_7_sequence_experiment"] = plot_sequence_panels(demo, frame=st.curved_first + 10)
    figs["sequence_measured_vs_formulas"] = plot_measured_vs_formula(ex).figure
    figs["fig7_curved_target_vs_snr"] = plot_snr_sweep(sweep).figure
    fig1_tab = f1.table()
    fig1_tab = fig1_tab[fig1_tab["S"] <= 8].reset_index(drop=True)
    i5 = ps["min_hits_T_h"] - 1
    fig2_tab = pd.DataFrame({"P_F": f2.p_f, "P_D (SNR link)": f2.p_d,
                             f"P_DS eq.12 (T_h={i5 + 1})": f2.pds[i5],
                             f"P_DS MC (T_h={i5 + 1})": f2.mc_pds[i5],
                             f"P_DT eq.13 (T_h={i5 + 1})": f2.pdt[i5],
                             f"P_DT MC (T_h={i5 + 1})": f2.mc_pdt[i5],
                             f"P_FT eq.9 (T_h={i5 + 1})": f2.pft[i5],
                             f"P_FT MC (T_h={i5 + 1})": f2.mc_pft[i5]})
    text = (
        "## Notes\n\n"
        "- Figs. 1-2 carry no printed numbers: the paper plots its eqs. (4)-(13). We plot them "
        "(P_D from the adopted link P_D = Q(Q^-1(P_F) - SNR)) with Monte Carlo estimates and the "
        "exact count of the spatial test (Binomial(T_S, P_D) + Binomial(W_S - T_S, P_F)).\n"
        "- Errata adopted: D >= S (eq. 2 prints D > S); eq. (6)'s P_1 clipped to 1 (it reaches "
        f"{float(hyp.p1_paper(st.p_d, st.p_f, st.window, st.size_px ** 2)):.2f} at the "
        f"experiment's P_D = {st.p_d:g}, P_F = {st.p_f:g}, T_S = {st.size_px ** 2}).\n"
        "- Fig. 2: T = 7 (the experiment's value; Fig. 2 does not state T).\n"
        "- The sequences are simulated (the paper's images are not available): 256x256, white "
        f"noise sigma {st.noise_sigma:g} DN, fluctuating clutter sigma {st.clutter_sigma:g} DN "
        f"(scale {st.clutter_scale_px:g} px, AR(1) {st.scene().clutter_memory:g}), jitter {st.jitter_px:g} px; main target "
        f"3x3 (FWHM 3 px), peak SNR {st.main_snr:.2f} solved so that CFAR detects its core with "
        f"P_D = {st.p_d:g} (the paper's value); CFAR background/noise by tile median and MAD "
        f"({st.tile} px tiles).\n"
        f"- Temporal test: nearest neighbour in the {st.gate}x{st.gate} gate around a "
        "constant-velocity prediction (last point until 3 hits).\n"
        "- Coverage of a target: fraction of its frames with a hit in any confirmed track "
        "assigned to it (>= half of the track's hits within 2.5 px of the truth); a track that "
        "breaks and restarts counts both segments ('tracks per target').\n"
        "- Beyond the paper: the initiator itself on short lattice sequences (stationary target, "
        "Bernoulli false alarms) against eqs. (12)-(13): nearest-neighbour association lets "
        "false alarms pull the gate off the target, so the true-track rate falls below P_DT "
        "at high P_F.\n")
    settings = {"quick": quick, "fig1_windows_per_curve": f1.mc_n_target,
                "fig2_tracks_per_P_F": f2.mc_n, "initiator_sequences_per_P_F": n_init,
                "sequences": n_seq,
                "snr_sweep_runs_per_snr": n_sweep}
    return Reproduction(
        slug=SLUG, title=TITLE, claims=[res1, res2, res3],
        tables={"Fig. 1 (formulas and Monte Carlo, S <= 8)": fig1_tab,
                "Fig. 2 (T_h = 5 slice)": fig2_tab,
                "Beyond: the initiator against eqs. (12)-(13)": ini_mc,
                "Sequences: targets, measured vs formulas": tab,
                "Sequences: P_FA vs S": ex["pfa_table"],
                "Sequences: P_FT vs T_h (fixed gate)": ex["pft_table"],
                "Fig. 7 target: recovery vs SNR": sweep},
        figures=figs, text=text, settings=settings)
