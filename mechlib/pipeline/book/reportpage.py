"""The reproduction report page (ReScience style) and its verdict summary.

Rows come from the records the notebooks wrote (:mod:`mechlib.report` builds them); this module
only arranges them: one table per thesis chapter in the thesis's order, a count of verdicts at the
top, each row linked to the section of the chapter page that shows it.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from mechlib import report
from mechlib.pipeline.book import artefacts

#: Verdict groups in the order the summary lists them: (key, label, prefix of the row verdict).
VERDICTS = (
    ("reproduced", "reproduced", report.REPRODUCED),
    ("within", "within tolerance", report.WITHIN),
    ("diverges", "diverges, with its cause", report.DIVERGES),
    ("supported", "claim supported", report.SUPPORTED),
    ("not_supported", "claim not supported", report.NOT_SUPPORTED),
    ("computed", "computed (no published value)", report.COMPUTED),
)
#: what a claim row shows as its published value (its "ours" is evidence text, kept as written)
CLAIM = report.claim_row("", "", "", True)["published"]
#: significant digits of our values and of the differences shown in the table
VALUE_DIGITS = 4
DIFF_DIGITS = 2
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


def verdict_key(verdict: str) -> str:
    """The summary group of a row's verdict text (``"diverges: …"`` → ``"diverges"``).

    Raises
    ------
    ValueError
        For a verdict that :mod:`mechlib.report` does not produce.
    """
    for key, _, prefix in sorted(VERDICTS, key=lambda v: -len(v[2])):
        if (
            verdict == prefix
            or verdict.startswith(prefix + " ")
            or verdict.startswith(prefix + ":")
        ):
            return key
    raise ValueError(f"unknown verdict {verdict!r}; known: {[v[2] for v in VERDICTS]}")


def count_verdicts(rows: Sequence[Row]) -> dict[str, int]:
    """Number of rows per verdict group, every group present (zero if none)."""
    counts = {key: 0 for key, _, _ in VERDICTS}
    for row in rows:
        counts[verdict_key(row.fields["verdict"])] += 1
    return counts


def summary_sentence(counts: dict[str, int]) -> str:
    """One sentence stating the verdict counts, e.g. for the landing page."""
    total = sum(counts.values())
    compared = total - counts["supported"] - counts["not_supported"] - counts["computed"]
    claims = counts["supported"] + counts["not_supported"]
    return (
        f"The reproduction report has {total} rows. Of the {compared} published values compared "
        f"with ours, {counts['reproduced']} are reproduced to the printed digits, "
        f"{counts['within']} agree within a stated tolerance and {counts['diverges']} diverge, "
        f"each with its cause named; of the {claims} claims of the thesis tested by computation, "
        f"{counts['supported']} are supported and {counts['not_supported']} are not; "
        f"{counts['computed']} rows are quantities the thesis does not publish, computed here."
    )


def fmt_number(x: float, digits: int = VALUE_DIGITS) -> str:
    """``digits`` significant digits, but never fewer than the integer digits below 10⁶."""
    if x == 0 or not 1 <= abs(x) < 1e6:
        return f"{x:.{digits}g}"
    integer_digits = len(str(int(abs(x))))
    return f"{x:.{max(digits, integer_digits)}g}"


def shorten_numbers(text: str, digits: int = VALUE_DIGITS) -> str:
    """Every plain number in a value list rounded by :func:`fmt_number`; other text kept."""
    return _NUMBER.sub(lambda m: fmt_number(float(m.group(0)), digits), text)


def fmt_difference(abs_diff: float | None, rel_diff: float | None) -> str:
    """Largest absolute and relative difference, two significant digits (— when none)."""
    if abs_diff is None:
        return "—"
    rel = "" if rel_diff is None else f" ({100 * rel_diff:.{DIFF_DIGITS}g} %)"
    return f"{abs_diff:.{DIFF_DIGITS}g}{rel}"


def _escape(text: object) -> str:
    """Plain text safe inside a MyST list-table cell (no markup, no line breaks)."""
    out = str(text).replace("\n", " ")
    for ch in "\\`*_[]{}<>|$":
        out = out.replace(ch, "\\" + ch)
    return out


def _verdict_cell(verdict: str) -> str:
    key = verdict_key(verdict)
    label = next(label for k, label, _ in VERDICTS if k == key)
    short = label.split(",")[0].replace(" (no published value)", "")
    prefix = next(p for k, _, p in VERDICTS if k == key)
    detail = verdict.removeprefix(prefix).lstrip(": ").strip()
    if detail.startswith("(") and detail.endswith(")"):
        detail = detail[1:-1]
    if key == "computed":
        detail = "no published value"
    text = f"{{bdg-{_BADGE[key]}}}`{short}`"
    return text + (f"\n\n    {_escape(detail)}" if detail else "")


_BADGE = {
    "reproduced": "success",
    "within": "info",
    "diverges": "warning",
    "supported": "success",
    "not_supported": "danger",
    "computed": "secondary",
}


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
        return (*artefacts.sort_key(found, chapter.number), chapter.pages.index(row.page), index)

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
        "  - Largest difference (relative)",
        "  - Verdict",
    ]
    for _, row in sorted(enumerate(rows), key=key):
        f = row.fields
        ours = f["ours"] if f["published"] == CLAIM else shorten_numbers(str(f["ours"]))
        lines += [
            f"* - {link(row.page, f['artefact'])}",
            f"  - {_escape(f['quantity'])}",
            f"  - {_escape(f['published'])}",
            f"  - {_escape(ours)}",
            f"  - {fmt_difference(f.get('max_abs_diff'), f.get('max_rel_diff'))}",
            f"  - {_verdict_cell(f['verdict'])}",
        ]
    lines.append("```")
    return "\n".join(lines)


def summary_table(rows_by_chapter: dict[int, list[Row]], chapters: Sequence[Chapter]) -> str:
    """Counts per verdict, per chapter and in total, as a Markdown table."""
    counts = {c.number: count_verdicts(rows_by_chapter.get(c.number, [])) for c in chapters}
    head = "| verdict | " + " | ".join(f"chapter {c.number}" for c in chapters) + " | total |"
    lines = [head, "|---|" + "---:|" * (len(chapters) + 1)]
    for key, label, _ in VERDICTS:
        per = [counts[c.number][key] for c in chapters]
        lines.append(f"| {label} | " + " | ".join(map(str, per)) + f" | {sum(per)} |")
    totals = [sum(counts[c.number].values()) for c in chapters]
    lines.append("| **all rows** | " + " | ".join(map(str, totals)) + f" | **{sum(totals)}** |")
    return "\n".join(lines)
