"""The Recorder, and the build wing's record helpers: compare, update, the cold re-run."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from pasting import pasting_recorder  # tests/ is on sys.path (pytest prepend import mode)

from mechlib import paths
from mechlib.pipeline.book import quoted
from mechlib.pipeline.cli import main as pipeline_main
from mechlib.pipeline.references import compare, update_references
from mechlib.pipeline.rerun import rerun, rerun_differences, rerun_identical
from mechlib.reporting import report
from mechlib.reporting.records import Recorder, load


def test_recorder_roundtrip_and_deterministic_bytes(tmp_path: Path) -> None:
    def write(folder: Path) -> bytes:
        rec = Recorder("demo")
        rec.value("b.matrix", np.arange(4.0).reshape(2, 2), rtol=1e-9)
        rec.value("a.flag", True)
        rec.value("a.count", np.int64(3), atol=0)
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
    rec.value("k", 1.0, atol=0)
    with pytest.raises(ValueError, match="already recorded"):
        rec.value("k", 2.0, atol=0)
    with pytest.raises(ValueError, match="rtol must be >= 0"):
        rec.value("j", 1.0, rtol=-1)
    with pytest.raises(ValueError, match="finite"):
        rec.value("nan", float("nan"), atol=0)
    for number in (1.0, 3, [1, 2], np.zeros(2)):  # a number states its tolerance, even exact
        with pytest.raises(ValueError, match="with its tolerance"):
            rec.value("t", number)
    rec.value("flag", np.bool_(True))  # booleans and strings are exact by nature
    rec.value("label", "θx")


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


def test_fe_cache_dir_follows_its_environment_variable(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv(paths.FE_CACHE_ENV, raising=False)
    assert paths.fe_cache_dir() == paths.REPO_ROOT / "build" / "cache" / "experiments"
    monkeypatch.setenv(paths.FE_CACHE_ENV, str(tmp_path))
    assert paths.fe_cache_dir() == tmp_path


_PROBE = """\
from mechlib.paths import fe_cache_dir, records_dir
from mechlib.reporting.records import Recorder
d = fe_cache_dir()
rec = Recorder("probe")
rec.value("cold_cache", not d.exists() or not any(d.iterdir()))
rec.value("private_cache", d.is_absolute() and d.parent == records_dir().parent)
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
    assert rerun_identical(first, notebooks) == []
    # ... and a first run that recorded something else is reported, naming the value
    wrong = Recorder("probe")
    wrong.value("cold_cache", False)
    wrong.value("private_cache", True)
    wrong.save(first)
    problems = rerun_identical(first, notebooks)
    assert len(problems) == 1 and "probe: second run differs" in problems[0]
    assert "cold_cache" in problems[0]


def test_a_rerun_into_a_relative_folder_writes_there(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    nbformat = pytest.importorskip("nbformat")
    (tmp_path / "nbs").mkdir()
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(_PROBE)])
    nbformat.write(nb, tmp_path / "nbs" / "probe.ipynb")
    monkeypatch.chdir(tmp_path)  # the kernel runs in nbs/: a relative path must not follow it
    assert pipeline_main(["rerun", "--out", "out", "--notebooks", "nbs"]) == 0
    values = load(tmp_path / "out" / "records" / "probe.json")["values"]
    assert values["cold_cache"]["value"] is True and values["private_cache"]["value"] is True


_CACHE_PROBE = """\
import os
from mechlib.paths import fe_cache_dir, fe_log_path
from mechlib.reporting.records import Recorder
rec = Recorder("probe")
rec.value("copied", sorted(p.name for p in fe_cache_dir().iterdir()))
rec.value("log_in_rerun", fe_log_path().parent == fe_cache_dir().parent)
rec.save()
"""


