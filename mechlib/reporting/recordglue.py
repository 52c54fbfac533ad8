"""A plan entry's glue: the names under which elements of a recorded value reach the prose.

A plan entry (:class:`~mechlib.reporting.recordplan.Entry`) glues its value by one spec or a
tuple of specs, merged (a name given twice is refused):

* a name (a scalar glued whole), or ``{name: index}`` (elements at fixed indices, stored as
  written: a fixed ``-1`` is stored as ``-1``);
* :class:`Extremes`: the smallest and largest element, of the whole value or of one row of a
  2-D value, and their labels;
* a function ``glue(value)`` or ``glue(value, context)`` giving ``{name: index}``: indices
  computed from the recorded value (and the notebook's context); a negative index is stored
  as the positive one it addresses, as numpy reads it (``-1`` of 8 elements as ``7``).

:func:`resolve` turns the specs into ``{name: index}`` and ``{name: label}`` for one value.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

#: the index of one element: an int for a 1-D value, a tuple for more dimensions
Index = int | tuple[int, ...]
#: ``glue(value)`` or ``glue(value, context)``: the glue names of elements chosen from the value
GlueOf = Callable[..., Mapping[str, Index]]


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
        The elements' labels (of a 1-D value; of the columns when ``row`` is given).
    low_label, high_label : str, optional
        Glue names of the labels of the smallest and the largest element (texts made of the key).
    fixed : mapping of str to index
        Further glue names of elements at fixed indices, as ``glue={name: index}``.
    row : int, optional
        Look within this row of a 2-D value only; the indices are then ``(row, column)``, a
        negative row stored as the positive one (``-1`` of 4 rows as ``3``).

    Raises
    ------
    ValueError
        No glue name at all, one named twice, a label glue without labels, or a row that is
        not an integer.
    """

    low: str | None = None
    high: str | None = None
    labels: Sequence[str] = ()
    low_label: str | None = None
    high_label: str | None = None
    fixed: Mapping[str, Index] = field(default_factory=dict)
    row: int | None = None

    def __post_init__(self) -> None:
        if not (self.low or self.high or self.low_label or self.high_label):
            raise ValueError("Extremes glues nothing: give low, high, low_label or high_label")
        names = [self.low, self.high, self.low_label, self.high_label, *self.fixed]
        names = [n for n in names if n]
        if len(set(names)) != len(names):
            raise ValueError(f"Extremes names a glue twice: {names}")
        if (self.low_label or self.high_label) and not self.labels:
            raise ValueError(f"Extremes {self.low_label or self.high_label!r} needs labels=")
        if self.row is not None and (
            isinstance(self.row, bool) or not isinstance(self.row, (int, np.integer))
        ):
            raise ValueError(
                f"Extremes row must be an integer (a row of a 2-D value), got {self.row!r}"
            )

    def glue(self, value: Any) -> tuple[dict[str, Index], dict[str, str]]:
        """The glue ``{name: index}`` of ``value``'s extremes and the ``{name: label}`` texts.

        Raises
        ------
        ValueError
            Labels that are not one per element of a 1-D value (per column with ``row``), or a
            ``row`` of a value that is not 2-D or has no such row.
        """
        array = np.asarray(value)
        row = None
        if self.row is not None:
            if array.ndim != 2 or not -array.shape[0] <= self.row < array.shape[0]:
                raise ValueError(f"Extremes row={self.row} of a value of shape {array.shape}")
            row = int(self.row) % array.shape[0]
            array = array[row]
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
            name: at[side] if row is None else (row, at[side])
            for side, name in (("low", self.low), ("high", self.high))
            if name
        }
        texts = {
            name: str(self.labels[at[side]])
            for side, name in (("low", self.low_label), ("high", self.high_label))
            if name
        }
        return indices, texts

    def names(self) -> tuple[list[str], list[str]]:
        """Its glue names: those of numbers, and those of labels."""
        numbers = [n for n in (self.low, self.high, *self.fixed) if n]
        return numbers, [n for n in (self.low_label, self.high_label) if n]


#: one glue spec of a plan entry
Spec = str | Mapping[str, Index] | Extremes | GlueOf
#: a plan entry's glue: one spec or a tuple of them, merged
GlueSpec = Spec | tuple[Spec, ...]


