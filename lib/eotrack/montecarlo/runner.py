"""The trial runner.

Trial ``i`` of a run with seed ``s`` always receives the generator
``numpy.random.default_rng(numpy.random.SeedSequence(s).spawn(n)[i])``, whichever backend runs
it, and the results come back in trial order. So a table computed serially, on local processes
or on a Dask cluster is the same to the last bit.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from typing import Any, TypeVar

import numpy as np

from eotrack.validation import check_int

__all__ = ["TrialRunner", "run_trials", "trial_generators"]

T = TypeVar("T")


def trial_generators(seed: int | np.random.SeedSequence, n_trials: int) -> list[np.random.Generator]:
    """Independent generators for ``n_trials`` trials, spawned from ``seed``.

    Parameters
    ----------
    seed
        Non-negative integer or a ``SeedSequence``.
    n_trials
        Number of trials (>= 0).
    """
    n = check_int(n_trials, "n_trials", min_value=0)
    return [np.random.default_rng(s) for s in _spawn(seed, n)]


def _spawn(seed: int | np.random.SeedSequence, n: int) -> list[np.random.SeedSequence]:
    if isinstance(seed, np.random.SeedSequence):
        ss = seed
    else:
        ss = np.random.SeedSequence(check_int(seed, "seed", min_value=0))
    return ss.spawn(n)


def _run_chunk(fn: Callable[..., Any], seeds: Sequence[np.random.SeedSequence],
               args: tuple, kwargs: dict) -> list[Any]:
    return [fn(np.random.default_rng(s), *args, **kwargs) for s in seeds]


@dataclass(frozen=True)
class TrialRunner:
    """Where and how trials run.

    Parameters
    ----------
    workers
        ``None`` or 1: serial in this process. ``n > 1``: ``n`` local processes.
        ``0``: one process per CPU.
    scheduler
        Address of a Dask distributed scheduler (``"tcp://host:8786"``) or a
        ``distributed.Client``; overrides ``workers``.
    progress
        Show a tqdm progress bar (notebook or terminal) while trials run.
    chunks_per_worker
        Trials are sent in this many chunks per worker (fewer round trips).
    """

    workers: int | None = None
    scheduler: Any = None
    progress: bool = True
    chunks_per_worker: int = 4

    def __post_init__(self) -> None:
        if self.workers is not None:
            check_int(self.workers, "workers", min_value=0)
        check_int(self.chunks_per_worker, "chunks_per_worker", min_value=1)
        if self.scheduler is not None and not isinstance(self.scheduler, str) \
                and not hasattr(self.scheduler, "submit"):
            raise TypeError("scheduler must be an address string or a distributed.Client, got "
                            f"{type(self.scheduler).__name__}")

    @property
    def backend(self) -> str:
        """``"serial"``, ``"processes"`` or ``"dask"``."""
        if self.scheduler is not None:
            return "dask"
        if self.workers is None or self.workers == 1:
            return "serial"
        return "processes"

    def map(self, fn: Callable[..., T], n_trials: int, *, seed: int | np.random.SeedSequence,
            args: tuple = (), kwargs: dict | None = None, desc: str | None = None) -> list[T]:
        """Run ``fn(rng, *args, **kwargs)`` for ``n_trials`` seeded trials.

        Parameters
        ----------
        fn
            Trial function; its first argument is the trial's ``numpy.random.Generator``. For
            processes and Dask it must be importable (a module-level function).
        n_trials
            Number of trials.
        seed
            Root seed of the run.
        args, kwargs
            Extra arguments passed to every trial.
        desc
            Progress-bar label.

        Returns
        -------
        list
            The trial results in trial order.
        """
        if not callable(fn):
            raise TypeError(f"fn must be callable, got {type(fn).__name__}")
        n = check_int(n_trials, "n_trials", min_value=0)
        kwargs = dict(kwargs or {})
        seeds = _spawn(seed, n)
        if n == 0:
            return []
        backend = self.backend
        if backend == "serial":
            return self._serial(fn, seeds, args, kwargs, desc)
        n_workers = self.workers or os.cpu_count() or 1
        if backend == "processes":
            return self._processes(fn, seeds, args, kwargs, desc, n_workers)
        return self._dask(fn, seeds, args, kwargs, desc)

    def _bar(self, total: int, desc: str | None):
        from tqdm.auto import tqdm

        return tqdm(total=total, desc=desc or "trials", disable=not self.progress, leave=False)

    def _chunks(self, seeds: list, n_workers: int) -> list[list]:
        n_chunks = min(len(seeds), n_workers * self.chunks_per_worker)
        return [list(c) for c in np.array_split(np.array(seeds, dtype=object), n_chunks)]

    def _serial(self, fn, seeds, args, kwargs, desc):
        out = []
        with self._bar(len(seeds), desc) as bar:
            for s in seeds:
                out.append(fn(np.random.default_rng(s), *args, **kwargs))
                bar.update()
        return out

    def _processes(self, fn, seeds, args, kwargs, desc, n_workers):
        chunks = self._chunks(seeds, n_workers)
        results: list[list] = [None] * len(chunks)  # type: ignore[list-item]
        with ProcessPoolExecutor(max_workers=n_workers) as pool, self._bar(len(seeds), desc) as bar:
            futs = {pool.submit(_run_chunk, fn, c, args, kwargs): i for i, c in enumerate(chunks)}
            from concurrent.futures import as_completed

            for f in as_completed(futs):
                i = futs[f]
                results[i] = f.result()
                bar.update(len(chunks[i]))
        return [r for chunk in results for r in chunk]

    def _dask(self, fn, seeds, args, kwargs, desc):
        try:
            from distributed import Client, as_completed
        except ImportError as exc:  # pragma: no cover - depends on the environment
            raise ImportError("a Dask scheduler needs the 'distributed' package "
                              "(pip install 'eotrack[parallel]')") from exc
        own = isinstance(self.scheduler, str)
        client = Client(self.scheduler) if own else self.scheduler
        try:
            n_workers = max(1, len(client.scheduler_info().get("workers", {})))
            chunks = self._chunks(seeds, n_workers)
            futs = [client.submit(_run_chunk, fn, c, args, kwargs, pure=False) for c in chunks]
            index = {f.key: i for i, f in enumerate(futs)}
            results: list[list] = [None] * len(chunks)  # type: ignore[list-item]
            with self._bar(len(seeds), desc) as bar:
                for f in as_completed(futs):
                    i = index[f.key]
                    results[i] = f.result()
                    bar.update(len(chunks[i]))
        finally:
            if own:
                client.close()
        return [r for chunk in results for r in chunk]


def run_trials(fn: Callable[..., T], n_trials: int, *, seed: int | np.random.SeedSequence,
               args: tuple = (), kwargs: dict | None = None, runner: TrialRunner | None = None,
               desc: str | None = None) -> list[T]:
    """Run seeded trials with ``runner`` (serial by default); see :meth:`TrialRunner.map`."""
    runner = runner if runner is not None else TrialRunner()
    if not isinstance(runner, TrialRunner):
        raise TypeError(f"runner must be a TrialRunner, got {type(runner).__name__}")
    return runner.map(fn, n_trials, seed=seed, args=args, kwargs=kwargs, desc=desc)
