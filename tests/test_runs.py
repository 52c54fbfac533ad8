"""The build wing's notebook execution: the papermill command, chapter inputs, parameter-name
checks, ``make run``'s failure line."""

from __future__ import annotations

import base64
import json
import re
from pathlib import Path

import pytest
import yaml

from mechlib.paths import REPO_ROOT
from mechlib.pipeline import chapters, execute, parameters, runs

ALLOWED = ["seed", "sigma", "n_per_leg", "sweep_amplitudes"]


def _notebook(path: Path, cells: list[dict]) -> Path:
    path.write_text(json.dumps({"cells": cells, "metadata": {}, "nbformat": 4}))
    return path


def _parameters_cell(source: list[str]) -> dict:
    return {"cell_type": "code", "metadata": {"tags": ["parameters"]}, "source": source}


def test_papermill_command_is_the_one_command_line() -> None:
    cmd = execute.papermill_command(
        Path("notebooks/a.ipynb"), Path("/out/a.ipynb"), ["-p", "seed", "1"], python="/env/bin/py"
    )
    assert cmd == [
        "/env/bin/py",
        "-m",
        "mechlib.pipeline.papermillrun",
        "-k",
        "python3",
        "--cwd",
        "notebooks",
        "--no-progress-bar",
        "notebooks/a.ipynb",
        "/out/a.ipynb",
        "-p",
        "seed",
        "1",
    ]


def test_every_papermill_parameter_form_is_read(tmp_path: Path) -> None:
    params_file = tmp_path / "p.yaml"
    params_file.write_text("n_per_leg: 9\nseed: 3\n")
    args = [
        *("-p", "sigma", "-1e-3"),  # a negative value is a value, not an option
        *("-k", "python3"),  # other papermill options are passed over
        *("-r", "seed", "7"),
        *("-y", "sweep_amplitudes: [0.1, 1.0]\nseed: 1"),
        "--parameters_yaml=sigma: 0.5",
        *("-psigm", "2"),  # click's short option with its first value attached
        *("-f", str(params_file)),
        *("--parameters_base64", base64.b64encode(b"colour: red").decode()),
        *("--parameters", "n_per_leg", "4"),
    ]
    assert parameters.given_parameters(args) == [
        "sigma",
        "seed",
        "sweep_amplitudes",
        "seed",
        "sigma",
        "sigm",
        "n_per_leg",
        "seed",
        "colour",
        "n_per_leg",
    ]
    assert parameters.given_parameters(["-y", ""]) == []


def test_malformed_parameter_arguments_are_refused(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"-p needs a name and a value, got \['-p', 'sigma'\]"):
        parameters.given_parameters(["-p", "sigma"])
    with pytest.raises(ValueError, match="-y must give a YAML mapping of parameter names"):
        parameters.given_parameters(["-y", "[1, 2]"])
    with pytest.raises(ValueError, match=r"-y must give a YAML mapping, got 'a: \[1' \(expected"):
        parameters.given_parameters(["-y", "a: [1"])
    with pytest.raises(ValueError, match="cannot read the file"):
        parameters.given_parameters(["-f", str(tmp_path / "missing.yaml")])
    with pytest.raises(ValueError, match="-b must be base64-encoded YAML"):
        parameters.given_parameters(["-b", "not base64!"])


def test_unknown_parameter_names_are_refused_by_name() -> None:
    given = parameters.check_parameter_names(["-p", "sigma", "1e-3", "-y", "seed: 2"], ALLOWED)
    assert given == ["sigma", "seed"]
    with pytest.raises(ValueError) as info:
        parameters.check_parameter_names(
            ["-p", "sigm", "1e-3", "-y", "colour: 1"], ALLOWED, "nb.ipynb"
        )
    assert str(info.value) == (
        "unknown parameter 'sigm' (did you mean 'sigma'?), 'colour' for nb.ipynb: its parameters "
        "cell defines seed, sigma, n_per_leg, sweep_amplitudes"
    )


