"""Where FE experiments run: in-process, on a pool of worker processes that share the cores, or
on a Dask cluster.

:func:`mechlib.campaign.experiments.run_experiments` takes any
:class:`concurrent.futures.Executor`. :func:`executor` gives the one a notebook asked for: with
``$MECHLIB_DASK_SCHEDULER`` set to a scheduler's address (``make store DASK_SCHEDULER=…``), every
campaign goes to that cluster (:func:`dask_executor`), whatever its ``workers``.
"""

from __future__ import annotations

import concurrent.futures as cf

from mechlib.params import check_int

__all__ = ["DASK_ENV", "InProcessExecutor", "dask_executor", "executor", "worker_pool"]

#: environment variable holding a Dask scheduler's address (unset: local processes)
DASK_ENV = "MECHLIB_DASK_SCHEDULER"
#: seconds a scheduler may take to answer before :func:`dask_executor` gives up
DASK_TIMEOUT_S = 10.0


def _limit_blas(threads: int) -> None:
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=threads, user_api="blas")  # for the life of the worker


def worker_pool(workers: int) -> cf.ProcessPoolExecutor:
    """A process pool for FE experiments whose workers share the cores' BLAS threads.

    Each worker's BLAS gets ``cores // workers`` threads, at least one, instead of every core:
    ``workers`` processes that each start a thread per core oversubscribe the machine. (An FE
    task itself, its model's build included, runs on one BLAS thread wherever it runs: the
    same bits in a pool, in-process or on Dask.)

    Parameters
    ----------
    workers : int
        Worker processes, 1 .. 64.
    """
    import os

    workers = check_int("workers", workers, low=1, high=64)
    threads = max(1, (os.cpu_count() or 1) // workers)
    return cf.ProcessPoolExecutor(max_workers=workers, initializer=_limit_blas, initargs=(threads,))


def executor(workers: int) -> cf.Executor:
    """Where FE tasks run: in-process for ``workers`` = 1, else :func:`worker_pool`.

    Use it as a context manager (``with executor(2) as pool:``); the in-process executor has
    nothing to shut down.

    Parameters
    ----------
    workers : int
        Worker processes, 1 .. 64.
    """
    import os

    workers = check_int("workers", workers, low=1, high=64)
    if os.environ.get(DASK_ENV):
        return dask_executor(os.environ[DASK_ENV])
    return InProcessExecutor() if workers == 1 else worker_pool(workers)


def dask_executor(address: object, timeout: float = DASK_TIMEOUT_S) -> cf.Executor:
    """An executor on the Dask cluster whose scheduler is at ``address``.

    ``distributed``'s ``Client(address).get_executor()``; shutting the executor down (leaving
    its ``with`` block) closes the client, not the cluster. Every worker of the cluster gets the
    :class:`~mechlib.campaign.daskworker.CampaignWorker` plugin: glibc's memory reuse
    that Dask's nanny switches off (1.6 times the time a non-linear run takes, measured), and
    one BLAS thread.

    Parameters
    ----------
    address : str or LocalCluster
        The scheduler's address (``tcp://host:port``) or a cluster object.
    timeout : float
        Seconds the scheduler may take to answer, > 0.

    Raises
    ------
    RuntimeError
        If no scheduler answers at ``address`` within ``timeout``: one line, naming it and
        what to do.
    """
    from distributed import Client

    try:
        client = Client(address, timeout=timeout)
    except (OSError, TimeoutError) as err:
        raise RuntimeError(
            f"no Dask scheduler answers at {address} within {timeout:g} s: start one (`dask "
            f"scheduler` and `dask worker <address>`) or unset {DASK_ENV} to run locally"
        ) from err
    from mechlib.campaign.daskworker import CampaignWorker

    client.register_plugin(CampaignWorker())  # every worker, present and future (see its doc)
    return _DaskExecutor(client)


def worker_count(pool: cf.Executor) -> int:
    """How many tasks ``pool`` runs at once: a process or thread pool's ``max_workers``, a Dask
    cluster's workers (when the campaign starts), 1 in-process."""
    if isinstance(pool, _DaskExecutor):
        return max(1, len(pool.client.scheduler_info().get("workers", {})))
    return int(getattr(pool, "_max_workers", 1) or 1)


class _DaskExecutor(cf.Executor):
    """``client.get_executor()`` that closes its client on shutdown."""

    def __init__(self, client) -> None:
        self.client = client
        self._inner = client.get_executor()

    def submit(self, fn, /, *args, **kwargs):
        """Submit ``fn(*args, **kwargs)`` to the cluster (a ``concurrent.futures.Future``)."""
        return self._inner.submit(fn, *args, **kwargs)

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:
        """Wait for the submitted calls (if ``wait``) and close the client."""
        self._inner.shutdown(wait=wait)
        self.client.close()


class InProcessExecutor(cf.Executor):
    """Runs each submitted call at once in the calling thread (the default executor)."""

    def submit(self, fn, /, *args, **kwargs):
        """Call ``fn(*args, **kwargs)`` now; its result or ``Exception`` goes into the future.

        ``KeyboardInterrupt``, ``SystemExit`` and the other ``BaseException`` subclasses that are
        not an ``Exception`` are not caught: they propagate at once, so Ctrl-C stops the whole
        run instead of failing one task and going on with the next.
        """
        fut: cf.Future = cf.Future()
        try:
            result = fn(*args, **kwargs)
        except Exception as err:  # reported through the future, as any executor does
            fut.set_exception(err)
        else:
            fut.set_result(result)
        return fut
