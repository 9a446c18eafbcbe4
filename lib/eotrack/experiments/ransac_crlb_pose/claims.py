"""Claims of the RANSAC + CRLB paper: the pre-registered protocol and the status decisions."""

from __future__ import annotations

import tomllib
from typing import Any

import numpy as np
import pandas as pd

from eotrack.repro import ClaimResult, Status, papers_repro_dir

from .scenario import READINGS, SLUG, Scenario, Settings
from .trials import readings_table, wilcoxon_less

__all__ = ["best_subset_gain", "bootstrap_ratio_ci", "evaluate", "load_protocol"]


def load_protocol() -> dict[str, Any]:
    """The ``[protocol]`` table of ``papers_repro/ransac_crlb_pose/claims.toml``.

    It names the primary reading of the §2.4 rule (fixed before the run, with its reasons in
    the file's comments), the exploratory readings, α and the multiple-comparison correction.
    """
    path = papers_repro_dir() / SLUG / "claims.toml"
    with path.open("rb") as fh:
        proto = dict(tomllib.load(fh).get("protocol", {}))
    for key in ("primary_reading", "exploratory_readings", "alpha"):
        if key not in proto:
            raise ValueError(f"{path}: [protocol] lacks {key!r}")
    for r in [proto["primary_reading"], *proto["exploratory_readings"]]:
        if r not in READINGS:
            raise ValueError(f"{path}: unknown reading {r!r}; known: {list(READINGS)}")
    return proto


def best_subset_gain(scenario: Scenario | None = None) -> float:
    """RMS ratio (best subset / all inliers) of an unweighted solver, equal geometry assumed.

    Unweighted least squares on N points with variances σ_i² has variance ∝ mean(σ²)/N; keeping
    only the lowest-variance class (a fraction 1/len(classes)) gives ∝ σ²_min/(N/len).
    """
    v = np.asarray((scenario or Scenario()).inlier_variances, float)
    return float(np.sqrt(len(v) * v.min() / v.mean()))


def bootstrap_ratio_ci(a: Any, b: Any, *, n_boot: int = 2000, seed: int = 0
                       ) -> tuple[float, float]:
    """95 % paired-bootstrap interval of ``mean(a) / mean(b)``."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    if a.shape != b.shape or a.ndim != 1 or len(a) < 2:
        raise ValueError("a and b must be 1-D of equal length ≥ 2")
    boot = np.random.default_rng(seed).integers(0, len(a), (n_boot, len(a)))
    lo, hi = np.percentile(a[boot].mean(1) / b[boot].mean(1), [2.5, 97.5])
    return float(lo), float(hi)


def _compare_claim(claim, ok: pd.DataFrame, q: str, reading: str, alpha: float,
                   table: pd.DataFrame) -> ClaimResult:
    a, b = ok[f"{q}_{reading}"].to_numpy(), ok[f"{q}_ransac"].to_numpy()
    p = wilcoxon_less(a, b)
    unit = "m" if q == "pos" else "deg"
    lo, hi = bootstrap_ratio_ci(a, b)
    ours = (f"{len(ok)} runs, primary reading '{reading}': mean {a.mean():.3g} vs "
            f"{b.mean():.3g} {unit} (ratio {a.mean() / b.mean():.3f}, 95 % CI {lo:.2f}–{hi:.2f}), "
            f"median {np.median(a):.3g} vs {np.median(b):.3g}; CRLB better in "
            f"{100 * np.mean(a < b):.0f} % of runs; one-sided Wilcoxon p = {p:.2g}")
    expl = table.xs(q, level="metric")
    expl = expl[expl["role"] == "exploratory"]
    ex = "; ".join(f"{r}: ratio {row['mean ratio']:.3f}, Holm p = {row['p (Holm)']:.2g}"
                   for r, row in expl.iterrows())
    ex_note = (f" Exploratory (Holm over {int(expl['family size'].max())} comparisons, cannot "
               f"change the status): {ex}.") if len(expl) else ""
    if a.mean() < b.mean() and p < alpha:
        status, note = Status.REPRODUCED, (
            f"The rule as printed (exact CRLB) selects every inlier (Fisher information is "
            f"additive); the pre-registered '{reading}' reading lowers the mean error and the "
            f"paired test is significant.")
    elif a.mean() < b.mean() or p < alpha:
        status, note = Status.PARTIAL, (
            f"Only one of 'lower mean' and 'p < {alpha}' holds for the pre-registered "
            f"'{reading}' reading (mean ratio {a.mean() / b.mean():.3f}, p = {p:.2g}); the paper "
            f"says 'clearly improved' but gives no numbers. An unweighted solver could gain at "
            f"most ≈{100 * (1 - best_subset_gain()):.0f} % RMS by keeping only low-noise points, "
            f"and the planar pose ambiguity adds run-to-run scatter at the printed noise level.")
    else:
        status, note = Status.NOT_REPRODUCED, (
            f"With the pre-registered '{reading}' reading the CRLB-selected mean "
            f"{a.mean():.3g} {unit} is not below RANSAC's {b.mean():.3g} {unit} and p = {p:.2g} "
            f"≥ {alpha}: the paper's improvement is not seen.")
    return ClaimResult.from_claim(claim, ours=ours, status=status, note=note + ex_note)


def evaluate(claims: dict, df: pd.DataFrame, df_counts: pd.DataFrame,
             protocol: dict | None = None) -> list[ClaimResult]:
    """One ClaimResult per claim id, decided by the pre-registered primary reading."""
    proto = protocol or load_protocol()
    reading, alpha = proto["primary_reading"], float(proto["alpha"])
    ok = df[df["success"]]
    table = readings_table(df, primary=reading)
    rows = [_compare_claim(claims["ransac_crlb_pose.fig4"], ok, "pos", reading, alpha, table),
            _compare_claim(claims["ransac_crlb_pose.fig5"], ok, "att", reading, alpha, table)]
    c6 = claims["ransac_crlb_pose.fig6"]
    okc = df_counts[df_counts["success"]]
    frac = (okc[f"n_{reading}"] / okc["n_inliers"]).to_numpy()
    n_fb = int(okc[f"fallback_{reading}"].sum())
    lo, hi = c6.paper["fraction_range"]
    in_range = lo <= frac.mean() <= hi
    ours = (f"{len(okc)} runs, primary reading '{reading}': selected / inliers = "
            f"{frac.mean():.3f} (min {frac.min():.2f}, max {frac.max():.2f}); ≥ 95 % of the "
            f"inliers kept in {int(np.sum(frac >= 0.95))} run(s); fell back to all inliers in "
            f"{n_fb} run(s); as printed (exact CRLB): "
            f"{(okc['n_as printed'] / okc['n_inliers']).mean():.2f}")
    if in_range and n_fb > 0:
        status, note = Status.REPRODUCED, ""
    elif in_range:
        status, note = Status.PARTIAL, (
            f"The fraction {frac.mean():.2f} is about two thirds, but no run fell back to all "
            f"inliers (the paper saw some): with the per-point start test a 6-point start that "
            f"beats the all-inlier score is found within {Settings().crlb_max_draws} draws "
            "every time. The rule as printed falls back in every run.")
    else:
        status, note = Status.NOT_REPRODUCED, (
            f"Selected fraction {frac.mean():.3f} outside [{lo}, {hi}] (paper: about "
            f"{c6.paper['selected_fraction']:.2f}); {n_fb} fall-back run(s). The rule as "
            "printed keeps every inlier (fraction 1.00) and falls back in every run.")
    rows.append(ClaimResult.from_claim(c6, ours=ours, status=status, note=note))
    return rows
