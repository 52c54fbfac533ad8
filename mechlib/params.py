"""Validation of user-facing parameters (mechlib arguments and notebook ``parameters`` cells).

Every check raises ``ValueError`` (or ``TypeError`` for a wrong type) with one message that names
the parameter, what was given and what is allowed. Nothing is clipped or coerced silently.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from numbers import Integral, Real
from typing import TypeVar

import numpy as np

T = TypeVar("T")


def check_int(name: str, value: object, *, low: int | None = None, high: int | None = None) -> int:
    """Return ``value`` as ``int`` if it is an integer in ``[low, high]``.

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    value : object
        The value to check; ``bool`` is rejected.
    low, high : int, optional
        Inclusive bounds; ``None`` means unbounded.

    Returns
    -------
    int

    Raises
    ------
    TypeError
        If ``value`` is not an integer.
    ValueError
        If ``value`` is outside ``[low, high]``.

    Examples
    --------
    >>> check_int("runs", 30, low=1, high=100)
    30
    >>> check_int("runs", 0, low=1, high=100)
    Traceback (most recent call last):
    ...
    ValueError: runs must be in [1, 100], got 0
    >>> check_int("runs", 12.0, low=1)
    Traceback (most recent call last):
    ...
    TypeError: runs must be an integer >= 1, got 12.0
    >>> check_int("runs", True)
    Traceback (most recent call last):
    ...
    TypeError: runs must be an integer, got True
    """
    if isinstance(value, bool) or not isinstance(value, Integral):
        raise TypeError(f"{name} must be an integer{_range_text(low, high)}, got {value!r}")
    value = int(value)
    _check_range(name, value, low, high)
    return value


def check_float(
    name: str,
    value: object,
    *,
    low: float | None = None,
    high: float | None = None,
    low_open: bool = False,
) -> float:
    """Return ``value`` as ``float`` if it is a finite real number in range.

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    value : object
        The value to check; ``bool`` is rejected.
    low, high : float, optional
        Bounds; ``None`` means unbounded. ``high`` is inclusive.
    low_open : bool
        If true the lower bound is exclusive (``value > low``).

    Returns
    -------
    float

    Raises
    ------
    TypeError
        If ``value`` is not a real number.
    ValueError
        If ``value`` is not finite or is out of range.

    Examples
    --------
    >>> check_float("budget_pct", 1, low=0.0, high=100.0, low_open=True)
    1.0
    >>> check_float("budget_pct", 0.0, low=0.0, high=100.0, low_open=True)
    Traceback (most recent call last):
    ...
    ValueError: budget_pct must be in (0.0, 100.0], got 0.0
    >>> check_float("sigma", float("nan"), low=0.0)
    Traceback (most recent call last):
    ...
    ValueError: sigma must be finite, got nan
    """
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(
            f"{name} must be a real number{_range_text(low, high, low_open)}, got {value!r}"
        )
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value!r}")
    too_low = low is not None and (value <= low if low_open else value < low)
    if too_low or (high is not None and value > high):
        raise ValueError(f"{name} must be{_range_text(low, high, low_open)}, got {value!r}")
    return value


def check_given(name: str, value: T | None, upstream: str) -> T:
    """Return ``value`` if it was given: ``None`` is a chapter input that nobody passed.

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    value : object or None
        The parameter's value; ``None`` (its default) means not given.
    upstream : str
        The notebook whose record the build fills it from.

    Raises
    ------
    ValueError
        If ``value`` is ``None``, saying where the value comes from and how to give it.
    """
    if value is None:
        raise ValueError(
            f"{name} was not given: it is an input from the {upstream} notebook's record, which "
            f"the build passes (make notebooks, make run); to run this notebook by hand, give it "
            f"with papermill's -p or -y"
        )
    return value


def check_choice(name: str, value: object, allowed: Iterable[object]) -> object:
    """Return ``value`` if it is one of ``allowed``.

    Raises
    ------
    ValueError
        If ``value`` is not in ``allowed``.

    Examples
    --------
    >>> check_choice("family", "gp", ["linear", "gp"])
    'gp'
    >>> check_choice("family", "spline", ["linear", "gp"])
    Traceback (most recent call last):
    ...
    ValueError: family must be one of ['linear', 'gp'], got 'spline'
    """
    allowed = tuple(allowed)
    if value not in allowed:
        raise ValueError(f"{name} must be one of {list(allowed)}, got {value!r}")
    return value


def check_increasing(
    name: str,
    values: object,
    *,
    low: float | None = None,
    high: float | None = None,
    low_open: bool = False,
    min_len: int = 2,
) -> np.ndarray:
    """Return ``values`` as a 1-D float array of at least ``min_len`` strictly increasing numbers.

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    values : array_like
        The sequence; each entry is checked as by :func:`check_float`.
    low, high, low_open
        Bounds of every entry, as in :func:`check_float`.
    min_len : int
        Smallest allowed number of entries.

    Raises
    ------
    ValueError
        If ``values`` is not 1-D, too short, not strictly increasing or has an entry out of range.
    """
    arr = np.asarray(values, dtype=object)
    bounds = _range_text(low, high, low_open)
    if arr.ndim != 1 or arr.size < min_len:
        raise ValueError(
            f"{name} must list at least {min_len} strictly increasing values{bounds}, "
            f"got {np.asarray(values).tolist()}"
        )
    out = np.array([check_float(name, v, low=low, high=high, low_open=low_open) for v in arr])
    if np.any(np.diff(out) <= 0):
        raise ValueError(
            f"{name} must list at least {min_len} strictly increasing values{bounds}, "
            f"got {out.tolist()}"
        )
    return out


def check_matrix(
    name: str, value: object, *, shape: tuple[int | None, int | None] | None = None
) -> np.ndarray:
    """Return ``value`` as a finite 2-D float array, optionally of a given shape.

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    value : array_like
        The matrix.
    shape : tuple of (int or None), optional
        Required shape; ``None`` in a position means any size.

    Raises
    ------
    ValueError
        If the value is not numbers, not 2-D (ragged rows included), has the wrong shape or
        holds NaN/inf.
    """
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as err:  # ragged rows, text: numpy's message names no value
        raise ValueError(
            f"{name} must be a 2-D array of numbers with rows of equal length, got {value!r:.80}"
        ) from err
    if arr.ndim != 2:
        raise ValueError(f"{name} must be a 2-D array, got {arr.ndim}-D with shape {arr.shape}")
    if shape is not None:
        for axis, want in enumerate(shape):
            if want is not None and arr.shape[axis] != want:
                raise ValueError(f"{name} must have shape {_shape_text(shape)}, got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must hold only finite numbers (found NaN or inf)")
    return arr


def _shape_text(shape: tuple[int | None, int | None]) -> str:
    return "(" + ", ".join("any" if s is None else str(s) for s in shape) + ")"


def _range_text(low: float | None, high: float | None, low_open: bool = False) -> str:
    if low is None and high is None:
        return ""
    if high is None:
        return f" {'>' if low_open else '>='} {low}"
    if low is None:
        return f" <= {high}"
    return f" in {'(' if low_open else '['}{low}, {high}]"


def _check_range(name: str, value: float, low: float | None, high: float | None) -> None:
    if (low is not None and value < low) or (high is not None and value > high):
        raise ValueError(f"{name} must be{_range_text(low, high)}, got {value!r}")
