"""JSON-ready copies of recorded values: numpy scalars and arrays, tuples, mappings."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np


def plain(value: Any) -> Any:
    """Convert numpy scalars/arrays and tuples to JSON-ready Python objects."""
    if isinstance(value, np.ndarray):
        return [plain(v) for v in value.tolist()]
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, float) and not np.isfinite(value):
        raise ValueError(f"records hold finite numbers only, got {value!r}")
    return value


def plain_tree(value: Any) -> Any:
    """:func:`plain` through mappings too (keys as strings)."""
    if isinstance(value, Mapping):
        return {str(k): plain_tree(v) for k, v in value.items()}
    if isinstance(value, np.ndarray):
        return [plain_tree(v) for v in value.tolist()]
    if isinstance(value, (list, tuple)):
        return [plain_tree(v) for v in value]
    return plain(value)


def is_number(value: Any) -> bool:
    """Whether ``value`` (a scalar or an array) holds numbers: integers or floats, not booleans."""
    return np.asarray(value).dtype.kind in "iuf"