def test_notebook_parameters_are_the_parameters_cell_assignments(tmp_path: Path) -> None:
    nb = _notebook(
        tmp_path / "a.ipynb",
        [
            {"cell_type": "markdown", "metadata": {}, "source": ["x = 1"]},
            _parameters_cell(
                [
                    "# a comment = with an equals sign\n",
                    "seed = 2010  # a = b in the comment\n",
                    "sigma: float = 1e-4\n",
                    "a, b = 1, 2\n",
                    "shape = {\n",
                    "    'r': 1.0,\n",
                    "}\n",
                ]
            ),
            {"cell_type": "code", "metadata": {}, "source": "later = 3"},
        ],
    )
    assert parameters.notebook_parameters(nb) == ["seed", "sigma", "a", "b", "shape"]
    assert parameters.notebook_parameters(_notebook(tmp_path / "none.ipynb", [])) == []
    bad = _notebook(tmp_path / "bad.ipynb", [_parameters_cell(["x = (\n"])])
    with pytest.raises(ValueError, match=r"the parameters cell of .*bad\.ipynb is not Python"):
        parameters.notebook_parameters(bad)


def test_a_parameter_papermill_cannot_see_is_still_a_parameter() -> None:
    # the line of tab_half_width holds a second "=" in its comment: papermill's inspection
    # skips it (and would warn "Passed unknown parameter"), the parameters cell defines it
    names = parameters.notebook_parameters(REPO_ROOT / "notebooks" / "hexflex_model.ipynb")
    assert "tab_half_width" in names and "stage_radius" in names


def test_the_failure_line_is_the_error_that_stopped_the_notebook() -> None:
    executed = {
        "cells": [
            {"cell_type": "markdown", "source": "An Exception was encountered"},
            {
                "cell_type": "code",
                "execution_count": 2,
                "outputs": [
                    {"output_type": "stream", "name": "stdout", "text": "hello"},
                    {"output_type": "error", "ename": "SystemExit", "evalue": "0"},
                ],
            },
            {
                "cell_type": "code",
                "execution_count": 3,
                "outputs": [
                    {
                        "output_type": "error",
                        "ename": "ValueError",
                        "evalue": "sigma must be >= 0, got -0.001",
                        "traceback": ["\x1b[0;31mValueError\x1b[0m long traceback"],
                    }
                ],
            },
        ]
    }
    assert runs.failure_message(executed) == (
        "ValueError: sigma must be >= 0, got -0.001 (cell In [3])"
    )
    executed["cells"][2]["outputs"][0]["evalue"] = "first line\n  second line"
    assert runs.failure_message(executed) == "ValueError: first line second line (cell In [3])"
    assert runs.failure_message({"cells": executed["cells"][:2]}) is None


def test_relay_holds_back_the_traceback() -> None:
    lines = ["Input Notebook: a\n", "Traceback (most recent call last):\n", '  File "x"\n', "E\n"]
    shown: list[str] = []
    held = runs.relay(lines, shown.append)
    assert shown == lines[:1] and held == lines[1:]


def test_a_misspelled_parameter_stops_make_run_before_anything_runs(tmp_path: Path, capsys) -> None:
    nb = _notebook(tmp_path / "nb.ipynb", [_parameters_cell(["sigma = 1e-4\n"])])
    argv = ["--notebook", str(nb), "--out", str(tmp_path / "runs"), "--", "-p", "sigm", "1e-3"]
    assert runs.main(argv) == 2
    err = capsys.readouterr().err
    assert "refused, nothing was run: unknown parameter 'sigm' (did you mean 'sigma'?)" in err
    assert "defines sigma" in err
    assert not (tmp_path / "runs").exists()


