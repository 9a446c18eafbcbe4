"""Tables and claim scoring of Huang, Zhang & Feng: each table of the paper from the scenario,
the displayed draw and the Monte Carlo (the notebook calls the same functions), the pure
evaluators that decide each claim's status from a small measurement, and :func:`score`, which
measures, calls the evaluators and assembles the report."""

from __future__ import annotations

import warnings
from dataclasses import replace

import numpy as np
import pandas as pd
from scipy.stats import t as student_t

from eotrack.geometry.triangulation import combine_estimates
from eotrack.montecarlo import TrialRunner, binomial_interval, run_trials
from eotrack.repro import ClaimResult, Reproduction, Status, evaluator, load_claims

from .scenario import EPOCH_UTC, PAIR_LABELS, PAIRS, SLUG, TITLE, ErrorConfig, Scenario
from .trials import (
    DisplayedDraw,
    MonteCarlo,
    SweepResult,
    closest_other_object_px,
    distance_sigma_px,
    error_budget_gate,
    objects_recovered,
    placement_trial,
    row_labels,
    sweep_rates,
    triangulate_object,
)

CONTRADICTED = Status.CONTRADICTED

__all__ = [
    "fig4_measure",
    "fig5_bootstrap",
    "fig5_summary",
    "fig5_table",
    "fig6_table",
    "paper_values",
    "placement_study",
    "rules_table",
    "score",
    "status_fig3",
    "status_fig4",
    "status_fig5",
    "status_fig6",
    "status_fig8",
    "status_table1",
    "status_table2",
    "status_table3",
    "status_table4",
    "status_table5",
    "table1",
    "table2_check",
    "table3",
    "table3_measure",
    "table4",
    "table4_paired",
    "table5",
]

_ERRORS = ErrorConfig()  # the paper's error model (default argument)


def paper_values() -> dict[str, dict]:
    """The paper's values of every claim (from ``papers_repro/epipolar/claims.toml``)."""
    return {k: c.paper for k, c in load_claims(SLUG).items()}


def _fmt(v: float, nd: int = 2) -> str:
    return "—" if v is None or not np.isfinite(v) else f"{v:.{nd}f}"


def table1(scen: Scenario) -> pd.DataFrame:
    """Table 1 (paper's elements) beside our two-body positions and Earth-clear sight lines."""
    t1 = paper_values()["epipolar.table1"]
    df = pd.DataFrame({"sat": t1["satellites"], "a_km": t1["a_km"], "e": t1["e"],
                       "i_deg": t1["i_deg"], "raan_deg": t1["raan_deg"],
                       "argp_deg": t1["argp_deg"], "nu_deg": t1["nu_deg"]})
    for i, n in enumerate("xyz"):
        df[f"r{n}_km (ours)"] = np.round(scen.sat_km[:, i], 1)
    df["clear LOS to its objects (ours)"] = [
        f"{int(scen.los_clear[k][scen.visible[k]].sum())}/{int(scen.visible[k].sum())}"
        for k in range(len(scen.cameras))]
    return df


def table3(scen: Scenario, draw: DisplayedDraw) -> pd.DataFrame:
    """Table 3: per object, the paper's pixels beside our noise-free true pixels (the scene),
    and what the displayed draw's summary made of the object: its rows labelled by the true
    identity of their elements (object name, ``false`` for a false target)."""
    obs, rows = draw.obs, draw.rows
    lab = row_labels(obs, rows)
    true_px = scen.true_pixels()
    out = []
    for j, name in enumerate(scen.names):
        rec = {"target": name}
        for k in range(len(scen.cameras)):
            pp = scen.paper_px[k, j]
            rec[f"map {k + 1} paper"] = "" if np.isnan(pp[0]) else f"({pp[0]:.0f},{pp[1]:.0f})"
            q = true_px[k, j]
            rec[f"map {k + 1} ours"] = f"({q[0]:.0f},{q[1]:.0f})" if scen.visible[k, j] else ""
        mine = [r for r in lab if np.any(r == j)]
        exact = [r for r in mine if np.all(r[r >= -1] == j)
                 and np.array_equal(r >= 0, scen.visible[:, j])]
        if exact:
            rec["displayed draw"] = "one exact row"
        elif not mine:
            rec["displayed draw"] = "no multi-map row"
        else:
            rec["displayed draw"] = " + ".join(
                "[" + ", ".join("·" if v == -2 else "false" if v == -1 else scen.names[v]
                                for v in r) + "]" for r in mine)
        out.append(rec)
    return pd.DataFrame(out)


def table4(draw: DisplayedDraw, mc: MonteCarlo) -> pd.DataFrame:
    """Table 4: mean distance of associated points to the line, paper beside the means over
    the Monte Carlo draws (all associated pairs, and the correct ones only). ``draw`` is kept
    for backward compatibility (the displayed draw no longer decides the claim)."""
    p4 = paper_values()["epipolar.table4"]
    n = mc.n_draws
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # pair (d): no correct pairs
        noisy = np.nanmean(mc.stack("mean_d"), 0)
        free = np.nanmean(mc.stack("mean_d0"), 0)
        noisy_t = np.nanmean(mc.stack("mean_d_true"), 0)
        free_t = np.nanmean(mc.stack("mean_d0_true"), 0)
    return pd.DataFrame({
        "pair": p4["pairs"],
        "paper noise-free (px)": p4["mean_distance_noise_free_px"],
        f"ours noise-free, {n} draws (px)": np.round(free, 3),
        "ours noise-free, correct pairs (px)": np.round(free_t, 3),
        "paper noisy (px)": p4["mean_distance_noisy_px"],
        f"ours noisy, {n} draws (px)": np.round(noisy, 3),
        "ours noisy, correct pairs (px)": np.round(noisy_t, 3),
        "noisy: ours − paper (px)": np.round(noisy - np.asarray(p4["mean_distance_noisy_px"]), 3),
    })


def fig5_table(sw: SweepResult) -> pd.DataFrame:
    """The Fig. 5 curves at every other threshold."""
    return pd.DataFrame({"L (px)": sw.thresholds, "correct": sw.accuracy.round(4),
                         "false (of associated)": sw.false_rate.round(4),
                         "missed": sw.miss_rate.round(4),
                         "total error": sw.error_rate.round(4)})[::2]


