"""A process's memory of a pure function of arrays."""

from __future__ import annotations

import numpy as np
import pytest

from mechlib.memo import array_memo


def test_the_same_values_give_the_same_object_and_others_a_new_call() -> None:
    calls = []

    @array_memo(maxsize=2)
    def fit(x, y, *, seed=0):
        calls.append(1)
        return {"sum": float(np.sum(x) + np.sum(y)) + seed}

    x, y = np.arange(6.0).reshape(3, 2), np.ones(3)
    first = fit(x, y, seed=1)
    assert fit(x.copy(), list(y), seed=1) is first  # equal values, another array: remembered
    assert len(calls) == 1
    assert fit(x, y, seed=2) is not first  # another keyword value
    assert fit(x.astype(np.float32), y, seed=1) is not first  # another dtype
    assert fit(x.reshape(2, 3), y, seed=1) is not first  # another shape
    assert fit(y, x, seed=1) is not first  # the arguments' order matters
    assert len(calls) == 5
    assert fit(x, y, seed=1) is not first  # forgotten: only the last two are kept
    fit.cache_clear()


def test_an_argument_it_cannot_digest_is_not_remembered() -> None:
    calls = []

    @array_memo(maxsize=4)
    def f(obj):
        calls.append(1)
        return obj

    f(object())
    f([object()])
    assert len(calls) == 2
    with pytest.raises(ValueError, match="maxsize must be an integer ≥ 1, got 0"):
        array_memo(0)
