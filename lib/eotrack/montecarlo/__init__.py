"""Seeded Monte Carlo trials: serial, local processes, or a Dask cluster — identical results."""

from __future__ import annotations

from .agreement import Agreement, binomial_interval, mc_agreement
from .runner import TrialRunner, run_trials, trial_generators

__all__ = ["Agreement", "TrialRunner", "binomial_interval", "mc_agreement", "run_trials",
           "trial_generators"]
