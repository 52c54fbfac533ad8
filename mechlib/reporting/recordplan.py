"""A chapter's record plan: every key it records, with its tolerance, glue names and report rows.

A plan is a mapping ``{key: Entry}`` kept beside the chapters (:mod:`mechlib.reporting.plans`)
and handed to the :class:`~mechlib.reporting.records.Recorder`: the notebook then records a key
with its value alone, ``rec.value(key, value)``, and the recorder takes the rest from the plan.
:func:`resolve` reads one entry for one value; :func:`unrecorded` lists what a run left out.

The plan's functions read the recorded value: ``rows(context)`` and ``tol(context)`` find it in
the context under ``"value"`` (beside the names the notebook passes as ``context=``); glue and
text functions take ``(value)`` or ``(value, context)``. A text made of several recorded keys
(:class:`MadeOf`) reads their values.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, NamedTuple

from mechlib.reporting import recordglue, report
from mechlib.reporting.jsonready import plain
from mechlib.reporting.recordglue import Extremes, GlueSpec, Index
from mechlib.reporting.tolerance import Tolerance

__all__ = [
    "Entry",
    "Extremes",
    "MadeOf",
    "Plan",
    "check_plan",
    "glue_names",
    "resolve",
    "unrecorded",
]

#: report rows whose text needs values the notebook computes: ``rows(context)``
RowsOf = Callable[[Mapping[str, Any]], Sequence[report.RowSpec]]
#: a tolerance that needs values the notebook computes: ``tol(context)``
TolOf = Callable[[Mapping[str, Any]], Tolerance]
#: a text glued from the recorded value: ``text(value)`` or ``text(value, context)``
TextOf = Callable[..., str | float]
#: glue as :class:`~mechlib.reporting.records.Recorder` takes it: a name, or ``{name: index}``
PlanGlue = str | Mapping[str, Index]
#: the keys a text is made of: a tuple, or ``keys(value)`` / ``keys(value, context)`` giving one
KeysOf = tuple[str, ...] | Callable[..., Sequence[str]]
#: the name under which plan functions find the recorded value in the context
VALUE = "value"
_ROW_TYPES = (report.Comparison, report.Check, report.Computed, report.NotReproduced)


class _NoValue:
    def __repr__(self) -> str:
        return "no value"


#: :attr:`Entry.value` of an entry that is not a constant
NO_VALUE: Any = _NoValue()


@dataclass(frozen=True)
class MadeOf:
    """A plan text made of several recorded keys, not of its entry's value alone.

    Glued when its entry is recorded, as ``rec.text(name, text, of="a,b,...")`` would glue it:
    made of the keys ``keys`` gives, which must be recorded by then (the entry's own key may be
    one of them); ``text`` reads their recorded values.

    Parameters
    ----------
    keys : tuple of str, or callable
        The record keys the text is made of, in the order its glue entry lists them; or
        ``keys(value)`` / ``keys(value, context)`` choosing them (a text whose sentence depends
        on what the run computed).
    text : callable
        ``text(values)`` or ``text(values, context)`` giving a str (or NaN): ``values`` maps each
        of the keys to its value as recorded (arrays as nested lists).

    Raises
    ------
    TypeError
        Keys that are neither a non-empty tuple of str nor callable, or a text not callable.
    """

    keys: KeysOf
    text: Callable[..., str | float]

    def __post_init__(self) -> None:
        if callable(self.keys):
            recordglue.takes_context(self.keys)
        elif not (
            isinstance(self.keys, tuple)
            and self.keys
            and all(isinstance(k, str) and k for k in self.keys)
        ):
            raise TypeError(
                f"MadeOf keys must be a tuple of record keys or keys(value), got {self.keys!r}"
            )
        if not callable(self.text):
            raise TypeError(f"MadeOf text must be text(values[, context]), got {self.text!r}")
        recordglue.takes_context(self.text)

    @property
    def functions(self) -> list[Callable[..., Any]]:
        """Its functions (to tell whether they read a context)."""
        return [self.text, *([self.keys] if callable(self.keys) else [])]

    def made(
        self, key: str, value: Any, context: Mapping[str, Any], recorded: Mapping[str, Any]
    ) -> tuple[str | float, str]:
        """The text and its ``of`` (the keys joined by commas), for ``value`` recorded under
        ``key`` after the values ``recorded`` (by key).

        Raises
        ------
        ValueError
            A key the text is made of that is not recorded (nor ``key``).
        """
        keys = tuple(
            recordglue.call(self.keys, value, context) if callable(self.keys) else self.keys
        )
        values = {**recorded, key: plain(value)}
        missing = [k for k in keys if k not in values]
        if missing:
            raise ValueError(f"{key}: its plan text is made of {missing}, which were not recorded")
        text = recordglue.call(self.text, {k: values[k] for k in keys}, context)
        return text, ",".join(keys)


@dataclass(frozen=True)
class Entry:
    """What a record key carries besides its value.

    Parameters
    ----------
    tol : Tolerance or callable
        Its named tolerance (:mod:`mechlib.reporting.tolerances`), or ``tol(context)`` giving one.
    glue : str, mapping, Extremes, callable, or a tuple of them, optional
        Glue name of a scalar, ``{name: index}`` for elements of an array, :class:`Extremes`
        for its smallest and largest elements (and their labels), or ``glue(value)`` /
        ``glue(value, context)`` giving ``{name: index}``; a tuple of these is merged
        (:mod:`mechlib.reporting.recordglue`).
    rows : RowSpec, sequence of RowSpec, or callable
        Its report rows, or ``rows(context)`` giving them when their text quotes the recorded
        value (``context["value"]``) or values the notebook computes (passed as ``context=``).
    optional : bool
        The key may be left out of a run (a parameter can switch its computation off).
    texts : mapping of str to callable or MadeOf
        Texts glued from the recorded value, each ``text(value)`` or ``text(value, context)``
        giving a str (or NaN), glued as made of the key (``rec.text(name, text, of=key)``); or
        a :class:`MadeOf`, a text made of several recorded keys.
    value : any, optional
        A constant fixed when the plan is written (a published number, a bound): recorded by
        :meth:`~mechlib.reporting.records.Recorder.constants`.

    Raises
    ------
    TypeError
        A ``tol`` that is neither a Tolerance nor callable, rows, glue or texts of another kind.
    ValueError
        A glue name given twice.
    """

    tol: Tolerance | TolOf
    glue: GlueSpec | None = None
    rows: report.RowSpec | Sequence[report.RowSpec] | RowsOf = ()
    optional: bool = False
    texts: Mapping[str, TextOf | MadeOf] = field(default_factory=dict)
    value: Any = NO_VALUE

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
        for name, text in self.texts.items():
            if (
                not isinstance(name, str)
                or not name
                or not (callable(text) or isinstance(text, MadeOf))
            ):
                raise TypeError(
                    f"Entry texts map glue names to text(value[, context]) or MadeOf: {name!r}"
                )
            if not isinstance(text, MadeOf):
                recordglue.takes_context(text)
        numbers, labels = recordglue.names(recordglue.specs(self.glue))
        twice = sorted(set(numbers + labels) & set(self.texts))
        if twice:
            raise ValueError(f"Entry glue names {twice} twice (in glue and in texts)")

    @property
    def is_constant(self) -> bool:
        """Whether the entry holds its value (:meth:`Recorder.constants` records it)."""
        return self.value is not NO_VALUE

    @property
    def needs_context(self) -> bool:
        """Whether the tolerance, rows, glue or texts are computed from a context."""
        functions = [
            s for s in recordglue.specs(self.glue) if not isinstance(s, (str, Mapping, Extremes))
        ]
        for text in self.texts.values():
            functions += text.functions if isinstance(text, MadeOf) else [text]
        return (
            callable(self.rows)
            or not isinstance(self.tol, Tolerance)
            or any(recordglue.takes_context(f) for f in functions)
        )


#: a chapter's plan: every record key it writes
Plan = Mapping[str, Entry]


class Resolved(NamedTuple):
    """What a plan entry gives one recorded value."""

    tol: Tolerance
    glue: dict[str, Index]
    texts: dict[str, str | float]
    rows: list[report.RowSpec]
    #: the keys (comma-separated) of the texts made of others than the recorded key
    text_of: dict[str, str]


def glue_names(entry: Entry) -> tuple[list[str], list[str]]:
    """The glue names of an entry: those of numbers, and those of labels and texts.

    Raises
    ------
    ValueError
        An entry glued by a function: its names are known only from the value.
    """
    glue = recordglue.specs(entry.glue)
    if any(not isinstance(s, (str, Mapping, Extremes)) for s in glue):
        raise ValueError(
            "its plan entry glues by a function, whose names are known only from the value: "
            "name the glue names instead"
        )
    numbers, labels = recordglue.names(glue)
    return numbers, labels + list(entry.texts)


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
    plan: Plan,
    key: str,
    value: Any,
    context: Mapping[str, Any] | None,
    notebook: str,
    recorded: Mapping[str, Any] | None = None,
) -> Resolved:
    """The tolerance, glue, texts and report rows the plan gives ``value`` under ``key``
    (``recorded``: the values recorded before, by key, that a :class:`MadeOf` text reads).

    Raises
    ------
    ValueError
        A key the plan does not hold, a context given where the entry reads none (or holding
        ``"value"``), a name the entry reads that the context does not hold, or a key a
        :class:`MadeOf` text is made of that is not recorded.
    """
    if key not in plan:
        raise ValueError(
            f"record key {key!r} is not in {notebook}'s plan (mechlib.reporting.plans."
            f"{notebook}): add its Entry there"
        )
    entry = plan[key]
    if context is not None and not entry.needs_context:
        raise ValueError(f"{key}: its plan entry reads no context, got context={sorted(context)}")
    if context is not None and VALUE in context:
        raise ValueError(
            f"{key}: context={sorted(context)} may not hold {VALUE!r}: the recorder puts the "
            f"recorded value there"
        )
    full = {**(context or {}), VALUE: value}
    try:
        tol = entry.tol if isinstance(entry.tol, Tolerance) else entry.tol(full)
        rows = list(entry.rows(full) if callable(entry.rows) else entry.rows)
        glue, labels = recordglue.resolve(recordglue.specs(entry.glue), value, full)
        texts, text_of = dict(labels), {}
        for name, f in entry.texts.items():
            if isinstance(f, MadeOf):
                texts[name], text_of[name] = f.made(key, value, full, recorded or {})
            else:
                texts[name] = recordglue.call(f, value, full)
    except KeyError as error:
        missing = error.args[0] if error.args else None
        if not isinstance(missing, str) or missing in full:
            raise
        hint = "" if context else ": pass them as context={...}"
        raise ValueError(
            f"{key}: its plan entry reads {missing!r} from the context, which holds "
            f"{sorted(context or {})}{hint}"
        ) from None
    if not isinstance(tol, Tolerance):
        raise TypeError(f"{key}: the plan's tol(context) must give a Tolerance, got {tol!r}")
    twice = sorted(set(glue) & set(texts))
    if twice:
        raise ValueError(f"{key}: its plan glues {twice} twice")
    return Resolved(tol, glue, texts, rows, text_of)


def unrecorded(plan: Plan, recorded: set[str]) -> list[str]:
    """The plan's keys, not optional, that were not recorded, in the plan's order."""
    return [k for k, e in plan.items() if not e.optional and k not in recorded]
