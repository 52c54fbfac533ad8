"""Executing one notebook of a build: the one papermill command line, and the chapter inputs.

:func:`papermill_command` is the papermill command line of the whole build: the Makefile's
notebooks (:func:`execute`), the cold re-run (:mod:`mechlib.pipeline.rerun`), ``make run``
(:mod:`mechlib.pipeline.runs`) and the notebook-parameter tests use it. :func:`execute` passes a
chapter the values its :data:`~mechlib.pipeline.chapters.CHAPTER_INPUTS` name, read from the
upstream chapters' records: a chapter's inputs travel as its parameters, never through files that
library code reads.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from collections.abc import Sequence
from pathlib import Path

import yaml

from mechlib.paths import DEFAULT_BUILD, PROGRESS_ENV, RECORDS_ENV, RECORDS_STRICT_ENV
from mechlib.pipeline.chapters import CHAPTER_INPUTS
from mechlib.pipeline.parameters import given_parameters
from mechlib.pipeline.progressview import ProgressView
from mechlib.reporting.records import load


def papermill_command(
    notebook: Path, output: Path, args: Sequence[str] = (), *, python: str = sys.executable
) -> list[str]:
    """The papermill command line that executes ``notebook`` into ``output``.

    Parameters
    ----------
    notebook : Path
        Source notebook; it runs with its own folder as working directory.
    output : Path
        Executed notebook to write.
    args : sequence of str
        Further papermill arguments (``-p name value`` …), appended as given.
    python : str
        Interpreter of the environment whose papermill runs the notebook (default: this one).

    Returns
    -------
    list of str
        ``<python> -m mechlib.pipeline.papermillrun -k python3 --cwd <notebook folder>
        --no-progress-bar <notebook> <output> <args>``: papermill's command line, its kernel's
        log at ERROR level (:mod:`mechlib.pipeline.papermillrun`).
    """
    notebook = Path(notebook)
    return [
        str(python),
        "-m",
        "mechlib.pipeline.papermillrun",
        "-k",
        "python3",
        "--cwd",
        str(notebook.parent),
        "--no-progress-bar",
        str(notebook),
        str(output),
        *args,
    ]


def upstream_record(notebook: str, records: Path, *, strict: bool | None = None) -> Path:
    """The record of ``notebook`` in ``records``, else in the default build's ``build/records`` —
    and then it says so on stderr (``make run`` into its own folder reads the default build's
    upstream record; a record of another folder is never taken without a word).

    Parameters
    ----------
    notebook : str
        The upstream notebook's name.
    records : Path
        Records folder of this build or run.
    strict : bool, optional
        Read ``records`` only (the determinism re-run); default: ``$MECHLIB_RECORDS_STRICT=1``.

    Raises
    ------
    FileNotFoundError
        When that notebook has not been executed, naming the command that does it.
    """
    strict = os.environ.get(RECORDS_STRICT_ENV) == "1" if strict is None else strict
    places = [Path(records).resolve() / f"{notebook}.json"]
    default = DEFAULT_BUILD.resolve() / "records" / f"{notebook}.json"
    if not strict and default != places[0]:
        places.append(default)
    path = next((p for p in places if p.exists()), None)
    if path is None:
        raise FileNotFoundError(
            f"no record of notebook {notebook!r} in {' or '.join(str(p.parent) for p in places)}: "
            f"execute it first (make notebooks)"
        )
    if path != places[0]:
        print(
            f"note: {notebook}'s record taken from {path} (none in {places[0].parent})",
            file=sys.stderr,
        )
    return path


def chapter_inputs(
    notebook: str, records: Path, given: Sequence[str] = (), *, strict: bool | None = None
) -> dict[str, object]:
    """The parameters of ``notebook`` that other chapters' records fill (:data:`CHAPTER_INPUTS`),
    except those named in ``given`` (a run that sets one itself keeps its value).

    Raises
    ------
    FileNotFoundError
        An upstream notebook has no record (see :func:`upstream_record`).
    KeyError
        An upstream record lacks the key, naming the keys it has.
    """
    values: dict[str, object] = {}
    for name, (upstream, key) in CHAPTER_INPUTS.get(notebook, {}).items():
        if name in given:
            continue
        path = upstream_record(upstream, records, strict=strict)
        recorded = {k: v["value"] for k, v in load(path)["values"].items()}
        if key.endswith(".*"):
            prefix = key[:-1]
            found = {k[len(prefix) :]: v for k, v in recorded.items() if k.startswith(prefix)}
        else:
            found = recorded.get(key)
        if not found:
            raise KeyError(f"{path} holds no value {key!r} (input {name!r} of {notebook})")
        values[name] = found
    return values


def input_arguments(
    notebook: str, records: Path, given: Sequence[str] = (), *, strict: bool | None = None
) -> list[str]:
    """papermill arguments (``-y``) that pass ``notebook`` its :func:`chapter_inputs`."""
    values = chapter_inputs(notebook, records, given, strict=strict)
    return ["-y", yaml.safe_dump(values, sort_keys=False)] if values else []


#: the end of the name a notebook is executed into before it is complete (the Makefile's
#: ``build/executed/<name>.tmp.ipynb``: papermill warns of an output not ending in ``.ipynb``)
PARTIAL_SUFFIX = ".tmp.ipynb"

#: how often a notebook's kernel is started when it dies before running any cell (two kernels
#: started at the same moment can race for their ports: seen once in a clean-clone test run)
KERNEL_START_ATTEMPTS = 3
#: what nbclient says when the kernel died before it ran anything
_KERNEL_DIED = "Kernel died before replying to kernel_info"


def kernel_died_at_start(stderr: str) -> bool:
    """Whether papermill's ``stderr`` says the kernel died before running any cell (a start
    failure, which a new attempt may not meet; a failing cell is never retried)."""
    return _KERNEL_DIED in stderr


def fe_summary_path(output: Path, name: str) -> Path:
    """Where :func:`execute` leaves the FE task counts of notebook ``name`` executed into
    ``output`` (``<output folder>/<name>.fe.json``: total and read from the cache)."""
    return Path(output).parent / f"{name}.fe.json"


def progress_file(output: Path) -> Path:
    """The file the FE campaigns of a notebook executed into ``output`` report their progress to
    (``$MECHLIB_PROGRESS``, :mod:`mechlib.progress`): ``.<output name>.progress`` beside it,
    absolute (the kernel runs in the notebooks' folder)."""
    output = Path(output)
    return output.with_name(f".{output.name}.progress").resolve()


def execute(notebook: Path, output: Path, records: Path, args: Sequence[str] = ()) -> int:
    """Execute ``notebook`` into ``output`` with papermill ``args`` (a profile's ``-f`` file …),
    its record into ``records`` and its chapter inputs read from there; papermill's exit code."""
    records = Path(records).resolve()  # absolute: the kernel runs in the notebooks' folder
    inputs = input_arguments(Path(notebook).stem, records, given_parameters(args), strict=True)
    cmd = papermill_command(Path(notebook), Path(output), [*inputs, *args])
    progress = progress_file(Path(output))
    env = dict(os.environ, **{RECORDS_ENV: str(records), PROGRESS_ENV: str(progress)})
    for attempt in range(KERNEL_START_ATTEMPTS):
        proc = subprocess.Popen(cmd, env=env, stderr=subprocess.PIPE, text=True)
        said = []
        with ProgressView(progress, Path(notebook).stem) as view:  # the FE campaigns' progress
            for line in proc.stderr:  # passed on as it comes, and kept
                sys.stderr.write(line)
                said.append(line)
        # what the provenance box says of the run's FE tasks (read by the book build)
        fe_summary_path(Path(output), Path(notebook).stem).write_text(json.dumps(view.tasks))
        progress.unlink(missing_ok=True)
        if proc.wait() == 0 or not kernel_died_at_start("".join(said)):
            break
        name = Path(notebook).name
        print(
            f"execute: the kernel of {name} died before it started (attempt {attempt + 1} of "
            f"{KERNEL_START_ATTEMPTS}); starting it again",
            flush=True,
        )
    return proc.returncode
