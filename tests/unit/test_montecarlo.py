"""The trial runner: identical results serially, on local processes and on a Dask cluster."""

import numpy as np
import pytest
from eotrack.montecarlo import TrialRunner, run_trials, trial_generators


def noisy_mean(rng: np.random.Generator, n: int, scale: float = 1.0) -> np.ndarray:
    """A trial: draws depend only on the trial's generator."""
    return scale * rng.standard_normal(n).cumsum()


def test_serial_equals_generators():
    out = run_trials(noisy_mean, 5, seed=3, args=(4,), runner=TrialRunner(progress=False))
    gens = trial_generators(3, 5)
    for o, g in zip(out, gens, strict=True):
        np.testing.assert_array_equal(o, g.standard_normal(4).cumsum())


def test_serial_processes_dask_identical():
    kwargs = {"scale": 2.0}
    serial = TrialRunner(progress=False).map(noisy_mean, 23, seed=11, args=(6,), kwargs=kwargs)
    procs = TrialRunner(workers=2, progress=False).map(noisy_mean, 23, seed=11, args=(6,),
                                                        kwargs=kwargs)
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                      host="127.0.0.1") as cluster, Client(cluster) as client:
        by_address = TrialRunner(scheduler=cluster.scheduler_address, progress=False).map(
            noisy_mean, 23, seed=11, args=(6,), kwargs=kwargs)
        by_client = TrialRunner(scheduler=client, progress=False).map(
            noisy_mean, 23, seed=11, args=(6,), kwargs=kwargs)
    for other in (procs, by_address, by_client):
        assert len(other) == 23
        for a, b in zip(serial, other, strict=True):
            np.testing.assert_array_equal(a, b)


def test_different_seeds_differ_and_order_kept():
    a = run_trials(noisy_mean, 3, seed=1, args=(3,), runner=TrialRunner(progress=False))
    b = run_trials(noisy_mean, 3, seed=2, args=(3,), runner=TrialRunner(progress=False))
    assert not np.array_equal(a[0], b[0])
    assert not np.array_equal(a[0], a[1])


def test_zero_trials_and_backend_names():
    assert TrialRunner(progress=False).map(noisy_mean, 0, seed=0, args=(2,)) == []
    assert TrialRunner().backend == "serial"
    assert TrialRunner(workers=1).backend == "serial"
    assert TrialRunner(workers=3).backend == "processes"
    assert TrialRunner(scheduler="tcp://127.0.0.1:1").backend == "dask"


@pytest.mark.parametrize(("kw", "exc", "match"), [
    ({"workers": -1}, ValueError, "workers must be >= 0"),
    ({"workers": 1.5}, TypeError, "workers must be an integer"),
    ({"scheduler": 42}, TypeError, "scheduler must be an address string"),
    ({"chunks_per_worker": 0}, ValueError, "chunks_per_worker must be >= 1"),
])
def test_bad_runner(kw, exc, match):
    with pytest.raises(exc, match=match):
        TrialRunner(**kw)


def test_bad_map_arguments():
    r = TrialRunner(progress=False)
    with pytest.raises(TypeError, match="fn must be callable"):
        r.map(3, 2, seed=0)
    with pytest.raises(ValueError, match="n_trials must be >= 0"):
        r.map(noisy_mean, -1, seed=0)
    with pytest.raises(ValueError, match="seed must be >= 0"):
        r.map(noisy_mean, 1, seed=-5)
    with pytest.raises(TypeError, match="runner must be a TrialRunner"):
        run_trials(noisy_mean, 1, seed=0, runner="serial")
