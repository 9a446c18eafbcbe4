"""Each claim of Li et al. (2008) evaluated against claims.toml, and the paper-beside-ours tables.

The criteria are fixed in ``papers_repro/track_init_ht/claims.toml`` before the run; the
functions here only apply them to the results of :mod:`.trials` and :mod:`.sequences`. The
notebook and :func:`~eotrack.experiments.track_init_ht.reproduce` call the same functions on the
same runs, so their statuses are the same.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pandas as pd

from eotrack.repro import ClaimResult, Status, load_claims

from .scenario import FAIL_PDA, HIGH_PDA, LOW_PFA, SLUG, SequenceSettings
from .trials import Fig1Result, Fig2Result

__all__ = [
    "evaluate_experiment",
    "evaluate_fig1",
    "evaluate_fig2",
    "experiment_table",
    "fig1_readings",
    "fig2_table",
]

#: S range over which the Fig. 1 Monte Carlo is compared with the closed forms.
S_CHECK = 12


def fig1_readings(res: Fig1Result, pda: np.ndarray) -> dict[str, Any]:
    """The paper's readings of Fig. 1 evaluated on one family of P_DA curves (``(n_snr, n_s)``)."""
    pfa = res.pfa
    ok_s = pfa <= LOW_PFA
    best = [float(pda[j, ok_s].max()) if ok_s.any() else 0.0 for j in range(len(res.snr))]
    snr = res.snr
    good = all(best[j] >= HIGH_PDA for j, s in enumerate(snr) if s >= 2)
    bad = all(best[j] < FAIL_PDA for j, s in enumerate(snr) if s < 2)
    r = {
        "pfa_decreasing": bool(np.all(np.diff(pfa) < 0) or np.all(np.diff(pfa[pfa > 0]) < 0)),
        "pda_nonincreasing_in_S": bool(np.all(np.diff(pda, axis=1) <= 1e-15)),
        "pda_increasing_in_snr": bool(np.all(np.diff(pda, axis=0) >= -1e-15)),
        "pda_ge_pfa": bool(np.all(pda >= pfa - 1e-15)),
        "best_pda_at_low_pfa": best,
    }
    r["all_hold"] = bool(r["pfa_decreasing"] and r["pda_nonincreasing_in_S"]
                         and r["pda_increasing_in_snr"] and r["pda_ge_pfa"] and good and bad)
    return r


def evaluate_fig1(f1: Fig1Result) -> ClaimResult:
    """Claim ``track_init.li_fig1`` from a Fig. 1 run."""
    claim = load_claims(SLUG)["track_init.li_fig1"]
    r_paper = fig1_readings(f1, f1.pda_paper)
    r_exact = fig1_readings(f1, f1.pda_exact)
    a_exact = f1.agreement("exact", s_max=S_CHECK)
    a_pfa = f1.agreement("pfa", s_max=S_CHECK)
    a_paper = f1.agreement("paper", s_max=S_CHECK)
    bp = ", ".join(f"SNR {s:g}: {v:.3f}" for s, v in zip(f1.snr, r_paper["best_pda_at_low_pfa"]))
    be = ", ".join(f"SNR {s:g}: {v:.3g}" for s, v in zip(f1.snr, r_exact["best_pda_at_low_pfa"]))
    ours = (f"eqs. (4)/(7) readings hold: {r_paper['all_hold']}; best P_DA with P_FA <= "
            f"{LOW_PFA:g}: {bp}. Exact count: {be}. Monte Carlo ({f1.mc_n_target:,} windows per "
            f"SNR) inside the 99.9 % Wilson interval of the exact count at "
            f"{a_exact.fraction_inside:.0%} of {a_exact.n_points} S<=12 points (P_FA eq. 4: "
            f"{a_pfa.fraction_inside:.0%}; family-wise chance of a false alarm <= "
            f"{a_exact.familywise_bound:.2g}) and of eq. (7) at {a_paper.fraction_inside:.0%}")
    if r_paper["all_hold"] and r_exact["all_hold"] and a_exact and a_pfa:
        return ClaimResult.from_claim(claim, ours=ours, status=Status.REPRODUCED)
    if r_paper["all_hold"] and a_exact and a_pfa:
        note = (f"Fig. 1 as printed (eqs. 4, 7) shows every reading. But eq. (6) gives all "
                f"W_S pixels the probability P_1 = P_D + P_0 (P_1 = "
                f"{', '.join(f'{v:.3f}' for v in f1.p1)}), and the Monte Carlo of the stated "
                f"pixel model follows the exact count, not eq. (7): with T_S = "
                f"{f1.settings['target_pixels']} target pixels the best P_DA at P_FA <= "
                f"{LOW_PFA:g} is only {be} — the 'SNR 2-3 works' reading does not survive the "
                "exact count.")
        return ClaimResult.from_claim(claim, ours=ours, status=Status.PARTIAL, note=note)
    note = (f"readings (paper formulas) hold: {r_paper['all_hold']}; Monte Carlo agrees with "
            f"the exact count: {a_exact.all_inside}, with eq. (4): {a_pfa.all_inside}")
    return ClaimResult.from_claim(claim, ours=ours, status=Status.NOT_REPRODUCED, note=note)


