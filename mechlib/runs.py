"""Re-run one notebook with new parameters into its own folder (``make run``).

``python -m mechlib.runs --notebook notebooks/X.ipynb --out build/runs -- -p name value ...``
executes the notebook with papermill into ``build/runs/X/<parameters>/`` with its record there
too, so the default run in ``build/executed`` and ``build/records`` is never overwritten.

:func:`papermill_command` is the one papermill command line of the Python code (this module,
:func:`mechlib.records.rerun_identical`, the notebook-parameter tests); the Makefile keeps its
own for the book's notebooks.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
from collections.abc import Sequence
from pathlib import Path

from mechlib.records import RECORDS_ENV


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


def run_folder_name(papermill_args: list[str]) -> str:
    """A readable folder name for a set of papermill ``-p name value`` arguments."""
    text = "_".join(a for a in papermill_args if a not in ("-p", "--parameters")) or "defaults"
    return re.sub(r"[^A-Za-z0-9.=_-]+", "-", text)[:120]


def main(argv: list[str] | None = None) -> int:
    """Execute the notebook and print where its outputs are."""
    parser = argparse.ArgumentParser(prog="python -m mechlib.runs")
    parser.add_argument("--notebook", type=Path, required=True)
    parser.add_argument("--out", type=Path, required=True)
    parser.add_argument("papermill_args", nargs=argparse.REMAINDER)
    args = parser.parse_args(argv)
    extra = [a for a in args.papermill_args if a != "--"]
    folder = (args.out / args.notebook.stem / run_folder_name(extra)).resolve()
    folder.mkdir(parents=True, exist_ok=True)
    out_nb = folder / args.notebook.name
    cmd = papermill_command(args.notebook, out_nb, extra)
    env = dict(os.environ, **{RECORDS_ENV: str(folder)})
    done = subprocess.run(cmd, env=env, check=False)
    print(f"executed notebook: {out_nb}")
    print(f"record:            {folder / (args.notebook.stem + '.json')}")
    if done.returncode:
        print("the run FAILED: the error is shown above and marked in the executed notebook")
    return done.returncode


if __name__ == "__main__":
    raise SystemExit(main())
