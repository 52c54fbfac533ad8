"""A notebook parameter of the wrong type or range stops the run with a clear message."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

from mechlib.paths import REPO_ROOT
from mechlib.pipeline.execute import papermill_command

_PYTHONPATH = {k: v for k, v in os.environ.items() if k == "PYTHONPATH"}


def _run_with(name: str, args: list[str], tmp_path: Path) -> tuple[int, str]:
    """Run notebooks/<name>.ipynb with papermill ``args``; return its exit code and all output."""
    nb = REPO_ROOT / "notebooks" / f"{name}.ipynb"
    out = tmp_path / "out.ipynb"
    done = subprocess.run(
        papermill_command(nb, out, args),
        capture_output=True,
        text=True,
        # nothing of the caller's environment but where it imports mechlib from, if it says
        env={"MECHLIB_RECORDS": str(tmp_path), "PATH": "", **_PYTHONPATH},
        check=False,
    )
    return done.returncode, done.stderr + (out.read_text() if out.exists() else "")


def test_bad_notebook_parameter_fails_with_its_name(tmp_path: Path) -> None:
    args = ["-p", "penalty", "elastic-net", "-p", "n_random_designs", "10"]
    code, output = _run_with("published_doe", args, tmp_path)
    assert code != 0
    assert "penalty must be one of ['ridge', 'lasso'], got 'elastic-net'" in output
    assert not (tmp_path / "published_doe.json").exists()


def test_a_sweep_that_is_not_increasing_is_refused_by_name(tmp_path: Path) -> None:
    args = ["-y", "sweep_amplitudes: [1.0, 0.1]"]
    code, output = _run_with("virtual_experiments", args, tmp_path)
    assert code != 0
    assert "sweep_amplitudes [N] must list at least 2 strictly increasing values" in output
    assert not (tmp_path / "virtual_experiments.json").exists()


def test_a_geometry_with_an_unknown_dimension_is_refused_by_name(tmp_path: Path) -> None:
    args = ["-y", "geometry: {colour: 1.0}"]
    code, output = _run_with("virtual_experiments", args, tmp_path)
    assert code != 0
    assert "unknown: ['colour']" in output
    assert not (tmp_path / "virtual_experiments.json").exists()


def test_a_dimension_out_of_its_bounds_is_refused_before_meshing(tmp_path: Path) -> None:
    code, output = _run_with("hexflex_model", ["-p", "beam_length", "40.0"], tmp_path)
    assert code != 0
    assert "beam_length [mm] must be in [2.0, 30.0], got 40.0" in output
    assert not (tmp_path / "hexflex_model.json").exists()


def test_a_negative_noise_level_is_refused_before_any_computation(tmp_path: Path) -> None:
    code, output = _run_with("beyond_5r", ["-p", "sigma", "-0.001"], tmp_path)
    assert code != 0
    assert "sigma [m, rad] must be" in output and "-0.001" in output
    assert not (tmp_path / "beyond_5r.json").exists()


def test_the_family_page_solves_no_more_runs_than_the_doe_chapters_draw(tmp_path: Path) -> None:
    # n_validation is the DOE chapter's (the build passes it); family_runs are the draw's first
    args = ["-p", "n_validation", "10", "-p", "family_runs", "20"]
    code, output = _run_with("nonlinear_family", args, tmp_path)
    assert code != 0
    assert "family_runs must be in [1, 10], got 20" in output
    assert not (tmp_path / "nonlinear_family.json").exists()


def test_a_drawn_load_out_of_the_elastica_range_is_refused_by_name(tmp_path: Path) -> None:
    code, output = _run_with("beyond_hexflex", ["-y", "drawn_loads: [[0, 50, 0]]"], tmp_path)
    assert code != 0
    assert "a_y (F_y L^2/EI) must be in [-40.0, 40.0], got 50.0" in output
    assert not (tmp_path / "beyond_hexflex.json").exists()


def test_a_mesh_size_out_of_range_is_refused_before_any_fe_run(tmp_path: Path) -> None:
    code, output = _run_with("parallelogram_fe", ["-p", "mesh_size", "50"], tmp_path)
    assert code != 0
    assert "mesh_size [mm] must be" in output and "50" in output
    assert not (tmp_path / "parallelogram_fe.json").exists()
