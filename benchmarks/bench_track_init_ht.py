"""Benchmark for notebook 03 (Li et al. 2008 hypothesis-testing track initiation).

1. Neighbourhood count (eq. 3) of a 256 x 256 binary image: ours (``neighbourhood_count``, default
   backend = cv2.boxFilter with an int32 output; and its numpy summed-area-table backend) versus
   ``scipy.ndimage.uniform_filter`` and OpenCV's ``cv2.boxFilter`` (same zero border), for the
   paper's 5 x 5 window and a larger 15 x 15 one; accuracy = max |difference| in counts.
2. Spatial clustering + temporal test over 50 frames of 256 x 256 (the paper's experiment
   settings; target <= 1 s), CFAR segmentation timed separately.
3. Exact P_DA of a spot with unequal pixels (``area_detection_pixels``, 9 target pixels, 7 x 7
   window) over 1,000 values of P_F x every S, against a direct per-P_F ``np.convolve`` of the
   target and noise pmfs; accuracy = max |difference|.

Run: ``.venv/bin/python benchmarks/bench_track_init_ht.py`` (about 20 s).
"""

from __future__ import annotations

import timeit

import cv2
import numpy as np
from eotrack.experiments.track_init_ht import SequenceSettings
from eotrack.imaging.cfar import cfar_segment
from eotrack.imaging.dim_targets import simulate_dim_sequence
from eotrack.imaging.neighbourhood import cluster_candidates, neighbourhood_count
from eotrack.tracking.initiation.temporal import TemporalContinuityInitiator
from scipy.ndimage import uniform_filter


def median_time(fn, number: int, repeat: int = 7) -> float:
    """Median seconds per call."""
    return float(np.median(timeit.repeat(fn, number=number, repeat=repeat)) / number)


def bench_box() -> None:
    rng = np.random.default_rng(0)
    g = (rng.random((256, 256)) < 0.03).astype(np.uint8)
    gf = g.astype(np.float32)
    print("neighbourhood count, 256 x 256 binary image (median per call)")
    print(f"{'window':>7} {'ours':>10} {'ours SAT':>10} {'scipy':>10} {'cv float':>10} "
          f"{'scipy/ours':>11} {'cv/ours':>8} {'max|diff|':>9}")
    for w in (5, 15):
        ours = neighbourhood_count(g, w)
        sat = neighbourhood_count(g, w, method="sat")
        sp = np.rint(uniform_filter(g.astype(float), w, mode="constant") * w * w)
        cv = np.rint(cv2.boxFilter(gf, -1, (w, w), normalize=False,
                                   borderType=cv2.BORDER_CONSTANT))
        err = max(np.abs(ours - sp).max(), np.abs(ours - cv).max(), np.abs(ours - sat).max())
        t_o = median_time(lambda w=w: neighbourhood_count(g, w), 200)
        t_sat = median_time(lambda w=w: neighbourhood_count(g, w, method="sat"), 200)
        t_s = median_time(lambda w=w: uniform_filter(g.astype(float), w, mode="constant"), 200)
        t_c = median_time(lambda w=w: cv2.boxFilter(gf, -1, (w, w), normalize=False,
                                                    borderType=cv2.BORDER_CONSTANT), 200)
        print(f"{w:>7} {t_o * 1e3:>8.3f}ms {t_sat * 1e3:>8.3f}ms {t_s * 1e3:>8.3f}ms "
              f"{t_c * 1e3:>8.3f}ms "
              f"{t_s / t_o:>11.2f} {t_c / t_o:>8.2f} {int(err):>9}")


def bench_pipeline() -> None:
    st = SequenceSettings()
    seq = simulate_dim_sequence(st.scene(), np.random.default_rng(1))
    g = np.stack([cfar_segment(im, st.p_f, tile=st.tile) for im in seq.images])
    ini = TemporalContinuityInitiator(st.temporal())

    def cluster_and_test():
        frames = [(float(t), cluster_candidates(gk, st.window, st.s)[0])
                  for t, gk in zip(seq.times_s, g)]
        return ini.initiate(frames)

    def cfar_all():
        return [cfar_segment(im, st.p_f, tile=st.tile) for im in seq.images]

    tracks = cluster_and_test()
    t_ct = median_time(cluster_and_test, 1, repeat=5)
    t_cf = median_time(cfar_all, 1, repeat=3)
    n_c = np.mean([len(cluster_candidates(gk, st.window, st.s)[0]) for gk in g])
    print(f"\n50 frames of 256 x 256 (CFAR P_F {st.p_f}, W_S {st.window}x{st.window}, S {st.s}, "
          f"M {st.gate}x{st.gate}, T {st.frames}, T_h {st.min_hits})")
    print(f"  clustering + temporal test: {t_ct:.3f} s  (target <= 1 s: "
          f"{'OK' if t_ct <= 1 else 'SLOW'}); {n_c:.1f} candidates/frame, {len(tracks)} tracks")
    print(f"  CFAR segmentation (tile median/MAD): {t_cf:.3f} s")


def bench_pixels() -> None:
    from eotrack.tracking import hypothesis as hyp
    from scipy.stats import binom

    p = np.array([0.95, 0.6, 0.6, 0.6, 0.6, 0.25, 0.25, 0.25, 0.25])
    pf = np.logspace(-4, -1, 1000)[:, None]
    s = np.arange(0, 50)[None, :]

    def direct():
        out = np.empty((pf.shape[0], s.shape[1]))
        tgt = np.array([1.0])
        for q in p:
            tgt = np.convolve(tgt, [1 - q, q])
        for i, f in enumerate(pf[:, 0]):
            pmf = np.convolve(tgt, binom.pmf(np.arange(41), 40, f))
            out[i] = pmf[::-1].cumsum()[::-1]
        return out

    ours = hyp.area_detection_pixels(p, pf, 7, s)
    err = float(np.abs(ours - direct()).max())
    t_o = median_time(lambda: hyp.area_detection_pixels(p, pf, 7, s), 5)
    t_d = median_time(direct, 2, repeat=3)
    print(f"\nexact P_DA, unequal spot pixels (9 px, 7 x 7), 1,000 P_F x 50 S: ours "
          f"{t_o * 1e3:.1f} ms, per-P_F convolution {t_d * 1e3:.1f} ms "
          f"({t_d / t_o:.1f}x), max|diff| {err:.1e}")


if __name__ == "__main__":
    bench_box()
    bench_pipeline()
    bench_pixels()
