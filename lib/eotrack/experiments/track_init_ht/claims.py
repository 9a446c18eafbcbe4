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

from eotrack.montecarlo import binomial_interval
from eotrack.repro import ClaimResult, Status, load_claims
from eotrack.repro.evaluators import evaluator
from eotrack.tracking import hypothesis as hyp

from .scenario import (
    CLOSE_RATIO,
    CONFIDENCE,
    FAIL_PDA,
    HIGH_PDA,
    LOW_PFA,
    RUN_CONFIDENCE,
    SLUG,
    SequenceSettings,
)
from .trials import Fig1Result, Fig2Result

__all__ = [
    "AGREEMENT_METHOD",
    "CURVED_COVERAGE",
    "GAP_LOW",
    "MAIN_COVERAGE",
    "eq7_ratio_floor",
    "evaluate_experiment",
    "evaluate_fig1",
    "evaluate_fig2",
    "experiment_measurement",
    "experiment_table",
    "fig1_exploratory",
    "fig1_measurement",
    "fig1_readings",
    "fig1_refutation",
    "fig2_gap_ceiling",
    "fig2_measurement",
    "fig2_table",
    "robust_pd",
    "run_share",
    "snr_for_recovery",
    "status_experiment",
    "status_fig1",
    "status_fig2",
]

#: S range over which the Fig. 1 Monte Carlo is compared with the closed forms.
S_CHECK = 12
#: Interval of the Monte Carlo agreement checks (claims.toml): exact coverage in the far tail.
AGREEMENT_METHOD = "clopper-pearson"
#: Criterion constants of ``track_init.li_experiment`` (claims.toml): coverage that makes a
#: target "confirmed", shares of runs required, clustering removal required.
MAIN_COVERAGE = 0.9
CURVED_COVERAGE = 0.5
MAIN_SHARE = 0.9
CURVED_SHARE = 0.5
REMOVED_MIN = 0.9
MAX_FALSE_TRACKS = 1


def run_share(k: int, n: int, confidence: float = RUN_CONFIDENCE) -> tuple[float, float, float]:
    """Share ``k / n`` of runs with its two-sided Clopper–Pearson interval ``(share, lo, hi)``.

    Raises
    ------
    ValueError
        ``n < 1`` or ``k`` outside ``[0, n]`` (from :func:`eotrack.montecarlo.binomial_interval`).
    """
    lo, hi = binomial_interval(k, n, confidence=confidence, method="clopper-pearson")
    return float(k) / float(n), float(lo), float(hi)


def fig1_readings(res: Fig1Result, pda: np.ndarray) -> dict[str, Any]:
    """The paper's readings of Fig. 1 evaluated on one family of P_DA curves (``(n_snr, n_s)``).

    ``all_hold`` uses the pre-stated SNR-1 cut (no S with P_FA <= LOW_PFA has P_DA >= FAIL_PDA).
    ``snr_low_ratio``: P_DA / P_FA at the smallest S with P_FA <= LOW_PFA for each SNR below 2,
    reported beside it (``snr_low_close``: <= CLOSE_RATIO); eq. (7) cannot meet it at the paper's
    settings for any P_D (:func:`eq7_ratio_floor`).
    """
    pfa = res.pfa
    ok_s = pfa <= LOW_PFA
    best = [float(pda[j, ok_s].max()) if ok_s.any() else 0.0 for j in range(len(res.snr))]
    snr = res.snr
    i_min = int(np.flatnonzero(ok_s)[0]) if ok_s.any() else len(pfa) - 1
    ratio = {float(s): float(pda[j, i_min] / pfa[i_min]) if pfa[i_min] > 0 else float("inf")
             for j, s in enumerate(snr) if s < 2}
    good = all(best[j] >= HIGH_PDA for j, s in enumerate(snr) if s >= 2)
    bad = all(best[j] < FAIL_PDA for j, s in enumerate(snr) if s < 2)
    close = all(v <= CLOSE_RATIO for v in ratio.values())  # reported only (claims.toml)
    r = {
        "pfa_decreasing": bool(np.all(np.diff(pfa) < 0) or np.all(np.diff(pfa[pfa > 0]) < 0)),
        "pda_nonincreasing_in_S": bool(np.all(np.diff(pda, axis=1) <= 1e-15)),
        "pda_increasing_in_snr": bool(np.all(np.diff(pda, axis=0) >= -1e-15)),
        "pda_ge_pfa": bool(np.all(pda >= pfa - 1e-15)),
        "best_pda_at_low_pfa": best,
        "s_min": int(res.s[i_min]),
        "snr_low_ratio": ratio,
        "snr_high_works": bool(good),
        "snr_low_fails": bool(bad),
        "snr_low_close": bool(close),
    }
    r["all_hold"] = bool(r["pfa_decreasing"] and r["pda_nonincreasing_in_S"]
                         and r["pda_increasing_in_snr"] and r["pda_ge_pfa"] and good and bad)
    return r


