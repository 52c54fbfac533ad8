"""The record/compare helpers themselves."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from mechlib import records
from mechlib.records import Recorder, compare, load, recorded_value, update_references


def test_recorder_roundtrip_and_deterministic_bytes(tmp_path: Path) -> None:
    def write(folder: Path) -> bytes:
        rec = Recorder("demo")
        rec.value("b.matrix", np.arange(4.0).reshape(2, 2), rtol=1e-9)
        rec.value("a.flag", True)
        rec.value("a.count", np.int64(3))
        return rec.save(folder).read_bytes()

    assert write(tmp_path / "one") == write(tmp_path / "two")
    data = load(tmp_path / "one" / "demo.json")
    assert data["values"]["b.matrix"]["value"] == [[0.0, 1.0], [2.0, 3.0]]
    assert data["values"]["a.count"]["value"] == 3


def test_tolerances_are_relative_and_absolute() -> None:
    ref = {"values": {"x": {"value": [100.0, 0.0], "rtol": 1e-3, "atol": 1e-6}}}
    assert compare({"values": {"x": {"value": [100.09, 5e-7]}}}, ref) == []
    assert compare({"values": {"x": {"value": [100.2, 0.0]}}}, ref)
    assert compare({"values": {"x": {"value": [100.0, 2e-6]}}}, ref)
    assert compare({"values": {"x": {"value": [100.0]}}}, ref)[0].startswith("x: shape")


def test_bad_records_are_refused() -> None:
    rec = Recorder("demo")
    rec.value("k", 1.0)
    with pytest.raises(ValueError, match="already recorded"):
        rec.value("k", 2.0)
    with pytest.raises(ValueError, match="rtol must be >= 0"):
        rec.value("j", 1.0, rtol=-1)
    with pytest.raises(ValueError, match="finite"):
        rec.value("nan", float("nan"))


def test_update_references_reports_changes(tmp_path: Path) -> None:
    records, refs = tmp_path / "records", tmp_path / "refs"
    rec = Recorder("nb")
    rec.value("v", 1.0, rtol=1e-6)
    rec.save(records)
    assert update_references(records, refs) == ["nb: new reference"]
    rec2 = Recorder("nb")
    rec2.value("v", 2.0, rtol=1e-6)
    rec2.save(records)
    lines = update_references(records, refs)
    assert lines[0].startswith("nb: v: got 2.0") and json.loads((refs / "nb.json").read_text())


def test_a_value_recorded_by_another_notebook_is_found_or_named(
    tmp_path: Path, monkeypatch
) -> None:
    rec = Recorder("upstream")
    rec.value("geometry", [1.0, 2.0])
    rec.save(tmp_path)
    monkeypatch.setenv(records.RECORDS_ENV, str(tmp_path))
    assert recorded_value("upstream", "geometry") == [1.0, 2.0]
    with pytest.raises(KeyError, match="recorded no value 'size'"):
        recorded_value("upstream", "size")
    with pytest.raises(FileNotFoundError, match=r"no record of notebook 'nowhere'.*make notebooks"):
        recorded_value("nowhere", "geometry")


def test_a_value_from_the_default_build_is_announced(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture
) -> None:
    default = tmp_path / "repo"
    rec = Recorder("upstream")
    rec.value("geometry", [3.0])
    rec.save(default / "build" / "records")
    monkeypatch.setattr(records, "REPO_ROOT", default)
    monkeypatch.setenv(records.RECORDS_ENV, str(tmp_path / "run"))  # holds no record
    assert recorded_value("upstream", "geometry") == [3.0]
    err = capsys.readouterr().err
    assert "upstream's 'geometry' taken from" in err and str(tmp_path / "run") in err
    monkeypatch.setenv(records.RECORDS_ENV, str(default / "build" / "records"))
    assert recorded_value("upstream", "geometry") == [3.0]
    assert capsys.readouterr().err == ""  # this build's own record: nothing to say


def test_fe_cache_dir_follows_its_environment_variable(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv(records.FE_CACHE_ENV, raising=False)
    assert records.fe_cache_dir() == records.REPO_ROOT / "build" / "cache" / "experiments"
    monkeypatch.setenv(records.FE_CACHE_ENV, str(tmp_path))
    assert records.fe_cache_dir() == tmp_path


_PROBE = """\
from mechlib.records import REPO_ROOT, Recorder, fe_cache_dir
d = fe_cache_dir()
rec = Recorder("probe")
rec.value("cold_cache", not d.exists() or not any(d.iterdir()))
rec.value("private_cache", (REPO_ROOT / "build") not in d.parents)
rec.save()
"""


def test_determinism_rerun_is_cold_and_flags_a_changed_record(tmp_path: Path) -> None:
    nbformat = pytest.importorskip("nbformat")
    notebooks, first = tmp_path / "notebooks", tmp_path / "records"
    notebooks.mkdir()
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(_PROBE)])
    nbformat.write(nb, notebooks / "probe.ipynb")
    expected = Recorder("probe")
    expected.value("cold_cache", True)
    expected.value("private_cache", True)
    expected.save(first)
    # the re-run sees an empty FE cache of its own, so its record equals the expected one ...
    assert records.rerun_identical(first, notebooks) == []
    # ... and a first run that recorded something else is reported, naming the value
    wrong = Recorder("probe")
    wrong.value("cold_cache", False)
    wrong.value("private_cache", True)
    wrong.save(first)
    problems = records.rerun_identical(first, notebooks)
    assert len(problems) == 1 and "probe: second run differs" in problems[0]
    assert "cold_cache" in problems[0]
