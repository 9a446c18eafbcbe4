"""Exercise checkers: ``check("wransac.3", answer)`` says right or wrong, with a hint.

Each paper registers its exercises in its own module (``eotrack.exercises.<slug>``), imported
on first use, so a notebook only needs::

    from eotrack.exercises import check
    check("wransac.3", my_answer)

The checker never prints the expected answer. Worked solutions live in
``notebooks/solutions/``; ``tests/exercises/`` runs every checker against a right and a wrong
answer.
"""

from __future__ import annotations

from eotrack.exercises.checkers import (
    ArrayAnswer,
    Checker,
    CheckResult,
    Choice,
    FunctionAnswer,
    NumericAnswer,
)
from eotrack.exercises.registry import check, exercise_ids, get_checker, register

__all__ = [
    "ArrayAnswer",
    "CheckResult",
    "Checker",
    "Choice",
    "FunctionAnswer",
    "NumericAnswer",
    "check",
    "exercise_ids",
    "get_checker",
    "register",
]
