"""Virtual experiments on an FE model: a design of loads in, stage poses out.

:func:`run_experiments` splits a design into tasks (blocks of rows for the linear model, one row
per task for the non-linear one), hands them to any :class:`concurrent.futures.Executor` — the
default runs them in-process; a dask cluster's ``client.get_executor()`` or a
``ProcessPoolExecutor`` work the same way — and caches each finished task on disk under a key
made of the model specification, the kind of analysis and the task's forces. A task that fails
is reported by experiment index, and every completed result is kept (in the cache and on the
exception). Workers build the FE model from a picklable specification
(:class:`~mechlib.campaign.spec.Spec`: the HexFlex's :class:`mechlib.hexflex.spec.ModelSpec`, a
compliant layout's :class:`mechlib.compliant.spec.MechanismSpec`) and keep it for the life of the
process, so each worker
pays the assembly and factorisation once; a task runs its BLAS on one thread wherever it runs.
"""

from __future__ import annotations

import concurrent.futures as cf
import functools
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mechlib.campaign.executors import InProcessExecutor, worker_count
from mechlib.campaign.solve import SOLVE_FIELDS as SOLVE_FIELDS
from mechlib.campaign.solve import STATE as STATE
from mechlib.campaign.solve import model_for as model_for
from mechlib.campaign.solve import release_models as release_models
from mechlib.campaign.solve import run_task
from mechlib.campaign.solve import solver_for as solver_for
from mechlib.campaign.spec import Spec
from mechlib.campaign.taskcache import (
    cache_result,
    cached_result,
    log_task,
    model_code_fingerprint,
    task_key,
)
from mechlib.fe.finite_pose import CONVENTIONS
from mechlib.params import check_choice, check_int
from mechlib.progress import Progress

#: task kinds: linear runs, non-linear runs, and the model's size (its free DOFs, one row of
#: zero forces), cached like the runs so that a build reading the cache builds no model for it
KINDS: tuple[str, ...] = ("linear", "nonlinear", "size")
#: every kind of task the FE cache, the results store and its cold checks hold: those of
#: :func:`run_experiments`, and ``STATE``, a non-linear run's converged displacement field (a
#: reduced-order model's snapshot, :func:`mechlib.hexflex.rom.snapshots.nonlinear_states`)
TASK_KINDS: tuple[str, ...] = (*KINDS, STATE)
#: Pose conventions a non-linear run returns (:mod:`mechlib.fe.finite_pose`): the
#: small-rotation fit of the stage nodes (the linear model's and the tables' pose), and the exact
#: rigid registration as a rotation vector or as intrinsic Euler XYZ angles. A linear run has
#: the first only (a linear displacement field is no finite rotation).
POSE_CONVENTIONS: tuple[str, ...] = CONVENTIONS
#: what a non-linear run reports after its poses (:class:`~mechlib.fe.nonlinear.
#: SolveStats`, summed over its load steps): corrections (back-substitutions), tangent
#: factorisations, load steps the modified method gave up on (solved again by Newton), and the
#: final ‖residual‖ / ‖load‖. A run that does not converge raises, so a stored run converged.
SOLVE_STATS: tuple[str, ...] = ("corrections", "factorisations", "restarts", "residual")
#: pose columns a run has: 6 per convention of its kind
POSE_COLUMNS = {"linear": 6, "nonlinear": 6 * len(CONVENTIONS), "size": 1}
#: columns a task returns (and the cache and the results store keep) per run: its poses, then,
#: for a non-linear run, its ``SOLVE_STATS``
RESULT_COLUMNS = {**POSE_COLUMNS, "nonlinear": POSE_COLUMNS["nonlinear"] + len(SOLVE_STATS)}
#: Rows per task for the linear model (one batched back-substitution each).
LINEAR_BLOCK = 250
KIND_NAMES = {"linear": "linear FE runs", "nonlinear": "non-linear FE runs", "size": "model sizes"}
"""What a campaign of each kind is called in its progress reports."""


class ExperimentError(RuntimeError):
    """Experiments failed.

    ``failed`` lists the run indices without a result; ``completed`` maps run index → its row
    (the columns asked for: a pose (6,), ``"all"`` (18,) or ``"stats"`` (4,)) of every finished
    run; ``reasons`` maps each failed index to its task's error message and
    ``residuals`` to the last relative residual of a non-linear run that did not converge
    (``nan`` when the error carries none).
    """

    def __init__(
        self,
        message: str,
        failed: list[int],
        completed: dict[int, np.ndarray],
        reasons: dict[int, str] | None = None,
        residuals: dict[int, float] | None = None,
    ):
        super().__init__(message)
        self.failed = failed
        self.completed = completed
        self.reasons = reasons or {}
        self.residuals = residuals or {}


@dataclass(frozen=True)
class FailedRun:
    """One experiment without a result: its index in the design, forces [N], the last relative
    residual of the non-linear solve (``nan`` if unknown) and the error message."""

    index: int
    forces: tuple[float, ...]
    residual: float
    reason: str