def test_a_rerun_from_a_cache_copy_reads_a_copy_and_logs_hits(tmp_path: Path) -> None:
    nbformat = pytest.importorskip("nbformat")
    (tmp_path / "nbs").mkdir()
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(_CACHE_PROBE)])
    nbformat.write(nb, tmp_path / "nbs" / "probe.ipynb")
    first = tmp_path / "cache"
    first.mkdir()
    (first / "a.npy").write_bytes(b"x")
    rerun(tmp_path / "nbs", tmp_path / "out", fe_cache_from=first)
    values = load(tmp_path / "out" / "records" / "probe.json")["values"]
    assert values["copied"]["value"] == ["a.npy"] and values["log_in_rerun"]["value"] is True
    (tmp_path / "out" / "fe-cache" / "a.npy").unlink()
    assert (first / "a.npy").exists()  # a copy: the first run's cache is untouched
    with pytest.raises(RuntimeError, match="fe_cache_from"):
        rerun(tmp_path / "nbs", tmp_path / "out2", fe_cache_from=tmp_path / "missing")


def test_a_rerun_names_the_notebook_that_failed_and_a_missing_record(tmp_path: Path) -> None:
    nbformat = pytest.importorskip("nbformat")
    notebooks = tmp_path / "notebooks"
    notebooks.mkdir()
    cell = nbformat.v4.new_code_cell('raise ValueError("probe_broke")')
    nbformat.write(nbformat.v4.new_notebook(cells=[cell]), notebooks / "broken.ipynb")
    with pytest.raises(RuntimeError, match=r"(?s)re-run of broken.ipynb failed.*probe_broke"):
        rerun(notebooks, tmp_path / "out")
    # a first-run record with no re-run record is a difference, not a pass
    first = tmp_path / "records"
    Recorder("broken").save(first)
    problems = rerun_differences(first, tmp_path / "out" / "records", notebooks)
    assert len(problems) == 1 and "broken: no re-run record" in problems[0]


def test_a_failed_chapter_stops_the_rerun_without_waiting_for_its_sibling(tmp_path: Path) -> None:
    import time

    nbformat = pytest.importorskip("nbformat")
    notebooks = tmp_path / "notebooks"
    notebooks.mkdir()
    for name, code in (("broken", 'raise ValueError("probe_broke")'),
                       ("slow", "import time\ntime.sleep(120)")):  # fmt: skip
        nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(code)])
        nb.metadata["kernelspec"] = {"name": "python3", "language": "python", "display_name": "Py"}
        nbformat.write(nb, notebooks / f"{name}.ipynb")
    t0 = time.monotonic()
    with pytest.raises(RuntimeError, match=r"re-run of broken\.ipynb failed"):
        rerun(notebooks, tmp_path / "out", jobs=2)
    assert time.monotonic() - t0 < 60  # the sleeping sibling (120 s) was stopped


# --- one call: record, glue, report ------------------------------------------------------------
def _pasting() -> tuple[Recorder, dict]:
    return pasting_recorder("nb")


def test_a_glued_value_is_recorded_and_pasted_as_a_python_number(tmp_path: Path) -> None:
    rec, pasted = _pasting()
    rec.value("miw.radius", np.float64(0.25), rtol=1e-9, glue="miw_r")
    rec.value("lenth.nu", np.array([19.6, 0.0, 3.1]), rtol=1e-9, glue={"nu_x": 0, "nu_thz": 2})
    rec.value("s.matrix", np.arange(4.0).reshape(2, 2), atol=0, glue={"s_10": (1, 0)})
    rec.value("n.runs", np.int64(12), atol=0, glue="n_runs")
    assert pasted == {"miw_r": 0.25, "nu_x": 19.6, "nu_thz": 3.1, "s_10": 2.0, "n_runs": 12}
    assert [type(pasted[k]) for k in ("miw_r", "s_10", "n_runs")] == [float, float, int]
    saved = load(rec.save(tmp_path))
    assert saved["values"]["miw.radius"] == {"value": 0.25, "rtol": 1e-9, "atol": 0.0}
    assert saved["glue"]["miw_r"] == {"key": "miw.radius"}
    assert saved["glue"]["s_10"] == {"key": "s.matrix", "index": [1, 0]}
    assert quoted.unchecked_glue(saved, ["miw_r", "nu_x", "s_10", "n_runs"]) == []


