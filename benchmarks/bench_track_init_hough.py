"""Benchmark: track initiation (classic Hough, logic n/m, modified Hough) — speed and quality.

1. The classic Hough accumulator on the same points: ours (numpy ``bincount``) versus
   ``cv2.HoughLinesPointSet`` and ``skimage.transform.hough_line``; target: ours within 1.5× of
   OpenCV.
2. Time per frame versus candidates per frame (uniform candidates, the worst case: the pair
   count grows as N²), steady state (frames 3.. of 6), for our verified modified Hough (targets
   ≤ 5 ms at 200 and ≤ 50 ms at 1,000), the paper's literal procedure and logic 3/4 (target
   ≤ 5 ms at 200). Times are the minimum over repeats of the process CPU time (robust to other
   processes on a shared machine) and, beside it, the median wall time.
3. The planted-scene Monte Carlo of claim ``track_init.planted_scenes``: recall and false
   tracks per scene of every initiator against the analytic chance rate of the χ² 3-of-4 rule.
4. Held-out scenes (accelerating objects, a clutter burst, irregular intervals, P_D 0.8):
   recall, false tracks, GOSPA and SIAP of the default initiator (the growth engine since
   issue 27's last round), of the causal engine (``grow=False``) and of its old opt-ins
   (:data:`HELDOUT_OPTS`) against logic 3/4. Criteria fixed before the decisive runs: the family
   :class:`~eotrack.experiments.track_init_hough.HeldOutConfig` at ±3 px/s², 60 scenes; the
   DEFAULT initiator's recall ≥ 0.90 **and** false tracks per scene ≤ logic 3/4's on the same
   scenes **and** ≤ 5 ms/frame at 200 candidates, ≤ 50 ms at 1,000 (section 2, at idle).
   Seeds: ``HELDOUT_SEED_FIRST`` (20261202, used once for the code of 00:17 UTC, now post hoc),
   ``HELDOUT_SEED_SECOND`` (20261204, decisive for the code of 01:43 UTC, then a development
   seed for the growth engine, with the tuning seeds 11 and 777), and ``HELDOUT_SEED``
   ``HELDOUT_SEED_THIRD`` (20261207, fixed with the criterion in commit 0ffc196; run once for
   the code 1fbbc7c whose growth was always on: met, but it changed the paper's scenes),
   ``HELDOUT_SEED_FOURTH`` (20261208, fixed at 06:51 UTC before it was drawn, same criterion; run
   once for the code 64e5a2f, whose growth ran only when the causal result showed accelerating
   tracks: recall 0.885, NOT met) and ``HELDOUT_SEED`` (20261209, fixed in commit 8053351 before it
   was drawn, same criterion; run once for the code ``HELDOUT_CODE`` = 1b1c4c2, whose growth also
   runs on a clutter burst or when its own result holds accelerating tracks of > m hits).
   20261207 and 20261208 are not drawn again.

Run: ``.venv/bin/python benchmarks/bench_track_init_hough.py`` (``--quick`` for fewer repeats
and scenes, ``--profile`` to print a cProfile of the verified initiator at 200 candidates).
"""

from __future__ import annotations

import argparse
import cProfile
import math
import os
import pstats
import time
from dataclasses import replace

import cv2
import numpy as np
import pandas as pd
from eotrack.experiments import track_init_hough as TH
from eotrack.tracking.initiation import (
    LogicInitiator,
    ModifiedHoughInitiator,
    hough_accumulator,
)
from skimage.transform import hough_line

TARGETS = {("modified Hough (ours)", 200): 5.0, ("modified Hough (ours)", 1000): 50.0,
           ("modified Hough (ours, growth forced)", 200): 5.0,
           ("modified Hough (ours, growth forced)", 1000): 50.0,
           ("modified Hough (ours, causal: grow=False)", 200): 5.0,
           ("modified Hough (ours, causal: grow=False)", 1000): 50.0,
           ("logic 3/4", 200): 5.0}
TARGETS_NAMES = ("modified Hough (ours)", "modified Hough (ours, growth forced)",
                 "modified Hough (ours, causal: grow=False)", "logic 3/4")
# the opt-in settings, the decisive seed and its targets live in the experiment package
HELDOUT_OPTS, HELDOUT_SEED, HELDOUT_TARGETS = TH.HELDOUT_OPTS, TH.HELDOUT_SEED, TH.HELDOUT_TARGETS
HELDOUT_SEED_FIRST = TH.HELDOUT_SEED_FIRST


