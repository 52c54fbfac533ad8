"""The reproduction report page (ReScience style) and its verdict summary.

Rows come from the records the notebooks wrote (:mod:`mechlib.reporting.report` builds them); this
module
only arranges them: one table per thesis chapter in the thesis's order, a count of verdicts at the
top, each row linked to the section of the chapter page that shows it.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from mechlib.pipeline import verdicts
from mechlib.pipeline.book import artefacts
from mechlib.reporting import report

#: what a claim row shows as its published value (its "ours" is evidence text, kept as written)
CLAIM = report.claim_row("", "", "", True)["published"]
#: significant digits of our values shown in the table
VALUE_DIGITS = 4
_NUMBER = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e[+-]?\d+)?(?![\w.])")


@dataclass(frozen=True)
class Chapter:
    """One thesis chapter of the report: its number, caption and pages (notebook names)."""

    number: int
    caption: str
    pages: tuple[str, ...]


@dataclass(frozen=True)
class Row:
    """A report row with the page (notebook name) that recorded it."""

    page: str
    fields: dict[str, Any]


def fmt_number(x: float, digits: int = VALUE_DIGITS) -> str:
    """``digits`` significant digits, but never fewer than the integer digits below 10⁶."""
    if x == 0 or not 1 <= abs(x) < 1e6:
        return f"{x:.{digits}g}"
    integer_digits = len(str(int(abs(x))))
    return f"{x:.{max(digits, integer_digits)}g}"


def shorten_numbers(text: str, digits: int = VALUE_DIGITS) -> str:
    """Every plain number in a value list rounded by :func:`fmt_number`; other text kept."""
    return _NUMBER.sub(lambda m: fmt_number(float(m.group(0)), digits), text)


def _escape(text: object) -> str:
    """Plain text safe inside a MyST list-table cell (no markup, no line breaks)."""
    out = str(text).replace("\n", " ")
    for ch in "\\`*_[]{}<>|$":
        out = out.replace(ch, "\\" + ch)
    return out


def chapter_table(rows: Sequence[Row], chapter: Chapter, link: Callable[[str, str], str]) -> str:
    """A MyST list-table of one chapter's rows in the thesis's order.

    Parameters
    ----------
    rows : sequence of Row
        The chapter's rows (any order).
    chapter : Chapter
        Gives the order of pages and the chapter number (see :data:`artefacts.KIND_ORDER`).
    link : callable
        ``link(page, artefact_text)`` returns the MyST link to the section showing the row.
    """

    def key(item: tuple[int, Row]) -> tuple:
        index, row = item
        found = artefacts.parse(row.fields["artefact"])
        page = chapter.pages.index(row.page) if row.page in chapter.pages else len(chapter.pages)
        return (*artefacts.sort_key(found, chapter.number), page, index)

    lines = [
        "```{list-table}",
        ":header-rows: 1",
        ":widths: 13 23 16 16 11 21",
        ":class: repro-report",
        "",
        "* - Artefact",
        "  - Quantity",
        "  - Published",
        "  - Ours",
        "  - Difference",
        "  - Verdict",
    ]
    for _, row in sorted(enumerate(rows), key=key):
        f = row.fields
        cells = verdicts.report_cells(f)
        ours = cells["ours"] if f["published"] == CLAIM else shorten_numbers(cells["ours"])
        lines += [
            f"* - {link(row.page, f['artefact'])}",
            f"  - {_escape(f['quantity'])}",
            f"  - {_escape(cells['published'])}",
            f"  - {_escape(ours)}",
            f"  - {_escape(cells['difference'])}",
            f"  - {_escape(cells['verdict'])}",
        ]
    lines.append("```")
    return "\n".join(lines)
