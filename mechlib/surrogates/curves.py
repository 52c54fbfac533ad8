"""Space-filling training designs, learning curves, and the force range within an error budget."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy.stats import qmc

from mechlib.params import check_choice, check_float, check_int, check_matrix
from mechlib.surrogates.families import (
    FAMILIES,
    RANGE_RTOL,
    Surrogate,
    fit_surrogate,
    n_terms,
)
from mechlib.surrogates.scoring import score

N_FORCES = 6
"""Forces of the HexFlex (T1D1 … T3D2, Eq 7)."""
LHS_OPTIMIZATION = "random-cd"
"""scipy's LHS optimisation: random permutations that lower the centred discrepancy."""
ERROR_BUDGET_PCT = 1.0
"""Default error budget [%] of :func:`range_within_budget`: max |error| / range per component."""
MAX_DESIGN_RUNS = 100_000
"""Largest design :func:`space_filling_design` builds."""


def space_filling_design(
    n_runs: int, amplitude: float, seed: int, *, n_forces: int = N_FORCES
) -> dict[str, object]:
    """Latin hypercube of forces in ±amplitude N, optimised on the centred discrepancy.

    ``scipy.stats.qmc.LatinHypercube(d=n_forces, optimization="random-cd", seed=seed)`` in the
    unit cube, mapped to ``amplitude · (2u − 1)``.

    Parameters
    ----------
    n_runs : int
        Runs, 2 to ``MAX_DESIGN_RUNS``.
    amplitude : float
        Half-width of the force range [N], > 0.
    seed : int
        Seed of the design.
    n_forces : int
        Number of forces (columns).

    Returns
    -------
    dict
        ``forces`` (n_runs, n_forces) [N]; ``cd2`` the squared centred L2 discrepancy of the
        unit-cube points (``qmc.discrepancy(method="CD")`` returns the square, as
        :func:`mechlib.doe.centered_l2_discrepancy_squared`); ``amplitude``.
    """
    n_runs = check_int("n_runs", n_runs, low=2, high=MAX_DESIGN_RUNS)
    amplitude = check_float("amplitude", amplitude, low=0.0, low_open=True)
    seed = check_int("seed", seed, low=0)
    n_forces = check_int("n_forces", n_forces, low=1)
    u = qmc.LatinHypercube(d=n_forces, optimization=LHS_OPTIMIZATION, seed=seed).random(n_runs)
    return {
        "forces": amplitude * (2 * u - 1),
        "cd2": float(qmc.discrepancy(u, method="CD")),
        "amplitude": amplitude,
    }


def sobol_design(
    n_runs: int, amplitude: float, seed: int, *, n_forces: int = N_FORCES
) -> dict[str, object]:
    """Scrambled Sobol' points in ±amplitude N: nested designs (every power-of-two prefix is a
    balanced design itself, so a learning curve on prefixes stays space-filling).

    ``scipy.stats.qmc.Sobol(d=n_forces, scramble=True, seed=seed).random_base2(m)`` in the unit
    cube, mapped to ``amplitude · (2u − 1)``.

    Parameters
    ----------
    n_runs : int
        Runs, a power of two from 2 to ``MAX_DESIGN_RUNS``.
    amplitude : float
        Half-width of the force range [N], > 0.
    seed : int
        Seed of the scrambling.
    n_forces : int
        Number of forces (columns), 1 to 21201 (scipy's Sobol' dimensions).

    Returns
    -------
    dict
        ``forces`` (n_runs, n_forces) [N]; ``cd2`` the squared centred L2 discrepancy of the
        unit-cube points; ``amplitude``.
    """
    n_runs = check_int("n_runs", n_runs, low=2, high=MAX_DESIGN_RUNS)
    if n_runs & (n_runs - 1):
        raise ValueError(f"n_runs must be a power of two for a Sobol' design, got {n_runs}")
    amplitude = check_float("amplitude", amplitude, low=0.0, low_open=True)
    seed = check_int("seed", seed, low=0)
    n_forces = check_int("n_forces", n_forces, low=1, high=21201)
    u = qmc.Sobol(d=n_forces, scramble=True, seed=seed).random_base2(n_runs.bit_length() - 1)
    return {
        "forces": amplitude * (2 * u - 1),
        "cd2": float(qmc.discrepancy(u, method="CD")),
        "amplitude": amplitude,
    }


