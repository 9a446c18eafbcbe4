"""Benchmark for notebook 06 (RANSAC + CRLB pose): ours vs OpenCV, time AND accuracy.

Run: ``.venv/bin/python benchmarks/bench_ransac_crlb_pose.py`` (≈ 1–2 min).

* robust pose on a random family of non-planar pixel-camera scenes (:func:`family_benchmark`):
  ours (:func:`eotrack.pose.ransac_pose`, defaults) vs the paper's 6-point DLT chain vs
  ``cv2.solvePnPRansac`` + LM — share found, median errors and CPU time, with the targets —
  and the same on four held-out families (:func:`heldout_families`: other noise, camera,
  20 points / 50 % outliers, millimetre and normalised image units);

* robust pose of 170 points at both noise units (1 mm = variances in mm² as printed; 0.01 mm =
  the pixel reading), one row per method: median CPU time per call, ratio to bare
  ``cv2.solvePnPRansac`` (SQPnP), and accuracy over 30 scenes (median attitude / position
  error, share of scenes with an attitude error > 20° — the mirrored planar solution);
* diagnosis of the 1 mm case: the same OpenCV solvers on the gross-error-free points WITHOUT
  RANSAC, and the reprojection-cost ratio of the two planar (IPPE) solutions;
* CRLB (6×6 Fisher information + inverse) of 170 points — target ≤ 1 ms;
* the 300-run Figs. 4–5 experiment — target ≤ 30 s (idle machine).

Findings (the 1 mm case, issue 17). Threshold units are consistent: image coordinates are mm on
the focal plane and ``K = diag(10, 10, 1)`` (f in mm), so ``reprojectionError`` is in the same
mm as the points (no pixel/normalised mix-up). The large SQPnP/EPnP errors are not RANSAC's
fault: on the clean points without RANSAC they are as large. At the printed noise (σ = 0.14–0.32
mm on a target image ≈ 2 mm wide) the plane has two poses whose reprojection costs differ by only
~3 % (median of the two IPPE solutions, solved in the plane frame); SQPnP and EPnP minimise
algebraic/object-space errors and land on the mirrored one in most scenes; OpenCV's IPPE, given coplanar points off the object's Z = 0 plane (ours lie at
Z_t = −1 m), returns two wrong poses (both ≈ 24° off) in about half the scenes even at tiny noise
— :func:`eotrack.pose.ippe_poses` solves it in the plane's own frame. ``ransac_pose_opencv`` now
(``disambiguate=True``, default) refines the SQPnP, DLT and both IPPE poses of the inliers,
keeps the lowest reprojection cost and repeats the inlier test — the paper's DLT refit does the
same — which brings it near the 6-point DLT's accuracy at ~10× bare OpenCV's time (still
below the DLT RANSAC's); ``disambiguate=False`` restores OpenCV's speed and its flips.
"""

from __future__ import annotations

import time
import timeit
from dataclasses import replace

import cv2
import numpy as np
from eotrack.experiments import ransac_crlb_pose as E
from eotrack.montecarlo import TrialRunner
from eotrack.pose import (
    ippe_poses,
    pose_crlb,
    random_pnp_scene,
    ransac_pose_dlt,
    ransac_pose_opencv,
    reprojection_errors,
    rotation_error_deg,
)

N_SCENES = 30


def median_ms(fn, number: int, repeat: int = 5) -> float:
    """Median over ``repeat`` of the mean CPU time of ``number`` calls, in ms.

    CPU time (``time.process_time``, OpenCV limited to one thread) rather than wall time: the
    machine this runs on may be shared, and wall time then measures the neighbours.
    """
    t = timeit.repeat(fn, number=number, repeat=repeat, timer=time.process_time)
    return 1e3 * float(np.median(t)) / number


def _cv_ransac(flag):
    def run(X, u, K, thr, rng):
        ok, rv, tv, _ = cv2.solvePnPRansac(X, u, K, None, reprojectionError=thr, confidence=0.99,
                                           iterationsCount=500, flags=flag)
        return (cv2.Rodrigues(rv)[0], tv.ravel()) if ok else None
    return run


