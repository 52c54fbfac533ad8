"""Records of key numbers: written by notebooks, compared with committed references.

A notebook creates one :class:`Recorder`, records each key number together with the tolerance
that the numerics can guarantee, and saves ``build/records/<notebook>.json``. The committed
reference ``tests/references/<notebook>.json`` is a copy of such a file, made by
``make references`` from a fresh run (never typed). :func:`compare` checks a run against its
reference with the reference's per-value tolerances.

Command line (used by the Makefile)::

    python -m mechlib.records update --records build/records --references tests/references
    python -m mechlib.records determinism --records build/records
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from mechlib.params import check_float

REPO_ROOT = Path(__file__).resolve().parents[1]
RECORDS_ENV = "MECHLIB_RECORDS"
FE_CACHE_ENV = "MECHLIB_FE_CACHE"


def records_dir() -> Path:
    """Folder that records are written to: ``$MECHLIB_RECORDS`` or ``<repo>/build/records``."""
    return Path(os.environ.get(RECORDS_ENV, REPO_ROOT / "build" / "records"))


def fe_cache_dir() -> Path:
    """Folder of cached FE results: ``$MECHLIB_FE_CACHE`` or ``<repo>/build/cache/experiments``."""
    return Path(os.environ.get(FE_CACHE_ENV, REPO_ROOT / "build" / "cache" / "experiments"))


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


@dataclass
class Recorder:
    """Collects the key numbers and reproduction-report rows of one notebook.

    Parameters
    ----------
    notebook : str
        Notebook name without extension; the record file is ``<notebook>.json``.
    """

    notebook: str
    values: dict[str, dict[str, Any]] = field(default_factory=dict)
    report: list[dict[str, Any]] = field(default_factory=list)

    def value(self, key: str, value: Any, *, rtol: float = 0.0, atol: float = 0.0) -> Any:
        """Record ``value`` under ``key`` with the tolerance a re-run must meet.

        Parameters
        ----------
        key : str
            Unique name, dotted by topic (``"table3.effects"``).
        value : float, int, bool, str or array_like
            The number(s). Arrays are stored as nested lists.
        rtol, atol : float
            Relative and absolute tolerance for numbers: ``|a - b| <= atol + rtol * |b|``.

        Returns
        -------
        The value as given, so a record can be written inline.
        """
        if key in self.values:
            raise ValueError(f"record key {key!r} was already recorded in {self.notebook}")
        check_float("rtol", rtol, low=0.0)
        check_float("atol", atol, low=0.0)
        self.values[key] = {"value": _plain(value), "rtol": rtol, "atol": atol}
        return value

    def report_row(self, row: dict[str, Any]) -> None:
        """Add one row of the reproduction report (see :mod:`mechlib.report`)."""
        self.report.append({k: _plain(v) for k, v in row.items()})

    def save(self, folder: Path | None = None) -> Path:
        """Write ``<folder>/<notebook>.json`` deterministically and return its path."""
        folder = Path(folder) if folder is not None else records_dir()
        folder.mkdir(parents=True, exist_ok=True)
        path = folder / f"{self.notebook}.json"
        payload = {"notebook": self.notebook, "values": self.values, "report": self.report}
        path.write_text(json.dumps(payload, indent=1, sort_keys=True) + "\n")
        return path


def load(path: Path) -> dict[str, Any]:
    """Read one record or reference file."""
    return json.loads(Path(path).read_text())


def recorded_value(notebook: str, key: str) -> Any:
    """A value recorded by another notebook: from ``records_dir()`` (this build or run) if it
    holds that notebook's record, else from the default build's ``build/records`` — and then it
    says so on stderr (a ``make run`` reads the default build's upstream record; a record of
    another profile is never taken without a word).

    Raises
    ------
    FileNotFoundError
        When that notebook has not been executed, naming the command that does it.
    """
    places = [
        records_dir() / f"{notebook}.json",
        REPO_ROOT / "build" / "records" / f"{notebook}.json",
    ]
    path = next((p for p in places if p.exists()), None)
    if path is None:
        raise FileNotFoundError(
            f"no record of notebook {notebook!r} in {places[0].parent} or {places[1].parent}: "
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


def rerun_identical(records: Path, notebooks: Path, python: str = sys.executable) -> list[str]:
    """Execute every notebook again and check its record is byte-identical to ``records``.

    The second run starts from an empty FE cache (``$MECHLIB_FE_CACHE`` in a temporary folder),
    so it checks that two cold computations agree, not merely that cached results are returned.
    """
    from mechlib.runs import papermill_command  # here: mechlib.runs imports this module

    problems = []
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, **{RECORDS_ENV: tmp, FE_CACHE_ENV: str(Path(tmp) / "fe-cache")})
        for nb in sorted(Path(notebooks).glob("*.ipynb")):
            first = Path(records) / f"{nb.stem}.json"
            if not first.exists():
                problems.append(f"{nb.stem}: no first-run record at {first}")
                continue
            cmd = papermill_command(nb, Path(tmp) / nb.name, python=python)
            subprocess.run(cmd, check=True, env=env, capture_output=True)
            if (Path(tmp) / first.name).read_bytes() != first.read_bytes():
                diffs = compare(load(Path(tmp) / first.name), load(first))
                problems.append(f"{nb.stem}: second run differs: {diffs or 'formatting only'}")
    return problems


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point (``update`` or ``determinism``)."""
    parser = argparse.ArgumentParser(prog="python -m mechlib.records")
    sub = parser.add_subparsers(dest="cmd", required=True)
    up = sub.add_parser("update", help="re-record references from build/records")
    up.add_argument("--records", type=Path, required=True)
    up.add_argument("--references", type=Path, required=True)
    det = sub.add_parser("determinism", help="re-run notebooks and require identical records")
    det.add_argument("--records", type=Path, required=True)
    det.add_argument("--notebooks", type=Path, default=REPO_ROOT / "notebooks")
    args = parser.parse_args(argv)
    if args.cmd == "update":
        for line in update_references(args.records, args.references):
            print(line)
        return 0
    problems = rerun_identical(args.records, args.notebooks)
    for p in problems:
        print("NOT DETERMINISTIC:", p)
    print("determinism: " + ("FAILED" if problems else "records identical on a second run"))
    return 1 if problems else 0


if __name__ == "__main__":
    raise SystemExit(main())
