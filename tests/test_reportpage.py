"""The reproduction report page, its appendix, and the book's print rules for numbers and
parameters (mechlib.pipeline.book.reportpage, printparams, pvalues; bookbuild's report pages)."""

from __future__ import annotations

import json
from pathlib import Path

from mechlib.pipeline import bookbuild
from mechlib.pipeline.book import reportpage
from mechlib.reporting import artefacts, report, verdicts

# --- report page ---------------------------------------------------------------------------------
ROWS = [
    report.compare_row("Eq 8", "S", [1.0], [1.0]),
    report.compare_row("Table 5", "err", [1.0], [1.5], cause="non-linear"),
    report.compare_row("Table 1", "levels", [1.0], [1.004], rtol=0.01),
    report.check_row(
        "Fig 6", "dominant factors", "x: T1D1 (-1.0 N)", True, basis="thesis-inconsistency"
    ),
    report.check_row("Table 3", "m = 6", "no", False, basis="construction"),
    report.computed_row("Fig 2", "dims", [0.493389]),
]


def test_numbers_keep_integer_digits_and_four_significant() -> None:
    assert reportpage.fmt_number(575314.0) == "575314"
    assert reportpage.fmt_number(58.1628) == "58.16"
    assert reportpage.fmt_number(9.70131e-13) == "9.701e-13"
    assert (
        reportpage.shorten_numbers("0.166667, -28.7638, … (36 values)")
        == "0.1667, -28.76, … (36 values)"
    )


def test_chapter_table_is_in_thesis_order_and_links_each_row() -> None:
    rows = [reportpage.Row("nb", r) for r in ROWS]
    chapter = reportpage.Chapter(2, "Chapter 2", ("nb",))
    table = reportpage.chapter_table(rows, chapter, lambda page, what: f"LINK[{page}:{what}]")
    order = [
        line.split(":")[1].rstrip("]") for line in table.splitlines() if line.startswith("* - LINK")
    ]
    # the compared values in the thesis's order, then the checks and claims (evidence as text)
    assert order == ["Table 1", "Table 5", "Fig 2", "Eq 8", "Table 3", "Fig 6"]
    values, statements = table.split("```\n\n```")
    assert "  - Published" in values and "  - Evidence" in statements
    assert "x: T1D1 (-1.0 N)" in statements  # claim evidence is shown as written
    assert "{category}`diverges`: non-linear" in table  # the category (marked), then the cause


def test_value_cells_print_summaries_alike_and_ours_with_the_thesis_digits() -> None:
    published = "72 values (12 × 6) from -7.863e+04 to 78610, max |x| = 78610"
    assert reportpage.compact_summary(published) == "12 × 6 values, -7.863e+04 to 7.861e+04"
    assert reportpage.compact_summary("16 values from -1 to 2") == "16 values, -1 to 2"
    assert reportpage.compact_summary("110.73, 0.123456", shorten=False) == "110.73, 0.123456"
    assert reportpage.ours_cell("0.0279401234", "0.0279401") == "0.0279401"
    assert reportpage.ours_cell("1.23456, 2", "1, 2") == "1.235, 2"
    assert reportpage.is_statement({"published": "(diagram)"})
    assert not reportpage.is_statement({"published": "1, 2"})


def test_printed_numbers_floor_p_values_round_times_and_drop_a_repeated_maximum() -> None:
    text = "Wilcoxon p = 2.1e-126 (met); p = 5.4e-09; 1.6001 µs against 2.2942e+05 µs, 110.3 µs"
    assert reportpage.print_numbers(text) == (
        "Wilcoxon p < 1e-10 (met); p = 5.4e-09; 1.6 µs against 230,000 µs, 110 µs"
    )
    assert reportpage.print_numbers("72 values (12 × 6) from -1 to 1, max |x| = 1") == (
        "72 values (12 × 6) from -1 to 1"
    )


