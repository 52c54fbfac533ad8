"""The tolerance of a recorded number: how far a re-run may move it, and why.

A record stores ``rtol`` and ``atol`` (``|a - b| <= atol + rtol * |b|``, see
:mod:`mechlib.reporting.records`). :class:`Tolerance` holds the two bounds with the reason a
re-run on another machine stays within them; the named instances the chapters' plans use are
in :mod:`mechlib.reporting.tolerances`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np


@dataclass(frozen=True)
class Tolerance:
    """How closely a re-run must reproduce a recorded value.

    Parameters
    ----------
    rtol : float
        Relative tolerance, ≥ 0.
    atol : float
        Absolute tolerance, ≥ 0, in the value's units.
    why : str
        One sentence: the numerics behind the value and why a re-run stays within the bounds.
    peak : float
        A further absolute tolerance as a fraction of the recorded value's largest magnitude
        (for arrays whose round-off scales with their largest entry), ≥ 0.

    Raises
    ------
    ValueError
        A negative or non-finite bound, or an empty ``why``.
    """

    rtol: float = 0.0
    atol: float = 0.0
    why: str = ""
    peak: float = 0.0

    def __post_init__(self) -> None:
        for name in ("rtol", "atol", "peak"):
            bound = getattr(self, name)
            if isinstance(bound, bool) or not isinstance(bound, (int, float)):
                raise ValueError(f"Tolerance {name} must be a number >= 0, got {bound!r}")
            if not math.isfinite(bound) or bound < 0:
                raise ValueError(f"Tolerance {name} must be finite and >= 0, got {bound!r}")
        if not self.why.strip():
            raise ValueError("a Tolerance says why a re-run stays within it: why= is empty")

    def atol_for(self, value: Any) -> float:
        """The absolute tolerance of ``value``: ``atol`` plus ``peak`` times its largest
        magnitude (just ``atol`` when ``peak`` is 0)."""
        if not self.peak:
            return self.atol
        return self.atol + self.peak * np.abs(np.asarray(value, dtype=float)).max()

    def scaled(self, reference: Any) -> Tolerance:
        """This tolerance with its ``peak`` taken from ``reference`` instead of the recorded
        value: ``atol + peak * max|reference|`` as a fixed ``atol`` (``peak`` 0), same ``why``.

        For ``atol=1e-6 * np.abs(eff).max()`` on a value other than ``eff``:
        ``tol=lambda c: FE_LINEAR.scaled(c["eff"])`` — the same float.

        Raises
        ------
        ValueError
            A ``reference`` that is empty or not finite (with a ``peak``).
        """
        if not self.peak:
            return self
        reference = np.asarray(reference, dtype=float)
        if not reference.size or not np.isfinite(reference).all():
            raise ValueError(
                f"Tolerance.scaled: reference must be finite numbers, got {reference!r}"
            )
        return replace(self, atol=float(self.atol_for(reference)), peak=0.0)
