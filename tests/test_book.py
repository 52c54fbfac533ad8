"""Book tooling that assembles pages: artefact parsing, cell rules, toc checks (the report page:
tests/test_reportpage.py)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml

from mechlib.paths import REPO_ROOT
from mechlib.pipeline import bookbuild
from mechlib.pipeline.book import cells
from mechlib.reporting import artefacts

FINAL_CELL = 'path = rec.save()\nprint(f"record written to {path}")'


# --- artefacts -----------------------------------------------------------------------------------
def test_parse_names_ranges_lists_and_kinds_in_order() -> None:
    assert artefacts.parse("Tables 2–3, Figs 6 and 7") == [
        ("table", 2),
        ("table", 3),
        ("fig", 6),
        ("fig", 7),
    ]
    assert artefacts.parse("Eq 8 — which published data?") == [("eq", 8)]
    assert artefacts.parse("Figures 2–5") == [("fig", 2), ("fig", 3), ("fig", 4), ("fig", 5)]
    assert artefacts.parse("Tables 6, 8") == [("table", 6), ("table", 8)]
    assert artefacts.parse("The units of the header") == []
    with pytest.raises(ValueError, match="5–2"):
        artefacts.parse("Tables 5–2")


def test_sort_key_follows_the_thesis_order_per_chapter() -> None:
    names = ["Eq 6", "Fig 2", "Table 5", "Table 1", "Fig 8", "Eq 9"]
    ordered = sorted(names, key=lambda n: artefacts.sort_key(artefacts.parse(n), 2))
    assert ordered == ["Table 1", "Table 5", "Fig 2", "Fig 8", "Eq 6", "Eq 9"]
    ordered3 = sorted(
        ["Table 6", "Fig 14", "Fig 10"], key=lambda n: artefacts.sort_key(artefacts.parse(n), 3)
    )
    assert ordered3 == ["Fig 10", "Fig 14", "Table 6"]


def test_find_section_prefers_most_artefacts_then_words_then_none() -> None:
    secs = [
        artefacts.Section("a-s1", "Table 2 — design", (("table", 2),)),
        artefacts.Section("a-s2", "Tables 2 and 3 — screening", (("table", 2), ("table", 3))),
        artefacts.Section("a-s3", "Identification of the dimensions", ()),
    ]
    assert artefacts.find_section(secs, "Table 2").label == "a-s1"
    assert artefacts.find_section(secs, "Tables 2–3").label == "a-s2"
    assert artefacts.find_section(secs, "identification").label == "a-s3"
    assert artefacts.find_section(secs, "Fig 9") is None


# --- cell rules ----------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "source",
    [
        FINAL_CELL,
        '_ = rec.value("k", 1.0, rtol=1e-3)',
        'for key, val in {"a": x, "b": y}.items():\n    glue(key, float(val), display=False)',
        'rec.value("d", dims, atol=0, row=report.Computed("Fig 2", "dims"))\nrec.value("n", n)',
        'rec.text("label", "θx", of="d")\nrec.value("r", r, rtol=1e-6, glue={"r0": 0})',
        "# round-off of printed sums\nROUNDOFF = 1e-9\nrec.value('e', e, rtol=ROUNDOFF)",
        'rec.value("a", a)\nrec.value("b", ok, context={"span_text": span_text});',
        'rec.mapping("geometry", geometry.as_dict())\nrec.skipped(["q_dep", "q.v"], why="one run")',
        "rec.constants()",
    ],
)
def test_bookkeeping_cells_are_recognised(source: str) -> None:
    assert cells.is_bookkeeping(source, {"rec"})


@pytest.mark.parametrize(
    "source",
    [
        'me6 = screening.margins(s0)\nglue("me6", me6, display=False)',  # computes
        'glue("fig", fig)',  # displays
        'print(f"effects {effects}")',  # prints a result
        "tol = 1e-9\nrec.value('e', e, rtol=tol)",  # a lower-case name is not a named tolerance
        'rec.value("b", ok, context={"s": f(x)})\nx = g(1)',  # computes after recording
        'rec.add_data("t", table, about="a table")',  # the data bundle: not a one-line record
        "rec.value(",  # does not parse
        "",
    ],
)
def test_computation_is_not_bookkeeping(source: str) -> None:
    assert not cells.is_bookkeeping(source, {"rec"})


def test_the_recorder_is_found_however_the_notebook_builds_it() -> None:
    sources = ['r = plans.recorder("x", registry=claimlist.claim)', 'q = Recorder("y")', "x = 2"]
    assert cells.recorder_names(sources) == {"r", "q"}
    assert cells.recorder_names(['r = recorder("x")', "x = f(1)"]) == {"r"}
    assert cells.recorder_names(["r = record()", "x = f(1)"]) == {"rec"}  # none: the default
    assert cells.is_bookkeeping('r.value("a", 1)', cells.recorder_names(sources[:1]))


def _code(source: str, tags: list[str] | None = None, outputs: list | None = None) -> dict:
    return {
        "cell_type": "code",
        "source": source,
        "metadata": {"tags": tags or []},
        "outputs": outputs or [],
        "execution_count": 1,
    }


def test_cell_tags_fold_compute_remove_bookkeeping_keep_parameters() -> None:
    rec = {"rec"}
    assert cells.cell_tags(_code("seed = 1", ["parameters"]), rec) == ["parameters"]
    assert cells.cell_tags(_code("import numpy", ["hide-input"]), rec) == ["hide-input"]
    assert cells.cell_tags(_code("x = f(1)\nx"), rec) == ["hide-input"]
    assert cells.cell_tags(_code(FINAL_CELL), rec) == ["remove-cell"]
    assert cells.cell_tags(_code(FINAL_CELL, ["hide-input"]), rec) == ["remove-cell"]
    assert cells.cell_tags(_code(FINAL_CELL, ["remove-output"]), rec) == ["remove-output"]
    shown = [{"output_type": "display_data", "data": {"image/png": "..."}, "metadata": {}}]
    assert cells.cell_tags(_code(FINAL_CELL, outputs=shown), rec) == ["hide-input"]


def test_neutralise_paths_and_warnings_but_not_units(tmp_path: Path) -> None:
    text = (
        f"record written to {tmp_path}/build/records/a.json\n"
        "install jax and jaxlib to use terms_jax.py!\n"
        "cache in /tmp/xyz/cache/run.npy; slope 57 µm/N, 3 rad/m\n"
    )
    out = cells.neutralise(text, tmp_path)
    assert (
        out == "record written to build/records/a.json\ncache in run.npy; slope 57 µm/N, 3 rad/m\n"
    )


def test_clean_outputs_drops_emptied_streams_and_cleans_glue_text(tmp_path: Path) -> None:
    outs = [
        {
            "output_type": "stream",
            "name": "stdout",
            "text": "install jax and jaxlib to use terms_jax.py!\n",
        },
        {
            "output_type": "display_data",
            "metadata": {"scrapbook": {"name": "p", "mime_prefix": "x/"}},
            "data": {"application/papermill.record/text/plain": f"'{tmp_path}/a/b.json'"},
        },
    ]
    cleaned = cells.clean_outputs(outs, tmp_path)
    assert len(cleaned) == 1
    assert cleaned[0]["data"]["application/papermill.record/text/plain"] == "'a/b.json'"


def test_headings_get_labels_and_sections_outside_code_fences() -> None:
    md = "# Title\ntext\n```\n# not a heading\n```\n## Table 3 — effects"
    text, secs = cells.label_headings(md, "nb", 4)
    assert [s.label for s in secs] == ["nb-s5", "nb-s6"]
    assert secs[1].artefacts == (("table", 3),)
    assert text.splitlines()[0] == "(nb-s5)=" and "(nb-s6)=\n## Table 3 — effects" in text
    assert "# not a heading" in text and text.count(")=") == 2


def test_prepare_notebook_applies_every_rule(tmp_path: Path) -> None:
    nb = {
        "cells": [
            {"cell_type": "markdown", "source": "## Table 1 — levels", "metadata": {}},
            _code("seed = 1", ["parameters"]),
            _code('rec = Recorder("x")\nx = 2'),
            _code(
                FINAL_CELL,
                outputs=[
                    {
                        "output_type": "stream",
                        "name": "stdout",
                        "text": f"record written to {tmp_path}/r.json\n",
                    }
                ],
            ),
        ],
        "metadata": {},
        "nbformat": 4,
        "nbformat_minor": 5,
    }
    out, secs = cells.prepare_notebook(nb, "my_nb", tmp_path)
    assert [c["metadata"].get("tags") for c in out["cells"]] == [
        None,
        ["parameters"],
        None,  # the parameters as printed (printparams)
        ["hide-input"],
        ["remove-cell"],
    ]
    assert out["cells"][4]["outputs"][0]["text"] == "record written to r.json\n"
    assert secs[0].label == "my-nb-s1" and out["cells"][0]["source"].startswith("(my-nb-s1)=")
    assert nb["cells"][2]["metadata"]["tags"] == []  # the input is not modified


# --- toc and report assembly ---------------------------------------------------------------------
def _book(tmp_path: Path, toc: dict) -> Path:
    (tmp_path / "chapters").mkdir()
    (tmp_path / "intro.md").write_text("# Intro\n")
    (tmp_path / "chapters" / "a.ipynb").write_text("{}")
    (tmp_path / "_toc.yml").write_text(yaml.safe_dump(toc))
    return tmp_path


def test_a_toc_entry_naming_no_page_is_reported_with_the_toc_file(tmp_path: Path) -> None:
    toc = {
        "format": "jb-book",
        "root": "intro",
        "parts": [
            {
                "caption": "Chapter 2 — x",
                "chapters": [{"file": "chapters/a"}, {"file": "chapters/typo"}],
            }
        ],
    }
    book = _book(tmp_path, toc)
    problems = bookbuild.missing_toc_pages(book)
    assert len(problems) == 1 and "_toc.yml" in problems[0] and "'chapters/typo'" in problems[0]
    toc["parts"][0]["chapters"].pop()
    (book / "_toc.yml").write_text(yaml.safe_dump(toc))
    assert bookbuild.missing_toc_pages(book) == []


def test_build_exits_2_naming_a_broken_toc_entry(
    tmp_path: Path, capsys: pytest.CaptureFixture
) -> None:
    toc = {
        "format": "jb-book",
        "root": "intro",
        "parts": [{"caption": "Chapter 2 — x", "chapters": [{"file": "chapters/nope"}]}],
    }
    (tmp_path / "book").mkdir()
    book = _book(tmp_path / "book", toc)
    (tmp_path / "executed").mkdir()
    (tmp_path / "records").mkdir()
    (tmp_path / "records" / "a.json").write_text(json.dumps({"notebook": "a", "values": {}}))
    code = bookbuild.main(
        [
            "--executed",
            str(tmp_path / "executed"),
            "--records",
            str(tmp_path / "records"),
            "--book",
            str(book),
        ]
    )
    assert code == 2
    assert "'chapters/nope' names no page" in capsys.readouterr().err


def test_the_books_toc_gives_chapters_2_and_3_with_their_notebooks() -> None:
    chapters = bookbuild.toc_chapters(yaml.safe_load((REPO_ROOT / "book" / "_toc.yml").read_text()))
    assert [c.number for c in chapters] == [2, 3]
    assert chapters[1].pages == ("fivebar_identification", "beyond_5r")
    assert "published_doe" in chapters[0].pages


def test_the_injected_parameters_replace_their_defaults_in_one_cell_without_directives() -> None:
    from mechlib.pipeline.book import cells

    nb = {
        "cells": [
            {"cell_type": "code", "metadata": {"tags": ["parameters"]}, "outputs": [],
             "source": "# fmt: off\nseed = 1  # the seed\ngeometry = None  # from the model\n"},
            {"cell_type": "code", "metadata": {"tags": ["injected-parameters"]}, "outputs": [],
             "source": "# Parameters\ngeometry = {'a': 1}\nextra = 2\n"},
            {"cell_type": "code", "metadata": {}, "outputs": [],
             "source": "x = [1,  2]  # fmt: skip\nx\n"},
        ]
    }  # fmt: skip
    out, _ = cells.prepare_notebook(nb, "p", Path("/nowhere"))
    assert len(out["cells"]) == 3
    params = out["cells"][0]["source"]
    assert "fmt" not in params and "seed = 1  # the seed" in params
    assert "geometry = {'a': 1}  # passed by the build; from the model" in params
    assert "extra = 2  # passed by the build" in params
    assert "`{'a': 1}`" in out["cells"][1]["source"]  # printed with the value it ran with
    assert out["cells"][2]["source"] == "x = [1,  2]\nx\n"


def test_a_notebook_still_executing_is_no_chapter(tmp_path: Path) -> None:
    """The Makefile executes into ``<name>.tmp.ipynb`` and renames it when done: the book copies
    only finished notebooks."""
    from mechlib.pipeline.execute import PARTIAL_SUFFIX

    executed = tmp_path / "executed"
    executed.mkdir()
    nb = {"cells": [], "metadata": {}, "nbformat": 4, "nbformat_minor": 5}
    (executed / "done.ipynb").write_text(json.dumps(nb))
    (executed / f"running{PARTIAL_SUFFIX}").write_text(json.dumps(nb))
    sections = bookbuild.copy_chapters(executed, tmp_path / "chapters")
    assert list(sections) == ["done"]
    assert [p.name for p in (tmp_path / "chapters").iterdir()] == ["done.ipynb"]
