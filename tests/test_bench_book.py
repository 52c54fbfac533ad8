"""make bench ONLY=book's reading of a build (mechlib.bench.book): no clone or build here."""

import json
from pathlib import Path

from mechlib.bench import book


def _executed(folder: Path, name: str, seconds: float | None) -> None:
    meta = {"papermill": {"duration": seconds}} if seconds is not None else {}
    (folder / f"{name}.ipynb").write_text(json.dumps({"cells": [], "metadata": meta}))


def test_chapter_durations_are_papermills_by_notebook(tmp_path: Path) -> None:
    _executed(tmp_path, "b_chapter", 12.5)
    _executed(tmp_path, "a_chapter", 80.0)
    _executed(tmp_path, "not_executed", None)
    assert book.chapter_durations(tmp_path) == {"a_chapter": 80.0, "b_chapter": 12.5}


def test_report_gives_the_total_then_the_chapters_longest_first() -> None:
    lines = book.report(
        {"commit": "abc", "clone_s": 1.2, "book_s": 250.0, "chapters": {"x": 10.0, "y": 70.0}}
    )
    assert lines[0].startswith("make book on a fresh clone of abc: 250 s (4.2 min")
    assert "sum 80 s" in lines[1]
    assert [line.split()[0] for line in lines[2:]] == ["y", "x"]
