"""How far the linear HexFlex model holds: linear against non-linear poses along a load ray.

:func:`linearity_sweep` solves one force direction at several amplitudes with both models;
:func:`linear_range` reads off, per pose component, how fast the linear model's error grows with
the load and where it passes a budget; :func:`crossing_labels` words those crossings for a table.
"""

from __future__ import annotations

import numpy as np

from mechlib.hexflex.fe.model import MAX_FORCE_N
from mechlib.hexflex.fe.nonlinear import NonlinearSolver
from mechlib.params import check_increasing, check_int, check_matrix

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
    model = solver.model
    lin = model.poses(amps[:, None] * d)
    nonlin, iters = np.zeros_like(lin), np.zeros(len(amps), dtype=int)
    facts = np.zeros(len(amps), dtype=int)
    for i, a in enumerate(amps):
        nonlin[i], stats = solver.pose(a * d, steps=max(1, int(np.ceil(steps * a))))
        iters[i], facts[i] = sum(stats.iterations), sum(stats.factorisations)
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
