"""akf_star claims: the paper's tables beside ours and one scorecard row per claim id."""

from __future__ import annotations

from typing import Any

import numpy as np
import pandas as pd

from eotrack.repro import ClaimResult, Status, load_claims

from .scenario import SLUG
from .trials import AblationResult

__all__ = ["claim_results", "paper_table", "side_by_side"]


def paper_table(claim: Any, key: str) -> pd.DataFrame:
    """A paper table of ``claims.toml`` (``mean_error_px`` or ``success_rate``) as a frame."""
    p = claim.paper
    return pd.DataFrame(p[key], index=p["scenarios"], columns=p["variants"])


def side_by_side(ours: pd.DataFrame, paper: pd.DataFrame, digits: int) -> pd.DataFrame:
    """Paper, ours and ours − paper per variant (columns ``<variant> paper/ours/Δ``)."""
    cols = {}
    for v in ours.columns:
        cols[f"{v} paper"] = paper[v].to_numpy()
        cols[f"{v} ours"] = ours[v].round(digits).to_numpy()
        cols[f"{v} Δ"] = (ours[v].to_numpy() - paper[v].to_numpy()).round(digits)
    return pd.DataFrame(cols, index=ours.index)
def _claims(res: AblationResult, claims: dict[str, Any]) -> list[ClaimResult]:
    E = res.mean_error()
    Ps = res.success_rate()
    C = res.continuity()
    out = []
    n_sc = len(E)

    # Table 1
    best = (E.idxmin(axis=1) == "BEAK-ST")
    worst = (E.idxmax(axis=1) == "Baseline")
    ours = "; ".join(f"{s}: " + "/".join(f"{x:.2f}" for x in row) for s, row in E.iterrows())
    st = Status.REPRODUCED if best.all() and worst.all() else (
        Status.PARTIAL if best.sum() >= 3 else Status.NOT_REPRODUCED)
    note = "" if st is Status.REPRODUCED else (
        f"BEAK-ST lowest in {best.sum()}/{n_sc} scenarios ({', '.join(E.index[~best]) or '-'} "
        f"not), Baseline highest in {worst.sum()}/{n_sc}.")
    note += (" Absolute errors differ from the paper's (simulated star sensor, not OTB100 "
             "frames); Baseline/GT errors are large where the global threshold loses the star.")
    out.append(ClaimResult.from_claim(claims["akf_star.table1"], status=st, note=note.strip(),
                                      ours="mean error px (Baseline/GT/SKF/BEAK-ST) " + ours))

    # Table 2
    top = Ps.max(axis=1)
    best2 = Ps["BEAK-ST"] >= top - 0.005
    worst2 = Ps["Baseline"] <= Ps.min(axis=1) + 0.005
    ours = "; ".join(f"{s}: " + "/".join(f"{x:.3f}" for x in row) for s, row in Ps.iterrows())
    st = Status.REPRODUCED if best2.all() and worst2.all() else (
        Status.PARTIAL if best2.sum() >= 3 else Status.NOT_REPRODUCED)
    note = "" if st is Status.REPRODUCED else (
        f"BEAK-ST highest in {best2.sum()}/{n_sc}, Baseline lowest in {worst2.sum()}/{n_sc}.")
    note += f" ε = {res.config.epsilon_px:g} px adopted (the paper does not state ε)."
    out.append(ClaimResult.from_claim(claims["akf_star.table2"], status=st, note=note.strip(),
                                      ours=f"success rate at ε={res.config.epsilon_px:g} px " + ours))

    # ablation pattern

    p = claims["akf_star.ablation_pattern"].paper
    holds = {}
    for s in p["threshold_helps_most"]:
        holds[s] = bool(E.loc[s, "BEAK-ST-SKF"] < E.loc[s, "BEAK-ST-GT"])
    for s in p["confidence_helps_most"]:
        holds[s] = bool(E.loc[s, "BEAK-ST-GT"] < E.loc[s, "BEAK-ST-SKF"])
    n_hold = sum(holds.values())
    st = Status.REPRODUCED if n_hold == len(holds) and best.all() else (
        Status.PARTIAL if n_hold >= 3 else Status.NOT_REPRODUCED)
    desc = ", ".join(f"{s} {'yes' if h else 'no'}" for s, h in holds.items())
    note = "" if st is Status.REPRODUCED else (
        f"reading holds in {n_hold}/{len(holds)} scenarios ({desc}); BEAK-ST best in "
        f"{best.sum()}/{n_sc}.")

    out.append(ClaimResult.from_claim(claims["akf_star.ablation_pattern"], status=st,
                                      ours=f"{n_hold}/{len(holds)} readings hold: {desc}",
                                      note=note))

    # Figs. 6-7
    curve = res.errors.mean(axis=(0, 1))                        # (V, n)
    i_b = res.variants.index("BEAK-ST")
    frac6 = float(np.mean(np.argmin(curve, axis=0) == i_b))
    st = Status.REPRODUCED if frac6 >= 0.8 else (Status.PARTIAL if frac6 >= 0.5
                                                 else Status.NOT_REPRODUCED)
    out.append(ClaimResult.from_claim(
        claims["akf_star.fig6"], status=st, ours=f"BEAK-ST lowest in {100 * frac6:.0f} % of frames",
        note="" if st is Status.REPRODUCED else
        f"BEAK-ST's mean-error curve is the lowest in only {100 * frac6:.0f} % of the frames."))
    sc = (res.errors <= res.config.epsilon_px).mean(axis=(0, 1))
    frac7 = float(np.mean(sc[i_b] >= sc.max(axis=0) - 0.01))
    st = Status.REPRODUCED if frac7 >= 0.8 else (Status.PARTIAL if frac7 >= 0.5
                                                 else Status.NOT_REPRODUCED)
    out.append(ClaimResult.from_claim(
        claims["akf_star.fig7"], status=st,
        ours=f"BEAK-ST highest (±0.01) in {100 * frac7:.0f} % of frames",
        note="" if st is Status.REPRODUCED else
        f"BEAK-ST's success curve is the highest in only {100 * frac7:.0f} % of the frames."))

    # headline
    cont = C["BEAK-ST"]
    red = 1 - E["BEAK-ST"].mean() / E["Baseline"].mean()
    ok_c = bool((cont > claims["akf_star.headline"].paper["continuity_min"]).all())
    ok_r = bool(0.25 <= red <= 0.60)
    st = Status.REPRODUCED if ok_c and ok_r else (
        Status.PARTIAL if ok_c or ok_r or red > 0.25 else Status.NOT_REPRODUCED)
    ours = (f"continuity of BEAK-ST {cont.min():.3f}-{cont.max():.3f} over the scenarios; mean "
            f"error {E['BEAK-ST'].mean():.2f} px vs Baseline {E['Baseline'].mean():.2f} px "
            f"({100 * red:.0f} % lower); BEAK-ST success rate {Ps['BEAK-ST'].min():.3f}-"
            f"{Ps['BEAK-ST'].max():.3f}")
    note = ("Continuity is our definition (estimate within the "
            f"{res.config.gate_px:g} px gate, occluded frames included); the paper's 40 % and its "
            "own Table 1 (52 %) disagree, and no Table 2 rate reaches 0.95, so 'continuity' must "
            "be a looser measure than the success rate.")
    if not ok_c:
        note += f" Continuity below 0.95 in {int((cont <= 0.95).sum())} scenario(s)."
    if not ok_r:
        note += (f" Error reduction {100 * red:.0f} % (outside 25-60 %): "
                 + ("the global-threshold Baseline loses the star altogether under strong and "
                    "stray light." if red > 0.6 else "smaller than the paper's."))
    out.append(ClaimResult.from_claim(claims["akf_star.headline"], status=st, ours=ours,
                                      note=note))
    return out


def claim_results(res: AblationResult) -> list[ClaimResult]:
    """One scorecard row per claim id, from an ablation result."""
    return _claims(res, load_claims(SLUG))


