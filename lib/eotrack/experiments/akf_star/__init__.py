"""Paper akf_star: adaptive anti-occlusion star tracking on a ship (Sheng 2026) — the ablation.

Modules by role: :mod:`.scenario` (variants, settings, filters), :mod:`.trials` (extraction +
tracking of one sequence, the Monte Carlo), :mod:`.explore` (the notebook's Explore panel:
the reproduction's measurements, re-filtered), :mod:`.figures`
(every plot) and :mod:`.claims` (paper tables beside ours, scorecard rows). ``reproduce`` runs
the same configuration as notebook 05.
"""

from __future__ import annotations

from dataclasses import asdict

from eotrack.montecarlo import TrialRunner
from eotrack.repro import Reproduction, load_claims

from .claims import claim_results, paper_table, side_by_side
from .explore import ExploreSession
from .figures import (
    VARIANT_STYLES,
    plot_confidence_trace,
    plot_diurnal_check,
    plot_error_curves,
    plot_example_frames,
    plot_explore_errors,
    plot_extraction_example,
    plot_frames_schematic,
    plot_real_sky,
    plot_sage_husa,
    plot_ship_attitude,
    plot_success_curves,
)
from .scenario import (
    N_SEEDS,
    SCENARIO_LABELS,
    SLUG,
    TITLE,
    VARIANT_PARTS,
    VARIANTS,
    AblationConfig,
    make_filter,
    singer_parameters,
)
from .trials import (
    SENSITIVITY_SETTINGS,
    AblationResult,
    SequenceMeasurements,
    ablation_trial,
    centroid_bias_table,
    consistency_table,
    detect_sequence,
    diurnal_check,
    measure_sequence,
    run_ablation,
    sensitivity_table,
    sequence_seed,
    track_measurements,
    track_sequence,
)

__all__ = [
    "N_SEEDS",
    "SCENARIO_LABELS",
    "SENSITIVITY_SETTINGS",
    "SLUG",
    "TITLE",
    "VARIANTS",
    "VARIANT_PARTS",
    "VARIANT_STYLES",
    "AblationConfig",
    "AblationResult",
    "ExploreSession",
    "SequenceMeasurements",
    "ablation_trial",
    "centroid_bias_table",
    "claim_results",
    "consistency_table",
    "detect_sequence",
    "diurnal_check",
    "make_filter",
    "measure_sequence",
    "paper_table",
    "plot_confidence_trace",
    "plot_diurnal_check",
    "plot_error_curves",
    "plot_example_frames",
    "plot_explore_errors",
    "plot_extraction_example",
    "plot_frames_schematic",
    "plot_real_sky",
    "plot_sage_husa",
    "plot_ship_attitude",
    "plot_success_curves",
    "report_text",
    "reproduce",
    "run_ablation",
    "sensitivity_table",
    "sequence_seed",
    "side_by_side",
    "singer_parameters",
    "track_measurements",
    "track_sequence",
]


def report_text(cfg: AblationConfig) -> str:
    """The data and adopted-settings paragraph of the REPORT (and the notebook)."""
    return (
        "Data: the paper used 'the first 200 frames of OTB100 sequences' (generic visual "
        "tracking data); we simulate a shipborne star sensor instead — real Gaia/Hipparcos "
        "stars around a 2nd-magnitude reference star seen from 30°N 123°E, astropy Alt/Az, "
        "roll/pitch/yaw as sums of sinusoids, Gaussian PSF with motion blur, shot and read "
        "noise, 8-bit output, 128×128 px, 10° field, 5 Hz. Not stated by the paper and adopted "
        f"here: ε = {cfg.epsilon_px:g} px, the association gate, C_img (SNR × flux "
        "consistency), ω, η, γ, λ and the growth of Q during occlusion "
        "(see eotrack.tracking.kalman.ConfidenceConfig). No parameter was tuned to the paper's "
        "numbers. The paper's extraction is used as printed (errata corrected) with two "
        "library defaults that are not the paper's: no cap on the number of stars and each "
        "region grown by 2 px before the centroid (the paper's region biases centroids by "
        "~0.1 px). EXPLORATORY settings, adopted after inspecting track losses (for "
        "robustness, not towards the paper's numbers, and disclosed as such): γ = 5 instead "
        "of the 99 % χ² value 3 (γ = 3 lost the star in rough-sea sequences), R ≤ 1 px² and "
        "q_a within [1, 16]× its sea-state prior in the Sage–Husa safeguard, an association "
        "gate capped at 30 px, and holding the last position after 5 frames without a "
        "measurement (all variants). A claim whose status depends on them is therefore no "
        "stronger than exploratory evidence. Mean errors are sensitive to the few sequences in "
        "which a track is lost; see the median and lost-track tables.")


def reproduce(*, quick: bool = False, runner: TrialRunner | None = None) -> Reproduction:
    """Run the ablation (N_SEEDS seeds × 200 frames × 5 scenarios — notebook 05's
    configuration; quick: 4 seeds × 120 frames)."""
    import matplotlib.pyplot as plt

    cfg = AblationConfig(n_seeds=4, n_frames=120) if quick else AblationConfig()
    claims = load_claims(SLUG)
    res = run_ablation(cfg, runner=runner)
    E, Ps, C = res.mean_error(), res.success_rate(), res.continuity()
    tables = {
        "Table 1 — mean tracking error (px), paper vs ours":
            side_by_side(E, paper_table(claims["akf_star.table1"], "mean_error_px"), 2),
        f"Table 2 — success rate (ε = {cfg.epsilon_px:g} px), paper vs ours":
            side_by_side(Ps, paper_table(claims["akf_star.table2"], "success_rate"), 3),
        f"Continuity (estimate within {cfg.gate_px:g} px of the truth)": C.round(3),
        "Median tracking error (px)": res.median_error().round(2),
        "Lost tracks (fraction of sequences ending > gate from the truth)":
            res.lost_fraction().round(3),
    }
    fig6, ax6 = plt.subplots(figsize=(6.4, 4.0))
    plot_error_curves(res, ax=ax6)
    fig7, ax7 = plt.subplots(figsize=(6.4, 4.0))
    plot_success_curves(res, ax=ax7)
    settings = {"n_seeds": cfg.n_seeds, "n_frames": cfg.n_frames, "epsilon_px": cfg.epsilon_px,
                "gate_px": cfg.gate_px, "gate_sigma": cfg.gate_sigma,
                "gate_max_px": cfg.gate_max_px, "hold_after": cfg.hold_after,
                "confidence": asdict(cfg.confidence),
                "extraction": asdict(cfg.extraction), "quick": quick}
    return Reproduction(SLUG, TITLE, claim_results(res), tables,
                        {"fig6_mean_tracking_error": fig6, "fig7_success_rate": fig7},
                        report_text(cfg), settings)
