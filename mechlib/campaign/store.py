"""A results store: the pose-level results of FE tasks, kept as one versioned data set.

The FE cache (:mod:`mechlib.campaign.experiments`) holds one ``<key>.npy`` file per task,
where the key digests the model specification, the kind of analysis, the load steps, the forces and
the sources that define a result
(:func:`~mechlib.campaign.taskcache.model_code_fingerprint`).
A store is a folder with two or three files: ``results.npz`` (every task's inputs and poses, a
few bytes a run; no displacement field), ``snapshots.npz`` when it holds ``STATE`` tasks (the
converged displacement fields a reduced-order model is built from,
:mod:`mechlib.hexflex.rom.snapshots`: 8 bytes a DOF) and ``manifest.json`` (format version, the
code fingerprint, a SHA-256 of each array file, counts, and what the build wing adds: commit,
date, processor, time); :mod:`~mechlib.campaign.storefiles` lays out the array files.
:func:`seed_cache` writes its tasks into an FE cache, where a build reads them as it reads any
cached task; a task missing from the store is computed and cached as before.
:func:`add_states` adds ``STATE`` tasks to a store without regenerating its runs.

What is refused, each with one line naming the thing and what to do (:class:`StoreError`): an
unknown format version, a malformed manifest, a ``results.npz`` or ``snapshots.npz`` whose
checksum differs from the manifest's (or a ``snapshots.npz`` it does not list), tasks other than
it counts, an entry whose key is not the digest of its own inputs (an edited force or
specification) or whose forces lie outside the model's force bound, and a store computed by
other FE code than the current one. Writing is atomic: a new store replaces the old one whole,
or not at all.

Several families of specifications share a store (:mod:`mechlib.campaign.spec`'s registry: the
HexFlex's ``ModelSpec``, six actuator forces; a compliant layout's ``MechanismSpec``, its own
load ports and bounds). Each family's keys carry the fingerprint of its own code, so the
manifest keeps one per family (:func:`fingerprints`); the primary family's is also
``fingerprint``. A store whose primary fingerprint is not the current code's is refused; its
entries of another family whose code changed since are not seeded (the build computes them
again). The store names no family: a task's family and bounds come from its key text through the
registry. Format 5 (cache format 5) keys on the
code's normalised syntax trees, each module's digest covering what it imports, so a docstring or
a comment edited keeps the store; a store of an older format is refused by its version.
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from functools import lru_cache
from pathlib import Path

import numpy as np

from mechlib.campaign.experiments import STATE
from mechlib.campaign.spec import families, family_of, primary, spec_from_key
from mechlib.campaign.storefiles import (
    REGENERATE,
    RESULTS,
    SNAPSHOTS_SHA,
    Entry,
    StoreError,
    counts,
    read_arrays,
    replace,
    staging,
    write_arrays,
    write_states,
)
from mechlib.campaign.storefiles import SNAPSHOTS as SNAPSHOTS  # re-exported
from mechlib.campaign.taskcache import cache_file, model_code_fingerprint, task_key

#: Format of ``manifest.json`` and ``results.npz`` this code writes and reads (:data:`READS`);
#: 4: keys of cache format 4 (the fingerprint digests the FE code's syntax trees); 5: of cache
#: format 5 (each module digested with all it imports, the task runner in every closure)
STORE_VERSION = 5
READS = (5,)


def family(spec: str) -> str:
    """The family (:func:`mechlib.campaign.spec.families`) of a task's specification text."""
    return family_of(spec)


def fingerprints() -> dict[str, str]:
    """The current code's fingerprint of each registered family's tasks."""
    return {f.name: model_code_fingerprint(f.spec.TASK_MODULES) for f in families()}


def fingerprint() -> str:
    """The current code's fingerprint of the primary family's tasks (a manifest's
    ``fingerprint``)."""
    return model_code_fingerprint(primary().spec.TASK_MODULES)


MANIFEST = "manifest.json"
#: manifest fields every store has (the build wing may add more: commit, processor, timings)
REQUIRED = ("version", "fingerprint", "fingerprints", "sha256", "entries", "runs")


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
            key = e["file"].split(".", 1)[0]
            task = (e["spec"], e["kind"], int(e["steps"]), np.array(e["forces"], dtype=float))
        except (ValueError, KeyError, TypeError, AttributeError) as err:
            raise StoreError(f"line {n} of {log} is not an FE task ({err})") from err
        path = Path(cache_dir) / cache_file(key, task[1])
        if key in seen or not path.is_file():
            continue
        seen[key] = Entry(key, *task, np.load(path))
    return list(seen.values())