def fig1_refutation(f1: Fig1Result) -> dict[str, Any]:
    """The exploratory Monte Carlo test of the paper's conclusion "SNR 2 or 3 works".

    At the smallest S with P_FA (eq. 4) <= LOW_PFA (the Monte Carlo P_DA is a tail count, so no
    larger S has a higher one), the Clopper–Pearson upper bound of the Monte Carlo P_DA at each
    SNR >= 2, family-wise 99.9 % (Bonferroni over those SNRs). ``refuted``: every bound < HIGH_PDA
    (the paper's "a suitable SNR, e.g. 2 or 3" is existential). Exploratory: the rule was set
    after results were seen, so it is reported (:func:`fig1_exploratory`) and never sets the
    status (claims.toml history).
    """
    ok_s = f1.pfa <= LOW_PFA
    i_min = int(np.flatnonzero(ok_s)[0])
    js = [j for j, s in enumerate(f1.snr) if s >= 2]
    n = f1.mc_n_target
    k = np.rint(f1.mc_pda[js, i_min] * n)
    _, hi = binomial_interval(k, n, confidence=1 - (1 - CONFIDENCE) / len(js),
                              method=AGREEMENT_METHOD)
    hi = np.atleast_1d(np.asarray(hi, dtype=float))
    return {"s_min": int(f1.s[i_min]), "snr": [float(f1.snr[j]) for j in js],
            "mc_pda": [float(f1.mc_pda[j, i_min]) for j in js],
            "upper": [float(v) for v in hi], "refuted": bool(np.all(hi < HIGH_PDA))}


def eq7_ratio_floor(p_f: float, window: int, target_pixels: int, s: int) -> float:
    """Smallest eq. (7) P_DA / P_FA at threshold ``s`` over every P_D (eq. 7 rises with P_D, so
    the floor is at P_D = 0, where eq. (6) still gives P_1 = 1 − (1 − P_F)^(W_S − T_S))."""
    return float(hyp.area_detection(0.0, p_f, window, target_pixels, s)
                 / hyp.area_false_alarm(p_f, window, s))


def robust_pd(p_f: float, window: int, target_pixels: int, s: int,
              level: float = HIGH_PDA) -> float:
    """Per-pixel P_D the exact count needs for P_DA >= ``level`` at threshold ``s`` (bisection):
    any SNR link giving a smaller P_D keeps the 'SNR works' reading refuted.

    Raises
    ------
    ValueError
        ``s`` outside ``1 .. window**2`` (eq. 4's domain).
    """
    if isinstance(s, bool) or not isinstance(s, (int, np.integer)) or not 1 <= s <= window ** 2:
        raise ValueError(f"s must be an int in 1..{window ** 2} (eq. 4's domain), got {s!r}")
    lo, hi = 0.0, 1.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if hyp.area_detection_exact(mid, p_f, window, target_pixels, s) >= level:
            hi = mid
        else:
            lo = mid
    return hi


