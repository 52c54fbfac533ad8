"""A new store compared with the previous one, and a stopped regeneration completed from it.

:func:`compare` matches a new store's tasks with the previous store's by their inputs (model,
kind, steps, forces; keys of any format) and records, for the manifest (``compared``), how many
both hold, how many are bit for bit the same and the largest difference of each kind of task.

A regeneration from an empty FE cache solves every task again with the current code. When it is
stopped before the end (a session's time, a node's walltime), :func:`carry` completes what it
solved with the previous store's other tasks, under the current keys, and says so — only if every
task that both hold is bit for bit the same in both, and with a record for the manifest
(``carried``): how many were carried, how many agreed, and the previous store's commit, format and
fingerprints. A later regeneration that solves them replaces the record (:mod:`.store`).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from mechlib.campaign import store
from mechlib.campaign.storefiles import Entry, StoreError, read_arrays
from mechlib.campaign.taskcache import task_key

#: what the manifest says of carried tasks
WHY = (
    "the regeneration from an empty FE cache was stopped before it solved these tasks; every task "
    "it solved that the previous store also held is bit for bit the previous store's (agreed), "
    "so these are carried under the current keys until a regeneration solves them"
)


def _task(e: Entry) -> tuple[str, str, int, bytes]:
    return e.spec, e.kind, e.steps, np.ascontiguousarray(e.forces, dtype=np.float64).tobytes()


def _previous(folder: Path) -> tuple[dict, list[Entry]]:
    """The manifest and the tasks of the store ``folder`` (any format)."""
    folder = Path(folder)
    try:
        manifest = json.loads((folder / store.MANIFEST).read_text())
    except (OSError, ValueError) as err:
        raise StoreError(f"no readable store manifest in {folder} ({err})") from err
    return manifest, read_arrays(folder, manifest)


def _origin(manifest: dict) -> dict:
    return {f: manifest.get(f) for f in ("commit", "date", "version", "fingerprints")}


def compare(entries: list[Entry], folder: Path) -> dict:
    """How the tasks ``entries`` compare with those of the previous store ``folder``.

    Parameters
    ----------
    entries : list of Entry
        A new store's tasks.
    folder : Path
        The previous store (any format: tasks are matched by model, kind, steps and forces).

    Returns
    -------
    dict
        ``tasks`` (of the new store), ``both`` (also in the previous one), ``identical`` (of
        those, bit for bit), ``largest_difference`` (by kind: the largest absolute difference of
        any result of a task both hold, in the results' units), ``only_previous`` (tasks the new
        store lacks) and ``from`` (the previous store's commit, date, format and fingerprints).

    Raises
    ------
    StoreError
        If the previous store cannot be read, or a task both hold has results of another shape.
    """
    manifest, previous = _previous(folder)
    new = {_task(e): e for e in entries}
    both = identical = 0
    largest: dict[str, float] = {}
    for old in previous:
        e = new.get(_task(old))
        if e is None:
            continue
        if e.results.shape != old.results.shape:
            raise StoreError(
                f"task {e.key} ({e.kind}) has results of shape {e.results.shape}, the previous "
                f"store's {old.results.shape}"
            )
        both += 1
        identical += bool(np.array_equal(e.results, old.results))
        diff = float(np.max(np.abs(e.results - old.results), initial=0.0))
        largest[e.kind] = max(largest.get(e.kind, 0.0), diff)
    return {
        "tasks": len(entries),
        "both": both,
        "identical": identical,
        "largest_difference": dict(sorted(largest.items())),
        "only_previous": len(previous) - both,
        "from": _origin(manifest),
    }


def carry(entries: list[Entry], folder: Path) -> tuple[list[Entry], dict]:
    """The tasks of the store ``folder`` (any format) that ``entries`` lacks, keyed for the
    current code, and the manifest's record of them.

    Parameters
    ----------
    entries : list of Entry
        The tasks a (stopped) regeneration solved.
    folder : Path
        The previous store.

    Returns
    -------
    carried : list of Entry
        The previous store's other tasks, each under its current key.
    record : dict
        ``entries`` (how many carried), ``agreed`` (tasks in both, all identical), ``from`` (the
        previous store's commit, format version and fingerprints) and ``why``.

    Raises
    ------
    StoreError
        If a task in both differs in a bit (nothing is carried then), or the previous store
        cannot be read.
    """
    manifest, previous = _previous(folder)
    solved = {_task(e): e for e in entries}
    agreed, carried = 0, []
    fingerprints = store.fingerprints()
    for e in previous:
        new = solved.get(_task(e))
        if new is None:
            key = task_key(e.spec, e.kind, e.forces, e.steps, fingerprints[store.family(e.spec)])
            carried.append(Entry(key, e.spec, e.kind, e.steps, e.forces, e.results))
        elif np.array_equal(new.results, e.results):
            agreed += 1
        else:
            raise StoreError(
                f"task {new.key} ({e.kind}) differs from the previous store's {e.key}: a store "
                "whose tasks moved is regenerated whole, never completed from the previous one"
            )
    record = {"entries": len(carried), "agreed": agreed, "from": _origin(manifest), "why": WHY}
    return carried, record
