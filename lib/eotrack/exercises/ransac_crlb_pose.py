"""Exercises of notebook 06 (RANSAC + CRLB feature selection for spacecraft pose).

Expected values are computed with the library when first checked; nothing is typed in except
the letters of the multiple-choice answers (definitions).
"""

from __future__ import annotations

import numpy as np

from eotrack.exercises import ArrayAnswer, Choice, FunctionAnswer, NumericAnswer, register

SLUG = "ransac_crlb_pose"

#: Exercise 1's point and camera: target point X (m), attitude angles (deg, extrinsic x-y-z,
#: R = eotrack.pose.attitude_matrix(angles)), t (m), f (mm), σ (mm). R ≠ I, so the
#: perturbation convention matters: −[R X]ₓ (camera frame, the library's) and −R[X]ₓ (body
#: frame) give different J₁.
EX1 = {"X": (0.5, -0.2, 0.3), "angles_deg": (30.0, -20.0, 50.0), "t": (0.4, -0.3, 10.0),
       "f_mm": 10.0, "sigma_mm": 0.2}


def _ex1_R() -> np.ndarray:
    from eotrack.pose import attitude_matrix

    return attitude_matrix(EX1["angles_deg"])


def _ex1_expected() -> np.ndarray:
    from eotrack.pose import intrinsic_matrix, pose_fisher_information

    return pose_fisher_information(np.array([EX1["X"]]), _ex1_R(), np.array(EX1["t"]),
                                   intrinsic_matrix(EX1["f_mm"]), EX1["sigma_mm"])


def _scaled_score(points, R, t, K, sigma) -> float:
    """Dimensionless score: weighted sum of the 7 CRLBs, translation terms divided by |t|²."""
    from eotrack.pose import quaternion_crlb, scaled_crlb_weights

    w = scaled_crlb_weights(float(np.linalg.norm(t)))
    return float(np.sum(w * np.diag(quaternion_crlb(points, R, t, K, sigma))))


def _ex2_expected() -> float:
    from eotrack.experiments.ransac_crlb_pose import Scenario, make_scene

    sc = Scenario()
    s = make_scene(np.random.default_rng(0), sc, outlier_fraction=0.0)
    return (_scaled_score(s.points[:6], sc.R, sc.t, sc.K, s.sigma[:6])
            / _scaled_score(s.points, sc.R, sc.t, sc.K, s.sigma))


def points_needed(points, R, t, K, sigma, frac):
    """Reference for exercise 3: the fewest leading points whose dimensionless CRLB score
    (exercise 2's) is within ``(1 + frac)`` of the score of all points (given order)."""
    from eotrack.pose import information_monotonicity, scaled_crlb_weights

    s = information_monotonicity(points, R, t, K, sigma,
                                 weights=scaled_crlb_weights(float(np.linalg.norm(t))))
    return int(6 + np.flatnonzero(s <= (1.0 + frac) * s[-1])[0])


def _ex3_inputs() -> list[tuple]:
    from eotrack.experiments.ransac_crlb_pose import Scenario, make_scene

    sc = Scenario()
    out = []
    for seed, frac in ((11, 0.1), (12, 0.25), (13, 0.5), (14, 0.05)):
        s = make_scene(np.random.default_rng(seed), sc, outlier_fraction=0.0)
        out.append((s.points, sc.R, sc.t, sc.K, s.sigma, frac))
    return out


def _ex4_expected() -> np.ndarray:
    from eotrack.experiments.ransac_crlb_pose import (
        bootstrap_ratio_ci,
        explore_runs,
        explore_selection,
    )

    att, _ = explore_selection(0.01, "pooled", 0.01)
    base = np.array([r["att_ransac"] for r in explore_runs(0.01)])
    return np.array(bootstrap_ratio_ci(att, base, seed=0))


register(f"{SLUG}.1", ArrayAnswer(
    "Derive the Fisher information J₁ = G₁ᵀG₁/σ² of ONE point for (δt, δθ) — perturbations "
    "t ← t + δt, R ← exp([δθ]ₓ) R (camera frame) — and evaluate it (6×6, units 1/m², 1/(m·rad), "
    f"1/rad²) for the target point X = {EX1['X']} m, R = attitude_matrix({EX1['angles_deg']}) "
    f"(deg, x-y-z), t = {EX1['t']} m, f = {EX1['f_mm']} mm, σ = {EX1['sigma_mm']} mm.",
    expected=_ex1_expected, rtol=1e-6, atol=1e-9,
    hint="∂u/∂x_c = (K[:2] − u e₃ᵀ)/z_c; ∂x_c/∂δt = I and ∂x_c/∂δθ = −[R X]ₓ (not −R[X]ₓ: "
         "that is a body-frame perturbation); J₁ has rank 2 (one point gives two numbers)."))

