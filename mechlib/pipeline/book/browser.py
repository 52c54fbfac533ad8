"""Open every page of the built book from ``file://`` in headless Chromium with the network off.

``python -m mechlib.pipeline check-browser --html book/_build/html --book book``
(``--screenshot PAGE=PNG`` also saves a screenshot)

For each page Chromium runs the page's scripts (``--virtual-time-budget``) and dumps the DOM. The
page's own ``_static/bookcheck.js`` writes on ``<html>`` whether MathJax finished and which
images failed to load. A page fails when

* MathJax did not finish, left a formula untypeset (a ``.math`` element without an
  ``mjx-container``, or raw ``\\(``/``\\[`` left in it) or reports an error (``mjx-merror``);
* an image failed to load;
* it shows fewer glued values (``pasted-*`` elements) than its source has ``{glue…}`` roles:
  myst-nb drops a glue reference it cannot resolve and leaves no trace in the HTML.

The network is off: Chromium runs in a network namespace of its own (``unshare -n``) where the
machine allows it (root, as in CI), and in any case sends every request to a dead proxy
(``--proxy-server=127.0.0.1:9``), so a page that needed the network fails here as it would on a
machine without one. Exit status: 0 when every page passes, 1 when one fails, 3 when no
Chromium is installed.
"""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from html.parser import HTMLParser
from pathlib import Path

from mechlib.pipeline.book import quoted

BROWSERS = ("chromium", "chromium-browser", "google-chrome")
FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--proxy-server=127.0.0.1:9",  # nothing listens there: any http(s) request fails
    "--proxy-bypass-list=<-loopback>",
)
VIRTUAL_TIME_MS = 20000
PAGE_TIMEOUT_S = 90
WINDOW = "1400,3000"
RAW_MATH = re.compile(r"\\\(|\\\[")


class _Dom(HTMLParser):
    """Collects what the checks need from a dumped DOM."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.marker: dict[str, str] = {}
        self.math_raw: list[str] = []  # text of .math elements not typeset
        self.errors = 0
        self.pasted = 0
        self._math_depth = 0  # > 0 inside an element with class "math"
        self._math_has_container = False
        self._math_text: list[str] = []
        self._stack: list[bool] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        values = {k: v or "" for k, v in attrs}
        classes = values.get("class", "").split()
        if tag == "html":
            self.marker = {k: v for k, v in values.items() if k.startswith("data-check-")}
        if tag == "mjx-merror":
            self.errors += 1
        if any(c.startswith("pasted-") for c in classes):
            self.pasted += 1
        is_math = "math" in classes and self._math_depth == 0
        if is_math:
            self._math_has_container, self._math_text = False, []
        if tag == "mjx-container" and self._math_depth:
            self._math_has_container = True
        if tag in VOID_ELEMENTS:
            return
        self._stack.append(is_math)
        self._math_depth += bool(self._math_depth) or is_math

    def handle_endtag(self, tag: str) -> None:
        if tag in VOID_ELEMENTS or not self._stack:
            return
        was_math = self._stack.pop()
        if self._math_depth:
            self._math_depth -= 1
        if was_math:
            text = "".join(self._math_text)
            if not self._math_has_container or RAW_MATH.search(text):
                self.math_raw.append(text.strip()[:60])

    def handle_data(self, data: str) -> None:
        if self._math_depth:
            self._math_text.append(data)


#: HTML elements that have no end tag
VOID_ELEMENTS = frozenset(
    {
        "area",
        "base",
        "br",
        "col",
        "embed",
        "hr",
        "img",
        "input",
        "link",
        "meta",
        "source",
        "track",
        "wbr",
    }
)


def glue_roles(source: Path) -> int:
    """Number of ``{glue…}`` roles in a page source (markdown cells only, for a notebook)."""
    return len(quoted.glue_references(quoted.markdown_of(source)))


def dom_problems(dom: str, expected_glue: int) -> list[str]:
    """What is wrong with one page's dumped DOM (empty when it reads well)."""
    parsed = _Dom()
    parsed.feed(dom)
    problems = []
    marker = parsed.marker
    if "data-check-math" not in marker:
        return ["the page's self-check (bookcheck.js) did not run: scripts failed or timed out"]
    if marker["data-check-math"] not in ("typeset", "no-math"):
        problems.append(f"math renderer: {marker['data-check-math']}")
    total, broken = (int(n) for n in marker.get("data-check-images", "0 0").split())
    if broken:
        problems.append(
            f"{broken} of {total} images failed to load: {marker.get('data-check-broken')}"
        )
    if parsed.math_raw:
        problems.append(
            f"{len(parsed.math_raw)} formulas left untypeset, e.g. {parsed.math_raw[0]!r}"
        )
    if parsed.errors:
        problems.append(f"{parsed.errors} MathJax errors (mjx-merror)")
    if parsed.pasted < expected_glue:
        problems.append(f"{expected_glue - parsed.pasted} of {expected_glue} glued values missing")
    return problems


