"""Converged non-linear displacement fields (snapshots) of a force design, cached on disk.

A reduced-order model is built from full solutions, not poses (:mod:`mechlib.hexflex.rom.model`):
:func:`nonlinear_states` solves each force vector with the model's non-linear solver (in an
executor, as :func:`mechlib.hexflex.campaign.experiments.run_experiments` does) and keeps each
field in the FE cache under a key made of the model code, the model specification and the forces.
"""

from __future__ import annotations

import concurrent.futures as cf
import hashlib
from pathlib import Path

import numpy as np

from mechlib.hexflex.campaign.executors import InProcessExecutor
from mechlib.hexflex.campaign.experiments import ModelSpec, check_forces_design, solver_for
from mechlib.hexflex.campaign.taskcache import model_code_fingerprint

#: 2: the code fingerprint digests the FE code's syntax trees (cache format 4)
_VERSION = 2


def _state(spec: ModelSpec, forces: np.ndarray) -> np.ndarray:
    return solver_for(spec).solve(forces)[0]


def state_key(spec: ModelSpec, forces: np.ndarray) -> str:
    """Cache file stem of the converged field of ``spec`` under ``forces`` (6,) [N]."""
    h = hashlib.sha256(f"state|{_VERSION}|{model_code_fingerprint()}|{spec.key()}|".encode())
    h.update(np.ascontiguousarray(forces, dtype=np.float64).tobytes())
    return h.hexdigest()[:32]


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
        Folder of cached fields (``<key>.state.npy``, 8 bytes a DOF); ``None``: no cache.

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
    paths = [
        Path(cache_dir) / f"{state_key(spec, f)}.state.npy" if cache_dir is not None else None
        for f in d
    ]
    if cache_dir is not None:
        Path(cache_dir).mkdir(parents=True, exist_ok=True)
    out: list[np.ndarray | None] = [
        np.load(p) if p is not None and p.exists() else None for p in paths
    ]
    pending = {pool.submit(_state, spec, d[i]): i for i, u in enumerate(out) if u is None}
    for fut in cf.as_completed(pending):
        i = pending[fut]
        out[i] = fut.result()
        if paths[i] is not None:
            tmp = paths[i].with_suffix(".tmp.npy")
            np.save(tmp, out[i])
            tmp.replace(paths[i])
    return np.array(out)
