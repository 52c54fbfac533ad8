"""Records against references: the comparison ``make check-records`` and ``make test`` make, and
``make references``, which re-records ``tests/references/`` from a build's records.

The committed reference ``tests/references/<notebook>.json`` is a copy of a record made by
``make references`` from a fresh run (never typed). :func:`compare` checks a run against its
reference with the reference's per-value tolerances (they are reviewed when committed).
"""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

import numpy as np

from mechlib.reporting.records import load


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
