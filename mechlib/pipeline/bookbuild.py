"""Assemble the book's generated pages from the executed notebooks and their records.

``python -m mechlib.pipeline book --executed build/executed --records build/records --book book``

* copies every executed notebook into ``book/chapters/`` with the presentation rules of
  :mod:`mechlib.pipeline.book.cells` applied (computation folded, bookkeeping removed, machine
  paths and library warnings neutralised, headings labelled);
* writes ``book/report.md``, the reproduction report of the thesis's values and claims, and
  ``book/report_beyond.md``, its appendix of the rows beyond the thesis
  (:mod:`mechlib.pipeline.book.reportpage`), and ``book/intro.md``, the landing page
  (:mod:`mechlib.pipeline.landing`), all from the records;
* draws the thesis's Figs 1 and 9 on their pages in ``book/generated/``
  (:mod:`mechlib.pipeline.book.methods`), and writes the data bundle there
  (:mod:`mechlib.pipeline.bundle`), which the landing page links;
* ends every generated page with how it was built (:mod:`mechlib.pipeline.provenance`);
* checks that every ``file:`` entry of ``book/_toc.yml`` names an existing page, naming the
  entry that does not.

All of these are build products (git-ignored): nothing on them is typed by hand.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path
from typing import Any

import yaml

from mechlib.paths import REPO_ROOT, STORE_DIR, records_dir
from mechlib.pipeline import bundle, bundleruns, landing, provenance, storeline
from mechlib.pipeline.book import explorer, methods, reportpage, verdictrole
from mechlib.pipeline.book.cells import prepare_notebook
from mechlib.pipeline.chapters import MAIN_PARAMETERS
from mechlib.pipeline.execute import PARTIAL_SUFFIX, fe_summary_path
from mechlib.reporting import artefacts, claimlist, verdicts

REPORT_HEADER = """---
html_theme.sidebar_secondary.remove: true
---

# Reproduction report

