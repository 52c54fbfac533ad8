"""One BLAS thread for a block of arithmetic, through threadpoolctl's cached controller."""

from __future__ import annotations

import numpy as np  # noqa: F401  (its BLAS loaded)
import scipy.linalg  # noqa: F401  (and SciPy's)
from threadpoolctl import threadpool_info

from mechlib.blas import one_thread


def _blas_threads() -> list[int]:
    return [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]


def test_one_thread_limits_every_blas_library_and_restores_them() -> None:
    before = _blas_threads()
    assert before  # NumPy's and SciPy's
    with one_thread():
        assert _blas_threads() == [1] * len(before)
        with one_thread():  # nested
            assert _blas_threads() == [1] * len(before)
    assert _blas_threads() == before
