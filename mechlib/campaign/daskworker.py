"""What a Dask worker of an FE campaign needs: glibc's default memory reuse, one BLAS thread,
and (optionally) the FE stack imported at start.

Dask's nanny starts each worker with ``MALLOC_TRIM_THRESHOLD_=65536`` (to return freed memory
to the system quickly). Setting that variable switches off glibc's adaptive threshold for
``mmap``, so every large temporary array of a non-linear solve is mapped, page-faulted and
unmapped again: measured on this project's non-linear runs, 1.6 times the time a run takes in
a worker started without it (0.87 s against 1.43 s a run, in one process, the same runs).
:func:`restore_malloc` puts glibc's large thresholds back (``mallopt``), and limits BLAS to one
thread (what the local pool gives each worker). :func:`~mechlib.campaign.executors.
dask_executor` installs it on every worker of the cluster, present and future, as a worker
plugin (:class:`CampaignWorker`); a worker started with ``--preload
mechlib.campaign.daskworker`` also imports the FE stack before its first task.
"""

from __future__ import annotations

import ctypes
import ctypes.util

#: glibc's ``mallopt`` parameters (malloc.h) and the values restored: freed memory below 64 MiB
#: stays with the process, blocks below 32 MiB (glibc's adaptive ceiling) come from the heap
M_TRIM_THRESHOLD, M_MMAP_THRESHOLD = -1, -3
TRIM_BYTES, MMAP_BYTES = 64 * 2**20, 32 * 2**20


def restore_malloc() -> bool:
    """Set glibc's trim and mmap thresholds to :data:`TRIM_BYTES` and :data:`MMAP_BYTES` and
    limit BLAS to one thread in this process; ``False`` where there is no glibc (nothing to
    undo there)."""
    import numpy  # noqa: F401  (NumPy's and SciPy's BLAS loaded before they are limited)
    import scipy.linalg  # noqa: F401
    from threadpoolctl import OpenBLASController, threadpool_limits

    threadpool_limits(limits=1, user_api="blas")
    # a limit set outside a ``with`` makes this thread OpenBLAS's only "controlling thread" in
    # threadpoolctl: a Dask worker runs its tasks in other threads, whose own limits
    # (``mechlib.blas.one_thread``) would then do nothing; give the control back
    OpenBLASController.clear_controlling_thread(force=True)
    name = ctypes.util.find_library("c")
    try:
        libc = ctypes.CDLL(name)
        mallopt = libc.mallopt
    except (OSError, AttributeError, TypeError):
        return False
    return bool(mallopt(M_TRIM_THRESHOLD, TRIM_BYTES)) and bool(
        mallopt(M_MMAP_THRESHOLD, MMAP_BYTES)
    )


def _plugin_base() -> type:
    from distributed.diagnostics.plugin import WorkerPlugin

    return WorkerPlugin


class CampaignWorker(_plugin_base()):
    """Worker plugin: :func:`restore_malloc` on every worker, when it joins the cluster."""

    name = "mechlib-campaign-worker"

    def setup(self, worker: object) -> None:
        """Called by Dask on each worker."""
        restore_malloc()


def dask_setup(worker: object = None) -> None:
    """Preload hook (``--preload mechlib.campaign.daskworker``): the FE stack imported
    before the first task, and :func:`restore_malloc`."""
    # the FE core (SciPy, threadpoolctl; SfePy itself and a mechanism's model modules are
    # imported by the first task that builds a model), before the first task
    import mechlib.fe.nonlinear  # noqa: F401

    restore_malloc()