One row per thesis artefact and compared quantity, generated from the records that the chapters'
notebooks wrote in this build (nothing on this page is typed by hand). The rows that go beyond the
thesis (our findings, and values with nothing published to compare) are counted below and listed
in the [appendix](report_beyond.md), page by page. Figures of this book are numbered B.1, B.2, …;
"Fig n" is the thesis's figure n. Each row has a verdict category: *reproduced* (our independent
computation agrees within the tolerance named after it: half a unit of the last printed digit,
round-off, or a stated one), *consistent by construction* (we fitted to the published value or
computed ours from it, so agreement is expected, not evidence), *diverges* (with the cause found
in the chapter), *inconsistency inside the thesis* (published values contradict each other),
*consistent inside the thesis* (published values set against each other agree), *not
reproduced*, a claim of the thesis (with the verdict the claims registry gives it, quoted by id,
from its parts that could fail; a part that cannot fail is shown and not counted, and a claim with
no other part is *consistent by construction*) and *redrawn* (a diagram of the thesis's method).
The difference is the largest one relative to the largest published value and, where the thesis
printed a finite number of digits, in units of half its last digit. A p-value below 1e-10 reads
"p < 1e-10", a time has two significant digits. Each artefact links to the section of the
chapter page that shows it.

"""
APPENDIX_HEADER = """---
html_theme.sidebar_secondary.remove: true
---

# Appendix: rows beyond the thesis

The rows of the [reproduction report](report.md) that go beyond the thesis, page by page in the
book's order: *our finding beyond the thesis* (a hypothesis or result of ours, with the verdict
the claims registry gives it, quoted by id; never counted with the thesis's claims) and
*computed* (a value the thesis does not publish). Generated from the records of this build, like
the report. Each artefact links to the section of the page that shows it.

"""
#: the file of the appendix page, beside ``report.md``
APPENDIX = "report_beyond"
PAGE_SUFFIXES = (".md", ".ipynb", ".rst")
_CHAPTER_CAPTION = re.compile(r"^Chapter\s+(\d+)\b")


def toc_entries(toc: dict[str, Any]) -> list[str]:
    """Every ``root`` and ``file`` entry of a jupyter-book ``_toc.yml``, in reading order."""
    found = [toc["root"]] if "root" in toc else []

    def walk(node: Any) -> None:
        if isinstance(node, dict):
            if "file" in node:
                found.append(node["file"])
            for key in ("parts", "chapters", "sections"):
                for child in node.get(key, []) or []:
                    walk(child)
        elif isinstance(node, list):
            for child in node:
                walk(child)

    walk(toc)
    return found


def missing_toc_pages(book: Path) -> list[str]:
    """Messages for ``_toc.yml`` entries that name no page (empty when all exist)."""
    toc_path = Path(book) / "_toc.yml"
    toc = yaml.safe_load(toc_path.read_text())
    problems = []
    for entry in toc_entries(toc):
        path = Path(book) / entry
        if path.suffix in PAGE_SUFFIXES and path.exists():
            continue
        if not any(path.with_name(path.name + s).exists() for s in PAGE_SUFFIXES):
            tried = ", ".join(f"{entry}{s}" for s in PAGE_SUFFIXES)
            problems.append(f"{toc_path}: entry {entry!r} names no page (looked for {tried})")
    return problems


def toc_chapters(toc: dict[str, Any]) -> list[reportpage.Chapter]:
    """The thesis chapters of the book: parts captioned "Chapter N …", with their notebook pages."""
    chapters = []
    for part in toc.get("parts", []):
        match = _CHAPTER_CAPTION.match(part.get("caption", ""))
        if not match:
            continue
        pages = tuple(
            Path(f).name
            for f in toc_entries({"chapters": part.get("chapters", [])})
            if f.startswith("chapters/")
        )
        chapters.append(reportpage.Chapter(int(match.group(1)), part["caption"], pages))
    return chapters


class Linker:
    """MyST links to the section of a chapter page that shows an artefact (else to the page)."""

    def __init__(self, sections: dict[str, list[artefacts.Section]]):
        self.sections = sections

    def __call__(self, page: str, what: str, text: str | None = None) -> str:
        if "/" in page:  # a generated page of the book (e.g. a redrawn method figure)
            return f"{{doc}}`{text or what} </{page}>`"
        section = artefacts.find_section(self.sections.get(page, []), what)
        if section is not None:
            return f"{{ref}}`{text} <{section.label}>`" if text else f"{{ref}}`{section.label}`"
        return f"{{doc}}`{text} </chapters/{page}>`" if text else f"{{doc}}`/chapters/{page}`"


def _write(path: Path, text: str) -> None:
    """Write only when the content changed (keeps Sphinx's incremental build incremental)."""
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


def copy_chapters(
    executed: Path, chapters: Path, made: str = ""
) -> dict[str, list[artefacts.Section]]:
    """Prepare every executed notebook into ``chapters``, ending with the provenance ``made``
    (:func:`provenance.text`) when given; return each page's sections."""
    chapters.mkdir(parents=True, exist_ok=True)
    sections = {}
    for nb_path in sorted(Path(executed).glob("*.ipynb")):
        if nb_path.name.endswith(PARTIAL_SUFFIX):  # a notebook still executing, or failed
            continue
        nb, sections[nb_path.stem] = prepare_notebook(
            json.loads(nb_path.read_text()), nb_path.stem, REPO_ROOT
        )
        if made:
            seconds = nb.get("metadata", {}).get("papermill", {}).get("duration")
            summary = fe_summary_path(nb_path, nb_path.stem)
            tasks = json.loads(summary.read_text()) if summary.is_file() else None
            main = MAIN_PARAMETERS.get(nb_path.stem, ())
            lines = provenance.rerun_lines(nb_path.stem, seconds, tasks, main)
            nb["cells"].append(provenance.notebook_cell(f"{made}\n{lines}"))
        _write(chapters / nb_path.name, json.dumps(nb, indent=1, ensure_ascii=False) + "\n")
    return sections


def report_rows(
    records: Path, chapters: list[reportpage.Chapter]
) -> dict[int, list[verdicts.ReportRow]]:
    """Every report row (:func:`mechlib.reporting.verdicts.all_rows`) grouped by the thesis
    chapter its page belongs to; a record of no chapter's page is named and left out."""
    chapter_of = {page: c.number for c in chapters for page in c.pages}
    chapter_of |= {
        page: ch
        for page, artefact, _ in verdicts.REDRAWN
        for k, n, ch, _ in verdicts.THESIS_ARTEFACTS
        if verdicts.artefact_name(k, n) == artefact
    }
    rows: dict[int, list[verdicts.ReportRow]] = {c.number: [] for c in chapters}
    for row in verdicts.all_rows(records):
        number = chapter_of.get(row.page)
        if number is None:
            print(f"bookbuild: {row.page} is no chapter page of _toc.yml: rows not reported")
        elif number in rows:
            rows[number].append(row)
    return rows


def report_markdown(
    rows: dict[int, list[verdicts.ReportRow]], chapters: list[reportpage.Chapter], link: Linker
) -> str:
    """The report page: rows per verdict category and a verdict per thesis artefact, then one
    table per chapter in the thesis's order."""
    every = [r for c in chapters for r in rows[c.number]]
    lines = [
        REPORT_HEADER,
        "## Summary",
        "",
        verdicts.counts_table(verdicts.category_counts(every), reportpage.category_markup),
        "",
        landing.counts_sentence(verdicts.thesis_claim_ids(every)),
        "",
        "The verdict per thesis artefact, rolled up from these rows, is on the "
        "[first page](intro.md).",
        "",
    ]
    for chapter in chapters:
        lines += [f"## {chapter.caption}", ""]
        thesis = [r for r in rows[chapter.number] if not reportpage.is_beyond(r)]
        if not thesis:
            lines += ["No rows were recorded for this chapter.", ""]
            continue
        lines += [
            reportpage.chapter_table(thesis, chapter, lambda page, what: link(page, what, what)),
            "",
        ]
        beyond = len(rows[chapter.number]) - len(thesis)
        if beyond:
            more = f"{beyond} more rows of this chapter go beyond the thesis"
            lines += [f"{more}: see the [appendix]({APPENDIX}.md).", ""]
    return "\n".join(lines)


def appendix_markdown(
    rows: dict[int, list[verdicts.ReportRow]], chapters: list[reportpage.Chapter], link: Linker
) -> str:
    """The appendix page: the rows beyond the thesis (:func:`reportpage.is_beyond`), under a
    heading per thesis chapter one compact table per page of the book in reading order (its
    heading links the page), each row in its page's order."""
    lines = [APPENDIX_HEADER]
    for chapter in chapters:
        beyond = [r for r in rows[chapter.number] if reportpage.is_beyond(r)]
        if beyond:
            lines += [f"## {chapter.caption}", ""]
        for page in dict.fromkeys([*chapter.pages, *(r.page for r in beyond)]):
            mine = [r for r in beyond if r.page == page]
            if not mine:
                continue
            sections = link.sections.get(page, [])
            title = sections[0].title if sections else page
            lines += [
                f"### {{doc}}`{title} </chapters/{page}>`",
                "",
                reportpage.appendix_table(mine, link, title),
                "",
            ]
    return "\n".join(lines)


def build(executed: Path, records: Path, book: Path, profile: str = "ci") -> list[str]:
    """Write every generated page of ``book`` (the landing page ``intro.md`` too, for the build
    ``profile``); return the problems found: the explorer page's model, ``_toc.yml``'s entries."""
    toc = yaml.safe_load((Path(book) / "_toc.yml").read_text())
    chapters = toc_chapters(toc)
    made = provenance.text(profile=profile)  # one build, one date on every page
    link = Linker(copy_chapters(executed, Path(book) / "chapters", made))
    rows = report_rows(records, chapters)
    footer = provenance.block(made)
    _write(Path(book) / "report.md", report_markdown(rows, chapters, link) + footer)
    _write(Path(book) / f"{APPENDIX}.md", appendix_markdown(rows, chapters, link) + footer)
    generated = Path(book) / "generated"
    generated.mkdir(parents=True, exist_ok=True)
    # every claim's verdict, judged again from the records and checked against the word its page
    # recorded: what the pages quote by id (the `verdict` role)
    judged = claimlist.judge(verdicts.load_records(records))
    _write(
        Path(book) / verdictrole.CLAIMS_FILE,
        json.dumps(claimlist.verdict_table(judged), indent=1, ensure_ascii=False) + "\n",
    )
    has_store = (STORE_DIR / "manifest.json").is_file()  # every FE run the book reads
    runs = bundleruns.store_tables(STORE_DIR) if has_store else {}
    data = bundle.write_bundle(
        records,
        generated / bundle.NAME,
        extra=runs,
        extra_readme=bundleruns.readme(runs) if has_store else "",
    )
    landing.write_landing(
        records,
        Path(book) / "intro.md",
        profile,
        link=link,
        provenance=f"{made}\n{storeline.landing_line(STORE_DIR)}",
        bundle=f"/{data.relative_to(Path(book)).as_posix()}",
        bundle_bytes=data.stat().st_size,
        bundle_members=bundle.members(data),
    )
    for page in methods.write_pages(generated, link):
        _write(page, page.read_text() + footer)
    problems = explorer.write_explorer(records, Path(book), footer)  # the page Try the model
    return problems + missing_toc_pages(book)


def main(argv: list[str] | None = None) -> int:
    """Generate the book's pages; exit 2 when ``_toc.yml`` names a page that does not exist."""
    parser = argparse.ArgumentParser(prog="python -m mechlib.pipeline book")
    parser.add_argument("--executed", type=Path, default=REPO_ROOT / "build" / "executed")
    parser.add_argument("--records", type=Path, default=records_dir())
    parser.add_argument("--book", type=Path, default=REPO_ROOT / "book")
    parser.add_argument("--profile", default="ci", help="the build profile the landing page names")
    args = parser.parse_args(argv)
    problems = build(args.executed, args.records, args.book, args.profile)
    for problem in problems:
        print(problem, file=sys.stderr)
    return 2 if problems else 0


if __name__ == "__main__":
    raise SystemExit(main())
