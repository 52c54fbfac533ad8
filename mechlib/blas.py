"""One BLAS thread for a block of FE arithmetic, at the cost of a context switch.

``threadpoolctl.threadpool_limits`` finds the process's BLAS libraries anew at every call
(measured 2.1 ms here; the non-linear solver's residual is called thousands of times a chapter).
:func:`one_thread` limits them through threadpoolctl's cached controller instead, which it makes
again only when the process has imported modules since (one of them may have loaded a library):
0.01 ms a call in a solver's loop, the same limit. One thread gives the same bits in every
process, whatever the machine's cores.
"""

from __future__ import annotations

from contextlib import AbstractContextManager

from threadpoolctl import get_cached_controller


def one_thread() -> AbstractContextManager:
    """A context in which every BLAS library loaded in this process runs on one thread."""
    return get_cached_controller().limit(limits=1, user_api="blas")
