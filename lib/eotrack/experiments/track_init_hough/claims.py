"""Each claim of ``papers_repro/track_init_hough/claims.toml`` evaluated against its criterion."""

from __future__ import annotations

import numpy as np
import pandas as pd

from eotrack.repro import ClaimResult, Status

from .scenario import XuConfig
from .trials import summarise_planted

__all__ = ["angle_summary", "evaluate", "evaluate_planted"]

MH = "modified Hough 3/4"


def _xu_status(ok6: bool, frac6: float, ok26: bool, frac26: float, full: float,
               part: float) -> Status:
    if ok6 and frac6 >= full:
        return Status.REPRODUCED
    if (ok6 and frac6 >= part) or (ok26 and frac26 >= full):
        return Status.PARTIAL
    return Status.NOT_REPRODUCED


def evaluate(claims, cfg: XuConfig, table2: pd.DataFrame, nominal: dict[int, dict],
             redraws: pd.DataFrame, comp: pd.DataFrame, angle: pd.DataFrame,
             planted: pd.DataFrame, chance_check: pd.DataFrame) -> list[ClaimResult]:
    """Every claim of claims.toml evaluated against its criterion (see the module doc)."""
    rows = []
    p2 = claims["track_init.xu_table2"].paper
    want = {0: int(p2["confirm_frame_track1"]), 1: int(p2["confirm_frame_track2"]),
            2: int(p2["confirm_frame_track3"]), 3: cfg.n_frames, 4: cfg.n_frames}

    def frames_ok(cf: dict, n_false: int) -> bool:
        return {i: f + 1 for i, f in cf.items()} == want and n_false == 0

    ok, frac, got = {}, {}, {}
    for nb in (6, 26):
        got[nb] = {i + 1: f + 1 for i, f in sorted(nominal[nb]["confirm_frame"].items())}
        ok[nb] = frames_ok(nominal[nb]["confirm_frame"], nominal[nb]["false"])
        r = redraws[redraws["neighbourhood"] == nb]
        frac[nb] = float(np.mean([frames_ok(cf, fl) for cf, fl in
                                  zip(r["confirm_frame"], r["false"])]))
    n_red = int((redraws["neighbourhood"] == 6).sum())
    status = _xu_status(ok[6], frac[6], ok[26], frac[26], 0.95, 0.0)
    note = ""
    if status is not Status.REPRODUCED:
        note = (f"paper's 6-neighbourhood: nominal scene track→frame {got[6]} (want "
                f"{ {i + 1: f for i, f in want.items()} }), false {nominal[6]['false']}; same "
                f"frames and no false track in {100 * frac[6]:.0f} % of {n_red} redraws. A track "
                "whose pair cells differ in two of (ρ, θ, v) is split and never reaches 3 votes. "
                f"With the 26-neighbourhood (our deviation): nominal {got[26]}, "
                f"{100 * frac[26]:.0f} % of redraws")
    rows.append(ClaimResult.from_claim(
        claims["track_init.xu_table2"],
        paper=f"track 1 confirmed at frame {want[0]}, tracks 2 and 3 at frame {want[1]}, tracks "
              "4 and 5 identified; Table 2 counts lost",
        ours=(f"6-nbhd (paper): confirmed per frame {table2['tracks confirmed'].tolist()}, "
              f"track→frame {got[6]}, {100 * frac[6]:.0f} % of {n_red} redraws right; "
              f"26-nbhd: {got[26]}, {100 * frac[26]:.0f} %; candidates per frame "
              f"{table2['candidates'].tolist()}"),
        status=status, note=note))

    p3 = claims["track_init.xu_fig3"].paper
    n_want = int(p3["n_tracks_extracted"])
    ok3, frac3 = {}, {}
    for nb in (6, 26):
        ok3[nb] = bool(nominal[nb]["exact"] and nominal[nb]["n_tracks"] == n_want)
        frac3[nb] = float(redraws[redraws["neighbourhood"] == nb]["exact"].mean())
    status = _xu_status(ok3[6], frac3[6], ok3[26], frac3[26], 0.95, 0.8)
    mean_false = {nb: float(redraws[redraws["neighbourhood"] == nb]["false"].mean())
                  for nb in (6, 26)}
    note = ""
    if status is not Status.REPRODUCED:
        note = (f"paper's 6-neighbourhood: nominal {nominal[6]['n_tracks']} tracks "
                f"(exact={nominal[6]['exact']}), exact recovery in {100 * frac3[6]:.0f} % of "
                f"{n_red} redraws (mean false tracks {mean_false[6]:.2f}); 26-neighbourhood "
                f"(our deviation): nominal exact={nominal[26]['exact']}, "
                f"{100 * frac3[26]:.0f} % (mean false {mean_false[26]:.2f})")
    rows.append(ClaimResult.from_claim(
        claims["track_init.xu_fig3"],
        paper=f"{n_want} tracks extracted = the {p3['n_objects']} planted, "
              f"{p3['n_false_tracks']} false",
        ours=(f"6-nbhd: {nominal[6]['n_tracks']} tracks, exact={nominal[6]['exact']}, exact in "
              f"{100 * frac3[6]:.0f} % of redraws; 26-nbhd: {nominal[26]['n_tracks']} tracks, "
              f"exact={nominal[26]['exact']}, {100 * frac3[26]:.0f} %"),
        status=status, note=note))

    cl = comp[(comp["sweep"] == "clutter") & (comp["clutter"] > 0)]
    piv_f = cl.pivot(index="clutter", columns="method", values="false_per_frame")
    piv_c = cl.pivot(index="clutter", columns="method", values="p_correct")
    a_ok = bool(np.all(piv_f.idxmax(axis=1) == "logic 2/3"))
    b_ok = bool(np.all(piv_f["angle logic 3/4"] < piv_f["logic 3/4"])
                and np.all(np.abs(piv_c["angle logic 3/4"] - piv_c["logic 3/4"]) <= 0.02))
    nominal_rows = comp[(comp["sweep"] == "clutter") & (comp["clutter"] <= 10)
                        & (comp["method"] == MH)]
    pd_rows = comp[(comp["sweep"] == "p_detect") & (comp["p_detect"] >= 0.9)
                   & (comp["method"] == MH)]
    mh_pc = float(min(nominal_rows["p_correct"].min(), pd_rows["p_correct"].min()))
    c_ok = bool(np.all(piv_f[MH] < piv_f["classic Hough 3/4"])) and mh_pc >= 0.9
    n_ok = a_ok + b_ok + c_ok
    status = (Status.REPRODUCED if n_ok == 3 else Status.PARTIAL if n_ok == 2
              else Status.NOT_REPRODUCED)
    angle_note = angle_summary(angle)
    top = piv_f.index.max()
    ours = (f"(a) 2/3 most false tracks at every density: {a_ok}; (b) angle < 3/4 false and "
            f"|ΔP_correct| ≤ 0.02: {b_ok}; (c) modified < classic Hough false tracks: "
            f"{bool(np.all(piv_f[MH] < piv_f['classic Hough 3/4']))}, "
            f"modified Hough P_correct ≥ {mh_pc:.3f}. At {top:g} false alarms/frame, false "
            "tracks/frame: " + ", ".join(f"{k} {v:.3f}" for k, v in piv_f.loc[top].items()))
    ang = piv_f["angle logic 3/4"] - piv_f["logic 3/4"]
    note = ("(b) at the 10 px prediction gate the angle constraint never acts (a point within "
            "10 px of a prediction at least v_min·Δt = 10 px ahead always makes an angle > 90°); "
            f"false-track differences angle − plain {ang.round(4).to_dict()}; it acts with "
            f"wider gates and denser clutter: {angle_note}")
    if status is not Status.REPRODUCED:
        parts = [note]
        if not a_ok:
            parts.append("(a) fails: most false tracks per density "
                         f"{piv_f.idxmax(axis=1).to_dict()}")
        if not b_ok:
            parts.append("(b) fails: angle − plain false tracks "
                         f"{(piv_f['angle logic 3/4'] - piv_f['logic 3/4']).round(4).to_dict()}, "
                         "ΔP_correct "
                         f"{(piv_c['angle logic 3/4'] - piv_c['logic 3/4']).round(3).to_dict()}")
        if not c_ok:
            parts.append("(c) fails: modified vs classic Hough false tracks "
                         f"{piv_f[MH].round(3).to_dict()} vs "
                         f"{piv_f['classic Hough 3/4'].round(3).to_dict()}, modified Hough "
                         f"P_correct min {mh_pc:.3f}")
        note = "; ".join(parts)
    rows.append(ClaimResult.from_claim(
        claims["track_init.method_comparison"],
        paper="2/3 too loose; angle constraint fewer false tracks at equal P_correct; classic "
              "Hough heavy, modified Hough initiates several objects in a few frames",
        ours=ours, status=status, note=note))
    rows.append(evaluate_planted(claims["track_init.planted_scenes"], planted, chance_check))
    return rows


