"""Whether a PDF of the book holds the whole book: pages, titles, figures, typeset math.

``check(pdf, html_dir)`` compares the PDF with the HTML it was printed from and lists

* a page count outside ``[low, high]``: at least one page per ``MAX_CHARS_PER_PAGE``
  characters of the pages' text, at most ``MAX_PAGES_PER_DOCUMENT`` per book page;
* a page title (each book page's first heading) missing from the PDF's text;
* a raster figure (``<img>`` of a PNG, JPEG or GIF in a page's ``<main>``) missing from the
  PDF: every image size (width × height in pixels) must occur in ``pdfimages -list`` at least
  as often as in the HTML — Chromium embeds an image at its own pixel size;
* formulas left as TeX: ``\\(``, ``\\[`` or ``$$`` in ``pdftotext``'s output;
* for paper: code-cell toggles ("Show code cell source"); text under 7 pt or math under 5 pt
  (``MIN_FONT_PT``); a ``file:`` link to no file beside the PDF, or a file the book links to
  (the data bundle) that the PDF does not link there; near-blank pages, words broken inside a
  narrow column, captions parted from their figure and live pages with no link
  (:mod:`mechlib.pipeline.pdfpages`).

Reads the PDF with Debian's ``poppler-utils`` (``pdfinfo``, ``pdftotext``, ``pdfimages``,
``pdftohtml``).
"""

from __future__ import annotations

import base64
import html
import io
import re
import shutil
import subprocess
import unicodedata
from collections import Counter
from dataclasses import dataclass, field
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

from PIL import Image

from mechlib.pipeline import pdfpages
from mechlib.pipeline.pdfpages import parted_captions  # noqa: F401  (the check's, re-exported)

MAX_CHARS_PER_PAGE = 6000  # an A4/Letter page of 10 pt text holds fewer characters than this
MAX_PAGES_PER_DOCUMENT = 60  # a book page (chapter) printing longer than this is a runaway
RASTER = (".png", ".jpg", ".jpeg", ".gif")
RAW_MATH = re.compile(r"\\\(|\\\[|\$\$")
INLINE_MATH = re.compile(r"\\\(.*?\\\)")  # math in a title: typeset, so not compared
# the smallest text a printed page may hold; math's second-level scripts as in a 10 pt LaTeX book
MIN_FONT_PT = {"text": 7.0, "math": 5.0}
TOGGLE = re.compile(r"(?:Show|Hide) code cell (?:source|outputs?|content)")
ICON_FONTS = ("FontAwesome",)  # glyphs of icons, not text
ZOOM = 3  # pdftohtml's largest zoom: font sizes in thirds of a point
FONTSPEC = re.compile(r'<fontspec id="(\d+)" size="(-?\d+)" family="([^"]*)"')
# parts of a page that are not its content: navigation, search, sidebars, headers
SKIPPED_TAGS = ("nav", "header", "footer", "script", "style", "noscript", "template", "dialog")


class ToolMissing(RuntimeError):
    """A program the PDF route needs is not installed."""


@dataclass
class PageInfo:
    """What the check needs from one HTML page."""

    next_href: str | None = None
    refresh: str | None = None
    titles: list[str] = field(default_factory=list)
    images: list[str] = field(default_factory=list)  # src of <img> in the content
    text_chars: int = 0
    documents: int = 0  # singlehtml: <span id="document-…">, one per page but the root
    files: list[str] = field(default_factory=list)  # href of links to files (not pages)


