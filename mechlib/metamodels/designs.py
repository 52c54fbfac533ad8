"""Training designs of forces in ±amplitude: a Latin hypercube optimised on the centred
discrepancy, and nested scrambled Sobol' points."""

from __future__ import annotations

from scipy.stats import qmc

from mechlib.params import check_float, check_int

N_FORCES = 6
"""Forces of the HexFlex (T1D1 … T3D2, Eq 7)."""
LHS_OPTIMIZATION = "random-cd"
"""scipy's LHS optimisation: random permutations that lower the centred discrepancy."""
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

    Examples
    --------
    A Latin hypercube: each force falls once in each of the ``n_runs`` equal strata of ±2 N.

    >>> import numpy as np
    >>> forces = space_filling_design(8, amplitude=2.0, seed=0)["forces"]
    >>> forces.shape, bool(np.abs(forces).max() <= 2.0)
    ((8, 6), True)
    >>> strata = np.floor((forces + 2.0) / (4.0 / 8)).astype(int)
    >>> all(sorted(column) == list(range(8)) for column in strata.T.tolist())
    True
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

    Examples
    --------
    >>> sobol_design(8, amplitude=1.0, seed=0)["forces"].shape
    (8, 6)
    >>> sobol_design(12, amplitude=1.0, seed=0)
    Traceback (most recent call last):
    ...
    ValueError: n_runs must be a power of two for a Sobol' design, got 12
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
