"""Exercises of notebook 04 (Xu & Wang 2016, modified Hough track initiation, with logic and
classic Hough baselines).

Expected values are computed with the library on first use; nothing is typed in.

1. derivation — the χ² disc of the third point: the variance factor ``c`` of a triplet (a
   function of the three frame times);
2. computation — the §4.6 sum Σ N₁N₂N₃ P₃ over the triplet shapes (every detection counted as
   available) in a seeded clutter-only scene;
3. exploration — the paper's procedure on the Explore panel's scenes at a clutter level the
   panel does not offer (35 per frame): false tracks per scene (6-neighbourhood, ρ from the
   image corner);
4. critique — in how many cell indices track 2's two pairs differ with finer cells
   (δρ = 3 px, δθ = 3°, δv = 3 px/s): would they save it from the 6-neighbourhood?
5. critique — the angle constraint at the comparison's 10 px gate.
"""

from __future__ import annotations

import numpy as np

from eotrack.exercises import FunctionAnswer, NumericAnswer, register

__all__: list[str] = []


def _disc_factor_reference(t1: float, t2: float, t3: float, which: int) -> float:
    """``|w|² / w_which²`` for the constant-velocity contrast ``w ∝ (t2 − t3, t3 − t1, t1 − t2)``
    of three hits at ``t1 < t2 < t3`` (``which`` ∈ {0, 1, 2}: the hit looked up)."""
    w = np.array([t2 - t3, t3 - t1, t1 - t2], dtype=float)
    return float(w @ w / w[int(which)] ** 2)


def _ex1_inputs() -> list[tuple]:
    return [(0.0, 1.0, 2.0, 1), (0.0, 1.0, 3.0, 1), (0.0, 1.0, 3.0, 0), (0.0, 2.0, 3.0, 2),
            (0.0, 0.7, 2.1, 1), (1.0, 1.5, 4.0, 0), (0.0, 1.0, 2.0, 2)]


def _ex2_expected() -> float:
    """Σ over ``triplet_shapes`` of N₁N₂N₃ · P₃ (no depletion), by the notebook's functions."""
    from eotrack.experiments import track_init_hough as TH

    cfg = TH.PlantedConfig()
    scene = TH.planted_scene(np.random.default_rng(2016), cfg, clutter_per_frame=30.0,
                             n_objects=0, n_stars=0)
    t = [tt for tt, _ in scene.frames]
    n = [len(xy) for _, xy in scene.frames]
    return float(sum(n[a] * n[b] * n[c] * TH.triplet_chance_probability(
        t[a], t[b], t[c], width=cfg.width_px, v_min=cfg.v_gate_px_s[0],
        v_max=cfg.v_gate_px_s[1], sigma_px=cfg.sigma_px, alpha=cfg.alpha)
        for a, b, c in TH.triplet_shapes(len(t))))


#: the finer cells of exercise 4 (δρ px, δθ degrees, δv px/s)
EX4_CELLS = (3.0, 3.0, 3.0)


def _ex4_expected() -> float:
    """Indices (ρ, θ, v) in which the cells of track 2's pairs (frames 1→2 and 2→4, 1-based)
    differ with the cells :data:`EX4_CELLS` (ρ from the image corner)."""
    import math

    from eotrack.experiments import track_init_hough as TH
    from eotrack.tracking.initiation import pair_parameters

    cfg = TH.xu_config()
    xs = TH.make_xu_scene(cfg)
    d_rho, d_theta, d_v = EX4_CELLS
    pts = {f: (xs.frames[f][0], xs.frames[f][1][np.flatnonzero(xs.labels[f] == 1)[0]])
           for f in (0, 1, 3)}
    cells = []
    for fa, fb in ((0, 1), (1, 3)):
        r, t, v, _ = (float(x[0]) for x in pair_parameters(
            pts[fa][1][None], pts[fb][1][None], pts[fb][0] - pts[fa][0]))
        cells.append((math.floor(r / d_rho), math.floor(math.degrees(t) / d_theta),
                      math.floor(v / d_v)))
    return float(sum(a != b for a, b in zip(*cells)))


