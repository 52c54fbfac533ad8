"""Where FE experiments run: in-process, or on a pool of worker processes that share the cores.

:func:`mechlib.hexflex.experiments.run_experiments` takes any
:class:`concurrent.futures.Executor`; these are the two it is usually given.
"""

from __future__ import annotations

import concurrent.futures as cf

from mechlib.params import check_int

__all__ = ["InProcessExecutor", "executor", "worker_pool"]


def _limit_blas(threads: int) -> None:
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=threads, user_api="blas")  # for the life of the worker


def worker_pool(workers: int) -> cf.ProcessPoolExecutor:
    """A process pool for FE experiments whose workers share the cores' BLAS threads.

    Each worker's BLAS (the linear model's SuperLU factorisation and SfePy's assembly run
    through it) gets ``cores // workers`` threads, at least one, instead of every core:
    ``workers`` processes that each start a thread per core oversubscribe the machine. (The
    non-linear solve's own kernels run on one thread in any case.)

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
    workers = check_int("workers", workers, low=1, high=64)
    return InProcessExecutor() if workers == 1 else worker_pool(workers)


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
