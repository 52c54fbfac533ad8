"""Virtual experiments on the HexFlex model: a design of actuator forces in, stage poses out.

:func:`run_experiments` splits a design into tasks (blocks of rows for the linear model, one row
per task for the non-linear one), hands them to any :class:`concurrent.futures.Executor` — the
default runs them in-process; a dask cluster's ``client.get_executor()`` or a
``ProcessPoolExecutor`` work the same way — and caches each finished task on disk under a key
made of the model specification, the kind of analysis and the task's forces. A task that fails
is reported by experiment index, and every completed result is kept (in the cache and on the
exception).

Workers build the FE model from a picklable :class:`ModelSpec` and keep it for the life of the
process, so each worker pays the assembly and factorisation once.
"""

from __future__ import annotations

import concurrent.futures as cf
import hashlib
import json
from dataclasses import asdict, dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from mechlib.hexflex.geometry import HexFlexGeometry
from mechlib.hexflex.model import (
    AL7075_POISSON,
    AL7075_YOUNG_MPA,
    MAX_FORCE_N,
    HexFlexModel,
    check_forces,
)
from mechlib.params import check_choice, check_increasing, check_int, check_matrix

KINDS: tuple[str, ...] = ("linear", "nonlinear")
#: Rows per task for the linear model (one batched back-substitution each).
LINEAR_BLOCK = 250
_CACHE_VERSION = 1
#: Modules whose source enters the cache key (see :func:`model_code_fingerprint`).
_MODEL_SOURCES: tuple[str, ...] = (
    "geometry.py",
    "mesh.py",
    "problem.py",
    "model.py",
    "nonlinear.py",
    "pose.py",
)


@dataclass(frozen=True)
class ModelSpec:
    """Everything that defines an FE model (picklable, hashable, JSON-serialisable)."""

    geometry: HexFlexGeometry
    young: float = AL7075_YOUNG_MPA
    poisson: float = AL7075_POISSON
    mesh_size: float | None = None
    element: str = "q2"

    def key(self) -> str:
        """Stable text of the specification (cache key ingredient)."""
        d = asdict(self)
        return json.dumps(d, sort_keys=True)

    def build(self) -> HexFlexModel:
        """A fresh model (assembly and factorisation)."""
        return HexFlexModel(
            self.geometry,
            young=self.young,
            poisson=self.poisson,
            mesh_size=self.mesh_size,
            element=self.element,
        )


@lru_cache(maxsize=4)
def model_for(spec: ModelSpec) -> HexFlexModel:
    """The model of ``spec``, built once per process."""
    return spec.build()


def _limit_blas(threads: int) -> None:
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=threads, user_api="blas")  # for the life of the worker


