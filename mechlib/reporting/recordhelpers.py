"""The recorder's shorthands for what the chapters repeat: a mapping of values, glue left out.

:class:`RecordHelpers` is a base of :class:`~mechlib.reporting.records.Recorder`; each helper
records exactly what the longer code it replaces recorded (the same keys, values and glue).
The extremes of an array are glued by the plan (:class:`~mechlib.reporting.recordplan.Extremes`).
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable, Iterable, Mapping
from typing import Any, Protocol

from mechlib.reporting import recordplan
from mechlib.reporting.jsonready import plain_tree


class _Recording(Protocol):
    plan: recordplan.Plan | None
    data: dict[str, tuple[str, str]]
    about: Mapping[str, str | Callable[[Mapping[str, Any]], str]]

    def value(self, key: str, value: Any, **kwargs: Any) -> Any: ...

    def text(self, name: str, text: str | float, *, of: str = "", why: str = "") -> Any: ...


class RecordHelpers:
    """Shorthands over :meth:`Recorder.value` and :meth:`Recorder.text`."""

    def mapping(
        self: _Recording,
        prefix: str | Mapping[str, Any],
        values: Mapping[str, Any] | None = None,
        **kwargs: Any,
    ) -> Mapping[str, Any]:
        """Record each ``values[name]`` under ``<prefix>.<name>``, in the mapping's order; or,
        given one mapping of full keys (``rec.mapping({"design.published": d, ...})``), each
        value under its key.

        Parameters
        ----------
        prefix : str or mapping
            The keys' common first part (``"geometry"``), or the mapping of full keys to values.
        values : mapping, optional
            Names to values (with a prefix only).
        **kwargs
            Passed to every :meth:`Recorder.value` call (``rtol=`` … without a plan).

        Returns
        -------
        mapping
            The mapping given, so that the record can be written inline.

        Raises
        ------
        TypeError
            A prefix without values, or a mapping of full keys with values too.
        """
        if isinstance(prefix, str) == (values is None):
            raise TypeError("mapping takes a prefix and its values, or one mapping of full keys")
        given: Mapping[str, Any] = values if values is not None else prefix  # type: ignore[assignment]
        keys = {f"{prefix}.{n}" if values is not None else n: v for n, v in given.items()}
        for key, value in keys.items():
            self.value(key, value, **kwargs)
        return given

    def constants(self: _Recording, *prefixes: str) -> dict[str, Any]:
        """Record the constants of the plan (entries with a ``value=``), in the plan's order,
        each as ``rec.value(key, entry.value)``: the same keys, values, tolerances, glue, texts
        and rows as those calls. With ``prefixes``, only those whose key starts with one of them
        (so that constants recorded at several places of a page keep their report order).

        Returns
        -------
        dict
            The constants recorded, by key.

        Raises
        ------
        ValueError
            A recorder without a plan, or no constant (with those prefixes) in the plan.
        """
        if self.plan is None:
            raise ValueError("constants: they are a plan's entries with value=; this has no plan")
        constants = {
            key: e.value
            for key, e in self.plan.items()
            if e.is_constant and (not prefixes or key.startswith(prefixes))
        }
        if not constants:
            raise ValueError(f"constants: the plan has no entry with value= under {prefixes}")
        for key, value in constants.items():
            self.value(key, value)
        return constants

    def skipped(
        self: _Recording,
        names: str | Iterable[str],
        *,
        why: str,
        text: str | float = float("nan"),
        label: str = "none",
    ) -> None:
        """Glue what this run does not compute, with the reason: each glue name gets ``text``
        (NaN by default, for a number) and is marked unchecked with ``why``.

        Parameters
        ----------
        names : str or iterable of str
            Glue names; a key of the plan stands for all its glue names (those of its labels
            and texts get ``label``; a key glued by a function is refused: name its glue).
        why : str
            Why the values are not computed (e.g. ``"not computed: nonlinear_runs = 0"``).
        text : str or float
            What the prose shows for a number: NaN by default.
        label : str
            What the prose shows for a label glued by a planned key.

        Raises
        ------
        ValueError
            An empty ``why``, a glue name already used, or a planned key that glues nothing.
        """
        if not why.strip():
            raise ValueError(f"skipped {names!r}: say why they are not computed (why=)")
        for name in [names] if isinstance(names, str) else list(names):
            if self.plan is not None and name in self.plan:
                try:
                    numbers, labels = recordplan.glue_names(self.plan[name])
                except ValueError as error:
                    raise ValueError(f"skipped {name!r}: {error}") from None
                if not numbers + labels:
                    raise ValueError(f"skipped {name!r}: its plan entry glues nothing")
                for glue in numbers:
                    self.text(glue, text, why=why)
                for glue in labels:
                    self.text(glue, label, why=why)
            else:
                self.text(name, text, why=why)

    def add_data(
        self: _Recording,
        name: str,
        content: Any,
        *,
        about: str | None = None,
        context: Mapping[str, Any] | None = None,
    ) -> None:
        """Keep a table or a model for the book's data bundle (not a record: nothing compares it).

        Parameters
        ----------
        name : str
            File stem, letters, digits and ``_``; unique in this notebook.
        content : pandas.DataFrame or mapping
            A table (written as CSV, full precision, headers with their units) or a JSON-ready
            mapping (written as JSON).
        about : str, optional
            One line for the bundle's README: what the file holds, with units. By default the
            recorder's ``about[name]`` (the plan module's ``DATA``): a str, or ``about(context)``.
        context : mapping, optional
            The notebook's values that ``about(context)`` quotes.

        Raises
        ------
        ValueError
            A name used twice or not of that form, an empty ``about``, one given here that the
            plan gives too (or none from either), a context for a plain ``about``, or content of
            another kind.
        """
        if not re.fullmatch(r"[A-Za-z0-9_]+", name) or name in {
            f.rsplit(".")[0] for f in self.data
        }:
            raise ValueError(f"data name {name!r} is not [A-Za-z0-9_]+ or was already used")
        planned = self.about.get(name)
        if (about is None) == (planned is None):
            where = "both here and in the plan's DATA" if about is not None else "nowhere"
            raise ValueError(f"data {name!r}: its about= is given {where}: give it once")
        if context is not None and not callable(planned):
            raise ValueError(f"data {name!r}: context= is read by an about(context) in DATA only")
        if callable(planned):
            try:
                planned = planned(context or {})
            except KeyError as missing:
                raise ValueError(
                    f"data {name!r}: its about reads {missing} from context={sorted(context or {})}"
                ) from None
        about = about if about is not None else planned
        if not isinstance(about, str) or not about.strip():
            raise ValueError(f"data {name!r} needs a one-line description (about), got {about!r}")
        if hasattr(content, "to_csv"):
            self.data[f"{name}.csv"] = (content.to_csv(index=False, lineterminator="\n"), about)
        elif isinstance(content, Mapping):
            text = json.dumps(plain_tree(content), indent=1, ensure_ascii=False) + "\n"
            self.data[f"{name}.json"] = (text, about)
        else:
            raise ValueError(f"data {name!r} must be a DataFrame or a mapping, got {type(content)}")
