"""Yan et al. 2019 — RANSAC / WRANSAC trajectory prediction for electro-optical tracking.

The package splits the experiment by role: :mod:`.scenario` (the real track, the noise,
the configuration), :mod:`.trials` (predictors, paired Monte Carlo runs, tables),
:mod:`.tables` (Table 1, paired ratios, the mechanism), :mod:`.figures` (plots) and
:mod:`.claims` (the scorecard). :func:`reproduce` runs everything
``make repro`` reports.
"""

from __future__ import annotations

from dataclasses import asdict, replace

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from eotrack.astro import UMBRA
from eotrack.montecarlo import TrialRunner
from eotrack.repro import Reproduction, load_claims

from .claims import evaluate
from .figures import (
    METHOD_LABELS,
    plot_budget,
    plot_eclipse_season,
    plot_error_distribution,
    plot_flowchart,
    plot_generalisation,
    plot_inlier_histograms,
    plot_leverage,
    plot_losses,
    plot_min_samples,
    plot_prediction,
    plot_pull,
    plot_ratio_table,
    plot_threshold_sensitivity,
)
from .orbit import (
    ORBIT_CRITERION,
    ORBIT_METHODS,
    ORBIT_SEEDS,
    PAIRED_RATIO,
    SINUSOID_METHODS,
    absolute_ra,
    orbit_comparison,
    orbit_criterion,
    orbit_inputs,
    orbit_seed_study,
    read_orbit_study,
    write_orbit_study,
)
from .scenario import (
    ARCSEC_PER_RAD,
    COORDS,
    GENERALISATION_CASES,
    NOISE_MODELS,
    READINGS,
    Scenario,
    WransacConfig,
    eclipse_season,
    make_scenario,
    simulate_observations,
    station_correlations,
    with_changes,
)
from .tables import (
    block_max,
    budget_table,
    error_table,
    ordering_verdict,
    pull_statistics,
    ratio_table,
    variance_ratio,
    worst_error_table,
)
from .trials import (
    ALL_METHODS,
    EXTRA_METHODS,
    GENERALISATION_METHODS,
    MAIN_METHODS,
    METHODS,
    MODELS,
    READING_METHODS,
    SENSITIVITY_WRANSAC,
    PredictionResults,
    budget_sweep,
    fit_predict,
    gauss_markov,
    run_prediction_experiment,
    student_t_efficiency,
    threshold_sensitivity,
)

__all__ = [
    "ALL_METHODS", "ARCSEC_PER_RAD", "COORDS", "EXTRA_METHODS", "GENERALISATION_CASES",
    "GENERALISATION_METHODS", "MAIN_METHODS", "METHODS", "METHOD_LABELS", "MODELS",
    "NOISE_MODELS", "READINGS", "READING_METHODS", "SENSITIVITY_WRANSAC", "SLUG", "STUDENT_METHODS", "TITLE",
    "PredictionResults", "Scenario", "WransacConfig", "block_max", "budget_sweep",
    "budget_table", "coords_table", "eclipse_season", "error_table", "evaluate", "fit_predict",
    "gauss_markov", "gauss_markov_table", "generalisation", "make_scenario", "ordering_verdict",
    "plot_budget", "plot_eclipse_season", "plot_error_distribution", "plot_flowchart",
    "plot_generalisation", "plot_inlier_histograms", "plot_leverage", "plot_losses",
    "plot_min_samples", "plot_prediction", "plot_pull", "plot_ratio_table",
    "plot_threshold_sensitivity", "pull_statistics", "pull_table", "ratio_table",
    "recommendation", "reproduce", "root_config", "run_prediction_experiment", "simulate_observations",
    "station_correlations", "student_t_efficiency", "threshold_sensitivity", "variance_ratio", "with_changes",
    "worst_error_table",
]

