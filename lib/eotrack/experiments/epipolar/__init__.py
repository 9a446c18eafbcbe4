"""Huang, Zhang & Feng — synchronous association of space targets across distributed star
sensors by the epipolar constraint, and triangulation.

The package is split by role: :mod:`.scenario` (Tables 1–3, the error model, one draw),
:mod:`.trials` (association, Monte Carlo, Fig. 6, error budget, the widget's precomputed
study), :mod:`.figures` (schematics and the paper's figures), :mod:`.claims` (tables and
scoring). ``reproduce`` runs them in order with the paper's settings.
"""

from __future__ import annotations

import numpy as np

from eotrack.montecarlo import TrialRunner
from eotrack.repro import Reproduction
from eotrack.validation import check_int

from .claims import *  # noqa: F403
from .claims import __all__ as _claims_all
from .claims import paper_values, score
from .figures import *  # noqa: F403
from .figures import __all__ as _figures_all
from .figures import render_maps
from .scenario import *  # noqa: F403
from .scenario import SLUG as SLUG
from .scenario import TITLE as TITLE
from .scenario import ErrorConfig, build_scenario
from .scenario import __all__ as _scenario_all
from .trials import *  # noqa: F403
from .trials import __all__ as _trials_all
from .trials import displayed_draw, run_fig6, run_scenario_draws

__all__ = sorted({"reproduce", "run_seeds", "DEFAULT_SEEDS", "N_DRAWS", "N_SIMS", "THRESHOLDS", *_claims_all,
                  *_figures_all, *_scenario_all, *_trials_all})

#: Trial counts of ``make repro`` (full) and ``make repro-quick``: (scenario draws, Fig. 6 sims).
N_DRAWS = {False: 300, True: 100}
N_SIMS = {False: 600, True: 200}
#: Thresholds of the Fig. 5 sweep (px).
THRESHOLDS = np.arange(0.5, 20.01, 0.5)


#: Seeds of the committed default run (``seed=None``).
DEFAULT_SEEDS = {"displayed": 2019, "draws": 20190401, "fig6": 600, "render": 7, "bootstrap": 0}


def run_seeds(seed: int | None = None) -> dict[str, int]:
    """The seeds of every generator of a run: the committed defaults for ``seed=None``, else
    independent integers derived from ``np.random.SeedSequence(seed)``."""
    if seed is None:
        return dict(DEFAULT_SEEDS)
    s = check_int(seed, "seed", min_value=0)
    state = np.random.SeedSequence(s).generate_state(len(DEFAULT_SEEDS), dtype=np.uint32)
    return {k: int(v) for k, v in zip(DEFAULT_SEEDS, state)}


def reproduce(*, quick: bool = False, runner: TrialRunner | None = None,
              n_draws: int | None = None, n_sims: int | None = None,
              seed: int | None = None) -> Reproduction:
    """Run every experiment of the paper and score the ten claims.

    ``n_draws`` (scenario draws, default 300, quick 100) and ``n_sims`` (Fig. 6 simulations,
    default 600, quick 200) override the trial counts. ``seed=None`` is the committed run;
    an integer is an independent root seed from which every generator is derived
    (:func:`run_seeds`).
    """
    n_draws = check_int(n_draws, "n_draws", min_value=1) if n_draws is not None else \
        N_DRAWS[bool(quick)]
    n_sims = check_int(n_sims, "n_sims", min_value=1) if n_sims is not None else \
        N_SIMS[bool(quick)]
    seeds = run_seeds(seed)
    P = paper_values()
    L = float(P["epipolar.fig4"]["threshold_px"])
    errors = ErrorConfig()
    scen = build_scenario()
    draw = displayed_draw(scen, errors, L, seed=seeds["displayed"])
    images = render_maps(scen, draw.obs, np.random.default_rng(seeds["render"]))
    mc = run_scenario_draws(scen, errors, THRESHOLDS, L, n_draws, runner=runner,
                            seed=seeds["draws"])
    res6 = run_fig6(n_sims, P["epipolar.fig6"]["threshold_px"], int(P["epipolar.fig6"]["n_points"]),
                    runner=runner, seed=seeds["fig6"])
    return score(scen, draw, mc, res6, errors=errors, images=images,
                 settings={"quick": quick, "seed": seed}, boot_seed=seeds["bootstrap"])
