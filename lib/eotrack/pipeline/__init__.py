"""The frames pipeline: FITS frames with headers → extraction → astrometric calibration against
the catalogue → star/target separation → track initiation → per-object measurements as an
astropy Table.

Use it on your own frames::

    from eotrack.pipeline import measure_frames
    table = measure_frames(sorted(Path("night").glob("*.fits")))
    table.write("measurements.ecsv")

Each FITS file needs ``DATE-OBS`` (or ``DATE-AVG``), ``EXPTIME`` and a celestial WCS of the
mount's believed pointing (see :mod:`eotrack.pipeline.frames`). A frame that cannot be read or
solved is skipped with a :class:`FrameSkippedWarning` naming it, the stage and the reason.
"""

from __future__ import annotations

from eotrack.astro.astrometry import PlateSolution, PlateSolveError

from .frames import FitsFrameError, Frame, read_fits, write_fits
from .measure import (
    MEASUREMENT_COLUMNS,
    FrameMeasurement,
    FrameSkippedWarning,
    PipelineConfig,
    cross_trail_psf_sigma,
    default_initiator,
    extract_frame,
    initiate_tracks,
    measure_frame,
    measure_frames,
    separate_targets,
    star_trail_px,
    target_border_px,
)
from .simulate import SimulatedSequence, simulate_sequence

__all__ = [
    "MEASUREMENT_COLUMNS",
    "FitsFrameError",
    "Frame",
    "FrameMeasurement",
    "FrameSkippedWarning",
    "PipelineConfig",
    "PlateSolution",
    "PlateSolveError",
    "SimulatedSequence",
    "cross_trail_psf_sigma",
    "default_initiator",
    "extract_frame",
    "initiate_tracks",
    "measure_frame",
    "measure_frames",
    "read_fits",
    "separate_targets",
    "simulate_sequence",
    "star_trail_px",
    "target_border_px",
    "write_fits",
]
