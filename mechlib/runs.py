"""Re-run one notebook with new parameters into its own folder (``make run``).

``python -m mechlib.runs --notebook notebooks/X.ipynb --out build/runs -- -p name value ...``
executes the notebook with papermill into ``build/runs/X/<parameters>/`` with its record there
too, so the default run in ``build/executed`` and ``build/records`` is never overwritten.

The arguments after ``--`` are papermill's: parameters as ``-p name value``, ``-r name value``
(raw string), ``-y 'yaml mapping'``, ``-f file.yaml`` or ``-b base64-yaml``, and any other
papermill option. Before anything runs, every parameter name they set is checked against the
names the notebook's ``parameters`` cell defines; a misspelled name is refused by name (papermill
itself only warns and runs the defaults). When the run fails, the error that stopped the
notebook (for a bad parameter value, the notebook's own ``ValueError`` message) is printed on one
line with the path of the executed notebook, which holds the full traceback.

:func:`papermill_command` is the one papermill command line of the Python code (this module,
:func:`mechlib.records.rerun`, the notebook-parameter tests); the Makefile keeps its
own for the book's notebooks.
"""

from __future__ import annotations

import argparse
import ast
import base64
import binascii
import difflib
import json
import os
import re
import subprocess
import sys
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path

import yaml

from mechlib.paths import DEFAULT_BUILD, RECORDS_ENV, RECORDS_STRICT_ENV
from mechlib.records import load