SLUG = "wransac"
TITLE = ("Yan L.J., Huang Y.M., Zhang Y.H., Tang T., Xia Y.X. Research on the application of "
         "RANSAC algorithm in electro-optical tracking of space targets. Opto-Electronic "
         "Engineering 46(11):180540, 2019. DOI 10.12086/oe.2019.180540")

#: Methods of the Student-t run (the reading × noise table needs only these).
STUDENT_METHODS = ("lsq", "ransac", *READING_METHODS, "ideal")
#: The budgets and methods of the U sweep (the Explore widget filters its result).
BUDGETS = (3, 5, 10, 30, 100, 300)
__all__ += [
    "BUDGETS",
    "BUDGET_METHODS",
    "ORBIT_CRITERION",
    "ORBIT_METHODS",
    "ORBIT_SEEDS",
    "ORBIT_STUDY_FILE",
    "PAIRED_RATIO",
    "SINUSOID_METHODS",
    "absolute_ra",
    "orbit_comparison",
    "orbit_criterion",
    "orbit_inputs",
    "orbit_seed_study",
    "orbit_text",
    "read_orbit_study",
    "write_orbit_study",
]
#: The orbit study written by the committed full run (``make repro``), read by the notebook.
ORBIT_STUDY_FILE = "orbit_study.json"
BUDGET_METHODS = ("lsq", "ransac", "wransac_hypothesis", "wransac_refit", "wransac_iterated",
                  "msac", "huber_ransac", "cauchy_ransac", "ideal")


def coords_table(corr: pd.DataFrame, paper: dict) -> pd.DataFrame:
    """§2 correlations, the paper's beside ours (rows: station change × coordinate)."""
    rows = []
    for change in ("longitude", "latitude"):
        for k in ("az", "el", "ra", "dec"):
            rows.append({"station change": change, "coordinate": k,
                         "paper": paper[change][k], "ours": corr.loc[change, k],
                         "paper − ours": paper[change][k] - corr.loc[change, k],
                         "ours (RA unwrapped)": corr.loc[change, "ra_unwrapped"]
                         if k == "ra" else np.nan})
    return pd.DataFrame(rows).set_index(["station change", "coordinate"])


def gauss_markov_table(res: PredictionResults, horizon_min: float = 72) -> pd.DataFrame:
    """The bound and the measured variances, per coordinate (72-min window, pooled).

    Columns: the Gauss–Markov prediction sd at the last observation's time step and at the end
    of the window, the pooled bound (mean over runs and times of σ_pred²), and the measured
    pooled variances of the ideal reference, RANSAC and the WRANSAC readings present.
    """
    rows = []
    win = res.window(horizon_min)
    for ci, coord in enumerate(COORDS):
        gm = res.gm_sd[:, ci]
        row = {"coordinate": coord,
               "σ_pred first step (″)": float(np.sqrt(np.mean(gm[:, 0] ** 2))),
               f"σ_pred at +{horizon_min:g} min (″)": float(np.sqrt(np.mean(gm[:, win][:, -1] ** 2))),
               "bound: mean σ_pred² (″²)": float(np.mean(gm[:, win] ** 2))}
        for m in ("ideal", "ransac", "wransac", "wransac_refit", "wransac_iterated"):
            if m in res.methods:
                row[f"{m} variance (″²)"] = float(np.var(res.method_errors(m, coord,
                                                                            horizon_min)))
        rows.append(row)
    return pd.DataFrame(rows).set_index("coordinate")


def pull_table(res: PredictionResults) -> pd.DataFrame:
    """The pull-toward-the-hypothesis statistics for both coordinates."""
    return pd.DataFrame({co: pull_statistics(res, co) for co in COORDS}).T