def _ex5_expected() -> float:
    """Circular segment of the r = 20 px gate behind the last point (d = 15 px) over πr²."""
    import math

    r, d = 20.0, 15.0
    return (r * r * math.acos(d / r) - d * math.sqrt(r * r - d * d)) / (math.pi * r * r)


def _ex3_expected() -> float:
    from eotrack.experiments import track_init_hough as TH

    return float(TH.explore_results(35.0, 6, False, False)["false"].mean())


register("track_init_hough.1", FunctionAnswer(
    "Derivation. Three hits at t1 < t2 < t3 pass the χ² test when the hit you look up lies in a "
    "disc of area π χ²₂(1−α) σ² c around the point predicted from the other two. Write "
    "disc_factor(t1, t2, t3, which) returning c for the hit `which` (0, 1 or 2) being looked up.",
    reference=_disc_factor_reference, inputs=_ex1_inputs, rtol=1e-9,
    hint="write the least-squares residual of three points as one contrast wᵀx with Σw = 0 and "
         "Σw t = 0; RSS = (wᵀx)²/|w|², and x_which − prediction = (wᵀx)/w_which"))

register("track_init_hough.2", NumericAnswer(
    "Computation. Draw the clutter-only planted scene planted_scene(default_rng(2016), "
    "PlantedConfig(), clutter_per_frame=30, n_objects=0, n_stars=0) and compute the number of "
    "passing triples Σ N₁N₂N₃ P₃ over the frame triples of triplet_shapes (§4.6's first step: "
    "every detection counted as available, before depletion and conflicts), with the planted "
    "scenes' gate, σ, α and field width.",
    expected=_ex2_expected, rtol=2e-3,  # 4 significant digits pass; the 10 px/s gate (0.75 %) not
    hint="N_f is the number of detections of frame f; P₃ is triplet_chance_probability of the "
         "three frames' times; the sum runs over every (a, b, c) of triplet_shapes(6)"))

register("track_init_hough.3", NumericAnswer(
    "Exploration. The Explore panel offers 5, 20 and 50 clutter points per frame. Run the "
    "paper's literal procedure (6-neighbourhood, ρ from the image corner) on the panel's scenes "
    "at 35 per frame: explore_results(35.0, 6, False, False). What is the mean number of false "
    "tracks per scene?",
    expected=_ex3_expected, rtol=1e-2,
    hint="explore_results returns per-scene arrays; average its 'false' entry"))

register("track_init_hough.4", NumericAnswer(
    "Critique. On the nominal Xu scene (make_xu_scene(xu_config())) the paper's 6-neighbourhood "
    "loses track 2 (seen in frames 1, 2 and 4). Would finer cells save it? With δρ = 3 px, "
    "δθ = 3°, δv = 3 px/s (ρ from the image corner), compute the cells (⌊ρ/δρ⌋, ⌊θ/δθ⌋, ⌊v/δv⌋) "
    "of track 2's pairs frame 1→2 and frame 2→4 and give the number of the three indices in "
    "which they differ.",
    expected=_ex4_expected, rtol=0.0, atol=0.0,
    hint="the detections of track 2 are those with label 1; pair_parameters (§4.1) gives ρ, θ "
         "(radians) and v for a pair and its time difference"))

register("track_init_hough.5", NumericAnswer(
    "Critique. The angle-constrained logic rejects a candidate X when the angle at the last point "
    "P between the previous point and X is <= 90°. Take v_min = 15 px/s, Δt = 1 s and a gate "
    "of radius r = 20 px around a prediction exactly v_min·Δt ahead of P. What fraction of the "
    "gate's area holds candidates the constraint rejects?",
    expected=_ex5_expected, rtol=1e-2,
    hint="X is rejected when it lies behind the line through P perpendicular to the motion; that "
         "line cuts the gate disc at distance v_min·Δt from its centre: a circular segment"))
