"""Lint cases of the RANSAC + CRLB figures not drawn by a REPORT figure (owner P06)."""

from __future__ import annotations

import numpy as np


def _scene_3d():
    from eotrack.experiments import ransac_crlb_pose as E

    return E.draw_scene_3d(E.make_scene(np.random.default_rng(1)))


def _ellipsoid():
    from eotrack.experiments import ransac_crlb_pose as E

    errs, C, _ = E.ml_pose_samples(40, n_points=60)
    return E.plot_crlb_ellipsoid(C, errs, block="att", n_sigma=2)


def _explore():
    from eotrack.experiments import ransac_crlb_pose as E

    return E.explore_figure("pooled", 1.0)


def _ecdf():
    from eotrack.experiments import ransac_crlb_pose as E
    from eotrack.montecarlo import TrialRunner

    st = E.Settings(readings=("pooled",))
    df = E.run_pose_experiment(8, settings=st, runner=TrialRunner(progress=False))
    return E.plot_error_ecdf(df, "att", ("ransac", "pooled"))


CASES = {"draw_scene_3d": _scene_3d, "plot_crlb_ellipsoid": _ellipsoid,
         "explore_figure": _explore, "plot_error_ecdf": _ecdf}
