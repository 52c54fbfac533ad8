"""Records of key numbers: written by notebooks, compared with committed references.

A notebook creates one :class:`Recorder`, records each key number together with the tolerance
that the numerics can guarantee — in the same call glued for the page's text and completed into
its reproduction-report row (:mod:`mechlib.report`) — and saves
``build/records/<notebook>.json``. The committed
reference ``tests/references/<notebook>.json`` is a copy of such a file, made by
``make references`` from a fresh run (never typed). :func:`compare` checks a run against its
reference with the reference's per-value tolerances.

Command line (used by the Makefile)::

    python -m mechlib.records update --records build/records --references tests/references
    python -m mechlib.records rerun --out build/rerun
    python -m mechlib.records determinism --records build/records --rerun build/rerun/records
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from mechlib import report
from mechlib.params import check_float
from mechlib.paths import (  # noqa: F401 (re-exported until the build wing moves out)
    FE_CACHE_ENV,
    RECORDS_ENV,
    RECORDS_STRICT_ENV,
    REPO_ROOT,
    fe_cache_dir,
    records_dir,
)


def _plain(value: Any) -> Any:
    """Convert numpy scalars/arrays and tuples to JSON-ready Python objects."""
    if isinstance(value, np.ndarray):
        return [_plain(v) for v in value.tolist()]
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, float) and not np.isfinite(value):
        raise ValueError(f"records hold finite numbers only, got {value!r}")
    return value


#: What a notebook may glue into its prose through :meth:`Recorder.value`: a name, or names
#: of elements of the recorded value by their index (``{"nu_x": 0, "nu_thx": 3}``).
Glue = str | Mapping[str, int | tuple[int, ...]]


def _is_number(value: Any) -> bool:
    return np.asarray(value).dtype.kind in "iuf"


def paste(name: str, value: Any) -> None:
    """Glue ``value`` under ``name`` for the notebook's prose (myst-nb, not displayed)."""
    from myst_nb import glue  # here: only notebooks paste, and myst-nb imports IPython

    glue(name, value, display=False)