def _task(spec: Spec, kind: str, forces: np.ndarray, steps: int) -> np.ndarray:
    return run_task(spec, kind, forces, steps)


class CodeMismatchError(RuntimeError):
    """A worker's FE code is not the code whose fingerprint the task's key holds."""


def same_code_task(
    fingerprint: str, spec: Spec, kind: str, forces: np.ndarray, steps: int
) -> np.ndarray:
    """:func:`task_poses`, refused where the worker's FE code (its fingerprint, computed once per
    process from the sources it finds) is not ``fingerprint``, the one the task's key was made
    with: a result is cached under a key that names the code that computed it. What every
    campaign submits to its executor (the runs here, the ROM's snapshot fields)."""
    here = model_code_fingerprint(spec.TASK_MODULES)
    if here != fingerprint:
        raise CodeMismatchError(
            f"the worker's FE code (fingerprint {here}) is not the submitting process's "
            f"({fingerprint}): run the same commit on every worker"
        )
    return _task(spec, kind, forces, steps)


def task_poses(spec: Spec, kind: str, forces: np.ndarray, steps: int) -> np.ndarray:
    """What one task of ``kind`` (:data:`TASK_KINDS`) computes and caches, computed now: per row
    of ``forces``, ``RESULT_COLUMNS[kind]`` columns (the poses; a non-linear run's
    ``SOLVE_STATS`` after them), or for a ``STATE`` task the converged displacement field
    (n_dofs columns) [mm] — what a cache miss runs, and what a cold check compares with a cached
    result."""
    return _task(spec, kind, np.asarray(forces, dtype=float), steps)


def _task_key(spec: Spec, kind: str, forces: np.ndarray, steps: int) -> str:
    return task_key(spec.key(), kind, forces, steps, model_code_fingerprint(spec.TASK_MODULES))


def run_experiments(
    spec: Spec,
    design: object,
    *,
    kind: str = "linear",
    steps: int = 1,
    executor: cf.Executor | None = None,
    cache_dir: Path | None = None,
    progress: bool = True,
    pose: str = "small",
) -> np.ndarray:
    """Stage poses (n, 6) [µm, µrad] of the experiments of a force design (n, 6) [N] (or, as
    ``pose`` says, the three conventions side by side or what each non-linear solve spent; for
    ``kind="size"``, (n, 1) the model's DOF count, see :func:`model_size`).

    Parameters
    ----------
    spec : Spec
        The FE model (:class:`mechlib.campaign.spec.Spec`: the HexFlex's ``ModelSpec``, or a
        compliant layout's ``MechanismSpec``).
    design : array_like (n, spec.n_loads)
        Loads per run (the HexFlex's: actuator forces T1D1 … T3D2 within ±``MAX_FORCE_N`` N; a
        layout's: one column per load port, in the ports' units), as ``spec.check_design``
        accepts them.
    kind : {"linear", "nonlinear", "size"}
        Linear statics (batched back-substitutions), the geometrically non-linear solve, or
        (:func:`model_size`) the model's number of free DOFs in one column.
    steps : int
        Load steps of the non-linear solve (1–100).
    executor : concurrent.futures.Executor, optional
        Where tasks run; default in-process.
    cache_dir : Path, optional
        Folder of cached task results; ``None`` disables caching.
    progress : bool
        Show a tqdm progress bar over the tasks to compute on standard error. Whatever it
        says, the campaign reports its progress and time estimate to ``$MECHLIB_PROGRESS``
        when that is set (:mod:`~mechlib.progress`: the build's terminal).
    pose : {"small", "rotvec", "euler_xyz", "all", "stats"}
        The pose convention (``POSE_CONVENTIONS``): the small-rotation fit (default; the only
        one of a linear run) or, for a non-linear run, the exact rigid registration of the stage
        nodes as translation + rotation vector or as intrinsic Euler XYZ angles; ``"all"``: the
        three side by side, (n, 18) in that order; ``"stats"``: not a pose but what each
        non-linear solve spent, (n, 4) as ``SOLVE_STATS``. A non-linear run computes all of
        them (one cache entry): asking for another costs no solve.

    Raises
    ------
    ExperimentError
        When tasks fail: names the failed runs, and carries every completed pose.
    """
    d = spec.check_design(design)
    kind = check_choice("kind", kind, KINDS)
    allowed = (*POSE_CONVENTIONS, "all", "stats") if kind == "nonlinear" else ("small",)
    pose = check_choice("pose", pose, allowed)
    width, n_poses = RESULT_COLUMNS[kind], POSE_COLUMNS[kind]
    cols = {"all": slice(0, n_poses), "stats": slice(n_poses, width)}.get(
        pose, slice(6 * allowed.index(pose), 6 * allowed.index(pose) + min(6, width))
    )
    steps = check_int("steps", steps, low=1, high=100)
    block = LINEAR_BLOCK if kind == "linear" else 1
    chunks = [np.arange(i, min(i + block, len(d))) for i in range(0, len(d), block)]
    out = np.full((len(d), width), np.nan)
    done = np.zeros(len(d), dtype=bool)
    if cache_dir is not None:
        cache_dir = Path(cache_dir)
        cache_dir.mkdir(parents=True, exist_ok=True)
    pool = executor if executor is not None else InProcessExecutor()
    todo = []  # the chunks to compute (the cached ones are read first: the meter counts them)
    for rows in chunks:
        path = cache_dir / f"{_task_key(spec, kind, d[rows], steps)}.npy" if cache_dir else None
        cached = cached_result(path, len(rows), width) if path is not None else None
        if cached is not None:
            out[rows], done[rows] = cached, True
            log_task(path, spec.key(), kind, d[rows], steps, hit=True)
        else:
            todo.append((rows, path))
    desc, n_cached = f"{KIND_NAMES[kind]} ({spec.mesh} mesh)", len(chunks) - len(todo)
    meter = Progress(desc, kind, spec.digest(), len(chunks), n_cached, worker_count(pool),
                     cache_dir, bar=progress)  # fmt: skip
    pending: dict[cf.Future, np.ndarray] = {}
    code = model_code_fingerprint(spec.TASK_MODULES)
    for rows, path in todo:
        fut = pool.submit(same_code_task, code, spec, kind, d[rows], steps)
        if path is not None:  # cached as soon as it is done: an interrupted run keeps it
            fut.add_done_callback(functools.partial(cache_result, path, len(rows)))
            log_task(path, spec.key(), kind, d[rows], steps, hit=False)
        fut.add_done_callback(lambda _: meter.update())  # live, also in-process
        pending[fut] = rows
    failed: list[tuple[int, Exception]] = []
    pending_rows = {int(rows[0]): rows for rows in pending.values()}
    for fut in cf.as_completed(pending):
        rows = pending[fut]
        try:
            res = np.asarray(fut.result(), dtype=float).reshape(len(rows), width)
        except Exception as err:  # reported below with the run index
            failed.append((int(rows[0]), err))
        else:
            out[rows], done[rows] = res, True
            if cache_dir is not None:  # the callback may not have run yet (pool threads)
                cache_result(
                    cache_dir / f"{_task_key(spec, kind, d[rows], steps)}.npy", len(rows), fut
                )
    meter.close(done=len(pending), failed=len(failed))  # late callbacks count for nothing
    if failed:
        failed.sort(key=lambda p: p[0])
        first, err = failed[0]
        lost = [int(i) for i in np.flatnonzero(~done)]
        reasons: dict[int, str] = {}
        residuals: dict[int, float] = {}
        for start, error in failed:
            rows = pending_rows[start]
            for i in rows:
                reasons[int(i)] = str(error)
                residuals[int(i)] = float(getattr(error, "residual", np.nan))
        raise ExperimentError(
            f"{len(lost)} of {len(d)} experiments failed (first: run {first}, forces "
            f"{d[first].tolist()} N: {err}); {int(done.sum())} completed results are kept",
            failed=lost,
            completed={int(i): out[i, cols].copy() for i in np.flatnonzero(done)},
            reasons=reasons,
            residuals=residuals,
        )
    return out[:, cols].copy()


