"""The exercise-checker core: every checker kind right and wrong, bad answers, unknown ids, and
the rule that a verdict never reveals the expected value."""

from __future__ import annotations

import math

import numpy as np
import pytest
from eotrack.exercises import (
    ArrayAnswer,
    CheckResult,
    Choice,
    FunctionAnswer,
    NumericAnswer,
    check,
    exercise_ids,
    get_checker,
    register,
)
from eotrack.exercises import registry as _registry
from hypothesis import given, settings
from hypothesis import strategies as st

SLUG = "coretest"


@pytest.fixture(autouse=True)
def clean_registry(monkeypatch):
    """Each test registers into a private copy of the registry (the papers' ids stay intact)."""
    monkeypatch.setattr(_registry, "_REGISTRY", dict(_registry._REGISTRY))


def _square(x):
    return np.asarray(x, dtype=float) ** 2


def _register_all():
    register(f"{SLUG}.1", NumericAnswer("U for P=0.99, eps=0.5, m=4?",
                                        expected=lambda: math.log(0.01) / math.log(1 - 0.5**4),
                                        rtol=1e-2, hint="use eq. (2) without rounding"))
    register(f"{SLUG}.2", ArrayAnswer("the unit vector along (3, 4)",
                                      expected=lambda: np.array([3.0, 4.0]) / 5.0, rtol=1e-6))
    register(f"{SLUG}.3", FunctionAnswer("square each element", reference=_square,
                                         inputs=lambda: [(np.arange(4.0),), (np.eye(2),)]))
    register(f"{SLUG}.4", Choice("which loss is bounded?", options=["a", "b", "c"], answer="b"))


# ---- right / wrong for each kind ------------------------------------------------------------

def test_numeric_right_and_wrong(capsys):
    _register_all()
    right = math.log(0.01) / math.log(1 - 0.5**4)
    assert check(f"{SLUG}.1", right * (1 + 5e-3))
    assert check(f"{SLUG}.1", np.float32(right))
    assert check(f"{SLUG}.1", np.array(right))  # 0-d array
    res = check(f"{SLUG}.1", right * 1.1)
    assert not res and isinstance(res, CheckResult)
    assert "use eq. (2) without rounding" in res.message
    out = capsys.readouterr().out  # check() shows its verdict outside a notebook too
    assert "✓ right" in out and "✗ not yet" in out


def test_array_right_and_wrong():
    _register_all()
    assert check(f"{SLUG}.2", [0.6, 0.8])
    assert check(f"{SLUG}.2", np.array([0.6, 0.8]))
    assert not check(f"{SLUG}.2", [0.8, 0.6])


def test_function_right_and_wrong():
    _register_all()
    assert check(f"{SLUG}.3", lambda x: np.asarray(x) ** 2)
    res = check(f"{SLUG}.3", lambda x: np.asarray(x) * 2)
    assert not res
    assert "differs on hidden input" in res.message and "hint" in res.message


def test_function_that_raises_is_wrong_not_an_error():
    _register_all()

    def broken(x):
        raise ZeroDivisionError("oops")

    res = check(f"{SLUG}.3", broken)
    assert not res
    assert "ZeroDivisionError" in res.message


def test_function_with_wrong_shape_or_type_is_wrong():
    _register_all()
    res = check(f"{SLUG}.3", lambda x: np.ravel(x) ** 2)
    assert not res and "shape" in res.message
    res = check(f"{SLUG}.3", lambda x: "squared")
    assert not res and "not numbers" in res.message


def test_function_cannot_alter_hidden_inputs():
    _register_all()

    def vandal(x):
        x[...] = 0.0
        return x

    assert not check(f"{SLUG}.3", vandal)
    assert check(f"{SLUG}.3", _square)  # the hidden inputs are intact afterwards


def test_choice_right_wrong_and_case():
    _register_all()
    assert check(f"{SLUG}.4", "b")
    assert check(f"{SLUG}.4", " B ")
    assert not check(f"{SLUG}.4", "a")


# ---- bad answers: clear TypeError / ValueError naming what was expected ---------------------

@pytest.mark.parametrize("answer", ["3.2", None, [1.0], (2.0,), True, {"u": 3}])
def test_numeric_bad_type(answer):
    _register_all()
    with pytest.raises(TypeError, match="expected a number"):
        check(f"{SLUG}.1", answer)


@pytest.mark.parametrize("answer", [float("nan"), float("inf")])
def test_numeric_not_finite(answer):
    _register_all()
    with pytest.raises(ValueError, match="finite"):
        check(f"{SLUG}.1", answer)


def test_array_bad_shape_names_the_expected_shape():
    _register_all()
    with pytest.raises(ValueError, match=r"shape \(2,\), got shape \(3,\)"):
        check(f"{SLUG}.2", [0.6, 0.8, 0.0])


@pytest.mark.parametrize("answer", [["a", "b"], [[1.0, 2.0], [3.0]], None, {"x": 1}])
def test_array_bad_type(answer):
    _register_all()
    with pytest.raises((TypeError, ValueError), match="expected an array"):
        check(f"{SLUG}.2", answer)


def test_array_nan_rejected():
    _register_all()
    with pytest.raises(ValueError, match="finite"):
        check(f"{SLUG}.2", [np.nan, 0.8])


def test_function_not_callable():
    _register_all()
    with pytest.raises(TypeError, match="expected a function"):
        check(f"{SLUG}.3", [0.0, 1.0])


