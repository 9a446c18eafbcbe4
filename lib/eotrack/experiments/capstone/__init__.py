"""Capstone — one night of GEO surveillance through every method of the collection.

Not a paper reproduction: it composes the library's parts (notebooks 01–05) into one chain and
measures the error each stage passes on. :mod:`.scenario` (the sky, stations, cameras and the
SGP4 truth), :mod:`.pipeline` (frames → extraction → separation → initiation → association →
triangulation → prediction, and the error budget), :mod:`.figures` (plots). There is no
``reproduce``: the capstone has no paper claims, so ``python -m eotrack.repro`` skips it.
"""

from __future__ import annotations

from .figures import (
    frame_example,
    plot_budget,
    plot_frame,
    plot_night,
    plot_pipeline,
    plot_prediction,
    plot_sweep,
    plot_triangulation,
    sweep_explorer,
)
from .pipeline import (
    PREDICTORS,
    SKY_LEVELS,
    BurstResult,
    NightResult,
    associate_tracklets,
    burst_index,
    eclipse_check,
    error_budget,
    noise_sweep,
    observe_burst,
    predict_through_eclipse,
    range_error_km,
    render_frame,
    run_night,
    separate_targets,
    sidereal_drift_px,
    target_peak_snr,
    triangulate_pairs,
)
from .scenario import (
    ARCSEC_PER_RAD,
    EARTH_RATE_RAD_S,
    Burst,
    CapstoneConfig,
    NightPlan,
    StationSpec,
    camera_matrix,
    make_plan,
    with_changes,
)

SLUG = "capstone"
TITLE = "Capstone — one night of GEO surveillance through every method of the collection"

__all__ = [
    "ARCSEC_PER_RAD",
    "EARTH_RATE_RAD_S",
    "PREDICTORS",
    "SKY_LEVELS",
    "SLUG",
    "TITLE",
    "Burst",
    "BurstResult",
    "CapstoneConfig",
    "NightPlan",
    "NightResult",
    "StationSpec",
    "associate_tracklets",
    "burst_index",
    "camera_matrix",
    "eclipse_check",
    "error_budget",
    "frame_example",
    "make_plan",
    "noise_sweep",
    "observe_burst",
    "plot_budget",
    "plot_frame",
    "plot_night",
    "plot_pipeline",
    "plot_prediction",
    "plot_sweep",
    "plot_triangulation",
    "predict_through_eclipse",
    "range_error_km",
    "render_frame",
    "run_night",
    "separate_targets",
    "sidereal_drift_px",
    "sweep_explorer",
    "target_peak_snr",
    "triangulate_pairs",
    "with_changes",
]
