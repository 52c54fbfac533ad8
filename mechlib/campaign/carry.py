"""Carrying a previous store's tasks into a new one whose regeneration was cut short.

A regeneration from an empty FE cache solves every task again with the current code. When it is
stopped before the end (a session's time, a node's walltime), :func:`carry` completes what it
solved with the previous store's other tasks, under the current keys, and says so — only if every
task that both hold is bit for bit the same in both, and with a record for the manifest
(``carried``): how many were carried, how many agreed, and the previous store's commit, format and
fingerprints. A later regeneration that solves them replaces the record (:mod:`.store`).
"""

from __future__ import annotations

from pathlib import Path

from mechlib.campaign import store
from mechlib.campaign.compare import origin, previous_store, same_bits, task_inputs
from mechlib.campaign.storefiles import Entry, StoreError
from mechlib.campaign.taskcache import task_key

#: what the manifest says of carried tasks
WHY = (
    "the regeneration from an empty FE cache was stopped before it solved these tasks; every task "
    "it solved that the previous store also held is bit for bit the previous store's (agreed), "
    "so these are carried under the current keys until a regeneration solves them"
)


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
        ``entries`` (how many carried), ``agreed`` (tasks in both, all identical) and
        ``agreed_by_family``, ``from`` (the previous store's commit, format version and
        fingerprints) and ``why``.

    Raises
    ------
    StoreError
        If a task in both differs in a bit (nothing is carried then), a family would be carried
        without one task of it solved and compared, or the previous store cannot be read.
    """
    manifest, previous = previous_store(folder)
    solved = {task_inputs(e): e for e in entries}
    agreed: dict[str, int] = {}
    carried = []
    fingerprints = store.fingerprints()
    for e in previous:
        family = store.family(e.spec)
        new = solved.get(task_inputs(e))
        if new is None:
            key = task_key(e.spec, e.kind, e.forces, e.steps, fingerprints[family])
            carried.append(Entry(key, e.spec, e.kind, e.steps, e.forces, e.results))
        elif same_bits(new.results, e.results):
            agreed[family] = agreed.get(family, 0) + 1
        else:
            raise StoreError(
                f"task {new.key} ({e.kind}) differs from the previous store's {e.key}: a store "
                "whose tasks moved is regenerated whole, never completed from the previous one"
            )
    unchecked = sorted({store.family(e.spec) for e in carried} - set(agreed))
    if unchecked:
        raise StoreError(
            f"no task of family {', '.join(unchecked)} was solved by this code to compare with "
            "the previous store: its tasks cannot be carried (solve some of them first)"
        )
    record = {
        "entries": len(carried),
        "agreed": sum(agreed.values()),
        "agreed_by_family": dict(sorted(agreed.items())),
        "from": origin(manifest),
        "why": WHY,
    }
    return carried, record