def fig1_measurement(f1: Fig1Result) -> dict[str, bool]:
    """The small measurement :func:`status_fig1` decides on (the claims.toml criterion).

    ``reversed`` is the Monte Carlo contradicting the paper's ordering P_DA > P_FA: some
    (S <= 12, SNR) whose estimated P_DA lies below P_FA with the two 99.9 % Clopper–Pearson
    intervals disjoint (target and noise-only windows are independent draws of the same pixel
    model). The exploratory test of "SNR 2 or 3 works" (:func:`fig1_refutation`, set after
    results were seen) is not part of it.
    """
    sel = f1.s <= S_CHECK
    n = f1.mc_n_target
    _, hi_d = binomial_interval(np.rint(f1.mc_pda[:, sel] * n), n, confidence=CONFIDENCE,
                                method=AGREEMENT_METHOD)
    lo_f, _ = binomial_interval(np.rint(f1.mc_pfa[sel] * f1.mc_n_noise), f1.mc_n_noise,
                                confidence=CONFIDENCE, method=AGREEMENT_METHOD)
    return {"readings_paper": fig1_readings(f1, f1.pda_paper)["all_hold"],
            "readings_exact": fig1_readings(f1, f1.pda_exact)["all_hold"],
            "mc_agrees_exact": bool(f1.agreement("exact", s_max=S_CHECK, familywise=True,
                                                 method=AGREEMENT_METHOD)),
            "mc_agrees_pfa": bool(f1.agreement("pfa", s_max=S_CHECK, familywise=True,
                                               method=AGREEMENT_METHOD)),
            "reversed": bool(np.any(np.asarray(hi_d) < np.asarray(lo_f)[None, :]))}


_F1_OK = {"readings_paper": True, "readings_exact": True, "mc_agrees_exact": True,
          "mc_agrees_pfa": True, "reversed": False}


@evaluator("track_init.li_fig1", cases=[
    (_F1_OK, Status.REPRODUCED),
    ({**_F1_OK, "readings_exact": False}, Status.PARTIAL),
    ({**_F1_OK, "readings_exact": False, "mc_agrees_exact": False}, Status.NOT_REPRODUCED),
    ({**_F1_OK, "readings_paper": False}, Status.NOT_REPRODUCED),
    ({**_F1_OK, "readings_exact": False, "reversed": True}, Status.CONTRADICTED),
])
def status_fig1(m: dict[str, bool]) -> Status:
    """Status of ``track_init.li_fig1`` from :func:`fig1_measurement` (claims.toml criterion)."""
    if m["reversed"]:
        return Status.CONTRADICTED
    mc = m["mc_agrees_exact"] and m["mc_agrees_pfa"]
    if m["readings_paper"] and m["readings_exact"] and mc:
        return Status.REPRODUCED
    if m["readings_paper"] and mc:
        return Status.PARTIAL
    return Status.NOT_REPRODUCED


def fig1_exploratory(f1: Fig1Result) -> str:
    """The exploratory reading of Fig. 1 (a rule set after results were seen; claims.toml
    history): does the Monte Carlo refute "SNR 2 or 3 keeps P_FA low and P_DA high"? Reported
    beside the status, never part of it."""
    rf = fig1_refutation(f1)
    pd_need = robust_pd(f1.settings["p_f"], f1.settings["window"],
                        f1.settings["target_pixels"], rf["s_min"])
    mcb = " and ".join(f"{v:.3f} at SNR {s:g} (upper bound {u:.3f})"
                       for s, v, u in zip(rf["snr"], rf["mc_pda"], rf["upper"]))
    verdict = ("refutes" if rf["refuted"] else "does not refute")
    return (f"Exploratory reading (rule set after results were seen; not the status): at the "
            f"smallest S with P_FA <= {LOW_PFA:g} (S = {rf['s_min']}) the Monte Carlo P_DA is "
            f"{mcb} (family-wise 99.9 %), so the pixel model {verdict} the paper's 'a suitable "
            f"SNR (e.g. 2 or 3) keeps P_FA low and P_DA high' (need >= {HIGH_PDA:g}); the exact "
            f"count needs P_D >= {pd_need:.3f} per target pixel there, whatever the SNR link.")


