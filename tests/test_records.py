"""Every notebook's record against its committed reference (run after the notebooks)."""

from __future__ import annotations

import copy
import os
from pathlib import Path

import pytest

from mechlib.paths import REPO_ROOT, records_dir
from mechlib.pipeline.book import quoted
from mechlib.pipeline.references import compare
from mechlib.reporting.records import load

REFERENCES = REPO_ROOT / "tests" / "references"
NOTEBOOKS = sorted(p.stem for p in (REPO_ROOT / "notebooks").glob("*.ipynb"))


def _quoted(notebook: str) -> list[str]:
    """Glue names the notebook's own text and the book's pages quote from it."""
    page = REPO_ROOT / "notebooks" / f"{notebook}.ipynb"
    names = [n for p, n in quoted.glue_references(quoted.markdown_of(page)) if not p]
    for md in sorted((REPO_ROOT / "book").glob("*.md")):
        names += [n for p, n in quoted.glue_references(md.read_text()) if Path(p).stem == notebook]
    return names


@pytest.mark.parametrize("notebook", NOTEBOOKS)
def test_every_number_the_text_quotes_is_a_recorded_value(notebook: str) -> None:
    """A number reaches the prose only through Recorder.value, so the comparison above checks
    it; text glued by Recorder.text says what it is made of or why it is not checked."""
    record = records_dir() / f"{notebook}.json"
    assert record.exists(), f"{notebook} wrote no record at {record}"
    names = _quoted(notebook)
    assert names, f"{notebook}'s text quotes no glued value: is the glue role pattern right?"
    problems = quoted.unchecked_glue(load(record), names)
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("notebook", NOTEBOOKS)
def test_record_matches_reference(notebook: str) -> None:
    record, reference = records_dir() / f"{notebook}.json", REFERENCES / f"{notebook}.json"
    assert reference.exists(), f"no reference for {notebook}: run `make references` and review it"
    assert record.exists(), f"{notebook} wrote no record at {record}"
    problems = compare(load(record), load(reference))
    assert not problems, "\n".join(problems)


def _shift(value: object, rtol: float, atol: float) -> object:
    """Move every number by ten times its tolerance (and by its own size)."""
    if isinstance(value, list):
        return [_shift(v, rtol, atol) for v in value]
    return value + abs(value) * (1 + 10 * rtol) + 10 * atol


def _numbers(value: object) -> list[float]:
    if isinstance(value, list):
        return [x for v in value for x in _numbers(v)]
    return [value] if isinstance(value, float) else []


@pytest.mark.parametrize("notebook", NOTEBOOKS)
def test_a_wrong_value_fails_the_comparison(notebook: str) -> None:
    """Perturb each numeric tolerance-bearing value beyond its tolerance: compare must object."""
    reference = load(REFERENCES / f"{notebook}.json")
    checked = 0
    for key, entry in reference["values"].items():
        flat = _numbers(entry["value"])
        if not flat or not (any(flat) or entry["atol"] > 0):
            continue
        bad = copy.deepcopy(reference)
        bad["values"][key]["value"] = _shift(entry["value"], entry["rtol"], entry["atol"])
        problems = compare(bad, reference)
        assert problems and problems[0].startswith(key), f"perturbing {key} went unnoticed"
        checked += 1
    assert checked > 0


def test_missing_and_extra_keys_are_reported(tmp_path: Path) -> None:
    ref = {"values": {"a": {"value": 1.0, "rtol": 0.0, "atol": 0.1}}}
    assert compare({"values": {}}, ref) == ["a: in the reference but not recorded by this run"]
    extra = {"values": {"a": {"value": 1.05}, "b": {"value": 2}}}
    assert compare(extra, ref) == ["b: recorded but not in the reference (run `make references`)"]
    assert compare({"values": {"a": {"value": 1.2}}}, ref)[0].startswith("a: got")


@pytest.mark.parametrize("notebook", NOTEBOOKS)
def test_record_comes_from_another_blas_kernel_than_its_reference(notebook: str) -> None:
    """Under `make test` (which names its kernel in $MECHLIB_TEST_KERNEL) the comparison above is
    across BLAS kernels: the record's kernel is the one asked for, the reference's another."""
    kernel = os.environ.get("MECHLIB_TEST_KERNEL")
    if not kernel:
        pytest.skip("not under make test: the notebooks ran with this machine's own kernel")
    record = load(records_dir() / f"{notebook}.json")
    reference = load(REFERENCES / f"{notebook}.json")
    assert record.get("blas") == kernel, f"computed with {record.get('blas')}, not {kernel}"
    assert reference.get("blas") not in (None, kernel), (
        f"the reference was recorded with {reference.get('blas')}: not a cross-kernel comparison"
    )