def worker_pool(workers: int) -> cf.ProcessPoolExecutor:
    """A process pool for FE experiments whose workers share the cores' BLAS threads.

    Each worker's BLAS (SuperLU's factorisations run through it) gets ``cores // workers``
    threads, at least one, instead of every core: ``workers`` processes that each start a
    thread per core oversubscribe the machine.

    Parameters
    ----------
    workers : int
        Worker processes, 1 .. 64.
    """
    import os

    workers = check_int("workers", workers, low=1, high=64)
    threads = max(1, (os.cpu_count() or 1) // workers)
    return cf.ProcessPoolExecutor(max_workers=workers, initializer=_limit_blas, initargs=(threads,))


class InProcessExecutor(cf.Executor):
    """Runs each submitted call at once in the calling thread (the default executor)."""

    def submit(self, fn, /, *args, **kwargs):
        """Call ``fn(*args, **kwargs)`` now; its result or ``Exception`` goes into the future.

        ``KeyboardInterrupt``, ``SystemExit`` and the other ``BaseException`` subclasses that are
        not an ``Exception`` are not caught: they propagate at once, so Ctrl-C stops the whole
        run instead of failing one task and going on with the next.
        """
        fut: cf.Future = cf.Future()
        try:
            result = fn(*args, **kwargs)
        except Exception as err:  # reported through the future, as any executor does
            fut.set_exception(err)
        else:
            fut.set_result(result)
        return fut


class ExperimentError(RuntimeError):
    """Experiments failed.

    ``failed`` lists the run indices without a result; ``completed`` maps run index → pose (6,)
    of every finished run; ``reasons`` maps each failed index to its task's error message and
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


def _task(spec: ModelSpec, kind: str, forces: np.ndarray, steps: int) -> np.ndarray:
    model = model_for(spec)
    if kind == "linear":
        return model.poses(forces)
    return np.array([model.poses_nonlinear(f, steps=steps)[0] for f in forces])


@lru_cache(maxsize=1)
def model_code_fingerprint() -> str:
    """Digest of the sources that define a model's results (geometry, mesh, FE model, pose fit).

    Part of every cache key, so that a change to the mesher or the solver can never return
    results computed by the old code.
    """
    h = hashlib.sha256()
    for name in _MODEL_SOURCES:
        h.update((Path(__file__).parent / name).read_bytes())
    return h.hexdigest()[:16]


def _task_key(spec: ModelSpec, kind: str, forces: np.ndarray, steps: int) -> str:
    h = hashlib.sha256()
    h.update(f"{_CACHE_VERSION}|{model_code_fingerprint()}|{spec.key()}|{kind}|{steps}|".encode())
    h.update(np.ascontiguousarray(forces, dtype=np.float64).tobytes())
    return h.hexdigest()[:32]


def check_forces_design(design: object) -> np.ndarray:
    """A design of actuator forces: (n, 6) finite values within ±``MAX_FORCE_N`` N."""
    d = np.asarray(design, dtype=float)
    if d.ndim != 2 or d.shape[1] != 6:
        raise ValueError(
            f"design must have 6 factor columns (T1D1 … T3D2) and one row per run, got shape "
            f"{d.shape}"
        )
    return check_forces("design [N]", d)


def run_experiments(
    spec: ModelSpec,
    design: object,
    *,
    kind: str = "linear",
    steps: int = 1,
    executor: cf.Executor | None = None,
    cache_dir: Path | None = None,
    progress: bool = True,
) -> np.ndarray:
    """Stage poses (n, 6) [µm, µrad] of the experiments of a force design (n, 6) [N].

    Parameters
    ----------
    spec : ModelSpec
        The FE model.
    design : array_like (n, 6)
        Actuator forces per run, columns T1D1 … T3D2, within ±``MAX_FORCE_N``.
    kind : {"linear", "nonlinear"}
        Linear statics (batched back-substitutions) or the geometrically non-linear solve.
    steps : int
        Load steps of the non-linear solve (1–100).
    executor : concurrent.futures.Executor, optional
        Where tasks run; default in-process.
    cache_dir : Path, optional
        Folder of cached task results; ``None`` disables caching.
    progress : bool
        Show a tqdm progress bar over tasks.

    Raises
    ------
    ExperimentError
        When tasks fail: names the failed runs, and carries every completed pose.
    """
    d = check_forces_design(design)
    kind = check_choice("kind", kind, KINDS)
    steps = check_int("steps", steps, low=1, high=100)
    block = LINEAR_BLOCK if kind == "linear" else 1
    chunks = [np.arange(i, min(i + block, len(d))) for i in range(0, len(d), block)]
    out = np.full((len(d), 6), np.nan)
    done = np.zeros(len(d), dtype=bool)
    if cache_dir is not None:
        cache_dir = Path(cache_dir)
        cache_dir.mkdir(parents=True, exist_ok=True)
    pending: dict[cf.Future, np.ndarray] = {}
    pool = executor if executor is not None else InProcessExecutor()
    for rows in chunks:
        path = cache_dir / f"{_task_key(spec, kind, d[rows], steps)}.npy" if cache_dir else None
        if path is not None and path.exists():
            out[rows], done[rows] = np.load(path), True
            continue
        pending[pool.submit(_task, spec, kind, d[rows], steps)] = rows
    failed: list[tuple[int, Exception]] = []
    bar = None
    if progress and pending:
        from tqdm.auto import tqdm

        bar = tqdm(total=len(pending), desc=f"{kind} FE experiments", unit="task")
    pending_rows = {int(rows[0]): rows for rows in pending.values()}
    for fut in cf.as_completed(pending):
        rows = pending[fut]
        try:
            res = np.asarray(fut.result(), dtype=float).reshape(len(rows), 6)
        except Exception as err:  # reported below with the run index
            failed.append((int(rows[0]), err))
        else:
            out[rows], done[rows] = res, True
            if cache_dir is not None:
                np.save(cache_dir / f"{_task_key(spec, kind, d[rows], steps)}.npy", res)
        if bar is not None:
            bar.update()
    if bar is not None:
        bar.close()
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
            completed={int(i): out[i].copy() for i in np.flatnonzero(done)},
            reasons=reasons,
            residuals=residuals,
        )
    return out


def run_keeping_failures(
    spec: ModelSpec, design: object, **kwargs
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
    poses : ndarray (m, 6)
        Their poses [µm, µrad].
    failures : list of FailedRun
        The other rows, by index, with their forces, last residual and error.
    """
    d = check_forces_design(design)
    try:
        return np.arange(len(d)), run_experiments(spec, d, **kwargs), []
    except ExperimentError as err:
        index = np.array(sorted(err.completed), dtype=int)
        poses = np.array([err.completed[i] for i in index], dtype=float).reshape(-1, 6)
        failures = [
            FailedRun(i, tuple(d[i].tolist()), err.residuals.get(i, np.nan), err.reasons.get(i, ""))
            for i in err.failed
        ]
        return index, poses, failures


def linearity_sweep(
    model: HexFlexModel, direction: object, amplitudes: object, steps: int = 1
) -> dict[str, np.ndarray]:
    """Non-linear against linear poses along one force direction scaled by several amplitudes.

    Parameters
    ----------
    model : HexFlexModel
        A Q2 model (its linear and non-linear solves are compared on the same mesh).
    direction : array_like (6,)
        Force direction; scaled so that its largest |component| is 1 N.
    amplitudes : array_like
        Largest actuator force of each case [N], in (0, ``MAX_FORCE_N``].
    steps : int
        Load steps per N of amplitude (at least one step per case).

    Returns
    -------
    dict
        ``amplitude`` (m,), ``linear`` and ``nonlinear`` poses (m, 6), ``rel_pct`` (m, 6) the
        pointwise relative error 100 |ψ_nl − ψ_lin| / |ψ_nl| of the linear model per component,
        ``iterations`` (m,) the corrections (back-substitutions) and ``factorisations`` (m,) the
        tangent factorisations spent.
    """
    d = check_matrix("direction", np.atleast_2d(np.asarray(direction, dtype=float)), shape=(1, 6))[
        0
    ]
    if not np.abs(d).max() > 0:
        raise ValueError("direction must have a non-zero component")
    d = d / np.abs(d).max()
    amps = np.atleast_1d(np.asarray(amplitudes, dtype=float))
    if amps.ndim != 1 or amps.size == 0 or np.any(~(amps > 0)) or np.any(amps > MAX_FORCE_N):
        raise ValueError(f"amplitudes must lie in (0, {MAX_FORCE_N:g}] N, got {amps.tolist()}")
    steps = check_int("steps", steps, low=1, high=100)
    lin = model.poses(amps[:, None] * d)
    nonlin, iters = np.zeros_like(lin), np.zeros(len(amps), dtype=int)
    facts = np.zeros(len(amps), dtype=int)
    for i, a in enumerate(amps):
        nonlin[i], stats = model.poses_nonlinear(a * d, steps=max(1, int(np.ceil(steps * a))))
        iters[i], facts[i] = sum(stats.iterations), sum(stats.factorisations)
    return {
        "amplitude": amps,
        "linear": lin,
        "nonlinear": nonlin,
        "rel_pct": 100 * np.abs(nonlin - lin) / np.abs(nonlin),
        "iterations": iters,
        "factorisations": facts,
    }


def linear_range(amplitude: object, rel_pct: object, level: float = 1.0) -> dict[str, np.ndarray]:
    """Where the linear model's error passes a budget, and how fast it grows, per component.

    Between two consecutive amplitudes the error of each component is taken to follow a power
    law, err ∝ amplitude**p; ``p`` is measured from the two points, and the amplitude at which
    the error reaches ``level`` is interpolated on that power law.

    Parameters
    ----------
    amplitude : array_like (m,)
        Strictly increasing load amplitudes [N], m ≥ 2 (``linearity_sweep``'s ``amplitude``).
    rel_pct : array_like (m, k)
        Positive, finite relative errors [%] of k components at each amplitude
        (``linearity_sweep``'s ``rel_pct``).
    level : float
        Error budget [%], > 0.

    Returns
    -------
    dict
        ``exponent`` (m−1, k): p between amplitudes i and i+1 (1: error proportional to the
        load). ``crossing`` (k,): the amplitude [N] at which the error first reaches ``level``,
        interpolated between the bracketing amplitudes; ``inf`` if it stays below ``level`` at
        every amplitude, and ``amplitude[0]`` if it is already at or above it there (then
        ``below_sweep`` is True: the crossing lies at or below the smallest amplitude).
    """
    a = check_increasing("amplitude [N]", amplitude, low=0.0, low_open=True)
    e = check_matrix("rel_pct", rel_pct, shape=(a.size, None))
    if np.any(e <= 0):
        raise ValueError("rel_pct must be > 0 everywhere (a power law needs a positive error)")
    if not (np.isfinite(level) and level > 0):
        raise ValueError(f"level must be a finite error budget > 0 %, got {level}")
    log_a, log_e = np.log(a), np.log(e)
    exponent = np.diff(log_e, axis=0) / np.diff(log_a)[:, None]
    crossing = np.full(e.shape[1], np.inf)
    below = e[0] >= level
    crossing[below] = a[0]
    for j in np.flatnonzero(~below):
        over = np.flatnonzero(e[:, j] >= level)
        if over.size:
            i = over[0]  # e[i-1, j] < level <= e[i, j]
            step = (np.log(level) - log_e[i - 1, j]) / exponent[i - 1, j]
            crossing[j] = np.exp(log_a[i - 1] + step)
    return {"exponent": exponent, "crossing": crossing, "below_sweep": below}


def crossing_labels(lin_range: dict[str, np.ndarray], amplitude: object) -> list[str]:
    """Table labels of :func:`linear_range`'s crossings: ``"> a_max"`` where a component stays
    below the budget over the sweep, ``"≤ a_min"`` where it is already above it at the smallest
    amplitude, else the interpolated amplitude [N] to two significant digits."""
    a = check_increasing("amplitude [N]", amplitude, low=0.0, low_open=True)
    labels = []
    for cross, below in zip(lin_range["crossing"], lin_range["below_sweep"], strict=True):
        if np.isinf(cross):
            labels.append(f"> {a[-1]:g}")
        else:
            labels.append(f"≤ {cross:g}" if below else f"{cross:.2g}")
    return labels