#: papermill's options that set notebook parameters, and how many values each takes.
PARAMETER_OPTIONS: dict[str, int] = {
    "-p": 2,
    "--parameters": 2,
    "-r": 2,
    "--parameters_raw": 2,
    "-y": 1,
    "--parameters_yaml": 1,
    "-f": 1,
    "--parameters_file": 1,
    "-b": 1,
    "--parameters_base64": 1,
}
#: Chapter inputs: notebook -> {parameter: (upstream notebook, record key)}. Whoever executes the
#: notebook passes each parameter the upstream notebook's recorded value (unless the run gives it);
#: a key ending in ``.*`` passes every value under that prefix, as a mapping by the rest of its
#: key (``geometry.thickness`` -> ``{"thickness": ...}``).
CHAPTER_INPUTS: dict[str, dict[str, tuple[str, str]]] = {
    "virtual_experiments": {
        "geometry": ("hexflex_model", "geometry.*"),
        "mesh_fraction": ("hexflex_model", "model.mesh_fraction"),
    },
}
#: Tag of the cell whose assignments are a notebook's parameters (papermill's convention).
PARAMETERS_TAG = "parameters"
#: First line of a Python traceback on stderr: what follows is held back (see :func:`relay`).
TRACEBACK_START = "Traceback (most recent call last):"


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
        Interpreter of the environment whose ``papermill`` script is used (default: this one).

    Returns
    -------
    list of str
        ``papermill -k python3 --cwd <notebook folder> --no-progress-bar <notebook> <output>
        <args>``.
    """
    papermill = str(Path(python).with_name("papermill"))
    notebook = Path(notebook)
    return [
        papermill,
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
    places = [Path(records) / f"{notebook}.json"]
    if not strict:
        places.append(DEFAULT_BUILD / "records" / f"{notebook}.json")
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


def run_folder_name(papermill_args: list[str]) -> str:
    """A readable folder name for a set of papermill ``-p name value`` arguments."""
    text = "_".join(a for a in papermill_args if a not in ("-p", "--parameters")) or "defaults"
    return re.sub(r"[^A-Za-z0-9.=_-]+", "-", text)[:120]


def _yaml_names(option: str, text: str | bytes) -> list[str]:
    """Top-level names of a YAML mapping given to ``option`` (empty YAML: none)."""
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as err:
        why = getattr(err, "problem", None) or type(err).__name__
        raise ValueError(f"{option} must give a YAML mapping, got {text!r} ({why})") from None
    if data is None:
        return []
    if not isinstance(data, dict):
        raise ValueError(
            f"{option} must give a YAML mapping of parameter names to values, got {text!r}"
        )
    return [str(k) for k in data]


def _option_values(args: Sequence[str]) -> list[tuple[str, list[str]]]:
    """Each parameter option in ``args`` with its values, in the forms papermill (click) takes.

    ``-p name value``, ``-pname value`` (short option with its first value attached),
    ``--parameters_yaml=text`` (long single-value option with ``=``); other arguments are
    skipped.
    """
    found, i = [], 0
    while i < len(args):
        token = args[i]
        head, eq, tail = token.partition("=")
        if token in PARAMETER_OPTIONS:
            option, values, i = token, [], i + 1
        elif token.startswith("--") and eq and PARAMETER_OPTIONS.get(head) == 1:
            option, values, i = head, [tail], i + 1
        elif not token.startswith("--") and token[:2] in PARAMETER_OPTIONS and len(token) > 2:
            option, values, i = token[:2], [token[2:]], i + 1
        else:
            i += 1
            continue
        need = PARAMETER_OPTIONS[option] - len(values)
        values += list(args[i : i + need])
        if len(values) < PARAMETER_OPTIONS[option]:
            what = "a name and a value" if PARAMETER_OPTIONS[option] == 2 else "a value"
            raise ValueError(f"{option} needs {what}, got {list(args[i - 1 :])}")
        found.append((option, values))
        i += need
    return found


def given_parameters(args: Sequence[str]) -> list[str]:
    """Names of the notebook parameters that papermill arguments set, in the order given.

    Parameters
    ----------
    args : sequence of str
        papermill arguments: ``-p``/``--parameters`` and ``-r``/``--parameters_raw`` name and
        value, ``-y``/``--parameters_yaml`` YAML text, ``-f``/``--parameters_file`` a YAML file
        (read here), ``-b``/``--parameters_base64`` base64-encoded YAML; other arguments are
        ignored.

    Returns
    -------
    list of str

    Raises
    ------
    ValueError
        If an option lacks its values, a YAML value is not a mapping, a parameters file cannot
        be read, or a base64 value does not decode.
    """
    names: list[str] = []
    for option, values in _option_values(args):
        if PARAMETER_OPTIONS[option] == 2:
            names.append(values[0])
        elif option in ("-f", "--parameters_file"):
            try:
                text = Path(values[0]).read_text()
            except OSError as err:
                raise ValueError(f"{option} {values[0]}: cannot read the file ({err})") from None
            names += _yaml_names(f"{option} {values[0]}", text)
        elif option in ("-b", "--parameters_base64"):
            try:
                text = base64.b64decode(values[0], validate=True)
            except (binascii.Error, ValueError):
                raise ValueError(
                    f"{option} must be base64-encoded YAML, got {values[0]!r}"
                ) from None
            names += _yaml_names(option, text)
        else:
            names += _yaml_names(option, values[0])
    return names


def check_parameter_names(
    args: Sequence[str], allowed: Sequence[str], notebook: str = "the notebook"
) -> list[str]:
    """Names set by papermill ``args``, refusing any that ``allowed`` does not list.

    Parameters
    ----------
    args : sequence of str
        papermill arguments (see :func:`given_parameters`).
    allowed : sequence of str
        The notebook's parameter names (:func:`notebook_parameters`).
    notebook : str
        How to name the notebook in the message.

    Returns
    -------
    list of str
        The given names.

    Raises
    ------
    ValueError
        Naming each unknown parameter (with the closest allowed name, if one is close) and
        listing the allowed ones.
    """
    given = given_parameters(args)
    unknown = [n for n in dict.fromkeys(given) if n not in allowed]
    if unknown:
        described = []
        for name in unknown:
            close = difflib.get_close_matches(name, list(allowed), n=1)
            described.append(f"{name!r}" + (f" (did you mean {close[0]!r}?)" if close else ""))
        raise ValueError(
            f"unknown parameter {', '.join(described)} for {notebook}: its parameters cell "
            f"defines {', '.join(allowed) if allowed else 'none'}"
        )
    return given


def parameters_cell_names(source: str) -> list[str]:
    """Names assigned at the top level of a parameters cell's source, in order."""
    names: list[str] = []
    for node in ast.parse(source).body:
        targets = node.targets if isinstance(node, ast.Assign) else []
        if isinstance(node, ast.AnnAssign):
            targets = [node.target]
        for target in targets:
            elts = target.elts if isinstance(target, (ast.Tuple, ast.List)) else [target]
            names += [e.id for e in elts if isinstance(e, ast.Name)]
    return list(dict.fromkeys(names))


