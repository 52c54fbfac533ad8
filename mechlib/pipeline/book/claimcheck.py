"""One verdict per claim across the book: the page check behind ``make check-book``.

Every verdict word on a page must be a quoted claim — a ``claim-verdict`` span of the
``verdict`` role (:mod:`mechlib.pipeline.book.verdictrole`), which names its claim by a class — or
part of a report category's name (a ``verdict-category`` span). This module finds, on the built
HTML pages:

* a verdict word ("supported", "not supported", "holds", "does not hold", "mixed") standing in
  the text outside those spans (prose, table or figure text; code is not read);
* a claim quoted with different words on two pages (naming both pages and both words), or with
  another word than this build's judgement (``book/generated/claims.json``).
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from html.parser import HTMLParser

from mechlib.pipeline.book.browser import VOID_ELEMENTS
from mechlib.pipeline.book.verdictrole import (
    CATEGORY_CLASS,
    CLAIM_CLASS_PREFIX,
    VERDICT_CLASS,
    claim_class,
)
from mechlib.reporting.claims import VERDICT_WORDS

#: a verdict word in running text (case-insensitive, whole words)
VERDICT_WORD = re.compile(r"\b(" + "|".join(re.escape(w) for w in VERDICT_WORDS) + r")\b", re.I)
#: elements whose text is not read: code, scripts, styles, navigation
_NOT_READ = {"script", "style", "head", "nav", "pre", "code", "svg"}
_CONTEXT = 40


class _Reader(HTMLParser):
    """Collects the quoted verdicts (class, word) and the other text of a page, with lines."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        # per open element: its tag and "", "skip", "verdict:<class>" or "category"
        self.stack: list[tuple[str, str]] = []
        self.quoted: list[tuple[int, str, str]] = []
        self.text: list[tuple[int, str]] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        if tag in VOID_ELEMENTS:
            return
        classes = (dict(attrs).get("class") or "").split()
        kind = ""
        if tag in _NOT_READ or "cell_input" in classes:
            kind = "skip"
        elif VERDICT_CLASS in classes:
            ids = [c for c in classes if c.startswith(CLAIM_CLASS_PREFIX)]
            kind = f"verdict:{ids[0] if ids else ''}"
            self.quoted.append((self.getpos()[0], kind.split(":", 1)[1], ""))
        elif CATEGORY_CLASS in classes:
            kind = "category"
        self.stack.append((tag, kind))

    def handle_endtag(self, tag: str) -> None:
        # close up to the matching element (an unclosed <p> or <li> inside it closes with it)
        tags = [t for t, _ in self.stack]
        if tag not in VOID_ELEMENTS and tag in tags:
            del self.stack[len(tags) - 1 - tags[::-1].index(tag) :]

    def handle_data(self, data: str) -> None:
        kinds = [k for _, k in self.stack]
        if "skip" in kinds or "category" in kinds:
            return
        if any(k.startswith("verdict:") for k in kinds):
            line, cls, word = self.quoted[-1]
            self.quoted[-1] = (line, cls, word + data)
            return
        self.text.append((self.getpos()[0], data))


def read_page(html: str) -> tuple[list[tuple[int, str, str]], list[tuple[int, str]]]:
    """The page's quoted verdicts ``(line, claim class, word)`` and its other text
    ``(line, text)``."""
    reader = _Reader()
    reader.feed(html)
    reader.close()
    return reader.quoted, reader.text


def stray_words(html: str, where: str) -> list[str]:
    """A problem for each verdict word that stands outside a quoted claim or a category name."""
    _, text = read_page(html)
    problems = []
    for line, data in text:
        for m in VERDICT_WORD.finditer(data):
            around = data[max(0, m.start() - _CONTEXT) : m.end() + _CONTEXT].replace("\n", " ")
            problems.append(
                f"{where}:{line}: verdict word {m.group(0)!r} outside a registered claim "
                f"(quote it with the verdict role): …{around.strip()}…"
            )
    return problems


def claim_problems(pages: Mapping[str, str], judged: Mapping[str, Mapping[str, str]]) -> list[str]:
    """Claims quoted differently on two pages or against this build's judgement, quoted claims
    the registry does not know, and stray verdict words, over ``{page: html}``.

    Parameters
    ----------
    pages : mapping
        ``{page name: HTML}``.
    judged : mapping
        ``{claim id: {"word": …, …}}`` (``book/generated/claims.json``).
    """
    ids = {claim_class(cid): cid for cid in judged}
    seen: dict[str, tuple[str, str]] = {}  # claim id -> (page, word) where first quoted
    problems = []
    for where, html in sorted(pages.items()):
        quoted, _ = read_page(html)
        for line, cls, word in quoted:
            word = word.strip()
            cid = ids.get(cls)
            if cid is None:
                problems.append(f"{where}:{line}: a verdict of no registered claim ({cls!r})")
                continue
            first = seen.setdefault(cid, (where, word))
            if word != first[1]:
                problems.append(
                    f"claim {cid!r} reads {first[1]!r} on {first[0]} and {word!r} on {where}"
                )
            if word != judged[cid]["word"]:
                problems.append(
                    f"{where}:{line}: claim {cid!r} reads {word!r}, this build judged "
                    f"{judged[cid]['word']!r}"
                )
        problems += stray_words(html, where)
    return problems