def _ours(**kw):
    def run(X, u, K, thr, rng):
        r = ransac_pose_opencv(X, u, K, threshold_px=thr, **kw)
        return (r.R, r.t) if r.success else None
    return run


def _dlt(cfg):
    def run(X, u, K, thr, rng):
        r = ransac_pose_dlt(X, u, K, rng, cfg)
        return (r.R, r.t) if r.success else None
    return run


N_FAMILY = 200
N_HELDOUT = 100


def _rescaled(s, scale: float):
    """The same scene in other image units: pixels × ``scale`` about the origin, K likewise."""
    S = np.diag([scale, scale, 1.0])
    return replace(s, pixels=s.pixels * scale, K=S @ s.K)


def heldout_families(n_scenes: int = N_HELDOUT, seed: int = 9001) -> dict:
    """Families the scale-aware threshold was NOT designed on (fixed before they were run).

    * other noise and camera: σ 1–5 px, f = 800 px, 640×480 image, principal point (300, 260),
      40 points, 40 % outliers, 5–20 m;
    * 20 points with 50 % outliers, f = 1000 px, σ 0.5–2 px;
    * the design family's geometry in focal-plane millimetres (5 µm pixels) and in normalised
      coordinates (``K`` → ``I``); OpenCV's 8 px default threshold is converted to those units
      for it (a user would have to), ours uses its defaults unchanged.

    The first run of these families failed on the first (σ 1–5 px): ``max_threshold_frac``
    0.25 rejected genuine noisy scenes; it became 1.0, so that family is no longer held out.
    Two further families, fixed before that change was run, check it:

    * σ 0.5–4 px, f = 600 px, 640×480, principal point (330, 230), 30 points, 40 % outliers,
      4–12 m;
    * 100 points with 60 % outliers (design camera and noise).

    Returns ``{name: (scenes, opencv_threshold)}``.
    """
    ss = np.random.SeedSequence(seed).spawn(5)
    r1, r2, r3, r4, r5 = (np.random.default_rng(x) for x in ss)
    fam4 = [random_pnp_scene(r4, n_points=30, outlier_fraction=0.4, sigma_px=(0.5, 4.0),
                             focal_px=600.0, principal_point=(330.0, 230.0),
                             image_size=(640, 480), distance_m=(4.0, 12.0))
            for _ in range(n_scenes)]
    fam5 = [random_pnp_scene(r5, n_points=100, outlier_fraction=0.6) for _ in range(n_scenes)]
    fam1 = [random_pnp_scene(r1, n_points=40, outlier_fraction=0.4, sigma_px=(1.0, 5.0),
                             focal_px=800.0, principal_point=(300.0, 260.0),
                             image_size=(640, 480), distance_m=(5.0, 20.0))
            for _ in range(n_scenes)]
    fam2 = [random_pnp_scene(r2, n_points=20, outlier_fraction=0.5, sigma_px=(0.5, 2.0),
                             focal_px=1000.0) for _ in range(n_scenes)]
    base = [random_pnp_scene(r3) for _ in range(n_scenes)]
    mm = 0.005
    return {"σ 1–5 px, f 800, 40 pts, 40 % out (seen)": (fam1, 8.0),
            "20 pts, 50 % out, f 1000": (fam2, 8.0),
            "design geometry in mm (5 µm px)": ([_rescaled(s, mm) for s in base], 8.0 * mm),
            "design geometry, normalised (K = I)": ([replace(s, pixels=(np.c_[s.pixels, np.ones(
                len(s.pixels))] @ np.linalg.inv(s.K).T)[:, :2], K=np.eye(3)) for s in base],
                8.0 / 1400.0),
            "fresh: σ 0.5–4 px, f 600, 30 pts, 40 % out": (fam4, 8.0),
            "fresh: 100 pts, 60 % out": (fam5, 8.0)}


