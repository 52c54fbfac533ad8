"""A PDF of the built book, printed offline by headless Chromium.

``python -m mechlib.pipeline.pdf build --html DIR --out book.pdf``
    prints the book's pages in reading order (the ``rel="next"`` chain from ``index.html``) to
    one PDF. ``DIR`` is a ``singlehtml`` build (one page: the whole book, one table of contents)
    or the multi-page ``html`` build (each page printed, then joined with poppler's
    ``pdfunite``). MathJax runs before the print (``--virtual-time-budget``) from the copy
    inside the build, with the network off. Each page is printed from a copy (see
    :func:`print_copy`): links to the page itself become in-document anchors, links to files of
    the build (the data bundle) point to a copy of the file beside the PDF, and code names may
    break after their dots and underscores. The print layout itself is ``@media print`` in
    ``book/_static/book.css``.

``python -m mechlib.pipeline.pdf check --pdf book.pdf --html DIR [--min-pages N] [--max-pages N]``
    exit 1 when the PDF misses part of the book (see :mod:`mechlib.pipeline.pdfcheck`): each
    problem on a line naming the value found and the one allowed.

``python -m mechlib.pipeline.pdf tools``
    exit 0 when Chromium and poppler-utils are installed, else 3 naming what is missing.

Needs Debian's ``chromium`` (build) and ``poppler-utils``. Exit status: 0 done or passed, 1 the
PDF misses something, 2 the HTML build is missing (or lacks an image it shows), 3 a program is
missing.
"""

from __future__ import annotations

import argparse
import html
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from urllib.parse import unquote, urlsplit

from mechlib.pipeline.book import browser as chromium
from mechlib.pipeline.pdfcheck import ToolMissing, check, page_order, pdf_pages, run_tool

POPPLER = ("pdfinfo", "pdftotext", "pdfimages", "pdftohtml", "pdfunite")
# the browser flags of the HTML check (offline, root, no first-run chatter), and no page header
FLAGS = (*chromium.FLAGS, "--no-pdf-header-footer")
VIRTUAL_TIME_MS = 30000  # virtual time for the page's scripts (MathJax) before the print
PRINT_TIMEOUT_S = 300  # wall-clock limit of one page's print
LINK = re.compile(r'(<a\s[^>]*?href=")([^"]*)(")')
CODE = re.compile(r'(<span class="pre">)([^<]*)(</span>)')  # the words of inline code
# a link of the printed page to a live page of the HTML build (explorerpage.LIVE_PAGE_CLASS)
LIVE = re.compile(r'(<a class="live-page" data-page="([^"]*)" href=")#(")')
FRAME = re.compile(r'<table [^>]*class="dataframe[^"]*"[^>]*>.*?</table>', re.DOTALL)
CELL = re.compile(r"<t([hd])\b([^>]*)>(.*?)</t[hd]>", re.DOTALL)
# a data frame wider than this many characters of its font (8 pt: a portrait page's width) is
# printed on a landscape page (book.css: table.print-wide); cells wrap between words (a
# number stays whole), headers also after their underscores (header_breaks)
PORTRAIT_CHARS = 98
# up to this many it is printed portrait in a narrow face at 7 pt instead (table.print-narrow:
# Liberation Sans Narrow, which Debian's chromium recommends, sets a digit in 0.46 em, 3.2 pt:
# 160 characters take 512 of the 527 pt between the margins); a landscape page would force a
# page break before and after the table and leave the page before it part empty
NARROW_CHARS = 160


find_browser = chromium.find_browser
offline_prefix = chromium.offline_prefix


def print_page(browser: str, page: Path, out: Path, profile: Path) -> None:
    """Print one HTML page to ``out`` with headless Chromium, its scripts run first.

    Raises
    ------
    RuntimeError
        When Chromium writes no PDF.
    """
    cmd = [
        *offline_prefix(),
        browser,
        *FLAGS,
        f"--user-data-dir={profile}",
        f"--virtual-time-budget={VIRTUAL_TIME_MS}",
        f"--print-to-pdf={out}",
        page.resolve().as_uri(),
    ]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=PRINT_TIMEOUT_S, check=False)
    if not out.is_file() or out.stat().st_size == 0:
        raise RuntimeError(
            f"Chromium wrote no PDF for {page} (exit {done.returncode}): "
            f"{done.stderr.strip()[-500:]}"
        )


def local_file(page: Path, href: str) -> Path | None:
    """The file of the build a link of ``page`` names (None: a page, an anchor, a URL)."""
    parts = urlsplit(html.unescape(href))
    if parts.scheme or parts.netloc or not parts.path or parts.path.endswith(".html"):
        return None
    target = (page.parent / unquote(parts.path)).resolve()
    return target if target.is_file() else None


