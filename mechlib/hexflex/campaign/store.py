"""A results store: the pose-level results of FE tasks, kept as one versioned data set.

The FE cache (:mod:`mechlib.hexflex.campaign.experiments`) holds one ``<key>.npy`` file per task,
where the key digests the model specification, the kind of analysis, the load steps, the forces and
the sources that define a result
(:func:`~mechlib.hexflex.campaign.taskcache.model_code_fingerprint`).
A store is a folder with two files: ``results.npz`` (every task's inputs and poses, a few bytes
a run; no displacement field) and ``manifest.json`` (format version, the code fingerprint, a
SHA-256 of ``results.npz``, counts, and what the build wing adds: commit, date, processor,
time). :func:`seed_cache` writes its tasks into an FE cache, where a build reads them as it reads
any cached task; a task missing from the store is computed and cached as before.

What is refused, each with one line naming the thing and what to do (:class:`StoreError`): an
unknown format version, a malformed manifest, a ``results.npz`` whose checksum differs from the
manifest's, an entry whose key is not the digest of its own inputs (an edited force or
specification) or whose forces lie outside the model's force bound, and a store computed by
other FE code than the current one. Writing is atomic: a new store replaces the old one whole,
or not at all.

Two mechanisms share a store: the HexFlex's tasks (:class:`ModelSpec`, six actuator forces) and
those of a compliant layout (:class:`~mechlib.compliant.spec.MechanismSpec`, its own load ports
and bounds). Each family's keys carry the fingerprint of its own code, so the manifest keeps one
per family (:data:`FAMILIES`); the HexFlex's is also ``fingerprint``. A store whose HexFlex
fingerprint is not the current code's is refused; its entries of a family whose code changed
since are not seeded (the build computes them again). Format 4 (cache format 4) keys on the
code's normalised syntax trees, so a docstring or a comment edited keeps the store; a store of
an older format is refused by its version.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import tempfile
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from mechlib.compliant.spec import MechanismSpec
from mechlib.hexflex.campaign.experiments import KINDS, RESULT_COLUMNS
from mechlib.hexflex.campaign.taskcache import model_code_fingerprint, task_key
from mechlib.hexflex.fe.model import MAX_FORCE_N

#: Format of ``manifest.json`` and ``results.npz`` this code writes and reads (:data:`READS`);
#: 4: keys of cache format 4 (the fingerprint digests the FE code's syntax trees), a format-3
#: store is re-keyed to it by :func:`mechlib.hexflex.campaign.rekey.rekey_store`
STORE_VERSION = 4
READS = (4,)
#: the families of tasks a store holds: the HexFlex's, a compliant layout's
FAMILIES: tuple[str, ...] = ("hexflex", "mechanism")


def family(spec: str) -> str:
    """The family (:data:`FAMILIES`) of a task's specification text."""
    return "mechanism" if spec.startswith('{"mechanism"') else "hexflex"


def fingerprints() -> dict[str, str]:
    """The current code's fingerprint of each family's tasks."""
    return {"hexflex": model_code_fingerprint(),
            "mechanism": model_code_fingerprint(MechanismSpec.TASK_MODULES)}  # fmt: skip


