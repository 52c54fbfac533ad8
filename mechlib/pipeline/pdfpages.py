"""What a printer would waste or a reader trip over, page by page of the book's PDF.

Reads ``pdftotext -bbox-layout`` output (pages, blocks, lines, words with their boxes) and lists

* near-blank pages (:func:`sparse_pages`): a page whose text spans less than :data:`MIN_FILL`
  of its height and that holds no figure of the book; the last page of a book page (a chapter)
  only needs :data:`MIN_TAIL_FILL` (see :func:`sparse_pages` for why);
* words broken inside a narrow column (:func:`broken_words`): a line ending in a fragment that
  is no word of the book, which the next line of its column completes to one ("numeric" + "al",
  "efficienc" + "y");
* live pages of the HTML book the PDF does not link (:func:`unlinked_live_pages`);
* captions parted from their figure (:func:`parted_captions`).

:func:`mechlib.pipeline.pdfcheck.check` runs them on the printed book.
"""

from __future__ import annotations

import html
import re
import unicodedata
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import unquote, urlsplit

#: the smallest share of a page's height its text must span (a page with a figure passes)
MIN_FILL = 0.2
#: the smallest share the last page of a book page (a chapter's tail) must span: 5 % of a Letter
#: page is three lines of the print's 9.75 pt text; less is a blank sheet for a line or two
MIN_TAIL_FILL = 0.05
CAPTION = re.compile(r"Figure\s+(?:[A-Z]\.)?\d+\b")  # numfig_format of book/_config.yml (B.1)
#: the report, read in one sitting: at most this many pages from its title to the next page's
REPORT_TITLE, REPORT_MAX_PAGES = "Reproduction report", 15
CAPTION_TOP_PT = 24.0  # a caption this close to the top margin has no figure above it
CAPTION_CHARS = 24  # a caption's first characters compared with the HTML's ("Figure B.3 The …")
#: characters a line break may follow or precede inside a word: code names break after dots and
#: underscores (mechlib/pipeline/pdf.py), compounds at their hyphens and dashes
BREAKABLE = "._/-–—"
#: how far (pt) the next line of a column may start from a line's left edge: a table cell's
#: lines and a paragraph's lines start at one x (the book's text is set ragged right)
COLUMN_PT = 1.5
#: a printed link to a live page of the HTML book (mechlib/pipeline/book/explorerpage.py)
LIVE_LINK = re.compile(r'<a class="live-page" data-page="([^"]*)"')
_PAGE = re.compile(r'<page width="([\d.]+)" height="([\d.]+)">(.*?)</page>', re.S)
_LINE = re.compile(
    r'<line xMin="([-\d.]+)" yMin="([-\d.]+)" xMax="[-\d.]+" yMax="([-\d.]+)">(.*?)</line>', re.S
)
_WORD = re.compile(r"<word [^>]*>([^<]*)</word>")
_TOKEN = re.compile(r"[\w'’.-]+")


@dataclass(frozen=True)
class Line:
    """One line of text on a page: its left edge, top and bottom (pt) and its words."""

    x0: float
    y0: float
    y1: float
    words: tuple[str, ...]


@dataclass
class Page:
    """One page of ``pdftotext -bbox-layout``: its height and its lines of text on the page
    (lines hidden above it left out), in the order pdftotext gives them."""

    height: float
    lines: list[Line] = field(default_factory=list)

    @property
    def fill(self) -> float:
        """The share of the page's height its text spans (first line's top to last's bottom)."""
        if not self.lines or not self.height:
            return 0.0
        return (max(ln.y1 for ln in self.lines) - min(ln.y0 for ln in self.lines)) / self.height

    @property
    def text(self) -> str:
        """The page's text, top line first."""
        return " ".join(" ".join(ln.words) for ln in sorted(self.lines, key=lambda ln: ln.y0))


def parse_layout(layout: str) -> list[Page]:
    """The pages of ``pdftotext -bbox-layout`` output."""
    pages = []
    for _, height, body in _PAGE.findall(layout):
        page = Page(float(height))
        for x0, y0, y1, text in _LINE.findall(body):
            words = tuple(unescape(w) for w in _WORD.findall(text))
            if words and float(y0) >= 0:
                page.lines.append(Line(float(x0), float(y0), float(y1), words))
        pages.append(page)
    return pages


def unescape(text: str) -> str:
    """The text of a word as pdftotext escapes it in XML."""
    return html.unescape(text)


def _flat(text: str) -> str:
    return " ".join(unicodedata.normalize("NFKC", text).split()).lower()