@dataclass
class Recorder:
    """Collects the key numbers, the numbers quoted in the prose and the report rows of one
    notebook.

    One call, :meth:`value`, records a number with its tolerance, makes it (or some of its
    elements) available to the prose under a glue name, and adds the report row that compares
    it with the thesis: every number the book quotes is then checked against the committed
    references. Text that is not a number goes to the prose through :meth:`text`, which says
    what it is made from or why it is not checked.

    Parameters
    ----------
    notebook : str
        Notebook name without extension; the record file is ``<notebook>.json``.
    paste : callable, optional
        ``paste(name, value)`` glues a value for the prose; default :func:`paste` (myst-nb).
    """

    notebook: str
    values: dict[str, dict[str, Any]] = field(default_factory=dict)
    report: list[dict[str, Any]] = field(default_factory=list)
    glued: dict[str, dict[str, Any]] = field(default_factory=dict)
    paste: Callable[[str, Any], None] = field(default=paste, repr=False)

    def value(
        self,
        key: str,
        value: Any,
        *,
        rtol: float | None = None,
        atol: float | None = None,
        glue: Glue | None = None,
        row: report.RowSpec | Sequence[report.RowSpec] | None = None,
    ) -> Any:
        """Record ``value`` under ``key`` with the tolerance a re-run must meet; glue it for the
        prose and add its report row(s).

        Parameters
        ----------
        key : str
            Unique name, dotted by topic (``"table3.effects"``).
        value : float, int, bool, str or array_like
            The number(s). Arrays are stored as nested lists.
        rtol, atol : float
            Relative and absolute tolerance of numbers: ``|a - b| <= atol + rtol * |b|``. A
            number (int or float, scalar or array) needs at least one of them (``atol=0`` for
            exact); booleans and strings are compared exactly.
        glue : str or dict, optional
            Glue name of a scalar number, or ``{name: index}`` to glue elements of an array
            (as Python ``float``/``int``, what myst-nb formats).
        row : report.Comparison, report.Claim or report.Computed, or a list of them
            Report rows completed with this value (see :mod:`mechlib.report`).

        Returns
        -------
        The value as given, so a record can be written inline.

        Raises
        ------
        ValueError
            A key or glue name used twice, a number without tolerance, a negative tolerance,
            a non-finite number, or a glued element that is not a number.
        """
        if key in self.values:
            raise ValueError(f"record key {key!r} was already recorded in {self.notebook}")
        if _is_number(value) and rtol is None and atol is None:
            raise ValueError(
                f"{key}: a number is recorded with its tolerance: give rtol and/or atol "
                f"(atol=0 for an exact value)"
            )
        rtol = check_float("rtol", 0.0 if rtol is None else rtol, low=0.0)
        atol = check_float("atol", 0.0 if atol is None else atol, low=0.0)
        entry = {"value": _plain(value), "rtol": rtol, "atol": atol}
        pasted, glued = {}, {}
        for name, index in ({glue: ()} if isinstance(glue, str) else dict(glue or {})).items():
            item = np.asarray(value)[index]
            if item.ndim or not _is_number(item):
                raise ValueError(
                    f"{key}: glue {name!r} must name one number, got {item!r} (text goes "
                    f"through Recorder.text)"
                )
            self._check_name(name)
            pasted[name] = item.item()
            glued[name] = {"key": key, **({"index": _plain(index)} if index != () else {})}
        specs = [] if row is None else [row] if hasattr(row, "row") else list(row)
        rows = [{k: _plain(v) for k, v in s.row(value).items()} for s in specs]
        # nothing is kept before every check has passed
        self.values[key] = entry
        self.glued |= glued
        self.report += rows
        for name, item in pasted.items():
            self.paste(name, item)
        return value

    def text(self, name: str, text: str | float, *, of: str = "", why: str = "") -> str | float:
        """Glue a text that is not a recorded number (a label, a formatted list) for the prose.

        Parameters
        ----------
        name : str
            Glue name.
        text : str or float
            The text; NaN for a number this run does not compute.
        of : str
            The record key(s) the text is made from (comma-separated), recorded before.
        why : str
            Otherwise, why the text is not checked (e.g. a machine-dependent timing).

        Raises
        ------
        ValueError
            A glue name used twice, neither or both of ``of`` and ``why``, an ``of`` key not
            recorded, or a finite number (numbers go through :meth:`value`).
        """
        if not isinstance(text, str) and not (isinstance(text, float) and np.isnan(text)):
            raise ValueError(f"text {name!r} must be a str or NaN, got {text!r} (numbers: value)")
        if bool(of) == bool(why):
            raise ValueError(f"text {name!r}: say what it is made of (of=) or why not (why=)")
        missing = [k.strip() for k in of.split(",") if of and k.strip() not in self.values]
        if missing:
            raise ValueError(f"text {name!r} is made of {missing}, which were not recorded")
        self._check_name(name)
        self.glued[name] = {"text_of": of} if of else {"unchecked": why}
        self.paste(name, text)
        return text

    def _check_name(self, name: str) -> None:
        if not name or name in self.glued:
            raise ValueError(f"glue name {name!r} is empty or was already used in {self.notebook}")

    def save(self, folder: Path | None = None) -> Path:
        """Write ``<folder>/<notebook>.json`` deterministically and return its path."""
        folder = Path(folder) if folder is not None else records_dir()
        folder.mkdir(parents=True, exist_ok=True)
        path = folder / f"{self.notebook}.json"
        payload = {
            "notebook": self.notebook,
            "values": self.values,
            "report": self.report,
            "glue": self.glued,
        }
        path.write_text(json.dumps(payload, indent=1, sort_keys=True) + "\n")
        return path


def load(path: Path) -> dict[str, Any]:
    """Read one record or reference file."""
    return json.loads(Path(path).read_text())


def recorded_value(notebook: str, key: str) -> Any:
    """A value recorded by another notebook: from ``records_dir()`` (this build or run) if it
    holds that notebook's record, else from the default build's ``build/records`` — and then it
    says so on stderr (a ``make run`` reads the default build's upstream record; a record of
    another profile is never taken without a word). With ``$MECHLIB_RECORDS_STRICT=1``, only
    ``records_dir()`` is read.

    Raises
    ------
    FileNotFoundError
        When that notebook has not been executed, naming the command that does it.
    """
    places = [records_dir() / f"{notebook}.json"]
    if os.environ.get(RECORDS_STRICT_ENV) != "1":
        places.append(REPO_ROOT / "build" / "records" / f"{notebook}.json")
    path = next((p for p in places if p.exists()), None)
    if path is None:
        raise FileNotFoundError(
            f"no record of notebook {notebook!r} in {' or '.join(str(p.parent) for p in places)}: "
            f"execute it first (make notebooks)"
        )
    if path != places[0]:
        print(
            f"note: {notebook}'s {key!r} taken from {path} (no record of {notebook} in "
            f"{places[0].parent})",
            file=sys.stderr,
        )
    values = load(path)["values"]
    if key not in values:
        raise KeyError(f"notebook {notebook!r} recorded no value {key!r}; it has {sorted(values)}")
    return values[key]["value"]


