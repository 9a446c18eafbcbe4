"""Tables and claim scoring of Huang, Zhang & Feng: each table of the paper from the scenario,
the displayed draw and the Monte Carlo (the notebook calls the same functions), and
:func:`score`, which turns them into the nine claim results of the report."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pandas as pd

from eotrack.geometry.triangulation import combine_estimates
from eotrack.repro import ClaimResult, Reproduction, Status, load_claims

from .scenario import EPOCH_UTC, PAIRS, SLUG, TITLE, ErrorConfig, Scenario
from .trials import (
    DisplayedDraw,
    MonteCarlo,
    SweepResult,
    closest_other_object_px,
    distance_sigma_px,
    error_budget_gate,
    objects_recovered,
    row_labels,
    triangulate_object,
)

__all__ = [
    "fig5_summary",
    "fig5_table",
    "fig6_table",
    "paper_values",
    "rules_table",
    "score",
    "table1",
    "table3",
    "table4",
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
    """Table 3: the paper's pixels beside the rows our summary produced for each object."""
    obs, rows = draw.obs, draw.rows
    lab = row_labels(obs, rows)
    out = []
    for j, name in enumerate(scen.names):
        rec = {"target": name}
        r = np.flatnonzero((lab == j).sum(1) >= 1)
        for k in range(len(scen.cameras)):
            pp = scen.paper_px[k, j]
            rec[f"map {k + 1} paper"] = "" if np.isnan(pp[0]) else f"({pp[0]:.0f},{pp[1]:.0f})"
            if len(r) and rows[r[0], k] >= 0:
                q = obs.points[k][rows[r[0], k]]
                rec[f"map {k + 1} ours"] = f"({q[0]:.0f},{q[1]:.0f})"
            else:
                rec[f"map {k + 1} ours"] = ""
        out.append(rec)
    return pd.DataFrame(out)


def table4(draw: DisplayedDraw, mc: MonteCarlo) -> pd.DataFrame:
    """Table 4: mean distance of associated points to the line, paper beside ours."""
    p4 = paper_values()["epipolar.table4"]
    mean_all = np.nanmean(mc.stack("mean_d"), 0)
    noisy = draw.scores["mean_distance_px"].to_numpy()
    return pd.DataFrame({
        "pair": p4["pairs"],
        "paper noise-free (px)": p4["mean_distance_noise_free_px"],
        "ours noise-free (px)": draw.scores0["mean_distance_px"].round(3),
        "paper noisy (px)": p4["mean_distance_noisy_px"],
        "ours noisy (px)": np.round(noisy, 3),
        "noisy − paper (px)": np.round(noisy - np.asarray(p4["mean_distance_noisy_px"]), 3),
        f"ours noisy, mean of {mc.n_draws} draws (px)": np.round(mean_all, 3)})


def fig5_table(sw: SweepResult) -> pd.DataFrame:
    """The Fig. 5 curves at every other threshold."""
    return pd.DataFrame({"L (px)": sw.thresholds, "correct": sw.accuracy.round(4),
                         "false (of associated)": sw.false_rate.round(4),
                         "missed": sw.miss_rate.round(4),
                         "total error": sw.error_rate.round(4)})[::2]


