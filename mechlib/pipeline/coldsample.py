"""The determinism check's cold sample: FE tasks a re-run read from its cache, recomputed cold.

``make test``'s determinism step (``python -m mechlib.pipeline determinism --rerun …``) compares
the re-run's records with the first run's and, through :func:`cold_sample`, recomputes a seeded
sample of the FE tasks the re-run did not solve but read (docs/determinism.md).
"""

from __future__ import annotations

from pathlib import Path

from mechlib.pipeline.rerun import FE_CACHE_COPY, HIT_LOG

#: non-linear FE tasks that the determinism check recomputes cold when the re-run read the first
#: run's FE cache (each about a non-linear run, 5–40 s on the models the chapters' studies refine,
#: plus one model build per model). With ``--store-checked`` (``make test``) the tasks the cache
#: holds from the results store are left out of this draw: the store's own cold sample
#: (``storecmd.COLD_NONLINEAR``) recomputes its entries in the same ``make test``, so this one
#: samples only what the first run solved itself (nothing, on a clean clone of a current store)
COLD_SAMPLE = 3


def cold_sample(rerun_dir: Path, n_nonlinear: int, store: Path | None = None) -> bool:
    """Recompute a seeded sample of the FE tasks a re-run read from its cache, and say whether
    the check failed.

    Parameters
    ----------
    rerun_dir : Path
        The re-run's folder: its hit log (``HIT_LOG``) and its ``fe-cache``.
    n_nonlinear : int
        Non-linear tasks to recompute (one block of linear runs besides).
    store : Path, optional
        The results store: tasks whose cache file holds its entry under the same key are left
        out (the store's own cold check covers them), and each such file must equal that entry.

    Returns
    -------
    bool
        True if a recomputed task differs from its cached result beyond ``AGREE_RTOL``, a cache
        file differs from the store's entry of its key, or the re-run read no non-linear task.
    """
    import numpy as np

    from mechlib.campaign.cachecheck import AGREE_RTOL, check_sample, read_log
    from mechlib.campaign.store import read_store
    from mechlib.fespecs import HEXFLEX  # noqa: F401  (the FE families registered)

    read = read_log(rerun_dir / HIT_LOG)
    if not any(e["kind"] == "nonlinear" for e in read):
        print("determinism: the re-run read no non-linear FE task from the cache to recompute")
        return True
    entries = {e.file: e.results for e in read_store(store)[1]} if store else {}
    cache = rerun_dir / FE_CACHE_COPY
    stored = {e["file"] for e in read if e["file"] in entries}
    edited = sorted(f for f in stored if not np.array_equal(np.load(cache / f), entries[f]))
    for f in edited:
        print(f"  cached task {f} DIFFERS from the results store's entry under its key")
    own = [e for e in read if e["file"] not in stored]
    if not own:
        print(
            f"determinism: all {len(read)} FE tasks the re-run read from the cache are the "
            f"results store's entries, which its own cold sample recomputes (store check)"
        )
        return bool(edited)
    per_kind = {"nonlinear": n_nonlinear, "linear": 1}
    checks = check_sample(
        rerun_dir / HIT_LOG, cache, per_kind, workers=2, exclude=frozenset(stored)
    )
    for c in checks:
        verdict = (
            "bit-identical"
            if c.identical
            else f"agrees (differs by up to {c.max_abs_diff:.3g})"
            if c.agrees
            else f"DIFFERS by up to {c.max_abs_diff:.3g}"
        )
        print(f"  cached {c.kind} task {c.file} ({c.rows} run(s)) recomputed cold: {verdict}")
    bad = [c for c in checks if not c.agrees]
    print(
        f"determinism: {len(checks) - len(bad)} of {len(checks)} sampled FE tasks (of the "
        f"{len(own)} the re-run read from the cache, {len(read) - len(own)} store entries left "
        f"to the store's check) recomputed cold agree with the cache "
        f"(within {AGREE_RTOL:g} of each task's largest pose component; "
        f"{sum(c.identical for c in checks)} bit-identical)"
    )
    return bool(bad) or bool(edited)