def generalisation(config: WransacConfig | None = None, *, n_runs: int = 100,
                   cases: dict | None = None, runner: TrialRunner | None = None
                   ) -> dict[str, PredictionResults]:
    """Paired runs of :data:`GENERALISATION_METHODS` on other objects and stations.

    Returns
    -------
    dict
        ``{case label: PredictionResults}``.
    """
    cfg = config or WransacConfig()
    out = {}
    for i, (label, changes) in enumerate((cases or GENERALISATION_CASES).items()):
        # a seed of its own per case: with the same seed and sampling times, a linear model
        # that fits each track exactly would give the same errors for every object
        c = replace(cfg, **{"seed": cfg.seed + 101 + i, **changes})
        out[label] = run_prediction_experiment(c, n_runs=n_runs, methods=GENERALISATION_METHODS,
                                               runner=runner)
    return out


def recommendation(table: pd.DataFrame) -> str:
    """A practitioner's recommendation computed from :func:`worst_error_table` output.

    Each method's worst 72-min error is divided by the best method's in the same case (the
    ideal reference excluded); methods are ranked by the largest such ratio over the cases,
    then by the mean median-run error. Cases where even the ideal reference (the right inliers,
    least squares) is off by more than 3× the main case's are reported as model-limited.
    """
    worst = table["worst"].drop(columns=["ideal"], errors="ignore")
    med = table["median run"].drop(columns=["ideal"], errors="ignore")
    rel = worst.div(worst.min(axis=1), axis=0)
    score = pd.DataFrame({"rel": rel.max(axis=0), "med": med.mean(axis=0)}).sort_values(
        ["rel", "med"])
    best = score.index[0]
    txt = (f"Over {len(table)} object/station cases, {METHOD_LABELS.get(best, best)} has the "
           f"smallest worst 72-min error relative to the best method of each case (at most "
           f"{score.iloc[0, 0]:.2f}× the best; mean median-run error {score.iloc[0, 1]:.1f}″)")
    for m in ("ransac", "wransac_hypothesis", "cauchy_ransac"):
        if m in score.index and m != best:
            txt += (f"; {METHOD_LABELS.get(m, m)}: at most {score.loc[m, 'rel']:.2f}× the best, "
                    f"{score.loc[m, 'med']:.1f}″")
    wins = worst.idxmin(axis=1).value_counts()
    txt += ". Smallest worst error per case: " + ", ".join(
        f"{METHOD_LABELS.get(m, m)} in {k} of {len(worst)}" for m, k in wins.items())
    if "wransac_hypothesis" in worst.columns and "wransac_hypothesis" not in wins.index:
        txt += " (WRANSAC with the paper-default hypothesis weights in none)"
    if "ideal" in table["median run"].columns:
        ideal = table["median run"]["ideal"]
        limited = ideal.index[ideal > 3 * ideal.min()]
        if len(limited):
            txt += (". Model-limited cases (even the ideal reference's median-run error exceeds "
                    f"3× the best case's {ideal.min():.0f}″): " + "; ".join(
                        f"{k.split(' (')[0]} ({ideal[k]:.0f}″)" for k in limited)
                    + " — there no robust estimator helps: the sidereal-rate model is wrong for "
                    "a drifting object; fit ω (or an orbit) instead")
    return txt + "."


def root_config(config: WransacConfig | None = None, seed: int | None = None) -> WransacConfig:
    """The configuration of a run from root seed ``seed`` (``None``: the committed default).

    Every generator of :func:`reproduce` derives from ``config.seed`` (the paired runs, the
    side studies at fixed offsets, the bootstrap), so a root seed replaces it by a value drawn
    from ``numpy.random.SeedSequence(seed)``.
    """
    cfg = config or WransacConfig()
    if seed is None:
        return cfg
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer) or seed < 0:
        raise ValueError(f"seed must be a non-negative int or None, got {seed!r}")
    return replace(cfg, seed=int(np.random.SeedSequence(int(seed)).generate_state(1)[0]))


