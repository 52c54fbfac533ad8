"""What one FE task computes: the model and solver a worker builds from a specification, and the
rows a task of each kind returns.

This module is part of every family's FE closure (:func:`mechlib.campaign.taskcache.
model_code_fingerprint` digests it with a specification's ``TASK_MODULES``): a change to how a
task is solved — the solve method it passes, the columns it returns, which model it shares among
specifications — changes every key, so no cached or stored result of the old code is read.
The runner around it (:mod:`mechlib.campaign.experiments`: splitting, caching, executors) is
not, since it cannot change a result.
"""

from __future__ import annotations

from dataclasses import fields, replace
from functools import lru_cache
from typing import TYPE_CHECKING

import numpy as np

from mechlib.blas import one_thread
from mechlib.fe.finite_pose import CONVENTIONS, finite_poses

if TYPE_CHECKING:
    from mechlib.campaign.spec import Spec
    from mechlib.fe.nonlinear import NonlinearSolver

#: the kind of a task that keeps a run's converged displacement field, not its poses: a
#: reduced-order model's snapshot (:mod:`mechlib.hexflex.rom.snapshots`), one run a task, its
#: result (1, n_dofs) [mm]
STATE = "state"
#: a specification's fields that set only its non-linear solve, not its model: the runner shares
#: one model among specifications that differ in these alone (each at its field's default)
SOLVE_FIELDS: tuple[str, ...] = ("quad_order",)


def model_for(spec: Spec) -> object:
    """The model of ``spec``, built once per process (one model for every ``quad_order``: the
    linear model's quadrature is fixed; a :data:`SOLVE_FIELDS` field is set to its default)."""
    solve_only = {f.name: f.default for f in fields(spec) if f.name in SOLVE_FIELDS}
    return _model(replace(spec, **solve_only))


@lru_cache(maxsize=4)
def _model(spec: Spec) -> object:
    with one_thread():  # the same bits wherever it is built
        return spec.build()


@lru_cache(maxsize=4)
def solver_for(spec: Spec) -> NonlinearSolver:
    """The non-linear solver of ``spec``'s model, built once per process (on
    :func:`model_for`'s model)."""
    return spec.SOLVER(model_for(spec), quad_order=spec.quad_order)


def release_models() -> None:
    """Forget the models and solvers this process keeps (:func:`model_for`,
    :func:`solver_for`): a Q2 solver of the identified model holds gigabytes, so a study that
    goes through several models releases each before building the next."""
    import gc

    solver_for.cache_clear()
    _model.cache_clear()
    gc.collect()


def run_task(spec: Spec, kind: str, forces: np.ndarray, steps: int) -> np.ndarray:
    """The rows one task of ``kind`` returns for the rows of ``forces``, BLAS on one thread (in
    a pool, in-process or on Dask alike): a linear task's poses (n, 6); a size task's DOF count
    (n, 1); a non-linear task's poses in every convention of
    :data:`mechlib.fe.finite_pose.CONVENTIONS` and its solve statistics; a :data:`STATE`
    task's converged displacement field (n, n_dofs) [mm]."""
    with one_thread():
        return _solve(spec, kind, forces, steps)


def _solve(spec: Spec, kind: str, forces: np.ndarray, steps: int) -> np.ndarray:
    if kind == "linear":
        return model_for(spec).poses(forces)
    if kind == "size":
        return np.full((len(forces), 1), float(model_for(spec).n_dofs))
    solver = solver_for(spec)
    if kind == STATE:  # the fields themselves, (rows, n_dofs) [mm]
        return np.array([solver.solve(f, steps=steps, method=spec.SOLVE_METHOD)[0] for f in forces])
    model = solver.model
    rows = []
    for f in forces:
        u, stats = solver.solve(f, steps=steps, method=spec.SOLVE_METHOD)
        exact = finite_poses(*model.stage_motion(u))
        spent = [sum(stats.iterations), sum(stats.factorisations), stats.restarts, stats.residual]
        # the small-rotation pose as the linear model computes it (bit for bit), then the others
        rows.append(
            np.concatenate([model.pose_of(u)] + [exact[c] for c in CONVENTIONS[1:]] + [spent])
        )
    return np.array(rows)
