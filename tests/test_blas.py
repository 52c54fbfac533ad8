"""One BLAS thread for a block of arithmetic, through a controller kept per process."""

from __future__ import annotations

import sys

import numpy as np  # noqa: F401  (its BLAS loaded)
import scipy.linalg  # noqa: F401  (and SciPy's)
from threadpoolctl import threadpool_info

from mechlib import blas


def _blas_threads() -> list[int]:
    return [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]


def test_one_thread_limits_every_blas_library_and_restores_them() -> None:
    before = _blas_threads()
    assert before  # NumPy's and SciPy's
    with blas.one_thread():
        assert _blas_threads() == [1] * len(before)
    assert _blas_threads() == before


def test_the_controller_is_kept_and_made_again_after_an_import() -> None:
    with blas.one_thread():
        pass
    kept = blas._MADE["controller"]
    with blas.one_thread():
        assert blas._MADE["controller"] is kept  # no new scan in a solver's loop
    sys.modules["mechlib_blas_test_marker"] = sys  # the process imported something since
    try:
        with blas.one_thread():
            assert blas._MADE["controller"] is not kept  # that import may have loaded a BLAS
            assert set(_blas_threads()) == {1}
    finally:
        del sys.modules["mechlib_blas_test_marker"]
