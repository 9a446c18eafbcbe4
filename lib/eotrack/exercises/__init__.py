"""Exercise checkers: ``check("wransac.3", answer)`` says right or wrong, with a hint.

Each paper registers its exercises in its own module (``eotrack.exercises.<slug>``), imported
on first use, so a notebook only needs::

    from eotrack.exercises import check
    check("wransac.3", my_answer)

The checker never prints the expected answer. Worked solutions live in
``notebooks/solutions/``; ``tests/exercises/`` runs every checker against a right and a wrong
answer.

Why our own small registry and not otter-grader or nbgrader (checked November 2026):

* **otter-grader** 7.0 (``grader.check("q1")``, the same loop for students) keeps each
  question's tests as typed values in per-notebook test files, checks notebook globals rather
  than an answer passed in, and pulls in ``nbconvert[webpdf]``, ``python-on-whales`` (Docker),
  ``ipylab``, ``dill`` and ``fica`` — a Docker-based autograder we would not use and a typed
  expected value, which our rule "expected values are computed by the library" forbids.
* **nbgrader** 0.9 is a classroom server workflow (release, collect, grade, with a SQL
  database, ``alembic``, ``notebook<8`` and ``rapidfuzz``), not a self-check a student runs
  alone; it also needs the classic ``notebook`` package this project does not install.

Neither fits a pinned, offline, self-study collection, so the checkers are ~300 lines here:
numbers with a tolerance, arrays, functions run on hidden inputs, multiple choice, and a
message that gives a hint but never the solution. A teacher who does run nbgrader can still
call :func:`check` from an nbgrader test cell.
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