def evaluate_fig1(f1: Fig1Result) -> ClaimResult:
    """Claim ``track_init.li_fig1`` from a Fig. 1 run (status by :func:`status_fig1`)."""
    claim = load_claims(SLUG)["track_init.li_fig1"]
    m = fig1_measurement(f1)
    status = status_fig1(m)
    r_paper = fig1_readings(f1, f1.pda_paper)
    r_exact = fig1_readings(f1, f1.pda_exact)
    rf = fig1_refutation(f1)
    a_exact = f1.agreement("exact", s_max=S_CHECK, familywise=True, method=AGREEMENT_METHOD)
    a_pfa = f1.agreement("pfa", s_max=S_CHECK, familywise=True, method=AGREEMENT_METHOD)
    a_paper = f1.agreement("paper", s_max=S_CHECK, familywise=True, method=AGREEMENT_METHOD)
    bp = ", ".join(f"SNR {s:g}: {v:.3f}" for s, v in zip(f1.snr, r_paper["best_pda_at_low_pfa"]))
    be = ", ".join(f"SNR {s:g}: {v:.3g}" for s, v in zip(f1.snr, r_exact["best_pda_at_low_pfa"]))
    rat = "; ".join(f"SNR {s:g}: eq. (7) {r_paper['snr_low_ratio'][s]:.3g}, exact count "
                    f"{r_exact['snr_low_ratio'][s]:.3g}" for s in r_paper["snr_low_ratio"])
    ours = (f"eqs. (4)/(7) readings hold: {r_paper['all_hold']}; best P_DA with P_FA <= "
            f"{LOW_PFA:g}: {bp}. Exact count: {be}. P_DA / P_FA at S = {rf['s_min']} "
            f"(reading 'very close' if <= {CLOSE_RATIO:g}): {rat}. Monte Carlo "
            f"({f1.mc_n_target:,} windows per "
            f"SNR) inside the family-wise 99.9 % Clopper-Pearson intervals (Bonferroni over the "
            f"{a_exact.n_points} S<=12 points) of the exact count at "
            f"{a_exact.fraction_inside:.0%} of points (P_FA eq. 4: "
            f"{a_pfa.fraction_inside:.0%}) and of eq. (7) at {a_paper.fraction_inside:.0%}; "
            f"Monte Carlo P_DA below P_FA with disjoint 99.9 % intervals anywhere: "
            f"{m['reversed']}")
    explo = fig1_exploratory(f1)
    if status is Status.REPRODUCED:
        note = explo
    elif status is Status.PARTIAL:
        note = (f"Fig. 1 as printed (eqs. 4, 7) shows every reading. But eq. (6) gives all "
                f"W_S pixels the probability P_1 = P_D + P_0 (P_1 = "
                f"{', '.join(f'{v:.3f}' for v in f1.p1)}), and the Monte Carlo of the stated "
                f"pixel model follows the exact count, not eq. (7): with T_S = "
                f"{f1.settings['target_pixels']} target pixels the best P_DA at P_FA <= "
                f"{LOW_PFA:g} is only {be}, so the exact count does not keep the readings. "
                + explo)
    else:
        note = (f"readings (paper formulas) hold: {r_paper['all_hold']}; Monte Carlo agrees "
                f"with the exact count: {a_exact.all_inside}, with eq. (4): {a_pfa.all_inside}; "
                f"Monte Carlo P_DA below P_FA with disjoint intervals: {m['reversed']}. "
                + explo)
    return ClaimResult.from_claim(claim, ours=ours, status=status, note=note)


#: The gap P_DS - P_DT at P_F = 1e-4 below which the partial band says it "vanishes".
GAP_LOW = 0.01


def fig2_gap_ceiling(p_f: float | np.ndarray, gate: int, frames: int) -> np.ndarray:
    """Largest possible gap P_DS − P_DT in the gate model, for every P_D and T_h.

    A track that passes the sequence test and not the true-track test needs at least one false
    alarm among the ``M − 1`` other gate pixels in ``T`` frames: gap ≤ 1 − (1 − P_F)^((M−1) T).
    """
    return 1.0 - (1.0 - np.asarray(p_f, dtype=float)) ** ((gate * gate - 1) * frames)