def test_rows_beyond_the_thesis_go_to_the_appendix_grouped_by_page(tmp_path: Path) -> None:
    beyond = [
        report.computed_row("Beyond the thesis: lean mesh", "largest difference [%]", [0.03]),
        report.compare_row(
            "Table 3", "ME of x, m = 7", [110.73], [110.86], rtol=0.01, source="ours"
        ),
    ]
    (tmp_path / "a.json").write_text(json.dumps({"notebook": "a", "report": ROWS[:2]}))
    (tmp_path / "b.json").write_text(json.dumps({"notebook": "b", "report": beyond}))
    chapters = [reportpage.Chapter(2, "Chapter 2 — x", ("a", "b"))]
    link = bookbuild.Linker({"b": [artefacts.Section("b-s1", "Page B", ())]})
    rows = bookbuild.report_rows(tmp_path, chapters)
    main = bookbuild.report_markdown(rows, chapters, link)
    appendix = bookbuild.appendix_markdown(rows, chapters, link)
    assert "largest difference" not in main and "2 more rows of this chapter" in main
    assert "## Chapter 2 — x\n\n### {doc}`Page B </chapters/b>`" in appendix
    assert "{doc}`lean mesh </chapters/b>`" in appendix
    # our value with as many digits as the thesis printed, the published value as printed
    assert "110.86 (published 110.73; 0.117 %" in appendix and "computed" in appendix
    assert "err" not in appendix.split("Page B")[1]


def test_the_printed_parameters_are_a_compact_table_of_values_and_units() -> None:
    from mechlib.pipeline.book import printparams

    cell = {"id": "p", "source": "# fmt: off\nt = 0.5  # mm, thickness\nseed = 1  # seed\nw = 2\n"}
    printed = printparams.print_cell(cell)
    assert printed["source"].startswith(":::{container} print-only params-print")
    assert (
        "* - `t`\n  - `0.5` mm\n  - `seed`\n  - `1`\n* - `w`\n  - `2`\n  - \n  - "
        in (printed["source"])
    )
    assert printparams.print_cell({"source": "# no parameters\n"}) is None


def test_report_links_rows_to_sections_or_pages(tmp_path: Path) -> None:
    rec = {"notebook": "a", "values": {}, "report": ROWS}
    (tmp_path / "a.json").write_text(json.dumps(rec))
    chapters = [reportpage.Chapter(2, "Chapter 2 — x", ("a",))]
    link = bookbuild.Linker(
        {"a": [artefacts.Section("a-s3", "Table 5 — validation", (("table", 5),))]}
    )
    text = bookbuild.report_markdown(bookbuild.report_rows(tmp_path, chapters), chapters, link)
    assert "{ref}`Table 5 <a-s3>`" in text and "{doc}`Eq 8 </chapters/a>`" in text
    assert verdicts.COUNTS_HEADER in text and text.index("## Summary") < text.index("## Chapter 2")


def test_p_values_below_the_floor_read_p_below_1e_10_in_text_and_frames() -> None:
    from mechlib.pipeline.book import pvalues

    glued = {"data": {pvalues.GLUE_PREFIX + "text/plain": "2.0657e-126"}}
    glued["metadata"] = {"scrapbook": {"name": "p_small"}}
    large = {"data": {pvalues.GLUE_PREFIX + "text/plain": "0.03"}, "metadata": {}}
    large["metadata"]["scrapbook"] = {"name": "p_large"}
    cells = [
        {"cell_type": "code", "source": "", "outputs": [glued, large]},
        {
            "cell_type": "markdown",
            "source": "(p = {glue:text}`p_small:.1e`; p = {glue:text}`p_large:.2g`)",
        },
    ]
    assert pvalues.floor_glued_p_values(cells) == 1
    assert cells[1]["source"] == "(p < 1e-10; p = {glue:text}`p_large:.2g`)"
    frame = (
        '<table class="dataframe"><thead><tr><th></th><th>a</th><th>Wilcoxon p</th></tr></thead>'
        "<tbody><tr><th>x</th><td>1e-20</td><td>2.1e-126</td></tr>"
        "<tr><th>Wilcoxon p (param.)</th><td>3e-12</td><td>0.04</td></tr></tbody></table>"
    )
    out = pvalues.print_frame(frame)
    assert "<tr><th>x</th><td>1e-20</td><td>&lt; 1e-10</td></tr>" in out  # the p column only
    assert "<td>&lt; 1e-10</td><td>0.04</td>" in out  # the p row; 0.04 stays
    times = (
        '<table class="dataframe"><thead><tr><th></th><th>µs a pose</th><th>n</th></tr></thead>'
        "<tbody><tr><th>GP</th><td>4547.2</td><td>1234</td></tr>"
        "<tr><th>S_T</th><td>0.01412</td><td>35.77</td></tr></tbody></table>"
    )
    out = pvalues.print_frame(times)
    assert "<td>4,500</td><td>1234</td>" in out and "<td>0.014</td><td>35.77</td>" in out
