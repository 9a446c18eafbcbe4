"""Each claim of ``papers_repro/track_init_hough/claims.toml`` evaluated against its criterion.

Every status is decided by a pure evaluator (registered with :func:`eotrack.repro.evaluator`
and synthetic cases reaching each status it can return) from a small measurement computed
here; :func:`evaluate` builds the measurements and the scorecard rows. The status is always the
paper's method's (6-neighbourhood, literal procedure); our variants (26-neighbourhood, the
verified initiator) are reported in the row's ``variant`` text and never set it.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pandas as pd
from scipy import stats

from eotrack.repro import ClaimResult, Status
from eotrack.repro.evaluators import evaluator

from .scenario import XuConfig
from .trials import summarise_planted

__all__ = ["angle_summary", "calibrated_chance_factor", "comparison_intervals", "evaluate",
           "evaluate_planted", "status_chance_rate", "status_method_comparison",
           "status_planted", "status_xu_fig3", "status_xu_table2"]

MH = "modified Hough 3/4"
FIVE = ("logic 2/3", "logic 3/4", "angle logic 3/4", "classic Hough 3/4", MH)
R, P, N, C = (Status.REPRODUCED, Status.PARTIAL, Status.NOT_REPRODUCED, Status.CONTRADICTED)


# --------------------------------------------------------------------------- evaluators
def _redraw_status(m: dict[str, Any]) -> Status:
    if m["nominal_ok"] and m["frac"] >= 0.95:
        return R
    if m["nominal_ok"] and m["frac"] >= 0.80:
        return P
    return N


_REDRAW_CASES = [(dict(nominal_ok=True, frac=0.97), R), (dict(nominal_ok=True, frac=0.85), P),
                 (dict(nominal_ok=True, frac=0.5), N), (dict(nominal_ok=False, frac=0.99), N),
                 (dict(nominal_ok=False, frac=0.52), N)]


@evaluator("track_init.xu_table2", cases=_REDRAW_CASES)
def status_xu_table2(m: dict[str, Any]) -> Status:
    """``nominal_ok``: the paper's 6-neighbourhood gives the right confirmation frames on the
    nominal scene; ``frac``: share of redraws where it does."""
    return _redraw_status(m)


@evaluator("track_init.xu_fig3", cases=_REDRAW_CASES)
def status_xu_fig3(m: dict[str, Any]) -> Status:
    """``nominal_ok``: exact recovery of the five tracks by the paper's rule on the nominal
    scene; ``frac``: share of redraws with exact recovery."""
    return _redraw_status(m)


def _ordering(lo: list[float], hi: list[float], sign: int) -> str:
    """'holds' if every interval is on the paper's side (sign +1: above 0, −1: below 0),
    'reversed' if some interval lies entirely on the other side, else 'neither'."""
    lo_, hi_ = np.asarray(lo, float), np.asarray(hi, float)
    if sign > 0:
        return "holds" if np.all(lo_ > 0) else "reversed" if np.any(hi_ < 0) else "neither"
    return "holds" if np.all(hi_ < 0) else "reversed" if np.any(lo_ > 0) else "neither"


_MC_OK = dict(a=([0.1, 0.2], [0.5, 0.6]), b=([-0.4, -0.3], [-0.1, -0.05]), b_dpc=0.01,
              c=([-2.0, -1.0], [-0.5, -0.2]), c_pc=0.95)


@evaluator("track_init.method_comparison", cases=[
    (_MC_OK, R),
    ({**_MC_OK, "b": ([0.0], [0.0])}, P),
    ({**_MC_OK, "b_dpc": 0.05}, P),
    ({**_MC_OK, "b": ([0.0], [0.0]), "c_pc": 0.8}, N),
    ({**_MC_OK, "b": ([0.1, 0.0], [0.3, 0.1])}, C),
    ({**_MC_OK, "c": ([0.5], [1.5])}, C),
])
def status_method_comparison(m: dict[str, Any]) -> Status:
    """Orderings (a)-(c) from Bonferroni-corrected paired intervals ``(lows, highs)`` of the
    differences 2/3 − other (``a``, paper: > 0), angle − plain 3/4 (``b``, < 0) and modified −
    classic Hough (``c``, < 0); ``b_dpc`` max |ΔP_correct| angle vs plain, ``c_pc`` the modified
    Hough's lowest P_correct at the paper's setting."""
    a = _ordering(*m["a"], +1)
    b = _ordering(*m["b"], -1)
    c = _ordering(*m["c"], -1)
    if "reversed" in (a, b, c):
        return C
    n_ok = (a == "holds") + (b == "holds" and m["b_dpc"] <= 0.02) \
        + (c == "holds" and m["c_pc"] >= 0.9)
    return R if n_ok == 3 else P if n_ok == 2 else N


@evaluator("track_init.planted_scenes", cases=[
    (dict(recall=0.97, false_over_chance=1.2), R),
    (dict(recall=0.90, false_over_chance=2.2), N),
    (dict(recall=0.97, false_over_chance=1.6), N),
    (dict(recall=0.93, false_over_chance=1.0), N),
])
def status_planted(m: dict[str, Any]) -> Status:
    """The paper's literal modified Hough: ``recall`` ≥ 0.95 and ``false_over_chance`` (false
    tracks over the calibrated chance rate) ≤ 1.5."""
    return R if m["recall"] >= 0.95 and m["false_over_chance"] <= 1.5 else N


@evaluator("track_init.chance_rate", cases=[
    (dict(ratio=[0.98, 1.01, 0.99], se=[0.017, 0.016, 0.016]), R),
    (dict(ratio=[0.87, 0.92, 0.93], se=[0.017, 0.016, 0.016]), N),
    (dict(ratio=[0.96, 1.0, 1.0], se=[0.01, 0.01, 0.01]), N),   # 4 s.e. off
    (dict(ratio=[0.99, 1.0, 1.0], se=[0.07, 0.03, 0.02]), N),   # underpowered
])
def status_chance_rate(m: dict[str, Any]) -> Status:
    """Passes if every level's measured/analytic ``ratio`` has a Poisson standard error ``se``
    ≤ 0.02 (enough scenes for the test to have power) and lies within 3 s.e. of 1 and within
    5 %."""
    r, se = np.asarray(m["ratio"], float), np.asarray(m["se"], float)
    ok = np.all(se <= 0.02) and np.all(np.abs(r - 1) <= 3 * se) and np.all(np.abs(r - 1) <= 0.05)
    return R if bool(ok) else N


# --------------------------------------------------------------------------- measurements
def comparison_intervals(trials: pd.DataFrame, n_frames: int, conf: float = 0.95
                         ) -> dict[str, tuple[list[float], list[float]]]:
    """Paired t intervals of false tracks per frame differences at every clutter density > 0.

    Parameters
    ----------
    trials
        Per-trial rows of :func:`~.trials.run_comparison` (``per_trial=True``): ``trial``,
        ``sweep``, ``clutter``, ``method``, ``false``.
    n_frames
        Frames per scene (false tracks are per frame).
    conf
        Family-wise confidence; Bonferroni over every density × ordering compared.

    Returns
    -------
    dict
        ``a`` (2/3 − each other method, pooled into one list), ``b`` (angle − plain 3/4),
        ``c`` (modified − classic Hough): ``(lows, highs)``; and ``n`` per density.
    """
    if not 0 < conf < 1:
        raise ValueError(f"conf must lie in (0, 1), got {conf}")
    cl = trials[(trials["sweep"] == "clutter") & (trials["clutter"] > 0)]
    piv = cl.pivot_table(index=["clutter", "trial"], columns="method", values="false")
    piv = piv / float(n_frames)
    pairs = {"a": [("logic 2/3", o) for o in FIVE[1:]], "b": [("angle logic 3/4", "logic 3/4")],
             "c": [(MH, "classic Hough 3/4")]}
    n_cmp = sum(len(v) for v in pairs.values()) * piv.index.get_level_values(0).nunique()
    out: dict[str, Any] = {}
    for key, prs in pairs.items():
        lo, hi = [], []
        for _lam, g in piv.groupby(level=0):
            for x, y in prs:
                d = (g[x] - g[y]).to_numpy()
                n = len(d)
                sd = float(np.std(d, ddof=1)) if n > 1 else np.inf
                q = float(stats.t.ppf(1 - (1 - conf) / (2 * n_cmp), max(n - 1, 1)))
                half = q * sd / np.sqrt(n)
                lo.append(float(d.mean() - half))
                hi.append(float(d.mean() + half))
        out[key] = (lo, hi)
    out["n"] = int(piv.groupby(level=0).size().min())
    return out


def calibrated_chance_factor(chance_check: pd.DataFrame) -> float:
    """What the analytic chance rate is worth: pooled measured / analytic of the clutter-only
    check (``sum measured / sum analytic`` over its levels)."""
    a = float(chance_check["analytic"].sum())
    if not a > 0:
        raise ValueError("chance_check has no analytic chance tracks to calibrate against")
    return float(chance_check["measured"].sum()) / a


# --------------------------------------------------------------------------- rows
def _frames_ok(cf: dict, n_false: int, want: dict[int, int]) -> bool:
    return {i: f + 1 for i, f in cf.items()} == want and n_false == 0


def evaluate(claims, cfg: XuConfig, table2: pd.DataFrame, nominal: dict[Any, dict],
             redraws: pd.DataFrame, comp: pd.DataFrame, angle: pd.DataFrame,
             planted: pd.DataFrame, chance_check: pd.DataFrame,
             comp_trials: pd.DataFrame | None = None, n_frames_comp: int = 6,
             planted_metrics: pd.DataFrame | None = None) -> list[ClaimResult]:
    """Every claim of claims.toml evaluated against its criterion (see the module doc)."""
    rows = []
    p2 = claims["track_init.xu_table2"].paper
    want = {1: int(p2["confirm_frame_track1"]), 2: int(p2["confirm_frame_track2"]),
            3: int(p2["confirm_frame_track3"]), 4: cfg.n_frames, 5: cfg.n_frames}
    ok, frac, got = {}, {}, {}
    keys = {6: 6, 26: 26, "ours": 0}
    for nb, col in keys.items():
        got[nb] = {i + 1: f + 1 for i, f in sorted(nominal[nb]["confirm_frame"].items())}
        ok[nb] = _frames_ok(nominal[nb]["confirm_frame"], nominal[nb]["false"],
                            {i - 1: f for i, f in want.items()})
        r = redraws[redraws["neighbourhood"] == col]
        frac[nb] = float(np.mean([_frames_ok(cf, fl, {i - 1: f for i, f in want.items()})
                                  for cf, fl in zip(r["confirm_frame"], r["false"])]))
    n_red = int((redraws["neighbourhood"] == 6).sum())
    status = status_xu_table2(dict(nominal_ok=ok[6], frac=frac[6]))
    variant = (f"26-neighbourhood (ours): nominal track→frame {got[26]}, right in "
               f"{100 * frac[26]:.0f} % of redraws; verified initiator: {got['ours']}, "
               f"{100 * frac['ours']:.0f} %")
    note = ""
    if status is not Status.REPRODUCED:
        note = (f"paper's 6-neighbourhood: nominal scene track→frame {got[6]} (want {want}), "
                f"false {nominal[6]['false']}; right in {100 * frac[6]:.0f} % of {n_red} "
                "redraws. A track whose pair cells differ in two of (ρ, θ, v) is split and never "
                "reaches 3 votes. Our variants' results (variant column) do not count.")
    rows.append(ClaimResult.from_claim(
        claims["track_init.xu_table2"],
        paper=f"track 1 confirmed at frame {want[1]}, tracks 2 and 3 at frame {want[2]}, tracks "
              "4 and 5 identified; Table 2 counts lost",
        ours=(f"6-nbhd (paper): confirmed per frame {table2['tracks confirmed'].tolist()}, "
              f"track→frame {got[6]}, {100 * frac[6]:.0f} % of {n_red} redraws right; "
              f"candidates per frame {table2['candidates'].tolist()}"),
        status=status, note=note, variant=variant))

    p3 = claims["track_init.xu_fig3"].paper
    n_want = int(p3["n_tracks_extracted"])
    ok3, frac3, mean_false = {}, {}, {}
    for nb, col in keys.items():
        ok3[nb] = bool(nominal[nb]["exact"] and nominal[nb]["n_tracks"] == n_want)
        r = redraws[redraws["neighbourhood"] == col]
        frac3[nb] = float(r["exact"].mean())
        mean_false[nb] = float(r["false"].mean())
    status = status_xu_fig3(dict(nominal_ok=ok3[6], frac=frac3[6]))
    note = ""
    if status is not Status.REPRODUCED:
        note = (f"paper's 6-neighbourhood: nominal {nominal[6]['n_tracks']} tracks "
                f"(exact={nominal[6]['exact']}), exact recovery in {100 * frac3[6]:.0f} % of "
                f"{n_red} redraws (mean false tracks {mean_false[6]:.2f}); our variants "
                "(variant column) do not count")
    rows.append(ClaimResult.from_claim(
        claims["track_init.xu_fig3"],
        paper=f"{n_want} tracks extracted = the {p3['n_objects']} planted, "
              f"{p3['n_false_tracks']} false",
        ours=(f"6-nbhd (paper): {nominal[6]['n_tracks']} tracks, exact={nominal[6]['exact']}, "
              f"exact in {100 * frac3[6]:.0f} % of redraws"),
        status=status, note=note,
        variant=(f"26-nbhd: {nominal[26]['n_tracks']} tracks, exact={nominal[26]['exact']}, "
                 f"{100 * frac3[26]:.0f} % of redraws (mean false {mean_false[26]:.2f}); "
                 f"verified: exact={nominal['ours']['exact']}, {100 * frac3['ours']:.0f} %")))

    rows.append(_method_comparison_row(claims["track_init.method_comparison"], comp, angle,
                                       comp_trials, n_frames_comp))
    rows.append(evaluate_planted(claims["track_init.planted_scenes"], planted, chance_check,
                                 planted_metrics))
    rows.append(_chance_row(claims["track_init.chance_rate"], chance_check))
    return rows


def _method_comparison_row(claim, comp: pd.DataFrame, angle: pd.DataFrame,
                           comp_trials: pd.DataFrame | None, n_frames: int) -> ClaimResult:
    cl = comp[(comp["sweep"] == "clutter") & (comp["clutter"] > 0)]
    piv_f = cl.pivot(index="clutter", columns="method", values="false_per_frame")
    piv_c = cl.pivot(index="clutter", columns="method", values="p_correct")
    if comp_trials is None:
        raise ValueError("comp_trials (per-trial comparison rows) are needed for the intervals")
    iv = comparison_intervals(comp_trials, n_frames)
    nominal_rows = comp[(comp["sweep"] == "clutter") & (comp["clutter"] <= 10)
                        & (comp["method"] == MH)]
    pd_rows = comp[(comp["sweep"] == "p_detect") & (comp["p_detect"] >= 0.9)
                   & (comp["method"] == MH)]
    mh_pc = float(min(nominal_rows["p_correct"].min(), pd_rows["p_correct"].min()))
    dpc = float(np.max(np.abs(piv_c["angle logic 3/4"] - piv_c["logic 3/4"])))
    m = dict(a=iv["a"], b=iv["b"], b_dpc=dpc, c=iv["c"], c_pc=mh_pc)
    status = status_method_comparison(m)
    words = {k: _ordering(*iv[k], +1 if k == "a" else -1) for k in "abc"}
    top = piv_f.index.max()

    def rng_txt(k):
        lo, hi = iv[k]
        return f"[{min(lo):.3f}, {max(hi):.3f}]"

    ours = (f"paired Bonferroni 95 % intervals over {iv['n']} scenes per density: (a) 2/3 − "
            f"others {words['a']} (all intervals within {rng_txt('a')}); (b) angle − plain "
            f"{words['b']} {rng_txt('b')}, max |ΔP_correct| {dpc:.3f}; (c) modified − classic "
            f"Hough {words['c']} {rng_txt('c')}, modified Hough P_correct ≥ {mh_pc:.3f}. At "
            f"{top:g} false alarms/frame, false tracks/frame: "
            + ", ".join(f"{k} {piv_f.loc[top, k]:.3f}" for k in FIVE))
    note = ("(b) at the 10 px prediction gate the angle constraint never acts (a point within "
            "10 px of a prediction at least v_min·Δt = 10 px ahead always makes an angle > 90°), "
            "so angle − plain is exactly 0 and (b) is not testable at this gate (our assumption, "
            "not the paper's): partial is our gate's doing; it acts with wider gates and denser "
            f"clutter (unpaired, exploratory): {angle_summary(angle)}. The 'paper' modified Hough "
            "is the paper's procedure plus our constant-velocity consistency check")
    if words["a"] != "holds":
        note += f"; (a) {words['a']}"
    if words["c"] != "holds" or mh_pc < 0.9:
        note += f"; (c) {words['c']}, P_correct {mh_pc:.3f}"
    variant = ("modified Hough 3/4 (26-nbhd) and (ours) at the top density: "
               f"{piv_f.loc[top].get('modified Hough 3/4 (26-nbhd)', np.nan):.3f}, "
               f"{piv_f.loc[top].get('modified Hough 3/4 (ours)', np.nan):.3f} false/frame")
    return ClaimResult.from_claim(
        claim, paper="2/3 too loose; angle constraint fewer false tracks at equal P_correct; "
                     "classic Hough heavy, modified Hough initiates several objects in a few "
                     "frames", ours=ours, status=status, note=note, variant=variant)


def angle_summary(angle: pd.DataFrame) -> str:
    """One line per (clutter, gate): false tracks per frame plain → angle-constrained."""
    piv = angle.pivot_table(index=["clutter", "gate_px"], columns="method",
                            values="false_per_frame")
    return "; ".join(f"{lam:g}/frame, {g:g} px: {r['logic 3/4']:.3g} → {r['angle logic 3/4']:.3g}"
                     for (lam, g), r in piv.iterrows())


def evaluate_planted(claim, planted: pd.DataFrame, chance_check: pd.DataFrame,
                     metrics: pd.DataFrame | None = None) -> ClaimResult:
    """Claim ``track_init.planted_scenes``: the paper's literal modified Hough's recall and false
    tracks against the calibrated chance rate; our verified variant and the standard metrics
    (GOSPA, SIAP; ``metrics`` = :func:`~.trials.summarise_metrics`) reported beside it."""
    summ = summarise_planted(planted).set_index("method")
    k = calibrated_chance_factor(chance_check)
    lit, ours = "modified Hough 3/4 (paper)", "modified Hough 3/4 (ours)"

    def meas(name: str) -> dict[str, float]:
        r = summ.loc[name]
        return dict(recall=float(r["recall"]),
                    false_over_chance=float(r["false per scene"] / (k * r["chance per scene"])))

    status = status_planted(meas(lit))

    def fmt(name: str) -> str:
        r, mm = summ.loc[name], meas(name)
        txt = (f"{name}: recall {r['recall']:.3f}, {r['false per scene']:.2f} false/scene = "
               f"{mm['false_over_chance']:.2f} × calibrated chance")
        if metrics is not None and name in metrics.index:
            g = metrics.loc[name]
            txt += (f", GOSPA {g['gospa']:.1f} (missed {g['gospa missed']:.1f}, false "
                    f"{g['gospa false']:.1f}, loc {g['gospa localisation']:.2f}), SIAP C "
                    f"{g['siap completeness']:.3f} S {g['siap spuriousness']:.3f}")
        return txt

    n = int(summ.loc[ours, "scenes"])
    ours_txt = (f"{n} scenes, calibrated chance rate {k * summ.loc[ours, 'chance per scene']:.2f}"
                f" tracks/scene (analytic × {k:.3f}); "
                + "; ".join(fmt(m) for m in summ.index if m != ours))
    note = ""
    if status is not Status.REPRODUCED:
        mm = meas(lit)
        note = (f"the paper's literal procedure misses the criterion (recall {mm['recall']:.3f} "
                f"vs >= 0.95, false/chance {mm['false_over_chance']:.2f} vs <= 1.5); our "
                "verified variant's result (variant column) does not count; 'paper' = the "
                "paper's procedure plus our constant-velocity check, and the chance yardstick "
                "is our χ² rule's, not the cell rule's (the recall half already fails)")
    return ClaimResult.from_claim(
        claim, paper="several objects initiated in a few frames, residual stars no obstacle "
                     "(one 4-frame scene)",
        ours=ours_txt, status=status, note=note, variant=fmt(ours))


def _chance_row(claim, chance_check: pd.DataFrame) -> ClaimResult:
    m = dict(ratio=chance_check["ratio"].tolist(), se=chance_check["ratio s.e."].tolist())
    status = status_chance_rate(m)
    ours = ", ".join(f"{c:g}/frame {r:.3f} ± {s:.3f}" for c, r, s in
                     zip(chance_check["clutter"], m["ratio"], m["se"]))
    k = calibrated_chance_factor(chance_check)
    if status is Status.REPRODUCED:
        note = (f"formula agrees at every level within 3 s.e. and 5 % (pooled ratio {k:.3f}); "
                "scenes per level " + "/".join(str(int(v)) for v in chance_check["scenes"]))
    elif np.any(np.asarray(m["se"]) > 0.02):
        note = (f"too few scenes for the test (s.e. > 0.02 at some level; pooled ratio "
                f"{k:.3f}): not evidence against the formula")
    else:
        note = (f"the formula misses a term at some level (pooled ratio {k:.3f}); the "
                "planted-scene criterion uses the pooled ratio")
    return ClaimResult.from_claim(claim, paper="(ours) analytic count with depletion and conflicts",
                                  ours="measured/analytic " + ours, status=status, note=note)
