"""Re-run one notebook with new parameters into its own folder (``make run``).

``python -m mechlib.pipeline run --notebook notebooks/X.ipynb --out build/runs -- -p name value``
executes the notebook with papermill into ``build/runs/X/<parameters>/`` with its record there
too, so the default run in ``build/executed`` and ``build/records`` is never overwritten. Its FE
campaigns' progress is drawn as the build's is
(:class:`~mechlib.pipeline.progressview.ProgressView`: size and expected time before a campaign
starts, then one line with its ETA on a terminal, a line every 30 s in a log).

The arguments after ``--`` are papermill's: parameters as ``-p name value``, ``-r name value``
(raw string), ``-y 'yaml mapping'``, ``-f file.yaml`` or ``-b base64-yaml``, and any other
papermill option. Before anything runs, every parameter name they set is checked against the
names the notebook's ``parameters`` cell defines; a misspelled name is refused by name (papermill
itself only warns and runs the defaults). When the run fails, the error that stopped the
notebook (for a bad parameter value, the notebook's own ``ValueError`` message) is printed on one
line with the path of the executed notebook, which holds the full traceback.

The parameter names are checked by :mod:`mechlib.pipeline.parameters`; the chapter's inputs from
other chapters' records are filled by :func:`mechlib.pipeline.execute.input_arguments` (from
``--records``: the build's records, else the default build's, with a note).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
from collections.abc import Callable, Iterable
from pathlib import Path

from mechlib.paths import DEFAULT_BUILD, PROGRESS_ENV, RECORDS_ENV
from mechlib.pipeline.execute import input_arguments, papermill_command, progress_file
from mechlib.pipeline.parameters import check_parameter_names, notebook_parameters
from mechlib.pipeline.progressview import ProgressView

#: First line of a Python traceback on stderr: what follows is held back (see :func:`relay`).
TRACEBACK_START = "Traceback (most recent call last):"


def run_folder_name(papermill_args: list[str]) -> str:
    """A readable folder name for a set of papermill ``-p name value`` arguments."""
    text = "_".join(a for a in papermill_args if a not in ("-p", "--parameters")) or "defaults"
    return re.sub(r"[^A-Za-z0-9.=_-]+", "-", text)[:120]


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
    parser = argparse.ArgumentParser(prog="python -m mechlib.pipeline run")
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
    progress = progress_file(out_nb)
    env = dict(os.environ, **{RECORDS_ENV: str(folder), PROGRESS_ENV: str(progress)})
    cmd = papermill_command(args.notebook, out_nb, [*inputs, *extra])
    with (
        ProgressView(progress, args.notebook.stem),  # the FE campaigns' progress, as execute's
        subprocess.Popen(
            cmd, env=env, stderr=subprocess.PIPE, encoding="utf-8", errors="replace"
        ) as proc,
    ):
        held = relay(proc.stderr, sys.stderr.write)
    progress.unlink(missing_ok=True)
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
