"""The built book (``book/_build/html``) reads offline: run after ``make book``.

Skipped when no book is built, except under ``make check-book`` (which ``make test`` runs right
after ``make book``), where ``MECHLIB_REQUIRE_BOOK=1`` turns a missing book into a failure.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest
import yaml

from mechlib.paths import REPO_ROOT, records_dir
from mechlib.pipeline import bookbuild
from mechlib.pipeline.book import htmlcheck, reportpage

HTML = REPO_ROOT / "book" / "_build" / "html"


@pytest.fixture(scope="module")
def html_root() -> Path:
    if not (HTML / "index.html").exists():
        if os.environ.get("MECHLIB_REQUIRE_BOOK") == "1":
            pytest.fail(f"no built book at {HTML}: `make book` did not produce it")
        pytest.skip("no built book: run `make book` (make test runs these checks after it)")
    return HTML


def _text(page: Path) -> str:
    return re.sub(r"\s+", " ", " ".join(htmlcheck.parse_page(page.read_text()).text))


def test_the_book_requests_nothing_from_the_network_and_shows_no_machine_state(
    html_root: Path,
) -> None:
    problems = htmlcheck.check_book(html_root, REPO_ROOT)
    assert not problems, "\n".join(problems)


def test_mathjax_is_served_from_the_build(html_root: Path) -> None:
    for page in sorted(html_root.rglob("*.html")):
        if page.relative_to(html_root).parts[0] in ("_static", "_sources"):
            continue
        scripts = [
            src
            for tag, src in htmlcheck.parse_page(page.read_text()).fetched
            if tag == "script" and "mathjax" in src.lower()
        ]
        for src in scripts:
            assert (page.parent / src.split("?")[0]).is_file(), (
                f"{page.name}: {src} is not in the build"
            )
    assert (html_root / "_static" / "mathjax" / "tex-chtml.js").stat().st_size > 100_000


def test_the_verdict_summary_is_computed_from_this_builds_records(html_root: Path) -> None:
    chapters = bookbuild.toc_chapters(yaml.safe_load((REPO_ROOT / "book" / "_toc.yml").read_text()))
    rows = bookbuild.report_rows(records_dir(), chapters)
    every = [r for c in chapters for r in rows[c.number]]
    sentence = reportpage.summary_sentence(reportpage.count_verdicts(every))
    assert every, f"no report rows in {records_dir()}"
    assert sentence in _text(html_root / "report.html")
    assert sentence in _text(html_root / "intro.html")


def test_chapters_fold_computation_and_drop_bookkeeping(html_root: Path) -> None:
    for page in sorted((html_root / "chapters").glob("*.html")):
        html = page.read_text()
        assert "tag_parameters" in html, f"{page.name}: no visible parameters cell"
        assert "tag_hide-input" in html, f"{page.name}: no folded computation"
        assert "rec.save()" not in html and "record written to" not in html, page.name
