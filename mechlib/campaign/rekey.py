"""Re-keying a results store of format 3 to format 4, with the proof that its runs still hold.

Cache format 3 keyed every task on :func:`byte_fingerprint`, a digest of the FE closure's bytes
and module names; format 4 keys it on
:func:`~mechlib.campaign.taskcache.model_code_fingerprint`, a digest of the same code's
normalised syntax trees. A format-3 store computed by code byte for byte the current one was
therefore computed by code whose format-4 fingerprint is the current one: its runs need new keys,
not new solves. :func:`rekey_store` checks exactly that — the store's fingerprints are the
current code's byte fingerprints, and every entry's key is the format-3 digest of its own inputs
— and only then writes each entry under its format-4 key, its results bit for bit.

:func:`byte_fingerprint` serves this check only; nothing keys on it.
"""

from __future__ import annotations

import dataclasses
import datetime as dt
import hashlib
import importlib.util
import os
import shutil
from pathlib import Path

import numpy as np

from mechlib.campaign import store
from mechlib.campaign.sources import model_modules
from mechlib.campaign.spec import families, primary
from mechlib.campaign.taskcache import _defines_code, task_key

#: the cache and store formats whose keys digest the FE code's bytes
OLD_CACHE_VERSION = OLD_STORE_VERSION = 3
#: what the manifest says of a re-keyed store
WHY = (
    "the FE code that computed these runs is byte for byte the code of this commit (its format-3 "
    "fingerprints equal the store's) and every key was the format-3 digest of its own inputs; "
    "keys now digest the code's syntax trees (cache format 4), results unchanged"
)
#: manifest fields of the computing build that a re-keyed store keeps
PROVENANCE = ("commit", "date", "processor", "python", "seconds", "workers", "from_empty")


def byte_fingerprint(task_modules: tuple[str, ...]) -> str:
    """The format-3 fingerprint of the current code: a digest of the names and bytes of the
    modules :func:`model_modules` finds (imports under ``if TYPE_CHECKING:`` followed, as
    format 3 did), a package ``__init__`` holding only its docstring left out.

    Parameters
    ----------
    task_modules : tuple of str
        The modules a task runs.

    Returns
    -------
    str
        16 hex digits.
    """
    h = hashlib.sha256()
    for name in model_modules(task_modules, format3=True):
        source = Path(importlib.util.find_spec(name).origin).read_bytes()
        if not _defines_code(source):
            continue
        h.update(name.encode())
        h.update(source)
    return h.hexdigest()[:16]


def byte_fingerprints() -> dict[str, str]:
    """:func:`byte_fingerprint` of each registered family's tasks."""
    return {f.name: byte_fingerprint(f.spec.TASK_MODULES) for f in families()}


def rekey_store(folder: Path, commit: str) -> tuple[dict, int]:
    """Re-key the format-3 store ``folder`` in place to the current format: written beside it,
    read back (every key checked against its inputs, every run bit for bit the old one's), then
    put in its place; on any failure the old store stays as it was.

    Parameters
    ----------
    folder : Path
        The store.
    commit : str
        The commit of the code that re-keys it (recorded in the manifest's ``rekeyed``).

    Returns
    -------
    dict
        The new manifest.
    int
        The number of entries re-keyed.

    Raises
    ------
    StoreError
        When the store is not of format 3, its checksum fails, it was computed by code other
        than the current one (its fingerprints are not the current byte fingerprints), an
        entry's key is not the format-3 digest of its inputs, or the store written does not read
        back with the same inputs and results.
    """
    folder = Path(folder)
    manifest = store.read_manifest(folder, reads=(OLD_STORE_VERSION,))
    old = byte_fingerprints()
    lead = primary().name
    stored = manifest.get("fingerprints", {lead: manifest["fingerprint"]})
    if stored != old or manifest["fingerprint"] != old[lead]:
        raise store.StoreError(
            f"the store {folder} was computed by FE code other than the current one (its "
            f"fingerprints {stored}, the current code's bytes {old}): it cannot be re-keyed; "
            f"regenerate it with `{store.REGENERATE}`"
        )
    entries = store.load_entries(folder, manifest)
    for e in entries:
        expected = task_key(
            e.spec, e.kind, e.forces, e.steps, old[store.family(e.spec)], OLD_CACHE_VERSION
        )
        if expected != e.key:
            raise store.StoreError(
                f"store entry {e.key} is not the format-{OLD_CACHE_VERSION} digest of its own "
                f"inputs ({expected}): it cannot be re-keyed; regenerate with `{store.REGENERATE}`"
            )
    new = store.fingerprints()
    rekeyed = [
        dataclasses.replace(e, key=task_key(e.spec, e.kind, e.forces, e.steps,
                                            new[store.family(e.spec)]))
        for e in entries
    ]  # fmt: skip
    if len({e.key for e in rekeyed}) != len(entries):
        raise store.StoreError(f"two entries of {folder} share a new key: not re-keyed")
    provenance = {k: manifest[k] for k in PROVENANCE if k in manifest}
    provenance["rekeyed"] = {
        "from": {"version": manifest["version"], "fingerprints": old},
        # the build that solved the runs, kept here too: a later pack that adds runs replaces
        # the top-level fields with its own
        "solved": {k: manifest[k] for k in PROVENANCE if k in manifest},
        "commit": commit,
        "date": dt.datetime.now(dt.UTC).isoformat(timespec="seconds"),
        "entries": len(entries),
        "why": WHY,
    }
    staged = folder.with_name(f".{folder.name}.rekeyed")
    try:
        store.write_store(rekeyed, staged, provenance)
        written, back = store.read_store(staged)  # every new key checked against its inputs
        _same_runs(entries, back)
    except BaseException:
        shutil.rmtree(staged, ignore_errors=True)
        raise
    retired = folder.with_name(f".{folder.name}.old")
    shutil.rmtree(retired, ignore_errors=True)
    os.replace(folder, retired)
    os.replace(staged, folder)
    shutil.rmtree(retired, ignore_errors=True)
    return written, len(back)


def _same_runs(before: list[store.Entry], after: list[store.Entry]) -> None:
    """Refuse a re-keyed store whose entries differ from the old ones in anything but the key."""
    same = len(before) == len(after) and all(
        (a.spec, a.kind, a.steps) == (b.spec, b.kind, b.steps)
        and np.array_equal(a.forces, b.forces)
        and np.array_equal(a.results, b.results, equal_nan=True)
        for a, b in zip(before, after, strict=True)
    )
    if not same:
        raise store.StoreError("the re-keyed store does not read back with the same runs")
