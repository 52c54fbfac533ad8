"""Static checks of the built HTML book: it reads offline and shows nothing of the build machine.

* no ``http(s)://`` in the ``src``/``href`` of a script, stylesheet, font, image or frame, nor in a
  ``url(...)``/``@import`` of any CSS file: the book requests nothing from the network;
* no absolute machine path and no known library warning in the text a reader sees;
* every internal link resolves: the file exists and so does its ``#fragment``.

``tests/test_book_html.py`` runs these over ``book/_build/html``.
"""

from __future__ import annotations

import re
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

from mechlib.pipeline.book.cells import KNOWN_WARNINGS

REMOTE = re.compile(r"^\s*(?:https?:)?//", re.IGNORECASE)
#: elements whose URL attributes the browser fetches by itself (an <a href> waits for a click)
FETCHED = {
    "script": ("src",),
    "link": ("href",),
    "img": ("src", "srcset"),
    "source": ("src", "srcset"),
    "iframe": ("src",),
    "embed": ("src",),
    "object": ("data",),
    "video": ("src", "poster"),
    "audio": ("src",),
    "image": ("href", "xlink:href"),
    "use": ("href", "xlink:href"),
}
CSS_REMOTE = re.compile(r"""(?:url\(\s*['"]?|@import\s+['"])\s*((?:https?:)?//[^'")\s]+)""", re.I)
MACHINE_PATH = re.compile(
    r"(?<![\w.~/:-])/(?:tmp|home|root|work|Users|var|opt|mnt|srv|private)/[\w.+-]+"
)
SKIPPED_TEXT = {"script", "style"}


class _Page(HTMLParser):
    """Collects fetched URLs, element ids, internal links and visible text of one page."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.fetched: list[tuple[str, str]] = []
        self.ids: set[str] = set()
        self.links: list[str] = []
        self.text: list[str] = []
        self.styles: list[str] = []
        self._inside: list[str] = []  # open <script>/<style> elements

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        values = {k: v or "" for k, v in attrs}
        for attr in FETCHED.get(tag, ()):
            if attr in values:
                self.fetched.append((tag, values[attr]))
        if "style" in values:
            self.styles.append(values["style"])
        if "id" in values:
            self.ids.add(values["id"])
        if tag == "a" and "name" in values:
            self.ids.add(values["name"])
        if tag == "a" and "href" in values:
            self.links.append(values["href"])
        if tag in SKIPPED_TEXT:
            self._inside.append(tag)

    def handle_endtag(self, tag: str) -> None:
        if self._inside and self._inside[-1] == tag:
            self._inside.pop()

    def handle_data(self, data: str) -> None:
        if not self._inside:
            self.text.append(data)
        elif self._inside[-1] == "style":
            self.styles.append(data)


def parse_page(html: str) -> _Page:
    """Parse one HTML page (see :class:`_Page` for what is collected)."""
    page = _Page()
    page.feed(html)
    page.close()
    return page


def remote_fetches(html: str) -> list[str]:
    """``tag url`` for every network URL the page would fetch by itself (scripts, styles,
    fonts and images), including ``url(...)`` in inline styles."""
    page = parse_page(html)
    found = [
        f"<{tag}> {url}"
        for tag, url in page.fetched
        if any(REMOTE.match(u) for u in url.split(","))
    ]
    found += [f"inline style {m.group(1)}" for s in page.styles for m in CSS_REMOTE.finditer(s)]
    return found


def css_remote_urls(css: str) -> list[str]:
    """Network URLs a stylesheet would load (``url(...)`` of fonts/images, ``@import``)."""
    return [m.group(1) for m in CSS_REMOTE.finditer(css)]


def leaks(html: str, repo_root: Path) -> list[str]:
    """Machine paths and known warnings in the text a reader sees."""
    text = " ".join(parse_page(html).text)
    found = [f"machine path {m.group(0)!r}" for m in MACHINE_PATH.finditer(text)]
    if str(repo_root) in text:
        found.append(f"repository path {str(repo_root)!r}")
    found += [f"library warning {w.pattern!r}" for w in KNOWN_WARNINGS if w.search(text)]
    return found


def broken_links(html_file: Path, root: Path, ids_of: dict[Path, set[str]]) -> list[str]:
    """Internal links of ``html_file`` whose file or ``#fragment`` does not exist under ``root``.

    ``ids_of`` caches the element ids of the pages already parsed.
    """
    problems = []
    for href in parse_page(html_file.read_text(errors="replace")).links:
        parts = urlsplit(href)
        if parts.scheme or parts.netloc or href.startswith("mailto:"):
            continue
        target = (
            (html_file.parent / unquote(parts.path)).resolve()
            if parts.path
            else html_file.resolve()
        )
        if not target.exists():
            problems.append(f"{html_file.relative_to(root)}: link {href!r} to a missing file")
            continue
        if parts.fragment and target.suffix == ".html":
            if target not in ids_of:
                ids_of[target] = parse_page(target.read_text(errors="replace")).ids
            if unquote(parts.fragment) not in ids_of[target]:
                problems.append(f"{html_file.relative_to(root)}: link {href!r} to a missing anchor")
    return problems


def check_book(html_root: Path, repo_root: Path) -> list[str]:
    """Every problem of the built book under ``html_root`` (empty when it reads offline)."""
    problems: list[str] = []
    ids_of: dict[Path, set[str]] = {}
    for css in sorted(Path(html_root).rglob("*.css")):
        problems += [
            f"{css.relative_to(html_root)}: loads {u}"
            for u in css_remote_urls(css.read_text(errors="replace"))
        ]
    for page in sorted(Path(html_root).rglob("*.html")):
        rel = page.relative_to(html_root)
        if rel.parts[0] in ("_static", "_sources"):
            continue
        html = page.read_text(errors="replace")
        problems += [f"{rel}: fetches {u}" for u in remote_fetches(html)]
        problems += [f"{rel}: {leak}" for leak in leaks(html, repo_root)]
        problems += broken_links(page, Path(html_root), ids_of)
    return problems