def fig2_measurement(f2: Fig2Result) -> dict[str, Any]:
    """The small measurement :func:`status_fig2` decides on (li_fig2 is not directional: at
    small P_F the gate model itself closes the gap, :func:`fig2_gap_ceiling`)."""
    gap = f2.pds - f2.pdt  # (T_h, P_F)
    return {"ge": bool(np.all(f2.pds >= f2.pdt - 1e-15)),
            "monotone": bool(np.all(np.diff(gap, axis=1) >= -1e-12)),
            "mc_agrees": all(bool(f2.agreement(w, familywise=True, method=AGREEMENT_METHOD))
                             for w in ("pds", "pdt", "pft")),
            "gap_low": float(gap[:, 0].max())}


_F2_OK = {"ge": True, "monotone": True, "mc_agrees": True, "gap_low": 1e-3}


@evaluator("track_init.li_fig2", cases=[
    (_F2_OK, Status.REPRODUCED),
    ({**_F2_OK, "monotone": False}, Status.PARTIAL),
    ({**_F2_OK, "monotone": False, "gap_low": 0.05}, Status.NOT_REPRODUCED),
    ({**_F2_OK, "mc_agrees": False}, Status.NOT_REPRODUCED),
    ({**_F2_OK, "ge": False}, Status.NOT_REPRODUCED),
])
def status_fig2(m: dict[str, Any]) -> Status:
    """Status of ``track_init.li_fig2`` from :func:`fig2_measurement` (claims.toml criterion)."""
    if m["ge"] and m["monotone"] and m["mc_agrees"]:
        return Status.REPRODUCED
    if m["ge"] and m["mc_agrees"] and m["gap_low"] < GAP_LOW:
        return Status.PARTIAL
    return Status.NOT_REPRODUCED


def evaluate_fig2(f2: Fig2Result, *, min_hits: int) -> ClaimResult:
    """Claim ``track_init.li_fig2`` from a Fig. 2 run (``min_hits``: the T_h quoted)."""
    claim = load_claims(SLUG)["track_init.li_fig2"]
    m = fig2_measurement(f2)
    status = status_fig2(m)
    p_f = f2.p_f
    gap = f2.pds - f2.pdt  # (T_h, P_F)
    peak_pf = p_f[np.argmax(gap, axis=1)]
    ag = {w: f2.agreement(w, familywise=True, method=AGREEMENT_METHOD) for w in ("pds", "pdt", "pft")}
    mc_gap0 = f2.mc_pds[:, 0] - f2.mc_pdt[:, 0]
    ceil0 = float(fig2_gap_ceiling(p_f[0], f2.settings["gate"], f2.settings["frames"]))
    i = min_hits - 1
    ours = (f"P_DS >= P_DT everywhere: {m['ge']}; gap P_DS - P_DT at T_h = {min_hits}: "
            f"{gap[i, -1]:.3f} at P_F = {p_f[-1]:g}, peak {gap[i].max():.3f} at "
            f"P_F = {peak_pf[i]:.2g}, {gap[i, 0]:.1e} at P_F = {p_f[0]:g} (largest "
            f"over T_h at P_F = {p_f[0]:g}: {m['gap_low']:.1e}); monotone in P_F for every T_h: "
            f"{m['monotone']}; Monte Carlo ({f2.mc_n:,} tracks per P_F) inside the family-wise "
            f"99.9 % Clopper-Pearson intervals (Bonferroni over each curve's {ag['pds'].n_points} points) "
            f"of eqs. (12)/(13)/(9) at " + "/".join(
                f"{a.fraction_inside:.0%}" for a in ag.values()) + " of points; paired Monte "
            f"Carlo gap P_DS - P_DT at P_F = {p_f[0]:g}: largest {float(np.max(mc_gap0)):.1e} "
            f"(the gate model caps it at {ceil0:.4f} for every P_D and T_h)")
    if status is Status.REPRODUCED:
        note = ""
    elif status is Status.PARTIAL:
        note = ("P_DS >= P_DT holds everywhere and the gap vanishes as P_F falls "
                f"(<= {m['gap_low']:.1e} at P_F = {p_f[0]:g}), but not monotonically over "
                f"[{p_f[0]:g}, {p_f[-1]:g}]: at SNR {f2.settings['snr']:g} the link makes "
                "P_D rise with P_F, so for large P_F both probabilities saturate and the gap "
                "shrinks again; it peaks at P_F = " + ", ".join(f"{v:.2g}" for v in peak_pf)
                + f" for T_h = 1..{len(f2.t_h)}. The paper's P_F range is not stated.")
    else:
        note = (f"P_DS >= P_DT: {m['ge']}, gap at smallest P_F {m['gap_low']:.2e}, MC agreement "
                "(family-wise) " + "/".join(f"{a.fraction_inside:.0%}" for a in ag.values())
                + ")")
    return ClaimResult.from_claim(claim, ours=ours, status=status, note=note)


