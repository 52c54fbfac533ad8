"""Captions and alt text of the chapters' figures (book build) and the redrawn method figures."""

from __future__ import annotations

from pathlib import Path

from mechlib.pipeline.book import figures, methods
from mechlib.pipeline.book.cells import prepare_notebook
from mechlib.reporting import verdicts

ROOT = Path("/nowhere/repo")
_IMAGE = {"output_type": "display_data", "data": {"image/png": "iVBOR", "text/plain": "<Fig>"}}


def _nb(*cells: dict) -> dict:
    return {"cells": list(cells), "metadata": {}, "nbformat": 4, "nbformat_minor": 5}


def _code(cid: str, outputs: list) -> dict:
    return {"cell_type": "code", "id": cid, "metadata": {}, "outputs": outputs, "source": "f()"}


def test_a_figure_cell_gets_its_numbered_caption_and_alt_text() -> None:
    nb, _ = prepare_notebook(_nb(_code("cell-15", [_IMAGE])), "fivebar_identification", ROOT)
    meta = nb["cells"][0]["metadata"]["mystnb"]
    caption, alt = figures.CAPTIONS["fivebar_identification"]["cell-15"]
    assert meta == {
        "figure": {"caption": caption, "name": "fivebar_identification-cell-15"},
        "image": {"alt": alt},
    }
    plain, _ = prepare_notebook(_nb(_code("cell-15", [])), "fivebar_identification", ROOT)
    assert "mystnb" not in plain["cells"][0]["metadata"]  # no figure, no caption


def test_uncaptioned_figures_and_stale_captions_are_named() -> None:
    nb = _nb(_code("new-cell", [_IMAGE]), _code("cell-15", []))
    problems = figures.uncaptioned("fivebar_identification", nb)
    assert any("'new-cell' has no caption" in p for p in problems)
    assert any("'cell-15', which draws no figure" in p for p in problems)


def test_captions_quote_no_number_and_alt_texts_are_not_paths() -> None:
    for page in figures.CAPTIONS.values():
        for caption, alt in page.values():
            assert caption and alt and "/" not in alt and not alt.endswith(".png")
            assert "{glue" not in caption


def test_the_redrawn_rows_name_the_method_figures_pages() -> None:
    drawn = {(f"generated/{m.page}", m.figure) for m in methods.METHOD_FIGURES}
    assert {(page, artefact) for page, artefact, _ in verdicts.REDRAWN} == drawn
    rows = verdicts.redrawn_rows()
    assert [r.category for r in rows] == [verdicts.cat.CAT_REDRAWN] * len(drawn)


def test_a_table_shown_beside_a_figure_moves_to_a_cell_of_its_own() -> None:
    table = {"output_type": "execute_result", "data": {"text/html": "<table/>"}, "metadata": {}}
    nb, _ = prepare_notebook(_nb(_code("cell-09", [table, _IMAGE])), "fivebar_identification", ROOT)
    figure, shown = nb["cells"]
    assert figure["outputs"] == [_IMAGE] and "mystnb" in figure["metadata"]
    assert shown["outputs"] == [table] and shown["metadata"] == {"tags": ["remove-input"]}
    assert shown["id"] == "cell-09-shown" and "mystnb" not in shown["metadata"]