def test_a_chapter_gets_its_inputs_from_the_upstream_record(tmp_path: Path, capsys) -> None:
    references = REPO_ROOT / "tests" / "references"  # copies of records, as a records folder
    model = json.loads((references / "hexflex_model.json").read_text())["values"]
    inputs = execute.chapter_inputs("virtual_experiments", references, strict=True)
    assert inputs["mesh_fraction"] == model["model.mesh_fraction"]["value"]
    assert inputs["geometry"]["thickness"] == model["geometry.thickness"]["value"]
    assert sorted(inputs["geometry"]) == sorted(
        k.removeprefix("geometry.") for k in model if k.startswith("geometry.")
    )
    # a value the run gives itself is kept; a notebook without inputs gets none
    assert list(execute.chapter_inputs("virtual_experiments", references, ["geometry"])) == [
        "mesh_fraction"
    ]
    assert execute.input_arguments("published_doe", tmp_path) == []
    # the -y text papermill reads back gives the recorded floats exactly
    option, text = execute.input_arguments("virtual_experiments", references, strict=True)
    assert option == "-y" and yaml.safe_load(text) == inputs
    with pytest.raises(FileNotFoundError, match=r"'hexflex_model'.*make notebooks"):
        execute.chapter_inputs("virtual_experiments", tmp_path, strict=True)
    assert capsys.readouterr().err == ""
    # the family page draws the DOE chapter's validation runs: its seed and its size
    doe_values = json.loads((references / "virtual_experiments.json").read_text())["values"]
    family = execute.chapter_inputs("nonlinear_family", references, strict=True)
    assert family["seed"] == doe_values["parameters.seed"]["value"]
    assert family["n_validation"] == doe_values["parameters.n_validation"]["value"]


def test_a_run_reads_the_default_build_inputs_with_a_note(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys
) -> None:
    default = tmp_path / "build"
    (default / "records").mkdir(parents=True)
    record = REPO_ROOT / "tests" / "references" / "hexflex_model.json"
    (default / "records" / "hexflex_model.json").write_bytes(record.read_bytes())
    monkeypatch.setattr(execute, "DEFAULT_BUILD", default)
    assert "geometry" in execute.chapter_inputs("virtual_experiments", tmp_path / "run")
    assert "hexflex_model's record taken from" in capsys.readouterr().err
    with pytest.raises(FileNotFoundError):
        execute.chapter_inputs("virtual_experiments", tmp_path / "run", strict=True)


def test_every_notebook_is_a_chapter_and_its_inputs_are_its_parameters() -> None:
    notebooks = REPO_ROOT / "notebooks"
    assert sorted(chapters.CHAPTERS) == sorted(p.stem for p in notebooks.glob("*.ipynb"))
    chapters.check_order()
    for chapter, inputs in chapters.CHAPTER_INPUTS.items():
        assert set(inputs) <= set(parameters.notebook_parameters(notebooks / f"{chapter}.ipynb"))
    assert chapters.upstream("virtual_experiments") == ["hexflex_model"]
    names = [Path(f"x/{c}.ipynb") for c in reversed(chapters.CHAPTERS)] + [Path("a.ipynb")]
    assert [p.stem for p in chapters.in_order(names)] == [*chapters.CHAPTERS, "a"]


def test_an_input_from_a_later_chapter_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(chapters.CHAPTER_INPUTS, "hexflex_model", {"g": ("beyond_5r", "k")})
    with pytest.raises(ValueError, match="'hexflex_model' comes from 'beyond_5r'"):
        chapters.check_order()


def test_a_chapter_deferred_after_a_later_one_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    chapters.check_order()  # the declared deferrals hold
    monkeypatch.setitem(chapters.DEFERRED, "hexflex_model", "beyond_5r")
    with pytest.raises(ValueError, match="deferred chapter 'hexflex_model' must come after"):
        chapters.check_order()


