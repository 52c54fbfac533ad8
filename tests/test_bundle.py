"""The data bundle: transcribed tables, every record, our runs of Tables 2 and 4."""

from __future__ import annotations

import csv
import io
import json
import zipfile
from pathlib import Path

import numpy as np
import pytest

from mechlib import published as pub
from mechlib.pipeline import bundle


def _records(folder: Path) -> None:
    folder.mkdir()
    values = {"table2.responses": {"value": np.arange(72.0).reshape(12, 6).tolist()}}
    (folder / "virtual_experiments.json").write_text(json.dumps({"values": values}))
    (folder / "published_doe.json").write_text(json.dumps({"values": {}}))


def test_bundle_holds_the_thesis_tables_every_record_and_the_runs(tmp_path: Path) -> None:
    _records(tmp_path / "records")
    out = bundle.write_bundle(tmp_path / "records", tmp_path / "out" / bundle.NAME)
    with zipfile.ZipFile(out) as archive:
        names = archive.namelist()
        table7 = list(csv.reader(io.StringIO(archive.read("thesis/table7.csv").decode())))
        runs = list(csv.reader(io.StringIO(archive.read("runs/table2_ours.csv").decode())))
        readme = archive.read("README.txt").decode()
    assert {"records/virtual_experiments.json", "records/published_doe.json"} <= set(names)
    assert "runs/table4_ours.csv" not in names  # not recorded in this build
    assert table7[1] == ["A1x", "m", "-0.5", "-0.4988"] and table7[3][1] == ""
    assert runs[0][:2] == ["run", "T1D1 [N]"] and len(runs) == 13
    assert [float(v) for v in runs[1][1:7]] == pub.TABLE2_DESIGN[0].tolist()
    assert "Not included" in readme
    again = bundle.write_bundle(tmp_path / "records", tmp_path / "again.zip")
    assert again.read_bytes() == out.read_bytes()  # equal contents, equal bytes


def test_bundle_needs_records(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match=r"no <notebook>\.json"):
        bundle.write_bundle(tmp_path, tmp_path / "b.zip")
