"""The built book (``book/_build/html``) reads offline: run after ``make book``.

Skipped when no book is built, except under ``make check-book`` (which ``make test`` runs right
after ``make book``), where ``MECHLIB_REQUIRE_BOOK=1`` turns a missing book into a failure.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest

from mechlib.paths import REPO_ROOT, records_dir
from mechlib.pipeline import pagecheck, verdicts
from mechlib.pipeline.book import htmlcheck

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


#: Thesis artefacts no report row compares yet (the landing page shows them as "no row"): this
#: build's uncovered set must equal it, so a lost row or a newly covered artefact is noticed.
UNCOVERED = {
    "Fig 1",
    "Fig 3",
    "Fig 4",
    "Fig 5",
    "Fig 8",
    "Fig 9",
    "Fig 11",
    "Fig 12",
    "Eq 10",
    "Eq 11",
}


def test_landing_and_report_count_this_builds_rows_alike(html_root: Path) -> None:
    rows = verdicts.load_rows(records_dir())
    assert rows, f"no report rows in {records_dir()}"
    landing = (REPO_ROOT / "book" / "intro.md").read_text()
    report_md = (REPO_ROOT / "book" / "report.md").read_text()
    assert pagecheck.counts_problems(landing, report_md, rows) == []
    table = verdicts.counts_table(verdicts.category_counts(rows))
    for line in table.splitlines()[2:]:  # each count row, as the pages render it
        cells = [c.strip() for c in line.strip("|").split("|")]
        assert cells[0] in _text(html_root / "report.html")
        assert cells[0] in _text(html_root / "intro.html")
    uncovered = {r["artefact"] for r in verdicts.rollup(rows) if r["verdict"] == verdicts.NO_ROW}
    assert uncovered == UNCOVERED


def test_pages_show_no_jargon_bare_output_or_package_path(html_root: Path) -> None:
    problems = []
    for page in sorted(html_root.rglob("*.html")):
        if page.relative_to(html_root).parts[0] in ("_static", "_sources", "_images"):
            continue
        problems += pagecheck.html_problems(page.read_text(), str(page.relative_to(html_root)))
    for name in ("intro.md", "report.md"):
        problems += pagecheck.markdown_problems((REPO_ROOT / "book" / name).read_text(), name)
    assert problems == [], "\n".join(problems)


def test_chapters_fold_computation_and_drop_bookkeeping(html_root: Path) -> None:
    for page in sorted((html_root / "chapters").glob("*.html")):
        html = page.read_text()
        assert "tag_parameters" in html, f"{page.name}: no visible parameters cell"
        assert "tag_hide-input" in html, f"{page.name}: no folded computation"
        assert "rec.save()" not in html and "record written to" not in html, page.name