def learning_curve(
    families: Sequence[str],
    forces: object,
    poses: object,
    val_forces: object,
    val_poses: object,
    sizes: Sequence[int],
    *,
    amplitude: float,
    seed: int = 0,
) -> dict[str, object]:
    """Validation error against the number of training runs: nested subsets (the first n runs).

    Parameters
    ----------
    families : sequence of str
        Names from ``FAMILIES``.
    forces, poses : array_like, shapes (runs, inputs), (runs, outputs)
        One training design (e.g. :func:`space_filling_design`) and its poses; the first ``n``
        rows are the subset of size ``n``, so the subsets are nested.
    val_forces, val_poses : array_like
        Held-out runs, inside the validated range.
    sizes : sequence of int
        Training sizes, increasing, each at most the runs available.
    amplitude : float
        Validated range [N] of every fit (the design's half-width).
    seed : int
        Passed to :func:`fit_surrogate`.

    Returns
    -------
    dict
        ``sizes`` (m,); ``families`` list; ``max_range_pct`` and ``rmse`` (families, m,
        outputs) and ``worst_pct`` (families, m): NaN where a size is below the family's
        :func:`n_terms`.

    Raises
    ------
    ValueError
        Unknown family, a size larger than the runs available or not increasing, shapes.
    """
    x = check_matrix("forces", forces)
    y = check_matrix("poses", poses, shape=(x.shape[0], None))
    fams = [check_choice("families", f, FAMILIES) for f in families]
    n = np.array([check_int("sizes", s, low=1, high=len(x)) for s in sizes])
    if n.size == 0 or np.any(np.diff(n) <= 0):
        raise ValueError(f"sizes must be increasing, got {n.tolist()}")
    shape = (len(fams), len(n), y.shape[1])
    out = {"max_range_pct": np.full(shape, np.nan), "rmse": np.full(shape, np.nan)}
    for i, fam in enumerate(fams):
        for j, size in enumerate(n):
            if size < n_terms(fam, x.shape[1]):
                continue
            fit = fit_surrogate(fam, x[:size], y[:size], amplitude=amplitude, seed=seed)
            s = score(fit, val_forces, val_poses)
            out["max_range_pct"][i, j] = s["max_range_pct"]
            out["rmse"][i, j] = s["rmse"]
    with np.errstate(all="ignore"):
        worst = np.max(out["max_range_pct"], axis=2)
    return {"sizes": n, "families": fams, "worst_pct": worst, **out}


def range_within_budget(
    surrogate: Surrogate,
    cases: Sequence[tuple[float, object, object]],
    *,
    budget_pct: float = ERROR_BUDGET_PCT,
) -> dict[str, object]:
    """Largest force amplitude up to which a meta-model meets an error budget.

    Parameters
    ----------
    surrogate : Surrogate
    cases : sequence of (amplitude, forces, poses)
        Validation sets at several amplitudes [N] (e.g. ±0.25, ±0.5, ±1 N), each inside the
        surrogate's validated range and its forces within its own amplitude.
    budget_pct : float
        Largest allowed max |error| as % of each component's range (Table 5's convention).

    Returns
    -------
    dict
        ``amplitudes`` (m,) sorted; ``worst_pct`` (m,) the largest component error at each;
        ``meets`` (m,) bool; ``amplitude``: the largest amplitude such that it and every
        smaller one meet the budget (0.0 when the smallest does not).

    Raises
    ------
    ValueError
        An amplitude outside the validated range, forces beyond their case's amplitude, shapes.
    """
    budget_pct = check_float("budget_pct", budget_pct, low=0.0, low_open=True)
    if len(cases) == 0:
        raise ValueError("cases must hold at least one (amplitude, forces, poses) validation set")
    rows = []
    for amp, f, p in cases:
        amp = check_float("amplitude", amp, low=0.0, high=surrogate.amplitude, low_open=True)
        x = check_matrix("forces", f, shape=(None, surrogate.n_inputs))
        if np.abs(x).max() > amp * (1 + RANGE_RTOL):
            raise ValueError(
                f"forces of the ±{amp} N case must lie in [-{amp}, {amp}] N, got "
                f"{float(np.abs(x).max())} N"
            )
        rows.append((amp, score(surrogate, x, p)["worst_pct"]))
    rows.sort()
    amps = np.array([a for a, _ in rows])
    worst = np.array([w for _, w in rows])
    meets = worst <= budget_pct
    ok = np.cumprod(meets).astype(bool)
    return {
        "amplitudes": amps,
        "worst_pct": worst,
        "meets": meets,
        "amplitude": float(amps[ok][-1]) if ok.any() else 0.0,
    }
