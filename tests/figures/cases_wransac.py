"""Lint cases of notebook 01's figures that no REPORT figure draws (P01 owns this file).

The Explore panel's figure, drawn on a small seeded U sweep as the notebook draws it.
"""

from __future__ import annotations

from typing import Any


def budget() -> Any:
    import matplotlib.pyplot as plt
    from eotrack.experiments import wransac as W
    from eotrack.montecarlo import TrialRunner

    err = W.budget_sweep(budgets=W.BUDGETS, methods=W.BUDGET_METHODS, n_runs=8,
                         runner=TrialRunner(progress=False))
    fig, ax = plt.subplots(figsize=(8, 4.5))
    fig.subplots_adjust(left=0.11, right=0.95, bottom=0.2, top=0.93)
    return W.plot_budget(err, W.BUDGETS, W.BUDGET_METHODS, 3,
                         ("ransac", "msac", "wransac_hypothesis", "lsq", "ideal"), ax=ax)


CASES = {"plot_budget": budget}
