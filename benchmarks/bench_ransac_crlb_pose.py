"""Benchmark for notebook 06 (RANSAC + CRLB pose): ours vs OpenCV on the same input.

Run: ``.venv/bin/python benchmarks/bench_ransac_crlb_pose.py`` (≈ 40 s).

* robust pose of 170 points: ``eotrack.pose.ransac_pose_opencv`` (wraps ``cv2.solvePnPRansac``
  with SQPnP, + ``solvePnPRefineLM``) and the paper's 6-point DLT RANSAC
  (``ransac_pose_dlt``) vs bare ``cv2.solvePnPRansac`` (SQPnP) — target: ours within 2×;
* CRLB (6×6 Fisher information + inverse) of 170 points — target ≤ 1 ms;
* the 300-run Figs. 4–5 experiment — target ≤ 30 s.
"""

from __future__ import annotations

import time
import timeit
from dataclasses import replace

import cv2
import numpy as np
from eotrack.experiments import ransac_crlb_pose as E
from eotrack.montecarlo import TrialRunner
from eotrack.pose import pose_crlb, ransac_pose_dlt, ransac_pose_opencv, rotation_error_deg


def median_ms(fn, number: int, repeat: int = 7) -> float:
    """Median over ``repeat`` of the mean CPU time of ``number`` calls, in ms.

    CPU time (``time.process_time``, OpenCV limited to one thread) rather than wall time: the
    machine this runs on may be shared, and wall time then measures the neighbours.
    """
    t = timeit.repeat(fn, number=number, repeat=repeat, timer=time.process_time)
    return 1e3 * float(np.median(t)) / number


def main() -> None:
    cv2.setNumThreads(1)
    print("timings: median CPU time per call (process_time), OpenCV single-threaded")
    st = E.Settings()
    for unit in (1.0, 0.01):
        sc = replace(E.Scenario(), noise_unit_mm=unit)
        thr = st.ransac_config(sc).inlier_threshold_px
        scene = E.make_scene(np.random.default_rng(0), sc, n_points=170)
        X, u, K = scene.points, scene.pixels, sc.K
        cfg = st.ransac_config(sc)

        def cv_bare(X=X, u=u, K=K, thr=thr):
            return cv2.solvePnPRansac(X, u, K, None, reprojectionError=thr, confidence=0.99,
                                      iterationsCount=500, flags=cv2.SOLVEPNP_SQPNP)

        def ours_cv(X=X, u=u, K=K, thr=thr):
            return ransac_pose_opencv(X, u, K, threshold_px=thr)

        def ours_cv_norefine(X=X, u=u, K=K, thr=thr):
            return ransac_pose_opencv(X, u, K, threshold_px=thr, refine=False)

        def paper_dlt(X=X, u=u, K=K, cfg=cfg):
            return ransac_pose_dlt(X, u, K, np.random.default_rng(1), cfg)

        t_cv = median_ms(cv_bare, 20)
        t_ours = median_ms(ours_cv, 20)
        t_ours_nr = median_ms(ours_cv_norefine, 20)
        t_dlt = median_ms(paper_dlt, 5)
        print(f"\n== robust pose, 170 points, noise unit {unit:g} mm (threshold {thr:.3g} mm)")
        print(f"cv2.solvePnPRansac (SQPnP)                 {t_cv:8.3f} ms")
        print(f"ours ransac_pose_opencv (refine=False)     {t_ours_nr:8.3f} ms   ratio "
              f"{t_ours_nr / t_cv:5.2f}   (same work: like for like)")
        print(f"ours ransac_pose_opencv (+ RefineLM)       {t_ours:8.3f} ms   ratio "
              f"{t_ours / t_cv:5.2f}   (default: adds solvePnPRefineLM on the inliers)")
        print(f"paper 6-point DLT RANSAC (+ refit)         {t_dlt:8.3f} ms   ratio "
              f"{t_dlt / t_cv:5.2f}")
        # accuracy over 30 scenes (median attitude error, deg; median position error, m)
        rng = np.random.default_rng(5)
        acc = {"cv2": [], "ours (cv2 + LM)": [], "paper DLT": []}
        for _ in range(30):
            s = E.make_scene(rng, sc, n_points=170)
            _ok, rv, tv, _ = cv2.solvePnPRansac(s.points, s.pixels, K, None,
                                               reprojectionError=thr, confidence=0.99,
                                               iterationsCount=500, flags=cv2.SOLVEPNP_SQPNP)
            acc["cv2"].append((rotation_error_deg(cv2.Rodrigues(rv)[0], s.R),
                               np.linalg.norm(tv.ravel() - s.t)))
            r = ransac_pose_opencv(s.points, s.pixels, K, threshold_px=thr)
            acc["ours (cv2 + LM)"].append((rotation_error_deg(r.R, s.R),
                                           np.linalg.norm(r.t - s.t)))
            r = ransac_pose_dlt(s.points, s.pixels, K, rng, cfg)
            acc["paper DLT"].append((rotation_error_deg(r.R, s.R), np.linalg.norm(r.t - s.t)))
        for k, v in acc.items():
            a = np.array(v)
            print(f"  accuracy {k:18s} median attitude {np.median(a[:, 0]):8.4f} deg, "
                  f"position {np.median(a[:, 1]):8.4f} m")

    sc = E.Scenario()
    scene = E.make_scene(np.random.default_rng(0), sc, n_points=170)
    R, t, K = sc.R, sc.t, sc.K
    t_crlb = median_ms(lambda: pose_crlb(scene.points, R, t, K, scene.sigma), 200)
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
