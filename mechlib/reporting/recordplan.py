"""A chapter's record plan: every key it records, with its tolerance, glue names and report rows.

A plan is a mapping ``{key: Entry}`` kept beside the chapters (:mod:`mechlib.reporting.plans`)
and handed to the :class:`~mechlib.reporting.records.Recorder`: the notebook then records a key
with its value alone, ``rec.value(key, value)``, and the recorder takes the rest from the plan.
:func:`resolve` reads one entry for one value; :func:`unrecorded` lists what a run left out.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mechlib.reporting import report
from mechlib.reporting.tolerances import Tolerance

#: report rows whose text needs values the notebook computes: ``rows(context)``
RowsOf = Callable[[Mapping[str, Any]], Sequence[report.RowSpec]]
#: a tolerance that needs values the notebook computes: ``tol(context)``
TolOf = Callable[[Mapping[str, Any]], Tolerance]
#: glue as :class:`~mechlib.reporting.records.Recorder` takes it: a name, or ``{name: index}``
PlanGlue = str | Mapping[str, int | tuple[int, ...]]
_ROW_TYPES = (report.Comparison, report.Check, report.Computed, report.NotReproduced)


@dataclass(frozen=True)
class Entry:
    """What a record key carries besides its value.

    Parameters
    ----------
    tol : Tolerance or callable
        Its named tolerance (:mod:`mechlib.reporting.tolerances`), or ``tol(context)`` giving one.
    glue : str, mapping or Extremes, optional
        Glue name of a scalar, ``{name: index}`` for elements of an array, or
        :class:`Extremes` for its smallest and largest elements (and their labels).
    rows : RowSpec, sequence of RowSpec, or callable
        Its report rows, or ``rows(context)`` giving them when their text quotes values the
        notebook computes (the notebook passes those as ``context=``).
    optional : bool
        The key may be left out of a run (a parameter can switch its computation off).

    Raises
    ------
    TypeError
        A ``tol`` that is neither a Tolerance nor callable, or rows of another kind.
    """

    tol: Tolerance | TolOf
    glue: PlanGlue | Extremes | None = None
    rows: report.RowSpec | Sequence[report.RowSpec] | RowsOf = ()
    optional: bool = False

    def __post_init__(self) -> None:
        if not isinstance(self.tol, Tolerance) and not callable(self.tol):
            raise TypeError(f"Entry tol must be a Tolerance or tol(context), got {self.tol!r}")
        if isinstance(self.rows, _ROW_TYPES):
            object.__setattr__(self, "rows", (self.rows,))
        elif not callable(self.rows):
            rows = tuple(self.rows)
            if not all(isinstance(r, _ROW_TYPES) for r in rows):
                raise TypeError(f"Entry rows must be report rows or rows(context), got {rows!r}")
            object.__setattr__(self, "rows", rows)

    @property
    def needs_context(self) -> bool:
        """Whether the tolerance or the rows are computed from the notebook's context."""
        return callable(self.rows) or not isinstance(self.tol, Tolerance)


