"""``python -m eotrack.repro [SLUG ...] [--quick] [--out DIR] [--workers N | --scheduler ADDR]``."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from . import available_slugs, experiment_module, papers_repro_dir, write_report
from .claims import load_claims
from .scorecard import check_claims_complete


def main(argv: list[str] | None = None) -> int:
    """Run the reproductions and write their reports; return a process exit code."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
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
    args = parser.parse_args(argv)

    slugs = args.slugs or available_slugs()
    for s in slugs:
        experiment_module(s)  # fail early on an unknown slug
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
        check_claims_complete(load_claims(slug), rep.claims)
        report = write_report(rep, out_root / slug)
        plt.close("all")
        dt = time.perf_counter() - t0
        print(rep.scorecard[["claim", "status", "ours"]].to_string(index=False))
        print(f"--> {rep.status_summary()}  [{dt:.1f} s]  {report}", flush=True)
        if not rep.claims:
            failed.append(slug)
    if args.out is None:  # the project's own reports: refresh the README's status table
        from .readme import update_readme

        if update_readme(out_root.parent):
            print("README.md notebook table updated from the scorecards")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