def write_store(entries: list[Entry], folder: Path, provenance: dict | None = None) -> Path:
    """Write ``entries`` as the store ``folder`` (replacing it whole, atomically): the runs'
    poses in ``results.npz``, the ``STATE`` tasks' fields (if any) in ``snapshots.npz``.

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
    tmp = staging(folder)
    try:
        manifest = {
            "version": STORE_VERSION,
            "fingerprint": fingerprint(),
            "fingerprints": fingerprints(),
            **write_arrays(tmp, entries),
            **counts(entries),
            **(provenance or {}),
        }
        (tmp / MANIFEST).write_text(json.dumps(manifest, indent=1, sort_keys=True) + "\n")
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    replace(tmp, folder)
    return folder


def add_states(folder: Path, states: list[Entry], provenance: dict) -> dict:
    """Put the ``STATE`` tasks ``states`` into the store ``folder`` beside its runs, without
    regenerating it: ``results.npz`` is kept byte for byte, ``snapshots.npz`` written anew with
    the stored fields and ``states`` (a stored field of the same key replaced), the manifest's
    counts and checksum updated and ``provenance`` kept as its ``snapshots`` field; the new store
    is read back, every key checked against its inputs, before it replaces the old one.

    Parameters
    ----------
    folder : Path
        The store, computed by the current FE code.
    states : list of Entry
        ``STATE`` tasks computed by the current FE code.
    provenance : dict
        What made them (commit, date, seconds …).

    Returns
    -------
    dict
        The new manifest.

    Raises
    ------
    StoreError
        As :func:`read_store`; a store of other FE code than the current one.
    ValueError
        For an entry of another kind.
    """
    folder = Path(folder)
    if any(e.kind != STATE for e in states):
        raise ValueError(f"states must be {STATE!r} tasks, got {sorted({e.kind for e in states})}")
    manifest, entries = read_store(folder)
    if manifest["fingerprints"] != fingerprints():
        raise StoreError(
            f"{folder} was computed by other FE code (fingerprints {manifest['fingerprints']}, "
            f"the current code's {fingerprints()}): regenerate it with `{REGENERATE}`"
        )
    kept = {e.key: e for e in entries if e.kind == STATE} | {e.key: e for e in states}
    tmp = staging(folder)
    try:
        shutil.copy2(folder / RESULTS, tmp / RESULTS)
        manifest = {
            **manifest,
            **counts([e for e in entries if e.kind != STATE] + list(kept.values())),
            SNAPSHOTS_SHA: write_states(tmp, list(kept.values())),
            "snapshots": provenance,
        }
        (tmp / MANIFEST).write_text(json.dumps(manifest, indent=1, sort_keys=True) + "\n")
        read_store(tmp)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    replace(tmp, folder)
    return manifest


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
    current, lead = fingerprints(), primary().name
    for e in entries:
        stored = manifest["fingerprints"].get(family(e.spec), "")
        if family(e.spec) == lead or stored == current.get(family(e.spec)):
            _check_entry(e)  # another family's entry of older code: not seeded, bounds unread
        expected = task_key(e.spec, e.kind, e.forces, e.steps, stored)
        if expected != e.key:
            raise StoreError(
                f"store entry {e.key} does not match its own inputs (specification, forces or "
                f"steps edited; their digest is {expected}): regenerate with `{REGENERATE}`"
            )
    return manifest, entries


def load_entries(folder: Path, manifest: dict) -> list[Entry]:
    """The entries of the store ``folder`` whose ``manifest`` was read — its runs, then its
    ``STATE`` tasks —, the array files' checksums and the manifest's counts verified, the keys
    not (:func:`read_store` checks them).

    Raises
    ------
    StoreError
        For an array file whose checksum differs from the manifest's, a ``snapshots.npz`` the
        manifest does not list, counts that differ from the manifest's.
    """
    return read_arrays(Path(folder), manifest)


@lru_cache(maxsize=64)
def _spec(text: str) -> object:
    return spec_from_key(text)


def _check_entry(e: Entry) -> None:
    """Refuse an entry whose loads lie beyond its model's bounds (its specification's
    ``check_design``) or whose results are not finite."""
    bad = not np.all(np.isfinite(e.results))
    try:
        _spec(e.spec).check_design(e.forces)
    except (ValueError, KeyError, TypeError):
        bad = True
    if bad:
        raise StoreError(
            f"store entry {e.key}: loads beyond its model's bounds or results not finite: "
            f"regenerate the store with `{REGENERATE}`"
        )


def seed_cache(folder: Path, cache_dir: Path) -> int:
    """Write every entry of the store ``folder`` into the FE cache ``cache_dir`` (atomically,
    file by file); returns the number of tasks written.

    Raises
    ------
    StoreError
        As :func:`read_store`, and when the store's primary family's tasks were computed by other
        FE code than the current (its fingerprint differs): one line, with the entry count and
        the command. Entries of another family computed by other code are left out, not refused.
    """
    manifest, entries = read_store(folder)
    now = fingerprint()
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
        os.replace(tmp, cache_dir / e.file)
    return len(entries)
