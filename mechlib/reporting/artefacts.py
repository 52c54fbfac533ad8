"""Thesis artefacts named in headings and report rows ("Table 3", "Figs 6–7", "Eqs 6–9").

A report row names its artefact as text; a notebook's headings name the artefacts their section
shows. Parsing both into ``(kind, number)`` pairs lets the report sort rows in the thesis's order
and link each row to the section that shows it, without any list of sections typed by hand.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass

Artefact = tuple[str, int]

#: The reproduction report's order inside each thesis chapter (issue 16, ReScience style):
#: chapter 2 lists Tables 1–5, then Figs 2–8, then Eqs 6–9; chapter 3 Figs 10–14, then Tables 6–8.
KIND_ORDER = {2: ("table", "fig", "eq"), 3: ("fig", "table", "eq")}
KIND_NAMES = {"table": "Table", "fig": "Fig", "eq": "Eq"}
_KIND_WORDS = {
    "table": "table",
    "tables": "table",
    "fig": "fig",
    "figs": "fig",
    "figure": "fig",
    "figures": "fig",
    "eq": "eq",
    "eqs": "eq",
}
_NUMBERS = r"\d+(?:\s*(?:[–—-]|,|and|&)\s*\d+)*"
_REF = re.compile(rf"\b(Tables?|Figs?|Figures?|Eqs?)\.?\s+({_NUMBERS})", re.IGNORECASE)
#: a range such as "2–40" is a typo beyond this many artefacts
_MAX_RANGE = 20


def parse(text: str) -> list[Artefact]:
    """The artefacts a text names, in order of mention, without repeats.

    Parameters
    ----------
    text : str
        E.g. ``"Tables 2–3, Figs 6 and 7"`` or ``"Eq 8 — which data?"``.

    Returns
    -------
    list of (kind, number)
        ``kind`` is ``"table"``, ``"fig"`` or ``"eq"``: ``[("table", 2), ("table", 3),
        ("fig", 6), ("fig", 7)]``.

    Raises
    ------
    ValueError
        For a decreasing or implausibly long range ("Tables 5–2").
    """
    found: list[Artefact] = []
    for match in _REF.finditer(text):
        kind = _KIND_WORDS[match.group(1).lower()]
        for piece in re.split(r"\s*(?:,|and|&)\s*", match.group(2)):
            ends = [int(n) for n in re.split(r"\s*[–—-]\s*", piece.strip())]
            first, last = ends[0], ends[-1]
            if last < first or last - first > _MAX_RANGE:
                raise ValueError(
                    f"artefact range {piece!r} in {text!r} is not a short increasing range"
                )
            for number in range(first, last + 1):
                if (kind, number) not in found:
                    found.append((kind, number))
    return found


def sort_key(artefacts: Sequence[Artefact], chapter: int) -> tuple[int, int]:
    """Position of a row naming ``artefacts`` in chapter ``chapter``'s report table.

    Rows sort by their first artefact: by kind in :data:`KIND_ORDER` of the chapter, then by
    number. A row that names no artefact goes last.
    """
    order = KIND_ORDER.get(chapter, ("table", "fig", "eq"))
    if not artefacts:
        return (len(order), 0)
    kind, number = artefacts[0]
    return (order.index(kind), number)


def name(artefact: Artefact) -> str:
    """``("fig", 6)`` → ``"Fig 6"``."""
    return f"{KIND_NAMES[artefact[0]]} {artefact[1]}"


@dataclass(frozen=True)
class Section:
    """A heading of a chapter page, with the label the book gives it.

    Attributes
    ----------
    label : str
        MyST target inserted before the heading (``{ref}`` resolves it, or the build fails).
    title : str
        Heading text.
    artefacts : tuple of (kind, number)
        What the heading names.
    """

    label: str
    title: str
    artefacts: tuple[Artefact, ...]


def find_section(sections: Sequence[Section], wanted: str) -> Section | None:
    """The section that best shows ``wanted``.

    Parameters
    ----------
    sections : sequence of Section
        One page's headings, in page order.
    wanted : str
        An artefact text (``"Figs 13–14 (sensitivity)"``): the first section naming most of its
        artefacts wins. Text without artefacts (``"identification"``) matches the first heading
        containing it, ignoring case.

    Returns
    -------
    Section or None
        None when nothing matches (link to the page instead).
    """
    targets = set(parse(wanted))
    if not targets:
        needle = wanted.strip().lower()
        return next((s for s in sections if needle and needle in s.title.lower()), None)
    best, best_hits = None, 0
    for section in sections:
        hits = len(targets & set(section.artefacts))
        if hits > best_hits:
            best, best_hits = section, hits
    return best