def experiment_measurement(ex: dict[str, Any]) -> dict[str, Any]:
    """The counts :func:`status_experiment` decides on, from :func:`~.sequences.sequence_experiment`.

    ``main_ok``: runs whose main target is confirmed with coverage ≥ 0.9 and ≤ 1 false track;
    ``curved_ok``: runs whose curved target has coverage ≥ 0.5; ``n_runs``; ``removed``: pooled
    fraction of CFAR false pixels removed by clustering.
    """
    runs = ex["runs"]
    return {"n_runs": len(runs), "removed": float(ex["removed"]),
            "main_ok": int(sum(r["coverage"][0] >= MAIN_COVERAGE
                               and r["n_false_tracks"] <= MAX_FALSE_TRACKS for r in runs)),
            "curved_ok": int(sum(r["coverage"][1] >= CURVED_COVERAGE for r in runs))}


_EX_OK = {"n_runs": 24, "removed": 0.99, "main_ok": 24, "curved_ok": 14}


@evaluator("track_init.li_experiment", cases=[
    (_EX_OK, Status.REPRODUCED),
    ({**_EX_OK, "curved_ok": 12}, Status.REPRODUCED),
    ({**_EX_OK, "curved_ok": 8}, Status.PARTIAL),      # 33 %, 95 % CP [16 %, 55 %]
    ({**_EX_OK, "curved_ok": 5}, Status.NOT_REPRODUCED),  # 21 %, CP upper 42 %
    ({**_EX_OK, "curved_ok": 0}, Status.NOT_REPRODUCED),  # 0 of 24 is not partial
    ({**_EX_OK, "removed": 0.8}, Status.NOT_REPRODUCED),
    ({**_EX_OK, "main_ok": 20}, Status.NOT_REPRODUCED),
])
def status_experiment(m: dict[str, Any]) -> Status:
    """Status of ``track_init.li_experiment`` from :func:`experiment_measurement`.

    Reproduced: clustering removes ≥ 90 %, the main target is confirmed in ≥ 90 % of runs and
    the curved target in ≥ 50 %. Partial (claims.toml ``partial_band``): the first two hold and
    the curved share is below 50 % while its 95 % Clopper–Pearson interval reaches 50 %.
    Otherwise not reproduced.
    """
    n = m["n_runs"]
    if m["removed"] < REMOVED_MIN or m["main_ok"] / n < MAIN_SHARE:
        return Status.NOT_REPRODUCED
    share, _, hi = run_share(m["curved_ok"], n)
    if share >= CURVED_SHARE:
        return Status.REPRODUCED
    if hi >= CURVED_SHARE:
        return Status.PARTIAL
    return Status.NOT_REPRODUCED


def _fmt_share(k: int, n: int) -> str:
    p, lo, hi = run_share(k, n)
    return f"{k}/{n} = {p:.0%} (95 % CP [{lo:.0%}, {hi:.0%}])"