def _compare_value(key: str, got: Any, ref: Any, rtol: float, atol: float) -> list[str]:
    if isinstance(ref, (str, bool)) or ref is None:
        return [] if got == ref else [f"{key}: got {got!r}, reference {ref!r}"]
    try:
        a = np.asarray(got, dtype=float)
        b = np.asarray(ref, dtype=float)
    except (TypeError, ValueError):
        return [] if got == ref else [f"{key}: got {got!r}, reference {ref!r}"]
    if a.shape != b.shape:
        return [f"{key}: shape {a.shape} differs from reference shape {b.shape}"]
    bad = np.abs(a - b) > atol + rtol * np.abs(b)
    if not np.any(bad):
        return []
    idx = tuple(int(i) for i in np.argwhere(bad)[0]) if a.ndim else ()
    where = f"[{', '.join(map(str, idx))}]" if idx else ""
    return [
        f"{key}{where}: got {a[idx].item()!r}, reference {b[idx].item()!r} "
        f"(tolerance atol={atol}, rtol={rtol}; {int(bad.sum())} value(s) outside)"
    ]


def compare(results: dict[str, Any], reference: dict[str, Any]) -> list[str]:
    """Compare a run's record with its reference.

    Tolerances are taken from the reference (they are reviewed when committed).

    Parameters
    ----------
    results, reference : dict
        Contents of a record file and of its reference file.

    Returns
    -------
    list of str
        One message per mismatch; empty when the run reproduces the reference.
    """
    problems = []
    got, ref = results["values"], reference["values"]
    for key in sorted(set(ref) - set(got)):
        problems.append(f"{key}: in the reference but not recorded by this run")
    for key in sorted(set(got) - set(ref)):
        problems.append(f"{key}: recorded but not in the reference (run `make references`)")
    for key in sorted(set(got) & set(ref)):
        r = ref[key]
        problems += _compare_value(key, got[key]["value"], r["value"], r["rtol"], r["atol"])
    return problems


def update_references(records: Path, references: Path) -> list[str]:
    """Copy every record into the references folder and describe what changed."""
    references.mkdir(parents=True, exist_ok=True)
    lines = []
    for src in sorted(Path(records).glob("*.json")):
        dst = references / src.name
        if dst.exists():
            diffs = compare(load(src), load(dst))
            lines += [f"{src.stem}: {d}" for d in diffs] or [f"{src.stem}: unchanged"]
        else:
            lines.append(f"{src.stem}: new reference")
        shutil.copyfile(src, dst)
    return lines


def rerun(notebooks: Path, out: Path, python: str = sys.executable) -> None:
    """Execute every notebook again, cold, into ``out`` (emptied first).

    The executed notebooks go to ``out/<name>.ipynb``, their records to ``out/records``
    (``$MECHLIB_RECORDS``, read strictly: a notebook reading another's record reads the
    re-run's), and their FE results to an empty cache of their own, ``out/fe-cache``
    (``$MECHLIB_FE_CACHE``): the re-run computes everything again and shares nothing with a
    first run, so the two can run at the same time (``make test`` does). Notebooks run in name
    order, which puts ``hexflex_model`` before ``virtual_experiments``, the one that reads it.

    Raises
    ------
    RuntimeError
        If a notebook fails, naming it and its executed copy (which holds the traceback), with
        the end of papermill's error output.
    """
    from mechlib.runs import input_arguments, papermill_command  # here: runs imports this module

    out = Path(out).resolve()  # absolute: the kernels run in the notebooks' folder
    shutil.rmtree(out, ignore_errors=True)
    (out / "records").mkdir(parents=True)
    env = dict(
        os.environ,
        **{
            RECORDS_ENV: str(out / "records"),
            FE_CACHE_ENV: str(out / "fe-cache"),
            RECORDS_STRICT_ENV: "1",
        },
    )
    for nb in sorted(Path(notebooks).glob("*.ipynb")):
        print(f"re-run: executing {nb.name}", flush=True)
        inputs = input_arguments(nb.stem, out / "records", strict=True)
        cmd = papermill_command(nb, out / nb.name, inputs, python=python)
        done = subprocess.run(cmd, env=env, capture_output=True, text=True)
        if done.returncode != 0:
            tail = "\n".join(done.stderr.splitlines()[-20:])
            raise RuntimeError(
                f"the re-run of {nb.name} failed (exit {done.returncode}; traceback in "
                f"{out / nb.name}):\n{tail}"
            )


