"""Seeded Monte Carlo trials: serial, local processes, or a Dask cluster — identical results."""

from __future__ import annotations

from .runner import TrialRunner, run_trials, trial_generators

__all__ = ["TrialRunner", "run_trials", "trial_generators"]
