"""The data bundle: transcribed tables, every record, our runs of Tables 2 and 4."""

from __future__ import annotations

import csv
import io
import json
import zipfile
from pathlib import Path

import numpy as np
import pytest

from mechlib import fespecs as fespecs  # the FE families a store holds, registered
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
    assert "table2_ours.csv" in readme
    again = bundle.write_bundle(tmp_path / "records", tmp_path / "again.zip")
    assert again.read_bytes() == out.read_bytes()  # equal contents, equal bytes


def test_bundle_needs_records(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match=r"no <notebook>\.json"):
        bundle.write_bundle(tmp_path, tmp_path / "b.zip")


def _store(folder: Path) -> Path:
    """A small store without FE: two HexFlex models with a linear and a non-linear task, two
    parallelogram models with a non-linear task each (one of two runs), keys as the code makes
    them."""
    from mechlib.campaign import store as st
    from mechlib.campaign.taskcache import task_key
    from mechlib.compliant.spec import MechanismSpec
    from mechlib.parallelogram import ourfe
    from mechlib.parallelogram.mechanism import layout

    fp = st.fingerprints()
    specs = [
        json.dumps({"geometry": {"thickness": t}, "mesh": "default", "mesh_size": 0.1,
                    "element": "q2", "young": 71700.0, "poisson": 0.33})
        for t in (0.5, 0.45)
    ]  # fmt: skip
    forces = np.array([[0.1, -0.2, 0.3, 0.0, 0.5, -1.0], [0.25, 0, 0, 0, 0, 0]])
    lin = np.arange(12.0).reshape(2, 6)
    nonlin = np.c_[np.arange(36.0).reshape(2, 18), [[3, 1, 0, 1e-12], [4, 2, 1, 2e-12]]]
    hexflex = fp["hexflex"]
    entries = [
        st.Entry(task_key(specs[0], "linear", forces, 1, hexflex), specs[0], "linear", 1, forces,
                 lin),
        st.Entry(task_key(specs[1], "nonlinear", forces, 2, hexflex), specs[1], "nonlinear", 2,
                 forces, nonlin),
    ]  # fmt: skip
    for layers, loads in ((2, [[0.0, 1.0, 0.0], [1.0, 0.5, 0.2]]), (1, [[0.5, 0.0, 0.1]])):
        spec = MechanismSpec(layout(stage_young=5e6), 10.0, layers).key()
        newton = ourfe.to_newton(loads)
        key = task_key(spec, "nonlinear", newton, 1, fp["mechanism"])
        entries.append(st.Entry(key, spec, "nonlinear", 1, newton, nonlin[: len(newton)] + layers))
    return st.write_store(entries, folder)


def test_store_tables_list_every_run_and_model(tmp_path: Path) -> None:
    from mechlib.pipeline import bundleruns

    tables = bundleruns.store_tables(_store(tmp_path / "store"))
    models = list(csv.DictReader(io.StringIO(tables["runs/models.csv"])))
    linear = list(csv.DictReader(io.StringIO(tables["runs/linear_runs.csv"])))
    nonlinear = list(csv.DictReader(io.StringIO(tables["runs/nonlinear_runs.csv"])))
    assert [m["thickness [mm]"] for m in models] == ["0.45", "0.5"]  # sorted by specification
    assert [r["model"] for r in linear] == ["M2", "M2"] and linear[1]["θz [µrad]"] == "11"
    assert linear[0]["T3D2 [N]"] == "-1"
    assert [r["model"] for r in nonlinear] == ["M1", "M1"] and nonlinear[0]["load steps"] == "2"
    assert nonlinear[1]["euler_xyz θz [µrad]"] == "35" and nonlinear[1]["restarts [count]"] == "1"
    assert float(nonlinear[0]["residual [relative]"]) == 1e-12


