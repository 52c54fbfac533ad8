"""Checks of the generated pages' text: jargon, debug outputs, machine paths, consistent counts.

Pure functions over text (a Markdown page, an HTML page, a notebook as a dict): each returns a
list of problems, one line each, naming where (page and line) and what; empty when the page is
clean. ``make test`` runs them over ``book/`` and ``book/_build/html``.

* Chapter text must not speak to developers: "issue", "make bench", "CI", "earlier version",
  "repository's history" (:data:`JARGON`) are refused in prose, except inside an admonition
  titled "Re-run this page" or "Re-run a chapter …" (:data:`RERUN_TITLE`), where commands
  belong. Code is not prose.
* A cell output must not be a bare number, list of numbers, boolean or string repr
  (``[110.85…, 265.29…]``, a lone ``0``, ``'yes'``): a value shown to the reader needs a label
  (a table, a sentence).
* No ``site-packages`` path, even a relative one, anywhere.
* An error relative to a pose component is in "% of full scale", the one measure the methods
  page defines (:data:`mechlib.metamodels.metrics.FULL_SCALE`): "% of range", "% of each
  component's range", "share of the range" are refused in prose (:data:`OTHER_MEASURE`), since
  a range reads as max − min.
* The landing page's counts per verdict equal the report page's and the records'.
"""

from __future__ import annotations

import bisect
import re
from collections.abc import Iterable, Mapping, Sequence
from html.parser import HTMLParser
from typing import Any

from mechlib.metamodels.metrics import FULL_SCALE
from mechlib.pipeline.book.browser import VOID_ELEMENTS
from mechlib.reporting import verdicts

#: Words a reader of the chapters should not meet: (what, pattern).
JARGON: tuple[tuple[str, re.Pattern[str]], ...] = (
    ("issue", re.compile(r"\bissues?\b", re.IGNORECASE)),
    ("make bench", re.compile(r"\bmake\s+bench\b")),
    ("CI", re.compile(r"\bCI\b")),
    ("earlier version", re.compile(r"\bearlier\s+version", re.IGNORECASE)),
    ("repository's history", re.compile(r"\brepository['’]s\s+history", re.IGNORECASE)),
)
#: the other names of an error relative to a pose component, refused for "% of full scale"
OTHER_MEASURE = re.compile(
    r"(?:%|\bper\s*cent|\bshares?)\s+of\s+(?:the\s+|each\s+|a\s+|its\s+|our\s+|their\s+|"
    r"that\s+|this\s+)?(?:[\w'’.-]+\s+){0,4}?ranges?\b",
    re.IGNORECASE,
)
JARGON += ((f"another measure than {FULL_SCALE!r}", OTHER_MEASURE),)
#: The admonition title under which commands and build words are allowed.
RERUN_TITLE = re.compile(r"re-?run\s+(this\s+page|a\s+chapter)", re.IGNORECASE)
SITE_PACKAGES = re.compile(r"site-packages")
_NUM = r"[-+]?(?:\d+(?:\.\d*)?(?:[eE][-+]?\d+)?|\.\d+|nan|inf)"
#: a Python string's repr ('yes', "a b"): what a cell shows when its last line is a str
_STRING = r"""(?:'(?:[^'\\\n]|\\.)*'|"(?:[^"\\\n]|\\.)*")"""
_SCALAR = rf"(?:{_NUM}|True|False|None|{_STRING}|np\.\w+\(\s*{_NUM}\s*\))"
#: an output that is only a number, a boolean, a string's repr or a list/tuple/array of them
BARE_OUTPUT = re.compile(
    rf"^\s*(?:{_SCALAR}|[\[(]\s*{_SCALAR}(?:\s*,\s*{_SCALAR})*\s*,?\s*[\])]|array\(.*\))\s*$",
    re.DOTALL,
)
_FENCE = re.compile(r"^\s*(`{3,}|~{3,}|:{3,})\s*(.*)$")
#: HTML elements whose text is not chapter prose
_NOT_PROSE = {"script", "style", "head", "nav", "header", "footer", "pre", "code", "svg"}
_CONTEXT = 30
#: a MyST role around a text ({category}`thesis claim supported`): its text
_ROLE = re.compile(r"\{\w+\}`([^`]*)`")