def fig5_summary(sw: SweepResult, boot: dict | None = None) -> pd.DataFrame:
    """Fig. 5's numbers, paper beside ours with the difference (and the bootstrap intervals
    of :func:`fig5_bootstrap` if given)."""
    p5 = paper_values()["epipolar.fig5"]
    lo, hi = p5["best_threshold_px"]
    band = (sw.thresholds >= lo) & (sw.thresholds <= hi)
    i = int(np.argmax(np.where(band, sw.accuracy, -1)))
    acc = float(sw.accuracy[i])

    def ci(k: str, f: float) -> str:
        return "" if boot is None else f"{f * boot[k][0]:.1f}–{f * boot[k][1]:.1f}"

    return pd.DataFrame([
        {"quantity": f"correct of true pairs (recall), best L in {lo:g}–{hi:g} px",
         "paper": p5["accuracy_at_best"], "ours": round(acc, 4),
         "ours interval": ci("acc_ci", 100) + (" %" if boot else ""),
         "ours − paper": round(acc - p5["accuracy_at_best"], 4),
         "at L (px)": float(sw.thresholds[i])},
        {"quantity": f"correct of associated (paper's 1 − 误判率), best L in {lo:g}–{hi:g} px",
         "paper": p5["accuracy_at_best"], "ours": "" if boot is None else round(boot["prec"], 4),
         "ours interval": ci("prec_ci", 100) + (" %" if boot else ""),
         "ours − paper": "" if boot is None else round(boot["prec"] - p5["accuracy_at_best"], 4),
         "at L (px)": np.nan if boot is None else boot["prec_L"]},
        {"quantity": "L of smallest total error (px)", "paper": f"{lo:g}–{hi:g}",
         "ours": sw.best_threshold, "ours interval": ci("best_L_ci", 1),
         "ours − paper": "", "at L (px)": sw.best_threshold},
        {"quantity": "groups of maps (draws)", "paper": p5["n_groups"], "ours": "",
         "ours interval": "", "ours − paper": "", "at L (px)": np.nan},
        {"quantity": "associated pairs at the best in-band L", "paper": p5["n_associated_pairs"],
         "ours": int(sw.n_associated[i]), "ours interval": "", "ours − paper": "",
         "at L (px)": float(sw.thresholds[i])},
        {"quantity": "true pairs", "paper": "", "ours": sw.n_true, "ours interval": "",
         "ours − paper": "", "at L (px)": np.nan},
    ])


def fig6_table(res6: dict) -> pd.DataFrame:
    """Fig. 6: paper, our Monte Carlo and its binomial / Poisson expectation, both variants."""
    p6 = paper_values()["epipolar.fig6"]
    run, an, po = res6["overlapping"]
    runr, anr, por = res6["random_f"]
    return pd.DataFrame({
        "L (px)": p6["threshold_px"], "paper": p6["max_false_rate"],
        "ours MC (overlapping views)": run[-1].round(3),
        "binomial (overlapping)": an.round(3), "Poisson (overlapping)": po.round(3),
        "ours MC (random F)": runr[-1].round(3), "binomial (random F)": anr.round(3),
        "Poisson (random F)": por.round(3)})


def table5(scen: Scenario, draw: DisplayedDraw) -> tuple[pd.DataFrame, dict]:
    """Table 5: pairwise and combined triangulation of GEO1 and GEO5, paper beside ours.

    Returns the table and ``{name: {"pairs", "combined", "truth"}}`` for Fig. 8.
    """
    p5t = paper_values()["epipolar.table5"]
    est_all, rows_out = {}, []
    for obj, key in ((0, "geo1_km"), (4, "geo5_km")):
        name = scen.names[obj]
        est, nray = triangulate_object(draw.obs, draw.rows, obj)
        truth = scen.objects_km[obj]
        comb = combine_estimates(np.stack(list(est.values())), rule="paper") if est else None
        est_all[name] = {"pairs": est, "combined": comb.position if comb else truth,
                         "truth": truth}
        paper_rows = dict(zip(p5t["pairs"], p5t[key]))
        for lbl in [*p5t["pairs"][:-2], "mean", "N-ray LS", "truth"]:
            pair = tuple(int(s) - 1 for s in lbl.split("&")) if "&" in lbl else None
            if pair is not None:
                ours = est.get(pair)
            elif lbl == "mean":
                ours = comb.position if comb else None
            elif lbl == "N-ray LS":
                ours = nray
            else:
                ours = truth
            pp = paper_rows.get(lbl, [np.nan] * 3)
            rows_out.append({
                "object": name, "pair": lbl,
                "paper (km)": "—" if np.isnan(pp[0]) else
                f"({pp[0]:.2f}, {pp[1]:.2f}, {pp[2]:.2f})",
                "ours (km)": "—" if ours is None else
                f"({ours[0]:.2f}, {ours[1]:.2f}, {ours[2]:.2f})",
                "ours − truth max |Δ| (km)": np.nan if ours is None else
                float(np.abs(ours - truth).max())})
    return pd.DataFrame(rows_out), est_all


def rules_table(mc: MonteCarlo) -> pd.DataFrame:
    """Beyond the paper: false and missed pairs of three association rules at the threshold."""
    n_true = mc.sweep.n_true
    return pd.DataFrame({
        "rule": ["paper (greedy nearest)", "global assignment (Hungarian)",
                 "paper + three-view check"],
        "false associations": [mc.total("false_nominal"), mc.total("false_hungarian"),
                               mc.total("false_3view")],
        "missed true pairs": [mc.total("missed_nominal"), mc.total("missed_hungarian"),
                              mc.total("missed_3view")],
        "true pairs": [int(n_true)] * 3})


# --------------------------------------------------------------------------- evaluators
# Each claim's status is a pure function of a small measurement (dict of numbers and
# intervals); the synthetic cases reach every status the function can return.
R_, P_, N_ = Status.REPRODUCED, Status.PARTIAL, Status.NOT_REPRODUCED


@evaluator("epipolar.table1", cases=[
    (dict(n_clear=23, n_sight=23, pattern_ok=True), R_),
    (dict(n_clear=22, n_sight=23, pattern_ok=True), N_),
    (dict(n_clear=23, n_sight=23, pattern_ok=False), N_)])
def status_table1(m: dict) -> Status:
    """Pass iff every sensor–object line of sight is Earth-clear and Table 3's pattern is
    realised."""
    return R_ if m["n_clear"] == m["n_sight"] and m["pattern_ok"] else N_


