"""A campaign on a Dask cluster against the local worker pool (``make bench ONLY=dask``).

The same non-linear runs of the DOE chapter's model (its lean stand-in, as the chapter solves
them; no FE cache) are solved on a local pool of ``workers`` processes with one BLAS thread each
(:func:`mechlib.campaign.executors.executor`, as the notebooks do, after the model is
built in the calling process, as the chapter builds it), and on a Dask cluster that this
benchmark starts itself: a scheduler and ``workers`` single-threaded worker processes
(``distributed.LocalCluster``), started with the preload module that cluster workers are
started with (:mod:`mechlib.campaign.daskworker`). Each is timed from the first
submitted task to the last result; the cluster's start-up (scheduler, workers, their imports)
is timed apart. The poses must be bit-identical. Printed:
``Dask / local pool: N.NNx (…, N runs, N workers)``.
"""

from __future__ import annotations

import time

import numpy as np

#: runs timed on each executor (two rounds of eight on two workers)
N_RUNS = 16
#: single-threaded workers of both the local pool and the cluster
WORKERS = 2
#: campaigns timed on each, alternating
ROUNDS = 3


def _design(n: int) -> np.ndarray:
    """The first ``n`` runs of the DOE chapter's seeded validation draw (±1 N)."""
    return np.random.default_rng(2010).uniform(-1.0, 1.0, (n, 6))


def dask_vs_local(
    n_runs: int = N_RUNS, workers: int = WORKERS, rounds: int = ROUNDS
) -> dict[str, float]:
    """Time ``n_runs`` non-linear runs on the local pool and on a Dask cluster, ``rounds``
    times each, alternating (the median of each is compared: a shared machine's load drifts)."""
    from distributed import LocalCluster

    from mechlib.bench.nonlinear import _chapter_spec
    from mechlib.campaign import daskworker, executors
    from mechlib.campaign import experiments as ex
    from mechlib.hexflex.studies import leanmesh
    from mechlib.paths import fe_cache_dir

    spec, source = _chapter_spec()
    # the chapter's non-linear model: the lean stand-in (its fit reads the FE cache: no solve)
    nl_spec = leanmesh.lean_spec(spec, cache_dir=fe_cache_dir())[0]
    ex.model_for(nl_spec)  # built in this process first, as the chapter does
    design = _design(n_runs)

    def campaign(pool, sign: float) -> tuple[float, np.ndarray]:
        t0 = time.perf_counter()
        poses = ex.run_experiments(
            nl_spec, sign * design, kind="nonlinear", executor=pool, cache_dir=None,
            progress=False,
        )  # fmt: skip
        return time.perf_counter() - t0, poses

    t0 = time.perf_counter()
    cluster = LocalCluster(
        n_workers=workers,
        threads_per_worker=1,
        processes=True,
        dashboard_address=None,
        preload=[daskworker.__name__],
    )
    start_s = time.perf_counter() - t0
    local_s, dask_s, same = [], [], []
    try:
        with executors.dask_executor(cluster) as remote:
            first_s, _ = campaign(remote, -1.0)  # its workers build the model
            for _ in range(rounds):
                with executors.worker_pool(workers) as pool:  # a pool per campaign, as a notebook
                    t, here = campaign(pool, 1.0)
                local_s.append(t)
                t, there = campaign(remote, 1.0)
                dask_s.append(t)
                same.append(np.array_equal(here, there))
    finally:
        cluster.close()
    local, dask = float(np.median(local_s)), float(np.median(dask_s))
    return {
        "geometry": source,
        "runs": n_runs,
        "workers": workers,
        "rounds": rounds,
        "local_s": local,
        "dask_s": dask,
        "local_spread_s": [min(local_s), max(local_s)],
        "dask_spread_s": [min(dask_s), max(dask_s)],
        "dask_first_s": first_s,
        "cluster_start_s": start_s,
        "ratio": dask / local,
        "identical": float(all(same)),
    }


def report(r: dict) -> list[str]:
    """The benchmark's lines: the ratio first (one run, both on this machine)."""
    return [
        f"Dask / local pool: {r['ratio']:.2f}x ({r['dask_s']:.1f} s against {r['local_s']:.1f} s, "
        f"{r['runs']} runs, {r['workers']} workers; medians of {r['rounds']} campaigns each, "
        f"alternating; poses bit-identical: {'yes' if r['identical'] else 'no'})",
        f"  spread: local {r['local_spread_s'][0]:.1f}-{r['local_spread_s'][1]:.1f} s, Dask "
        f"{r['dask_spread_s'][0]:.1f}-{r['dask_spread_s'][1]:.1f} s; the cluster's first "
        f"campaign (each worker builds the model) {r['dask_first_s']:.1f} s; its start-up "
        f"(scheduler, workers, their preload) {r['cluster_start_s']:.1f} s, not counted",
    ]