def snr_for_recovery(sweep: pd.DataFrame) -> float:
    """Lowest SNR of the sweep whose curved target is recovered in ≥ 50 % of runs (NaN: none)."""
    rec = sweep.loc[sweep["recovered share"] >= CURVED_SHARE, "SNR"]
    return float(rec.min()) if len(rec) else float("nan")


def evaluate_experiment(ex: dict[str, Any], sweep: pd.DataFrame,
                        st: SequenceSettings) -> ClaimResult:
    """Claim ``track_init.li_experiment`` (status by :func:`status_experiment`); the sweep is
    exploratory and enters only the note."""
    claim = load_claims(SLUG)["track_init.li_experiment"]
    m = experiment_measurement(ex)
    status = status_experiment(m)
    n = m["n_runs"]
    tab = ex["table"]
    snr50 = snr_for_recovery(sweep)
    snr50_txt = f"{snr50:g}" if np.isfinite(snr50) else f"> {sweep['SNR'].max():g}"
    h, w = st.shape
    ours = (f"{n} simulated {h}x{w}x{st.n_frames} sequences: CFAR P_F measured "
            f"{ex['p_f']:.4f}; clustering removes {m['removed']:.1%} of false pixels "
            f"({ex['candidates_per_frame']:.1f} candidates/frame left); main target (peak SNR "
            f"{st.main_snr:.2f}) confirmed with >= 90 % coverage and <= 1 false track in "
            f"{_fmt_share(m['main_ok'], n)} of runs (false tracks/run "
            f"{np.mean(ex['false_tracks']):.2f}); curved SNR-{st.curved_snr:g} target recovered "
            f"in {_fmt_share(m['curved_ok'], n)} of runs (per-frame P_DA "
            f"{tab['P_DA measured'].iloc[1]:.2f}; eq. (7) predicts "
            f"{tab['P_DA eq.7 (paper)'].iloc[1]:.2f}, exact count "
            f"{tab['P_DA exact'].iloc[1]:.2f})")
    if status is Status.REPRODUCED:
        note = ""
    elif m["removed"] >= REMOVED_MIN and m["main_ok"] / n >= MAIN_SHARE:
        kind = ("its interval still reaches 50 %" if status is Status.PARTIAL
                else "its 95 % interval lies wholly below the 50 % the criterion asks")
        note = (f"The main target is separated as in Figs. 4-6, but the SNR-{st.curved_snr:g}, "
                f"{st.size_px}x{st.size_px} curved target of Fig. 7 is recovered in "
                f"{_fmt_share(m['curved_ok'], n)} of runs; {kind}. With P_F = {st.p_f:g} its "
                f"pixels are detected with P_D = {tab['pixel P_D (3x3 core)'].iloc[1]:.2f}, so "
                f"the {st.window}x{st.window} window reaches S = {st.s} in "
                f"{tab['P_DA measured'].iloc[1]:.0%} of frames (exact count "
                f"{tab['P_DA exact'].iloc[1]:.2f}) and T_h = {st.min_hits} of T = {st.frames} "
                f"is rarely met. The paper's own eq. (7) would predict P_DA = "
                f"{tab['P_DA eq.7 (paper)'].iloc[1]:.2f}. Exploratory (not part of the "
                f"criterion): in the same scene, with the same noise, the target is recovered "
                f"in >= 50 % of {int(sweep['runs'].iloc[0])} runs from SNR {snr50_txt}. The "
                "paper's SNR definition and scene are not given.")
    else:
        note = (f"clustering removed {m['removed']:.1%} (need 90 %), main target runs OK "
                f"{_fmt_share(m['main_ok'], n)} (need 90 %)")
    return ClaimResult.from_claim(claim, ours=ours, status=status, note=note)


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
    snr50 = snr_for_recovery(sweep)
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
        ("Fig. 7", "curved target's SNR (paper: its one example; ours: the lowest SNR "
                   "recovered in >= 50 % of runs, point estimate of the exploratory sweep)",
         ps["curved_snr"], snr50),
    ]
    df = pd.DataFrame(rows, columns=["figure", "quantity", "paper", "ours"])
    df["ours − paper"] = df["ours"] - df["paper"]
    return df