def rerun_differences(records: Path, rerun_records: Path, notebooks: Path) -> list[str]:
    """Each notebook whose re-run record is not byte-identical to its first one, with the
    values that differ (empty: the two runs agree)."""
    problems = []
    for nb in sorted(Path(notebooks).glob("*.ipynb")):
        first, second = Path(records) / f"{nb.stem}.json", Path(rerun_records) / f"{nb.stem}.json"
        missing = [
            f"{which} record at {path}"
            for which, path in (("first-run", first), ("re-run", second))
            if not path.exists()
        ]
        if missing:
            problems.append(f"{nb.stem}: no " + " and no ".join(missing))
        elif second.read_bytes() != first.read_bytes():
            diffs = compare(load(second), load(first))
            problems.append(f"{nb.stem}: second run differs: {diffs or 'formatting only'}")
    return problems


def rerun_identical(records: Path, notebooks: Path, python: str = sys.executable) -> list[str]:
    """Execute every notebook again (:func:`rerun`, in a temporary folder) and check its record
    is byte-identical to the one in ``records`` (:func:`rerun_differences`).

    The second run starts from an empty FE cache (``$MECHLIB_FE_CACHE`` in a temporary folder),
    so it checks that two cold computations agree, not merely that cached results are returned.
    """
    with tempfile.TemporaryDirectory() as tmp:
        rerun(notebooks, Path(tmp), python=python)
        return rerun_differences(records, Path(tmp) / "records", notebooks)


def execute(notebook: Path, output: Path, records: Path, args: Sequence[str] = ()) -> int:
    """Execute ``notebook`` into ``output`` with papermill ``args``, its record into ``records``
    and its chapter inputs (:func:`mechlib.runs.input_arguments`) read from there; papermill's
    exit code."""
    from mechlib.runs import given_parameters, input_arguments, papermill_command

    records = Path(records).resolve()
    inputs = input_arguments(Path(notebook).stem, records, given_parameters(args), strict=True)
    cmd = papermill_command(Path(notebook), Path(output), [*inputs, *args])
    return subprocess.run(cmd, env=dict(os.environ, **{RECORDS_ENV: str(records)})).returncode


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point (``update``, ``rerun``, ``determinism`` or ``execute``)."""
    parser = argparse.ArgumentParser(prog="python -m mechlib.records")
    sub = parser.add_subparsers(dest="cmd", required=True)
    up = sub.add_parser("update", help="re-record references from build/records")
    up.add_argument("--records", type=Path, required=True)
    up.add_argument("--references", type=Path, required=True)
    det = sub.add_parser("determinism", help="re-run notebooks and require identical records")
    det.add_argument("--records", type=Path, required=True)
    det.add_argument("--notebooks", type=Path, default=REPO_ROOT / "notebooks")
    det.add_argument(
        "--rerun", type=Path, help="records of a re-run already made (`rerun`): compare only"
    )
    again = sub.add_parser("rerun", help="execute every notebook again, cold, into a folder")
    again.add_argument("--out", type=Path, required=True)
    again.add_argument("--notebooks", type=Path, default=REPO_ROOT / "notebooks")
    ex = sub.add_parser("execute", help="execute one notebook of a build, its inputs filled")
    ex.add_argument("--notebook", type=Path, required=True)
    ex.add_argument("--out", type=Path, required=True)
    ex.add_argument("--records", type=Path, required=True)
    ex.add_argument("papermill_args", nargs=argparse.REMAINDER)
    args = parser.parse_args(argv)
    if args.cmd == "execute":
        extra = [a for a in args.papermill_args if a != "--"]
        return execute(args.notebook, args.out, args.records, extra)
    if args.cmd == "update":
        for line in update_references(args.records, args.references):
            print(line)
        return 0
    if args.cmd == "rerun":
        try:
            rerun(args.notebooks, args.out)
        except RuntimeError as err:
            print(err, file=sys.stderr)
            return 1
        print(f"re-run: every notebook executed again into {args.out}")
        return 0
    if args.rerun is None:
        problems = rerun_identical(args.records, args.notebooks)
    else:
        problems = rerun_differences(args.records, args.rerun, args.notebooks)
    for p in problems:
        print("NOT DETERMINISTIC:", p)
    print("determinism: " + ("FAILED" if problems else "records identical on a second run"))
    return 1 if problems else 0


if __name__ == "__main__":
    raise SystemExit(main())