def test_a_value_glued_with_the_wrong_number_fails_the_comparison(tmp_path: Path) -> None:
    reference = Recorder("nb", paste=lambda name, v: None)
    reference.value("mc.rms_dc_um", 41.7, rtol=1e-6, glue="rms_dc")
    rec, pasted = _pasting()
    rec.value("mc.rms_dc_um", 41.8, rtol=1e-6, glue="rms_dc")  # what the prose now quotes
    assert pasted == {"rms_dc": 41.8}
    problems = compare(load(rec.save(tmp_path / "run")), load(reference.save(tmp_path / "ref")))
    assert len(problems) == 1 and problems[0].startswith("mc.rms_dc_um: got 41.8, reference 41.7")


def test_a_number_quoted_around_the_recorder_is_found() -> None:
    rec, _ = _pasting()
    rec.value("a", 1.0, atol=0, glue="a")
    rec.text("component", "θx", of="a")
    rec.text("latency", "3.2", why="machine-dependent timing")
    record = {"notebook": "nb", "values": rec.values, "glue": rec.glued}
    markdown = "{glue:text}`a:.2f`, {glue:text}`component`, {glue}`latency`, {glue:text}`b:.1f`"
    names = [n for _, n in quoted.glue_references(markdown)]
    assert quoted.unchecked_glue(record, names) == ["nb: 'b' is quoted but not glued by Recorder"]
    record["glue"]["c"] = {"key": "gone"}
    assert quoted.unchecked_glue(record, ["c"]) == ["nb: 'c' is glued from 'gone', not recorded"]


def test_glue_references_name_the_page_and_drop_the_format() -> None:
    text = "x {glue:text}`chapters/a.ipynb::ratio:.1f` y {glue}`n` z {glue:text}`p:.2%`"
    assert quoted.glue_references(text) == [("chapters/a.ipynb", "ratio"), ("", "n"), ("", "p")]


def test_bad_glue_and_text_are_refused() -> None:
    rec, pasted = _pasting()
    rec.value("v", [1.0, 2.0], atol=0, glue={"v0": 0})
    with pytest.raises(ValueError, match="must name one number"):
        rec.value("w", [1.0, 2.0], atol=0, glue="w")  # an array needs an index per name
    with pytest.raises(ValueError, match="must name one number"):
        rec.value("f", True, glue="f")  # a bool is no number to quote
    with pytest.raises(ValueError, match="already used"):
        rec.value("u", [3.0, 4.0], atol=0, glue={"fresh": 0, "v0": 1})
    assert "fresh" not in rec.glued  # a refused call leaves nothing behind
    with pytest.raises(ValueError, match="of=\\) or why"):
        rec.text("t", "θx")
    with pytest.raises(ValueError, match="not recorded"):
        rec.text("t", "θx", of="nowhere")
    with pytest.raises(ValueError, match="str or NaN"):
        rec.text("t", 0.5, why="a number must not dodge its record")
    assert np.isnan(rec.text("t", float("nan"), why="not computed in this run"))
    assert np.isnan(pasted["t"])
    assert list(pasted) == ["v0", "t"] and "w" not in rec.values and "u" not in rec.values


def test_report_rows_report_the_recorded_value() -> None:
    rec, _ = _pasting()
    published = [1.0, 2.0]
    rec.value(
        "t.eff",
        [1.004, 2.0],
        rtol=1e-9,
        row=report.Comparison("Table 3", "effects", published, resolution=0.005),
    )
    rec.value(
        "t.part", [[5.0, 1.0]], rtol=0, atol=0, row=report.Comparison("Eq 8", "x", 1.0, part=(0, 1))
    )
    rec.value(
        "t.holds",
        [True, True],
        row=report.Check("Fig 6", "statement", "evidence", basis="thesis-inconsistency"),
    )
    rec.value("t.dims", [0.3, 0.5], atol=0, row=report.Computed("Fig 2", "dims"))
    verdicts = [r["verdict"] for r in rec.report]
    assert verdicts == ["reproduced", "reproduced", "consistent inside the thesis", report.COMPUTED]
    assert rec.report[0]["ours"] == "1.004, 2"
    with pytest.raises(ValueError, match="a cause must be given"):
        rec.value("t.bad", 1.2, rtol=0, row=report.Comparison("T", "q", 1.0))
    with pytest.raises(TypeError, match="a check holds or not"):
        rec.value("t.num", 0.7, atol=0, row=report.Check("T", "c", "e", basis="construction"))
    assert "t.bad" not in rec.values and "t.num" not in rec.values


