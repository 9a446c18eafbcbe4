"""Robust pose on families of random scenes unlike the paper's: ours vs the paper's chain vs
OpenCV — one computation shared by notebook 06 and ``benchmarks/bench_ransac_crlb_pose.py``.

:func:`pose_family_comparison` solves every scene of a family with each method and returns the
per-scene errors and the CPU time; :func:`family_table` turns that into the table both show.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from typing import Any

import numpy as np
import pandas as pd

from eotrack.pose import RansacConfig, ransac_pose, ransac_pose_dlt, rotation_error_deg

__all__ = ["FAMILY_METHODS", "FOUND_DEG", "OPENCV", "OURS", "PAPER", "family_table",
           "pose_family_comparison"]

#: The methods' names (rows of :func:`family_table`).
OURS = "ransac_pose (defaults)"
PAPER = "paper's chain (6-point DLT)"
OPENCV = "cv2.solvePnPRansac + LM"
FAMILY_METHODS = (OURS, PAPER, OPENCV)
#: A scene counts as found when the rotation error is below this (degrees).
FOUND_DEG = 5.0


def _ours(s: Any, i: int, _thr: float):
    r = ransac_pose(s.points, s.pixels, s.K, np.random.default_rng(i))
    return (r.R, r.t) if r.success else None


def _paper(s: Any, i: int, _thr: float):
    r = ransac_pose_dlt(s.points, s.pixels, s.K, np.random.default_rng(i),
                        RansacConfig.paper(inlier_threshold_px=4.0, min_inlier_ratio=0.6))
    return (r.R, r.t) if r.success else None


def _opencv(s: Any, _i: int, thr: float):
    import cv2

    ok, rv, tv, idx = cv2.solvePnPRansac(s.points, s.pixels, s.K, None, reprojectionError=thr)
    if not ok or idx is None:
        return None
    rv, tv = cv2.solvePnPRefineLM(s.points[idx.ravel()], s.pixels[idx.ravel()], s.K, None, rv,
                                  tv)
    return cv2.Rodrigues(rv)[0], tv.ravel()


_SOLVERS = {OURS: _ours, PAPER: _paper, OPENCV: _opencv}


def pose_family_comparison(scenes: Sequence[Any], *, cv_threshold: float = 8.0,
                           methods: Sequence[str] = FAMILY_METHODS
                           ) -> dict[str, tuple[np.ndarray, float]]:
    """Solve every scene with each method: ours (:func:`eotrack.pose.ransac_pose`, defaults,
    seeded by the scene's index), the paper's chain (6-point DLT RANSAC, threshold 4 px, inlier
    ratio 0.6) and OpenCV (``cv2.solvePnPRansac`` with its defaults at ``cv_threshold``, then
    ``cv2.solvePnPRefineLM`` on its inliers).

    Parameters
    ----------
    scenes : sequence of PnPScene
        Scenes with ``points``, ``pixels``, ``K``, ``R``, ``t``
        (:func:`eotrack.pose.random_pnp_scene`).
    cv_threshold : float
        OpenCV's ``reprojectionError``, in the scenes' image units.
    methods : sequence of str
        Which of :data:`FAMILY_METHODS`, in this order.

    Returns
    -------
    dict
        ``method → (errors, ms)``: ``errors`` an ``(n_scenes, 2)`` array of rotation error
        (degrees) and position error (the scenes' length unit), ``inf`` where the method
        failed; ``ms`` the CPU time per scene in milliseconds.

    Raises
    ------
    ValueError
        If ``scenes`` is empty, ``cv_threshold`` is not positive or a method is unknown.
    """
    scenes = list(scenes)
    if not scenes:
        raise ValueError("scenes must hold at least one scene")
    if not np.isfinite(cv_threshold) or cv_threshold <= 0:
        raise ValueError(f"cv_threshold must be positive, got {cv_threshold}")
    unknown = [m for m in methods if m not in _SOLVERS]
    if unknown:
        raise ValueError(f"methods {unknown} unknown; allowed: {FAMILY_METHODS}")
    out: dict[str, tuple[np.ndarray, float]] = {}
    for name in methods:
        fn = _SOLVERS[name]
        c0 = time.process_time()
        res = [fn(s, i, cv_threshold) for i, s in enumerate(scenes)]
        ms = 1e3 * (time.process_time() - c0) / len(scenes)
        errs = np.array([(rotation_error_deg(r[0], s.R), float(np.linalg.norm(r[1] - s.t)))
                         if r is not None else (np.inf, np.inf) for r, s in zip(res, scenes)])
        out[name] = (errs, ms)
    return out


def family_table(result: dict[str, tuple[np.ndarray, float]], *, reference: str | None = OPENCV,
                 timing: bool = True) -> pd.DataFrame:
    """One row per method of :func:`pose_family_comparison`'s result: scenes found (rotation
    error < :data:`FOUND_DEG`), of how many, median rotation and position errors, CPU ms per
    scene (``timing``), and each as a multiple of ``reference``'s (``None``: no ratios).

    Raises
    ------
    ValueError
        If ``result`` is empty or ``reference`` is not one of its methods.
    """
    if not result:
        raise ValueError("result must hold at least one method")
    if reference is not None and reference not in result:
        raise ValueError(f"reference {reference!r} is not among {list(result)}")
    rows = {}
    for name, (e, ms) in result.items():
        row = {f"found (< {FOUND_DEG:g}°)": int(np.sum(e[:, 0] < FOUND_DEG)), "of": len(e),
               "median rotation error (deg)": float(np.median(e[:, 0])),
               "median position error (m)": float(np.median(e[:, 1]))}
        if timing:
            row["CPU ms per image"] = ms
        rows[name] = row
    table = pd.DataFrame(rows).T
    found = f"found (< {FOUND_DEG:g}°)"
    table[[found, "of"]] = table[[found, "of"]].astype(int)
    if reference is not None:
        ref = table.loc[reference]
        short = "OpenCV" if reference == OPENCV else reference
        for col, what in (("median rotation error (deg)", "rotation"),
                          ("median position error (m)", "position"),
                          *((("CPU ms per image", "time"),) if timing else ())):
            table[f"{what} × {short}"] = table[col] / ref[col]
    return table