def fig5_summary(sw: SweepResult) -> pd.DataFrame:
    """Fig. 5's numbers, paper beside ours with the difference."""
    p5 = paper_values()["epipolar.fig5"]
    lo, hi = p5["best_threshold_px"]
    band = (sw.thresholds >= lo) & (sw.thresholds <= hi)
    i = int(np.argmax(np.where(band, sw.accuracy, -1)))
    acc = float(sw.accuracy[i])
    return pd.DataFrame([
        {"quantity": f"correct association, best L in {lo:g}–{hi:g} px",
         "paper": p5["accuracy_at_best"], "ours": round(acc, 4),
         "ours − paper": round(acc - p5["accuracy_at_best"], 4),
         "at L (px)": float(sw.thresholds[i])},
        {"quantity": "L of smallest total error (px)", "paper": f"{lo:g}–{hi:g}",
         "ours": sw.best_threshold, "ours − paper": "", "at L (px)": sw.best_threshold},
        {"quantity": "groups of maps (draws)", "paper": p5["n_groups"], "ours": "",
         "ours − paper": "", "at L (px)": np.nan},
        {"quantity": "true pairs (paper: associated pairs)", "paper": p5["n_associated_pairs"],
         "ours": sw.n_true, "ours − paper": "", "at L (px)": np.nan},
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


def score(scen: Scenario, draw: DisplayedDraw, mc: MonteCarlo, res6: dict, *,
          errors: ErrorConfig = _ERRORS, images: list | None = None,
          settings: dict | None = None) -> Reproduction:
    """Score the nine claims from precomputed results (no new trials).

    ``images`` (the rendered star maps) switches on the report's figures; the notebook draws
    its own and leaves it ``None``.
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
    obs, sc, sc0 = draw.obs, draw.scores, draw.scores0

    # ---- Table 1
    tables["Table 1"] = table1(scen)
    ok1 = bool(scen.los_clear[scen.visible].all())
    results.append(ClaimResult.from_claim(
        claims["epipolar.table1"], status=Status.REPRODUCED if ok1 else Status.NOT_REPRODUCED,
        ours=f"all {int(scen.visible.sum())} sensor–object lines of sight clear of the Earth: "
             f"{ok1}; Table 3 visibility realised with 25 px margins",
        note="" if ok1 else "some line of sight is blocked by the Earth"))

    # ---- Fig. 3
    counts = [int(v) for v in scen.visible.sum(1)]
    ok3 = counts == list(P["epipolar.fig3"]["objects_per_map"]) and \
        not np.any(scen.visible[1] & scen.visible[2])
    if images is not None:
        figures["fig3_star_maps"] = figs.plot_fig3(scen, obs, images)
    results.append(ClaimResult.from_claim(
        claims["epipolar.fig3"], status=Status.REPRODUCED if ok3 else Status.NOT_REPRODUCED,
        ours=f"objects per map {counts}; {errors.n_false} boxed false targets per map; "
             f"stars: Gaia DR3 to G 10 + synthetic to Mv {scen.sensor.limit_mag:g}",
        note="" if ok3 else "visibility differs from Table 3"))

    # ---- Fig. 4
    if images is not None:
        figures["fig4_pairwise_association"] = figs.plot_fig4(scen, obs, draw.matches)
    tables["Fig. 4 (displayed draw, L = 10 px)"] = sc
    all_true = int(sc["missed"].sum()) == 0
    confusable = closest_other_object_px(scen)
    no_23 = int(sc.loc[3, "true"]) == 0
    f_nom, f_3v = mc.total("false_nominal"), mc.total("false_3view")
    mi_nom, mi_3v = mc.total("missed_nominal"), mc.total("missed_3view")
    draws_with_false = float(np.mean(mc.stack("false_nominal") > 0))
    ok4 = all_true and no_23 and f_nom > 0 and f_3v < f_nom
    results.append(ClaimResult.from_claim(
        claims["epipolar.fig4"], status=Status.REPRODUCED if ok4 else Status.PARTIAL,
        ours=(f"displayed draw: {int(sc['correct'].sum())}/{int(sc['true'].sum())} true pairs "
              f"associated, {int(sc['false'].sum())} false; pair 2-3 true pairs: "
              f"{int(sc.loc[3, 'true'])}. {n_draws} draws: false associations in "
              f"{100 * draws_with_false:.0f} % of draws, {f_nom} in all; three-view check leaves "
              f"{f_3v} (missed {mi_nom} → {mi_3v})"),
        note="" if ok4 else "; ".join(filter(None, [
            "" if all_true else
            (f"displayed draw: {int(sc['missed'].sum())} true pair(s) lost to a nearer wrong "
             "candidate (noise-free, another object lies within "
             + ", ".join(f"{v:.1f} px in pair {k}" for k, v in confusable.items() if v < 5)
             + " of an object's epipolar line)"),
            "" if no_23 else "maps 2 and 3 share an object",
            "" if f_nom > 0 else "no false association in any draw",
            "" if f_3v < f_nom else "the three-view check does not reduce false associations",
        ]))))

    # ---- Table 3
    tables["Table 3"] = table3(scen, draw)
    n_obj = len(scen.names)
    rec_disp = objects_recovered(obs, draw.rows, scen)
    rec_mc = mc.stack("objects_recovered")
    share_perfect = float(np.mean(mc.stack("perfect_table")))
    extra = len(draw.rows) - rec_disp
    if rec_disp == n_obj:
        st3 = Status.REPRODUCED
    elif rec_mc.mean() >= 7:
        st3 = Status.PARTIAL
    else:
        st3 = Status.NOT_REPRODUCED
    results.append(ClaimResult.from_claim(
        claims["epipolar.table3"], status=st3,
        ours=(f"displayed draw: {rec_disp}/{n_obj} objects recovered as Table 3 rows, "
              f"{extra} further multi-map row(s) from false associations; over {n_draws} draws "
              f"{rec_mc.mean():.1f}/{n_obj} on average, all nine in "
              f"{100 * np.mean(rec_mc == n_obj):.0f} %, table exactly Table 3 in "
              f"{100 * share_perfect:.0f} %"),
        note="" if st3 is Status.REPRODUCED else
        (f"{n_obj - rec_disp} object(s) split or merged with a false target in the displayed "
         "draw: with several points per epipolar band (3 false targets per map plus objects "
         "seen by one sensor of a pair) the nearest candidate is sometimes the wrong one")))

    # ---- Table 4
    tables["Table 4"] = table4(draw, mc)
    mean_all = np.nanmean(mc.stack("mean_d"), 0)
    has = (sc["associated"].to_numpy() > 0) & (sc0["associated"].to_numpy() > 0)
    nz, nn = sc0["mean_distance_px"].to_numpy(), sc["mean_distance_px"].to_numpy()
    ordered = bool(np.all(nn[has] > nz[has]))
    fin = mean_all[np.isfinite(mean_all)]
    in_range = bool(np.all((fin > 1) & (fin < 10)))
    ok_t4 = ordered and in_range and no_23
    results.append(ClaimResult.from_claim(
        claims["epipolar.table4"], status=Status.REPRODUCED if ok_t4 else Status.PARTIAL,
        ours=("noisy > noise-free for every pair: " + str(ordered) + "; noisy means over draws "
              + ", ".join(_fmt(v) for v in mean_all) + " px; noise-free "
              + ", ".join(_fmt(v, 3) for v in nz) + " px"),
        note=("" if ok_t4 else "noise-free distances are ~0 here (no error source left but "
              "lens distortion); the paper's non-zero noise-free values imply an unstated error "
              "(rounding to whole pixels gives ~0.3 px)")))

    # ---- Fig. 5
    p5 = P["epipolar.fig5"]
    sig_rms_nom, _ = error_budget_gate(scen, errors)
    _, gate_rms = error_budget_gate(scen, replace(
        errors, attitude_arcmin=errors.attitude_arcmin * 3**0.5))
    if images is not None:
        figures["fig5_false_association_rate"] = figs.plot_fig5(
            sw.thresholds, sw.accuracy, sw.false_rate, sw.miss_rate, sw.error_rate,
            paper=p5).figure
    lo, hi = p5["best_threshold_px"]
    band = (sw.thresholds >= lo) & (sw.thresholds <= hi)
    best_L = sw.best_threshold
    acc_band = float(sw.accuracy[band].max())
    ok5 = acc_band >= 0.85 and lo <= best_L <= hi
    tables["Fig. 5"] = fig5_table(sw)
    tables["Fig. 5 — paper beside ours"] = fig5_summary(sw)
    results.append(ClaimResult.from_claim(
        claims["epipolar.fig5"], status=Status.REPRODUCED if ok5 else Status.PARTIAL,
        ours=(f"{n_draws} draws, {sw.n_true} true pairs "
              f"({int(sw.n_associated[sw.thresholds == L][0])} associated at L = {L:g}); "
              f"best L = {best_L:g} px (total error {100 * sw.error_rate.min():.1f} %); "
              f"correct rate in 8–12 px up to {100 * acc_band:.1f} %"),
        note="" if ok5 else
        (f"best L {best_L:g} px, max correct in 8–12 px {100 * acc_band:.1f} %: the optimum "
         f"follows the spread of true-pair distances, σ ≈ {sig_rms_nom:.1f} px for uniform ±1′ "
         f"attitude errors; read as 1′ rms, the 99 % error-budget gate is {gate_rms:.1f} px "
         "(notebook, Beyond). False targets per map (3, unstated in the paper) set the false "
         "share")))

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
    agree = bool(np.all(np.abs(run[-1] - an) < 0.02) and np.all(np.abs(runr[-1] - anr) < 0.02))
    paper6 = np.asarray(p6["max_false_rate"])
    match_paper = bool(np.all(np.abs(run[-1] - paper6) < 0.03)
                       or np.all(np.abs(runr[-1] - paper6) < 0.03))
    results.append(ClaimResult.from_claim(
        claims["epipolar.fig6"],
        status=Status.REPRODUCED if (agree and match_paper) else Status.NOT_REPRODUCED,
        ours=("overlapping views: " + ", ".join(f"{100 * v:.0f} %" for v in run[-1])
              + " (analytic " + ", ".join(f"{100 * v:.0f} %" for v in an) + "); random F: "
              + ", ".join(f"{100 * v:.0f} %" for v in runr[-1])),
        note=("" if (agree and match_paper) else
              f"MC agrees with the binomial expectation ({agree}); the paper's values do not "
              "follow from 100 uniform points in a 512×512 image: a band of half-width L around "
              "an epipolar line crossing the image holds 2·L·ℓ·100/512² other points on average "
              "(≈2 at L = 5 px). The paper does not state image size or how F and the points "
              "were drawn; a saturating curve like its 17/19/21 % needs most lines to miss "
              "the image, as with a random F.")))

    # ---- Table 5 and Fig. 8
    tol = float(P["epipolar.table5"]["tolerance_km"])
    tables["Table 5"], est_all = table5(scen, draw)
    disp_err = [float(np.abs(e["combined"] - e["truth"]).max()) for e in est_all.values()]
    tri = mc.stack("tri_err_km")
    share_ok = float(np.mean(np.all(tri <= tol, axis=1)))
    med = np.nanmedian(tri, 0)
    ok5t = all(e <= tol for e in disp_err) and share_ok >= 0.5
    base = [float(np.linalg.norm(scen.sat_km[a] - scen.sat_km[b])) for a, b in PAIRS
            if np.any(scen.visible[a] & scen.visible[b])]
    rng_km = float(np.mean(np.linalg.norm(
        scen.objects_km[None] - scen.sat_km[:, None], axis=2)[scen.visible]))
    results.append(ClaimResult.from_claim(
        claims["epipolar.table5"], status=Status.REPRODUCED if ok5t else Status.NOT_REPRODUCED,
        ours=(f"displayed draw: max coordinate error GEO1 {disp_err[0]:.1f} km, GEO5 "
              f"{disp_err[1]:.1f} km; over {n_draws} draws median {med[0]:.1f} / {med[1]:.1f} km,"
              f" both within {tol:g} km in {100 * share_ok:.0f} %"),
        note=("" if ok5t else "with attitude errors up to 1′ (2.9e-4 rad) a line of sight from "
              f"{rng_km:,.0f} km misses by up to ~{rng_km * 2.9e-4:.0f} km, and the short "
              f"baselines (sensors {min(base):,.0f}–{max(base):,.0f} km apart) stretch that "
              "along the line of sight; 3 km needs arcsecond-level "
              "attitude errors (notebook, Beyond). GEO1 has one pair only (Table 3 puts it in "
              "maps 1 and 4; the paper's Table 5 also uses 1&2 and 2&4)")))
    if images is not None:
        figures["fig8_triangulation_3d"] = figs.plot_fig8(scen, est_all).figure
    sep = float(np.linalg.norm(scen.objects_km[0] - scen.objects_km[4]))
    ok8 = all(e < sep / 10 for e in disp_err)
    results.append(ClaimResult.from_claim(
        claims["epipolar.fig8"], status=Status.REPRODUCED if ok8 else Status.NOT_REPRODUCED,
        ours=f"separation GEO1–GEO5 {sep:.0f} km; estimate errors {disp_err[0]:.1f}, "
             f"{disp_err[1]:.1f} km",
        note="" if ok8 else (f"errors {disp_err[0]:.0f} and {disp_err[1]:.0f} km against a "
                             f"{sep:.0f} km separation: the Table 5 error (1′ attitude noise)")))

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
            "sigma": sig, "gate99": gate99}
    st = {"scenario_draws": n_draws, "fig6_simulations": len(run), "threshold_px": L,
          "errors": errors, "epoch_utc": EPOCH_UTC}
    st.update(settings or {})
    return Reproduction(slug=SLUG, title=TITLE, claims=results, tables=tables,
                        figures=figures, text=text, settings=st, data=data)
