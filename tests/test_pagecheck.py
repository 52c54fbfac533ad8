"""Checks of generated text: jargon, bare outputs, site-packages paths (positive and negative)."""

from __future__ import annotations

import pytest

from mechlib.pipeline import pagecheck as pc


@pytest.mark.parametrize(
    ("text", "word"),
    [
        ("The issue asks for < 1 %.", "issue"),
        ("Known Issues remain.", "issue"),
        ("(`make bench` measures the time)", "make bench"),
        ("the run count is a parameter: CI records a small run", "CI"),
        ("An earlier version of this page hung each tab", "earlier version"),
        ("(see the repository's\nhistory)", "repository's history"),
        ("see the repository’s history", "repository's history"),
    ],
)
def test_jargon_in_prose_is_found(text: str, word: str) -> None:
    problems = pc.markdown_problems(text, "page.md")
    assert len(problems) == 1 and f"{word!r} in the text" in problems[0]


@pytest.mark.parametrize(
    "text",
    [
        "Tissues and CIRCLE and CIs are words; a confidence interval is fine.",
        "```bash\nmake bench  # CI issue\n```\nPlain prose.",
        "```{admonition} Re-run this page\n`make bench` and CI are named here.\n```",
        ":::{admonition} Re-run this page\n:class: tip\nthe issue tracker\n:::",
    ],
)
def test_words_that_are_not_jargon_or_not_prose_pass(text: str) -> None:
    assert pc.markdown_problems(text, "page.md") == []


def test_other_admonitions_and_directives_are_prose() -> None:
    text = "```{note}\nsee the issue\n```\n\n```{list-table}\n* - CI\n```\n"
    problems = pc.markdown_problems(text, "page.md")
    assert [p.split(":")[1] for p in problems] == ["2", "6"]


def test_a_code_fence_inside_a_directive_is_still_code() -> None:
    text = "````{note}\nprose\n```python\n# CI\n```\nthe issue\n````\n"
    problems = pc.markdown_problems(text, "p.md")
    assert len(problems) == 1 and problems[0].startswith("p.md:6:")


@pytest.mark.parametrize(
    "output",
    ["0", "  0\n", "[110.85342447283215, 265.29464450568]", "(1, 2.5e-3)", "True",
     "np.float64(0.25)", "array([1., 2.])", "-3.5e+02", "'yes'", '"not the same"',
     "['yes', 'no']"],
)  # fmt: skip
def test_bare_outputs_are_found(output: str) -> None:
    assert pc.is_bare_output(output)


@pytest.mark.parametrize(
    "output",
    [
        "",
        "ME = 110.85",
        "     x    y\nT1D1 1 0",
        "record written to r.json",
        "[ME, SME]",
        "it's 'yes' here",
        "<IPython.core.display.Math object>",
    ],
)
def test_labelled_outputs_pass(output: str) -> None:
    assert not pc.is_bare_output(output)


def test_site_packages_paths_are_found_even_relative() -> None:
    text = "ok\n.venv/lib/python3.11/site-packages/sklearn/_gpr.py:6: ConvergenceWarning\n"
    assert pc.site_package_problems(text, "p") == [
        "p:2: a site-packages path: .venv/lib/python3.11/site-packages/sklearn/_gpr.py:6: "
        "ConvergenceWarning"
    ]
    assert pc.site_package_problems("packages of the site", "p") == []


HTML = """<html><head><title>CI issue</title></head><body>
<nav>Open an issue</nav>
<p>The model converges.</p>
<div class="cell docutils container">
<div class="cell_input docutils container"><pre># CI: make bench</pre></div>
<div class="cell_output docutils container">
<div class="output text_plain highlight-myst-ansi notranslate">
<div class="highlight"><pre><span></span>{output}
</pre></div></div></div></div>
<div class="admonition tip"><p class="admonition-title">Re-run this page</p><p>make bench</p></div>
<div class="admonition note"><p class="admonition-title">Note</p><p>{note}</p></div>
<img src="a.png"><br>
<p>{prose}</p>
</body></html>"""


def test_html_clean_page_passes() -> None:
    html = HTML.format(output="ME = 110.85", note="a note", prose="Plain text.")
    assert pc.html_problems(html, "p.html") == []


def test_html_problems_are_found_with_their_lines() -> None:
    html = HTML.format(
        output="[110.85342447283215, 265.29464450568]",
        note="see the earlier version",
        prose="files in lib/site-packages/x",
    )
    problems = pc.html_problems(html, "p.html")
    assert len(problems) == 3
    assert problems[0].startswith("p.html:11: 'earlier version' in the text: …")
    assert problems[1:] == [
        "p.html:8: a bare output, '[110.85342447283215, 265.29464450568]': give it a label or a "
        "table",
        "p.html:13: a site-packages path: <p>files in lib/site-packages/x</p>",
    ]


def _cell(kind: str, source: str, outputs: list | None = None, tags: list | None = None) -> dict:
    cell = {"cell_type": kind, "source": source, "metadata": {"tags": tags or []}}
    return cell | ({"outputs": outputs or []} if kind == "code" else {})


def test_notebook_outputs_and_markdown_are_checked_as_the_book_shows_them() -> None:
    result = {"output_type": "execute_result", "data": {"text/plain": "0"}}
    table = {"output_type": "execute_result", "data": {"text/plain": "0", "text/html": "<table>"}}
    nb = {
        "cells": [
            _cell("markdown", "# Page\n\nThe issue asks for it."),
            _cell("code", "x", [result]),
            _cell("code", "x", [result], tags=["remove-output"]),
            _cell("code", "x", [result], tags=["remove-cell"]),
            _cell("code", "df", [table]),
            _cell("markdown", "CI", tags=["remove-cell"]),
        ]
    }
    problems = pc.notebook_problems(nb, "nb")
    assert len(problems) == 2 and problems[0].startswith("nb cell 0:3: 'issue' in the text")
    assert problems[1] == "nb cell 1: a bare output, '0': label it"


@pytest.mark.parametrize(
    "text",
    [
        "misses by 41.9 % of range at ±1 N",
        "by up to 3 % of each pose component's range",
        "the elastica departs by 20, 3 and 42 % of our ranges",
        "both as shares of the linear validation runs' ranges",
        "a table column: worst error [% of range]",
    ],
)
def test_another_name_for_the_books_one_measure_is_refused(text: str) -> None:
    problems = pc.markdown_problems(text, "p.md")
    assert len(problems) == 1 and "another measure than '% of full scale'" in problems[0]


def test_the_books_one_measure_and_other_ranges_pass() -> None:
    text = "misses by 41.9 % of full scale over the force range of ±1 N, its range of movement"
    assert pc.markdown_problems(text, "p.md") == []
    html = "<p>Largest error [% of range]</p>"
    assert pc.html_problems(html, "p.html")
