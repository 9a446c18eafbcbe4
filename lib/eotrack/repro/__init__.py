"""Reproduction machinery: claims, scorecards, reports and the ``python -m eotrack.repro`` CLI.

An experiment module ``eotrack.experiments.<slug>`` exposes ``SLUG``, ``TITLE`` and
``reproduce(*, quick=False, runner=None, seed=None) -> Reproduction``; this package finds it, runs it and
writes ``papers_repro/<slug>/REPORT.md``, ``scorecard.json`` and ``figures/*.png``.
"""

from __future__ import annotations

from .claims import KINDS, Claim, CriterionChange, load_claims, papers_repro_dir
from .collection import (
    central_verdict,
    collection_notebooks,
    collection_scorecard,
    notebook_for_slug,
)
from .evaluators import (
    Evaluator,
    check_evaluator,
    evaluate,
    evaluator,
    registered_evaluators,
)
from .registry import available_slugs, experiment_module
from .report import Reproduction, central_line, write_report
from .scorecard import (
    ClaimResult,
    Status,
    allowed_statuses,
    check_claims_complete,
    scorecard,
    status_summary,
)
from .stability import Stability, read_stability, write_stability

__all__ = [
    "KINDS",
    "Claim",
    "ClaimResult",
    "CriterionChange",
    "Evaluator",
    "Reproduction",
    "Stability",
    "Status",
    "allowed_statuses",
    "available_slugs",
    "central_line",
    "central_verdict",
    "check_claims_complete",
    "check_evaluator",
    "collection_notebooks",
    "collection_scorecard",
    "evaluate",
    "evaluator",
    "experiment_module",
    "load_claims",
    "notebook_for_slug",
    "papers_repro_dir",
    "read_stability",
    "registered_evaluators",
    "scorecard",
    "status_summary",
    "write_report",
    "write_stability",
]
