"""The built book (``book/_build/html``) reads offline: run after ``make book``.

Skipped when no book is built, except under ``make check-book`` (which ``make test`` runs right
after ``make book``), where ``MECHLIB_REQUIRE_BOOK=1`` turns a missing book into a failure.
"""

from __future__ import annotations

import json
import os
import re
import zipfile
from pathlib import Path

import pytest

from mechlib.paths import REPO_ROOT, records_dir
from mechlib.pipeline import bundle, pagecheck
from mechlib.pipeline.book import claimcheck, figures, htmlcheck, verdictrole
from mechlib.reporting import claimlist, verdicts

HTML = REPO_ROOT / "book" / "_build" / "html"


@pytest.fixture(scope="module")
def html_root() -> Path:
    if not (HTML / "index.html").exists():
        if os.environ.get("MECHLIB_REQUIRE_BOOK") == "1":
            pytest.fail(f"no built book at {HTML}: `make book` did not produce it")
        pytest.skip("no built book: run `make book` (make test runs these checks after it)")
    return HTML


def _text(page: Path) -> str:
    """A page's text on one line, with Sphinx's typographic apostrophes as typed ones."""
    text = " ".join(htmlcheck.parse_page(page.read_text()).text).replace("\u2019", "'")
    return re.sub(r"\s+", " ", text)


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
UNCOVERED: set[str] = set()


def test_landing_and_report_count_this_builds_rows_alike(html_root: Path) -> None:
    rows = verdicts.all_rows(records_dir())
    assert rows, f"no report rows in {records_dir()}"
    landing = (REPO_ROOT / "book" / "intro.md").read_text()
    report_md = (REPO_ROOT / "book" / "report.md").read_text()
    assert pagecheck.counts_problems(landing, report_md, rows) == []
    table = verdicts.counts_table(verdicts.category_counts(rows))
    for line in table.splitlines()[2:]:  # each count row, as the pages render it
        cells = [c.strip() for c in line.strip("|").split("|")]
        assert cells[0] in _text(html_root / "report.html")
        assert cells[0] in _text(html_root / "intro.html")
    uncovered = {
        r["artefact"]
        for r in verdicts.rollup(rows)
        if r["verdict"] == verdicts.NO_ROW and not r["counted_under"]  # Fig 7: under Fig 6
    }
    assert uncovered == UNCOVERED


def test_pages_show_no_jargon_bare_output_or_package_path(html_root: Path) -> None:
    problems = []
    for page in sorted(html_root.rglob("*.html")):
        if page.relative_to(html_root).parts[0] in ("_static", "_sources", "_images"):
            continue
        problems += pagecheck.html_problems(page.read_text(), str(page.relative_to(html_root)))
    for name in ("intro.md", "report.md", "report_beyond.md"):
        problems += pagecheck.markdown_problems((REPO_ROOT / "book" / name).read_text(), name)
    assert problems == [], "\n".join(problems)


def test_chapters_fold_computation_and_drop_bookkeeping(html_root: Path) -> None:
    for page in sorted((html_root / "chapters").glob("*.html")):
        html = page.read_text()
        assert "tag_parameters" in html, f"{page.name}: no visible parameters cell"
        assert "tag_hide-input" in html, f"{page.name}: no folded computation"
        assert "rec.save()" not in html and "record written to" not in html, page.name


def test_every_chapter_figure_has_a_numbered_caption_and_alt_text(html_root: Path) -> None:
    executed = records_dir().parent / "executed"
    problems = [
        p
        for nb in sorted(executed.glob("*.ipynb"))
        for p in figures.uncaptioned(nb.stem, json.loads(nb.read_text()))
    ]
    for page in sorted((html_root / "chapters").glob("*.html")):
        html = page.read_text()
        images = re.findall(r"<img [^>]*>", html)
        captioned = re.findall(r"<figure[^>]*>\s*<img [^>]*>\s*<figcaption>", html)
        if len(captioned) != len(images):
            problems.append(f"{page.name}: {len(images) - len(captioned)} figures without caption")
        problems += [
            f"{page.name}: alt text {alt!r} is a file name"
            for alt in re.findall(r'<img [^>]*alt="([^"]*)"', html)
            if not alt or alt.endswith((".png", ".svg")) or "/" in alt
        ]
    assert problems == [], "\n".join(problems)


def test_every_generated_page_says_how_it_was_built(html_root: Path) -> None:
    pages = [html_root / "intro.html", html_root / "report.html", html_root / "report_beyond.html"]
    pages += sorted((html_root / "chapters").glob("*.html"))
    pages += sorted((html_root / "generated").glob("*.html"))
    for page in pages:
        text = _text(page)
        assert "commit " in text and "processor: " in text, f"{page.name}: no provenance"


def test_the_data_bundle_is_linked_and_holds_every_record(html_root: Path) -> None:
    found = sorted(html_root.glob(f"_downloads/*/{bundle.NAME}"))
    assert len(found) == 1, f"no single {bundle.NAME} in {html_root / '_downloads'}"
    assert bundle.NAME in (html_root / "intro.html").read_text()
    with zipfile.ZipFile(found[0]) as archive:
        names = set(archive.namelist())
        for record in sorted(records_dir().glob("*.json")):
            assert f"records/{record.name}" in names, record.name
            assert archive.read(f"records/{record.name}") == record.read_bytes()
    assert {"thesis/table2_printed.csv", "thesis/eq8_S_T.csv", "thesis/table7.csv"} <= names


def test_every_claim_reads_one_verdict_on_every_page_and_no_verdict_word_stands_alone(
    html_root: Path,
) -> None:
    judged = json.loads((REPO_ROOT / "book" / verdictrole.CLAIMS_FILE).read_text())
    # a build with the default parameters judges every claim of the registry
    assert sorted(judged) == sorted(claimlist.CLAIMS)
    pages = {
        str(page.relative_to(html_root)): page.read_text()
        for page in sorted(html_root.rglob("*.html"))
        if page.relative_to(html_root).parts[0] not in ("_static", "_sources", "_images")
    }
    problems = claimcheck.claim_problems(pages, judged)
    assert problems == [], "\n".join(problems)
    # the thesis's claims are quoted on their own page and in the report, ours in its appendix
    for claim_id, claim in judged.items():
        report = "report.html" if claim["source"] == "thesis" else "report_beyond.html"
        for page in (f"chapters/{claim['page']}.html", report):
            assert verdictrole.claim_class(claim_id) in pages[page], (claim_id, page)