def angle_summary(angle: pd.DataFrame) -> str:
    """One line per (clutter, gate): false tracks per frame plain → angle-constrained."""
    piv = angle.pivot_table(index=["clutter", "gate_px"], columns="method",
                            values="false_per_frame")
    return "; ".join(f"{lam:g}/frame, {g:g} px: {r['logic 3/4']:.3g} → {r['angle logic 3/4']:.3g}"
                     for (lam, g), r in piv.iterrows())


def evaluate_planted(claim, planted: pd.DataFrame, chance_check: pd.DataFrame) -> ClaimResult:
    """Claim ``track_init.planted_scenes``: recall and false tracks against the chance rate."""
    p = claim.paper
    rmin, qmax = float(p["recall_min"]), float(p["false_over_chance_max"])
    tol = float(p["chance_check_tolerance"])
    summ = summarise_planted(planted).set_index("method")
    ratio_ok = bool(np.all(np.abs(chance_check["ratio"] - 1) <= tol))

    def holds(name: str) -> bool:
        r = summ.loc[name]
        return bool(r["recall"] >= rmin and r["false / chance"] <= qmax and ratio_ok)

    lit, ours = "modified Hough 3/4 (paper)", "modified Hough 3/4 (ours)"
    status = (Status.REPRODUCED if holds(lit) else Status.PARTIAL if holds(ours)
              else Status.NOT_REPRODUCED)

    def fmt(name: str) -> str:
        r = summ.loc[name]
        return (f"{name}: recall {r['recall']:.3f}, {r['false per scene']:.2f} false/scene = "
                f"{r['false / chance']:.2f} × chance")

    n = int(summ.loc[ours, "scenes"])
    ours_txt = (f"{n} scenes, chance rate {summ.loc[ours, 'chance per scene']:.2f} tracks/scene; "
                + "; ".join(fmt(m) for m in summ.index)
                + "; clutter-only check measured/analytic "
                + ", ".join(f"{c:g}/frame {r:.2f}" for c, r in
                            zip(chance_check["clutter"], chance_check["ratio"])))
    note = ""
    if status is not Status.REPRODUCED:
        r = summ.loc[lit]
        note = (f"the paper's literal procedure misses the criterion (recall {r['recall']:.3f} vs "
                f">= {rmin}, false/chance {r['false / chance']:.2f} vs <= {qmax}); our verified "
                f"variant {'meets' if holds(ours) else 'misses'} it"
                + ("" if ratio_ok else "; the analytic chance rate failed its Monte Carlo check"))
    return ClaimResult.from_claim(
        claim, paper="several objects initiated in a few frames, residual stars no obstacle "
                     "(one 4-frame scene)",
        ours=ours_txt, status=status, note=note)
