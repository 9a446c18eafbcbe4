"""Exercises of notebook 02 (Huang, Zhang & Feng, epipolar association across star sensors).

Expected values are computed with the library on first use; nothing is typed in.

1. derivation — the smallest number of estimates for which a 3σ rule can reject one;
2. computation — eq. (8) as a function (run on hidden inputs);
3. exploration — the threshold of smallest total error in the notebook's widget;
4. critique — the paper's "10 mrad" jitter in pixels of its own sensor;
5. computation — the error-budget gate with the paper's 1′ read as an rms error.
"""

from __future__ import annotations

import numpy as np

from eotrack.exercises import FunctionAnswer, NumericAnswer, register
from eotrack.geometry import epipolar_distances, max_z_score

__all__: list[str] = []


def _ex1_expected() -> int:
    n = 2
    while max_z_score(n) <= 3.0:
        n += 1
    return n


def _ex2_inputs() -> list[tuple]:
    rng = np.random.default_rng(1234)
    out = []
    for n1, n2, scale in ((5, 4, 1.0), (1, 7, 1e-3), (12, 12, 250.0), (3, 1, -4.0)):
        F = rng.normal(size=(3, 3)) * scale
        out.append((F, rng.uniform(0, 512, (n1, 2)), rng.uniform(0, 512, (n2, 2))))
    return out


def _ex3_expected() -> float:
    from eotrack.experiments.epipolar import threshold_study

    th, r = threshold_study().curves()
    return float(th[int(np.argmin(r["total"]))])


def _ex4_expected() -> float:
    from eotrack.experiments.epipolar import SensorConfig

    return float(10e-3 * SensorConfig().K[0, 0])


def _ex5_expected() -> float:
    from eotrack.experiments.epipolar import ErrorConfig, build_scenario, error_budget_gate

    return float(error_budget_gate(build_scenario(), ErrorConfig(attitude_arcmin=3**0.5))[1])


register("epipolar.1", NumericAnswer(
    "The smallest number n of estimates for which the paper's 3σ rule can reject one.",
    expected=_ex1_expected, rtol=0.0, atol=1e-9,
    hint="the extreme case is one sample against n − 1 equal ones; solve (n − 1)/√n > 3"))

register("epipolar.2", FunctionAnswer(
    "dist(F, p1, p2): the (n1, n2) matrix of point-to-epipolar-line distances of eq. (8).",
    reference=epipolar_distances, inputs=_ex2_inputs, rtol=1e-6, atol=1e-6,
    hint="lines = [p1 | 1] Fᵀ; divide each line by sqrt(a² + b²); then |a u + b v + c| for "
         "every point of image 2 — and check the shape is (n1, n2), not (n2, n1)"))

register("epipolar.3", NumericAnswer(
    "Threshold L (px) of smallest total error in the Explore panel, paper's error model.",
    expected=_ex3_expected, rtol=0.0, atol=0.5,
    hint="set attitude ±1′ and 3 false targets, move L and watch the solid curve (or the "
         "total in the title)"))

register("epipolar.4", NumericAnswer(
    "The paper's 10 mrad jitter expressed in pixels of the experiment's 2°, 512-px sensor.",
    expected=_ex4_expected, rtol=0.02,
    hint="an angle θ (rad) near the axis moves the image by f/dx · θ pixels; f/dx comes from "
         "eq. (7)"))

register("epipolar.5", NumericAnswer(
    "The 99 % error-budget gate (px) with the paper's 1′ read as an rms attitude error.",
    expected=_ex5_expected, rtol=0.02,
    hint="uniform noise of bound b has rms b/√3, so pass attitude_arcmin = √3 to ErrorConfig; "
         "the gate is the second value error_budget_gate returns"))