@evaluator("epipolar.table2", cases=[
    (dict(offaxis_err_px=1e-9, max_distortion_px=0.1, accuracy_px=0.4), R_),
    (dict(offaxis_err_px=0.5, max_distortion_px=0.1, accuracy_px=0.4), N_),
    (dict(offaxis_err_px=1e-9, max_distortion_px=2.0, accuracy_px=0.4), N_),
    (dict(offaxis_err_px=1e-9, max_distortion_px=0.1, accuracy_px=1.5), N_)])
def status_table2(m: dict) -> Status:
    """Pass iff eq. (7) puts 1° at 256 px, distortion stays below 0.5 px and the X/Y accuracy
    is sub-pixel."""
    ok = m["offaxis_err_px"] < 1e-6 and m["max_distortion_px"] < 0.5 and m["accuracy_px"] < 1
    return R_ if ok else N_


@evaluator("epipolar.fig3", cases=[
    (dict(objects_per_map=[6, 4, 4, 9], paper=[6, 4, 4, 9], shared_23=0), R_),
    (dict(objects_per_map=[6, 4, 5, 9], paper=[6, 4, 4, 9], shared_23=0), N_),
    (dict(objects_per_map=[6, 4, 4, 9], paper=[6, 4, 4, 9], shared_23=1), N_)])
def status_fig3(m: dict) -> Status:
    """Pass iff the objects per map equal Table 3's and maps 2 and 3 share none."""
    ok = list(m["objects_per_map"]) == list(m["paper"]) and m["shared_23"] == 0
    return R_ if ok else N_


@evaluator("epipolar.fig4", cases=[
    (dict(share_ci=(0.6, 0.8), shared_23=0, n_false=40), R_),
    (dict(share_ci=(0.02, 0.2), shared_23=0, n_false=40), P_),
    (dict(share_ci=(0.0, 0.05), shared_23=0, n_false=40), N_),
    (dict(share_ci=(0.6, 0.8), shared_23=0, n_false=0), N_),
    (dict(share_ci=(0.6, 0.8), shared_23=2, n_false=40), N_)])
def status_fig4(m: dict) -> Status:
    """Share of draws with every true pair associated (95 % Wilson interval) and the pair
    structure of Fig. 4 (see the claim's criterion). Our three-view check (a variant) is
    reported, not scored."""
    structure = m["shared_23"] == 0 and m["n_false"] > 0
    lo, hi = m["share_ci"]
    if structure and lo >= 0.5:
        return R_
    if structure and hi < 0.5 and hi >= 0.1:
        return P_
    return N_


@evaluator("epipolar.table3", cases=[
    (dict(all_nine_ci=(0.55, 0.7), mean_recovered_ci=(8.4, 8.6), n_objects=9), R_),
    (dict(all_nine_ci=(0.2, 0.3), mean_recovered_ci=(7.2, 7.6), n_objects=9), P_),
    (dict(all_nine_ci=(0.2, 0.3), mean_recovered_ci=(6.8, 7.4), n_objects=9), N_),
    (dict(all_nine_ci=(0.0, 0.02), mean_recovered_ci=(5.5, 6.0), n_objects=9), N_)])
def status_table3(m: dict) -> Status:
    """Over the draws: all nine objects recovered in a majority of draws (95 % Wilson lower
    end >= 0.5); partial if the 95 % interval of the mean number recovered lies at or above
    7 of 9."""
    if m["all_nine_ci"][0] >= 0.5:
        return R_
    return P_ if m["mean_recovered_ci"][0] >= 7 else N_


@evaluator("epipolar.table4", cases=[
    (dict(diff_ci=[(0.5, 1.0)] * 5, level_ratio=[1.2, 0.8, 1.5, 0.7]), R_),
    (dict(diff_ci=[(0.5, 1.0)] * 5, level_ratio=[1.2, 0.8, 1.5, 0.29]), P_),
    (dict(diff_ci=[(0.5, 1.0)] * 3 + [(-0.2, 0.4)] * 2, level_ratio=[1.0] * 4), P_),
    (dict(diff_ci=[(0.5, 1.0)] * 4 + [(-1.0, -0.2)], level_ratio=[1.0] * 4), N_),
    (dict(diff_ci=[(-0.3, 0.4)] * 5, level_ratio=[1.0] * 4), N_),
    (dict(diff_ci=[(-1.0, -0.2)] * 3 + [(0.5, 1.0)] * 2, level_ratio=[1.0] * 4), CONTRADICTED)])
def status_table4(m: dict) -> Status:
    """Paired (noisy − noise-free) mean-distance intervals, one per map pair with true pairs
    (family-wise 95 %), and our noisy level over the paper's per pair (``level_ratio``, the
    pairs where the paper prints a noisy value): see the claim's criterion."""
    ci = np.asarray(m["diff_ci"], float)
    above = int(np.sum(ci[:, 0] > 0))
    below = int(np.sum(ci[:, 1] < 0))
    n = len(ci)
    ratio = np.asarray(m["level_ratio"], float)
    level_ok = bool(np.all((ratio >= 0.5) & (ratio <= 2.0)))
    if below >= n // 2 + 1:
        return CONTRADICTED
    if above == n and level_ok:
        return R_
    if above >= n // 2 + 1 and below == 0:
        return P_
    return N_


@evaluator("epipolar.fig5", cases=[
    (dict(best_L_ci=(8.5, 11.0), acc_ci=(0.86, 0.9), prec_ci=(0.86, 0.9), band=(8, 12),
          acc_min=0.85), R_),
    (dict(best_L_ci=(4.0, 5.0), acc_ci=(0.86, 0.9), prec_ci=(0.86, 0.9), band=(8, 12),
          acc_min=0.85), P_),
    (dict(best_L_ci=(9.0, 10.0), acc_ci=(0.80, 0.84), prec_ci=(0.86, 0.9), band=(8, 12),
          acc_min=0.85), P_),
    (dict(best_L_ci=(9.0, 10.0), acc_ci=(0.86, 0.9), prec_ci=(0.70, 0.75), band=(8, 12),
          acc_min=0.85), P_),
    (dict(best_L_ci=(7.0, 10.0), acc_ci=(0.86, 0.88), prec_ci=(0.70, 0.75), band=(8, 12),
          acc_min=0.85), N_),
    (dict(best_L_ci=(4.0, 5.0), acc_ci=(0.70, 0.75), prec_ci=(0.86, 0.9), band=(8, 12),
          acc_min=0.85), N_)])