def find_browser() -> str | None:
    """Path of a Chromium executable, or None."""
    return next((p for p in map(shutil.which, BROWSERS) if p), None)


def offline_prefix() -> list[str]:
    """``["unshare", "-n"]`` where a process may get a network namespace without any network."""
    unshare = shutil.which("unshare")
    if unshare is None:
        return []
    done = subprocess.run([unshare, "-n", "true"], capture_output=True, check=False)
    return [unshare, "-n"] if done.returncode == 0 else []


def dump_dom(browser: str, page: Path, profile: Path, screenshot: Path | None = None) -> str:
    """The DOM of ``page`` after its scripts ran (and a 1400 px wide screenshot if asked)."""
    cmd = [
        *offline_prefix(),
        browser,
        *FLAGS,
        f"--user-data-dir={profile}",
        f"--virtual-time-budget={VIRTUAL_TIME_MS}",
    ]
    if screenshot is not None:
        cmd += [f"--screenshot={screenshot}", f"--window-size={WINDOW}"]
    else:
        cmd += ["--dump-dom"]
    done = subprocess.run(
        [*cmd, page.resolve().as_uri()],
        capture_output=True,
        text=True,
        timeout=PAGE_TIMEOUT_S,
        check=False,
    )
    return done.stdout


def pages_of(html_root: Path, book: Path) -> list[tuple[Path, Path | None]]:
    """Every built page with its source in ``book`` (None for Sphinx's own pages)."""
    found = []
    for page in sorted(Path(html_root).rglob("*.html")):
        rel = page.relative_to(html_root)
        if rel.parts[0] in ("_static", "_sources", "_images"):
            continue
        stem = rel.with_suffix("")
        source = next(
            (
                Path(book) / f"{stem}{s}"
                for s in (".md", ".ipynb")
                if (Path(book) / f"{stem}{s}").exists()
            ),
            None,
        )
        found.append((page, source))
    return found


def check(html_root: Path, book: Path, browser: str, workers: int = 2) -> dict[str, list[str]]:
    """Problems per page (pages without problems are left out)."""
    pages = pages_of(html_root, book)
    if not pages:
        return {str(html_root): ["no built pages: run `make book` first"]}
    with tempfile.TemporaryDirectory() as tmp, ThreadPoolExecutor(workers) as pool:
        doms = list(
            pool.map(
                lambda i: dump_dom(browser, pages[i][0], Path(tmp) / f"p{i}"), range(len(pages))
            )
        )
    result = {}
    for (page, source), dom in zip(pages, doms, strict=True):
        problems = dom_problems(dom, glue_roles(source) if source else 0)
        if problems:
            result[str(page.relative_to(html_root))] = problems
    return result


def main(argv: list[str] | None = None) -> int:
    """Command line: check every page; optionally save screenshots (``PAGE=PNG``)."""
    parser = argparse.ArgumentParser(prog="python -m mechlib.pipeline check-browser")
    parser.add_argument("--html", type=Path, required=True)
    parser.add_argument("--book", type=Path, required=True)
    parser.add_argument("--screenshot", action="append", default=[], metavar="PAGE=PNG")
    args = parser.parse_args(argv)
    browser = find_browser()
    if browser is None:
        print(f"no Chromium found (looked for {', '.join(BROWSERS)})", file=sys.stderr)
        return 3
    problems = check(args.html, args.book, browser)
    for page, found in problems.items():
        for p in found:
            print(f"{page}: {p}")
    for spec in args.screenshot:
        page, png = spec.split("=", 1)
        with tempfile.TemporaryDirectory() as tmp:
            dump_dom(browser, args.html / page, Path(tmp), screenshot=Path(png).resolve())
        print(f"screenshot of {page}: {png}")
    n = len(pages_of(args.html, args.book))
    print(f"browser check: {n - len(problems)} of {n} pages passed" + (" " if problems else ""))
    return 1 if problems else 0


if __name__ == "__main__":
    raise SystemExit(main())
