"""A new FE results store compared with the one it replaces, task by task.

Tasks are matched by their inputs — model specification, kind, load steps and forces — not by
their keys, so stores of any key format compare. :func:`compare` gives the manifest's
``compared`` record; :mod:`.carry` uses the same matching.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from mechlib.campaign import store
from mechlib.campaign.storefiles import Entry, StoreError, read_arrays

#: the units of a task's results, by kind (poses in µm and µrad, :mod:`mechlib.fe.pose`; a snapshot
#: is a displacement field in mm; a size counts degrees of freedom)
RESULT_UNITS = {"linear": "µm, µrad", "nonlinear": "µm, µrad", "size": "DOFs", "state": "mm"}


def task_inputs(e: Entry) -> tuple[str, str, int, bytes]:
    """What a task is, whatever its key: its model, kind, steps and forces (as bytes)."""
    return e.spec, e.kind, e.steps, np.ascontiguousarray(e.forces, dtype=np.float64).tobytes()


def previous_store(folder: Path) -> tuple[dict, list[Entry]]:
    """The manifest and the tasks of the store ``folder`` (any format).

    Raises
    ------
    StoreError
        If its manifest cannot be read.
    """
    folder = Path(folder)
    try:
        manifest = json.loads((folder / store.MANIFEST).read_text())
    except (OSError, ValueError) as err:
        raise StoreError(f"no readable store manifest in {folder} ({err})") from err
    return manifest, read_arrays(folder, manifest)


def origin(manifest: dict) -> dict:
    """The commit, date, format version and fingerprints a store's ``manifest`` records."""
    return {f: manifest.get(f) for f in ("commit", "date", "version", "fingerprints")}


def same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether two results are bit for bit the same (dtype, shape and bytes; ``-0.0`` is not
    ``0.0``).

    >>> same_bits(np.zeros(2), np.zeros(2)), same_bits(np.zeros(2), -np.zeros(2))
    (True, False)
    """
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def compare(entries: list[Entry], folder: Path) -> dict:
    """How the tasks ``entries`` compare with those of the previous store ``folder``.

    Parameters
    ----------
    entries : list of Entry
        A new store's tasks.
    folder : Path
        The previous store (any format: tasks are matched by :func:`task_inputs`).

    Returns
    -------
    dict
        ``tasks`` (of the new store), ``both`` (also in the previous one), ``identical`` (of
        those, bit for bit), ``largest_difference`` (by kind: the largest absolute difference of
        any result of a task both hold), ``units`` (of those differences, by kind:
        :data:`RESULT_UNITS`), ``only_previous`` (the previous store's tasks the new one lacks)
        and ``from`` (:func:`origin`).

    Raises
    ------
    StoreError
        If the previous store cannot be read, or a task both hold has results of another shape
        or a difference that is not finite.
    """
    manifest, previous = previous_store(folder)
    new = {task_inputs(e): e for e in entries}
    both = identical = 0
    largest: dict[str, float] = {}
    for old in previous:
        e = new.get(task_inputs(old))
        if e is None:
            continue
        if e.results.shape != old.results.shape:
            raise StoreError(
                f"task {e.key} ({e.kind}) has results of shape {e.results.shape}, the previous "
                f"store's {old.results.shape}"
            )
        same = same_bits(e.results, old.results)
        diff = 0.0 if same else float(np.max(np.abs(e.results - old.results), initial=0.0))
        if not np.isfinite(diff):
            raise StoreError(f"task {e.key} ({e.kind}): a difference from the previous store "
                             f"that is not finite ({diff})")  # fmt: skip
        both += 1
        identical += same
        largest[e.kind] = max(largest.get(e.kind, 0.0), diff)
    return {
        "tasks": len(entries),
        "both": both,
        "identical": identical,
        "largest_difference": dict(sorted(largest.items())),
        "units": {k: RESULT_UNITS.get(k, "") for k in sorted(largest)},
        "only_previous": len(previous) - both,
        "from": origin(manifest),
    }