class _PageParser(HTMLParser):
    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.info = PageInfo()
        self._skip = 0  # depth inside a skipped element
        self._main = 0  # depth inside <main>: the page's content
        self._h1: list[str] | None = None
        self._title_next = False

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        a = {k: v or "" for k, v in attrs}
        if tag == "link" and a.get("rel") == "next":
            self.info.next_href = a.get("href")
        if tag == "meta" and a.get("http-equiv", "").lower() == "refresh":
            self.info.refresh = a.get("content", "").partition("url=")[2] or None
        if a.get("id", "").startswith("document-"):
            self.info.documents += 1
            self._title_next = True  # singlehtml: the page's title is the next heading
        if tag == "main":
            self._main += 1
        if tag in SKIPPED_TAGS:
            self._skip += 1
        elif self._skip or not self._main:
            return
        elif tag == "img" and a.get("src"):
            self.info.images.append(a["src"])
        elif tag == "a" and linked_file(a.get("href", "")):
            self.info.files.append(a["href"])
        elif tag == "h1" or (tag in ("h2", "h3") and self._title_next):
            self._h1, self._title_next = [], False

    def handle_endtag(self, tag: str) -> None:
        if tag in SKIPPED_TAGS and self._skip:
            self._skip -= 1
        if tag == "main" and self._main:
            self._main -= 1
        if tag in ("h1", "h2", "h3") and self._h1 is not None:
            title = " ".join("".join(self._h1).replace("#", " ").split())
            if title and title not in self.info.titles:
                self.info.titles.append(title)
            self._h1 = None

    def handle_data(self, data: str) -> None:
        if self._skip or not self._main:
            return
        if self._h1 is not None:
            self._h1.append(data)
        self.info.text_chars += len(data.strip())


def linked_file(href: str) -> str | None:
    """The file name a relative link to a file names (None: a page, an anchor, a URL)."""
    parts = urlsplit(href)
    if parts.scheme or parts.netloc or not parts.path or parts.path.endswith(".html"):
        return None
    return unquote(parts.path).rsplit("/", 1)[-1] or None


def parse_page(html: str) -> PageInfo:
    """Reading-order link, titles, content images and text size of one HTML page."""
    parser = _PageParser()
    parser.feed(html)
    return parser.info


def page_order(html_dir: Path) -> list[Path]:
    """The book's pages in reading order: ``index.html`` (or its redirect), then ``rel=next``.

    Raises
    ------
    FileNotFoundError
        When ``html_dir`` has no ``index.html``.
    """
    page = Path(html_dir) / "index.html"
    if not page.is_file():
        raise FileNotFoundError(f"no index.html in {html_dir}: build the book first")
    refresh = parse_page(page.read_text(encoding="utf-8")).refresh
    if refresh:
        page = page.parent / unquote(urlsplit(refresh).path)
    order: list[Path] = []
    while page.is_file() and page.resolve() not in order:
        order.append(page.resolve())
        nxt = parse_page(page.read_text(encoding="utf-8")).next_href
        if not nxt:
            break
        page = page.parent / unquote(urlsplit(nxt).path)
    return order


def image_size(page: Path, src: str) -> tuple[int, int] | None:
    """Pixel size of a raster ``<img src>`` of ``page`` (None for vector or remote images).

    Raises
    ------
    FileNotFoundError
        When the image file is not in the build.
    """
    if src.startswith("data:image/"):
        header, _, payload = src.partition(",")
        if not any(t in header for t in ("png", "jpeg", "gif")):
            return None
        return Image.open(io.BytesIO(base64.b64decode(payload))).size
    parts = urlsplit(src)
    if parts.scheme or not parts.path.lower().endswith(RASTER):
        return None
    path = page.parent / unquote(parts.path)
    if not path.is_file():
        raise FileNotFoundError(f"{page.name} shows {src}, which is not in the build")
    return Image.open(path).size


@dataclass
class HtmlSummary:
    """What the book's HTML says the PDF must hold."""

    pages: int
    documents: int
    titles: list[str]
    image_sizes: Counter[tuple[int, int]]
    text_chars: int
    files: list[str] = field(default_factory=list)  # names of the files the pages link to
    words: set[str] = field(default_factory=set)  # every word of the pages' text
    live: list[str] = field(default_factory=list)  # live pages a printed page links to
    captions: list[str] = field(default_factory=list)  # the figure captions' text


def summarize_html(html_dir: Path) -> HtmlSummary:
    """Page titles, raster image sizes and text size of the book's pages in reading order."""
    sizes: Counter[tuple[int, int]] = Counter()
    titles: list[str] = []
    files: list[str] = []
    chars = documents = 0
    pages = page_order(html_dir)
    words: set[str] = set()
    live: list[str] = []
    captions: list[str] = []
    for page in pages:
        text = page.read_text(encoding="utf-8")
        info = parse_page(text)
        words |= pdfpages.book_words(html.unescape(re.sub(r"<[^>]*>", " ", text)))
        live += pdfpages.live_pages(text)
        captions += pdfpages.figure_captions(text)
        titles += [t for t in info.titles if t not in titles]
        files += [n for n in map(linked_file, info.files) if n and n not in files]
        chars += info.text_chars
        documents += info.documents + 1  # singlehtml: the root page has no marker
        sizes.update(s for s in (image_size(page, src) for src in info.images) if s)
    return HtmlSummary(len(pages), documents, titles, sizes, chars, files, words, live, captions)