def jargon_problems(lines: Iterable[tuple[int, str]], where: str) -> list[str]:
    """A problem for each jargon word in ``(line number, prose)`` pairs (a phrase may run over
    a line break)."""
    numbers, pieces, starts, offset = [], [], [], 0
    for number, piece in lines:
        numbers.append(number)
        starts.append(offset)
        pieces.append(piece)
        offset += len(piece) + 1
    text = "\n".join(pieces)
    problems = []
    for what, pattern in JARGON:
        for match in pattern.finditer(text):
            number = numbers[bisect.bisect_right(starts, match.start()) - 1]
            start, end = max(match.start() - _CONTEXT, 0), match.end() + _CONTEXT
            context = " ".join(text[start:end].split())
            problems.append(f"{where}:{number}: {what!r} in the text: …{context}…")
    return problems


def site_package_problems(text: str, where: str) -> list[str]:
    """A problem for each line that shows a ``site-packages`` path."""
    return [
        f"{where}:{number}: a site-packages path: {line.strip()[:80]}"
        for number, line in enumerate(text.splitlines(), 1)
        if SITE_PACKAGES.search(line)
    ]


def is_bare_output(text: str) -> bool:
    """Whether a cell output is only a number, boolean, string repr or list of them (no label)."""
    return bool(text.strip()) and BARE_OUTPUT.match(text) is not None


def markdown_prose(text: str) -> list[tuple[int, str]]:
    """The prose lines of a MyST page: code blocks and the "Re-run this page" admonition left
    out, the content of other directives (tables, notes) and their options kept."""
    out, stack = [], []  # stack of (fence, keep)
    for number, line in enumerate(text.splitlines(), 1):
        match = _FENCE.match(line)
        if match and stack and match.group(1)[0] == stack[-1][0][0]:
            if len(match.group(1)) >= len(stack[-1][0]) and not match.group(2):
                stack.pop()
                continue
        if match and all(keep for _, keep in stack):
            info = match.group(2)
            rerun = info.startswith("{admonition}") and RERUN_TITLE.search(info)
            stack.append((match.group(1), info.startswith("{") and not rerun))
            continue
        if all(keep for _, keep in stack):
            out.append((number, line))
    return out


def markdown_problems(text: str, where: str) -> list[str]:
    """Jargon in the prose of a generated Markdown page, and site-packages paths anywhere."""
    return jargon_problems(markdown_prose(text), where) + site_package_problems(text, where)


class _Splitter(HTMLParser):
    """Splits an HTML page into prose (with line numbers) and cell outputs."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.prose: list[tuple[int, str]] = []
        self.outputs: list[tuple[int, str]] = []
        self.stack: list[str] = []  # per open element: "", "skip", "output" or "admonition"
        self.admonitions: list[list[Any]] = []  # [title, [(line, text)]]
        self.pending_title = False

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        if tag in VOID_ELEMENTS:
            return
        classes = (dict(attrs).get("class") or "").split()
        kind = ""
        if tag in _NOT_PROSE or "cell_input" in classes:
            kind = "skip"
        elif "cell_output" in classes:
            kind = "output"
        elif "admonition" in classes:
            kind = "admonition"
            self.admonitions.append(["", []])
        if "admonition-title" in classes:
            self.pending_title = True
        if tag == "pre" and "output" in self.stack:
            self.outputs.append((self.getpos()[0], ""))
        self.stack.append(kind)

    def handle_endtag(self, tag: str) -> None:
        if tag in VOID_ELEMENTS or not self.stack:
            return
        kind = self.stack.pop()
        if kind == "admonition":
            title, lines = self.admonitions.pop()
            if not RERUN_TITLE.search(title):
                (self.admonitions[-1][1] if self.admonitions else self.prose).extend(lines)
        self.pending_title = False if kind != "skip" else self.pending_title

    def handle_data(self, data: str) -> None:
        line = self.getpos()[0]
        if "output" in self.stack and "skip" in self.stack and self.outputs:
            self.outputs[-1] = (self.outputs[-1][0], self.outputs[-1][1] + data)
        if "skip" in self.stack or "output" in self.stack or not data.strip():
            return
        if self.admonitions:
            if self.pending_title:
                self.admonitions[-1][0] += data
            self.admonitions[-1][1].append((line, data))
        else:
            self.prose.append((line, data))


def html_problems(html: str, where: str) -> list[str]:
    """Jargon in an HTML page's prose, bare cell outputs, and site-packages paths anywhere."""
    splitter = _Splitter()
    splitter.feed(html)
    splitter.close()
    bare = [
        f"{where}:{line}: a bare output, {text.strip()[:60]!r}: give it a label or a table"
        for line, text in splitter.outputs
        if is_bare_output(text)
    ]
    return jargon_problems(splitter.prose, where) + bare + site_package_problems(html, where)


