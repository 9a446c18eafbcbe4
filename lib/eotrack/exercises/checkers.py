"""Answer checkers: numbers with a tolerance, arrays, functions on hidden inputs, choices.

The expected value is given as a zero-argument callable computed with the library on first
use (so importing a paper's exercises is cheap and no result is typed in), or as a constant
where the answer is a definition (a choice, a formula's exponent).
"""

from __future__ import annotations

import copy
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["ArrayAnswer", "CheckResult", "Checker", "Choice", "FunctionAnswer",
           "NumericAnswer"]


@dataclass(frozen=True)
class CheckResult:
    """The verdict on one answer; truthy when right. Its text never contains the solution.

    In a notebook it shows as one Markdown line (✅ right / ❌ not yet, with the hint);
    :func:`eotrack.exercises.check` shows it as soon as it is computed, so the check also
    shows inside an ``if`` block, and the returned value is not shown a second time.
    """

    exercise: str
    correct: bool
    message: str

    def __bool__(self) -> bool:
        return self.correct

    def __str__(self) -> str:
        mark = "✓ right" if self.correct else "✗ not yet"
        return f"{self.exercise}: {mark} — {self.message}"

    def _repr_markdown_(self) -> str:
        mark = "✅ **right**" if self.correct else "❌ **not yet**"
        return f"{self.exercise}: {mark} — {self.message}"

    def show(self) -> None:
        """Display the verdict (Markdown in a Jupyter kernel, a plain line elsewhere)."""
        try:
            from IPython import get_ipython

            shell = get_ipython()
        except ImportError:  # pragma: no cover - IPython is a dependency of the notebooks
            shell = None
        if shell is not None and getattr(shell, "kernel", None) is not None:
            from IPython.display import Markdown, display

            display(Markdown(self._repr_markdown_()))
        else:
            print(self)

    def _ipython_display_(self) -> None:
        if self.__dict__.pop("_shown", False):  # check() has just shown it: skip once
            return
        self.show()


def _resolve(expected: Any) -> Any:
    return expected() if callable(expected) else expected


class _Lazy:
    """Compute the expected value once, on first use."""

    def __init__(self, expected: Any) -> None:
        self._src = expected
        self._done = False
        self._value: Any = None

    def get(self) -> Any:
        if not self._done:
            self._value = _resolve(self._src)
            self._done = True
        return self._value


@dataclass
class Checker:
    """Base class: ``question`` says what is asked, ``hint`` is shown when the answer is wrong."""

    question: str
    hint: str = "check your derivation against the notebook's section on this step"
    expects: str = "an answer"
    exercise: str = field(default="", init=False)

    def validate(self, answer: Any) -> Any:  # pragma: no cover - overridden
        return answer

    def judge(self, answer: Any) -> bool:  # pragma: no cover - overridden
        raise NotImplementedError

    def __call__(self, answer: Any) -> CheckResult:
        value = self.validate(answer)
        ok = bool(self.judge(value))
        msg = "well done." if ok else f"hint: {self.hint}"
        return CheckResult(self.exercise, ok, msg)


def _check_tolerances(rtol: Any, atol: Any) -> None:
    for name, v in (("rtol", rtol), ("atol", atol)):
        if isinstance(v, bool) or not isinstance(v, int | float) or not v >= 0 \
                or not np.isfinite(v):
            raise ValueError(f"{name} must be a finite number >= 0, got {v!r}")


def _as_float(answer: Any, what: str) -> float:
    if isinstance(answer, bool) or not isinstance(answer, int | float | np.integer | np.floating):
        if isinstance(answer, np.ndarray) and answer.shape == ():
            answer = answer.item()
        else:
            raise TypeError(f"expected {what}: a single real number, got "
                            f"{type(answer).__name__}")
    x = float(answer)
    if not np.isfinite(x):
        raise ValueError(f"expected {what}: a finite number, got {x!r}")
    return x


@dataclass
class NumericAnswer(Checker):
    """A single number, right within ``rtol``/``atol`` of the expected value."""

    expected: Any = None
    rtol: float = 1e-3
    atol: float = 0.0
    expects: str = "a number"

    def __post_init__(self) -> None:
        if self.expected is None:
            raise ValueError("NumericAnswer needs expected (a number or a callable)")
        _check_tolerances(self.rtol, self.atol)
        self._lazy = _Lazy(self.expected)

    def validate(self, answer: Any) -> float:
        return _as_float(answer, self.expects)

    def judge(self, answer: float) -> bool:
        exp = float(self._lazy.get())
        return bool(np.isclose(answer, exp, rtol=self.rtol, atol=self.atol))