def evaluate_fig2(f2: Fig2Result, *, min_hits: int) -> ClaimResult:
    """Claim ``track_init.li_fig2`` from a Fig. 2 run (``min_hits``: the T_h quoted)."""
    claim = load_claims(SLUG)["track_init.li_fig2"]
    p_f = f2.p_f
    ge = bool(np.all(f2.pds >= f2.pdt - 1e-15))
    gap = f2.pds - f2.pdt  # (T_h, P_F)
    closes = bool(np.all(np.diff(gap, axis=1) >= -1e-12))
    peak_pf = p_f[np.argmax(gap, axis=1)]
    gap_low = float(gap[:, 0].max())
    ag = {w: f2.agreement(w) for w in ("pds", "pdt", "pft")}
    ok_mc = all(ag.values())
    i = min_hits - 1
    ours = (f"P_DS >= P_DT everywhere: {ge}; gap P_DS - P_DT at T_h = {min_hits}: "
            f"{gap[i, -1]:.3f} at P_F = {p_f[-1]:g}, peak {gap[i].max():.3f} at "
            f"P_F = {peak_pf[i]:.2g}, {gap[i, 0]:.1e} at P_F = {p_f[0]:g} (largest "
            f"over T_h at P_F = {p_f[0]:g}: {gap_low:.1e}); monotone in P_F for every T_h: "
            f"{closes}; Monte Carlo ({f2.mc_n:,} tracks per P_F) inside the 99.9 % Wilson "
            f"interval of eqs. (12)/(13)/(9) at " + "/".join(
                f"{a.fraction_inside:.0%}" for a in ag.values()) + " of points")
    if ge and closes and ok_mc:
        return ClaimResult.from_claim(claim, ours=ours, status=Status.REPRODUCED)
    if ge and ok_mc and gap_low < 0.01:
        note = ("P_DS >= P_DT holds everywhere and the gap vanishes as P_F falls "
                f"(<= {gap_low:.1e} at P_F = {p_f[0]:g}), but not monotonically over "
                f"[{p_f[0]:g}, {p_f[-1]:g}]: at SNR {f2.settings['snr']:g} the link makes "
                "P_D rise with P_F, so for large P_F both probabilities saturate and the gap "
                "shrinks again; it peaks at P_F = " + ", ".join(f"{v:.2g}" for v in peak_pf)
                + f" for T_h = 1..{len(f2.t_h)}. The paper's P_F range is not stated.")
        return ClaimResult.from_claim(claim, ours=ours, status=Status.PARTIAL, note=note)
    note = (f"P_DS >= P_DT: {ge}, gap at smallest P_F {gap_low:.2e}, MC agreement "
            + "/".join(f"{a.fraction_inside:.0%}" for a in ag.values()))
    return ClaimResult.from_claim(claim, ours=ours, status=Status.NOT_REPRODUCED, note=note)


def _snr_for_recovery(sweep: pd.DataFrame) -> str:
    rec = sweep.loc[sweep["recovered (coverage >= 0.5)"] >= 0.5, "SNR"]
    return f"{rec.min():g}" if len(rec) else f"> {sweep['SNR'].max():g}"


