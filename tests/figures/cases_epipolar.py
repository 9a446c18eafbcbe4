"""Lint cases of notebook 02's figures that no REPORT figure draws (P02 owns this file).

All are drawn on the built scenario (deterministic) and small seeded runs, as the notebook
draws them.
"""

from __future__ import annotations

from typing import Any


def _scen() -> Any:
    from eotrack.experiments import epipolar as E

    return E.build_scenario()


def distance_check() -> Any:
    import numpy as np
    from eotrack.experiments import epipolar as E
    from eotrack.montecarlo import TrialRunner

    scen = _scen()
    mc = E.run_scenario_draws(scen, n_draws=20, runner=TrialRunner(progress=False))
    sig, _ = E.error_budget_gate(scen)
    return E.plot_distance_check(np.concatenate([o["true_d"] for o in mc.trials]), sig)


def epipolar_geometry() -> Any:
    from eotrack.experiments import epipolar as E

    return E.plot_epipolar_geometry(_scen(), pair=(0, 3), target=4)


def frame_chain() -> Any:
    from eotrack.experiments import epipolar as E

    return E.plot_frame_chain(_scen(), 0)


def gate_study() -> Any:
    import matplotlib.pyplot as plt
    from eotrack.experiments import epipolar as E
    from eotrack.montecarlo import TrialRunner

    scen = _scen()
    run = TrialRunner(progress=False)
    from eotrack.plotting import legend_outside

    fig, axs = plt.subplots(1, 2, figsize=(7.2, 3.8), sharey=True, layout="constrained")
    E.plot_gate_study(E.gate_study(scen, (0.5, 1.0), n_draws=10, runner=run), ax=axs[0],
                      legend=False)
    E.plot_gate_study(E.gate_study(scen, (0.5, 1.0), gaussian=True, n_draws=10, runner=run),
                      ax=axs[1], legend=False)
    legend_outside(fig, where="below", ncol=3)
    return fig


def threshold_tradeoff() -> Any:
    from eotrack.experiments import epipolar as E

    return E.plot_threshold_tradeoff(E.threshold_study(1.0, 3, n_draws=20), 10.0)


def triangulation() -> Any:
    from eotrack.experiments import epipolar as E

    scen = _scen()
    return E.plot_triangulation(scen, E.displayed_draw(scen).obs, pair=(0, 3), target=4)


CASES = {
    "plot_distance_check": distance_check,
    "plot_epipolar_geometry": epipolar_geometry,
    "plot_frame_chain": frame_chain,
    "plot_gate_study": gate_study,
    "plot_threshold_tradeoff": threshold_tradeoff,
    "plot_triangulation": triangulation,
}