def family_benchmark(n_scenes: int = N_FAMILY, seed: int = 2026, scenes=None,
                     cv_threshold: float = 8.0, paper: bool = True) -> dict:
    """Robust pose on random non-planar scenes (:func:`eotrack.pose.random_pnp_scene`).

    Default family (the design family of the scale-aware threshold): 60 points in a 2 m cube at
    8–15 m, a 1280×960 px camera with an off-centre principal point, per-point noise σ 0.3–1.5
    px, 30 % gross mismatches. Ours: :func:`ransac_pose` with the default
    :class:`RansacConfig` (scale-aware threshold); the paper's chain: 6-point DLT RANSAC as the
    experiment configures it (threshold 4 px here); OpenCV: ``cv2.solvePnPRansac`` (its
    defaults, threshold ``cv_threshold``) + ``cv2.solvePnPRefineLM`` on its inliers. Targets:
    found (rotation error < 5°) in ≥ 95 % of scenes, median errors ≤ 1.0× OpenCV's, CPU time
    ≤ 3× OpenCV's. ``scenes`` replaces the family (see :func:`heldout_families`).
    """
    if scenes is None:
        rng = np.random.default_rng(seed)
        scenes = [random_pnp_scene(rng) for _ in range(n_scenes)]
    methods = E.FAMILY_METHODS if paper else (E.OURS, E.OPENCV)
    return E.pose_family_comparison(scenes, cv_threshold=cv_threshold, methods=methods)


def _print_family(title: str, fam: dict) -> None:
    table = E.family_table(fam)
    print(title)
    print(table.to_string(float_format=lambda v: f"{v:.4g}"))
    ours, cv = table.loc[E.OURS], table.loc[E.OPENCV]
    ok = (ours["found (< 5°)"] >= 0.95 * ours["of"]
          and ours["median rotation error (deg)"] <= cv["median rotation error (deg)"]
          and ours["median position error (m)"] <= cv["median position error (m)"]
          and ours["CPU ms per image"] <= 3 * cv["CPU ms per image"])
    print(f"  targets (ours): found ≥ 0.95, rot and pos ≤ 1.0× OpenCV, time ≤ 3× OpenCV: "
          f"{'MET' if ok else 'NOT MET'}\n")


