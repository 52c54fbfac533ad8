"""The reproduction report page (ReScience style), its verdict summary and its appendix.

Rows come from the records the notebooks wrote (:mod:`mechlib.reporting.report` builds them); this
module only arranges them. The report holds the rows on the thesis's own values and claims: one
table per thesis chapter in the thesis's order, each row linked to the section of the chapter page
that shows it. The rows beyond the thesis (:data:`BEYOND`: our findings and values with nothing
published to compare) go to an appendix, one compact table per page of the book
(:func:`appendix_table`). In both, a p-value below :data:`P_FLOOR` reads "p < 1e-10" (a normal
approximation says nothing further out) and a time has two significant digits
(:func:`print_numbers`).
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
#: the rows beyond the thesis, printed in the appendix (the counts table's "beyond the thesis")
BEYOND = (cat.CAT_OURS, cat.CAT_COMPUTED)
#: the smallest p-value printed as a number; below it the text reads "p < 1e-10"
P_FLOOR = 1e-10
#: significant digits of a time
TIME_DIGITS = 2
_P_VALUE = re.compile(r"\bp = (\d+(?:\.\d+)?(?:e[+-]?\d+)?)")
_TIME = re.compile(r"(?<![\w.])(\d+(?:\.\d+)?(?:e[+-]?\d+)?)( ?(?:µs|ms|ns)\b)")
#: a summary of a long array (:func:`mechlib.reporting.categories.summarise`): its trailing
#: "max |x|" repeats the larger end of its range
_SUMMARY = re.compile(r"(\d+) values(?: \(([^)]*)\))? from (\S+) to (\S+)(?:, max \|x\| = \S+)?")
#: a marker in the Published cell of a row that compares no values: "(claim)", "(diagram)"
_MARKER = re.compile(r"\([a-z ]+\)")
#: the columns of a chapter's values table and of its claims-and-checks table (header, width %)
VALUE_COLUMNS = (
    ("Artefact", 11),
    ("Quantity", 22),
    ("Published", 17),
    ("Ours", 17),
    ("Difference", 12),
    ("Verdict", 21),
)
STATEMENT_COLUMNS = (("Artefact", 11), ("Claim or check", 31), ("Evidence", 38), ("Verdict", 20))
APPENDIX_COLUMNS = (
    ("Artefact", 11),
    ("Quantity or finding", 39),
    ("Ours; a finding's verdict", 50),
)
_SUMMARY_MAX = re.compile(r"(\d+ values(?: \([^)]*\))? from \S+ to \S+), max \|x\| = \S+")


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
    return f"{marked}: {_escape(print_numbers(detail))}" if detail else marked


def fmt_number(x: float, digits: int = VALUE_DIGITS) -> str:
    """``digits`` significant digits, but never fewer than the integer digits below 10⁶."""
    if x == 0 or not 1 <= abs(x) < 1e6:
        return f"{x:.{digits}g}"
    integer_digits = len(str(int(abs(x))))
    return f"{x:.{max(digits, integer_digits)}g}"


def shorten_numbers(text: str, digits: int = VALUE_DIGITS) -> str:
    """Every plain number in a value list rounded by :func:`fmt_number`; other text kept."""
    return _NUMBER.sub(lambda m: fmt_number(float(m.group(0)), digits), text)


def print_numbers(text: str) -> str:
    """``text`` as the report prints it: a p-value below :data:`P_FLOOR` as ``p < 1e-10``, a
    time (µs, ms, ns) to :data:`TIME_DIGITS` significant digits, and an array's summary without
    its ``max |x|`` (the larger end of the range it gives).

    >>> print_numbers("p = 2.1e-126; 1.6001 µs; 2.2942e+05 µs; 12 values from -1 to 3, max |x| = 3")
    'p < 1e-10; 1.6 µs; 230,000 µs; 12 values from -1 to 3'
    """

    def p_value(m: re.Match[str]) -> str:
        return f"p < {P_FLOOR:.0e}" if float(m.group(1)) < P_FLOOR else m.group(0)

    def time(m: re.Match[str]) -> str:
        rounded = float(f"{float(m.group(1)):.{TIME_DIGITS}g}")
        return (f"{rounded:,.0f}" if rounded >= 100 else f"{rounded:g}") + m.group(2)

    text = _P_VALUE.sub(p_value, text)
    text = _TIME.sub(time, text)
    return _SUMMARY_MAX.sub(r"\1", text)


def is_beyond(row: Row) -> bool:
    """Whether a row goes beyond the thesis (category in :data:`BEYOND`): the appendix prints it."""
    return row.category in BEYOND


def _escape(text: object) -> str:
    """Plain text safe inside a MyST list-table cell (no markup, no line breaks)."""
    out = str(text).replace("\n", " ")
    for ch in "\\`*_[]{}<>|$":
        out = out.replace(ch, "\\" + ch)
    return out


def is_statement(fields: dict[str, Any]) -> bool:
    """Whether a row states something rather than compares values: a claim, a check or a
    redrawn diagram (its Published cell is a marker such as ``(claim)``, its Ours the evidence)."""
    published = str(fields["published"])
    return published in STATEMENT_ROWS or bool(_MARKER.fullmatch(published))


def compact_summary(text: str, shorten: bool = True) -> str:
    """A Published/Ours cell with an array's summary made short and alike on both sides: its
    size and range to :data:`VALUE_DIGITS` digits; any other text with every number so
    shortened (:func:`shorten_numbers`) when ``shorten``, else as recorded (a published value
    keeps the digits the thesis printed).

    >>> compact_summary("72 values (12 × 6) from -7.863e+04 to 78610, max |x| = 78610")
    '12 × 6 values, -7.863e+04 to 7.861e+04'
    """
    m = _SUMMARY.fullmatch(text.strip())
    if m is None:
        return shorten_numbers(text) if shorten else text
    count, shape, low, high = m.groups()
    size = shape or f"{count}"
    low, high = (f"{float(v):.{VALUE_DIGITS}g}" for v in (low, high))
    return f"{size} values, {low} to {high}"


def significant_digits(text: str) -> int:
    """The significant digits a printed number shows ("0.0279401" → 6, "110.73" → 5)."""
    mantissa = re.split(r"[eE]", text.strip().lstrip("+-−"))[0].replace(".", "")
    return len(mantissa.lstrip("0")) or 1


def ours_cell(ours: str, published: str) -> str:
    """Our value as the report prints it: :func:`compact_summary`'d, but numbers set one for one
    against published ones keep as many significant digits as the thesis printed (so that
    "0.02794" never reads as differing from "0.0279401" in the sixth digit).

    >>> ours_cell("0.02794012", "0.0279401"), ours_cell("110.862, 57.5312", "110.73, 57.53")
    ('0.0279401', '110.86, 57.53')
    """
    mine, theirs = ours.split(", "), published.split(", ")
    numbers = all(_NUMBER.fullmatch(v.strip()) for v in [*mine, *theirs])
    if numbers and len(mine) == len(theirs):
        return ", ".join(
            fmt_number(float(v), max(significant_digits(p), VALUE_DIGITS))
            for v, p in zip(mine, theirs, strict=True)
        )
    return compact_summary(ours)


def thesis_order(rows: Sequence[Row], chapter: Chapter) -> list[Row]:
    """A chapter's rows in the thesis's order of artefacts (:data:`artefacts.KIND_ORDER`),
    then by page, then as recorded."""

    def key(item: tuple[int, Row]) -> tuple:
        index, row = item
        found = artefacts.parse(row.fields["artefact"])
        page = chapter.pages.index(row.page) if row.page in chapter.pages else len(chapter.pages)
        return (*artefacts.sort_key(found, chapter.number), page, index)

    return [row for _, row in sorted(enumerate(rows), key=key)]


def chapter_table(rows: Sequence[Row], chapter: Chapter, link: Callable[[str, str], str]) -> str:
    """MyST list-tables of one chapter's rows in the thesis's order: the compared values, then
    the claims and checks (rows whose evidence is text, :func:`is_statement`).

    Parameters
    ----------
    rows : sequence of Row
        The chapter's rows (any order).
    chapter : Chapter
        Gives the order of pages and the chapter number (see :data:`artefacts.KIND_ORDER`).
    link : callable
        ``link(page, artefact_text)`` returns the MyST link to the section showing the row.

    Returns
    -------
    str
        A values table (artefact, quantity, published, ours, difference, verdict) and a
        statements table (artefact, statement, evidence, verdict); a table with no row is left
        out.
    """
    ordered = thesis_order(rows, chapter)
    values = [r for r in ordered if not is_statement(r.fields)]
    statements = [r for r in ordered if is_statement(r.fields)]
    parts = []
    if values:
        lines = [*_table_head(VALUE_COLUMNS, "repro-report repro-values")]
        for row in values:
            f = row.fields
            cells = verdicts.report_cells(f)
            lines += [
                f"* - {link(row.page, f['artefact'])}",
                f"  - {_escape(print_numbers(f['quantity']))}",
                f"  - {_escape(print_numbers(compact_summary(cells['published'], False)))}",
                f"  - {_escape(print_numbers(ours_cell(cells['ours'], cells['published'])))}",
                f"  - {_escape(cells['difference'])}",
                f"  - {verdict_cell(f)}",
            ]
        parts.append("\n".join([*lines, "```"]))
    if statements:
        lines = [*_table_head(STATEMENT_COLUMNS, "repro-report repro-statements")]
        for row in statements:
            f = row.fields
            lines += [
                f"* - {link(row.page, f['artefact'])}",
                f"  - {_escape(print_numbers(f['quantity']))}",
                f"  - {_escape(print_numbers(verdicts.report_cells(f)['ours']))}",
                f"  - {verdict_cell(f)}",
            ]
        parts.append("\n".join([*lines, "```"]))
    return "\n\n".join(parts)


def _table_head(columns: Sequence[tuple[str, int]], classes: str) -> list[str]:
    """The opening lines of a MyST list-table: ``columns`` as (header, width in %)."""
    return [
        "```{list-table}",
        ":header-rows: 1",
        f":widths: {' '.join(str(w) for _, w in columns)}",
        f":class: {classes}",
        "",
        "* - " + "\n  - ".join(name for name, _ in columns),
    ]


def appendix_cells(fields: dict[str, Any]) -> str:
    """The Ours cell of a row beyond the thesis, in MyST: our value (with the published one it
    was set against, if any), and after it, for a finding of ours, its verdict word (a computed
    value has none: the column would hold "computed" row after row)."""
    cells = verdicts.report_cells(fields)
    published = cells["published"]
    if published in STATEMENT_ROWS:
        ours = cells["ours"]
    else:
        ours = ours_cell(cells["ours"], published)
        if published not in ("—", ""):
            ours += f" (published {compact_summary(published, False)}; {cells['difference']})"
    ours = _escape(print_numbers(ours))
    if verdicts.row_category(fields) == cat.CAT_COMPUTED:
        return ours
    verdict = verdict_cell(fields).replace(category_markup(cat.CAT_OURS), "finding", 1)
    return f"{ours} — {verdict}"


def short_artefact(text: str, page_title: str = "") -> str:
    """What the appendix's Artefact cell shows of a row's artefact: a thesis artefact as named
    ("Fig 10", "Beyond the thesis: the Eq 8 family"), else the part that tells rows of one page
    apart ("Beyond the 5R (3-RRR)" → "3-RRR", "…: lean mesh" → "lean mesh"), else "section";
    "section" too when that part only repeats words of the page's title (the heading above the
    table says it already).

    >>> short_artefact("Beyond the HexFlex (parallelogram flexure)", "A parallelogram flexure")
    'section'
    """
    if artefacts.parse(text):
        return text
    part = re.search(r"\(([^)]*)\)|: (.+)$", text)
    if part is None:
        return "section"
    short = part.group(1) or part.group(2)
    title = set(re.findall(r"[\w-]+", page_title.lower()))
    return "section" if title and set(re.findall(r"[\w-]+", short.lower())) <= title else short


def appendix_table(
    rows: Sequence[Row], link: Callable[[str, str, str], str], page_title: str = ""
) -> str:
    """A compact MyST list-table of one page's rows beyond the thesis, in the page's order.

    Parameters
    ----------
    rows : sequence of Row
        The rows, all of one page.
    link : callable
        ``link(page, artefact_text, shown_text)`` returns the MyST link to the section showing
        the row.
    page_title : str, optional
        The title of the rows' page (:func:`short_artefact` does not repeat it).

    Returns
    -------
    str
        Columns: artefact (:func:`short_artefact`, linked), quantity or finding, ours
        (:func:`appendix_cells`).
    """
    lines = _table_head(APPENDIX_COLUMNS, "repro-report repro-appendix")
    for row in rows:
        shown = short_artefact(row.fields["artefact"], page_title)
        lines += [
            f"* - {link(row.page, row.fields['artefact'], shown)}",
            f"  - {_escape(print_numbers(row.fields['quantity']))}",
            f"  - {appendix_cells(row.fields)}",
        ]
    lines.append("```")
    return "\n".join(lines)