def book_page_starts(pages: list[Page], titles: list[str]) -> set[int]:
    """The numbers of the pages on which a book page (a chapter) begins: taking the titles in
    reading order (:func:`mechlib.pipeline.pdfcheck.summarize_html`'s), the first page after
    the previous start whose text opens with the title (a later heading that repeats a title,
    as the report's appendix does, starts nothing)."""
    starts: set[int] = set()
    first = 1
    texts = [_flat(page.text) for page in pages]
    for title in (t for t in titles if t.strip()):
        head = _flat(title)[:40]
        found = next((n for n in range(first, len(pages) + 1) if texts[n - 1].startswith(head)), 0)
        if found:
            starts.add(found)
            first = found + 1
    return starts


def page_span(pages: list[Page], titles: list[str], title: str) -> int:
    """How many pages the book page ``title`` (one of ``titles``) prints on (0: not found)."""
    starts = sorted(book_page_starts(pages, titles))
    first = next((n for n in starts if _flat(pages[n - 1].text).startswith(_flat(title))), 0)
    if not first:
        return 0
    return next((n for n in starts if n > first), len(pages) + 1) - first


def sparse_pages(
    pages: list[Page],
    figure_pages: set[int],
    starts: set[int] | None = None,
    min_fill: float = MIN_FILL,
) -> list[tuple[int, float]]:
    """Page number and fill of each near-blank page.

    A page holding a figure of the book passes. Any other page must be filled with text to at
    least ``min_fill`` of its height, except the last page of a book page (the next page begins
    another, ``starts``, or it is the PDF's last page), which needs :data:`MIN_TAIL_FILL` only.
    Why: each book page starts a new sheet, as a printed book's chapters do
    (``book/_static/book.css``), so a chapter's last sheet holds whatever is left of it, a few
    lines or a full page, and that amount follows from the chapter's length, not from the
    layout; a page in the middle of a chapter that is mostly empty is a fault of the layout (a
    block that does not fit pushed whole to the next sheet, a forced break). A tail of less
    than :data:`MIN_TAIL_FILL` is still refused: a sheet for a line or two.

    Parameters
    ----------
    pages : list of Page
        The PDF's pages (:func:`parse_layout`).
    figure_pages : set of int
        The pages holding a figure of the book (:func:`image_pages`).
    starts : set of int, optional
        The pages on which a book page begins (:func:`book_page_starts`); none when not given.
    min_fill : float
        The share of its height a page's text must span.

    Returns
    -------
    list of (int, float)
        The near-blank pages and the share their text spans.
    """
    starts = starts or set()
    sparse = []
    for n, page in enumerate(pages, start=1):
        tail = n == len(pages) or n + 1 in starts
        floor = MIN_TAIL_FILL if tail else min_fill
        if page.fill < floor and n not in figure_pages:
            sparse.append((n, page.fill))
    return sparse


def image_pages(listing: str, sizes: set[tuple[int, int]] | None = None) -> set[int]:
    """The pages holding a raster image, from ``pdfimages -list`` (masks left out); with
    ``sizes``, only an image of one of those pixel sizes counts (the book's figures: Chromium
    also rasterises the shadows of boxes, which are no figure)."""
    found = set()
    for line in listing.splitlines()[2:]:
        cols = line.split()
        if len(cols) > 4 and cols[2] == "image":
            if sizes is None or (int(cols[3]), int(cols[4])) in sizes:
                found.add(int(cols[0]))
    return found


def book_words(text: str) -> set[str]:
    """The words of the book's text (lower case, outer punctuation stripped)."""
    return {w.strip(".'’-").lower() for w in _TOKEN.findall(text)} - {""}


def _next_in_column(lines: list[Line], line: Line) -> Line | None:
    """The line printed right below ``line`` in its column: the nearest line under it that
    starts at its left edge (within :data:`COLUMN_PT`) no further down than one line."""
    height = line.y1 - line.y0
    below = [
        ln
        for ln in lines
        if abs(ln.x0 - line.x0) <= COLUMN_PT and line.y0 + 0.5 * height < ln.y0 <= line.y1 + height
    ]
    return min(below, key=lambda ln: ln.y0, default=None)


def broken_words(pages: list[Page], words: set[str]) -> list[tuple[int, str]]:
    """Page and ``"fragment|rest"`` of each word broken across two lines of one column (of a
    paragraph or of a table cell, :func:`_next_in_column`): the line's last word is no word of
    ``words`` and, joined to the next line's first word, is one. A break after or before a
    character of :data:`BREAKABLE` is allowed."""
    found = []
    for n, page in enumerate(pages, start=1):
        for line in page.lines:
            nxt = _next_in_column(page.lines, line)
            if nxt is None:
                continue
            head, tail = line.words[-1], nxt.words[0]
            if head[-1] in BREAKABLE or tail[0] in BREAKABLE:
                continue
            a, joined = head.strip(".,;:()'’").lower(), (head + tail).strip(".,;:()'’").lower()
            if a and a not in words and joined in words and a.isalpha():
                found.append((n, f"{head}|{tail}"))
    return found


