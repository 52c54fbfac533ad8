"""Wall-clock timing of small calls, for benchmarks and notebook latency tables (never tests)."""

from __future__ import annotations

import timeit
from collections.abc import Callable
from functools import partial

from mechlib.params import check_int


def seconds_per_call(
    fn: Callable[..., object], *args: object, repeats: int = 5, number: int | None = None
) -> float:
    """Best-of-``repeats`` time of one call ``fn(*args)`` [s].

    ``number`` calls are timed together per repeat (default: enough for ≈ 0.05 s, as
    ``timeit``'s autorange chooses); the minimum over repeats is the least noisy estimate on a
    shared machine.
    """
    repeats = check_int("repeats", repeats, low=1, high=1000)
    timer = timeit.Timer(partial(fn, *args))
    if number is None:
        number, _ = timer.autorange()
        number = max(1, number // 4)
    number = check_int("number", number, low=1)
    return min(timer.repeat(repeat=repeats, number=number)) / number
