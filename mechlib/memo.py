"""A process's memory of a pure function of arrays: the same inputs give the same object back.

A chapter fits the same meta-model to the same runs more than once (its comparison at the
largest training design and its learning curve's last point; the learning curve's first points
and the budget study at the full force range); :func:`array_memo` keeps the last results of a
function by a digest of its arguments' values (dtype, shape and bytes of an array), so the
second call costs nothing and returns the very same fitted object. Only for functions whose
result depends on their arguments alone (seeded, no clock, no global state) and is not changed
by its callers.
"""

from __future__ import annotations

import functools
import hashlib
from collections import OrderedDict
from collections.abc import Callable
from typing import Any

import numpy as np

_SCALARS = (str, int, float, bool, type(None))


def array_memo(maxsize: int) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Decorator: remember the last ``maxsize`` results of a function of arrays and scalars.

    Arguments other than scalars, arrays and (nested) lists or tuples of numbers are not
    digested: such a call runs the function and is not remembered. ``fn.cache_clear()`` forgets.
    """
    if not isinstance(maxsize, int) or maxsize < 1:
        raise ValueError(f"maxsize must be an integer ≥ 1, got {maxsize!r}")

    def wrap(fn: Callable[..., Any]) -> Callable[..., Any]:
        kept: OrderedDict[str, Any] = OrderedDict()

        @functools.wraps(fn)
        def call(*args: Any, **kwargs: Any) -> Any:
            key = _digest(args, kwargs)
            if key is None:
                return fn(*args, **kwargs)
            if key in kept:
                kept.move_to_end(key)
                return kept[key]
            out = kept[key] = fn(*args, **kwargs)
            if len(kept) > maxsize:
                kept.popitem(last=False)
            return out

        call.cache_clear = kept.clear  # type: ignore[attr-defined]
        return call

    return wrap


def _digest(args: tuple, kwargs: dict) -> str | None:
    """SHA-256 of the arguments' names, types and contents, or None if one cannot be digested."""
    h = hashlib.sha256()
    for name, v in [*enumerate(args), *sorted(kwargs.items())]:
        h.update(f"{name}=".encode())
        if isinstance(v, _SCALARS):
            h.update(f"{type(v).__name__}:{v!r};".encode())
            continue
        try:
            a = np.asarray(v)
        except (TypeError, ValueError):
            return None
        if a.dtype == object:
            return None
        a = np.ascontiguousarray(a)
        h.update(f"array:{a.dtype.str}:{a.shape};".encode())
        h.update(a.tobytes())
    return h.hexdigest()