def live_pages(html: str) -> list[str]:
    """The live pages of the HTML book a printed page links to (``data-page`` of its links)."""
    return LIVE_LINK.findall(html)


def unlinked_live_pages(live: list[str], hrefs: list[str], pdf_dir: Path) -> list[str]:
    """One line per live page the PDF has no working link to: a link relative to the PDF that
    ends with the page's path and names an existing file."""
    problems = []
    for page in dict.fromkeys(live):
        targets = [
            h for h in hrefs if not urlsplit(h).scheme and unquote(urlsplit(h).path).endswith(page)
        ]
        if not any((Path(pdf_dir) / unquote(urlsplit(h).path)).is_file() for h in targets):
            problems.append(
                f"the printed page names the live page {page} with no working link to it "
                f"(links found: {targets or 'none'}; allowed: a link relative to the PDF)"
            )
    return problems


def figure_captions(page_html: str) -> list[str]:
    """The text of each figure caption (``<figcaption>``) of an HTML page, whitespace folded."""
    return [
        " ".join(html.unescape(re.sub(r"<[^>]*>", " ", body)).split())
        for body in re.findall(r"<figcaption\b[^>]*>(.*?)</figcaption>", page_html, re.S)
    ]


def parted_captions(layout: str, captions: Sequence[str] | None = None) -> list[tuple[int, str]]:
    """Page and first line of each caption parted from its figure (``pdftotext -bbox-layout``).

    A caption follows its figure: one that is a page's first line, within ``CAPTION_TOP_PT``
    of the highest first line of any page, has its figure on the page before (lines above
    the page, text hidden off it, are left out). A line is a caption when it reads "Figure n"
    and, given the book's ``captions`` (:func:`figure_captions`), opens like one of them: a
    sentence of the text that begins with a reference ("Figure B.37 shows …") is none.
    """
    heads = None if captions is None else {_flat(c)[:CAPTION_CHARS] for c in captions}
    firsts = []
    for page in layout.split("<page ")[1:]:
        lines = [
            (float(y), " ".join(re.findall(r"<word [^>]*>([^<]*)</word>", body)))
            for y, body in re.findall(r'<line [^>]*yMin="([-\d.]+)"[^>]*>(.*?)</line>', page, re.S)
        ]
        firsts.append(min((ln for ln in lines if ln[1] and ln[0] >= 0), default=None))
    top = min((f[0] for f in firsts if f), default=0.0)
    return [
        (n, f[1])
        for n, f in enumerate(firsts, start=1)
        if f
        and f[0] <= top + CAPTION_TOP_PT
        and CAPTION.match(f[1])
        and (heads is None or any(h.startswith(_flat(f[1])[:CAPTION_CHARS]) for h in heads))
    ]


def layout_problems(
    layout: str,
    figure_pages: set[int],
    words: set[str],
    live: list[str],
    hrefs: list[str],
    pdf_dir: Path,
    titles: Sequence[str] = (),
    captions: Sequence[str] | None = None,
) -> list[str]:
    """Every problem of this module's checks, one line each, naming the value found and the one
    allowed; ``titles`` are the book pages' titles (:func:`book_page_starts`), ``captions`` its
    figure captions (:func:`parted_captions`)."""
    pages = parse_layout(layout)
    starts = book_page_starts(pages, list(titles))
    report = page_span(pages, list(titles), REPORT_TITLE)
    problems = (
        [f"the report prints on {report} pages, allowed ≤ {REPORT_MAX_PAGES} (one sitting)"]
        if report > REPORT_MAX_PAGES
        else []
    )
    problems += [
        f"page {n} is near-blank: its text spans {100 * share:.0f} % of its height and it holds "
        f"no figure (allowed ≥ {100 * MIN_FILL:.0f} % or a figure; ≥ {100 * MIN_TAIL_FILL:.0f} % "
        "on the last page of a chapter)"
        for n, share in sparse_pages(pages, figure_pages, starts)
    ]
    problems += [
        f"page {n}: a word broken across two lines ({pair!r}), allowed: none"
        for n, pair in broken_words(pages, words)
    ]
    problems += [
        f"page {n} begins with a caption parted from its figure ({line[:40]!r}), allowed: none"
        for n, line in parted_captions(layout, captions)
    ]
    return problems + unlinked_live_pages(live, hrefs, pdf_dir)