def page_range(summary: HtmlSummary, min_pages: int = 1, max_pages: int = 0) -> tuple[int, int]:
    """Allowed page count ``[low, high]`` of the book's PDF (``max_pages``: a ceiling, 0 none)."""
    low = max(min_pages, 1, summary.text_chars // MAX_CHARS_PER_PAGE)
    high = MAX_PAGES_PER_DOCUMENT * summary.documents
    return low, max(low, min(high, max_pages) if max_pages else high)


def parse_pdfimages_list(listing: str) -> Counter[tuple[int, int]]:
    """Image sizes (width, height) in the output of ``pdfimages -list``, masks left out."""
    sizes: Counter[tuple[int, int]] = Counter()
    for line in listing.splitlines()[2:]:
        cols = line.split()
        if len(cols) > 4 and cols[2] == "image":
            sizes[int(cols[3]), int(cols[4])] += 1
    return sizes


def raw_math(text: str, context: int = 25) -> list[str]:
    """Snippets of ``text`` around TeX math delimiters left untypeset."""
    return [
        " ".join(text[max(m.start() - context, 0) : m.end() + context].split())
        for m in RAW_MATH.finditer(text)
    ]


def missing_titles(titles: list[str], text: str) -> list[str]:
    """Titles not found in ``text`` (whitespace- and ligature-insensitive; math left out)."""
    flat = " ".join(unicodedata.normalize("NFKC", text).split())
    return [
        title
        for title in titles
        if not all(
            " ".join(unicodedata.normalize("NFKC", chunk).split()) in flat
            for chunk in INLINE_MATH.split(title)
        )
    ]


def missing_images(
    html_sizes: Counter[tuple[int, int]], pdf_sizes: Counter[tuple[int, int]]
) -> list[str]:
    """One line per image size the PDF holds fewer times than the HTML shows it."""
    return [
        f"{w}x{h} px image: {n} in the HTML, {pdf_sizes[w, h]} in the PDF"
        for (w, h), n in sorted(html_sizes.items())
        if pdf_sizes[w, h] < n
    ]


def smallest_text(xml: str) -> dict[str, tuple[float, int, str]]:
    """Smallest font size in points, its page and its text, of ``"text"`` and of ``"math"``.

    Reads ``pdftohtml -xml -zoom 3`` output (sizes to a third of a point). Math is set in fonts
    with no name (MathJax's: Chromium embeds them as unnamed Type 3 fonts; every other font is
    a named subset, ``ABCDEF+DejaVuSans``); icon fonts are left out.
    """
    fonts: dict[str, tuple[float, str]] = {}
    smallest: dict[str, tuple[float, int, str]] = {}
    for page in re.finditer(r'<page number="(\d+)".*?</page>', xml, re.DOTALL):
        for fid, size, family in FONTSPEC.findall(page.group(0)):
            fonts[fid] = int(size) / ZOOM, family
        for fid, body in re.findall(r'<text [^>]*font="(\d+)"[^>]*>(.*?)</text>', page.group(0)):
            (size, family), words = fonts[fid], " ".join(re.sub(r"<[^>]*>", "", body).split())
            kind = "text" if "+" in family else "math"
            icon = any(name in family for name in ICON_FONTS)
            if words and not icon and size < smallest.get(kind, (1e9,))[0]:
                smallest[kind] = (size, int(page.group(1)), words)
    return smallest


def broken_links(hrefs: list[str], pdf_dir: Path, files: list[str]) -> list[str]:
    """One line per link to a file that is not a relative link to a file beside the PDF (an
    absolute ``file:`` link breaks when the PDF moves), or a linked file not linked."""
    where = Path(pdf_dir).resolve()
    targets = [n for h in hrefs if not h.startswith("file:") and (n := linked_file(h))]
    bad = [f"link to {h}: absolute (allowed: a link relative to the PDF)" for h in hrefs
           if h.startswith("file:")]  # fmt: skip
    bad += [f"link to {n}: no such file beside the PDF (allowed: a file in {where})" for n in
            dict.fromkeys(targets) if not (where / n).is_file()]  # fmt: skip
    return bad + [f"the book links {n}; the PDF has no link to it beside the PDF (allowed: {n})"
                  for n in files if n not in targets]  # fmt: skip


def run_tool(cmd: list[str], timeout: float = 120) -> str:
    """Standard output of a poppler program (``cmd[0]``) run on ``cmd[1:]``.

    Raises
    ------
    ToolMissing
        When the program is not installed.
    RuntimeError
        When it exits with an error.
    """
    tool = shutil.which(cmd[0])
    if tool is None:
        raise ToolMissing(f"{cmd[0]} not found: apt-get install poppler-utils")
    done = subprocess.run(
        [tool, *cmd[1:]], capture_output=True, text=True, timeout=timeout, check=False
    )
    if done.returncode:
        raise RuntimeError(f"{' '.join(cmd)} exited {done.returncode}: {done.stderr.strip()}")
    return done.stdout


def pdf_pages(pdf: Path) -> int:
    """Page count (``pdfinfo``)."""
    found = re.search(r"^Pages:\s+(\d+)", run_tool(["pdfinfo", str(pdf)]), re.MULTILINE)
    if found is None:
        raise RuntimeError(f"pdfinfo reports no page count for {pdf}")
    return int(found.group(1))


def check(pdf: Path, html_dir: Path, min_pages: int = 1, max_pages: int = 0) -> list[str]:
    """Problems of the book's PDF against its HTML (empty when it is complete).

    Parameters
    ----------
    pdf : Path
        The printed book.
    html_dir : Path
        The HTML build it was printed from (``html`` or ``singlehtml``).
    min_pages : int
        A lower bound of the page count on top of the one the text size gives.
    max_pages : int
        A ceiling of the page count (0: only the runaway bound per document).

    Returns
    -------
    list of str
        One line per problem, naming the value found and the one allowed.
    """
    summary = summarize_html(html_dir)
    problems = []
    pages = pdf_pages(pdf)
    low, high = page_range(summary, min_pages, max_pages)
    if not low <= pages <= high:
        problems.append(
            f"{pages} pages, allowed [{low}, {high}] ({summary.text_chars} characters of text "
            f"at ≤ {MAX_CHARS_PER_PAGE} a page; ≤ {MAX_PAGES_PER_DOCUMENT} pages per document, "
            f"{summary.documents} documents; ceiling {max_pages or 'none'})"
        )
    text = run_tool(["pdftotext", "-enc", "UTF-8", str(pdf), "-"])
    problems += [
        f"page title missing from the PDF text: {t!r}" for t in missing_titles(summary.titles, text)
    ]
    listing = run_tool(["pdfimages", "-list", str(pdf)])
    pdf_sizes = parse_pdfimages_list(listing)
    problems += missing_images(summary.image_sizes, pdf_sizes)
    raw = raw_math(text)
    if raw:
        problems.append(
            f"{len(raw)} TeX math delimiters left untypeset (allowed 0), e.g. {raw[0]!r}"
        )
    toggles = TOGGLE.findall(text)
    if toggles:
        problems.append(f"{len(toggles)} code-cell toggles printed ({toggles[0]!r}), allowed 0")
    xml = run_tool(["pdftohtml", "-xml", "-i", "-stdout", "-zoom", str(ZOOM), str(pdf)])
    problems += [
        f"{kind} at {pt:.2f} pt on page {n} ({words[:40]!r}), allowed ≥ {MIN_FONT_PT[kind]} pt"
        for kind, (pt, n, words) in smallest_text(xml).items()
        if pt < MIN_FONT_PT[kind]
    ]
    layout = run_tool(["pdftotext", "-bbox-layout", "-enc", "UTF-8", str(pdf), "-"])
    hrefs = [html.unescape(h) for h in re.findall(r'<a href="([^"]*)"', xml)]
    figures = pdfpages.image_pages(listing, set(summary.image_sizes))
    problems += pdfpages.layout_problems(
        layout,
        figures,
        summary.words,
        summary.live,
        hrefs,
        Path(pdf).parent,
        summary.titles,
        summary.captions,
    )
    return problems + broken_links(hrefs, Path(pdf).parent, summary.files)
