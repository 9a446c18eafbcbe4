"""Exercises of notebook 02 (Huang, Zhang & Feng, epipolar association across star sensors).

Expected values are computed with the library on first use; nothing is typed in.

1. derivation — the smallest number of estimates for which a 2.5σ rule can reject one
   (the notebook states the 3σ case; Samuelson's inequality);
2. computation — eq. (8) as a function with numpy only (run on hidden inputs; a function that
   calls eotrack or OpenCV is rejected);
3. exploration — the threshold of smallest total error in the notebook's widget with 6 false
   targets per map;
4. critique — the paper's "10 mrad" jitter in pixels of the reference ST-APS2-2 sensor;
5. computation — the 90 % error-budget gate with the paper's 1′ read as an rms error and a
   100 µrad jitter (a setting no table of the notebook prints).
"""

from __future__ import annotations

import dis
import inspect
import types
from dataclasses import dataclass
from typing import Any

import numpy as np

from eotrack.exercises import FunctionAnswer, NumericAnswer, register
from eotrack.geometry import epipolar_distances, max_z_score

__all__ = ["NumpyOnlyFunctionAnswer", "uses_forbidden"]


#: the z-score rule of exercise 1 (the paper's is 3σ, discussed in the notebook)
EX1_K = 2.5
#: widget setting of exercise 3: attitude bound (′) and false targets per map (a setting no
#: table of the notebook prints)
EX3_ATTITUDE, EX3_N_FALSE = 1.0, 6
#: the Explore slider's grid (px) on which exercise 3's answer is read
EX3_GRID = np.arange(0.5, 30.0 + 1e-9, 0.5)
#: exercise 5: probability of the gate, jitter (µrad); the attitude 1′ is read as rms
EX5_P, EX5_JITTER_URAD = 0.90, 100.0

_FORBIDDEN = ("eotrack", "cv2")
#: names that import or evaluate code at run time (an import inside the function body)
_DYNAMIC = ("__import__", "import_module", "eval", "exec", "compile")


def _code_objects(code: types.CodeType):
    yield code
    for c in code.co_consts:
        if isinstance(c, types.CodeType):
            yield from _code_objects(c)


def _forbidden_in_code(code: types.CodeType) -> str | None:
    """An ``import eotrack…`` / ``import cv2`` statement or a dynamic import in ``code`` (or
    in the functions defined inside it), else None."""
    for co in _code_objects(code):
        for ins in dis.get_instructions(co):
            if ins.opname == "IMPORT_NAME" and str(ins.argval).split(".")[0] in _FORBIDDEN:
                return f"import {ins.argval}"
        dyn = set(co.co_names) & set(_DYNAMIC)
        if dyn:
            return sorted(dyn)[0]
    return None


def _forbidden_name(obj: Any) -> str | None:
    """The eotrack / OpenCV object ``obj`` is or refers to (functions, modules), else None."""
    mod = obj.__name__ if isinstance(obj, types.ModuleType) else \
        getattr(obj, "__module__", None) or ""
    if isinstance(mod, str) and mod.split(".")[0] in _FORBIDDEN and mod != "__main__":
        return getattr(obj, "__qualname__", getattr(obj, "__name__", repr(obj)))
    return None


def uses_forbidden(fn: Any) -> str | None:
    """Name of an eotrack / OpenCV object that ``fn`` is, wraps or references, else None."""
    seen = set()
    todo = [fn]
    while todo:
        f = todo.pop()
        if id(f) in seen:
            continue
        seen.add(id(f))
        name = _forbidden_name(f)
        if name:
            return name
        inner = getattr(f, "func", None)  # functools.partial
        if inner is not None:
            todo.append(inner)
        if isinstance(f, types.FunctionType):
            name = _forbidden_in_code(f.__code__)
            if name:
                return name
            try:
                cv = inspect.getclosurevars(f)
            except (TypeError, ValueError):  # pragma: no cover - exotic callables
                continue
            for v in [*cv.globals.values(), *cv.nonlocals.values()]:
                if isinstance(v, types.FunctionType | types.ModuleType) or callable(v):
                    todo.append(v)
    return None


@dataclass
class NumpyOnlyFunctionAnswer(FunctionAnswer):
    """A :class:`FunctionAnswer` that also rejects a function using eotrack or OpenCV."""

    def judge(self, answer: Any) -> bool:
        name = uses_forbidden(answer)
        if name:
            self._why = (f"your function uses {name} from eotrack/OpenCV; the exercise asks "
                         "for numpy only")
            return False
        return super().judge(answer)


def _ex1_expected() -> int:
    n = 2
    while max_z_score(n) <= EX1_K:
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

    r = threshold_study(EX3_ATTITUDE, EX3_N_FALSE).rates(EX3_GRID)
    return float(EX3_GRID[int(np.argmin(r["total"]))])


def _ex4_expected() -> float:
    from eotrack.experiments.epipolar import ST_APS2_2

    return float(10e-3 * ST_APS2_2.K[0, 0])


def _ex5_expected() -> float:
    from eotrack.experiments.epipolar import ErrorConfig, build_scenario, error_budget_gate

    return float(error_budget_gate(build_scenario(), ErrorConfig(
        attitude_arcmin=3**0.5, jitter_urad=EX5_JITTER_URAD), p=EX5_P)[1])


register("epipolar.1", NumericAnswer(
    "The smallest number n of estimates for which a 2.5σ rule (sample standard deviation) "
    "can reject one.",
    expected=_ex1_expected, rtol=0.0, atol=1e-9,
    hint="the extreme case is one sample against n − 1 equal ones; with s from n − 1 in the "
         "denominator its z-score is (n − 1)/√n — solve (n − 1)/√n > 2.5 (√(n − 1) is the "
         "population-s version)"))

register("epipolar.2", NumpyOnlyFunctionAnswer(
    "dist(F, p1, p2): the (n1, n2) matrix of point-to-epipolar-line distances of eq. (8), "
    "numpy only.",
    reference=epipolar_distances, inputs=_ex2_inputs, rtol=1e-6, atol=1e-6,
    hint="lines = [p1 | 1] Fᵀ; divide each line by sqrt(a² + b²); then |a u + b v + c| for "
         "every point of image 2 — and check the shape is (n1, n2), not (n2, n1)"))

register("epipolar.3", NumericAnswer(
    "Threshold L (px) of smallest total error in the Explore panel at the paper's ±1′ attitude "
    "error with 6 false targets per map.",
    expected=_ex3_expected, rtol=0.0, atol=0.25,
    hint="set attitude ±1′ (paper) and 6 false targets, move L and watch the solid curve (or "
         "the total in the title)"))

register("epipolar.4", NumericAnswer(
    "The paper's 10 mrad jitter expressed in pixels of the reference ST-APS2-2 sensor "
    "(20°, 1024 px, Table 2).",
    expected=_ex4_expected, rtol=0.02,
    hint="an angle θ (rad) near the axis moves the image by f/dx · θ pixels; f/dx comes from "
         "eq. (7) with the reference sensor's field of view and resolution"))

register("epipolar.5", NumericAnswer(
    "The 90 % error-budget gate (px) with the paper's 1′ read as an rms attitude error and a "
    "100 µrad centroid jitter.",
    expected=_ex5_expected, rtol=0.02,
    hint="uniform noise of bound b has rms b/√3: which bound has an rms of 1′? The gate is "
         "σ·√χ²₁(p) — one degree of freedom (a distance to a line is one coordinate) — and "
         "the probability asked is not the library's default"))
