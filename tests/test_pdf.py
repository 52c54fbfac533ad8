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

from mechlib.pipeline import pdf, pdfcheck, pdfpages

PAGE = """<html><head>{head}</head><body>
<nav><img src="logo.png"><h1>Navigation</h1></nav>
<main>{body}</main>
<footer>the footer's text is not content</footer></body></html>"""


# pdftohtml -xml -zoom 3 output: fonts are declared once, on the page that first uses them
XML = """<pdf2xml><page number="1" height="2376" width="1836">
<fontspec id="0" size="36" family="AAAAAA+DejaVuSans" color="#000000"/>
<fontspec id="1" size="28" family="BAAAAA+FontAwesome6Free-Solid" color="#000000"/>
<fontspec id="2" size="15" family="Times" color="#000000"/>
<text top="1" left="1" width="9" height="9" font="0">Body <a href="{href}">bundle</a></text>
<text top="1" left="1" width="9" height="9" font="1">\uf019</text>
<text top="1" left="1" width="9" height="9" font="2"><i>n</i></text>
</page><page number="2" height="2376" width="1836">
<fontspec id="3" size="{size}" family="CAAAAA+DejaVuSans" color="#000000"/>
<text top="1" left="1" width="9" height="9" font="3">tiny</text>
<text top="1" left="1" width="9" height="9" font="3"> </text>
</page></pdf2xml>"""


def layout(*pages: list[tuple[float, str]]) -> str:
    """``pdftotext -bbox-layout`` output of pages, each a list of (yMin, line text)."""
    return (
        "<doc>"
        + "".join(
            '<page width="612" height="792"><flow><block>'
            + "".join(
                f'<line xMin="50" yMin="{y}" xMax="500" yMax="{y + 12}">'
                + "".join(
                    f'<word xMin="1" yMin="{y}" xMax="2" yMax="3">{w}</word>' for w in t.split()
                )
                + "</line>"
                for y, t in page
            )
            + "</block></flow></page>"
            for page in pages
        )
        + "</doc>"
    )


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
            '<img src="f.svg"><span id="document-x"></span><h2>Second page</h2><h2>Sub</h2>'
            '<a href="_downloads/1/d%20b.zip"></a><a href="b.html#x"></a><a href="#y"></a>'
            '<a href="https://example.org/c.zip"></a>',
        )
    )
    assert info.files == ["_downloads/1/d%20b.zip"]  # a file, not a page, anchor or URL
    assert pdfcheck.linked_file(info.files[0]) == "d b.zip"
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
    assert pdfcheck.page_range(summary, max_pages=130) == (5, 130)  # a ceiling of paper