def test_store_tables_hold_the_parallelogram_runs_and_say_how_many(tmp_path: Path) -> None:
    from mechlib.compliant.spec import MechanismSpec
    from mechlib.pipeline import bundleruns

    folder = _store(tmp_path / "store")
    tables = bundleruns.store_tables(folder)
    models = list(csv.DictReader(io.StringIO(tables["runs/layout_models.csv"])))
    runs = list(csv.DictReader(io.StringIO(tables["runs/layout_nonlinear_runs.csv"])))
    assert [(m["model"], m["layers"]) for m in models] == [("L1", "1"), ("L2", "2")]
    spec = MechanismSpec.from_key(models[1]["specification (JSON)"])  # the model, in full
    assert spec.layers == 2 and spec.mesh_size == 10.0
    assert [r["model"] for r in runs] == ["L1", "L2", "L2"]
    assert float(runs[0]["M_z [N·mm]"]) > 0 and runs[1]["F_x [N]"] == "0"
    assert runs[2]["small x [µm]"] == "20" and runs[0]["corrections [count]"] == "4"  # 3 + 1
    manifest = json.loads((folder / "manifest.json").read_text())
    assert manifest["runs"]["nonlinear"] == 5  # two HexFlex runs, three parallelogram runs
    counts = bundleruns.run_counts(tables)
    assert counts == {"runs/linear_runs.csv": 2, "runs/nonlinear_runs.csv": 2,
                      "runs/layout_nonlinear_runs.csv": 3}  # fmt: skip
    readme = bundleruns.readme(tables)
    assert "5 non-linear and 2 linear runs in all" in readme
    assert "nonlinear_runs.csv: 2;" in readme and "layout_nonlinear_runs.csv: 3)" in readme
    assert max(len(line) for line in readme.splitlines()) <= 100


def test_store_tables_refuse_to_lose_runs(tmp_path: Path) -> None:
    from mechlib.campaign.store import StoreError
    from mechlib.pipeline import bundleruns

    folder = _store(tmp_path / "store")
    manifest = json.loads((folder / "manifest.json").read_text())
    manifest["runs"]["nonlinear"] += 1  # a run the tables would leave out
    (folder / "manifest.json").write_text(json.dumps(manifest))
    with pytest.raises(StoreError, match="hold 5 nonlinear runs, the store's manifest counts 6"):
        bundleruns.store_tables(folder)


def test_the_bundle_holds_as_many_runs_as_the_landing_quotes() -> None:
    """The repository's store: the bundle's runs of each kind are the manifest's, which the
    landing page quotes."""
    from mechlib.paths import STORE_DIR
    from mechlib.pipeline import bundleruns, storeline

    if not (STORE_DIR / "manifest.json").is_file():
        pytest.skip("no results store in this checkout")
    tables = bundleruns.store_tables(STORE_DIR)
    manifest = json.loads((STORE_DIR / "manifest.json").read_text())
    counts = bundleruns.run_counts(tables)
    nonlinear = sum(counts.get(n, 0) for n in bundleruns.RUN_FILES["nonlinear"])
    assert nonlinear == manifest["runs"]["nonlinear"]
    assert counts["runs/layout_nonlinear_runs.csv"] > 0  # the parallelogram's runs are in
    line = storeline.landing_line(STORE_DIR)
    if "read from the results store" in line:
        assert f"{nonlinear} geometrically non-linear runs" in line