def cpu_and_wall(fn, repeat: int) -> tuple[float, float]:
    """(minimum process CPU time, median wall time) of ``fn()`` in seconds, after a warm-up."""
    fn()
    cpu, wall = [], []
    for _ in range(repeat):
        c0, w0 = time.process_time(), time.perf_counter()
        fn()
        cpu.append(time.process_time() - c0)
        wall.append(time.perf_counter() - w0)
    return float(np.min(cpu)), float(np.median(wall))


def bench_accumulator(n_points: int = 800, seed: int = 0, repeat: int = 60) -> None:
    rng = np.random.default_rng(seed)
    width = 512
    theta0, rho0 = math.radians(62.2), 300.0
    n = np.array([math.cos(theta0), math.sin(theta0)])
    u = np.array([-n[1], n[0]])
    line = rho0 * n + np.outer(np.linspace(-120, 120, 25), u)
    pts = np.concatenate([line, rng.uniform(0, width, (n_points - len(line), 2))])
    pts = np.round(pts)  # integer pixels so the three see the same input
    pts = pts[np.all((pts >= 0) & (pts < width), axis=1)]
    theta = (np.arange(180) + 0.5) * math.radians(1.0)
    rmax = math.ceil(width * math.sqrt(2))
    pts32 = pts.astype(np.float32).reshape(-1, 1, 2)
    img = np.zeros((width, width), dtype=bool)
    img[pts[:, 1].astype(int), pts[:, 0].astype(int)] = True
    fns = {
        "ours (numpy bincount)": lambda: hough_accumulator(pts, 1.0, 1.0, rho_max=rmax),
        "cv2.HoughLinesPointSet": lambda: cv2.HoughLinesPointSet(
            pts32, 5, 3, -rmax, rmax, 1.0, 0.0, math.pi, math.radians(1.0)),
        "skimage.hough_line": lambda: hough_line(img, theta=theta),
    }
    # each method in its own block of repeats (steady state, as the baseline was
    # measured), the blocks alternated over three rounds so load hits them alike
    cpu = {k: [] for k in fns}
    for _ in range(3):
        for k, f in fns.items():
            f()
            for _ in range(repeat // 3):
                c0 = time.process_time()
                f()
                cpu[k].append(time.process_time() - c0)
    t = {k: float(np.min(v)) for k, v in cpu.items()}
    r, th, votes = fns["ours (numpy bincount)"]().peak()
    cv_best = fns["cv2.HoughLinesPointSet"]().reshape(-1, 3)[0]
    print(f"1) classic Hough accumulator, {len(pts)} points (25 on a line ρ={rho0:g}, "
          f"θ={math.degrees(theta0):g}°), δρ = 1 px, δθ = 1° — min CPU ms over {repeat}")
    for k, v in t.items():
        print(f"   {k:26s} {1e3 * v:8.3f} ms")
    ratio = t["ours (numpy bincount)"] / t["cv2.HoughLinesPointSet"]
    print(f"   ratio ours/OpenCV = {ratio:.2f} (target ≤ 1.5: {'ok' if ratio <= 1.5 else 'MISSED'}); "
          f"ours/skimage = {t['ours (numpy bincount)'] / t['skimage.hough_line']:.2f}")
    print(f"   peaks: ours ρ={r:.1f} θ={math.degrees(th):.2f}° ({votes} votes), OpenCV "
          f"ρ={cv_best[1]:.1f} θ={math.degrees(cv_best[2]):.2f}° ({int(cv_best[0])} votes)")


def bench_per_frame(sizes=(50, 100, 200, 500, 1000), repeat: int = 7) -> pd.DataFrame:
    # the default runs the growth engine unless the frames are crowded (grow_max_seeds: here
    # from ~400 uniform candidates per frame), then the causal engine; "growth forced" lifts
    # that switch so the growth engine's own time is measured too
    inits = {"modified Hough (ours)": ModifiedHoughInitiator(),
             "modified Hough (ours, growth forced)": ModifiedHoughInitiator(
                 grow_max_seeds=1e12, grow_min_accelerating=0),
             "modified Hough (ours, causal: grow=False)": ModifiedHoughInitiator(grow=False),
             "modified Hough (paper, literal)": ModifiedHoughInitiator(literal=True),
             "logic 3/4": LogicInitiator()}
    limit = {"modified Hough (paper, literal)": 200, "logic 3/4": 500}
    rows = []
    for n_c in sizes:
        rng = np.random.default_rng(1)
        frames = [(float(k), rng.uniform(0, 512, (n_c, 2))) for k in range(6)]
        for name, ini in inits.items():
            if n_c > limit.get(name, 10**9):
                continue
            rep = repeat if not (name.startswith("modified Hough (paper") and n_c > 50) else 1
            c6, w6 = cpu_and_wall(lambda fr=frames, i=ini: i.initiate(fr), rep)
            c2, w2 = cpu_and_wall(lambda fr=frames, i=ini: i.initiate(fr[:2]), rep)
            cpu_ms = 1e3 * (c6 - c2) / 4  # steady state: frames 3-6 pair with two earlier ones
            wall_ms = 1e3 * (w6 - w2) / 4
            tgt = TARGETS.get((name, n_c))
            rows.append({"candidates/frame": n_c, "initiator": name, "CPU ms/frame": cpu_ms,
                         "wall ms/frame": wall_ms, "target ms": tgt,
                         "meets": None if tgt is None else bool(cpu_ms <= tgt)})
    df = pd.DataFrame(rows)
    lit = df[df["initiator"] == "modified Hough (paper, literal)"].set_index("candidates/frame")
    ours = df[df["initiator"] == "modified Hough (ours)"].set_index("candidates/frame")
    df["speed-up vs literal"] = [
        lit.loc[r["candidates/frame"], "CPU ms/frame"] / r["CPU ms/frame"]
        if r["initiator"] == "modified Hough (ours)" and r["candidates/frame"] in lit.index
        else np.nan for _, r in df.iterrows()]
    print("\n2) time per frame, uniform candidates, steady state (min CPU over repeats; median "
          "wall beside it)")
    with pd.option_context("display.width", 160, "display.float_format", "{:.2f}".format):
        print(df.to_string(index=False))
    del ours
    return df


def bench_planted(n_scenes: int, n_chance: int) -> None:
    cfg = TH.PlantedConfig()
    t0 = time.perf_counter()
    chance = TH.chance_rate_check(cfg, n_trials=n_chance)
    df = TH.run_planted(cfg, n_scenes=n_scenes)
    summ = TH.summarise_planted(df)
    print(f"\n3) planted scenes ({n_scenes} random scenes: 2-8 objects at 5-150 px/s, P_D 0.9, "
          "10-40 residual stars, clutter 5-50/frame, σ 0.3 px; gate [3, 240] px/s)")
    with pd.option_context("display.width", 160, "display.float_format", "{:.3f}".format):
        print(summ.to_string(index=False))
        print("   chance rate check on clutter-only scenes (measured / analytic):")
        print(chance[["clutter", "scenes", "measured per scene", "analytic per scene",
                      "ratio", "ratio s.e."]].to_string(index=False))
    ours = summ.set_index("method").loc["modified Hough 3/4 (ours)"]
    print(f"   verified modified Hough: recall {ours['recall']:.3f} (target ≥ 0.95), false/scene "
          f"{ours['false per scene']:.2f} = {ours['false / chance']:.2f} × chance (target ≤ 1.5) "
          f"— {time.perf_counter() - t0:.0f} s")


def bench_heldout(n_scenes: int, seed: int = 777, accel_px_s2: float = 3.0,
                  metrics: bool = True) -> dict:
    """Held-out scenes (issue 27): mild accelerations, a 150-false-alarm burst in one frame,
    irregular intervals, P_D 0.8. Targets: recall ≥ 0.90 and false tracks ≤ logic 3/4's.
    Beside recall: GOSPA (c = ``METRIC_CUTOFF_PX``, p = 1, mean per frame from frame 2) and
    SIAP completeness / spuriousness (Stone Soup), scene means."""
    from eotrack.experiments.track_init_hough.trials import METRIC_CUTOFF_PX
    from eotrack.tracking.metrics import initiation_metrics

    cfg = replace(TH.HeldOutConfig(), accel_px_s2=accel_px_s2)
    inits = {"modified Hough (ours, default)": ModifiedHoughInitiator(v_min=3, v_max=240),
             "modified Hough (ours, causal: grow=False)": ModifiedHoughInitiator(
                 v_min=3, v_max=240, grow=False),
             "modified Hough (ours, causal + old opt-ins)": ModifiedHoughInitiator(
                 v_min=3, v_max=240, **HELDOUT_OPTS),
             "logic 3/4": LogicInitiator(n=3, m=4, v_min=3, v_max=240, gate_px=10.0)}
    rng = np.random.default_rng(seed)
    tot = {k: [0, 0, 0] for k in inits}
    met = {k: [] for k in inits}
    for _ in range(n_scenes):
        scene = TH.heldout_scene(rng, cfg)
        for name, ini in inits.items():
            tracks = ini.initiate(scene.frames)
            r = TH.score_tracks(tracks, scene)
            tot[name][0] += r["correct"]
            tot[name][1] += r["eligible"]
            tot[name][2] += r["false"]
            if metrics:
                met[name].append(initiation_metrics(tracks, scene.frames, scene.truth_xy,
                                                    width=cfg.width_px, c=METRIC_CUTOFF_PX,
                                                    first_frame=2))
    role = ("DECISIVE held-out seed" if seed == HELDOUT_SEED else
            "fourth decisive seed (its code: 64e5a2f), now post hoc"
            if seed == TH.HELDOUT_SEED_FOURTH else
            "third decisive seed (its code: growth always on), now post hoc"
            if seed == TH.HELDOUT_SEED_THIRD else
            "second decisive seed, now a development seed" if seed == TH.HELDOUT_SEED_SECOND
            else "first decisive seed, now post hoc" if seed == HELDOUT_SEED_FIRST
            else "tuning seed")
    print(f"\n4) {role} {seed}: scenes ({n_scenes}: {cfg.n_frames} frames at {cfg.dt_s} s intervals, "
          f"accelerations ±{cfg.accel_px_s2:g} px/s² along and across, P_D {cfg.p_detect}, "
          f"a burst of {cfg.burst} false alarms in one frame)")
    out = {}
    for name, (c, e, f) in tot.items():
        row = {"recall": c / max(e, 1), "false per scene": f / n_scenes, "eligible": e}
        if metrics:
            row.update(pd.DataFrame(met[name]).mean().to_dict())
        out[name] = row
        extra = (f"  GOSPA {row['gospa']:.1f} (missed {row['gospa missed']:.1f}, false "
                 f"{row['gospa false']:.1f}, loc {row['gospa localisation']:.2f})  SIAP C "
                 f"{row['siap completeness']:.3f} S {row['siap spuriousness']:.3f}"
                 if metrics else "")
        print(f"   {name:44s} recall {row['recall']:.3f}  false/scene {row['false per scene']:.2f}"
              + extra)
    lg = tot["logic 3/4"]
    d = tot["modified Hough (ours, default)"]
    print(f"   default: recall ≥ {HELDOUT_TARGETS['recall']}: "
          f"{d[0] / max(d[1], 1) >= HELDOUT_TARGETS['recall']}; false ≤ logic 3/4: {d[2] <= lg[2]}")
    return out


def record_heldout(path: str = "papers_repro/track_init_hough/heldout_benchmark.json") -> dict:
    """Run the decisive held-out seed, the first (now post hoc) one and the per-frame times of
    the default and the opt-ins, and write them with the date and load (read by notebook 04)."""
    import json

    t0 = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    load0 = os.getloadavg()[0]
    rec = {"date": t0, "load average at start": load0, "cpu count": os.cpu_count(),
           "targets": HELDOUT_TARGETS, "opts": HELDOUT_OPTS, "scenes": 60, "accel_px_s2": 3.0,
           "seeds": {}}
    rec["code"] = TH.HELDOUT_CODE
    # the decisive seed once, and a development seed; the earlier decisive seeds (20261207,
    # 20261208) are not drawn again (their records: heldout_benchmark_1fbbc7c.json and
    # heldout_benchmark_64e5a2f.json)
    for seed, role in ((HELDOUT_SEED, "decisive"),
                       (TH.HELDOUT_SEED_SECOND, "second decisive seed, now development")):
        rec["seeds"][str(seed)] = {"role": role, "initiators": bench_heldout(60, seed=seed)}
    df = bench_per_frame(sizes=(200, 1000), repeat=3)
    df = df[df["initiator"].isin(list(TARGETS_NAMES))]
    rec["per frame"] = df[["candidates/frame", "initiator", "CPU ms/frame",
                           "wall ms/frame"]].to_dict("records")
    rec["per frame on held-out scenes"] = bench_heldout_time()
    rec["load average at end"] = os.getloadavg()[0]
    with open(path, "w", encoding="utf-8") as fh:
        json.dump(rec, fh, indent=1, default=float)
    print(f"\nwrote {path}")
    return rec


def bench_heldout_time(n_scenes: int = 20, seed: int = 777) -> list[dict]:
    """CPU ms per frame of the default (growth runs on every scene of this family: a burst),
    of the causal engine and of logic 3/4 on held-out scenes of a tuning seed — the case where
    section 2's uniform candidates (crowded frames: causal engine) do not measure the growth."""
    cfg = TH.HeldOutConfig()
    inits = {"modified Hough (ours, default)": ModifiedHoughInitiator(v_min=3, v_max=240),
             "modified Hough (ours, causal: grow=False)": ModifiedHoughInitiator(
                 v_min=3, v_max=240, grow=False),
             "logic 3/4": LogicInitiator(n=3, m=4, v_min=3, v_max=240, gate_px=10.0)}
    rng = np.random.default_rng(seed)
    scenes = [TH.heldout_scene(rng, cfg) for _ in range(n_scenes)]
    n_det = float(np.mean([len(xy) for sc in scenes for _, xy in sc.frames]))
    n_max = float(np.mean([max(len(xy) for _, xy in sc.frames) for sc in scenes]))
    rows = []
    print(f"\n   held-out scenes ({n_scenes}, seed {seed}): {n_det:.0f} detections per frame on "
          f"average, {n_max:.0f} in the burst frame — CPU ms per frame (min of 3)")
    for name, ini in inits.items():
        cpu, _ = cpu_and_wall(lambda ini=ini: [ini.initiate(sc.frames) for sc in scenes], 3)
        ms = 1e3 * cpu / (n_scenes * cfg.n_frames)
        rows.append({"initiator": name, "CPU ms/frame": ms, "mean detections/frame": n_det,
                     "burst frame detections": n_max})
        print(f"   {name:44s} {ms:7.2f} ms/frame")
    return rows


def profile_verified(n_c: int = 200) -> None:
    rng = np.random.default_rng(1)
    frames = [(float(k), rng.uniform(0, 512, (n_c, 2))) for k in range(6)]
    ini = ModifiedHoughInitiator()
    ini.initiate(frames)
    pr = cProfile.Profile()
    pr.enable()
    for _ in range(5):
        ini.initiate(frames)
    pr.disable()
    print(f"\nprofile: verified modified Hough, {n_c} candidates/frame, 5 runs of 6 frames")
    pstats.Stats(pr).sort_stats("tottime").print_stats(10)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer repeats and scenes")
    ap.add_argument("--profile", action="store_true", help="cProfile the verified initiator")
    ap.add_argument("--record", action="store_true",
                    help="only the held-out record read by notebook 04 (writes its JSON)")
    args = ap.parse_args()
    if args.record:
        record_heldout()
        raise SystemExit(0)
    t_start = time.perf_counter()
    print(f"load average at start: {os.getloadavg()[0]:.1f} ({os.cpu_count()} CPUs)")
    bench_accumulator(repeat=20 if args.quick else 60)
    bench_per_frame(repeat=3 if args.quick else 7)
    bench_planted(20 if args.quick else 100, 10 if args.quick else 100)
    for acc in (3.0, 5.0):  # seed 777: a tuning seed (the settings were chosen on 11, 777 and
        bench_heldout(15 if args.quick else 60, accel_px_s2=acc)  # 20261204)
    bench_heldout(15 if args.quick else 60, seed=HELDOUT_SEED_FIRST, accel_px_s2=3.0)
    bench_heldout(15 if args.quick else 60, seed=TH.HELDOUT_SEED_SECOND, accel_px_s2=3.0)
    bench_heldout(15 if args.quick else 60, seed=HELDOUT_SEED, accel_px_s2=3.0)
    bench_heldout_time(5 if args.quick else 20)
    if args.profile:
        profile_verified()
    print(f"\nload average at end: {os.getloadavg()[0]:.1f}; total "
          f"{time.perf_counter() - t_start:.0f} s")