def status_fig5(m: dict) -> Status:
    """Best threshold's bootstrap interval against the paper's 8–12 px, and the best in-band
    correct rate against 85 % under BOTH readings of "correct" (of the true pairs, ``acc_ci``;
    of the associated pairs, ``prec_ci`` — the paper's 误判率 reading)."""
    lo, hi = m["band"]
    best_in = m["best_L_ci"][0] >= lo and m["best_L_ci"][1] <= hi
    acc_ok = m["acc_ci"][0] >= m["acc_min"] and m["prec_ci"][0] >= m["acc_min"]
    if best_in and acc_ok:
        return R_
    return P_ if (best_in or acc_ok) else N_


@evaluator("epipolar.fig6", cases=[
    (dict(mc_vs_analytic=0.01, paper_gap=0.02), R_),
    (dict(mc_vs_analytic=0.01, paper_gap=0.40), N_)])
def status_fig6(m: dict) -> Status:
    """The paper within 3 points of our MC. Our MC must agree with its own expectation within
    2 points: if it does not, that is a defect of our simulation, not a finding about the
    paper, and ``RuntimeError`` is raised instead of a status."""
    if not m["mc_vs_analytic"] < 0.02:
        raise RuntimeError(f"Fig. 6: our Monte Carlo is {m['mc_vs_analytic']:.3f} from its own "
                           "binomial expectation (> 0.02): a simulation defect, not a result")
    return R_ if m["paper_gap"] < 0.03 else N_


@evaluator("epipolar.table5", cases=[
    (dict(share_ok_ci=(0.55, 0.75)), R_),
    (dict(share_ok_ci=(0.40, 0.62)), N_),
    (dict(share_ok_ci=(0.0, 0.013)), N_)])
def status_table5(m: dict) -> Status:
    """Both objects within the tolerance in a majority of the draws: the 95 % Wilson interval
    of that share has its lower end >= 0.5."""
    return R_ if m["share_ok_ci"][0] >= 0.5 else N_


@evaluator("epipolar.fig8", cases=[
    (dict(share_ci=(0.6, 0.8)), R_),
    (dict(share_ci=(0.4, 0.6)), P_),
    (dict(share_ci=(0.08, 0.16)), N_)])
def status_fig8(m: dict) -> Status:
    """Share of draws in which both combined estimates' errors are below a tenth of the
    objects' separation (95 % Wilson interval): above 0.5 reproduced, containing 0.5 partial,
    below not reproduced."""
    lo, hi = m["share_ci"]
    if lo >= 0.5:
        return R_
    return P_ if hi >= 0.5 else N_


# --------------------------------------------------------------------------- measurements
def table2_check(scen: Scenario) -> dict:
    """Measurement of ``epipolar.table2``: eq. (7) at 1° off axis, the largest distortion
    shift over the image, the X/Y accuracy in pixels."""
    from eotrack.geometry.camera import project_points

    s = scen.sensor
    K = s.K
    uv = project_points([[np.tan(np.radians(s.fov_deg / 2)), 0.0, 1.0]], K, np.eye(3),
                        np.zeros(3))[0]
    n = s.resolution_px
    g = np.linspace(-0.5, n - 0.5, 33)
    px = np.stack(np.meshgrid(g, g), -1).reshape(-1, 2)
    d = np.linalg.solve(K, np.column_stack([px, np.ones(len(px))]).T).T
    shift = project_points(d, K, np.eye(3), np.zeros(3), s.dist) - px
    return {"offaxis_err_px": float(abs(uv[0] - s.principal_point_px[0] - n / 2)),
            "max_distortion_px": float(np.hypot(*shift.T).max()),
            "accuracy_px": float(np.radians(s.accuracy_xy_arcsec / 3600) * K[0, 0])}


def fig4_measure(scen: Scenario, mc: MonteCarlo, *, confidence: float = 0.95) -> dict:
    """Measurement of ``epipolar.fig4`` over the Monte Carlo draws (Wilson interval)."""
    k = int(np.sum(mc.stack("all_true_associated")))
    lo, hi = binomial_interval(k, mc.n_draws, confidence=confidence)
    f_nom, f_3v = mc.total("false_nominal"), mc.total("false_3view")
    return {"share": k / mc.n_draws, "share_ci": (float(lo), float(hi)),
            "shared_23": int(np.sum(scen.visible[1] & scen.visible[2])), "n_false": f_nom,
            "removed_share": 1 - f_3v / f_nom if f_nom else 0.0}


def table3_measure(recovered, n_objects: int) -> dict:
    """Measurement of ``epipolar.table3`` from the per-draw counts of objects recovered: 95 %
    Wilson interval of the share of draws recovering all ``n_objects``, 95 % t interval of the
    mean number recovered."""
    rec = np.asarray(recovered, float)
    if rec.ndim != 1 or len(rec) == 0:
        raise ValueError(f"recovered must be a non-empty 1-D array, got shape {rec.shape}")
    k9 = int(np.sum(rec == n_objects))
    se = float(rec.std(ddof=1) / np.sqrt(len(rec))) if len(rec) > 1 else np.inf
    q = float(student_t.ppf(0.975, max(len(rec) - 1, 1)))
    return {"all_nine_ci": tuple(float(x) for x in binomial_interval(k9, len(rec),
                                                                     confidence=0.95)),
            "mean_recovered_ci": (float(rec.mean()) - q * se, float(rec.mean()) + q * se),
            "n_objects": int(n_objects), "all_nine_share": k9 / len(rec),
            "mean_recovered": float(rec.mean())}


