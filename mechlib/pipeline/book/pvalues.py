"""p-values and times in a chapter as the book prints them: "p < 1e-10", two digits.

A chapter's markdown quotes a p-value it glued, ``p = {glue:text}`p_dc_trad:.1e```. Far in the
tail a normal approximation says nothing more than "very small" ("p = 2.1e-126" claims a
precision it does not have), so :func:`floor_glued_p_values` writes such a quotation as
``p < 1e-10`` when the glued value (read from the executed notebook's glue outputs) is below
:data:`mechlib.pipeline.book.reportpage.P_FLOOR`; the report does the same to its cells
(:func:`mechlib.pipeline.book.reportpage.print_numbers`). In a data frame the same holds for
the cells of a p-value's row or column, and a time's cells have two significant digits (they
differ between runs and machines; :func:`print_frame`).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

from mechlib.pipeline.book.reportpage import P_FLOOR, TIME_DIGITS

#: the MIME prefix under which myst-nb's ``glue`` stores a value in a cell's outputs
GLUE_PREFIX = "application/papermill.record/"
#: "p = " followed by the text of a value glued on the same page (format spec optional)
_QUOTED_P = re.compile(r"\bp = \{glue:text\}`([A-Za-z_]\w*)(?::[^`]*)?`")


def glued_numbers(cells: list[dict[str, Any]]) -> dict[str, float]:
    """The numbers a notebook glued (key → value), from its cells' outputs."""
    found = {}
    for cell in cells:
        for out in cell.get("outputs", []):
            name = out.get("metadata", {}).get("scrapbook", {}).get("name")
            text = out.get("data", {}).get(f"{GLUE_PREFIX}text/plain")
            if name and text is not None:
                try:
                    found[name] = float(text)
                except ValueError:
                    continue
    return found


def floor_glued_p_values(cells: list[dict[str, Any]]) -> int:
    """Rewrite, in place, each markdown quotation ``p = {glue:text}`key…``` whose glued value
    is below :data:`P_FLOOR` as ``p < 1e-10``; return how many were rewritten."""
    values = glued_numbers(cells)
    count = 0

    def floor(m: re.Match[str]) -> str:
        nonlocal count
        value = values.get(m.group(1))
        if value is None or value >= P_FLOOR:
            return m.group(0)
        count += 1
        return f"p < {P_FLOOR:.0e}"

    for cell in cells:
        if cell.get("cell_type") == "markdown":
            cell["source"] = _QUOTED_P.sub(floor, "".join(cell.get("source", "")))
    return count


#: a header naming a p-value: the word "p" ("Wilcoxon p", "Wilcoxon p (param.)", "p-value")
_P_HEADER = re.compile(r"(?<![\w.])p(?:-value)?(?![\w.])")
#: a header naming a time: its unit ("µs a pose (one)", "solve time median [ms]", "[s]")
_TIME_HEADER = re.compile(r"(?<![\w.])(?:µs|ms|ns)(?![\w.])|\[s\]")
_ROW = re.compile(r"<tr\b.*?</tr>", re.S)
_CELL = re.compile(r"(<t([hd])\b[^>]*>)(.*?)(</t[hd]>)", re.S)
_FRAME = re.compile(r'<table [^>]*class="dataframe[^"]*"[^>]*>.*?</table>', re.S)


def _text(body: str) -> str:
    return " ".join(re.sub(r"<[^>]*>", " ", body).split())


def _number(body: str) -> float | None:
    try:
        return float(_text(body).replace("−", "-"))
    except ValueError:
        return None


def _p_cell(body: str) -> str:
    """A p-value's cell: ``&lt; 1e-10`` when it is below :data:`P_FLOOR`."""
    value = _number(body)
    return f"&lt; {P_FLOOR:.0e}" if value is not None and 0 <= value < P_FLOOR else body


def _time_cell(body: str) -> str:
    """A time's cell to :data:`TIME_DIGITS` significant digits (times vary between runs)."""
    value = _number(body)
    if value is None:
        return body
    rounded = float(f"{value:.{TIME_DIGITS}g}")
    return f"{rounded:,.0f}" if abs(rounded) >= 10**TIME_DIGITS else f"{rounded:g}"


def _rule(header: str) -> Callable[[str], str] | None:
    """The rule of a row's or column's cells, from its header's text."""
    if _P_HEADER.search(header):
        return _p_cell
    return _time_cell if _TIME_HEADER.search(header) else None


def print_frame(table: str) -> str:
    """A data frame's HTML as the book prints it: each p-value below :data:`P_FLOOR` as
    ``< 1e-10`` and each time to :data:`TIME_DIGITS` significant digits, in a row whose header
    names a p-value (:data:`_P_HEADER`) or a time unit (:data:`_TIME_HEADER`), and in such a
    column (any header row may name a column's; a row's own header wins)."""
    columns = {}
    for row in _ROW.findall(table):
        cells = _CELL.findall(row)
        if cells and all(kind == "h" for _, kind, _, _ in cells):
            for i, (_, _, body, _) in enumerate(cells):
                columns[i] = _rule(_text(body)) or columns.get(i)

    def fix_row(m: re.Match[str]) -> str:
        row, cells = m.group(0), _CELL.findall(m.group(0))
        if not cells or all(kind == "h" for _, kind, _, _ in cells):
            return row
        own = _rule(_text(cells[0][2])) if cells[0][1] == "h" else None
        out = []
        for i, (start, kind, body, end) in enumerate(cells):
            rule = own or columns.get(i)
            out.append(start + (rule(body) if kind == "d" and rule else body) + end)
        return row[: row.index(cells[0][0])] + "".join(out) + "</tr>"

    return _ROW.sub(fix_row, table)


def print_output_frames(outputs: list[dict[str, Any]]) -> None:
    """Apply :func:`print_frame` to every data frame of a cell's HTML outputs, in place."""
    for out in outputs:
        data = out.get("data", {})
        if "text/html" in data:
            text = "".join(data["text/html"])
            data["text/html"] = _FRAME.sub(lambda m: print_frame(m.group(0)), text)
