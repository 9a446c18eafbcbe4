"""Benchmark for notebook 02 (epipolar association).

1. The 100×100 point-to-epipolar-line distance matrix: ``eotrack.geometry.epipolar_distances``
   against a plain-numpy formula (``|p2ᵀ F p1|`` for all pairs, then the line norms), OpenCV's
   ``cv2.computeCorrespondEpilines`` followed by the line-point products, and a Python double
   loop of eq. (8). Medians of repeated timeit runs, ratios and the largest disagreement.
2. The Fig. 5 sweep: 300 seeded scenario draws × 40 thresholds (target ≤ 20 s), and the full
   per-draw experiment (sweep + three association rules + summary + triangulation).

Run: ``.venv/bin/python benchmarks/bench_epipolar.py`` (≈ 30 s).
"""

from __future__ import annotations

import time
import timeit

import cv2
import numpy as np
from eotrack.experiments import epipolar as E
from eotrack.geometry import epipolar_distances, fundamental_from_poses
from eotrack.montecarlo import TrialRunner, run_trials


def median_time(fn, number: int, repeat: int = 7) -> float:
    return float(np.median(timeit.repeat(fn, number=number, repeat=repeat)) / number)


def main() -> None:
    scen = E.build_scenario()
    ca, cb = scen.cameras[0], scen.cameras[3]
    F = fundamental_from_poses(ca.K, ca.R, ca.c, cb.K, cb.R, cb.c)
    rng = np.random.default_rng(0)
    p1 = p2 = np.zeros((0, 2))

    def ours():  # p1, p2 are rebound below for each size
        return epipolar_distances(F, p1, p2)

    def plain_numpy():
        h1 = np.column_stack([p1, np.ones(len(p1))])
        h2 = np.column_stack([p2, np.ones(len(p2))])
        lines = h1 @ F.T
        return np.abs(lines @ h2.T) / np.hypot(lines[:, 0], lines[:, 1])[:, None]

    def opencv():
        lines = cv2.computeCorrespondEpilines(p1.reshape(-1, 1, 2), 1, F).reshape(-1, 3)
        return np.abs(lines[:, :2] @ p2.T + lines[:, 2:])

    def python_loop():
        out = np.empty((len(p1), len(p2)))
        for i, (u1, v1) in enumerate(p1):
            a, b, c = F @ (u1, v1, 1.0)
            n = (a * a + b * b) ** 0.5
            for j, (u2, v2) in enumerate(p2):
                out[i, j] = abs(a * u2 + b * v2 + c) / n
        return out

    for n_pts in (100, 1000):
        p1 = rng.uniform(0, 512, (n_pts, 2))
        p2 = rng.uniform(0, 512, (n_pts, 2))
        ref = ours()
        reps = 200 if n_pts == 100 else 10
        print(f"== {n_pts} × {n_pts} distance matrix (median per call)")
        t_ours = median_time(ours, reps)
        rows = [("eotrack epipolar_distances", t_ours, ref)]
        peers = [("plain numpy", plain_numpy, reps), ("cv2.computeCorrespondEpilines", opencv, reps)]
        if n_pts == 100:
            peers.append(("python double loop (eq. 8)", python_loop, 3))
        for name, fn, n in peers:
            rows.append((name, median_time(fn, n, repeat=5 if n < 10 else 7), fn()))
        for name, t, val in rows:
            print(f"  {name:32s} {1e6 * t:10.1f} µs   time / ours {t / t_ours:7.2f}   "
                  f"max |Δ| {np.abs(val - ref).max():.1e} px")

    th = np.arange(0.5, 20.01, 0.5)
    runner = TrialRunner(progress=False)
    t0 = time.perf_counter()
    sw = E.run_sweep(scen, E.ErrorConfig(), th, 300, runner=runner)
    t_sweep = time.perf_counter() - t0
    print(f"== Fig. 5 sweep: 300 draws × {len(th)} thresholds: {t_sweep:.2f} s "
          f"(target ≤ 20 s); best L = {sw.best_threshold:g} px")
    t0 = time.perf_counter()
    run_trials(E.scenario_trial, 300, seed=1, runner=runner, args=(scen, E.ErrorConfig(), th, 10.0))
    print(f"== full per-draw experiment, 300 draws: {time.perf_counter() - t0:.2f} s")
    t0 = time.perf_counter()
    run_trials(E.fig6_trial, 600, seed=600, runner=runner, args=(np.array([5.0, 10, 15, 20]),))
    print(f"== Fig. 6, 600 simulations of 100 × 100 points: {time.perf_counter() - t0:.2f} s")


if __name__ == "__main__":
    main()