def frame_chars(table: str) -> int:
    """Width of a data frame in characters: each column's longest word (cells wrap between words
    in print, a header's names also after their underscores) and two characters of padding
    (column-spanning header cells are left out)."""
    widths: dict[int, int] = {}
    for row in re.findall(r"<tr\b.*?</tr>", table, re.DOTALL):
        for col, (kind, attrs, body) in enumerate(CELL.findall(row)):
            if "colspan" in attrs:
                break
            text = html.unescape(re.sub(r"<[^>]*>", " ", body))
            if kind == "h":
                text = text.replace("_", "_ ")
            wide = max(map(len, text.split() or [""]))
            widths[col] = max(widths.get(col, 0), wide + 2)
    return sum(widths.values())


def header_breaks(table: str) -> str:
    """A data frame's table with ``<wbr>`` after each underscore of its header cells, so that a
    column named ``tab_half_width`` may wrap there (:func:`frame_chars` counts it so)."""
    return re.sub(
        r"(<th\b[^>]*>)(.*?)(</th>)",
        lambda m: m.group(1) + m.group(2).replace("_", "_<wbr>") + m.group(3),
        table,
        flags=re.DOTALL,
    )


def mark_wide(m: re.Match[str]) -> str:
    """A data frame's table (:func:`header_breaks`), its class ``print-narrow`` added when it is
    wider than a page at 8 pt (:data:`PORTRAIT_CHARS`), ``print-wide`` when wider than a page
    in a narrow face at 7 pt (:data:`NARROW_CHARS`)."""
    table = header_breaks(m.group(0))
    chars = frame_chars(table)
    if chars <= PORTRAIT_CHARS:
        return table
    kind = "print-narrow" if chars <= NARROW_CHARS else "print-wide"
    return table.replace('class="dataframe', f'class="{kind} dataframe', 1)


def live_root(html_dir: Path) -> Path:
    """The multi-page HTML build a printed live-page link opens: ``html/`` beside a
    ``singlehtml`` build, else the build itself."""
    html_dir = Path(html_dir)
    beside = html_dir.parent / "html"
    return beside if html_dir.name == "singlehtml" and beside.is_dir() else html_dir


def print_copy(page: Path, pdf_dir: Path, live: Path | None = None) -> tuple[str, list[Path]]:
    """The HTML of ``page`` as printed, and the files its links need beside the PDF.

    Links to ``page`` itself (``intro.html#x``) become in-document anchors (``#x``), which
    Chromium prints as links inside the PDF; a link to a file of the build (the data bundle)
    points to the file's copy in ``pdf_dir`` (an absolute ``file:`` URI: Chromium writes no
    relative link; :func:`relative_file_links` makes it relative in the printed PDF);
    ``<wbr>`` after each dot and underscore of inline code lets a long name
    (``mechlib.doe.centered_l2``) break there in a narrow table column; a data frame wider than
    a portrait page (:func:`frame_chars`) gets the class ``print-wide``; a link to a live page
    (class ``live-page``, ``data-page`` naming it) opens that page of the HTML build ``live``
    (an absolute ``file:`` URI, made relative to the PDF by :func:`relative_file_links`).

    Parameters
    ----------
    page : Path
        The HTML page.
    pdf_dir : Path
        The folder of the PDF.
    live : Path, optional
        The multi-page HTML build (:func:`live_root`); live-page links stay as they are without.

    Returns
    -------
    str
        The HTML to print.
    list of Path
        The build's files it links to (to copy into ``pdf_dir``).
    """
    files: list[Path] = []

    def relink(m: re.Match[str]) -> str:
        href = m.group(2)
        parts = urlsplit(html.unescape(href))
        if parts.path == page.name and not (parts.scheme or parts.netloc):
            href = f"#{parts.fragment}"
        elif (target := local_file(page, href)) is not None:
            files.append(target)
            href = html.escape((pdf_dir.resolve() / target.name).as_uri())
        return f"{m.group(1)}{href}{m.group(3)}"

    text = LINK.sub(relink, page.read_text(encoding="utf-8"))
    if live is not None:
        text = LIVE.sub(
            lambda m: m.group(1) + html.escape((live.resolve() / m.group(2)).as_uri()) + m.group(3),
            text,
        )
    text = CODE.sub(
        lambda m: m.group(1) + re.sub(r"([._])", r"\1<wbr>", m.group(2)) + m.group(3), text
    )
    return FRAME.sub(mark_wide, text), files