def test_choice_not_an_option_lists_the_options():
    _register_all()
    with pytest.raises(ValueError, match=r"\['a', 'b', 'c'\]"):
        check(f"{SLUG}.4", "d")


def test_bad_answer_raises_our_message_not_numpy_internals():
    _register_all()
    with pytest.raises(TypeError) as info:
        check(f"{SLUG}.2", object())
    assert "numpy" not in str(info.value).lower()


# ---- ids and registration ---------------------------------------------------------------------

def test_unknown_exercise_of_a_known_paper_lists_its_ids():
    _register_all()
    with pytest.raises(ValueError, match=r"unknown exercise 'coretest.9'.*coretest.1"):
        check(f"{SLUG}.9", 1.0)


def test_unknown_paper_lists_the_papers():
    _register_all()
    with pytest.raises(ValueError, match=r"unknown exercise 'nosuchpaper.1'; papers with "
                                         r"exercises: .*coretest"):
        get_checker("nosuchpaper.1")


@pytest.mark.parametrize("bad", [3, None, ("coretest", 1)])
def test_exercise_id_must_be_a_string(bad):
    with pytest.raises(TypeError, match="exercise id must be a string"):
        check(bad, 1.0)


@pytest.mark.parametrize("bad", ["coretest", "coretest.", ".1", "a.b.c", 7])
def test_register_rejects_malformed_ids(bad):
    with pytest.raises(ValueError, match=r"slug\.n"):
        register(bad, Choice("q", options=["a"], answer="a"))


def test_register_rejects_duplicates_and_non_checkers():
    _register_all()
    with pytest.raises(ValueError, match="already registered"):
        register(f"{SLUG}.1", Choice("q", options=["a"], answer="a"))
    with pytest.raises(TypeError, match="Checker"):
        register(f"{SLUG}.8", lambda a: True)


def test_exercise_ids_of_one_slug():
    _register_all()
    assert exercise_ids(SLUG) == [f"{SLUG}.{k}" for k in range(1, 5)]


@pytest.mark.parametrize("make", [
    lambda: NumericAnswer("q"),
    lambda: ArrayAnswer("q"),
    lambda: FunctionAnswer("q", reference=_square),
    lambda: Choice("q", options=["a", "b"], answer="z"),
    lambda: Choice("q"),
    lambda: NumericAnswer("q", expected=1.0, rtol=-1e-3),
    lambda: ArrayAnswer("q", expected=[1.0], atol=float("nan")),
])
def test_checker_construction_errors(make):
    with pytest.raises(ValueError):
        make()


def test_function_answer_needs_callables():
    with pytest.raises(TypeError, match="callables"):
        FunctionAnswer("q", reference=_square, inputs=[(1.0,)])


def test_expected_is_computed_lazily_and_once():
    calls = []

    def expensive():
        calls.append(1)
        return 2.0

    register(f"{SLUG}.7", NumericAnswer("q", expected=expensive))
    assert calls == []  # registering computes nothing
    assert check(f"{SLUG}.7", 2.0)
    assert not check(f"{SLUG}.7", 3.0)
    assert calls == [1]


# ---- the verdict never reveals the solution -------------------------------------------------

def _texts(res: CheckResult) -> str:
    return f"{res}\n{res._repr_markdown_()}\n{res.message}\n{res!r}"


def _forms(x: float) -> list[str]:
    return [repr(x), str(x), f"{x:.6g}", f"{x:.4g}", f"{x:.3f}", f"{x:.2e}"]


_finite = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False).filter(
    lambda v: abs(v) > 1e-3)


@settings(max_examples=60, deadline=None)
@given(expected=_finite, answer=_finite)
def test_numeric_verdict_never_contains_the_expected_value(expected, answer):
    _registry._REGISTRY.pop(f"{SLUG}.p", None)
    register(f"{SLUG}.p", NumericAnswer("q", expected=lambda: expected, rtol=1e-3,
                                        hint="look at the notebook's eq. (2)"))
    res = get_checker(f"{SLUG}.p")(answer)
    text = _texts(res)
    for form in _forms(expected):
        if form not in _forms(answer) and form not in "look at the notebook's eq. (2)":
            assert form not in text


@settings(max_examples=40, deadline=None)
@given(expected=st.lists(_finite, min_size=1, max_size=4),
       answer=st.lists(_finite, min_size=1, max_size=4))
def test_array_verdict_never_contains_the_expected_values(expected, answer):
    _registry._REGISTRY.pop(f"{SLUG}.q", None)
    register(f"{SLUG}.q", ArrayAnswer("q", expected=lambda: np.array(expected), rtol=1e-3))
    checker = get_checker(f"{SLUG}.q")
    try:
        res = checker(answer)
    except ValueError as exc:  # a shape mismatch names the shape, never the values
        text = str(exc)
    else:
        text = _texts(res)
    for v in expected:
        for form in _forms(v):
            if all(form not in _forms(a) for a in answer) and len(form) > 3:
                assert form not in text


def test_result_in_a_notebook_is_markdown_and_not_shown_twice(monkeypatch):
    shown = []
    res = CheckResult("x.1", True, "well done.")
    monkeypatch.setattr(CheckResult, "show", lambda self: shown.append(str(self)))
    object.__setattr__(res, "_shown", True)  # as check() leaves it
    res._ipython_display_()                   # the cell's automatic display is skipped once
    assert shown == []
    res._ipython_display_()                   # an explicit later display shows it
    assert shown == ["x.1: ✓ right — well done."]
    assert res._repr_markdown_().startswith("x.1: ✅ **right**")