MANIFEST = "manifest.json"
RESULTS = "results.npz"
#: manifest fields every store has (the build wing may add more: commit, processor, timings)
REQUIRED = ("version", "fingerprint", "fingerprints", "sha256", "entries", "runs")
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
    (``SOLVE_STATS``: corrections, factorisations, restarts, final relative residual)."""

    key: str
    spec: str
    kind: str
    steps: int
    forces: np.ndarray
    results: np.ndarray


def entries_from_cache(log: Path, cache_dir: Path) -> list[Entry]:
    """The tasks listed in an FE task log (``$MECHLIB_FE_LOG``: one JSON line a task), with
    their poses read from ``cache_dir``; a task without a cached result (it failed) is left out.

    Raises
    ------
    StoreError
        If the log is missing or holds a line that is not a task.
    """
    if not Path(log).is_file():
        raise StoreError(f"no FE task log at {log}: run the notebooks with $MECHLIB_FE_LOG set")
    seen: dict[str, Entry] = {}
    for n, line in enumerate(Path(log).read_text().splitlines(), start=1):
        if not line.strip():
            continue
        try:
            e = json.loads(line)
            key = e["file"].removesuffix(".npy")
            task = (e["spec"], e["kind"], int(e["steps"]), np.array(e["forces"], dtype=float))
        except (ValueError, KeyError, TypeError) as err:
            raise StoreError(f"line {n} of {log} is not an FE task ({err})") from err
        path = Path(cache_dir) / f"{key}.npy"
        if key in seen or not path.is_file():
            continue
        seen[key] = Entry(key, *task, np.load(path))
    return list(seen.values())


def write_store(entries: list[Entry], folder: Path, provenance: dict | None = None) -> Path:
    """Write ``entries`` as the store ``folder`` (replacing it whole, atomically).

    Parameters
    ----------
    entries : list of Entry
        The tasks, all computed by the current FE code.
    folder : Path
        The store's folder.
    provenance : dict, optional
        Extra manifest fields (commit, date, processor, seconds per run …).

    Returns
    -------
    Path
        ``folder``.
    """
    folder = Path(folder)
    specs = sorted({e.spec for e in entries})
    rows = np.array([len(e.forces) for e in entries], dtype=np.int64)
    results = np.full((int(rows.sum()), max(RESULT_COLUMNS.values())), np.nan)
    widths = np.array([e.forces.shape[1] for e in entries], dtype=np.int64)
    forces = np.full((int(rows.sum()), int(widths.max(initial=6))), np.nan)
    at = 0
    for e in entries:
        forces[at : at + len(e.forces), : e.forces.shape[1]] = e.forces
        at += len(e.forces)
    at = 0
    for e in entries:
        results[at : at + len(e.forces), : e.results.shape[1]] = e.results
        at += len(e.forces)
    arrays = {
        "keys": np.array([e.key for e in entries], dtype="U32"),
        "spec_index": np.array([specs.index(e.spec) for e in entries], dtype=np.int64),
        "specs": np.array(specs, dtype=object).astype(str),
        "kind": np.array([KINDS.index(e.kind) for e in entries], dtype=np.int64),
        "steps": np.array([e.steps for e in entries], dtype=np.int64),
        "rows": rows,
        "widths": widths,
        "forces": forces,
        "results": results,
    }
    folder.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(dir=folder.parent, prefix=f".{folder.name}."))
    np.savez_compressed(tmp / RESULTS, **arrays)
    kinds = [e.kind for e in entries]
    manifest = {
        "version": STORE_VERSION,
        "fingerprint": model_code_fingerprint(),
        "fingerprints": fingerprints(),
        "sha256": _sha256(tmp / RESULTS),
        "entries": {k: kinds.count(k) for k in KINDS},
        "runs": {k: int(rows[[i for i, x in enumerate(kinds) if x == k]].sum()) for k in KINDS},
        **(provenance or {}),
    }
    (tmp / MANIFEST).write_text(json.dumps(manifest, indent=1, sort_keys=True) + "\n")
    old = folder.with_name(f".{folder.name}.old")
    shutil.rmtree(old, ignore_errors=True)
    if folder.exists():
        os.replace(folder, old)
    os.replace(tmp, folder)
    shutil.rmtree(old, ignore_errors=True)
    return folder


def read_manifest(folder: Path, reads: tuple[int, ...] = READS) -> dict:
    """The manifest of the store ``folder``, checked for version (one of ``reads``) and fields.

    Raises
    ------
    StoreError
        A missing or malformed manifest, an unknown version.
    """
    path = Path(folder) / MANIFEST
    try:
        manifest = json.loads(path.read_text())
    except FileNotFoundError as err:
        raise StoreError(f"no store manifest at {path}: regenerate it with `{REGENERATE}`") from err
    except ValueError as err:
        raise StoreError(f"the store manifest {path} is not valid JSON ({err})") from err
    if not isinstance(manifest, dict) or any(f not in manifest for f in REQUIRED):
        raise StoreError(f"the store manifest {path} lacks fields: needs {', '.join(REQUIRED)}")
    if manifest["version"] not in reads:
        raise StoreError(
            f"the store {folder} has format version {manifest['version']!r}; this code reads "
            f"versions {', '.join(map(str, reads))}: regenerate it with `{REGENERATE}`"
        )
    return manifest


def read_store(folder: Path) -> tuple[dict, list[Entry]]:
    """The manifest and entries of the store ``folder``, every entry verified.

    Raises
    ------
    StoreError
        As :func:`read_manifest`; a ``results.npz`` whose checksum differs from the manifest's;
        an entry whose key is not its inputs' digest (named), or whose forces exceed the force
        bound.
    """
    folder = Path(folder)
    manifest = read_manifest(folder)
    entries = load_entries(folder, manifest)
    for e in entries:
        fingerprint = manifest["fingerprints"].get(family(e.spec), "")
        if family(e.spec) == "hexflex" or fingerprint == fingerprints()[family(e.spec)]:
            _check_entry(e)  # a layout's entry of older code: not seeded, its bounds unread
        expected = task_key(e.spec, e.kind, e.forces, e.steps, fingerprint)
        if expected != e.key:
            raise StoreError(
                f"store entry {e.key} does not match its own inputs (specification, forces or "
                f"steps edited; their digest is {expected}): regenerate with `{REGENERATE}`"
            )
    return manifest, entries


def load_entries(folder: Path, manifest: dict) -> list[Entry]:
    """The entries of the store ``folder`` whose ``manifest`` was read, its checksum verified,
    their keys not (:func:`read_store` checks them).

    Raises
    ------
    StoreError
        For a ``results.npz`` whose checksum differs from the manifest's.
    """
    folder = Path(folder)
    if _sha256(folder / RESULTS) != manifest["sha256"]:
        raise StoreError(
            f"{folder / RESULTS} does not match the checksum of its manifest (edited or "
            f"corrupt): regenerate the store with `{REGENERATE}`"
        )
    with np.load(folder / RESULTS) as z:
        a = {k: z[k] for k in z.files}
    starts = np.r_[0, np.cumsum(a["rows"])]
    widths = a.get("widths", np.full(len(a["keys"]), 6))
    entries = []
    for i, key in enumerate(a["keys"].tolist()):
        kind = KINDS[int(a["kind"][i])]
        forces = a["forces"][starts[i] : starts[i + 1], : int(widths[i])]
        entries.append(Entry(
            key, str(a["specs"][a["spec_index"][i]]), kind, int(a["steps"][i]), forces,
            a["results"][starts[i] : starts[i + 1], : RESULT_COLUMNS[kind]],
        ))  # fmt: skip
    return entries


@lru_cache(maxsize=64)
def _mechanism(spec: str) -> MechanismSpec:
    return MechanismSpec.from_key(spec)


def _check_entry(e: Entry) -> None:
    """Refuse an entry whose loads lie beyond its model's bounds or whose results are not
    finite."""
    bad = not np.all(np.isfinite(e.results))
    if family(e.spec) == "hexflex":
        bad = bad or np.abs(e.forces).max(initial=0.0) > MAX_FORCE_N
        bound = f"±{MAX_FORCE_N} N"
    else:
        try:
            _mechanism(e.spec).check_design(e.forces)
        except (ValueError, KeyError, TypeError):
            bad = True
        bound = "its load ports' bounds"
    if bad:
        raise StoreError(
            f"store entry {e.key}: loads beyond {bound} or results not finite: regenerate the "
            f"store with `{REGENERATE}`"
        )


def seed_cache(folder: Path, cache_dir: Path) -> int:
    """Write every entry of the store ``folder`` into the FE cache ``cache_dir`` (atomically,
    file by file); returns the number of tasks written.

    Raises
    ------
    StoreError
        As :func:`read_store`, and when the store's HexFlex tasks were computed by other FE code
        than the current (its fingerprint differs): one line, with the entry count and the
        command. Entries of a compliant layout computed by other code are left out, not refused.
    """
    manifest, entries = read_store(folder)
    now = model_code_fingerprint()
    if manifest["fingerprint"] != now:
        raise StoreError(
            f"the {len(entries)} entries of {folder} were computed by other FE code "
            f"(fingerprint {manifest['fingerprint']}, the current code's {now}): regenerate "
            f"them with `{REGENERATE}`"
        )
    current = fingerprints()
    entries = [e for e in entries if manifest["fingerprints"].get(family(e.spec)) ==
               current[family(e.spec)]]  # fmt: skip
    cache_dir = Path(cache_dir)
    cache_dir.mkdir(parents=True, exist_ok=True)
    for e in entries:
        fd, tmp = tempfile.mkstemp(dir=cache_dir, suffix=".npy.tmp")
        with os.fdopen(fd, "wb") as fh:
            np.save(fh, e.results)
        os.replace(tmp, cache_dir / f"{e.key}.npy")
    return len(entries)


def _sha256(path: Path) -> str:
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except FileNotFoundError as err:
        raise StoreError(f"no {path}: regenerate the store with `{REGENERATE}`") from err