register(f"{SLUG}.2", NumericAnswer(
    "The paper's score adds translation variances (m²) to quaternion variances (no unit); make "
    "it dimensionless with weights scaled_crlb_weights(|t|) (translation terms divided by "
    "|t|²). For make_scene(np.random.default_rng(0), outlier_fraction=0.0) on the paper's "
    "Scenario(), true pose and true σ_i, compute score(first 6 points) / score(all points) of "
    "that dimensionless score on the 7 CRLB values (quaternion_crlb).",
    expected=_ex2_expected, rtol=1e-4,
    hint="np.sum(w * np.diag(quaternion_crlb(points, R, t, K, sigma))) with "
         "w = scaled_crlb_weights(np.linalg.norm(t)); the ratio is ≥ 1 because information "
         "only adds up."))

register(f"{SLUG}.3", FunctionAnswer(
    "Write points_needed(points, R, t, K, sigma, frac) → int: the fewest leading points (taken "
    "in the given order, at least 6) whose dimensionless CRLB score (exercise 2's: weights "
    "scaled_crlb_weights(|t|)) is within (1 + frac) of the score of all the points — a "
    "stopping rule that CAN drop points.",
    reference=points_needed, inputs=_ex3_inputs, rtol=0.0, atol=0.0,
    hint="information_monotonicity(..., weights=...) gives the score of every leading set "
         "S_6 ⊂ S_7 ⊂ … ⊂ S_n; it is non-increasing, so the first index under the target is "
         "the answer."))

register(f"{SLUG}.4", ArrayAnswer(
    "The Explore panel shows a few dozen cached runs (E.EXPLORE_RUNS). At the pixel reading (noise unit 0.01 mm) with "
    "the 'pooled' reading, compute the 95 % paired-bootstrap interval (lo, hi) of the mean "
    "attitude-error ratio CRLB selection / RANSAC only over those runs: att, _ = "
    "E.explore_selection(0.01, 'pooled', 0.01); base = the runs' 'att_ransac' from "
    "E.explore_runs(0.01); E.bootstrap_ratio_ci(att, base, seed=0). Then do the same at 1 mm "
    "and say whether that many runs can tell the two noise levels apart.",
    expected=_ex4_expected, rtol=0.03, atol=0.0,
    hint="the ratio is CRLB / RANSAC (not the inverse); the interval, not the point estimate."))

register(f"{SLUG}.5", Choice(
    "Transfer. Suppose each point's noise σ_i were known and the score were the exact CRLB "
    "with J = Σ G_iᵀG_i / σ_i² (points of very different σ_i). A point with a large σ_i is "
    "offered to the set. Which holds? (a) it raises the score, so the rule drops it; (b) it "
    "still lowers (or keeps) the score — its term is smaller but still positive semi-definite "
    "— so the rule keeps it; (c) whether it is kept depends on the order in which points are "
    "added; (d) the 6-point start test now passes, so points can be dropped.",
    options=["a", "b", "c", "d"], answer="b",
    hint="how big is G_iᵀG_i/σ_i² when σ_i is large, and what is its sign?"))

register(f"{SLUG}.6", Choice(
    "Critique. Suppose eq. (5) had given each point its own, known σ_i (so the σ_i are part of "
    "the paper's model, not an oracle). Which reading would the protocol's textual argument "
    "(the score must be able to rise, and use only what the model contains) then pick? "
    "(a) 'as printed' (exact CRLB with those σ_i); (b) 'sandwich' — the covariance of the "
    "unweighted pose with the known σ_i, which can rise when a noisy point joins; (c) 'pooled' "
    "— one σ² estimated from the residuals; (d) 'tolerance'.",
    options=["a", "b", "c", "d"], answer="b",
    hint="with known σ_i the exact CRLB is still monotone (exercise 5); which score can rise, "
         "and does it then need anything the model lacks?"))