def placement_study(scenarios: dict[str, Scenario], errors: ErrorConfig = _ERRORS,
                    thresholds=None, threshold: float = 10.0, n_draws: int = 100, *,
                    band: tuple[float, float] | None = None, seed: int = 20190401,
                    runner: TrialRunner | None = None, boot_seed: int = 0) -> pd.DataFrame:
    """Figs. 4–5, Table 3, Table 5 and Fig. 8 statistics on other object placements (same
    seeds for each, so the same errors and false targets; with the main run's seed and count
    the numbers of that scene are the main run's): recall and precision at ``threshold``,
    their best values inside Fig. 5's band (default the paper's 8–12 px), the best threshold
    of the sweep, Table 3's objects recovered with the intervals of its criterion and the
    status that criterion would give on that placement (exploratory: the scored status is the
    one of our scene); per triangulated object (GEO1, GEO5) the share of draws in which it has
    a summary row and the median largest coordinate error over those draws with a 95 %
    bootstrap interval (2,000 resamples); Fig. 8's share of draws in which both errors lie
    below a tenth of the scene's own GEO1–GEO5 separation (a missing row counts as not
    resolved), with its 95 % Wilson interval."""
    if not isinstance(scenarios, dict) or not scenarios:
        raise TypeError("scenarios must be a non-empty dict of name -> Scenario")
    th = np.arange(0.5, 20.01, 0.5) if thresholds is None else np.asarray(thresholds, float)
    k_l = np.flatnonzero(np.isclose(th, threshold))
    if len(k_l) != 1:
        raise ValueError(f"threshold={threshold!r} must be one of the thresholds")
    lo, hi = (tuple(float(x) for x in load_claims(SLUG)["epipolar.fig5"].paper[
        "best_threshold_px"]) if band is None else (float(band[0]), float(band[1])))
    in_band = (th >= lo) & (th <= hi)
    if not in_band.any():
        raise ValueError(f"band={band!r} contains none of the thresholds")
    rows = {}
    for name, sc in scenarios.items():
        if not isinstance(sc, Scenario):
            raise TypeError(f"scenarios[{name!r}] must be a Scenario, got {type(sc).__name__}")
        out = run_trials(placement_trial, n_draws, seed=seed, runner=runner,
                         args=(sc, errors, th, float(threshold)), desc=f"placement {name}")
        sw = sweep_rates(np.sum([o["correct"] for o in out], 0),
                         np.sum([o["false"] for o in out], 0),
                         float(sum(o["n_true"] for o in out)), th)
        m = table3_measure([o["objects_recovered"] for o in out], len(sc.names))
        tri = np.stack([np.asarray(o["tri_err_km"], float) for o in out])
        sep = float(np.linalg.norm(sc.objects_km[0] - sc.objects_km[4]))
        with np.errstate(invalid="ignore"):
            k8 = int(np.sum(np.all(tri < sep / 10, axis=1)))
        brng = np.random.default_rng(boot_seed)
        tri_cols = {}
        for j, obj in enumerate(("GEO1", "GEO5")):
            v = tri[:, j][np.isfinite(tri[:, j])]
            tri_cols[f"{obj} has a row (share)"] = len(v) / len(tri)
            if len(v):
                med = np.median(brng.choice(v, (2000, len(v))), axis=1)
                tri_cols[f"{obj} median max|Δ| (km)"] = float(np.median(v))
                tri_cols[f"{obj} median, 95 % bootstrap"] = "{:.0f}–{:.0f}".format(
                    *np.quantile(med, [0.025, 0.975]))
            else:
                tri_cols[f"{obj} median max|Δ| (km)"] = np.nan
                tri_cols[f"{obj} median, 95 % bootstrap"] = "—"
        rows[name] = {
            f"correct of true at L = {threshold:g}": float(sw.accuracy[k_l[0]]),
            f"correct of associated at L = {threshold:g}": float(1 - sw.false_rate[k_l[0]]),
            f"best in {lo:g}–{hi:g} px, correct of true": float(sw.accuracy[in_band].max()),
            f"best in {lo:g}–{hi:g} px, correct of associated":
                float((1 - sw.false_rate[in_band]).max()),
            "best L (px)": sw.best_threshold,
            "objects recovered (mean)": m["mean_recovered"],
            "mean, 95 % t": "{:.2f}–{:.2f}".format(*m["mean_recovered_ci"]),
            "all nine (share)": m["all_nine_share"],
            "all nine, 95 % Wilson": "{:.3f}–{:.3f}".format(*m["all_nine_ci"]),
            "Table 3 status": str(status_table3(m)),
            **tri_cols,
            "GEO1–GEO5 separation (km)": sep,
            "Fig. 8: both below separation/10": k8 / len(tri),
            "Fig. 8, 95 % Wilson": "{:.3f}–{:.3f}".format(
                *binomial_interval(k8, len(tri), confidence=0.95))}
    return pd.DataFrame(rows).T


def table4_paired(scen: Scenario, mc: MonteCarlo, *, confidence: float = 0.95,
                  key: str = "mean_d") -> pd.DataFrame:
    """Paired (noisy − noise-free) mean distance per map pair over the draws, with two-sided
    t intervals at family-wise ``confidence`` (Bonferroni over the pairs with true pairs).

    ``key="mean_d_true"`` uses the correct associations only.
    """
    if key not in ("mean_d", "mean_d_true"):
        raise ValueError(f"key must be 'mean_d' or 'mean_d_true', got {key!r}")
    noisy, free = mc.stack(key), mc.stack(key.replace("mean_d", "mean_d0"))
    use = [i for i, (a, b) in enumerate(PAIRS) if np.any(scen.visible[a] & scen.visible[b])]
    q = student_t.ppf(1 - (1 - confidence) / (2 * len(use)), max(mc.n_draws - 1, 1))
    rows = []
    for i in use:
        d = noisy[:, i] - free[:, i]
        d = d[np.isfinite(d)]
        m, se = (float(d.mean()), float(d.std(ddof=1) / np.sqrt(len(d)))) if len(d) > 1 \
            else (np.nan, np.nan)
        rows.append({"pair": PAIRS[i], "n_draws": len(d),
                     "noisy mean (px)": float(np.nanmean(noisy[:, i])),
                     "noise-free mean (px)": float(np.nanmean(free[:, i])),
                     "noisy − noise-free (px)": m, "ci_low": m - q * se, "ci_high": m + q * se})
    return pd.DataFrame(rows)


def fig5_bootstrap(mc: MonteCarlo, band: tuple[float, float], *, n_boot: int = 2000,
                   confidence: float = 0.95, rng: np.random.Generator | None = None) -> dict:
    """Bootstrap over the draws (resampled with replacement) of the best threshold and of the
    best correct rate inside ``band`` under both readings — correct of the true pairs
    (``acc``) and correct of the associated pairs (``prec``, 1 − the paper's 误判率): point
    values and percentile intervals."""
    rng = np.random.default_rng(0) if rng is None else rng
    th = mc.sweep.thresholds
    C, Fa = mc.stack("correct"), mc.stack("false")
    n_true = np.array([o["n_true"] for o in mc.trials], float)
    w = rng.multinomial(mc.n_draws, np.full(mc.n_draws, 1 / mc.n_draws), size=n_boot)
    c, f, nt = w @ C, w @ Fa, w @ n_true
    err = (nt[:, None] - c + f) / nt[:, None]
    acc = c / nt[:, None]
    inb = (th >= band[0]) & (th <= band[1])
    best = th[np.argmin(err, 1)]
    accb = acc[:, inb].max(1)
    with np.errstate(invalid="ignore", divide="ignore"):
        prec = c / (c + f)  # the paper's reading: 1 − false / associated
        prec0 = C.sum(0) / (C.sum(0) + Fa.sum(0))
    precb = np.nanmax(prec[:, inb], 1)
    a = (1 - confidence) / 2
    return {"best_L": mc.sweep.best_threshold,
            "best_L_ci": tuple(float(x) for x in np.quantile(best, [a, 1 - a])),
            "acc": float(mc.sweep.accuracy[inb].max()),
            "acc_ci": tuple(float(x) for x in np.quantile(accb, [a, 1 - a])),
            "prec": float(np.nanmax(prec0[inb])),
            "prec_L": float(th[inb][int(np.nanargmax(prec0[inb]))]),
            "prec_ci": tuple(float(x) for x in np.quantile(precb, [a, 1 - a])),
            "n_boot": n_boot, "confidence": confidence}


