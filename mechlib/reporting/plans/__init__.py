"""The chapters' record plans: one module per notebook, named as the notebook.

Each module holds ``PLAN: dict[str, Entry]``, every record key of its chapter spelled once with
its named tolerance (:mod:`mechlib.reporting.tolerances`), glue names and report rows
(:mod:`mechlib.reporting.report`). Beside ``PLAN`` a module may hold
``DATA: dict[str, str | about(context)]``, the one-line description of each file the notebook
keeps for the data bundle (``rec.add_data(name, table)``), ``TIMINGS: dict[str, str]``, the glue
name of each timing key (``rec.timing(key, t)``), and ``UNCHECKED: dict[str, str]``, why the text
glued under a name is not checked (``rec.text(name, text)``, a reason several texts share written
once). Every notebook builds its recorder with :func:`recorder`, which hands them all over::

    rec = plans.recorder("published_doe", registry=claimlist.claim)
    rec.value("table2.pb_rows", mapping["rows"])  # tolerance, glue and rows from the plan

A module whose name starts with ``_`` holds what several plans share (rows, texts), not a plan.

A plan module may import :mod:`mechlib.published`, the reporting modules (report, tolerances,
categories) and the constants its rows quote; the recorder itself imports none of them.
"""

from __future__ import annotations

import importlib
import re
from types import ModuleType
from typing import Any

from mechlib.reporting.recordplan import Entry, Extremes, MadeOf, Plan
from mechlib.reporting.records import Recorder

__all__ = ["Entry", "Extremes", "MadeOf", "Plan", "load", "recorder"]


def load(notebook: str) -> Plan:
    """The record plan of ``notebook`` (its module's ``PLAN``).

    Raises
    ------
    ValueError
        A name that is not a notebook's (lower-case letters, digits and ``_``, not first), or
        one whose module is missing or holds no ``PLAN``.
    """
    return _module(notebook).PLAN


def recorder(notebook: str, **kwargs: Any) -> Recorder:
    """The :class:`~mechlib.reporting.records.Recorder` of ``notebook`` with its plan module's
    ``PLAN``, ``DATA`` (as ``about``), ``TIMINGS`` (as ``timing_glue``) and ``UNCHECKED`` (as
    ``unchecked``); ``kwargs`` go to the recorder (``registry=``, ``paste=``).

    Raises
    ------
    ValueError
        As :func:`load`.
    """
    module = _module(notebook)
    return Recorder(
        notebook,
        plan=module.PLAN,
        about=getattr(module, "DATA", {}),
        timing_glue=getattr(module, "TIMINGS", {}),
        unchecked=getattr(module, "UNCHECKED", {}),
        **kwargs,
    )


def _module(notebook: str) -> ModuleType:
    if not isinstance(notebook, str) or not re.fullmatch(r"[a-z0-9][a-z0-9_]*", notebook):
        raise ValueError(
            f"notebook must be a notebook's name (lower-case letters, digits and _, not first: "
            f"a module starting with _ holds what plans share), got {notebook!r}"
        )
    try:
        module = importlib.import_module(f"{__name__}.{notebook}")
    except ModuleNotFoundError as error:
        if error.name != f"{__name__}.{notebook}":
            raise
        raise ValueError(f"no record plan for {notebook!r}: write {__name__}.{notebook}") from None
    if not hasattr(module, "PLAN"):
        raise ValueError(
            f"{__name__}.{notebook} holds no PLAN: it is not {notebook!r}'s record plan"
        )
    return module