@dataclass
class ArrayAnswer(Checker):
    """An array of a given shape, right element-wise within ``rtol``/``atol``."""

    expected: Any = None
    rtol: float = 1e-3
    atol: float = 0.0
    expects: str = "an array"

    def __post_init__(self) -> None:
        if self.expected is None:
            raise ValueError("ArrayAnswer needs expected (an array or a callable)")
        _check_tolerances(self.rtol, self.atol)
        self._lazy = _Lazy(self.expected)

    def validate(self, answer: Any) -> np.ndarray:
        exp = np.asarray(self._lazy.get(), dtype=float)
        try:
            a = np.asarray(answer, dtype=float)
        except (TypeError, ValueError):
            raise TypeError(f"expected {self.expects}: numbers of shape {exp.shape}, got "
                            f"{type(answer).__name__}") from None
        if a.shape != exp.shape:
            raise ValueError(f"expected {self.expects} of shape {exp.shape}, got shape "
                             f"{a.shape}")
        if not np.all(np.isfinite(a)):
            raise ValueError(f"expected {self.expects}: finite numbers only (found NaN/inf)")
        return a

    def judge(self, answer: np.ndarray) -> bool:
        exp = np.asarray(self._lazy.get(), dtype=float)
        return bool(np.allclose(answer, exp, rtol=self.rtol, atol=self.atol))


@dataclass
class FunctionAnswer(Checker):
    """A function, run on hidden inputs and compared with the reference implementation.

    ``inputs`` is a callable returning a list of argument tuples; ``reference`` computes the
    right output for each.
    """

    reference: Callable[..., Any] | None = None
    inputs: Callable[[], Sequence[tuple]] | None = None
    rtol: float = 1e-6
    atol: float = 1e-9
    expects: str = "a function"

    def __post_init__(self) -> None:
        if self.reference is None or self.inputs is None:
            raise ValueError("FunctionAnswer needs reference and inputs")
        if not callable(self.reference) or not callable(self.inputs):
            raise TypeError("FunctionAnswer: reference and inputs must be callables")
        _check_tolerances(self.rtol, self.atol)
        self._why = ""

    def validate(self, answer: Any) -> Callable[..., Any]:
        if not callable(answer):
            raise TypeError(f"expected {self.expects} (a callable), got {type(answer).__name__}")
        return answer

    def judge(self, answer: Callable[..., Any]) -> bool:
        """Run ``answer`` on every hidden input (on copies, so it cannot alter them)."""
        self._why = ""
        for k, args in enumerate(self.inputs(), start=1):
            want = np.asarray(self.reference(*copy.deepcopy(args)), dtype=float)
            try:
                out = answer(*copy.deepcopy(args))
            except Exception as exc:  # the student's function failed on a hidden input: wrong
                self._why = (f"your function raised {type(exc).__name__} on hidden input {k}"
                             f"{': ' + str(exc)[:120] if str(exc) else ''}")
                return False
            try:
                got = np.asarray(out, dtype=float)
            except (TypeError, ValueError):
                self._why = (f"your function returned {type(out).__name__} on hidden input {k}, "
                             "not numbers")
                return False
            if got.shape != want.shape:
                self._why = (f"your function returned shape {got.shape} on hidden input {k}; "
                             f"expected shape {want.shape}")
                return False
            if not np.allclose(got, want, rtol=self.rtol, atol=self.atol, equal_nan=True):
                self._why = f"your function's output differs on hidden input {k}"
                return False
        return True

    def __call__(self, answer: Any) -> CheckResult:
        result = super().__call__(answer)
        if result.correct or not self._why:
            return result
        return CheckResult(result.exercise, False, f"{self._why}; {result.message}")


@dataclass
class Choice(Checker):
    """One option among ``options`` (compared case-insensitively for strings)."""

    options: Sequence[Any] = ()
    answer: Any = None
    expects: str = "one of the options"

    def __post_init__(self) -> None:
        if not self.options or self.answer not in self.options:
            raise ValueError("Choice needs options and an answer among them")

    def validate(self, answer: Any) -> Any:
        norm = [str(o).strip().lower() for o in self.options]
        key = str(answer).strip().lower()
        if key not in norm:
            # an option written as it is labelled in the question: "(d)", "d)", "[d]", "d."
            bare = re.sub(r"^[(\[]\s*(.*?)\s*[)\]]$", r"\1", key)
            bare = re.sub(r"^(.*?)\s*[).:]$", r"\1", bare).strip()
            # … or the whole option line copied: "(d) for no observer", "d) for no observer"
            line = re.match(r"^[(\[]?\s*([^\s()\[\]]+?)\s*[)\]:.]\s+\S", key)
            if bare not in norm and line and line.group(1) in norm:
                bare = line.group(1)
            if bare not in norm:
                raise ValueError(f"expected one of {list(self.options)}, got {answer!r}")
            key = bare
        return self.options[norm.index(key)]

    def judge(self, answer: Any) -> bool:
        return answer == self.answer