def build(html_dir: Path, out: Path, browser: str | None = None) -> Path:
    """Print the book in ``html_dir`` to the PDF ``out``.

    Parameters
    ----------
    html_dir : Path
        A ``singlehtml`` build (one print) or a multi-page ``html`` build (one print per
        page in reading order, joined by ``pdfunite``).
    out : Path
        The PDF to write; its folder is created.
    browser : str, optional
        Chromium's path; found on ``PATH`` when not given.

    Returns
    -------
    Path
        ``out``; the files its links open (the data bundle) are copied beside it.

    Raises
    ------
    ToolMissing
        When Chromium (or ``pdfunite`` for a multi-page build) is not installed.
    """
    browser = browser or find_browser()
    if browser is None:
        raise ToolMissing(f"no Chromium found (looked for {', '.join(chromium.BROWSERS)})")
    pages = page_order(html_dir)
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        parts = [Path(tmp) / f"{i:03d}.pdf" for i in range(len(pages))]
        for i, (page, part) in enumerate(zip(pages, parts, strict=True)):
            text, files = print_copy(page, out.parent, live_root(html_dir))
            for file in files:
                shutil.copyfile(file, out.parent / file.name)
            copy = page.with_name(f".print-{page.name}")  # beside the page: its links resolve
            copy.write_text(text, encoding="utf-8")
            try:
                print_page(browser, copy, part, Path(tmp) / f"profile{i}")
            finally:
                copy.unlink()
        if len(parts) == 1:
            shutil.copyfile(parts[0], out)
        else:
            run_tool(["pdfunite", *map(str, parts), str(out)])
    relative_file_links(out)
    return out


def relative_file_links(pdf: Path) -> int:
    """Rewrite the PDF's links to files beside it (``/URI (file:///…/<dir>/name)``, all Chromium
    writes) as links relative to the PDF (``/URI (name)``), and links to files in the folder
    above it (the HTML build beside the PDF's folder: ``file:///…/_build/html/x.html``) as
    ``/URI (../html/x.html)``, so that they work wherever the PDF and its files are moved
    together; return how many were rewritten.

    The new link is padded with spaces (blanks between a dictionary's entries) to the old one's
    length, so that every object keeps its byte offset and the cross-reference table stays valid.
    """
    pdf = Path(pdf)
    data = pdf.read_bytes()
    here = pdf.parent.resolve()
    count = 0
    for folder, up, name in ((here, b"", rb"[^()/\\]+"), (here.parent, b"../", rb"[^()\\]+")):
        prefix = folder.as_uri().encode() + b"/"

        def relative(m: re.Match[bytes], up: bytes = up) -> bytes:
            old = m.group(0)
            new = b"/URI (" + up + m.group(1) + b")"
            return new + b" " * (len(old) - len(new))

        pattern = re.compile(rb"/URI \(" + re.escape(prefix) + b"(" + name + rb")\)")
        data, n = pattern.subn(relative, data)
        count += n
    if count:
        pdf.write_bytes(data)
    return count


def missing_tools() -> list[str]:
    """The programs of the PDF route that are not installed (Chromium, poppler's)."""
    missing = [] if find_browser() else ["chromium"]
    return missing + [tool for tool in POPPLER if shutil.which(tool) is None]


def main(argv: list[str] | None = None) -> int:
    """Command line: ``build``, ``check`` or ``tools`` (see the module's docstring)."""
    parser = argparse.ArgumentParser(prog="python -m mechlib.pipeline.pdf")
    sub = parser.add_subparsers(dest="command", required=True)
    b = sub.add_parser("build", help="print the HTML book to one PDF")
    b.add_argument("--html", type=Path, required=True, help="html or singlehtml build folder")
    b.add_argument("--out", type=Path, required=True)
    c = sub.add_parser("check", help="check the PDF against the HTML it was printed from")
    c.add_argument("--pdf", type=Path, required=True)
    c.add_argument("--html", type=Path, required=True)
    c.add_argument("--min-pages", type=int, default=1)
    c.add_argument("--max-pages", type=int, default=0, help="a ceiling of the page count")
    sub.add_parser(
        "tools", help="exit 3 (naming them) when programs the PDF route needs are missing"
    )
    args = parser.parse_args(argv)
    if args.command == "tools":
        missing = missing_tools()
        if missing:
            print(f"missing: {' '.join(missing)} (apt-get install chromium poppler-utils)")
        return 3 if missing else 0
    try:
        if args.command == "build":
            out = build(args.html, args.out)
            print(f"PDF: {out.resolve()} ({pdf_pages(out)} pages)")
            return 0
        problems = check(args.pdf, args.html, args.min_pages, args.max_pages)
    except ToolMissing as missing:
        print(missing, file=sys.stderr)
        return 3
    except FileNotFoundError as absent:
        print(absent, file=sys.stderr)
        return 2
    for p in problems:
        print(f"{args.pdf}: {p}")
    print(f"PDF check: {'FAILED' if problems else 'passed'} ({args.pdf})")
    return 1 if problems else 0


if __name__ == "__main__":
    raise SystemExit(main())
