"""The image-sequence experiment of Li et al. (2008), Figs. 3–7, on simulated sequences.

One run (:func:`run_sequence`) simulates a sequence (:class:`~.scenario.SequenceSettings`),
segments every frame by CFAR, clusters it (eqs. 2–3), runs the temporal test and measures what
the paper's formulas predict: ``P_FA`` (eq. 4), ``P_DA`` (eq. 7 and the exact count),
``P_FT`` (eq. 9), ``P_DS`` and ``P_DT`` (eqs. 12–13). :func:`sequence_experiment` pools many
runs; :func:`snr_sweep` asks how bright the curved target of Fig. 7 must be.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np
import pandas as pd

from eotrack.imaging.dim_targets import DimSequence, simulate_dim_sequence
from eotrack.imaging.neighbourhood import candidate_frames, neighbourhood_count
from eotrack.montecarlo import TrialRunner, run_trials, trial_generators
from eotrack.tracking import hypothesis as hyp
from eotrack.tracking.initiation.base import Track
from eotrack.tracking.initiation.temporal import TemporalContinuityInitiator

from .scenario import SequenceSettings

__all__ = ["curved_pda_predictions", "match_tracks", "pool_runs", "run_sequence",
           "sequence_experiment", "snr_sweep", "sweep_example", "sweep_table"]


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


def sequence_experiment(st: SequenceSettings, n_runs: int, *,
                        seed: int | np.random.SeedSequence = 3,
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
    return pool_runs(runs, st)


def pool_runs(runs: list[dict[str, Any]], st: SequenceSettings) -> dict[str, Any]:
    """Pool the per-run measurements of :func:`run_sequence` (``keep=False``) into the result of
    :func:`sequence_experiment` (the stored study of :mod:`.stored` is pooled by this too).

    Raises
    ------
    ValueError
        ``runs`` is empty.
    """
    if not runs:
        raise ValueError("runs must hold at least one run of run_sequence")
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
        "runs": runs, "n_runs": len(runs), "p_f": p_f, "removed": removed, "p_cand": p_cand,
        "table": pd.DataFrame(rows), "pfa_table": pfa_tab, "pft_table": pft_tab,
        "false_tracks": [r["n_false_tracks"] for r in runs],
        "candidates_per_frame": float(np.mean([r["candidates_per_frame"] for r in runs])),
        "main_snr": st.main_snr,
    }


def snr_sweep(st: SequenceSettings, snrs: list[float], n_runs: int, *,
              seed: int | np.random.SeedSequence = 3, runner: TrialRunner | None = None,
              paper_runs: list[dict[str, Any]] | None = None,
              return_runs: bool = False) -> pd.DataFrame:
    """Recovery of the curved target versus its SNR, in the experiment's own scene.

    Every SNR runs the same ``n_runs`` sequences as :func:`sequence_experiment` with the same
    ``seed`` (common random numbers: the same noise, clutter and jitter; only the curved
    target's amplitude changes), so the row at the paper's SNR *is* the experiment. Pass that
    experiment's ``runs`` as ``paper_runs`` to reuse them instead of simulating them again.

    Returns
    -------
    pandas.DataFrame
        One row per SNR: ``P_DA measured``, ``recovered runs`` (coverage ≥ 0.5),
        ``recovered share`` with its 95 % Clopper–Pearson interval (``CP low``, ``CP high``),
        ``mean coverage``, ``false tracks / run``, ``runs``. With ``return_runs``:
        ``(table, {SNR: runs})`` (what :mod:`.stored` keeps).
    """
    if not isinstance(n_runs, (int, np.integer)) or isinstance(n_runs, bool) or n_runs < 1:
        raise ValueError(f"n_runs must be a positive int, got {n_runs!r}")
    if paper_runs is not None and len(paper_runs) != n_runs:
        raise ValueError(f"paper_runs has {len(paper_runs)} runs, n_runs is {n_runs}")
    by_snr = {}
    for snr in snrs:
        if paper_runs is not None and float(snr) == float(st.curved_snr):
            by_snr[float(snr)] = paper_runs
        else:
            by_snr[float(snr)] = run_trials(_sequence_trial, n_runs, seed=seed, runner=runner,
                                            args=(replace(st, curved_snr=float(snr)),),
                                            desc=f"SNR {snr:g}")
    tab = sweep_table(by_snr, st)
    return (tab, by_snr) if return_runs else tab


def sweep_table(runs_by_snr: dict[float, list[dict[str, Any]]], st: SequenceSettings
                ) -> pd.DataFrame:
    """The table of :func:`snr_sweep` from its runs (``{SNR: runs of run_sequence}``)."""
    from .claims import CURVED_COVERAGE, run_share

    i = 1 if st.include_main else 0
    rows = []
    for snr, runs in runs_by_snr.items():
        n_runs = len(runs)
        cov = np.array([r["coverage"][i] for r in runs])
        fr = np.array([r["target_frames"][i] for r in runs])
        k = int(np.sum(cov >= CURVED_COVERAGE))
        share, lo, hi = run_share(k, n_runs)
        rows.append({"SNR": float(snr),
                     "P_DA measured": float(np.sum([r["target_area_det"][i] for r in runs])
                                            / fr.sum()),
                     "recovered runs": k, "recovered share": share, "CP low": lo, "CP high": hi,
                     "mean coverage": float(cov.mean()),
                     "false tracks / run": float(np.mean([r["n_false_tracks"] for r in runs])),
                     "runs": n_runs})
    return pd.DataFrame(rows)


def sweep_example(st: SequenceSettings, snr: float, n_runs: int, *,
                  seed: int | np.random.SeedSequence = 3,
                  recovered: bool = False) -> dict[str, Any]:
    """A run of :func:`snr_sweep` (and of :func:`sequence_experiment`) at ``snr``, kept for plots.

    The same generators as the sweep's sequences, so a Fig. 7 panel shows a member of the
    sweep, not another draw. ``recovered=False``: run 0. ``recovered=True``: the first run
    (in the sweep's order) whose curved target is recovered (coverage ≥ 0.5), or run 0 if
    none is. The returned dict holds ``"run_index"``.
    """
    gens = trial_generators(seed, n_runs)
    st_snr = replace(st, curved_snr=float(snr))
    first = None
    for i, rng in enumerate(gens if recovered else gens[:1]):
        run = run_sequence(rng, st_snr, keep=True)
        run["run_index"] = i
        first = first if first is not None else run
        if not recovered or run["coverage"][-1] >= 0.5:
            return run
    return first


def curved_pda_predictions(ex: dict[str, Any], st: SequenceSettings, *,
                           n_phase: int = 10) -> dict[str, float]:
    """Per-frame P_DA of the curved target predicted from measured inputs (notebook, Fig. 7).

    The spot of eq. (1) at the curved target's SNR, sampled at pixel centres, is put at
    ``n_phase × n_phase`` uniform sub-pixel phases; each core pixel is detected with
    ``Q(Q⁻¹(P_F) − a g_i)`` at the *measured* ``P_F``. Returns the mean over phases of
    (i) ``"per-pixel"``: the Poisson-binomial core count plus ``Bin(W_S − T_S, P_F)``
    (:func:`~eotrack.tracking.hypothesis.area_detection_pixels`), and (ii) ``"with measured
    background"``: the core count plus the measured count distribution of background windows
    (``W_S`` pixels, so the noise part is bounded from above).
    """
    from scipy.stats import norm

    p_f = float(ex["p_f"])
    z = norm.isf(p_f)
    sig = st.sigma_px
    u = (np.arange(n_phase) + 0.5) / n_phase - 0.5
    k = np.arange(st.size_px) - st.size_px // 2
    d_bg = np.sum([r["d_hist"] for r in ex["runs"]], axis=0).astype(float)
    d_bg /= d_bg.sum()
    per_pixel, with_bg = [], []
    for dy in u:
        for dx in u:
            g = np.exp(-0.5 * np.add.outer((k - dy) ** 2, (k - dx) ** 2).ravel() / sig ** 2)
            q = norm.sf(z - st.curved_snr * g)
            per_pixel.append(float(hyp.area_detection_pixels(q, p_f, st.window, st.s)))
            pmf = np.array([1.0])
            for qi in q:
                pmf = np.convolve(pmf, [1.0 - qi, qi])
            with_bg.append(float(np.convolve(pmf, d_bg)[st.s:].sum()))
    return {"per-pixel": float(np.mean(per_pixel)),
            "with measured background": float(np.mean(with_bg))}