def test_the_rerun_runs_two_chapters_at_a_time_each_after_its_inputs(tmp_path: Path) -> None:
    nbformat = pytest.importorskip("nbformat")
    notebooks, marker = tmp_path / "notebooks", tmp_path / "independent-started"
    notebooks.mkdir()
    stamp = (
        "import time\nfrom pathlib import Path\nfrom mechlib.reporting.records import Recorder\n"
    )
    stamp += f"M = Path({str(marker)!r})\n"
    upstream = stamp + (  # the model page waits (30 s at most) for the independent chapter
        "t0 = time.time()\nwhile not M.exists() and time.time() - t0 < 30:\n    time.sleep(0.1)\n"
        "rec = Recorder('hexflex_model')\nrec.value('saw_the_other_running', M.exists())\n"
        "rec.value('geometry.thickness', 0.5, rtol=0)\n"
        "rec.value('model.mesh_fraction', 0.5, atol=0)\nrec.save()\n"
    )
    downstream_params = "geometry = None\nmesh_fraction = None\n"
    downstream = stamp + (
        "rec = Recorder('virtual_experiments')\n"
        "rec.value('got_inputs', geometry == {'thickness': 0.5} and mesh_fraction == 0.5)\n"
        "rec.save()\n"
    )
    independent = stamp + "M.touch()\nrec = Recorder('fivebar_identification')\nrec.save()\n"
    for name, cells in (
        ("hexflex_model", [upstream]),
        ("virtual_experiments", [downstream_params, downstream]),
        ("fivebar_identification", [independent]),
    ):
        nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(c) for c in cells])
        nb.cells[0].metadata["tags"] = ["parameters"] if name == "virtual_experiments" else []
        nb.metadata["kernelspec"] = {"name": "python3", "language": "python", "display_name": "Py"}
        nbformat.write(nb, notebooks / f"{name}.ipynb")
    rerun(notebooks, tmp_path / "out", jobs=2)
    got = {n: load(tmp_path / "out" / "records" / f"{n}.json")["values"] for n in
           ("hexflex_model", "virtual_experiments")}  # fmt: skip
    # the DOE chapter ran after the model page (it got its inputs), the last chapter of the
    # order beside it (one at a time, the model page would have waited for it in vain)
    assert got["virtual_experiments"]["got_inputs"]["value"] is True
    assert got["hexflex_model"]["saw_the_other_running"]["value"] is True
    with pytest.raises(ValueError, match="jobs"):
        rerun(notebooks, tmp_path / "out", jobs=0)


def test_a_timing_is_kept_apart_glued_and_ignored_by_the_determinism_check(tmp_path: Path) -> None:
    rec, pasted = _pasting()
    rec.value("model.worst_pct", 0.05, rtol=1e-3)
    rec.timing("model.single_us", 42.5, glue="single_us")
    assert pasted == {"single_us": 42.5}
    with pytest.raises(ValueError, match="already recorded"):
        rec.timing("model.worst_pct", 1.0)
    with pytest.raises(ValueError, match=r"model\.slow_us"):
        rec.timing("model.slow_us", float("nan"))
    first = load(rec.save(tmp_path / "a"))
    assert (
        first["timings"] == {"model.single_us": 42.5} and "model.single_us" not in first["values"]
    )
    assert quoted.unchecked_glue(first, ["single_us"]) == []
    again = Recorder("nb", paste=lambda *a: None)
    again.value("model.worst_pct", 0.05, rtol=1e-3)
    again.timing("model.single_us", 51.0, glue="single_us")
    again.save(tmp_path / "b")
    notebooks = tmp_path / "notebooks"
    notebooks.mkdir()
    (notebooks / "nb.ipynb").write_text("{}")
    assert rerun_differences(tmp_path / "a", tmp_path / "b", notebooks) == []
    other = Recorder("nb", paste=lambda *a: None)
    other.value("model.worst_pct", 0.06, rtol=1e-3)
    other.timing("model.single_us", 42.5)
    other.save(tmp_path / "c")
    assert rerun_differences(tmp_path / "a", tmp_path / "c", notebooks)  # a value changed
    # a record without timings is written as before (no empty section)
    assert "timings" not in load(Recorder("plain", paste=lambda *a: None).save(tmp_path))
