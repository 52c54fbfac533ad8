"""The book's PDF: reading order, what the HTML asks of the PDF, and the check's verdicts.

The parsing and the verdicts are tested on hand-made HTML and poppler outputs; the end-to-end
tests print tiny pages with headless Chromium and run only where Chromium and poppler-utils are
installed (``.ci/run`` installs both).
"""

from __future__ import annotations

import shutil
from collections import Counter
from pathlib import Path

import pytest
from PIL import Image

from mechlib.pipeline import pdf, pdfcheck

PAGE = """<html><head>{head}</head><body>
<nav><img src="logo.png"><h1>Navigation</h1></nav>
<main>{body}</main>
<footer>the footer's text is not content</footer></body></html>"""


def write_page(path: Path, body: str, head: str = "") -> Path:
    path.write_text(PAGE.format(head=head, body=body), encoding="utf-8")
    return path


def png(path: Path, size: tuple[int, int]) -> Path:
    Image.new("RGB", size, (200, 30, 30)).save(path)
    return path


def test_parse_page_reads_main_only() -> None:
    info = pdfcheck.parse_page(
        PAGE.format(
            head='<link rel="next" href="b.html">',
            body='<h1>Title <a class="headerlink">#</a></h1><p>abc</p><img src="f.png">'
            '<img src="f.svg"><span id="document-x"></span><h2>Second page</h2><h2>Sub</h2>',
        )
    )
    assert info.next_href == "b.html"
    assert info.titles == ["Title", "Second page"]  # "Sub" is a section, not a page title
    assert info.images == ["f.png", "f.svg"]  # the <nav>'s logo is not content
    assert info.documents == 1
    assert info.text_chars == len("Title#abcSecond pageSub")


def test_page_order_follows_redirect_and_next_links_and_stops_on_a_cycle(
    tmp_path: Path,
) -> None:
    (tmp_path / "index.html").write_text('<meta http-equiv="Refresh" content="0; url=a.html" />')
    write_page(tmp_path / "a.html", "<h1>A</h1>", head='<link rel="next" href="b.html">')
    write_page(tmp_path / "b.html", "<h1>B</h1>", head='<link rel="next" href="a.html">')
    assert [p.name for p in pdfcheck.page_order(tmp_path)] == ["a.html", "b.html"]
    with pytest.raises(FileNotFoundError, match=r"no index\.html"):
        pdfcheck.page_order(tmp_path / "missing")


def test_summary_counts_raster_images_by_pixel_size(tmp_path: Path) -> None:
    png(tmp_path / "f1.png", (40, 30))
    png(tmp_path / "f2.png", (50, 20))
    write_page(
        tmp_path / "index.html",
        '<h1>Book</h1><img src="f1.png"><img src="f2.png"><img src="f1.png">'
        '<img src="d.svg"><img src="https://example.org/x.png">',
    )
    summary = pdfcheck.summarize_html(tmp_path)
    assert summary.image_sizes == Counter({(40, 30): 2, (50, 20): 1})
    (tmp_path / "f2.png").unlink()
    with pytest.raises(FileNotFoundError, match=r"index\.html shows f2\.png"):
        pdfcheck.summarize_html(tmp_path)
    assert pdf.main(["check", "--pdf", "x.pdf", "--html", str(tmp_path)]) == 2
    assert summary.titles == ["Book"]
    assert summary.pages == summary.documents == 1


def test_pdfimages_listing_leaves_masks_out() -> None:
    listing = """page   num  type   width height color comp bpc  enc interp  object ID x-ppi y-ppi
--------------------------------------------------------------------------------------------
   2     0 image     400   300  icc     3   8  image  no        19  0    96    96 7234B 2.0%
   2     1 smask     400   300  gray    1   8  image  no        19  0    96    96 1234B 1.0%
   3     2 image     400   300  icc     3   8  image  no        19  0    96    96 7234B 2.0%
"""
    assert pdfcheck.parse_pdfimages_list(listing) == Counter({(400, 300): 2})


