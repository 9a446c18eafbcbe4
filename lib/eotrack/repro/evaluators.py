"""Claim evaluators: each claim's status is a pure function of a small measurement.

An experiment's ``claims.py`` registers one evaluator per claim, with synthetic measurements
that reach every status the claim's criterion allows::

    @evaluator("wransac.table1", cases=[
        ({"ratio_ci": (0.5, 0.9)}, Status.REPRODUCED),
        ({"ratio_ci": (0.8, 1.3)}, Status.NOT_REPRODUCED),
        ({"ratio_ci": (1.9, 2.7)}, Status.CONTRADICTED),
    ])
    def table1_status(m) -> Status: ...

``reproduce()`` calls the registered function on the measured values, so the status the report
shows and the status the cases test come from one piece of code. :func:`check_evaluator`
verifies the cases against the claim (every allowed status reached — a status function with a
floor fails — and each case giving its expected status); the unit tests run it on every claim of
every paper.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from .claims import Claim
from .scorecard import Status, allowed_statuses

__all__ = ["Evaluator", "check_evaluator", "evaluate", "evaluator", "registered_evaluators"]


@dataclass(frozen=True)
class Evaluator:
    """A claim's status function and the synthetic cases it is tested on."""

    claim_id: str
    fn: Callable[[Any], Status | str]
    cases: tuple[tuple[Any, Status], ...]

    def __call__(self, measurement: Any) -> Status:
        return Status(self.fn(measurement))


_REGISTRY: dict[str, Evaluator] = {}


def evaluator(claim_id: str, *, cases: Iterable[tuple[Any, Status | str]]
              ) -> Callable[[Callable[[Any], Status | str]], Callable[[Any], Status]]:
    """Register ``fn`` as the status function of ``claim_id``, with its synthetic ``cases``.

    Parameters
    ----------
    claim_id
        e.g. ``"wransac.table1"``.
    cases
        ``(measurement, expected status)`` pairs; together they must reach every status the
        claim allows (see :func:`check_evaluator`).

    Returns
    -------
    callable
        A decorator; the decorated function is returned wrapped so that it returns a
        :class:`Status`.
    """
    if not isinstance(claim_id, str) or "." not in claim_id:
        raise ValueError(f"claim_id must be '<slug>.<name>', got {claim_id!r}")
    cs = tuple((m, Status(s)) for m, s in cases)
    if not cs:
        raise ValueError(f"evaluator {claim_id!r}: give at least one case per reachable status")

    def deco(fn: Callable[[Any], Status | str]) -> Callable[[Any], Status]:
        if not callable(fn):
            raise TypeError(f"evaluator {claim_id!r}: expected a function, got {type(fn).__name__}")
        ev = Evaluator(claim_id, fn, cs)
        _REGISTRY[claim_id] = ev  # re-import (notebook reload) replaces the entry
        return ev

    return deco


def registered_evaluators(slug: str | None = None) -> Mapping[str, Evaluator]:
    """The registered evaluators (of one paper's slug, or all), by claim id."""
    if slug is None:
        return dict(_REGISTRY)
    return {k: v for k, v in _REGISTRY.items() if k.split(".", 1)[0] == slug}


def evaluate(claim_id: str, measurement: Any) -> Status:
    """Status of ``claim_id`` for ``measurement`` by its registered evaluator."""
    try:
        ev = _REGISTRY[claim_id]
    except KeyError:
        raise ValueError(f"no evaluator registered for claim {claim_id!r}; known: "
                         f"{sorted(_REGISTRY)}") from None
    return ev(measurement)


def check_evaluator(claim: Claim, ev: Evaluator | None = None) -> list[str]:
    """Problems with ``claim``'s evaluator (empty list: none).

    Checks that an evaluator is registered, that its cases reach every status the criterion
    allows (``reproduced`` and ``not reproduced``; ``partial`` when the claim has a
    ``partial_band``; ``contradicted`` when it is ``directional``), that no case expects a status
    the criterion forbids, and that each case gives its expected status.
    ``not reproducible`` is allowed for results but need not be reached.
    """
    ev = ev if ev is not None else _REGISTRY.get(claim.id)
    if ev is None:
        return [f"{claim.id}: no evaluator registered (use @eotrack.repro.evaluator)"]
    problems = []
    allowed = set(allowed_statuses(claim))
    required = allowed - {Status.NOT_REPRODUCIBLE}
    reached = {s for _, s in ev.cases}
    if missing := required - reached:
        problems.append(f"{claim.id}: no case reaches {sorted(map(str, missing))}")
    if bad := reached - allowed:
        problems.append(f"{claim.id}: cases expect {sorted(map(str, bad))}, which the claim "
                        "does not allow (partial needs partial_band, contradicted needs "
                        "directional, a check only passes or fails)")
    for k, (m, want) in enumerate(ev.cases):
        try:
            got = ev(m)
        except Exception as exc:
            problems.append(f"{claim.id}: case {k} raised {type(exc).__name__}: {exc}")
            continue
        if got is not want:
            problems.append(f"{claim.id}: case {k} gives {got}, expected {want}")
    return problems
