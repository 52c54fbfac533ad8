"""The re-run given the first run: its chapters' inputs and their order."""

from __future__ import annotations

from pathlib import Path

import pytest

from mechlib.pipeline.rerun import longest_first, rerun
from mechlib.reporting.records import Recorder, load


def test_a_rerun_given_the_first_run_takes_its_inputs_and_starts_longest_first(
    tmp_path: Path,
) -> None:
    nbformat = pytest.importorskip("nbformat")
    notebooks, marker = tmp_path / "notebooks", tmp_path / "downstream-ran"
    notebooks.mkdir()
    stamp = "from pathlib import Path\nfrom mechlib.reporting.records import Recorder\n"
    stamp += f"M = Path({str(marker)!r})\n"
    cells = {
        "hexflex_model": [
            stamp + "rec = Recorder('hexflex_model')\n"
            "rec.value('downstream_ran_before', M.exists())\n"
            "rec.value('geometry.thickness', 0.5, rtol=0)\n"
            "rec.value('model.mesh_fraction', 0.5, atol=0)\nrec.save()\n"
        ],
        "virtual_experiments": [
            "geometry = None\nmesh_fraction = None\n",
            stamp + "M.touch()\nrec = Recorder('virtual_experiments')\n"
            "rec.value('thickness', geometry['thickness'], rtol=0)\nrec.save()\n",
        ],
    }
    first = tmp_path / "first"
    for name, sources in cells.items():
        nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(c) for c in sources])
        nb.cells[0].metadata["tags"] = ["parameters"] if name == "virtual_experiments" else []
        nb.metadata["kernelspec"] = {"name": "python3", "language": "python", "display_name": "Py"}
        nbformat.write(nb, notebooks / f"{name}.ipynb")
        # the first run's executed copy: the downstream chapter took longest
        nb.metadata["papermill"] = {"duration": 9.0 if name == "virtual_experiments" else 1.0}
        (first / "executed").mkdir(parents=True, exist_ok=True)
        nbformat.write(nb, first / "executed" / f"{name}.ipynb")
    upstream = Recorder("hexflex_model", paste=lambda *a: None)
    upstream.value("geometry.thickness", 0.7, rtol=0)  # the first run's value, not the re-run's
    upstream.value("model.mesh_fraction", 0.5, atol=0)
    upstream.save(first / "records")
    rerun(notebooks, tmp_path / "out", jobs=1, first_run=first)
    got = {n: load(tmp_path / "out" / "records" / f"{n}.json")["values"] for n in cells}
    # one job: the longest chapter went first, on the first run's record, before its upstream
    assert got["virtual_experiments"]["thickness"]["value"] == 0.7
    assert got["hexflex_model"]["downstream_ran_before"]["value"] is True
    order = longest_first(
        [notebooks / "a.ipynb", *sorted(notebooks.glob("*.ipynb"))], first / "executed"
    )
    assert [p.stem for p in order] == ["a", "virtual_experiments", "hexflex_model"]
    with pytest.raises(RuntimeError, match="first_run"):
        rerun(notebooks, tmp_path / "out", first_run=tmp_path / "nowhere")
    (first / "records" / "hexflex_model.json").unlink()  # refused before the re-run is removed
    with pytest.raises(RuntimeError, match="lack an input of virtual_experiments"):
        rerun(notebooks, tmp_path / "out", first_run=first)
    assert (tmp_path / "out" / "records" / "hexflex_model.json").exists()