def _variants(ratios: pd.DataFrame, default: str) -> dict[str, tuple[float, float, float]]:
    """Our WRANSAC variants' 72-min ratios to RANSAC (all but the paper-default Gaussian cell)."""
    out = {}
    for (noise, coord, meth), row in ratios.iterrows():
        if not str(meth).startswith("WRANSAC") or (noise == "gaussian" and meth.endswith(default)):
            continue
        out[f"{noise}, {coord}, {meth}"] = (float(row["var ratio to RANSAC"]), float(row["95 % lo"]),
                                            float(row["95 % hi"]))
    return out


def orbit_text(table: pd.DataFrame, seeds: pd.DataFrame | None = None, *,
               sigma_arcsec: float = 3.0) -> str:
    """The orbit-fit comparison in words: the criterion, its outcome, why, and the advice.

    ``table`` is :func:`orbit_comparison` output; ``seeds`` (optional) the
    :func:`orbit_seed_study` over independent root seeds. Every number is read from them.
    """
    ok, crit = orbit_criterion(table)
    drift = crit[crit["drifting"]]
    worst, med = table["worst"], table["median run"]
    sin_cols = [m for m in worst.columns if m not in ("orbit", "ideal")]
    ratio_all = worst[sin_cols].min(axis=1) / worst["orbit"]
    ratio_med = med[sin_cols].min(axis=1) / med["orbit"]
    ms = table["ms per fit"]

    def name(k: str) -> str:
        return k.split(" (")[0]

    txt = (f"Criterion (stated before the run): {ORBIT_CRITERION} Outcome: "
           + ("**met**" if ok else "**not met**") + " — " + "; ".join(
               f"{name(k)}: best sinusoid {METHOD_LABELS.get(r['best sinusoid predictor'], r['best sinusoid predictor'])} "
               f"{r['its worst (″)']:.0f}″ vs orbit fit {r['orbit fit worst (″)']:.0f}″ "
               f"(×{r['ratio']:.1f})" for k, r in drift.iterrows()) + ". ")
    if seeds is not None and len(seeds):
        parts = []
        for k, g in seeds.groupby("case", sort=False):
            share = g["met"].mean()
            committed = bool(drift.loc[k, "ratio"] >= PAIRED_RATIO) if k in drift.index else None
            fragile = committed is not None and (share not in (0.0, 1.0)
                                                 or bool(share) != committed)
            parts.append(f"{name(k)} meets it on {int(g['met'].sum())} of {len(g)} (ratio "
                         f"{g['ratio'].min():.1f}–{g['ratio'].max():.1f}, orbit fit's worst "
                         f"{g['orbit fit worst (″)'].min():.0f}–"
                         f"{g['orbit fit worst (″)'].max():.0f}″)"
                         + (" — **fragile**: the committed run's outcome is one draw" if fragile
                            else ""))
        txt += (f"Over {seeds['root seed'].nunique()} independent root seeds (the seeds of "
                "`--seeds 5`, the same runs per case): " + "; ".join(parts) + ". ")
    # why the max-over-runs statistic misses: tail of a noise-limited fit vs a biased model
    p90 = table["p90 run"] if "p90 run" in table.columns.get_level_values(0) else None
    why = []
    for k in drift.index:
        o_med, o_max = med.loc[k, "orbit"], worst.loc[k, "orbit"]
        best = drift.loc[k, "best sinusoid predictor"]
        s_med, s_max = med.loc[k, best], worst.loc[k, best]
        w = (f"{name(k)}: orbit fit per-run worst error median {o_med:.1f}″"
             + (f", 90th percentile {p90.loc[k, 'orbit']:.1f}″" if p90 is not None else "")
             + f", maximum {o_max:.1f}″ (max/median ×{o_max / o_med:.1f}); "
             f"{METHOD_LABELS.get(best, best)} median {s_med:.0f}″ "
             f"({s_med / sigma_arcsec:.0f}σ), max/median ×{s_max / s_med:.1f}")
        if ("paired", "median ratio") in table.columns:
            w += (f"; paired per run, best sinusoid over orbit: median "
                  f"×{table.loc[k, ('paired', 'median ratio')]:.1f}, ≥ {PAIRED_RATIO:g}× in "
                  f"{100 * table.loc[k, ('paired', 'share ≥ 5×')]:.0f} % of runs")
        why.append(w)
    if why:
        txt += ("Why the worst-over-runs statistic decides it: the orbit fit is noise-limited, so "
                "its maximum over runs is set by a continuous tail of its error distribution, "
                "while the sinusoid predictors are bias-limited (the model is wrong for a "
                "drifting object) and their maximum stays close to their median — " + "; ".join(why)
                + " (the paired ratio is a supplementary statistic, not the criterion). ")
    others = ~crit["drifting"]
    if others.any():
        txt += (f"On the other (geostationary) cases the orbit fit is about "
                f"{ratio_med[others].mean():.0f}× better: worst-error ratio "
                f"{ratio_all[others].min():.1f}–{ratio_all[others].max():.1f}, median-run ratio "
                f"{ratio_med[others].min():.1f}–{ratio_med[others].max():.1f} — it has 6 free "
                "parameters for both angles instead of 4 per angle, and the dynamics tie the "
                "two angles and the range together. ")
    txt += (f"Time per fit: the orbit fit takes about {ms['orbit'].mean() / ms['ransac'].mean():.0f}× "
            "a RANSAC fit of both coordinates (Gauss IOD on a few triplets + robust least squares, "
            f"two-body; here {ms['orbit'].mean():.0f} ms vs {ms['ransac'].mean():.1f} ms, WRANSAC "
            f"{ms['wransac_hypothesis'].mean():.1f} ms — absolute times depend on the machine "
            "and its load). ")
    if (ratio_all > 1).all():
        txt += ("Recommendation: predict through a shadow or cloud gap from a robustly fitted "
                "orbit — it has the smallest worst error on every case"
                + ("" if ok else ", though not the pre-stated 5× margin on every drifting case")
                + "; among the sinusoid-model estimators the choice matters less than the model.")
    return txt


