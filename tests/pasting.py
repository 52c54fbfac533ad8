"""A recorder whose glue is kept in a dict, for tests of record plans and glue (not a test file)."""

from __future__ import annotations

from typing import Any

from mechlib.reporting import plans
from mechlib.reporting.records import Recorder


def pasting_recorder(
    name: str, plan: dict[str, plans.Entry] | None = None
) -> tuple[Recorder, dict[str, Any]]:
    """A :class:`Recorder` of notebook ``name`` (with ``plan``) and the dict its glue goes to."""
    pasted: dict[str, Any] = {}
    return Recorder(name, paste=pasted.__setitem__, plan=plan), pasted


def planned(notebook: str) -> tuple[Recorder, dict[str, Any]]:
    """:func:`pasting_recorder` with the chapter ``notebook``'s own record plan."""
    return pasting_recorder(notebook, plans.load(notebook))