def evaluate_experiment(ex: dict[str, Any], sweep: pd.DataFrame,
                        st: SequenceSettings) -> ClaimResult:
    """Claim ``track_init.li_experiment`` from :func:`~.sequences.sequence_experiment` and the sweep."""
    claim = load_claims(SLUG)["track_init.li_experiment"]
    runs = ex["runs"]
    main_ok = np.array([r["coverage"][0] >= 0.9 and r["n_false_tracks"] <= 1 for r in runs])
    curved_rec = float(np.mean([r["coverage"][1] >= 0.5 for r in runs]))
    tab = ex["table"]
    ok_removed = ex["removed"] >= 0.9
    ok_main = main_ok.mean() >= 0.9
    ok_curved = curved_rec >= 0.5
    snr50 = _snr_for_recovery(sweep)
    h, w = st.shape
    ours = (f"{len(runs)} simulated {h}x{w}x{st.n_frames} sequences: CFAR P_F measured "
            f"{ex['p_f']:.4f}; clustering removes {ex['removed']:.1%} of false pixels "
            f"({ex['candidates_per_frame']:.1f} candidates/frame left); main target (peak SNR "
            f"{st.main_snr:.2f}) confirmed with >= 90 % coverage and <= 1 false track in "
            f"{main_ok.mean():.0%} of runs (false tracks/run {np.mean(ex['false_tracks']):.2f});"
            f" curved SNR-{st.curved_snr:g} target recovered in {curved_rec:.0%} of runs "
            f"(per-frame P_DA {tab['P_DA measured'].iloc[1]:.2f}; eq. (7) predicts "
            f"{tab['P_DA eq.7 (paper)'].iloc[1]:.2f}, exact count "
            f"{tab['P_DA exact'].iloc[1]:.2f}); recovered in >= 50 % of "
            f"{int(sweep['runs'].iloc[0])} runs from SNR {snr50}")
    if ok_removed and ok_main and ok_curved:
        return ClaimResult.from_claim(claim, ours=ours, status=Status.REPRODUCED)
    if ok_removed and ok_main:
        note = (f"The main target is separated as in Figs. 4-6, but the SNR-{st.curved_snr:g}, "
                f"{st.size_px}x{st.size_px} curved target of Fig. 7 is recovered in only "
                f"{curved_rec:.0%} of runs: with P_F = {st.p_f:g} its pixels are detected with "
                f"P_D = {tab['pixel P_D (3x3 core)'].iloc[1]:.2f}, so the {st.window}x"
                f"{st.window} window reaches S = {st.s} in {tab['P_DA measured'].iloc[1]:.0%} "
                f"of frames (exact count {tab['P_DA exact'].iloc[1]:.2f}) and T_h = "
                f"{st.min_hits} of T = {st.frames} is rarely met. The paper's own eq. (7) would "
                f"predict P_DA = {tab['P_DA eq.7 (paper)'].iloc[1]:.2f}. Our target reaches "
                f"50 % recovery at SNR {snr50}. The paper's SNR definition and scene are not "
                "given.")
        return ClaimResult.from_claim(claim, ours=ours, status=Status.PARTIAL, note=note)
    note = (f"clustering removed {ex['removed']:.1%} (need 90 %), main target runs OK "
            f"{main_ok.mean():.0%} (need 90 %)")
    return ClaimResult.from_claim(claim, ours=ours, status=Status.NOT_REPRODUCED, note=note)


def fig2_table(f2: Fig2Result, *, min_hits: int) -> pd.DataFrame:
    """Fig. 2 at one ``T_h``: formulas and Monte Carlo versus ``P_F``."""
    i = min_hits - 1
    return pd.DataFrame({"P_F": f2.p_f, "P_D (SNR link)": f2.p_d,
                         f"P_DS eq.12 (T_h={min_hits})": f2.pds[i],
                         f"P_DS MC (T_h={min_hits})": f2.mc_pds[i],
                         f"P_DT eq.13 (T_h={min_hits})": f2.pdt[i],
                         f"P_DT MC (T_h={min_hits})": f2.mc_pdt[i],
                         f"P_FT eq.9 (T_h={min_hits})": f2.pft[i],
                         f"P_FT MC (T_h={min_hits})": f2.mc_pft[i]})


def experiment_table(ex: dict[str, Any], sweep: pd.DataFrame, st: SequenceSettings,
                     ps: dict[str, Any]) -> pd.DataFrame:
    """Figs. 4–7: the numbers the paper states beside ours, with the difference.

    Paper values come from claims.toml (``ps`` = :func:`~.scenario.paper_settings`); the paper
    states the CFAR ``P_F`` and ``P_D`` (Fig. 4), the curved target's SNR and its 30 tracked
    frames (Fig. 7). Clustering (Fig. 5) and the main track (Fig. 6) are described in words only.
    """
    tab = ex["table"]
    rec = sweep.loc[sweep["recovered (coverage >= 0.5)"] >= 0.5, "SNR"]
    snr50 = float(rec.min()) if len(rec) else float("nan")
    curved_cov = float(tab["mean coverage"].iloc[1])
    rows = [
        ("Fig. 4", "CFAR per-pixel false-alarm rate P_F", ps["cfar_p_f"], ex["p_f"]),
        ("Fig. 4", "main target pixel detection rate P_D", ps["cfar_p_d"],
         float(tab["pixel P_D (3x3 core)"].iloc[0])),
        ("Fig. 5", "fraction of CFAR false pixels removed by clustering", np.nan, ex["removed"]),
        ("Fig. 6", "main target: fraction of its frames in a confirmed track", np.nan,
         float(tab["mean coverage"].iloc[0])),
        ("Fig. 6", "false tracks per sequence", np.nan, float(np.mean(ex["false_tracks"]))),
        ("Fig. 7", f"curved target: frames tracked (of its {st.curved_frames})", float(ps["curved_frames"]),
         curved_cov * st.curved_frames),
        ("Fig. 7", "SNR at which the curved target is recovered in >= 50 % of runs",
         ps["curved_snr"], snr50),
    ]
    df = pd.DataFrame(rows, columns=["figure", "quantity", "paper", "ours"])
    df["ours − paper"] = df["ours"] - df["paper"]
    return df