def test_check_names_each_problem_with_its_allowed_value(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    png(tmp_path / "f.png", (40, 30))
    write_page(tmp_path / "index.html", '<h1>Book</h1><p>text</p><img src="f.png">')
    outputs = {
        "pdfinfo": "Pages:          0\n",
        "pdftotext": "Book \\(x\\) text Show code cell source",
        "pdfimages": "header\n-----\n",
        "pdftohtml": XML.format(size=18, href="file:///elsewhere/d.zip"),
    }
    monkeypatch.setattr(pdfcheck, "run_tool", lambda cmd, timeout=120: outputs[cmd[0]])
    problems = pdfcheck.check(tmp_path / "book.pdf", tmp_path)
    assert problems[0].startswith("0 pages, allowed [1, 60]")
    assert problems[1] == "40x30 px image: 1 in the HTML, 0 in the PDF"
    assert problems[2].startswith("1 TeX math delimiters left untypeset (allowed 0)")
    assert problems[3] == "1 code-cell toggles printed ('Show code cell source'), allowed 0"
    assert problems[4] == "text at 6.00 pt on page 2 ('tiny'), allowed ≥ 7.0 pt"
    assert problems[5].startswith("link to file:///elsewhere/d.zip: absolute (allowed: a link")
    assert len(problems) == 6


def test_smallest_text_and_math_leave_icons_out_and_fail_below_the_limits() -> None:
    smallest = pdfcheck.smallest_text(XML.format(size=18, href="x"))
    assert smallest == {"text": (6.0, 2, "tiny"), "math": (5.0, 1, "n")}
    assert pdfcheck.smallest_text(XML.format(size=21, href="x"))["text"][0] == 7.0
    assert pdfcheck.smallest_text("<pdf2xml></pdf2xml>") == {}


def test_captions_at_the_top_of_a_page_are_parted_from_their_figure() -> None:
    pages = layout(
        [(30.0, "Chapter one"), (300.0, "Figure 1 a caption below its figure")],
        [(32.0, "Figure 2 a caption whose figure is on the page before"), (46.0, "its end")],
        [(-900.0, "hidden text off the page"), (250.0, "Figure 3 under a vector drawing")],
        [],  # a page of drawing only
        [(60.0, "Figure 4 under a 30 pt drawing")],
    )
    assert pdfcheck.parted_captions(pages) == [
        (2, "Figure 2 a caption whose figure is on the page before")
    ]
    assert pdfcheck.parted_captions(layout([(30.0, "Figures 2–5 draw it")])) == []
    # given the book's captions, a sentence that begins with a reference is no caption
    text = layout([(32.0, "Figure B.2 shows where"), (46.0, "x")], [(32.0, "Figure B.3 Mesh of")])
    captions = pdfpages.figure_captions(
        '<figcaption><p><span class="caption-number">Figure B.3 </span>Mesh of\n the plate'
        "</p></figcaption><figcaption>Figure B.2 The plate</figcaption>"
    )
    assert captions == ["Figure B.3 Mesh of the plate", "Figure B.2 The plate"]
    assert pdfpages.parted_captions(text, captions) == [(2, "Figure B.3 Mesh of")]


def test_links_to_files_must_be_relative_and_name_a_file_beside_the_pdf(tmp_path: Path) -> None:
    (tmp_path / "pdf").mkdir()
    (tmp_path / "pdf" / "d.zip").write_bytes(b"zip")
    where = (tmp_path / "pdf").resolve()
    ok = ["d.zip", "https://x.org/a.zip", "#anchor", "book.html#p5"]
    assert pdfcheck.broken_links(ok, tmp_path / "pdf", ["d.zip"]) == []
    absolute = (tmp_path / "pdf" / "d.zip").as_uri()
    problems = pdfcheck.broken_links([absolute, "e.zip", "e.zip"], tmp_path / "pdf", ["d.zip"])
    assert problems == [
        f"link to {absolute}: absolute (allowed: a link relative to the PDF)",
        f"link to e.zip: no such file beside the PDF (allowed: a file in {where})",
        "the book links d.zip; the PDF has no link to it beside the PDF (allowed: d.zip)",
    ]


def test_file_links_are_made_relative_in_place(tmp_path: Path) -> None:
    from mechlib.pipeline import pdf

    folder = tmp_path / "out"
    folder.mkdir()
    uri = f"{folder.resolve().as_uri()}/data.zip".encode()
    body = b"%PDF-1.4\n1 0 obj\n<</A <</S /URI /URI (" + uri + b")>>>>\nendobj\nxref 0 2\n"
    (folder / "b.pdf").write_bytes(body)
    assert pdf.relative_file_links(folder / "b.pdf") == 1
    out = (folder / "b.pdf").read_bytes()
    assert len(out) == len(body) and b"/URI (data.zip) " in out and b"file:" not in out
    assert out.index(b"endobj") == body.index(b"endobj")  # offsets kept: the xref holds
    assert pdf.relative_file_links(folder / "b.pdf") == 0
    live = f"{tmp_path.resolve().as_uri()}/html/generated/explorer.html".encode()
    (folder / "c.pdf").write_bytes(body.replace(uri, live))
    assert pdf.relative_file_links(folder / "c.pdf") == 1
    assert b"/URI (../html/generated/explorer.html) " in (folder / "c.pdf").read_bytes()


def test_a_live_page_link_opens_the_page_of_the_html_build(tmp_path: Path) -> None:
    (tmp_path / "html").mkdir()
    single = tmp_path / "singlehtml"
    single.mkdir()
    write_page(single / "index.html", '<a class="live-page" data-page="g/e.html" href="#">g</a>')
    assert pdf.live_root(single) == tmp_path / "html"
    text, _ = pdf.print_copy(single / "index.html", tmp_path, pdf.live_root(single))
    assert f'href="{(tmp_path / "html" / "g" / "e.html").resolve().as_uri()}"' in text


def test_print_copy_relinks_breaks_code_names_and_marks_wide_frames(tmp_path: Path) -> None:
    (tmp_path / "_downloads").mkdir()
    (tmp_path / "_downloads" / "d.zip").write_bytes(b"zip")
    wide = "<tr>" + "<td>123456.789</td>" * 12 + "</tr>"
    page = write_page(
        tmp_path / "intro.html",
        '<a href="intro.html#fig-1">Figure 1</a><a href="other.html#x">x</a>'
        '<a class="reference download" href="_downloads/d.zip">data</a><a href="gone.zip">g</a>'
        '<code><span class="pre">mechlib.doe.l2_cd</span></code>'
        f'<table border="1" class="dataframe"><tr><th>a long header</th></tr>{wide}</table>'
        '<table class="dataframe"><tr><th colspan="12">spans all</th></tr><tr><td>1</td></tr>'
        "</table>",
    )
    text, files = pdf.print_copy(page, tmp_path / "pdf")
    assert files == [(tmp_path / "_downloads" / "d.zip").resolve()]
    assert '<a href="#fig-1">' in text and '<a href="other.html#x">' in text
    assert f'href="{(tmp_path / "pdf" / "d.zip").resolve().as_uri()}"' in text
    assert 'href="gone.zip"' in text  # no file in the build: left as it is
    assert "mechlib.<wbr>doe.<wbr>l2_<wbr>cd" in text
    # 12 columns of 12 characters: portrait in a narrow face; the other frame fits as it is
    assert text.count("print-narrow") == 1 and "print-wide" not in text
    assert pdf.frame_chars(f"<table>{wide}</table>") == 12 * 12
    assert pdf.frame_chars("<table><tr><th>a long header</th></tr></table>") == 6 + 2
    # a header breaks after its underscores; cells between words (a number stays whole)
    assert (
        pdf.frame_chars("<table><tr><th>tab_half_width</th><td>1 to 2</td></tr></table>") == 7 + 4
    )
    frame = '<table class="dataframe"><tr><th>tab_half_width</th></tr></table>'
    assert pdf.header_breaks(frame).count("_<wbr>") == 2
    widest = "<tr>" + "<td>123456.789</td>" * 14 + "</tr>"
    marked = pdf.FRAME.sub(pdf.mark_wide, f'<table class="dataframe">{widest}</table>')
    assert 'class="print-wide dataframe' in marked  # 168 characters: a landscape page


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
    (good / "_downloads").mkdir()
    (good / "_downloads" / "data.zip").write_bytes(b"zip")
    write_page(
        good / "index.html",
        '<h1>First page</h1><p>Typeset by hand: x².</p><img src="f.png">'
        '<p><a href="_downloads/data.zip">the data</a></p>',
        head='<link rel="next" href="two.html">',
    )
    write_page(good / "two.html", "<h1>Second page</h1><p>More text.</p>")
    # no MathJax on the page: the TeX stays raw; the hidden figure is not printed
    # and a printed toggle, 5 pt text, a caption alone at the top of page 2
    write_page(
        bad / "index.html",
        '<h1>Broken page</h1><p>Raw \\(x^2\\) math.</p><img src="f.png" style="display:none">'
        '<p>Show code cell source</p><p style="font-size:5pt">small print</p>'
        '<figure style="break-before:page"><figcaption>Figure 1 a caption alone</figcaption>'
        "</figure>",
    )
    pdf.build(good, tmp_path / "good.pdf")
    assert pdfcheck.pdf_pages(tmp_path / "good.pdf") == 2  # each page printed, then joined
    assert (tmp_path / "data.zip").read_bytes() == b"zip"  # the linked file, beside the PDF
    assert pdfcheck.check(tmp_path / "good.pdf", good) == []
    (tmp_path / "data.zip").unlink()
    assert pdfcheck.check(tmp_path / "good.pdf", good)[0].startswith("link to ")
    pdf.build(bad, tmp_path / "bad.pdf")
    problems = pdfcheck.check(tmp_path / "bad.pdf", bad, min_pages=3)
    assert problems[0].startswith("2 pages, allowed [3, 60]")
    assert "64x48 px image: 1 in the HTML, 0 in the PDF" in problems
    assert problems[2].startswith("1 TeX math delimiters left untypeset (allowed 0)")
    assert problems[3] == "1 code-cell toggles printed ('Show code cell source'), allowed 0"
    assert problems[4].startswith("text at 5.00 pt on page 1 ('small print'), allowed ≥ 7.0")
    # page 1 ends at a forced break inside the chapter; page 2, its tail, holds one line
    assert problems[5].startswith("page 1 is near-blank: its text spans 18 %")
    assert problems[6].startswith("page 2 is near-blank")
    assert problems[7].startswith("page 2 begins with a caption parted from its figure")
    assert len(problems) == 8
    assert pdf.main(["check", "--pdf", str(tmp_path / "bad.pdf"), "--html", str(bad)]) == 1


def test_near_blank_pages_fail_unless_they_hold_a_figure_or_end_a_chapter() -> None:
    full = [(60.0 + 14 * k, f"line {k} of a full page") for k in range(40)]
    tail = [(60.0, "Provenance of the page"), (74.0, "commit abc"), (88.0, "Python 3.11")]
    pages = pdfpages.parse_layout(
        layout(full, tail, [(60.0, "Second chapter")], [(60.0, "x")], tail, [(60.0, "x")])
    )
    starts = pdfpages.book_page_starts(pages, ["First chapter", "Second chapter"])
    assert starts == {3}  # the first title is on no page; a later repeat starts nothing
    # 2: a chapter's last page with three lines (5.3 %); 3: one line; 4: figure; 5: mid-chapter
    # at 5.3 %; 6: the book's last page with one line (1.5 %)
    sparse = pdfpages.sparse_pages(pages, figure_pages={4}, starts=starts)
    assert [n for n, _ in sparse] == [3, 5, 6]
    assert pdfpages.page_span(pages, ["First chapter", "Second chapter"], "Second chapter") == 4
    assert pdfpages.page_span(pages, ["Second chapter"], "Other") == 0
    long_report = [[(60.0, "Reproduction report")], *[[(60.0, "rows")]] * 15]
    problems = pdfpages.layout_problems(
        layout(*long_report), set(range(1, 17)), set(), [], [], Path("."), ["Reproduction report"]
    )
    assert problems == ["the report prints on 16 pages, allowed ≤ 15 (one sitting)"]
    listing = "page num type width height\n---\n   3  0 image 64 48\n   3  1 smask 64 48\n"
    listing += "   5  2 image 2123 424\n"  # a box's shadow, rasterised: no figure of the book
    assert pdfpages.image_pages(listing) == {3, 5}
    assert pdfpages.image_pages(listing, {(64, 48)}) == {3}


def test_a_word_broken_inside_a_narrow_column_is_found() -> None:
    words = pdfpages.book_words("a better numerical efficiency; mechlib.doe.centered_l2, x-ray")
    pages = pdfpages.parse_layout(
        layout(
            [(60.0, "better numeric"), (72.0, "al efficienc"), (84.0, "y (conditioning)")],
            [(60.0, "mechlib.doe."), (72.0, "centered_l2"), (84.0, "a better"), (96.0, "x")],
        )
    )
    assert pdfpages.broken_words(pages, words) == [(1, "numeric|al"), (1, "efficienc|y")]


def test_a_live_page_needs_a_working_link_relative_to_the_pdf(tmp_path: Path) -> None:
    html_page = '<p class="print-only">Live: <a class="live-page" data-page="g/e.html" href="#">'
    live = pdfpages.live_pages(html_page)
    assert live == ["g/e.html"]
    (tmp_path / "html" / "g").mkdir(parents=True)
    (tmp_path / "pdf").mkdir()
    assert pdfpages.unlinked_live_pages(live, ["../html/g/e.html"], tmp_path / "pdf")
    (tmp_path / "html" / "g" / "e.html").write_text("<p>live</p>")
    assert pdfpages.unlinked_live_pages(live, ["../html/g/e.html"], tmp_path / "pdf") == []
    assert pdfpages.unlinked_live_pages(live, [], tmp_path / "pdf")