def test_verdicts_on_raw_math_images_titles_and_page_range() -> None:
    assert pdfcheck.raw_math("typeset x² here") == []
    found = pdfcheck.raw_math("see \\(x^2\\) and $$ y $$ and \\[ z \\]")
    assert len(found) == 4 and "\\(x^2" in found[0]
    assert pdfcheck.missing_images(Counter({(4, 3): 2, (5, 5): 1}), Counter({(4, 3): 3})) == [
        "5x5 px image: 1 in the HTML, 0 in the PDF"
    ]
    assert pdfcheck.missing_images(Counter({(4, 3): 2}), Counter({(4, 3): 1})) == [
        "4x3 px image: 2 in the HTML, 1 in the PDF"
    ]
    assert pdfcheck.missing_titles(["Fig \\(x\\) ﬁt", "Absent"], "Fig x\nfit") == ["Absent"]
    summary = pdfcheck.HtmlSummary(3, 3, [], Counter(), text_chars=30_000)
    assert pdfcheck.page_range(summary) == (5, 3 * pdfcheck.MAX_PAGES_PER_DOCUMENT)
    assert pdfcheck.page_range(summary, min_pages=12)[0] == 12


def test_check_names_each_problem_with_its_allowed_value(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    png(tmp_path / "f.png", (40, 30))
    write_page(tmp_path / "index.html", '<h1>Book</h1><p>text</p><img src="f.png">')
    outputs = {
        "pdfinfo": "Pages:          0\n",
        "pdftotext": "Book \\(x\\) text",
        "pdfimages": "header\n-----\n",
    }
    monkeypatch.setattr(pdfcheck, "run_tool", lambda cmd, timeout=120: outputs[cmd[0]])
    problems = pdfcheck.check(tmp_path / "book.pdf", tmp_path)
    assert problems[0].startswith("0 pages, allowed [1, 60]")
    assert problems[1] == "40x30 px image: 1 in the HTML, 0 in the PDF"
    assert problems[2].startswith("1 TeX math delimiters left untypeset (allowed 0)")
    assert len(problems) == 3


def test_missing_tools_are_reported(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(shutil, "which", lambda name: None)
    with pytest.raises(pdfcheck.ToolMissing, match="pdfinfo not found"):
        pdfcheck.pdf_pages(Path("x.pdf"))
    with pytest.raises(pdfcheck.ToolMissing, match="no Chromium"):
        pdf.build(Path("."), Path("x.pdf"))
    assert pdf.missing_tools() == ["chromium", *pdf.POPPLER]
    assert pdf.main(["tools"]) == 3


needs_chromium = pytest.mark.skipif(
    pdf.find_browser() is None or shutil.which("pdftotext") is None,
    reason="needs chromium and poppler-utils (apt-get install chromium poppler-utils)",
)


@needs_chromium
def test_printed_book_passes_and_a_broken_one_fails(tmp_path: Path) -> None:
    good, bad = tmp_path / "good", tmp_path / "bad"
    for book in (good, bad):
        book.mkdir()
        png(book / "f.png", (64, 48))
    write_page(
        good / "index.html",
        '<h1>First page</h1><p>Typeset by hand: x².</p><img src="f.png">',
        head='<link rel="next" href="two.html">',
    )
    write_page(good / "two.html", "<h1>Second page</h1><p>More text.</p>")
    # no MathJax on the page: the TeX stays raw; the hidden figure is not printed
    write_page(
        bad / "index.html",
        '<h1>Broken page</h1><p>Raw \\(x^2\\) math.</p><img src="f.png" style="display:none">',
    )
    pdf.build(good, tmp_path / "good.pdf")
    assert pdfcheck.pdf_pages(tmp_path / "good.pdf") == 2  # each page printed, then joined
    assert pdfcheck.check(tmp_path / "good.pdf", good) == []
    pdf.build(bad, tmp_path / "bad.pdf")
    problems = pdfcheck.check(tmp_path / "bad.pdf", bad, min_pages=3)
    assert problems[0].startswith("1 pages, allowed [3, 60]")
    assert "64x48 px image: 1 in the HTML, 0 in the PDF" in problems
    assert problems[-1].startswith("1 TeX math delimiters left untypeset (allowed 0)")
    assert pdf.main(["check", "--pdf", str(tmp_path / "bad.pdf"), "--html", str(bad)]) == 1
