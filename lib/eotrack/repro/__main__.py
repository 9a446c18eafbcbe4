"""``python -m eotrack.repro [SLUG ...] [--quick] [--seeds K] [--out DIR] [--workers N | --scheduler ADDR]``.

``--seeds K`` also re-runs each paper on the independent root seeds 1 … K (at the same counts)
and writes ``stability.json`` beside the report: the share of seeds giving the committed status
per claim (``make repro-stability``).
"""

from __future__ import annotations

import argparse
import inspect
import sys
import time
from pathlib import Path

from . import available_slugs, experiment_module, papers_repro_dir, write_report
from .claims import load_claims
from .scorecard import check_claims_complete
from .stability import write_stability


def _seeded(mod, slug: str):
    if "seed" not in inspect.signature(mod.reproduce).parameters:
        raise SystemExit(f"--seeds: eotrack.experiments.{slug}.reproduce() takes no `seed`; "
                         "every experiment must accept reproduce(..., seed=int) for stability")
    return mod.reproduce


def main(argv: list[str] | None = None) -> int:
    """Run the reproductions and write their reports; return a process exit code."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from eotrack.plotting import use_house_style

    use_house_style()  # the REPORT figures in the notebooks' house style
    import pandas as pd

    from eotrack.montecarlo import TrialRunner

    parser = argparse.ArgumentParser(prog="python -m eotrack.repro", description=__doc__)
    parser.add_argument("slugs", nargs="*", help=f"papers to reproduce (default: all of "
                        f"{', '.join(available_slugs())})")
    parser.add_argument("--quick", action="store_true", help="reduced trial counts (for tests)")
    parser.add_argument("--out", type=Path, default=None,
                        help="output root (default: papers_repro/); reports go to OUT/<slug>/")
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--workers", type=int, default=None, help="local worker processes")
    group.add_argument("--scheduler", default=None, help="Dask scheduler address (tcp://host:port)")
    parser.add_argument("--no-progress", action="store_true", help="hide progress bars")
    parser.add_argument("--seeds", type=int, default=0, metavar="K",
                        help="also run on root seeds 1..K and write stability.json (default 0)")
    args = parser.parse_args(argv)
    if args.seeds < 0:
        parser.error(f"--seeds must be >= 0, got {args.seeds}")

    slugs = args.slugs or available_slugs()
    for s in slugs:
        m = experiment_module(s)  # fail early on an unknown slug
        if args.seeds:
            _seeded(m, s)
    out_root = args.out if args.out is not None else papers_repro_dir()
    runner = TrialRunner(workers=args.workers, scheduler=args.scheduler,
                         progress=not args.no_progress)
    pd.set_option("display.width", 200)
    pd.set_option("display.max_colwidth", 60)
    failed = []
    for slug in slugs:
        mod = experiment_module(slug)
        t0 = time.perf_counter()
        print(f"\n=== {slug}: {mod.TITLE}", flush=True)
        rep = mod.reproduce(quick=args.quick, runner=runner)
        claims = load_claims(slug)
        check_claims_complete(claims, rep.claims)
        if args.seeds:
            seeds = list(range(1, args.seeds + 1))
            per: dict[str, list[str]] = {c: [] for c in claims}
            for sd in seeds:
                t1 = time.perf_counter()
                keep = set(plt.get_fignums())  # the committed run's figures, saved below
                r = mod.reproduce(quick=args.quick, runner=runner, seed=sd)
                check_claims_complete(claims, r.claims)
                for row in r.claims:
                    per[row.claim].append(str(row.status))
                for num in set(plt.get_fignums()) - keep:
                    plt.close(num)
                print(f"    seed {sd}: {r.status_summary()}  [{time.perf_counter() - t1:.1f} s]",
                      flush=True)
            (out_root / slug).mkdir(parents=True, exist_ok=True)
            write_stability(out_root / slug, seeds, per, quick=args.quick)
        report = write_report(rep, out_root / slug, claims=claims)
        plt.close("all")
        dt = time.perf_counter() - t0
        print(rep.scorecard[["claim", "kind", "status", "ours"]].to_string(index=False))
        print(f"--> {rep.status_summary()}  [{dt:.1f} s]  {report}", flush=True)
        print(f"    {rep.central_line()}", flush=True)
        if not rep.claims:
            failed.append(slug)
    if args.out is None:  # the project's own reports: refresh the README's status table
        from .readme import update_readme

        if update_readme(out_root.parent):
            print("README.md notebook table updated from the scorecards")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