@dataclass(frozen=True)
class Extremes:
    """Glue for the smallest and largest elements of a recorded array, and their labels.

    Where a notebook wrote ``glue={"lo": int(a.argmin()), "hi": int(a.argmax())}`` and
    ``rec.text("lo_component", R[int(a.argmin())], of=key)``, its plan writes
    ``glue=Extremes(low="lo", high="hi", labels=R, low_label="lo_component")``: the same glue
    entries, indices and texts.

    Parameters
    ----------
    low, high : str, optional
        Glue names of the smallest and the largest element (first one on ties, as ``argmin``).
    labels : sequence of str
        The elements' labels (a 1-D value), for ``low_label`` and ``high_label``.
    low_label, high_label : str, optional
        Glue names of the labels of the smallest and the largest element (texts made of the key).
    fixed : mapping of str to index
        Further glue names of elements at fixed indices, as ``glue={name: index}``.

    Raises
    ------
    ValueError
        No glue name at all, one named twice, or a label glue without labels.
    """

    low: str | None = None
    high: str | None = None
    labels: Sequence[str] = ()
    low_label: str | None = None
    high_label: str | None = None
    fixed: Mapping[str, int | tuple[int, ...]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if not (self.low or self.high or self.low_label or self.high_label):
            raise ValueError("Extremes glues nothing: give low, high, low_label or high_label")
        names = [self.low, self.high, self.low_label, self.high_label, *self.fixed]
        names = [n for n in names if n]
        if len(set(names)) != len(names):
            raise ValueError(f"Extremes names a glue twice: {names}")
        if (self.low_label or self.high_label) and not self.labels:
            raise ValueError(f"Extremes {self.low_label or self.high_label!r} needs labels=")

    def glue(self, value: Any) -> tuple[dict[str, int | tuple[int, ...]], dict[str, str]]:
        """The glue ``{name: index}`` of ``value``'s extremes and the ``{name: label}`` texts.

        Raises
        ------
        ValueError
            Labels that are not one per element of a 1-D value.
        """
        array = np.asarray(value)
        if self.labels and (array.ndim != 1 or len(self.labels) != array.size):
            raise ValueError(
                f"Extremes: {len(self.labels)} labels for a value of shape {array.shape}"
            )
        where = {"low": array.argmin(), "high": array.argmax()}
        at = {
            side: int(i)
            if array.ndim == 1
            else tuple(int(j) for j in np.unravel_index(i, array.shape))
            for side, i in where.items()
        }
        indices = dict(self.fixed) | {
            name: at[side] for side, name in (("low", self.low), ("high", self.high)) if name
        }
        texts = {
            name: str(self.labels[at[side]])
            for side, name in (("low", self.low_label), ("high", self.high_label))
            if name
        }
        return indices, texts


#: a chapter's plan: every record key it writes
Plan = Mapping[str, Entry]


def glue_names(entry: Entry) -> tuple[list[str], list[str]]:
    """The glue names of an entry: those of numbers, and those of labels (texts)."""
    glue = entry.glue
    if isinstance(glue, Extremes):
        numbers = [n for n in (glue.low, glue.high, *glue.fixed) if n]
        return numbers, [n for n in (glue.low_label, glue.high_label) if n]
    return ([glue] if isinstance(glue, str) else list(glue or {})), []


def check_plan(plan: Plan, notebook: str) -> None:
    """Refuse a plan that is not a mapping of string keys to :class:`Entry`.

    Raises
    ------
    TypeError
        Naming the first key of another kind or holding something else than an Entry.
    """
    if not isinstance(plan, Mapping):
        raise TypeError(f"{notebook}'s plan must be a mapping key -> Entry, got {type(plan)}")
    for key, entry in plan.items():
        if not isinstance(key, str) or not isinstance(entry, Entry):
            raise TypeError(f"{notebook}'s plan: {key!r} must be a str mapped to an Entry")


def resolve(
    plan: Plan, key: str, context: Mapping[str, Any] | None, notebook: str
) -> tuple[Tolerance, PlanGlue | Extremes | None, list[report.RowSpec]]:
    """The tolerance, glue and report rows the plan gives ``key`` in this ``context``.

    Raises
    ------
    ValueError
        A key the plan does not hold, a context missing where the entry needs one (or given
        where it needs none), or a context missing a name the entry reads.
    """
    if key not in plan:
        raise ValueError(
            f"record key {key!r} is not in {notebook}'s plan (mechlib.reporting.plans."
            f"{notebook}): add its Entry there"
        )
    entry = plan[key]
    if entry.needs_context and context is None:
        raise ValueError(
            f"{key}: its plan entry builds its rows or tolerance from values of the notebook: "
            f"pass them as context={{...}}"
        )
    if context is not None and not entry.needs_context:
        raise ValueError(f"{key}: its plan entry reads no context, got context={sorted(context)}")
    try:
        tol = entry.tol if isinstance(entry.tol, Tolerance) else entry.tol(context or {})
        rows = list(entry.rows(context or {}) if callable(entry.rows) else entry.rows)
    except KeyError as missing:
        raise ValueError(
            f"{key}: its plan entry reads {missing} from the context, which holds "
            f"{sorted(context or {})}"
        ) from None
    if not isinstance(tol, Tolerance):
        raise TypeError(f"{key}: the plan's tol(context) must give a Tolerance, got {tol!r}")
    return tol, entry.glue, rows


def unrecorded(plan: Plan, recorded: set[str]) -> list[str]:
    """The plan's keys, not optional, that were not recorded, in the plan's order."""
    return [k for k, e in plan.items() if not e.optional and k not in recorded]
