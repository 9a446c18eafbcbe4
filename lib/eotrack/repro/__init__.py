"""Reproduction machinery: claims, scorecards, reports and the ``python -m eotrack.repro`` CLI.

An experiment module ``eotrack.experiments.<slug>`` exposes ``SLUG``, ``TITLE`` and
``reproduce(*, quick=False, runner=None) -> Reproduction``; this package finds it, runs it and
writes ``papers_repro/<slug>/REPORT.md``, ``scorecard.json`` and ``figures/*.png``.
"""

from __future__ import annotations

from .claims import Claim, load_claims, papers_repro_dir
from .collection import collection_notebooks, collection_scorecard, notebook_for_slug
from .registry import available_slugs, experiment_module
from .report import Reproduction, write_report
from .scorecard import ClaimResult, Status, check_claims_complete, scorecard

__all__ = [
    "Claim",
    "ClaimResult",
    "Reproduction",
    "Status",
    "available_slugs",
    "check_claims_complete",
    "collection_notebooks",
    "collection_scorecard",
    "experiment_module",
    "load_claims",
    "notebook_for_slug",
    "papers_repro_dir",
    "scorecard",
    "write_report",
]
