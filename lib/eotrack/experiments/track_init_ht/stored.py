"""track_init_ht: the committed run's image sequences, stored for notebook 03.

``make repro`` (:func:`~eotrack.experiments.track_init_ht.reproduce`, committed run only:
``seed=None``, full counts) writes :data:`STORED_FILE` into ``papers_repro/track_init_ht/``:
the per-run measurements of :func:`~.sequences.run_sequence` for every sequence of the
experiment (Figs. 4–7) and of the Fig. 7 SNR sweep, with the settings, the counts, the seed and
a hash of the code that computed them. The notebook reads it (:func:`sequence_study`) instead of
simulating the 120 sequences again (≈ 50 s); the pooling (:func:`~.sequences.pool_runs`,
:func:`~.sequences.sweep_table`) and every criterion are applied by the current code at read
time. Without the file, with another code hash or other settings, it runs them live and says so.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import asdict
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from eotrack.montecarlo import TrialRunner

from .scenario import SWEEP_SNR, SequenceSettings
from .sequences import pool_runs, sequence_experiment, snr_sweep, sweep_table

__all__ = ["STORED_FILE", "code_hash", "read_stored", "sequence_study", "write_stored"]

#: File name under ``papers_repro/track_init_ht/``.
STORED_FILE = "sequence_study.json"
_FORMAT = 1
#: The files whose code computes a run (simulation, CFAR, clustering, temporal test, the
#: measurements, the seeding). Input validation (eotrack.validation) and the pooling at read
#: time are left out: they do not change a stored run.
_CODE = ("experiments/track_init_ht/scenario.py", "experiments/track_init_ht/sequences.py",
         "imaging/dim_targets.py", "imaging/psf.py", "imaging/cfar.py", "imaging/neighbourhood.py",
         "tracking/initiation/base.py", "tracking/initiation/temporal.py",
         "tracking/hypothesis.py", "montecarlo/runner.py")


def code_hash() -> str:
    """SHA-256 (16 hex digits) of the files that compute a sequence run (:data:`_CODE`)."""
    lib = Path(__file__).resolve().parents[2]
    h = hashlib.sha256()
    for rel in _CODE:
        h.update(rel.encode())
        h.update((lib / rel).read_bytes())
    return h.hexdigest()[:16]


def _enc(v: Any) -> Any:
    if isinstance(v, np.ndarray):
        return {"dtype": str(v.dtype), "shape": list(v.shape), "v": v.ravel().tolist()}
    if isinstance(v, (np.integer,)):
        return int(v)
    if isinstance(v, (np.floating,)):
        return float(v)
    if isinstance(v, list):
        return [_enc(x) for x in v]
    return v


def _dec(v: Any) -> Any:
    if isinstance(v, dict) and set(v) == {"dtype", "shape", "v"}:
        return np.asarray(v["v"], dtype=v["dtype"]).reshape(v["shape"])
    return v


def _settings(st: SequenceSettings) -> dict[str, Any]:
    return json.loads(json.dumps(asdict(st)))


def _seed_key(seed: int | np.random.SeedSequence) -> Any:
    if isinstance(seed, np.random.SeedSequence):
        return {"entropy": int(seed.entropy), "spawn_key": [int(k) for k in seed.spawn_key]}
    return int(seed)


def write_stored(path: str | Path, st: SequenceSettings, runs_by_snr: dict[float, list[dict]],
                 *, n_runs: int, seed: int | np.random.SeedSequence) -> None:
    """Write the runs (``{SNR: runs of run_sequence(keep=False)}``; the paper's SNR holds the
    experiment's runs) to ``path`` with the settings, counts, seed and :func:`code_hash`.

    Raises
    ------
    ValueError
        The paper's SNR is missing or a list does not hold ``n_runs`` runs.
    """
    if isinstance(n_runs, bool) or not isinstance(n_runs, (int, np.integer)) or n_runs < 1:
        raise ValueError(f"n_runs must be a positive int, got {n_runs!r}")
    if float(st.curved_snr) not in {float(k) for k in runs_by_snr}:
        raise ValueError(f"runs_by_snr must hold the experiment's SNR {st.curved_snr:g}")
    bad = {k: len(v) for k, v in runs_by_snr.items() if len(v) != n_runs}
    if bad:
        raise ValueError(f"every SNR needs n_runs = {n_runs} runs, got {bad}")
    content = {"format": _FORMAT, "code_hash": code_hash(), "settings": _settings(st),
               "n_runs": int(n_runs), "seed": _seed_key(seed),
               "written_by": "python -m eotrack.repro track_init_ht (make repro)",
               "snrs": [float(k) for k in runs_by_snr],
               "runs": [[{k: _enc(v) for k, v in r.items()} for r in runs]
                        for runs in runs_by_snr.values()]}
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(json.dumps(content, separators=(",", ":")) + "\n")


def read_stored(path: str | Path, st: SequenceSettings, *, n_runs: int,
                seed: int | np.random.SeedSequence, snrs: list[float]
                ) -> dict[float, list[dict[str, Any]]]:
    """The stored runs ``{SNR: runs}`` when ``path`` was written by this code for exactly these
    settings, counts, seed and SNRs.

    Raises
    ------
    FileNotFoundError
        ``path`` does not exist (``python -m eotrack.repro track_init_ht`` writes it).
    ValueError
        The file was written by other code (hash) or for other settings; the message says which.
    """
    p = Path(path)
    if not p.is_file():
        raise FileNotFoundError(f"{p} does not exist: `python -m eotrack.repro track_init_ht` "
                                "(make repro) writes it")
    try:
        d = json.loads(p.read_text())
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise ValueError(f"{p} is not a stored study (not valid JSON: {exc}): run `python -m "
                         "eotrack.repro track_init_ht`") from None
    if not isinstance(d, dict) or not isinstance(d.get("runs"), list):
        raise ValueError(f"{p} is not a stored study (no table with 'runs'): run `python -m "
                         "eotrack.repro track_init_ht`")
    want = {"format": _FORMAT, "code_hash": code_hash(), "settings": _settings(st),
            "n_runs": int(n_runs), "seed": _seed_key(seed), "snrs": [float(s) for s in snrs]}
    diff = [k for k, v in want.items() if d.get(k) != v]
    if diff:
        raise ValueError(f"{p} does not match this code and run ({', '.join(diff)} differ): "
                         "run `python -m eotrack.repro track_init_ht`")
    return {float(s): [{k: _dec(v) for k, v in r.items()} for r in runs]
            for s, runs in zip(d["snrs"], d["runs"])}


def sequence_study(st: SequenceSettings, n_runs: int, sweep_runs: int, *,
                   seed: int | np.random.SeedSequence = 3, path: str | Path | None = None,
                   runner: TrialRunner | None = None
                   ) -> tuple[dict[str, Any], pd.DataFrame, str]:
    """The sequence experiment and the Fig. 7 sweep: ``(ex, sweep, source)``.

    From the stored run (``path``, default ``papers_repro/track_init_ht/`` +
    :data:`STORED_FILE`) when it matches (``sweep_runs == n_runs``, same settings, seed, SNRs
    and code), else live (:func:`~.sequences.sequence_experiment`, :func:`~.sequences.snr_sweep`).
    ``source`` says which, and why a stored file was not used.
    """
    snrs = [float(st.curved_snr) + d for d in SWEEP_SNR]
    reason = f"the sweep has {sweep_runs} runs, the experiment {n_runs} (QUICK counts)"
    if sweep_runs == n_runs:
        if path is None:
            from eotrack.repro import papers_repro_dir

            from .scenario import SLUG
            path = papers_repro_dir() / SLUG / STORED_FILE
        try:
            by_snr = read_stored(path, st, n_runs=n_runs, seed=seed, snrs=snrs)
        except (FileNotFoundError, ValueError) as exc:
            reason = str(exc)
        else:
            ex = pool_runs(by_snr[float(st.curved_snr)], st)
            return ex, sweep_table(by_snr, st), (
                f"stored run: {Path(path).name} (written by make repro, code hash "
                f"{code_hash()}; {n_runs} sequences x {len(snrs)} SNRs)")
    ex = sequence_experiment(st, n_runs, seed=seed, runner=runner)
    sweep = snr_sweep(st, snrs, sweep_runs, seed=seed, runner=runner,
                      paper_runs=ex["runs"] if sweep_runs == n_runs else None)
    return ex, sweep, f"live run ({reason})"