def notebook_parameters(path: Path) -> list[str]:
    """Parameter names of a notebook: the assignments of its cell tagged ``parameters``.

    Read with Python's own parser rather than ``papermill.inspect_notebook``, which skips any
    line holding a second ``=`` (in a comment, say: hexflex_model's ``tab_half_width``).

    Raises
    ------
    ValueError
        If the parameters cell is not valid Python.
    """
    nb = json.loads(Path(path).read_text())
    for cell in nb.get("cells", []):
        if PARAMETERS_TAG in cell.get("metadata", {}).get("tags", []):
            source = cell.get("source", "")
            source = "".join(source) if isinstance(source, list) else source
            try:
                return parameters_cell_names(source)
            except SyntaxError as err:
                raise ValueError(f"the parameters cell of {path} is not Python: {err}") from None
    return []


def failure_message(executed: dict) -> str | None:
    """The error that stopped an executed notebook, on one line; ``None`` if there is none.

    Follows papermill: the first ``error`` output of any cell, except ``SystemExit`` with an
    empty or zero code. Returns ``"<ename>: <evalue> (cell In [<n>])"``.
    """
    for cell in executed.get("cells", []):
        for out in cell.get("outputs", []):
            if out.get("output_type") != "error":
                continue
            ename, evalue = out.get("ename", "Error"), str(out.get("evalue", ""))
            if ename == "SystemExit" and evalue in ("", "0"):
                continue
            text = " ".join(line.strip() for line in evalue.splitlines() if line.strip())
            return f"{ename}: {text} (cell In [{cell.get('execution_count')}])"
    return None


def relay(lines: Iterable[str], write: Callable[[str], object]) -> list[str]:
    """Pass ``lines`` to ``write`` until a Python traceback starts; return the held-back rest."""
    held: list[str] = []
    for line in lines:
        if held or line.rstrip("\r\n") == TRACEBACK_START:
            held.append(line)
        else:
            write(line)
    return held


def main(argv: list[str] | None = None) -> int:
    """Execute the notebook and print where its outputs are (or, on failure, why not)."""
    parser = argparse.ArgumentParser(prog="python -m mechlib.runs")
    parser.add_argument("--notebook", type=Path, required=True)
    parser.add_argument("--out", type=Path, required=True)
    parser.add_argument(
        "--records",
        type=Path,
        default=DEFAULT_BUILD / "records",
        help="records of the build whose chapters give this notebook its inputs",
    )
    parser.add_argument("papermill_args", nargs=argparse.REMAINDER)
    args = parser.parse_args(argv)
    extra = [a for a in args.papermill_args if a != "--"]
    try:
        given = check_parameter_names(extra, notebook_parameters(args.notebook), str(args.notebook))
        inputs = input_arguments(args.notebook.stem, args.records, given)
    except (OSError, ValueError, KeyError) as err:
        print(f"refused, nothing was run: {err}", file=sys.stderr)
        return 2
    folder = (args.out / args.notebook.stem / run_folder_name(extra)).resolve()
    folder.mkdir(parents=True, exist_ok=True)
    out_nb = folder / args.notebook.name
    out_nb.unlink(missing_ok=True)  # a failure is read from this run's notebook, never an older one
    env = dict(os.environ, **{RECORDS_ENV: str(folder)})
    cmd = papermill_command(args.notebook, out_nb, [*inputs, *extra])
    with subprocess.Popen(
        cmd, env=env, stderr=subprocess.PIPE, encoding="utf-8", errors="replace"
    ) as proc:
        held = relay(proc.stderr, sys.stderr.write)
    message = None
    if proc.returncode and out_nb.exists():
        try:
            message = failure_message(json.loads(out_nb.read_text()))
        except (OSError, ValueError):
            message = None
    if message is not None:
        print(f"the run FAILED: {message}; executed notebook: {out_nb}", file=sys.stderr)
        return proc.returncode
    sys.stderr.writelines(held)
    print(f"executed notebook: {out_nb}")
    print(f"record:            {folder / (args.notebook.stem + '.json')}")
    if proc.returncode:
        print("the run FAILED: the error is shown above and marked in the executed notebook")
    return proc.returncode


if __name__ == "__main__":
    raise SystemExit(main())
