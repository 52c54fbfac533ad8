"""What a printer would waste or a reader trip over, page by page of the book's PDF.

Reads ``pdftotext -bbox-layout`` output (pages, blocks, lines, words with their boxes) and lists

* near-blank pages (:func:`sparse_pages`): a page whose text spans less than
  :data:`MIN_FILL` of its height and that holds no raster figure;
* words broken inside a narrow column (:func:`broken_words`): a line ending in a fragment that
  is no word of the book, which the next line of its block completes to one ("numeric" + "al",
  "efficienc" + "y");
* live pages of the HTML book the PDF does not link (:func:`unlinked_live_pages`);
* captions parted from their figure (:func:`parted_captions`).

:func:`mechlib.pipeline.pdfcheck.check` runs them on the printed book.
"""

from __future__ import annotations

import html
import itertools
import re
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import unquote, urlsplit

#: the smallest share of a page's height its text must span (a page with a raster image passes)
MIN_FILL = 0.2
CAPTION = re.compile(r"Figure\s+(?:[A-Z]\.)?\d+\b")  # numfig_format of book/_config.yml (B.1)
CAPTION_TOP_PT = 24.0  # a caption this close to the top margin has no figure above it
#: characters a line break may follow or precede inside a word: code names break after dots and
#: underscores (mechlib/pipeline/pdf.py), compounds at their hyphens and dashes
BREAKABLE = "._/-–—"
#: a printed link to a live page of the HTML book (mechlib/pipeline/book/explorerpage.py)
LIVE_LINK = re.compile(r'<a class="live-page" data-page="([^"]*)"')
_PAGE = re.compile(r'<page width="([\d.]+)" height="([\d.]+)">(.*?)</page>', re.S)
_LINE = re.compile(r'<line [^>]*yMin="([-\d.]+)"[^>]*yMax="([-\d.]+)"[^>]*>(.*?)</line>', re.S)
_WORD = re.compile(r"<word [^>]*>([^<]*)</word>")
_TOKEN = re.compile(r"[\w'’.-]+")


@dataclass
class Page:
    """One page of ``pdftotext -bbox-layout``: its height and its blocks of lines."""

    height: float
    blocks: list[list[tuple[float, float, list[str]]]] = field(default_factory=list)

    @property
    def lines(self) -> list[tuple[float, float, list[str]]]:
        """Every line of the page with text, on the page (not hidden above it)."""
        return [ln for b in self.blocks for ln in b if ln[2] and ln[0] >= 0]


def parse_layout(layout: str) -> list[Page]:
    """The pages of ``pdftotext -bbox-layout`` output, each line as (yMin, yMax, words)."""
    pages = []
    for _, height, body in _PAGE.findall(layout):
        page = Page(float(height))
        for block in re.findall(r"<block\b.*?</block>", body, re.S):
            page.blocks.append(
                [
                    (float(y0), float(y1), [unescape(w) for w in _WORD.findall(text)])
                    for y0, y1, text in _LINE.findall(block)
                ]
            )
        pages.append(page)
    return pages


def unescape(text: str) -> str:
    """The text of a word as pdftotext escapes it in XML."""
    return html.unescape(text)


def sparse_pages(
    pages: list[Page], image_pages: set[int], min_fill: float = MIN_FILL
) -> list[tuple[int, float]]:
    """Page number and fill of each near-blank page: its text spans less than ``min_fill`` of its
    height (first line's top to last line's bottom) and it holds no raster image."""
    sparse = []
    for n, page in enumerate(pages, start=1):
        lines = page.lines
        fill = (max(y1 for _, y1, _ in lines) - min(y0 for y0, _, _ in lines)) if lines else 0.0
        share = fill / page.height if page.height else 0.0
        if share < min_fill and n not in image_pages:
            sparse.append((n, share))
    return sparse


def image_pages(listing: str) -> set[int]:
    """The pages holding a raster image, from ``pdfimages -list`` (masks left out)."""
    return {
        int(cols[0])
        for line in listing.splitlines()[2:]
        if len(cols := line.split()) > 4 and cols[2] == "image"
    }


def book_words(text: str) -> set[str]:
    """The words of the book's text (lower case, outer punctuation stripped)."""
    return {w.strip(".'’-").lower() for w in _TOKEN.findall(text)} - {""}


def broken_words(pages: list[Page], words: set[str]) -> list[tuple[int, str]]:
    """Page and ``"fragment|rest"`` of each word broken across two lines of one block: the
    line's last word is no word of ``words`` and, joined to the next line's first word, is one.
    A break after or before a character of :data:`BREAKABLE` is allowed."""
    found = []
    for n, page in enumerate(pages, start=1):
        for block in page.blocks:
            for (_, _, this), (_, _, nxt) in itertools.pairwise(block):
                if not this or not nxt:
                    continue
                head, tail = this[-1], nxt[0]
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


def parted_captions(layout: str) -> list[tuple[int, str]]:
    """Page and first line of each caption parted from its figure (``pdftotext -bbox-layout``).

    A caption follows its figure: one that is a page's first line, within ``CAPTION_TOP_PT``
    of the highest first line of any page, has its figure on the page before (lines above
    the page, text hidden off it, are left out).
    """
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
        if f and f[0] <= top + CAPTION_TOP_PT and CAPTION.match(f[1])
    ]


def layout_problems(
    layout: str,
    image_pages: set[int],
    words: set[str],
    live: list[str],
    hrefs: list[str],
    pdf_dir: Path,
) -> list[str]:
    """Every problem of this module's checks, one line each, naming the value found and the one
    allowed."""
    pages = parse_layout(layout)
    problems = [
        f"page {n} is near-blank: its text spans {100 * share:.0f} % of its height and it holds "
        f"no figure (allowed ≥ {100 * MIN_FILL:.0f} % or a figure)"
        for n, share in sparse_pages(pages, image_pages)
    ]
    problems += [
        f"page {n}: a word broken inside a line ({pair!r}), allowed: none"
        for n, pair in broken_words(pages, words)
    ]
    problems += [
        f"page {n} begins with a caption parted from its figure ({line[:40]!r}), allowed: none"
        for n, line in parted_captions(layout)
    ]
    return problems + unlinked_live_pages(live, hrefs, pdf_dir)
