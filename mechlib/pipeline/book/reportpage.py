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

from mechlib.reporting import artefacts, report, verdicts
from mechlib.reporting import categories as cat
from mechlib.reporting.claims import CLAIM_PUBLISHED

#: what a claim's or a check's row shows as its published value (its "ours" is evidence text,
#: kept as written)
STATEMENT_ROWS = (CLAIM_PUBLISHED, report.CHECK_PUBLISHED)
#: significant digits of our values shown in the table
VALUE_DIGITS = 4
_NUMBER = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e[+-]?\d+)?(?![\w.])")


@dataclass(frozen=True)
class Chapter:
    """One thesis chapter of the report: its number, caption and pages (notebook names)."""

    number: int
    caption: str
    pages: tuple[str, ...]


#: the report row of a notebook (:class:`mechlib.reporting.verdicts.ReportRow`)
Row = verdicts.ReportRow
#: the book's roles (:mod:`mechlib.pipeline.book.verdictrole`) that set a verdict category's name
#: and a claim's verdict word apart from prose, so that the page check can tell them from it
CATEGORY_ROLE, VERDICT_ROLE = "category", "verdict"


def category_markup(category: str) -> str:
    """A verdict category's name as the book marks it (checked apart from prose)."""
    return f"{{{CATEGORY_ROLE}}}`{category}`"


def verdict_markup(claim_id: str) -> str:
    """A claim's verdict word, quoted from the claims registry by id."""
    return f"{{{VERDICT_ROLE}}}`{claim_id}`"


def verdict_cell(fields: dict[str, Any]) -> str:
    """The Verdict cell of a report row in MyST: its category (and the claim's verdict word by id,
    for a claim), then its cause or the tolerance its agreement met."""
    cells = verdicts.report_cells(fields)
    category = verdicts.row_category(fields)
    detail = cells["verdict"].removeprefix(category).removeprefix(": ")
    if fields.get("claim"):
        head = "thesis claim" if category in cat.CLAIM_CATEGORIES else category
        marked = f"{category_markup(head)}: {verdict_markup(fields['claim'])}"
    else:
        marked = category_markup(category)
    return f"{marked}: {_escape(detail)}" if detail else marked


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
        ours = cells["ours"] if f["published"] in STATEMENT_ROWS else shorten_numbers(cells["ours"])
        lines += [
            f"* - {link(row.page, f['artefact'])}",
            f"  - {_escape(f['quantity'])}",
            f"  - {_escape(cells['published'])}",
            f"  - {_escape(ours)}",
            f"  - {_escape(cells['difference'])}",
            f"  - {verdict_cell(f)}",
        ]
    lines.append("```")
    return "\n".join(lines)
