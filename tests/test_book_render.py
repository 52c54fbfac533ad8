"""Book tooling that draws and checks: flow diagrams, method pages, HTML and browser checks."""

from __future__ import annotations

import importlib
import json
from itertools import pairwise
from pathlib import Path

import matplotlib.pyplot as plt
import pytest
from matplotlib.patches import FancyArrowPatch, FancyBboxPatch

from mechlib.pipeline.book import browser, diagrams, htmlcheck, methods


# --- diagrams and method pages -------------------------------------------------------------------
def test_box_layout_stacks_boxes_without_overlap_and_arrows_join_them() -> None:
    boxes = diagrams.box_layout(4)
    assert all(a[1] > b[3] for a, b in pairwise(boxes))  # a lies above b
    for (start, end), (a, b) in zip(diagrams.arrow_segments(boxes), pairwise(boxes), strict=True):
        assert start[1] == a[1] and end[1] == b[3]
    with pytest.raises(ValueError, match="at least one step"):
        diagrams.box_layout(0)


def test_flow_diagram_draws_one_box_per_step_and_the_loop() -> None:
    steps = [diagrams.Step(f"step {i}", "note") for i in range(3)]
    fig = diagrams.flow_diagram(steps, diagrams.Loop(2, 0, "again"))
    ax = fig.axes[0]
    assert sum(isinstance(p, FancyBboxPatch) for p in ax.patches) == 3
    assert sum(isinstance(p, FancyArrowPatch) for p in ax.patches) == 3  # 2 forward + loop
    assert any(t.get_text() == "again" for t in ax.texts)
    assert any(t.get_text().startswith("3. step 2") for t in ax.texts)
    plt.close(fig)
    with pytest.raises(ValueError, match="loop"):
        diagrams.flow_diagram(steps, diagrams.Loop(0, 2, "down"))


@pytest.mark.parametrize("method", methods.METHOD_FIGURES, ids=lambda m: m.figure)
def test_method_steps_name_functions_that_exist(method: methods.MethodFigure) -> None:
    for step in method.steps:
        for dotted in step.functions:
            module, _, attr = dotted.rpartition(".")
            try:
                importlib.import_module(dotted)
            except ModuleNotFoundError:
                assert hasattr(importlib.import_module(module), attr), dotted


def test_method_pages_are_written_deterministically(tmp_path: Path) -> None:
    def link(page: str, what: str) -> str:
        return f"[{what}]({page})"

    pages = methods.write_pages(tmp_path, link)
    svg = (tmp_path / "method_doe.svg").read_bytes()
    methods.write_pages(tmp_path, link)
    assert (tmp_path / "method_doe.svg").read_bytes() == svg
    text = pages[1].read_text()
    assert "```{figure} protocol_5r.svg" in text and "Thesis Fig 9, redrawn." in text
    assert ":alt: Flow diagram of " in text and "1. " in methods.alt_text(methods.FIG9)
    assert "[Fig 12](fivebar_identification)" in text and "back to step 1" in text


# --- HTML and browser checks ---------------------------------------------------------------------
def test_remote_fetches_are_found_but_reader_links_are_not() -> None:
    html = (
        '<script src="https://cdn.example/mathjax.js"></script><link rel="stylesheet" '
        'href="//fonts.example/css"><img src="_images/a.png"><a href="https://example.org">x</a>'
        '<div style="background: url(http://x.example/i.png)"></div>'
        '<script src="_static/a.js"></script>'
    )
    found = htmlcheck.remote_fetches(html)
    assert len(found) == 3 and all("example" in f for f in found)
    assert htmlcheck.remote_fetches('<script src="_static/mathjax/tex-chtml.js"></script>') == []
    assert htmlcheck.css_remote_urls("@font-face{src:url('https://f.example/x.woff')}") == [
        "https://f.example/x.woff"
    ]
    assert htmlcheck.css_remote_urls("src:url(fonts/x.woff)") == []


def test_leaks_find_machine_paths_and_warnings_in_visible_text_only() -> None:
    root = Path("/srv/repo")
    assert htmlcheck.leaks("<p>slope 57 µm/N and 3 rad/m</p>", root) == []
    assert htmlcheck.leaks("<p>record written to /tmp/i16/build/a.json</p>", root)
    assert htmlcheck.leaks("<p>install jax and jaxlib to use terms_jax.py!</p>", root)
    assert htmlcheck.leaks('<script>var p = "/tmp/x/y";</script>', root) == []


def test_broken_links_report_missing_files_and_anchors(tmp_path: Path) -> None:
    (tmp_path / "b.html").write_text('<h1 id="here">B</h1>')
    page = tmp_path / "a.html"
    page.write_text(
        '<a href="b.html#here">ok</a><a href="b.html#gone">x</a><a href="c.html">y</a>'
        '<a href="https://example.org/#q">ext</a>'
    )
    problems = htmlcheck.broken_links(page, tmp_path, {})
    assert len(problems) == 2 and "#gone" in problems[0] and "c.html" in problems[1]


GOOD_DOM = (
    '<html data-check-math="typeset" data-check-images="2 0" data-check-broken="">'
    '<body><span class="math"><mjx-container><mjx-math></mjx-math></mjx-container></span>'
    '<span class="pasted-text">1.0</span><img src="a.png"></body></html>'
)


def test_dom_problems_pass_a_good_page_and_name_each_failure() -> None:
    assert browser.dom_problems(GOOD_DOM, 1) == []
    assert "glued values missing" in browser.dom_problems(GOOD_DOM, 2)[0]
    raw = GOOD_DOM.replace("<mjx-container><mjx-math></mjx-math></mjx-container>", r"\(S_T\)")
    assert "untypeset" in browser.dom_problems(raw, 1)[0]
    broken = GOOD_DOM.replace('"2 0" data-check-broken=""', '"2 1" data-check-broken="a.png"')
    assert "images failed to load: a.png" in browser.dom_problems(broken, 1)[0]
    assert "did not run" in browser.dom_problems("<html><body></body></html>", 0)[0]
    stalled = GOOD_DOM.replace('data-check-math="typeset"', 'data-check-math="no-renderer"')
    assert "math renderer" in browser.dom_problems(stalled, 1)[0]
    err = GOOD_DOM.replace("<mjx-math></mjx-math>", "<mjx-merror></mjx-merror>")
    assert "mjx-merror" in browser.dom_problems(err, 1)[0]


def test_glue_roles_are_counted_in_markdown_only(tmp_path: Path) -> None:
    md = tmp_path / "p.md"
    md.write_text("a {glue:text}`nb.ipynb::x:.2f` b {glue}`y`")
    nb = tmp_path / "n.ipynb"
    nb.write_text(
        json.dumps(
            {
                "cells": [
                    {"cell_type": "markdown", "source": ["is {glue:text}`x:.1f`"]},
                    {"cell_type": "code", "source": "# {glue:text}`not counted`"},
                ]
            }
        )
    )
    assert browser.glue_roles(md) == 2 and browser.glue_roles(nb) == 1
