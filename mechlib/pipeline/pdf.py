"""A PDF of the built book, printed offline by headless Chromium.

``python -m mechlib.pipeline.pdf build --html DIR --out book.pdf``
    prints the book's pages in reading order (the ``rel="next"`` chain from ``index.html``) to
    one PDF. ``DIR`` is a ``singlehtml`` build (one page: the whole book, one table of contents)
    or the multi-page ``html`` build (each page printed, then joined with poppler's
    ``pdfunite``). MathJax runs before the print (``--virtual-time-budget``) from the copy
    inside the build, with the network off.

``python -m mechlib.pipeline.pdf check --pdf book.pdf --html DIR [--min-pages N]``
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
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from mechlib.pipeline.book import browser as chromium
from mechlib.pipeline.pdfcheck import ToolMissing, check, page_order, pdf_pages, run_tool

POPPLER = ("pdfinfo", "pdftotext", "pdfimages", "pdfunite")
# the browser flags of the HTML check (offline, root, no first-run chatter), and no page header
FLAGS = (*chromium.FLAGS, "--no-pdf-header-footer")
VIRTUAL_TIME_MS = 30000  # virtual time for the page's scripts (MathJax) before the print
PRINT_TIMEOUT_S = 300  # wall-clock limit of one page's print


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
        ``out``.

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
            print_page(browser, page, part, Path(tmp) / f"profile{i}")
        if len(parts) == 1:
            shutil.copyfile(parts[0], out)
        else:
            run_tool(["pdfunite", *map(str, parts), str(out)])
    return out


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
        problems = check(args.pdf, args.html, args.min_pages)
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
