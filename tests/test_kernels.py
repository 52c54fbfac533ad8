"""The BLAS kernel make test's notebooks run with (mechlib.pipeline.kernels)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from mechlib.pipeline import kernels


def test_the_other_kernel_is_neither_the_machines_nor_the_references() -> None:
    assert kernels.other_kernel("Haswell") == "Sandybridge"
    assert kernels.other_kernel("SkylakeX") == "Sandybridge"
    assert kernels.other_kernel("Sandybridge") == "Haswell"
    assert kernels.other_kernel("SkylakeX", {"Sandybridge"}) == "Haswell"
    assert kernels.other_kernel("Haswell", {"Sandybridge"}) == "Nehalem"
    with pytest.raises(ValueError, match="no kernel of"):
        kernels.other_kernel("Sandybridge", {"Haswell", "Nehalem"})


def _write(folder: Path, name: str, blas: str | None) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    payload = {"values": {}} | ({"blas": blas} if blas else {})
    (folder / f"{name}.json").write_text(json.dumps(payload))


def test_reference_kernels_and_the_own_kernel_check(tmp_path: Path) -> None:
    _write(tmp_path / "ref", "a", "Haswell")
    _write(tmp_path / "ref", "b", None)
    assert kernels.reference_kernels(tmp_path / "ref") == {"Haswell"}
    _write(tmp_path / "rec", "a", "Haswell")
    _write(tmp_path / "rec", "b", "Sandybridge")
    assert kernels.check_own_kernel(tmp_path / "rec", "Haswell") == [
        "b: computed with the Sandybridge kernel, not this machine's own (Haswell)"
    ]


@pytest.mark.parametrize("kernel", ["Sandybridge", "Haswell"])
def test_openblas_coretype_sets_the_kernel_a_process_reports(kernel: str) -> None:
    """The override make test relies on takes effect (and the name is what records carry)."""
    env = dict(os.environ, OPENBLAS_CORETYPE=kernel)
    out = subprocess.run(
        [sys.executable, "-m", "mechlib.pipeline.kernels", "own"],
        env=env, capture_output=True, text=True, check=True,
    )  # fmt: skip
    assert out.stdout.strip() == kernel


def test_spread_lists_values_that_move_more_than_a_tenth_of_their_tolerance(
    tmp_path: Path,
) -> None:
    ref = {"values": {"x": {"value": [1.0, 2.0], "rtol": 1e-3, "atol": 0.0},
                      "n": {"value": 3, "rtol": 0.0, "atol": 0.0}}}  # fmt: skip
    (tmp_path / "ref").mkdir()
    (tmp_path / "ref" / "nb.json").write_text(json.dumps(ref))
    for kernel, x in (("A", [1.0, 2.0]), ("B", [1.0, 2.0005])):
        (tmp_path / kernel).mkdir()
        rec = {"values": {"x": {"value": x}, "n": {"value": 3}}}
        (tmp_path / kernel / "nb.json").write_text(json.dumps(rec))
    runs = {k: tmp_path / k for k in "AB"}
    rows = kernels.spread(runs, tmp_path / "ref")
    assert len(rows) == 1 and rows[0].startswith("nb x[1]: spread 0.0005 = 0.25 of its tolerance")
    assert kernels.spread(runs, tmp_path / "ref", share=0.3) == []


def test_notebooks_executed_with_another_kernel_are_forgotten(tmp_path: Path) -> None:
    _write(tmp_path / "rec", "a", "Haswell")
    _write(tmp_path / "rec", "b", "Sandybridge")
    (tmp_path / "ex").mkdir()
    for name in "abc":
        (tmp_path / "ex" / f"{name}.ipynb").write_text("{}")
    assert kernels.forget_other_kernels(tmp_path / "rec", tmp_path / "ex", "Sandybridge") == ["a"]
    assert sorted(p.stem for p in (tmp_path / "ex").glob("*.ipynb")) == ["b", "c"]
