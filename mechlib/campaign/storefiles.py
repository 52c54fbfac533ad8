"""The files of a results store (:mod:`mechlib.campaign.store`): its tasks packed into
arrays and back, their checksums and counts, and the atomic replacement of a store.

``results.npz`` holds every task's inputs (keys, specifications, load steps, loads) and its
results (rows, columns of its kind, NaN-padded); ``snapshots.npz``, when the store holds
``STATE`` tasks, their inputs alike and their displacement fields end to end (``sizes``: each
field's width, its model's DOF count), float64, so a field comes back bit for bit.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mechlib.campaign.experiments import KINDS, RESULT_COLUMNS, STATE, TASK_KINDS
from mechlib.campaign.taskcache import cache_file

RESULTS = "results.npz"
#: the displacement fields of the ``STATE`` tasks, and the manifest field of its SHA-256
SNAPSHOTS, SNAPSHOTS_SHA = "snapshots.npz", "snapshots_sha256"
#: command that regenerates the store, named by every refusal of a stale store
REGENERATE = "make store"


class StoreError(RuntimeError):
    """A store that cannot be used as it is (the message says which part and what to do)."""


@dataclass(frozen=True)
class Entry:
    """One FE task: its cache key, model specification (:meth:`ModelSpec.key` text, or a
    compliant layout's :meth:`MechanismSpec.key`), kind, load steps, forces (rows, 6) [N] (a
    layout's loads: rows, its ports, in their units) and results (rows,
    ``RESULT_COLUMNS[kind]``): the poses [µm, µrad] (6 of a linear task, 18 of a non-linear
    one: three conventions) and a non-linear run's solve statistics after them
    (``SOLVE_STATS``: corrections, factorisations, restarts, final relative residual); a
    ``STATE`` task's result is its run's displacement field (1, n_dofs) [mm]."""

    key: str
    spec: str
    kind: str
    steps: int
    forces: np.ndarray
    results: np.ndarray

    @property
    def file(self) -> str:
        """The task's file name in an FE cache."""
        return cache_file(self.key, self.kind)


def write_arrays(folder: Path, entries: list[Entry]) -> dict[str, str]:
    """Write ``entries`` into ``folder``: the runs' in ``results.npz``, the ``STATE`` tasks' (if
    any) in ``snapshots.npz``; the manifest's checksum fields of what was written."""
    poses = [e for e in entries if e.kind != STATE]
    states = [e for e in entries if e.kind == STATE]
    arrays = _task_arrays(poses)
    results = np.full((int(arrays["rows"].sum()), max(RESULT_COLUMNS.values())), np.nan)
    at = np.r_[0, np.cumsum(arrays["rows"])]
    for i, e in enumerate(poses):
        results[at[i] : at[i + 1], : e.results.shape[1]] = e.results
    arrays["kind"] = np.array([KINDS.index(e.kind) for e in poses], dtype=np.int64)
    np.savez_compressed(folder / RESULTS, **arrays, results=results)
    sums = {"sha256": sha256(folder / RESULTS)}
    return sums | ({SNAPSHOTS_SHA: write_states(folder, states)} if states else {})


def _task_arrays(entries: list[Entry]) -> dict[str, np.ndarray]:
    """The inputs of ``entries`` as arrays: keys, specifications (each once) and each entry's
    index into them, load steps, rows, load columns and loads (all rows, padded with NaN)."""
    specs = sorted({e.spec for e in entries})
    rows = np.array([len(e.forces) for e in entries], dtype=np.int64)
    widths = np.array([e.forces.shape[1] for e in entries], dtype=np.int64)
    forces = np.full((int(rows.sum()), int(widths.max(initial=6))), np.nan)
    at = np.r_[0, np.cumsum(rows)]
    for i, e in enumerate(entries):
        forces[at[i] : at[i + 1], : e.forces.shape[1]] = e.forces
    return {
        "keys": np.array([e.key for e in entries], dtype="U32"),
        "spec_index": np.array([specs.index(e.spec) for e in entries], dtype=np.int64),
        "specs": np.array(specs, dtype=object).astype(str),
        "steps": np.array([e.steps for e in entries], dtype=np.int64),
        "rows": rows,
        "widths": widths,
        "forces": forces,
    }


def write_states(folder: Path, states: list[Entry]) -> str:
    """Write the ``STATE`` tasks as ``folder/snapshots.npz`` (their inputs, each field's width
    ``sizes`` and the fields end to end, float64); its SHA-256."""
    sizes = np.array([e.results.shape[1] for e in states], dtype=np.int64)
    fields = np.concatenate([e.results.ravel() for e in states]) if states else np.zeros(0)
    np.savez_compressed(folder / SNAPSHOTS, **_task_arrays(states), sizes=sizes, fields=fields)
    return sha256(folder / SNAPSHOTS)


