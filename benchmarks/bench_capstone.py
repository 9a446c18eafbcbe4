"""Benchmark for notebook 07 (the capstone): the whole night and the QUICK night.

Targets (issue #30): the whole night (1,200 frames: render, extract, solve the plate, separate,
initiate; then associate, triangulate, fit orbits and predict) in ≤ 2 min on this 2-core
machine, serially; the QUICK night in well under 30 s. Both wall time and CPU time
(``time.process_time``) are printed: on a shared, oversubscribed machine the wall time is
dominated by preemption, and the CPU time is what an idle machine would take. The load
average at the start is printed too.

Run: ``.venv/bin/python benchmarks/bench_capstone.py`` (≈ 2 min idle). ``--quick`` times only
the QUICK night.
"""

from __future__ import annotations

import os
import sys
import time

from eotrack.experiments import capstone as C


def timed(cfg: C.CapstoneConfig) -> tuple[float, float, C.NightResult]:
    C.make_plan(cfg)  # the plan (SGP4, Sun, stations) is cached: time it apart
    t0, c0 = time.perf_counter(), time.process_time()
    night = C.run_night(cfg)
    return time.perf_counter() - t0, time.process_time() - c0, night


def main() -> None:
    print(f"load average at start: {os.getloadavg()[0]:.1f} (2 cores)")
    t0, c0 = time.perf_counter(), time.process_time()
    C.make_plan(C.CapstoneConfig())
    print(f"plan of the whole night: {time.perf_counter() - t0:.1f} s wall, "
          f"{time.process_time() - c0:.1f} s CPU")
    runs = [("QUICK night", C.quick_config(), 30.0)]
    if "--quick" not in sys.argv:
        runs.append(("whole night", C.CapstoneConfig(), 120.0))
    for name, cfg, target in runs:
        wall, cpu, night = timed(cfg)
        n = len(night.plan.bursts)
        print(f"{name}: {n} bursts, {n * cfg.burst_frames} frames — {wall:.1f} s wall, "
              f"{cpu:.1f} s CPU ({cpu / n * 1e3:.0f} ms CPU per burst); stage wall times "
              + ", ".join(f"{k} {v:.1f} s" for k, v in night.wall_s.items())
              + f"; target ≤ {target:g} s: wall {'met' if wall <= target else 'NOT met'}, "
              f"CPU {'met' if cpu <= target else 'NOT met'}")


if __name__ == "__main__":
    main()