def reproduce(*, quick: bool = False, runner: TrialRunner | None = None,
              config: WransacConfig | None = None, seed: int | None = None) -> Reproduction:
    """Run everything the paper reports, plus the paired-run analysis of the finding.

    ``quick`` (tests) uses 40 paired runs instead of 300 and fewer runs in the side studies.
    ``seed`` (an int) is an independent root seed from which every generator of the run is
    derived (:func:`root_config`); ``None`` is the committed default run.

    Returns
    -------
    eotrack.repro.Reproduction
    """
    cfg = root_config(config, seed)
    claims = load_claims(SLUG)
    runner = runner or TrialRunner()
    n_runs = 40 if quick else cfg.n_runs
    n_side = 10 if quick else 100
    sc = make_scenario(cfg)
    res = run_prediction_experiment(cfg, scenario=sc, n_runs=n_runs, runner=runner)
    res_t = run_prediction_experiment(replace(cfg, inlier_noise="student_t"), scenario=sc,
                                      n_runs=n_runs, methods=STUDENT_METHODS, runner=runner)
    ratios = ratio_table({"gaussian": res, f"student_t ν={cfg.student_nu:g}": res_t})
    budget_err = budget_sweep(cfg, scenario=sc, budgets=BUDGETS, methods=BUDGET_METHODS,
                              n_runs=n_side, runner=runner)
    budget = budget_table(budget_err, BUDGETS, BUDGET_METHODS)
    sens = threshold_sensitivity(cfg, scenario=sc, n_runs=n_side // 2, runner=runner)
    corr = station_correlations(cfg, step_s=300.0)
    gen = generalisation(cfg, n_runs=n_side, runner=runner)
    gen[f"NORAD {cfg.norad_id} (main), {cfg.station[0]:g}°, {cfg.station[1]:g}°E"] = res
    worst = worst_error_table({k: v for k, v in gen.items()}, coord="both")
    gen_cols = [m for m in GENERALISATION_METHODS if m in worst["worst"].columns]
    worst = worst.loc[:, [(s, m) for s in ("worst", "median run") for m in gen_cols]]
    orbit = orbit_comparison(cfg, n_runs=5 if quick else n_side // 2, runner=runner,
                             main_label=f"NORAD {cfg.norad_id} (main), {cfg.station[0]:g}°, "
                             f"{cfg.station[1]:g}°E")
    # the criterion over the root seeds of --seeds 5 (the committed run only; quick: a smoke run)
    orbit_seeds = None
    if seed is None:
        orbit_seeds = orbit_seed_study(cfg, seeds=ORBIT_SEEDS[:1] if quick else ORBIT_SEEDS,
                                       n_runs=2 if quick else n_side // 2, runner=runner)
        if not quick:  # read by the notebook (the study takes about a minute)
            from eotrack.repro import papers_repro_dir

            out = papers_repro_dir() / SLUG
            out.mkdir(parents=True, exist_ok=True)
            write_orbit_study(out / ORBIT_STUDY_FILE, orbit, orbit_seeds, n_runs=n_side // 2)
    table_paper = claims["wransac.table1"].paper["values"]
    t1 = ("sin", "lsq", "ransac", "wransac", "ideal")
    tables = {
        "Table 1 — Dec prediction errors (arcsec), paper beside ours, with the ideal reference":
            error_table(res, "dec", table_paper, t1),
        "Table 1 — RA prediction errors (arcsec), paper beside ours, with the ideal reference":
            error_table(res, "ra", table_paper, t1),
        "Variance ratio to RANSAC (72 min), weighting reading × inlier noise, paired runs, "
        "95 % bootstrap intervals": ratios,
        "Gauss–Markov / Cramér–Rao bound and measured variances (72-min window)":
            gauss_markov_table(res),
        "The pull toward the hypothesis (+72 min)": pull_table(res),
        "§2 — station-change correlations": coords_table(corr, claims["wransac.coords"].paper),
        "Beyond — fraction of runs with the whole 72-min Dec prediction within 27″ vs U":
            budget,
        "Beyond — median RMS 72-min Dec error vs t/σ per loss": sens,
        "Beyond — generalisation: worst |error| (RA or Dec) within 72 min per method": worst,
        "Beyond — orbit fit vs sinusoid predictors: worst and median-run 72-min |error| (″), "
        "ms per fit (common noise and outliers)": orbit,
    }
    if orbit_seeds is not None:
        tables["Beyond — orbit criterion on the drifting cases over independent root seeds"] = (
            orbit_seeds.set_index(["case", "root seed"]))
    figs = {}
    specs = [
        ("fig1_min_samples", lambda ax: plot_min_samples(paper=claims["wransac.fig1"].paper,
                                                         ax=ax), None),
        ("fig2_losses", lambda ax: plot_losses(ax=ax), None),
        ("fig3_flowchart", lambda ax: plot_flowchart(ax=ax), (6.5, 7.2)),
        ("mechanism_pull", lambda ax: plot_pull(res, ax=ax), (5.5, 4.5)),
        ("mechanism_leverage", lambda ax: plot_leverage(res, ax=ax), (6, 3.8)),
        ("ratio_table_dec", lambda ax: plot_ratio_table(ratios, "dec", ax=ax), None),
        ("beyond_threshold_sensitivity", lambda ax: plot_threshold_sensitivity(sens, ax=ax),
         None),
        ("beyond_eclipse_season", lambda ax: plot_eclipse_season(sc, ax=ax), None),
        ("beyond_generalisation", lambda ax: plot_generalisation(worst, ax=ax), None),
        ("beyond_orbit_fit", lambda ax: plot_generalisation(
            orbit, ax=ax, title="Orbit fit vs sinusoid predictors"), None),
    ]
    for name, fn, size in specs:
        fig, ax = plt.subplots(figsize=size) if size else plt.subplots()
        fn(ax)
        figs[name] = fig
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.4))
    plot_inlier_histograms(res, axes=axes)
    figs["fig4_fig5_inlier_histograms"] = fig
    for coord in COORDS:
        fig, ax = plt.subplots(figsize=(7.5, 4))
        plot_prediction(res, coord=coord, ax=ax)
        figs[f"fig6_prediction_{coord}"] = fig
        fig, ax = plt.subplots(figsize=(7.5, 4))
        plot_error_distribution(res, coord=coord,
                                bound=claims["wransac.fig7"].paper["bound_arcsec"], ax=ax)
        figs[f"fig7_error_{coord}"] = fig
    rows = evaluate(claims, res, corr, variants=_variants(ratios, cfg.weighting))
    in_shadow = float(np.mean(sc.shadow_pred == UMBRA)) * 100
    reproducing = ratios[ratios["verdict"].str.startswith("paper")]
    which = "; ".join(f"{n}, {c}: {m}" for n, c, m in reproducing.index) or "none"
    text = (
        "## Scenario\n\n"
        f"{sc.description}. {len(sc.t_obs_s)} observations at {cfg.cadence_s:g} s; σ = "
        f"{cfg.sigma_arcsec:g}″; gross errors on {100 * cfg.outlier_fraction:g} % of points, "
        f"uniform in ±[{cfg.gross_error_arcsec[0]:g}, {cfg.gross_error_arcsec[1]:g}]″ (ours: the "
        f"paper states only ε = {cfg.outlier_ratio}); model y = a sin ωt + b cos ωt + c + d t "
        f"(ω sidereal, m = 4: our reading); t = {cfg.threshold_arcsec:g}″; U = {cfg.n_hypotheses} "
        f"(eq. 2) is the minimum number of draws; the loop's maximum is not stated, we draw "
        f"{cfg.n_draws}. {in_shadow:.0f} % of the 72-min prediction window is in umbra.\n\n"
        f"**Paired runs.** {n_runs} runs with common random numbers: in each run every method "
        "sees the same noisy data and the same minimal samples. Variance ratios carry 95 % "
        f"bootstrap intervals ({cfg.n_bootstrap} resamples of the runs). The paper's \"max over "
        "its 20 runs\" statements are judged as the median over disjoint blocks of 20 runs.\n\n"
        "**Readings.** The claims use the weighting reading fixed before any run (weights from "
        "the best hypothesis's residuals) and Gaussian noise. The other two readings and the "
        "Student-t noise are exploratory (2 × 3 = 6 cells tried): cells whose interval lies "
        f"below 1 (the paper's ordering): {which}.\n\n"
        f"**Generalisation.** {recommendation(worst)}\n\n"
        f"**Orbit fit (beyond the paper).** {orbit_text(orbit, orbit_seeds, sigma_arcsec=cfg.sigma_arcsec)}\n\n"
        "Table 1's coordinate is not stated in the paper; we report Dec and RA (RA as the "
        "drift against the sidereal rotation, arcsec of RA).")
    return Reproduction(slug=SLUG, title=TITLE, claims=rows, tables=tables, figures=figs,
                        text=text,
                        data={"scenario": sc, "results": res, "student": res_t, "ratios": ratios,
                              "threshold_sensitivity": sens, "budget": budget,
                              "budget_errors": budget_err, "budgets": BUDGETS,
                              "budget_methods": BUDGET_METHODS, "correlations": corr,
                              "generalisation": gen, "worst": worst, "orbit": orbit,
                              "orbit_seeds": orbit_seeds},
                        settings={**dict(asdict(cfg)), "n_runs_used": n_runs, "quick": quick,
                                  "root seed": seed,
                                  "U": cfg.n_hypotheses, "hypotheses drawn": cfg.n_draws,
                                  "side-study runs": n_side})