def counts(entries: list[Entry]) -> dict[str, dict[str, int]]:
    """The manifest's ``entries`` (tasks) and ``runs`` (rows) of each kind."""
    return {
        "entries": {k: sum(e.kind == k for e in entries) for k in TASK_KINDS},
        "runs": {k: sum(len(e.forces) for e in entries if e.kind == k) for k in TASK_KINDS},
    }


def staging(folder: Path) -> Path:
    """An empty folder beside ``folder`` to write a new store in."""
    folder.parent.mkdir(parents=True, exist_ok=True)
    return Path(tempfile.mkdtemp(dir=folder.parent, prefix=f".{folder.name}."))


def replace(tmp: Path, folder: Path) -> None:
    """Put the written store ``tmp`` in the place of ``folder``: whole, or not at all."""
    old = folder.with_name(f".{folder.name}.old")
    shutil.rmtree(old, ignore_errors=True)
    if folder.exists():
        os.replace(folder, old)
    os.replace(tmp, folder)
    shutil.rmtree(old, ignore_errors=True)


def read_arrays(folder: Path, manifest: dict) -> list[Entry]:
    """The entries of the store ``folder`` whose ``manifest`` was read — its runs, then its
    ``STATE`` tasks —, the array files' checksums and the manifest's counts verified, the keys
    not.

    Raises
    ------
    StoreError
        For an array file whose checksum differs from the manifest's, a ``snapshots.npz`` the
        manifest does not list, counts that differ from the manifest's.
    """
    a = _arrays(folder / RESULTS, manifest["sha256"])
    starts = np.r_[0, np.cumsum(a["rows"])]
    kinds = [KINDS[int(k)] for k in a["kind"]]
    results = [a["results"][starts[i] : starts[i + 1], : RESULT_COLUMNS[k]]
               for i, k in enumerate(kinds)]  # fmt: skip
    entries = _entries(a, kinds, results)
    if SNAPSHOTS_SHA in manifest:
        a = _arrays(folder / SNAPSHOTS, manifest[SNAPSHOTS_SHA])
        at = np.r_[0, np.cumsum(a["rows"] * a["sizes"])]
        fields = [a["fields"][at[i] : at[i + 1]].reshape(int(r), int(n))
                  for i, (r, n) in enumerate(zip(a["rows"], a["sizes"], strict=True))]  # fmt: skip
        entries += _entries(a, [STATE] * len(fields), fields)
    elif (folder / SNAPSHOTS).exists():
        raise StoreError(
            f"{folder / SNAPSHOTS} is not listed in its manifest (added by hand?): regenerate the "
            f"store with `{REGENERATE}`"
        )
    held = counts(entries)["entries"]
    if any(held[k] != manifest["entries"].get(k, 0) for k in TASK_KINDS):
        raise StoreError(
            f"the store {folder} holds {held} tasks, its manifest counts {manifest['entries']}: "
            f"regenerate it with `{REGENERATE}`"
        )
    return entries


def _arrays(path: Path, expected: str) -> dict[str, np.ndarray]:
    """The arrays of a store's file, refused unless its SHA-256 is ``expected``."""
    if sha256(path) != expected:
        raise StoreError(
            f"{path} does not match the checksum of its manifest (edited or corrupt): "
            f"regenerate the store with `{REGENERATE}`"
        )
    with np.load(path) as z:
        return {k: z[k] for k in z.files}


def _entries(a: dict, kinds: list[str], results: list[np.ndarray]) -> list[Entry]:
    """The entries of a store file's arrays ``a``, with their ``kinds`` and ``results``."""
    starts = np.r_[0, np.cumsum(a["rows"])]
    widths = a.get("widths", np.full(len(a["keys"]), 6))
    return [
        Entry(key, str(a["specs"][a["spec_index"][i]]), kinds[i], int(a["steps"][i]),
              a["forces"][starts[i] : starts[i + 1], : int(widths[i])], results[i])
        for i, key in enumerate(a["keys"].tolist())
    ]  # fmt: skip


def sha256(path: Path) -> str:
    """The SHA-256 of a store's file (hex), refused if it is missing."""
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except FileNotFoundError as err:
        raise StoreError(f"no {path}: regenerate the store with `{REGENERATE}`") from err
