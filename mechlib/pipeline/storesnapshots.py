"""``python -m mechlib.pipeline store add-snapshots``: the reduced-order model's snapshot fields of
the default build, added to the results store without regenerating its runs.

The meta-model page (``notebooks/nonlinear_metamodels.ipynb``) builds its reduced-order model
from the converged displacement fields of the 42 runs of Tables 2 and 4 (its ``design_runs``:
:func:`snapshot_runs`) on its non-linear model: with its default
``nonlinear_mesh="lean"``, the lean stand-in (:func:`~mechlib.hexflex.studies.leanmesh.lean_spec`)
of the model page's model, whose geometry and mesh fraction the build passes it from that
chapter's record (:data:`~mechlib.pipeline.chapters.CHAPTER_INPUTS`). :func:`add_snapshots` builds
the same specification from the same record, reads each field from the build's FE cache or
solves it (:func:`~mechlib.hexflex.rom.snapshots.nonlinear_states`, which caches it), and adds
the 42 ``STATE`` tasks to the store (:func:`~mechlib.campaign.store.add_states`): its
runs kept byte for byte, the manifest's counts, checksum and ``snapshots`` provenance (commit,
date, seconds, how many were solved and how many read) updated — from a committed work tree
only, as ``make store``.
"""

from __future__ import annotations

import datetime as dt
import platform
import time
from pathlib import Path

import numpy as np

from mechlib import published as pub
from mechlib.campaign import store
from mechlib.campaign.executors import executor
from mechlib.campaign.experiments import STATE, release_models
from mechlib.campaign.taskcache import cache_file
from mechlib.hexflex.geometry import HexFlexGeometry
from mechlib.hexflex.rom.snapshots import STATE_STEPS, nonlinear_states, state_key
from mechlib.hexflex.spec import ModelSpec
from mechlib.hexflex.studies.leanmesh import lean_spec
from mechlib.pipeline.execute import chapter_inputs
from mechlib.pipeline.provenance import cpu_model

#: the chapter whose reduced-order model the snapshots train
CHAPTER = "nonlinear_metamodels"
#: what the manifest's ``snapshots`` field says they are
ABOUT = (
    "the converged fields of the 12 + 30 runs of Tables 2 and 4 on the meta-model page's lean "
    "non-linear model: the snapshots of its reduced-order model"
)


def snapshot_runs() -> np.ndarray:
    """The meta-model page's snapshot runs (its ``design_runs``): the 12 runs of Table 2 and the
    30 of Table 4, in that order, (42, 6) [N]."""
    return np.vstack([pub.TABLE2_DESIGN, pub.TABLE4_DESIGN])


def default_spec(records: Path, cache: Path | None) -> ModelSpec:
    """The non-linear model of the meta-model page with its default parameters: the lean
    stand-in of the model page's model, from that chapter's record in ``records``.

    Parameters
    ----------
    records : Path
        The build's records folder (``build/records``).
    cache : Path, optional
        The FE cache the lean fit reads its compliances from (computed when absent).

    Raises
    ------
    FileNotFoundError
        When the model page has no record (build it first: ``make notebooks``).
    """
    inputs = chapter_inputs(CHAPTER, Path(records))
    g = HexFlexGeometry.from_dict(inputs["geometry"])
    spec = ModelSpec(g, mesh_size=float(inputs["mesh_fraction"]) * g.narrowest)
    stand_in = lean_spec(spec, cache_dir=cache)[0]
    release_models()  # the model page's linear model, used for the fit only
    return stand_in


def snapshot_entries(
    spec: ModelSpec, design: np.ndarray, cache: Path, workers: int = 1
) -> tuple[list[store.Entry], int]:
    """The ``STATE`` tasks of ``design`` on ``spec`` as store entries, each field read from the
    FE cache ``cache`` or solved (and cached); and how many were read.

    Parameters
    ----------
    spec : ModelSpec
        The model.
    design : ndarray (runs, 6)
        Actuator forces [N].
    cache : Path
        The build's FE cache.
    workers : int
        Processes solving the missing fields (1: this process).
    """
    files = [Path(cache) / cache_file(state_key(spec, f), STATE) for f in design]
    read = sum(f.is_file() for f in files)
    with executor(workers) as pool:
        fields = nonlinear_states(spec, design, executor=pool, cache_dir=cache)
    entries = [
        store.Entry(state_key(spec, f), spec.key(), STATE, STATE_STEPS, f[None, :].copy(), u[None])
        for f, u in zip(design, fields, strict=True)
    ]
    return entries, read


def add_snapshots(
    folder: Path, records: Path, cache: Path, head: str, workers: int = 1
) -> tuple[dict, int]:
    """Add the meta-model page's snapshot tasks to the store ``folder`` (see the module's
    docstring); the new manifest and how many fields were solved.

    Parameters
    ----------
    folder : Path
        The results store, computed by the current FE code.
    records : Path
        The build's records (the model page's gives the model).
    cache : Path
        The build's FE cache (seeded from the store).
    head : str
        The committed work tree's commit.
    workers : int
        Processes solving the missing fields.

    Raises
    ------
    StoreError
        A store that cannot be read as it is, or of other FE code.
    """
    manifest = store.read_manifest(folder)
    if manifest["fingerprints"] != store.fingerprints():  # refused before any solve
        raise store.StoreError(
            f"{folder} was computed by other FE code (fingerprints {manifest['fingerprints']}, "
            f"the current code's {store.fingerprints()}): regenerate it with `{store.REGENERATE}`"
        )
    start = time.perf_counter()
    entries, read = snapshot_entries(default_spec(records, cache), snapshot_runs(), cache, workers)
    provenance = {
        "about": ABOUT,
        "commit": head,
        "date": dt.datetime.now(dt.UTC).isoformat(timespec="seconds"),
        "processor": cpu_model(),
        "python": platform.python_version(),
        "seconds": round(time.perf_counter() - start, 1),
        "workers": workers,
        "solved": len(entries) - read,
        "read": read,
    }
    return store.add_states(folder, entries, provenance), len(entries) - read