def _text(source: str | Sequence[str]) -> str:
    return source if isinstance(source, str) else "".join(source)


def notebook_problems(nb: Mapping[str, Any], where: str) -> list[str]:
    """The checks over a chapter notebook as the book shows it (cells tagged ``remove-cell``
    left out, outputs of ``remove-output`` cells too); ``line`` is the cell's index."""
    problems = []
    for index, cell in enumerate(nb.get("cells", [])):
        tags = set(cell.get("metadata", {}).get("tags", []))
        here = f"{where} cell {index}"
        if "remove-cell" in tags:
            continue
        if cell["cell_type"] == "markdown":
            problems += markdown_problems(_text(cell["source"]), here)
            continue
        if cell["cell_type"] != "code" or "remove-output" in tags:
            continue
        for output in cell.get("outputs", []):
            data = output.get("data", {})
            text = _text(output.get("text", data.get("text/plain", "")))
            if "text/plain" in data and set(data) & {"text/html", "image/png", "image/svg+xml"}:
                text = ""  # a table or figure: its text repr is not shown
            if is_bare_output(text):
                problems.append(f"{here}: a bare output, {text.strip()[:60]!r}: label it")
            problems += site_package_problems(text, here)
    return problems


def count_table(text: str) -> dict[str, int]:
    """The counts per verdict of a page (the table :func:`verdicts.counts_table` writes);
    empty when the page has none."""
    lines = text.splitlines()
    if verdicts.COUNTS_HEADER not in lines:
        return {}
    counts = {}
    for line in lines[lines.index(verdicts.COUNTS_HEADER) + 2 :]:
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        cells[0] = _ROLE.sub(r"\1", cells[0])  # a category marked by the book's role
        if cells[0] in verdicts.cat.CATEGORIES:
            counts[cells[0]] = int(cells[-1])
    return counts


def counts_problems(landing: str, report: str, rows: Sequence[verdicts.ReportRow]) -> list[str]:
    """Whether the landing page and the report page show the same counts as the records.

    Parameters
    ----------
    landing, report : str
        The two pages' Markdown.
    rows : sequence of ReportRow
        The records' rows (:func:`verdicts.load_rows`).
    """
    want = verdicts.category_counts(rows)
    problems = []
    for name, text in (("landing page", landing), ("report page", report)):
        shown = count_table(text)
        if not shown:
            problems.append(f"{name}: no table of counts per verdict ({verdicts.COUNTS_HEADER})")
            continue
        problems += [
            f"{name}: {category!r} shows {shown.get(category)} rows, the records have {n}"
            for category, n in want.items()
            if shown.get(category) != n
        ]
    return problems


def artefact_problems(rows: Sequence[verdicts.ReportRow]) -> list[str]:
    """A problem for each thesis artefact that no report row covers."""
    return [f"{name}: no report row" for name in verdicts.missing_artefacts(rows)]
