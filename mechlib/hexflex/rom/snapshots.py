"""Converged non-linear displacement fields (snapshots) of a force design: FE tasks of their own
kind, cached, logged and stored like the campaign's runs.

A reduced-order model is built from full solutions, not poses (:mod:`mechlib.hexflex.rom.model`):
:func:`nonlinear_states` runs one ``STATE`` task per force vector
(:func:`~mechlib.campaign.experiments.same_code_task`: the model's non-linear solver, one
load step, the campaign's method) in an executor, as
:func:`~mechlib.campaign.experiments.run_experiments` does. Each field is cached under
the campaign's task key (:func:`~mechlib.campaign.taskcache.task_key`: the FE code's
fingerprint, the model specification, the kind, the steps and the forces) as
``<key>.state.npy``, each task is logged to ``$MECHLIB_FE_LOG``, so ``make store`` packs the
fields into the results store (``store/snapshots.npz``), ``store seed`` writes them back into a
build's cache and ``store check`` recomputes a sample of them cold.
"""

from __future__ import annotations

import concurrent.futures as cf
import functools
from pathlib import Path

import numpy as np

from mechlib.campaign.executors import InProcessExecutor
from mechlib.campaign.experiments import same_code_task
from mechlib.campaign.taskcache import (
    STATE,
    cache_file,
    cache_result,
    log_task,
    model_code_fingerprint,
    task_key,
)
from mechlib.hexflex.spec import ModelSpec, check_forces_design

#: load steps of a snapshot run (the solver's default: the whole load at once)
STATE_STEPS = 1


def state_key(spec: ModelSpec, forces: np.ndarray) -> str:
    """The task key of the converged field of ``spec`` under ``forces`` (6,) [N] (the campaign's
    :func:`~mechlib.campaign.taskcache.task_key` of a ``STATE`` task of one run)."""
    row = np.asarray(forces, dtype=float).reshape(1, -1)
    fingerprint = model_code_fingerprint(spec.TASK_MODULES)
    return task_key(spec.key(), STATE, row, STATE_STEPS, fingerprint)


def _cached_state(path: Path | None) -> np.ndarray | None:
    """The cached field (1, n_dofs) at ``path``, or ``None`` if absent, unreadable, of another
    shape or not finite (then it is solved again)."""
    if path is None or not path.is_file():
        return None
    try:
        field = np.load(path)
    except (OSError, ValueError, EOFError):
        return None
    return field if field.ndim == 2 and len(field) == 1 and np.all(np.isfinite(field)) else None


def nonlinear_states(
    spec: ModelSpec,
    design: object,
    *,
    executor: cf.Executor | None = None,
    cache_dir: Path | None = None,
) -> np.ndarray:
    """Converged non-linear displacement fields (runs, n_dofs) [mm] of a force design.

    Parameters
    ----------
    spec : ModelSpec
        The FE model (Q2).
    design : array_like (runs, 6)
        Actuator forces [N] within the model's force bound.
    executor : concurrent.futures.Executor, optional
        Where the solves run; default in-process.
    cache_dir : Path, optional
        Folder of the FE cache (a field is ``<key>.state.npy``, (1, n_dofs), 8 bytes a DOF; a
        results store seeds it); ``None``: no cache.

    Returns
    -------
    numpy.ndarray (runs, n_dofs)

    Raises
    ------
    mechlib.fe.nonlinear.ConvergenceError
        From the first run that does not converge (a snapshot set must be complete).
    """
    d = check_forces_design(design)
    pool = executor if executor is not None else InProcessExecutor()
    if cache_dir is not None:
        Path(cache_dir).mkdir(parents=True, exist_ok=True)
    paths = [
        Path(cache_dir) / cache_file(state_key(spec, f), STATE) if cache_dir is not None else None
        for f in d
    ]
    out: list[np.ndarray | None] = [_cached_state(p) for p in paths]
    pending: dict[cf.Future, int] = {}
    code = model_code_fingerprint(spec.TASK_MODULES)
    for i, field in enumerate(out):
        if field is not None:
            log_task(paths[i], spec.key(), STATE, d[i : i + 1], STATE_STEPS, hit=True)
            continue
        fut = pool.submit(same_code_task, code, spec, STATE, d[i : i + 1], STATE_STEPS)
        if paths[i] is not None:  # cached as soon as it is done: an interrupted run keeps it
            fut.add_done_callback(functools.partial(cache_result, paths[i], 1))
            log_task(paths[i], spec.key(), STATE, d[i : i + 1], STATE_STEPS, hit=False)
        pending[fut] = i
    for fut in cf.as_completed(pending):
        i = pending[fut]
        out[i] = np.asarray(fut.result(), dtype=float).reshape(1, -1)
        if paths[i] is not None:  # the callback may not have run yet (pool threads)
            cache_result(paths[i], 1, fut)
    return np.vstack(out)