_FAKE_PAPERMILL = """\
import json, os, sys
events = [
    {"event": "start", "to_compute": 3, "done": 0, "estimate_s": 120.0, "per_task_s": 60.0,
     "measured_when": "2026-11-27T10:00:00+00:00"},
    {"event": "tick", "to_compute": 3, "done": 1, "elapsed_s": 40.0},
    {"event": "end", "to_compute": 3, "done": 3, "elapsed_s": 110.0},
]
with open(os.environ["MECHLIB_PROGRESS"], "a") as fh:
    for e in events:
        base = {"desc": "non-linear FE runs", "total": 4, "cached": 1, "workers": 2}
        fh.write(json.dumps({**base, **e}) + "\\n")
sys.stderr.write("Executing notebook with kernel: python3\\n")
"""


def test_make_run_draws_the_progress_of_its_fe_campaigns(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys
) -> None:
    import sys

    from mechlib.pipeline import progressview

    nb = _notebook(tmp_path / "nb.ipynb", [_parameters_cell(["seed = 1\n"])])
    monkeypatch.setattr(progressview, "LOG_EVERY_S", 0.0)  # every tick a log line
    monkeypatch.setattr(
        runs, "papermill_command", lambda *a: [sys.executable, "-c", _FAKE_PAPERMILL]
    )
    argv = ["--notebook", str(nb), "--out", str(tmp_path / "runs"), "--", "-p", "seed", "2"]
    assert runs.main(argv) == 0
    err = capsys.readouterr().err.splitlines()  # not a terminal: lines, as in a log
    drawn = [line for line in err if line.startswith("[nb] ")]  # papermill's own lines between
    assert drawn[0] == (
        "[nb] non-linear FE runs: 4 tasks, 1 in the cache, 3 to compute on 2 workers: about "
        "2.0 min (60 s a task on one worker, measured on this machine on 2026-11-27)"
    )
    assert drawn[1] == (
        "[nb] non-linear FE runs: 1/3 computed (1 cached) on 2 workers, one every 40 s, ETA 80 s"
    )
    assert (
        drawn[2]
        == "[nb] non-linear FE runs: 3 computed in 1.8 min on 2 workers, 1 read from the cache"
    )
    assert "Executing notebook with kernel: python3" in err
    assert list((tmp_path / "runs" / "nb" / "seed=2").glob(".*.progress")) == []  # cleaned up


def test_papermill_prints_no_warning_a_user_cannot_act_on(tmp_path: Path) -> None:
    """Neither papermill's warning of an output name without ``.ipynb`` (the Makefile executes
    into ``<name>.tmp.ipynb``) nor the kernel's of TCP without encryption (its log at ERROR
    level)."""
    import subprocess

    import nbformat

    nb = nbformat.v4.new_notebook()
    nb.cells = [
        nbformat.v4.new_code_cell("x = 1", metadata={"tags": ["parameters"]}),
        nbformat.v4.new_code_cell("print(2 * x)"),
    ]
    nb.metadata["kernelspec"] = {"name": "python3", "language": "python", "display_name": "P"}
    nbformat.write(nb, tmp_path / "nb.ipynb")
    out = tmp_path / f"nb{execute.PARTIAL_SUFFIX}"
    cmd = execute.papermill_command(tmp_path / "nb.ipynb", out, ["-p", "x", "21"])
    done = subprocess.run(cmd, capture_output=True, text=True, check=False, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "Warning" not in done.stderr and "WARNING" not in done.stderr, done.stderr
    assert "without encryption" not in done.stderr and "does not end in" not in done.stderr
    assert nbformat.read(out, as_version=4).cells[-1].outputs[0]["text"] == "42\n"


def test_the_makefile_executes_into_a_name_papermill_accepts() -> None:
    makefile = (REPO_ROOT / "Makefile").read_text()
    outs = re.findall(r"\$\(PIPELINE\) execute .*?--out (\S+)", makefile)
    assert outs == ["$(BUILD)/executed/$*.tmp.ipynb"]
    assert outs[0].endswith(execute.PARTIAL_SUFFIX)
    assert f"mv {outs[0]} $@" in makefile