def main() -> None:
    cv2.setNumThreads(1)
    _print_family(f"== robust pose on {N_FAMILY} random non-planar scenes (design family: 60 "
                  "points, 8–15 m, σ 0.3–1.5 px, 30 % outliers, off-centre principal point)",
                  family_benchmark())
    for name, (scenes, thr) in heldout_families().items():
        _print_family(f"== held-out: {name} ({len(scenes)} scenes; OpenCV threshold {thr:.3g})",
                      family_benchmark(scenes=scenes, cv_threshold=thr, paper=False))
    print("timings: median CPU time per call (process_time), OpenCV single-threaded; "
          f"accuracy over {N_SCENES} scenes of 170 points")
    st = E.Settings()
    for unit in (1.0, 0.01):
        sc = replace(E.Scenario(), noise_unit_mm=unit)
        cfg = st.ransac_config(sc)
        thr = cfg.inlier_threshold_px
        methods = {
            "cv2.solvePnPRansac SQPnP": _cv_ransac(cv2.SOLVEPNP_SQPNP),
            "cv2.solvePnPRansac EPnP": _cv_ransac(cv2.SOLVEPNP_EPNP),
            "cv2.solvePnPRansac IPPE": _cv_ransac(cv2.SOLVEPNP_IPPE),
            "cv2.solvePnPRansac ITERATIVE": _cv_ransac(cv2.SOLVEPNP_ITERATIVE),
            "ours opencv (no LM, no disamb.)": _ours(refine=False, disambiguate=False),
            "ours opencv (+LM, no disamb.)": _ours(disambiguate=False),
            "ours opencv (+LM + disamb., default)": _ours(),
            "paper 6-point DLT RANSAC (+refit)": _dlt(cfg),
        }
        scene = E.make_scene(np.random.default_rng(0), sc, n_points=170)
        X, u, K = scene.points, scene.pixels, sc.K
        times = {k: median_ms(lambda f=f, X=X, u=u, K=K, thr=thr:
                              f(X, u, K, thr, np.random.default_rng(1)), 5)
                 for k, f in methods.items()}
        acc = {k: [] for k in methods}
        clean = {k: [] for k in ("SQPnP", "EPnP", "IPPE (OpenCV)", "ITERATIVE",
                                 "IPPE in plane frame (ours)")}
        ratio = []
        rng = np.random.default_rng(5)
        for _ in range(N_SCENES):
            s = E.make_scene(rng, sc, n_points=170)
            for k, f in methods.items():
                r = f(s.points, s.pixels, K, thr, rng)
                acc[k].append((np.inf, np.inf) if r is None else
                              (rotation_error_deg(r[0], s.R), np.linalg.norm(r[1] - s.t)))
            Xc, uc = s.points[~s.gross], s.pixels[~s.gross]
            for k, flag in (("SQPnP", cv2.SOLVEPNP_SQPNP), ("EPnP", cv2.SOLVEPNP_EPNP),
                            ("IPPE (OpenCV)", cv2.SOLVEPNP_IPPE),
                            ("ITERATIVE", cv2.SOLVEPNP_ITERATIVE)):
                _, rv, _ = cv2.solvePnP(Xc, uc, K, None, flags=flag)
                clean[k].append(rotation_error_deg(cv2.Rodrigues(rv)[0], s.R))
            sols = ippe_poses(Xc, uc, K)
            clean["IPPE in plane frame (ours)"].append(rotation_error_deg(sols[0][0], s.R))
            c = [np.sum(reprojection_errors(Xc, uc, R, t, K) ** 2) for R, t in sols]
            ratio.append(c[1] / c[0])
        t_ref = times["cv2.solvePnPRansac SQPnP"]
        print(f"\n== robust pose, 170 points, noise unit {unit:g} mm (threshold {thr:.3g} mm, "
              "same units as the image coordinates)")
        print(f"{'method':40s} {'time ms':>8s} {'ratio':>6s} {'med att deg':>12s} "
              f"{'med pos m':>10s} {'att>20°':>8s}")
        for k in methods:
            a = np.array(acc[k])
            print(f"{k:40s} {times[k]:8.3f} {times[k] / t_ref:6.2f} {np.median(a[:, 0]):12.4f} "
                  f"{np.median(a[:, 1]):10.4f} {np.mean(a[:, 0] > 20):8.2f}")
        print("  diagnosis — solvers on the clean points, no RANSAC (median attitude error, "
              "share > 20°):")
        for k, v in clean.items():
            v = np.array(v)
            print(f"    {k:30s} {np.median(v):9.4f} deg  {np.mean(v > 20):5.2f}")
        print(f"    reprojection cost, 2nd / 1st planar solution: median {np.median(ratio):.3f}")

    sc = E.Scenario()
    scene = E.make_scene(np.random.default_rng(0), sc, n_points=170)
    t_crlb = median_ms(lambda: pose_crlb(scene.points, sc.R, sc.t, sc.K, scene.sigma), 200)
    print(f"\n== CRLB of 170 points (Fisher information + inverse): {t_crlb:.3f} ms "
          f"(target ≤ 1 ms)")

    t0, c0 = time.perf_counter(), time.process_time()
    df = E.run_pose_experiment(300, scenario=sc, settings=st,
                               runner=TrialRunner(progress=False))
    dt, dc = time.perf_counter() - t0, time.process_time() - c0
    print(f"\n== 300-run experiment (Figs. 4–5, RANSAC + {len(st.readings)} selection "
          f"readings + ML): {dt:.1f} s wall, {dc:.1f} s CPU (target ≤ 30 s); "
          f"{int(df['success'].sum())} runs succeeded")


if __name__ == "__main__":
    main()
