"""How far the linear HexFlex model holds: linear against non-linear poses along a load ray.

:func:`linearity_sweep` solves one force direction at several amplitudes with both models
(:func:`sweep_runs`: the same as cached FE experiments);
:func:`linear_range` reads off, per pose component, how fast the linear model's error grows with
the load and where it passes a budget; :func:`crossing_labels` words those crossings for a table.
"""

from __future__ import annotations

import functools
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from mechlib.fe.nonlinear import NonlinearSolver
from mechlib.hexflex.fe.model import MAX_FORCE_N
from mechlib.params import check_increasing, check_int, check_matrix

if TYPE_CHECKING:
    import concurrent.futures as cf

    from mechlib.hexflex.spec import ModelSpec

#: The linear model's error budget of the chapter's sweep [%]: where the linear model stops
#: being "accurate" (the largest pointwise error of a pose component).
ERROR_BUDGET_PCT = 1.0


def linearity_sweep(
    solver: NonlinearSolver, direction: object, amplitudes: object, steps: int = 1
) -> dict[str, np.ndarray]:
    """Non-linear against linear poses along one force direction scaled by several amplitudes.

    Parameters
    ----------
    solver : NonlinearSolver
        The non-linear solver of a Q2 model (``solver.model``: its linear and non-linear solves
        are compared on the same mesh).
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
    amps, forces, case_steps = _cases(direction, amplitudes, steps)
    model = solver.model
    lin = model.poses(forces)
    nonlin, iters = np.zeros_like(lin), np.zeros(len(amps), dtype=int)
    facts = np.zeros(len(amps), dtype=int)
    for i, (f, n) in enumerate(zip(forces, case_steps, strict=True)):
        nonlin[i], stats = solver.pose(f, steps=int(n))
        iters[i], facts[i] = sum(stats.iterations), sum(stats.factorisations)
    return _sweep(amps, lin, nonlin, iters, facts)


def sweep_runs(
    spec: ModelSpec,
    direction: object,
    amplitudes: object,
    steps: int = 1,
    *,
    executor: cf.Executor | None = None,
    cache_dir: Path | None = None,
) -> dict[str, np.ndarray]:
    """:func:`linearity_sweep` of ``spec``'s model as FE experiments: each case one non-linear
    run of :func:`mechlib.campaign.experiments.run_experiments` (cached, so a build
    seeded with stored results solves none), the linear poses from the cached compliance.

    Parameters
    ----------
    spec : ModelSpec
        The model of the non-linear runs.
    direction, amplitudes, steps
        As :func:`linearity_sweep`.
    executor : concurrent.futures.Executor, optional
        Where the runs are solved; default in-process.
    cache_dir : Path, optional
        FE cache; without one the runs go through a temporary cache (one solve a case).

    Returns
    -------
    dict
        As :func:`linearity_sweep` (the same poses, corrections and factorisations).

    Raises
    ------
    mechlib.campaign.experiments.ExperimentError
        When a case does not converge (named).
    """
    from mechlib.campaign import experiments as ex
    from mechlib.hexflex.studies.departure import linear_poses_for

    amps, forces, case_steps = _cases(direction, amplitudes, steps)
    with tempfile.TemporaryDirectory() as scratch:
        cache = Path(scratch) if cache_dir is None else Path(cache_dir)
        nonlin, spent = np.zeros_like(forces), np.zeros((len(amps), len(ex.SOLVE_STATS)))
        for n in np.unique(case_steps):
            rows = np.flatnonzero(case_steps == n)
            run = functools.partial(
                ex.run_experiments, spec, forces[rows], kind="nonlinear", steps=int(n),
                executor=executor, cache_dir=cache, progress=False,
            )  # fmt: skip
            nonlin[rows], spent[rows] = run(), run(pose="stats")  # the second: from the cache
        lin = linear_poses_for(spec, forces, cache)
    stat = {name: spent[:, k].astype(int) for k, name in enumerate(ex.SOLVE_STATS)}
    return _sweep(amps, lin, nonlin, stat["corrections"], stat["factorisations"])


def _cases(
    direction: object, amplitudes: object, steps: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Checked amplitudes (m,) [N], the forces (m, 6) [N] along ``direction`` scaled to them, and
    each case's load steps (``steps`` per N, at least one)."""
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
    case_steps = np.maximum(1, np.ceil(steps * amps)).astype(int)
    return amps, amps[:, None] * d, case_steps


def _sweep(amps, lin, nonlin, iters, facts) -> dict[str, np.ndarray]:
    return {
        "amplitude": amps,
        "linear": lin,
        "nonlinear": nonlin,
        "rel_pct": 100 * np.abs(nonlin - lin) / np.abs(nonlin),
        "iterations": iters,
        "factorisations": facts,
    }


def linear_range(
    amplitude: object, rel_pct: object, level: float = ERROR_BUDGET_PCT
) -> dict[str, np.ndarray]:
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
