"""The numbers the book's prose quotes: each must be a value the notebook recorded.

A notebook glues a number for its text through :meth:`mechlib.reporting.records.Recorder.value`,
which
records it with its tolerance and notes the glue name in the record's ``"glue"`` section (text
glued by :meth:`~mechlib.reporting.records.Recorder.text` is noted there with what it is made of,
or why
it is not checked). :func:`unchecked_glue` compares the glue roles of a page with that section,
so a number that reached the prose by a plain ``glue`` call — unchecked by the references — is
found (``tests/test_records.py``).
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable
from pathlib import Path
from typing import Any

#: A myst-nb glue role in markdown: ``{glue}`name` ``, ``{glue:text}`page.ipynb::name:.2f` ``.
GLUE_ROLE = re.compile(r"\{glue(?::\w+)?\}`([^`]+)`")


def glue_references(markdown: str) -> list[tuple[str, str]]:
    """``(page, name)`` of every glue role in ``markdown``; ``page`` is ``""`` for the page's
    own notebook, else the path before ``::``."""
    refs = []
    for body in GLUE_ROLE.findall(markdown):
        page, _, rest = body.rpartition("::")
        refs.append((page, rest.split(":", 1)[0]))
    return refs


def unchecked_glue(record: dict[str, Any], names: Iterable[str]) -> list[str]:
    """Why some of the glue ``names`` a page quotes from ``record``'s notebook are not checked.

    Returns
    -------
    list of str
        One message per name that was glued around the :class:`Recorder` (or not at all), and
        per glued name whose record key is missing; empty when every quoted number is a recorded
        value (or a text the record explains).
    """
    glued, values, problems = record.get("glue", {}), record["values"], []
    for name in sorted(set(names)):
        entry = glued.get(name)
        if entry is None:
            problems.append(f"{record['notebook']}: {name!r} is quoted but not glued by Recorder")
            continue
        keys = entry.get("key", "") or entry.get("text_of", "")
        known = record.get("timings", {}) if entry.get("timing") else values
        for key in filter(None, (k.strip() for k in keys.split(","))):
            if key not in known:
                problems.append(
                    f"{record['notebook']}: {name!r} is glued from {key!r}, not recorded"
                )
    return problems


def markdown_of(page: Path) -> str:
    """The markdown of a page: a ``.md`` file, or the markdown cells of a notebook."""
    text = Path(page).read_text()
    if Path(page).suffix != ".ipynb":
        return text
    cells = json.loads(text).get("cells", [])
    return "\n".join("".join(c["source"]) for c in cells if c.get("cell_type") == "markdown")
