"""The parameters of a chapter as the printed book shows them: a compact table, not the cell.

A chapter's ``parameters`` cell (papermill's convention) is the one cell a reader of the HTML book
edits; on paper it is a page of code. :func:`print_cell` turns it into a markdown cell that only
the print shows (class ``print-only``, see ``book/_static/book.css``): each parameter's name and
the value it ran with, with the unit its comment opens with, two parameters a row.
"""

from __future__ import annotations

import re
from typing import Any

#: ``name = value  # comment`` at the start of a line of a parameters cell
_LINE = re.compile(r"^([A-Za-z_]\w*)\s*=\s*(.+?)(?:\s+#\s*(.*))?$")
#: units a parameter's comment may open with ("mm, plate thickness" → mm)
UNITS = ("mm", "µm", "m", "N", "MPa", "GPa", "rad", "mrad", "µrad", "s", "ms", "µs", "Hz", "%")
#: parameters a row of the printed table
PER_ROW = 2
#: the classes of the printed table's container
CLASSES = "print-only params-print"


def parameters(source: str) -> list[tuple[str, str, str]]:
    """``(name, value, unit)`` of each assignment in a parameters cell, in order.

    The unit is the first word of the line's comment when it is one of :data:`UNITS`, else "".

    >>> parameters("# one a line\\nthickness = 0.505  # mm, plate thickness\\nseed = 2010  # seed")
    [('thickness', '0.505', 'mm'), ('seed', '2010', '')]
    """
    found = []
    for line in source.splitlines():
        m = _LINE.match(line.strip())
        if not m:
            continue
        name, value, comment = m.group(1), m.group(2).strip(), m.group(3) or ""
        first = re.split(r"[,;\s]", comment.strip(), maxsplit=1)[0]
        found.append((name, value, first if first in UNITS else ""))
    return found


def _cell_text(text: str) -> str:
    """Text safe as inline code inside a MyST list-table cell."""
    return "`" + text.replace("`", "'").replace("|", "\\|") + "`"


def table(source: str) -> str:
    """The MyST of the printed parameters of a ``parameters`` cell's ``source`` ("" for none)."""
    found = parameters(source)
    if not found:
        return ""
    lines = [
        f":::{{container}} {CLASSES}",
        "**Parameters of this page's run** (the HTML book shows them as its first code cell, "
        "each with its meaning and range)",
        "",
        "```{list-table}",
        ":header-rows: 1",
        "",
        "* - " + "\n  - ".join(["Parameter", "Value"] * PER_ROW),
    ]
    for start in range(0, len(found), PER_ROW):
        cells = []
        for name, value, unit in found[start : start + PER_ROW]:
            cells += [_cell_text(name), _cell_text(value) + (f" {unit}" if unit else "")]
        cells += [""] * (2 * PER_ROW - len(cells))
        lines.append("* - " + "\n  - ".join(cells))
    return "\n".join([*lines, "```", ":::"])


def print_cell(parameters_cell: dict[str, Any]) -> dict[str, Any] | None:
    """A markdown cell holding the printed table of a ``parameters`` cell, or None when it
    assigns nothing."""
    text = table("".join(parameters_cell.get("source", "")))
    if not text:
        return None
    return {
        "cell_type": "markdown",
        "id": f"{parameters_cell.get('id', 'parameters')}-print",
        "metadata": {},
        "source": text,
    }