def score(scen: Scenario, draw: DisplayedDraw, mc: MonteCarlo, res6: dict, *,
          errors: ErrorConfig = _ERRORS, images: list | None = None,
          settings: dict | None = None, boot_seed: int = 0) -> Reproduction:
    """Score the ten claims from precomputed results (no new trials): measure, call each
    claim's evaluator, assemble the report.

    ``images`` (the rendered star maps) switches on the report's figures; the notebook draws
    its own and leaves it ``None``. ``boot_seed`` seeds the Fig. 5 bootstrap.
    """
    from . import figures as figs

    claims = load_claims(SLUG)
    P = {k: c.paper for k, c in claims.items()}
    L = draw.threshold
    sw = mc.sweep
    n_draws = mc.n_draws
    results: list[ClaimResult] = []
    tables: dict[str, pd.DataFrame] = {}
    figures: dict[str, object] = {}
    obs, sc = draw.obs, draw.scores

    def add(cid: str, status: Status, ours: str, note: str) -> None:
        results.append(ClaimResult.from_claim(claims[cid], status=status, ours=ours,
                                              note="" if status is R_ else note))

    # ---- Table 1 (check)
    tables["Table 1"] = table1(scen)
    m1 = {"n_clear": int(scen.los_clear[scen.visible].sum()),
          "n_sight": int(scen.visible.sum()), "pattern_ok": True}  # build_scenario enforces it
    add("epipolar.table1", status_table1(m1),
        f"{m1['n_clear']}/{m1['n_sight']} sensor–object lines of sight clear of the Earth; "
        "Table 3 visibility realised with 25 px margins", "some line of sight is blocked")

    # ---- Table 2 (check)
    m2 = table2_check(scen)
    add("epipolar.table2", status_table2(m2),
        f"1° off axis lands {m2['offaxis_err_px']:.1e} px from 256 px; distortion moves "
        f"points by at most {m2['max_distortion_px']:.3f} px; 6″ = {m2['accuracy_px']:.2f} px",
        "eq. (7), the distortion bound or the accuracy check fails")

    # ---- Fig. 3 (check)
    m3 = {"objects_per_map": [int(v) for v in scen.visible.sum(1)],
          "paper": list(P["epipolar.fig3"]["objects_per_map"]),
          "shared_23": int(np.sum(scen.visible[1] & scen.visible[2]))}
    if images is not None:
        figures["fig3_star_maps"] = figs.plot_fig3(scen, obs, images)
    add("epipolar.fig3", status_fig3(m3),
        f"objects per map {m3['objects_per_map']}; {errors.n_false} boxed false targets per "
        f"map; stars: Gaia DR3 to G 10 + synthetic to Mv {scen.sensor.limit_mag:g}",
        "visibility differs from Table 3")

    # ---- Fig. 4
    if images is not None:
        figures["fig4_pairwise_association"] = figs.plot_fig4(scen, obs, draw.matches)
    tables["Fig. 4 (displayed draw, L = 10 px)"] = sc
    m4 = fig4_measure(scen, mc)
    confusable = closest_other_object_px(scen)
    lo4, hi4 = m4["share_ci"]
    # the two ways a true pair is lost, separated: beyond the gate (noise) or taken by a
    # nearer wrong candidate (the rest of the misses)
    true_d = np.concatenate([o["true_d"] for o in mc.trials])
    n_far = int(np.sum(true_d >= L))
    n_missed = mc.total("missed_nominal")
    add("epipolar.fig4", status_fig4(m4),
        f"every true pair associated in {100 * m4['share']:.1f} % of {n_draws} draws "
        f"(95 % {100 * lo4:.1f}–{100 * hi4:.1f} %); displayed draw "
        f"{int(sc['correct'].sum())}/{int(sc['true'].sum())}, {int(sc['false'].sum())} false; "
        f"maps 2–3 share {m4['shared_23']} objects; {m4['n_false']} false associations in "
        f"all draws; our three-view check (a variant, not scored) removes "
        f"{100 * m4['removed_share']:.0f} %",
        f"of {n_missed} true pairs lost over the draws, {n_far} lie beyond L = {L:g} px "
        f"(noise) and {n_missed - n_far} were taken by a nearer wrong candidate (noise-free, "
        "another object lies within "
        + ", ".join(f"{v:.1f} px in pair {k}" for k, v in confusable.items() if v < 5)
        + f" of an object's epipolar line); with {int(sc['true'].sum())} true pairs per draw, "
        "a draw with none lost is rare")

    # ---- Table 3
    tables["Table 3"] = table3(scen, draw)
    rec_mc = mc.stack("objects_recovered")
    n_obj = len(scen.names)
    k9 = int(np.sum(rec_mc == n_obj))
    m3t = {**table3_measure(rec_mc, n_obj),
           "displayed_recovered": objects_recovered(obs, draw.rows, scen)}
    add("epipolar.table3", status_table3(m3t),
        f"displayed draw: {m3t['displayed_recovered']}/{n_obj} objects recovered as Table 3 "
        f"rows, {len(draw.rows) - m3t['displayed_recovered']} further multi-map row(s); over "
        f"{n_draws} draws {rec_mc.mean():.2f}/{n_obj} on average (95 % "
        f"{m3t['mean_recovered_ci'][0]:.2f}–{m3t['mean_recovered_ci'][1]:.2f}), all nine in "
        f"{100 * k9 / n_draws:.0f} % (95 % {100 * m3t['all_nine_ci'][0]:.0f}–"
        f"{100 * m3t['all_nine_ci'][1]:.0f} %), table exactly Table 3 in "
        f"{100 * np.mean(mc.stack('perfect_table')):.0f} %",
        "objects are split or merged with a false target in most draws: with several points "
        "per epipolar band (3 false targets per "
        "map plus objects seen by one sensor of a pair) the nearest candidate is sometimes "
        "the wrong one")

    # ---- Table 4 (paired over the draws)
    tables["Table 4"] = table4(draw, mc)
    t4p = table4_paired(scen, mc)
    tables["Table 4 — paired over the draws (Bonferroni 95 %)"] = t4p.assign(
        pair=[f"{a + 1}-{b + 1}" for a, b in t4p["pair"]])
    paper_noisy = np.asarray(P["epipolar.table4"]["mean_distance_noisy_px"], float)
    pidx = [PAIRS.index(tuple(pr)) for pr in t4p["pair"]]
    ratio4 = np.asarray(t4p["noisy mean (px)"], float) / paper_noisy[pidx]
    m4t = {"diff_ci": list(zip(t4p["ci_low"], t4p["ci_high"])),
           "level_ratio": ratio4[np.isfinite(ratio4)].tolist()}
    st4 = status_table4(m4t)
    # the criterion before 2026-11-22 (one displayed draw; noisy means in 1-10 px), kept so
    # the report can say what the post-results change did
    dn = draw.scores["mean_distance_px"].to_numpy(float)
    d0 = draw.scores0["mean_distance_px"].to_numpy(float)
    both = np.isfinite(dn) & np.isfinite(d0)
    old_ok = bool(np.all(dn[both] > d0[both])
                  and np.all((dn[np.isfinite(dn)] > 1) & (dn[np.isfinite(dn)] < 10)))
    worst_old = int(np.nanargmin(np.where(np.isfinite(dn), dn, np.inf)))
    results.append(ClaimResult.from_claim(
        claims["epipolar.table4"], status=st4,
        ours=(f"{n_draws} paired draws; noisy − noise-free (px, Bonferroni 95 %): "
              + "; ".join(f"{a + 1}-{b + 1} {m:+.2f} [{lo:+.2f}, {hi:+.2f}]" for (a, b), m, lo, hi
                          in zip(t4p["pair"], t4p["noisy − noise-free (px)"], t4p["ci_low"],
                                 t4p["ci_high"]))),
        note=("noisy level over the paper's (b, c, e, f): "
              + ", ".join(f"{v:.2f}" for v in m4t["level_ratio"])
              + " (the criterion asks 0.5–2); with ±1′ uniform attitude errors our noisy "
              f"means are {t4p['noisy mean (px)'].min():.1f}–{t4p['noisy mean (px)'].max():.1f}"
              f" px against the paper's {np.nanmin(paper_noisy):.1f}–"
              f"{np.nanmax(paper_noisy):.1f} px. History: the criterion was "
              "changed on 2026-11-22 after results were seen; under the earlier one-draw "
              f"criterion the status would be "
              f"'{'reproduced' if old_ok else 'not reproduced'}' (displayed draw, pair "
              f"{PAIR_LABELS[worst_old]} noisy mean {dn[worst_old]:.3f} px)")))

    # ---- Fig. 5 (bootstrap over the draws)
    p5 = P["epipolar.fig5"]
    lo, hi = p5["best_threshold_px"]
    b5 = fig5_bootstrap(mc, (lo, hi), rng=np.random.default_rng(boot_seed),
                        confidence=1 - 0.05 / 3)  # Bonferroni over the three intervals
    m5 = {"best_L_ci": b5["best_L_ci"], "acc_ci": b5["acc_ci"], "prec_ci": b5["prec_ci"],
          "band": (lo, hi), "acc_min": 0.85}
    st5 = status_fig5(m5)
    sig_rms_nom, gate_nom = error_budget_gate(scen, errors)
    _, gate_rms = error_budget_gate(scen, replace(
        errors, attitude_arcmin=errors.attitude_arcmin * 3**0.5))
    if images is not None:
        figures["fig5_false_association_rate"] = figs.plot_fig5(
            sw.thresholds, sw.accuracy, sw.false_rate, sw.miss_rate, sw.error_rate,
            paper=p5).figure
    tables["Fig. 5"] = fig5_table(sw)
    tables["Fig. 5 — paper beside ours"] = fig5_summary(sw, b5)
    add("epipolar.fig5", st5,
        f"{n_draws} draws, {sw.n_true} true pairs "
        f"({int(sw.n_associated[sw.thresholds == L][0])} associated at L = {L:g}); best L = "
        f"{b5['best_L']:g} px (98.3 % {b5['best_L_ci'][0]:g}–{b5['best_L_ci'][1]:g}); best "
        f"correct rate in {lo:g}–{hi:g} px: of the associated pairs (the paper's 误判率 "
        f"reading) {100 * b5['prec']:.1f} % (98.3 % {100 * b5['prec_ci'][0]:.1f}–"
        f"{100 * b5['prec_ci'][1]:.1f} %), of the true pairs {100 * b5['acc']:.1f} % (98.3 % "
        f"{100 * b5['acc_ci'][0]:.1f}–{100 * b5['acc_ci'][1]:.1f} %)",
        "the best L lies below 8–12 px because false candidates in the epipolar bands pull "
        "it below the spread of the true-pair distances; "
        f"σ ≈ {sig_rms_nom:.1f} px for "
        f"uniform ±1′ attitude errors (99 % χ²₁ gate {gate_nom:.1f} px, the library default); "
        f"read as 1′ rms the gate is {gate_rms:.1f} px (notebook, Beyond, exploratory). False "
        "targets per map (3, unstated in the paper) set the false share")

    # ---- Fig. 6
    p6 = P["epipolar.fig6"]
    L6 = np.asarray(p6["threshold_px"], float)
    run, an, _ = res6["overlapping"]
    runr, anr, _ = res6["random_f"]
    if images is not None:
        figures["fig6_monte_carlo_bound"] = figs.plot_fig6(
            {Lv: run[:, i] for i, Lv in enumerate(L6)}, {Lv: an[i] for i, Lv in enumerate(L6)},
            p6).figure
    tables["Fig. 6"] = fig6_table(res6)
    paper6 = np.asarray(p6["max_false_rate"])
    m6 = {"mc_vs_analytic": float(max(np.abs(run[-1] - an).max(), np.abs(runr[-1] - anr).max())),
          "paper_gap": float(min(np.abs(run[-1] - paper6).max(),
                                 np.abs(runr[-1] - paper6).max()))}
    add("epipolar.fig6", status_fig6(m6),
        "overlapping views: " + ", ".join(f"{100 * v:.0f} %" for v in run[-1])
        + " (analytic " + ", ".join(f"{100 * v:.0f} %" for v in an) + "); random F: "
        + ", ".join(f"{100 * v:.0f} %" for v in runr[-1]),
        f"MC within {100 * m6['mc_vs_analytic']:.1f} points of its binomial expectation; the "
        f"paper's values are {100 * m6['paper_gap']:.0f}+ points away: they do not follow "
        "from 100 uniform points in a 512×512 image: a band of half-width L around an "
        "epipolar line crossing the image holds 2·L·ℓ·100/512² other points on average "
        "(≈2 at L = 5 px). The paper does not state image size or how F and the points were "
        "drawn; a saturating curve like its 17/19/21 % needs most lines to miss the image, as "
        "with a random F.")

    # ---- Table 5 and Fig. 8
    tol = float(P["epipolar.table5"]["tolerance_km"])
    tables["Table 5"], est_all = table5(scen, draw)
    disp_err = [float(np.abs(e["combined"] - e["truth"]).max()) for e in est_all.values()]
    tri = mc.stack("tri_err_km")
    with np.errstate(invalid="ignore"):
        k5 = int(np.sum(np.all(tri <= tol, axis=1)))  # a missing row counts as a failure
    m5t = {"displayed_err_km": disp_err, "share_ok": k5 / n_draws, "tol_km": tol,
           "share_ok_ci": tuple(float(x) for x in binomial_interval(k5, n_draws,
                                                                    confidence=0.95))}
    med = np.nanmedian(tri, 0)
    base = [float(np.linalg.norm(scen.sat_km[a] - scen.sat_km[b])) for a, b in PAIRS
            if np.any(scen.visible[a] & scen.visible[b])]
    rng_km = float(np.mean(np.linalg.norm(
        scen.objects_km[None] - scen.sat_km[:, None], axis=2)[scen.visible]))
    add("epipolar.table5", status_table5(m5t),
        f"displayed draw: max coordinate error GEO1 {disp_err[0]:.1f} km, GEO5 "
        f"{disp_err[1]:.1f} km; over {n_draws} draws median {med[0]:.1f} / {med[1]:.1f} km, "
        f"both within {tol:g} km in {100 * m5t['share_ok']:.0f} % (95 % "
        f"{100 * m5t['share_ok_ci'][0]:.0f}–{100 * m5t['share_ok_ci'][1]:.0f} %)",
        "with attitude errors up to 1′ (2.9e-4 rad) a line of sight from "
        f"{rng_km:,.0f} km misses by up to ~{rng_km * 2.9e-4:.0f} km, and the short baselines "
        f"(sensors {min(base):,.0f}–{max(base):,.0f} km apart) stretch that along the line of "
        "sight; 3 km needs arcsecond-level attitude errors and a centroid jitter well below "
        f"{errors.jitter_urad:g} µrad, which alone sets a floor of a few km (notebook, "
        "Beyond; a smaller position error does not help). GEO1 has one "
        "pair only (Table 3 puts it in maps 1 and 4; the paper's Table 5 also uses 1&2 and "
        "2&4)")
    if images is not None:
        figures["fig8_triangulation_3d"] = figs.plot_fig8(
            scen, est_all, paper=P["epipolar.table5"]).figure
    sep = float(np.linalg.norm(scen.objects_km[0] - scen.objects_km[4]))
    t5p = P["epipolar.table5"]
    sep_paper = float(np.linalg.norm(np.subtract(t5p["geo1_km"][-1], t5p["geo5_km"][-1])))
    k8 = [int(np.sum(np.all(tri < s / 10, axis=1))) for s in (sep, sep_paper)]
    share8 = [k / n_draws for k in k8]
    ci8 = [tuple(float(x) for x in binomial_interval(k, n_draws, confidence=0.95)) for k in k8]
    m8 = {"share_ci": ci8[0]}
    st8_paper = status_fig8({"share_ci": ci8[1]})
    add("epipolar.fig8", status_fig8(m8),
        f"separation GEO1–GEO5 {sep:.0f} km (ours, GEO5 from Table 3) / {sep_paper:.0f} km "
        f"(Table 5 truths); both combined errors below a tenth of the separation in "
        f"{100 * share8[0]:.1f} % (95 % {100 * ci8[0][0]:.1f}–{100 * ci8[0][1]:.1f} %) / "
        f"{100 * share8[1]:.1f} % (95 % {100 * ci8[1][0]:.1f}–{100 * ci8[1][1]:.1f} %) of the "
        f"{n_draws} draws; at the paper's separation the status would be '{st8_paper}' "
        f"(displayed draw: errors {disp_err[0]:.1f}, {disp_err[1]:.1f} km)",
        f"median errors {med[0]:.0f} and {med[1]:.0f} km against a {sep:.0f} km separation "
        "(the Table 5 error, 1′ attitude noise)")

    # ---- Beyond: error-budget gate, three-view check, global assignment
    sig = distance_sigma_px(scen, errors)
    sig_rms, gate99 = error_budget_gate(scen, errors)
    tables["Beyond: association rules at L = 10 px"] = rules_table(mc)
    text = (f"Scenario built from Tables 1–3 (see the notebook): {errors.n_false} false targets "
            f"per map (not stated in the paper), jitter {errors.jitter_urad:g} µrad "
            f"(erratum: the paper prints 10 mrad). Error-budget gate (99 %, χ²₁): "
            f"{gate99:.1f} px from the rms distance σ = {sig_rms:.2f} px.")
    data = {"scenario": scen, "draw": draw, "obs": obs, "obs0": draw.obs0,
            "matches": draw.matches, "images": images, "trials": mc.trials, "sweep": sw,
            "fig6": res6, "fig6_L": L6, "estimates": est_all, "rows": draw.rows,
            "sigma": sig, "gate99": gate99, "fig5_bootstrap": b5, "table4_paired": t4p,
            "fig4": m4}
    st = {"scenario_draws": n_draws, "fig6_simulations": len(run), "threshold_px": L,
          "errors": errors, "epoch_utc": EPOCH_UTC}
    st.update(settings or {})
    return Reproduction(slug=SLUG, title=TITLE, claims=results, tables=tables,
                        figures=figures, text=text, settings=st, data=data)