def test_bundle_ships_notebook_data_and_the_evaluator(tmp_path: Path) -> None:
    import pandas as pd

    from mechlib.reporting.records import Recorder

    _records(tmp_path / "records")
    rec = Recorder("nonlinear_metamodels", paste=lambda *_: None)
    rec.add_data("realtime_model", {"format": "x", "coef": np.eye(2)}, about="the model")
    rec.add_data("curves", pd.DataFrame({"runs": [16, 32], "err [%]": [1.5, 0.25]}), about="c")
    rec.save(tmp_path / "records")
    out = bundle.write_bundle(
        tmp_path / "records", tmp_path / "b.zip", extra={"runs/x.csv": "a\n"}, extra_readme="X\n"
    )
    with zipfile.ZipFile(out) as archive:
        names = set(archive.namelist())
        readme = archive.read("README.txt").decode()
        model = json.loads(archive.read("data/nonlinear_metamodels/realtime_model.json"))
        curves = archive.read("data/nonlinear_metamodels/curves.csv").decode()
    assert {bundle.EVALUATOR, "runs/x.csv"} <= names
    assert "records/data" not in " ".join(names)  # data are not records
    assert model["coef"] == [[1.0, 0.0], [0.0, 1.0]] and curves == "runs,err [%]\n16,1.5\n32,0.25\n"
    assert "realtime_model.json: the model" in readme and readme.count("X\n") == 1
    assert "evaluator.py" in readme


def test_add_data_refuses_bad_names_and_kinds() -> None:
    from mechlib.reporting.records import Recorder

    rec = Recorder("nb", paste=lambda *_: None)
    with pytest.raises(ValueError, match="not \\[A-Za-z0-9_\\]"):
        rec.add_data("a/b", {}, about="x")
    with pytest.raises(ValueError, match="description"):
        rec.add_data("a", {}, about=" ")
    with pytest.raises(ValueError, match="DataFrame or a mapping"):
        rec.add_data("a", [1, 2], about="x")
    rec.add_data("a", {}, about="x")
    with pytest.raises(ValueError, match="already used"):
        rec.add_data("a", {}, about="y")


def test_the_link_says_what_the_zip_holds() -> None:
    small = bundle.link_text("/d.zip", 167_000, ["records/a.json"])
    assert "(one zip, 167 kB)" in small and "designs of Tables 2 and 4" in small
    assert "every FE run" not in small and "evaluator" not in small
    full = bundle.link_text("/d.zip", 2_100_000, ["runs/nonlinear_runs.csv", bundle.EVALUATOR])
    assert "(one zip, 2.1 MB)" in full and "every FE run the book reads" in full
    assert "plain-Python evaluator" in full and "learning curves" not in full


def test_the_bundle_carries_every_verdict_machine_readable(tmp_path: Path) -> None:
    """claims.json: the references' claims, each part with its record keys, values, limit and
    whether it can fail; no word rests on a part that cannot fail; the README says how to read
    it."""
    from mechlib.reporting import claimlist
    from mechlib.reporting import claims as claims_mod

    references = Path(__file__).parent / "references"
    out = bundle.write_bundle(references, tmp_path / bundle.NAME)
    with zipfile.ZipFile(out) as archive:
        data = json.loads(archive.read("claims.json"))
        readme = archive.read("README.txt").decode()
    assert "claims.json" in readme and "can_fail" in readme and "% of full scale" in readme
    by_id = {c["id"]: c for c in data["claims"]}
    assert set(by_id) <= set(claimlist.CLAIMS) and "ch2.linear" in by_id
    linear = by_id["ch2.linear"]
    assert linear["word"] == "not supported" and linear["where"] == "sec. 2.7; Table 5"
    assert [p["can_fail"] for p in linear["parts"]] == [False, True]
    part = linear["parts"][1]
    assert part["record_keys"][0]["key"] == "table5.nonlinear.max_range_pct"
    assert part["limit"] == 1.0 and part["holds"] is False and len(part["values"][0]) == 6
    for claim in data["claims"]:  # the word is the one its parts that can fail give
        holds = [p["holds"] for p in claim["parts"]]
        counted = [p["can_fail"] for p in claim["parts"]]
        assert claim["word"] == claims_mod.verdict_word(claim["source"], holds, counted)
        if not any(counted):
            assert claim["word"] == claims_mod.BY_CONSTRUCTION, claim["id"]
    assert by_id["ch3.i.5r"]["word"] == by_id["ch3.ii.5r"]["word"] == claims_mod.BY_CONSTRUCTION