def model_size(spec: Spec, cache_dir: Path | None = None) -> int:
    """Free DOFs (after clamping the ground) of ``spec``'s model, read from ``cache_dir`` when a
    build counted them before (a ``"size"`` task of :func:`run_experiments`, one row of zero
    forces); ``cache_dir=None``: no cache, the model is built."""
    zeros = np.zeros((1, spec.n_loads))
    return int(run_experiments(spec, zeros, kind="size", cache_dir=cache_dir, progress=False)[0, 0])


def run_keeping_failures(
    spec: Spec, design: object, **kwargs
) -> tuple[np.ndarray, np.ndarray, list[FailedRun]]:
    """:func:`run_experiments` for statistics that must leave failed runs out, and say so.

    Parameters
    ----------
    spec, design, **kwargs
        As for :func:`run_experiments`.

    Returns
    -------
    index : ndarray (m,) of int
        Rows of ``design`` that have a result, increasing.
    poses : ndarray (m, k)
        Their rows: poses (6 or, with ``pose="all"``, 18) [µm, µrad], or with ``pose="stats"``
        the solve statistics (4).
    failures : list of FailedRun
        The other rows, by index, with their forces, last residual and error.
    """
    d = spec.check_design(design)
    try:
        return np.arange(len(d)), run_experiments(spec, d, **kwargs), []
    except ExperimentError as err:
        index = np.array(sorted(err.completed), dtype=int)
        n_cols = {"all": POSE_COLUMNS["nonlinear"], "stats": len(SOLVE_STATS)}.get(
            kwargs.get("pose"), 6
        )
        poses = np.array([err.completed[i] for i in index], dtype=float).reshape(-1, n_cols)
        failures = [
            FailedRun(i, tuple(d[i].tolist()), err.residuals.get(i, np.nan), err.reasons.get(i, ""))
            for i in err.failed
        ]
        return index, poses, failures