def takes_context(function: Callable[..., Any]) -> bool:
    """Whether a plan function is ``f(value, context)`` rather than ``f(value)``.

    Raises
    ------
    TypeError
        A function of neither one nor two required positional arguments.
    """
    try:
        parameters = inspect.signature(function).parameters.values()
    except (TypeError, ValueError):  # a builtin such as ``str``: of the value alone
        return False
    kinds = (inspect.Parameter.POSITIONAL_ONLY, inspect.Parameter.POSITIONAL_OR_KEYWORD)
    required = [p for p in parameters if p.kind in kinds and p.default is p.empty]
    if len(required) not in (1, 2):
        raise TypeError(
            f"a plan function takes (value) or (value, context), {function!r} takes "
            f"{len(required)} required arguments"
        )
    return len(required) == 2


def call(function: Callable[..., Any], value: Any, context: Mapping[str, Any]) -> Any:
    """``function(value, context)`` or ``function(value)``, as it is written."""
    return function(value, context) if takes_context(function) else function(value)


def specs(glue: GlueSpec | None) -> tuple[Spec, ...]:
    """The specs of a plan entry's glue, checked.

    Raises
    ------
    TypeError
        A spec that is not a name, a mapping, :class:`Extremes` or a function.
    ValueError
        A glue name given twice among the fixed names.
    """
    found = () if glue is None else glue if isinstance(glue, tuple) else (glue,)
    for spec in found:
        if not isinstance(spec, (str, Mapping, Extremes)) and not callable(spec):
            raise TypeError(
                f"plan glue must be a name, {{name: index}}, Extremes or glue(value[, context]), "
                f"got {spec!r}"
            )
        if callable(spec) and not isinstance(spec, (Mapping, Extremes)):
            takes_context(spec)
    numbers, labels = names(found)
    repeated = sorted({n for n in numbers + labels if (numbers + labels).count(n) > 1})
    if repeated:
        raise ValueError(f"plan glue names {repeated} twice")
    return found


def names(glue: Sequence[Spec]) -> tuple[list[str], list[str]]:
    """The glue names the specs give whatever the value: of numbers and of labels (a
    function's names are known only from the value)."""
    numbers: list[str] = []
    labels: list[str] = []
    for spec in glue:
        if isinstance(spec, Extremes):
            more, texts = spec.names()
            numbers += more
            labels += texts
        elif isinstance(spec, str):
            numbers.append(spec)
        elif isinstance(spec, Mapping):
            numbers += list(spec)
    return numbers, labels


def _positive(name: str, index: Any, shape: tuple[int, ...]) -> Index:
    """A function's index with negative entries as the positive ones numpy addresses."""
    parts = index if isinstance(index, tuple) else (index,)
    if len(parts) > len(shape) or not all(
        isinstance(i, (int, np.integer)) and not isinstance(i, bool) for i in parts
    ):
        raise ValueError(
            f"glue {name!r}: index {index!r} is not an int or a tuple of ints into a value of "
            f"shape {shape}"
        )
    out = []
    for i, n in zip(parts, shape, strict=False):
        if not -n <= i < n:
            raise ValueError(f"glue {name!r}: index {index!r} outside a value of shape {shape}")
        out.append(int(i) % n)
    return tuple(out) if isinstance(index, tuple) else out[0]


def resolve(
    glue: Sequence[Spec], value: Any, context: Mapping[str, Any]
) -> tuple[dict[str, Index], dict[str, str]]:
    """The glue ``{name: index}`` and label texts ``{name: label}`` of ``value`` by its specs.

    Raises
    ------
    ValueError
        A name given by two specs, or a function's index outside the value.
    """
    indices: dict[str, Index] = {}
    texts: dict[str, str] = {}
    shape = np.shape(value)
    for spec in glue:
        labels: dict[str, str] = {}
        if isinstance(spec, str):
            got: dict[str, Index] = {spec: ()}
        elif isinstance(spec, Extremes):
            got, labels = spec.glue(value)
        elif isinstance(spec, Mapping):
            got = dict(spec)
        else:
            made = call(spec, value, context)
            got = {name: _positive(name, i, shape) for name, i in dict(made).items()}
        twice = sorted((set(got) | set(labels)) & (set(indices) | set(texts)))
        if twice:
            raise ValueError(f"plan glue names {twice} twice")
        indices |= got
        texts |= labels
    return indices, texts
