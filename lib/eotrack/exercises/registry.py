"""The registry of exercises: ids ``"<slug>.<n>"``, checkers registered by each paper's module."""

from __future__ import annotations

import importlib
import pkgutil
from typing import Any

from eotrack.exercises.checkers import Checker, CheckResult

__all__ = ["check", "exercise_ids", "get_checker", "register"]

_REGISTRY: dict[str, Checker] = {}


def register(exercise_id: str, checker: Checker) -> Checker:
    """Register ``checker`` under ``exercise_id`` (``"<slug>.<n>"``); return it.

    Raises
    ------
    ValueError
        If the id is malformed or already taken.
    TypeError
        If ``checker`` is not a :class:`Checker`.
    """
    if not isinstance(exercise_id, str) or exercise_id.count(".") != 1 \
            or not all(exercise_id.split(".")):
        raise ValueError(f"exercise id must look like 'slug.n', got {exercise_id!r}")
    if not isinstance(checker, Checker):
        raise TypeError(f"checker must be an eotrack.exercises Checker, got "
                        f"{type(checker).__name__}")
    if exercise_id in _REGISTRY:
        raise ValueError(f"exercise {exercise_id!r} is already registered")
    checker.exercise = exercise_id
    _REGISTRY[exercise_id] = checker
    return checker


def _paper_modules() -> list[str]:
    import eotrack.exercises as pkg

    skip = {"checkers", "registry"}
    return [m.name for m in pkgutil.iter_modules(pkg.__path__)
            if not m.name.startswith("_") and m.name not in skip]


def _load(slug: str) -> None:
    if slug in _paper_modules():
        importlib.import_module(f"eotrack.exercises.{slug}")


def exercise_ids(slug: str | None = None) -> list[str]:
    """All registered exercise ids (of one paper if ``slug`` is given), loading the modules."""
    for s in ([slug] if slug else _paper_modules()):
        _load(s)
    return sorted(k for k in _REGISTRY if slug is None or k.split(".")[0] == slug)


def get_checker(exercise_id: str) -> Checker:
    """The checker of ``exercise_id``.

    Raises
    ------
    ValueError
        If no such exercise exists (the message lists the known ids of that paper).
    """
    if not isinstance(exercise_id, str):
        raise TypeError(f"exercise id must be a string like 'wransac.3', got "
                        f"{type(exercise_id).__name__}")
    slug = exercise_id.split(".")[0]
    _load(slug)
    if exercise_id not in _REGISTRY:
        known = sorted(k for k in _REGISTRY if k.split(".")[0] == slug)
        papers = sorted(set(_paper_modules()) | {k.split(".")[0] for k in _REGISTRY})
        raise ValueError(f"unknown exercise {exercise_id!r}; "
                         + (f"known for {slug!r}: {known}" if known else
                            f"papers with exercises: {papers}"))
    return _REGISTRY[exercise_id]


def check(exercise_id: str, answer: Any) -> CheckResult:
    """Check ``answer`` to exercise ``exercise_id``; show right/wrong with a hint, return it.

    The verdict is shown at once (a Markdown line in a notebook, printed elsewhere), so it
    appears even when ``check`` is called inside an ``if`` block.

    The result is truthy when the answer is right and never contains the solution. A wrong
    type or shape of answer raises ``TypeError``/``ValueError`` saying what was expected.
    """
    checker = get_checker(exercise_id)
    result = checker(answer)
    result.show()
    object.__setattr__(result, "_shown", True)  # a notebook does not show it twice
    return result
