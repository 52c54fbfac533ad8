"""Named tolerances of values from iterative solvers, fits and seeded Monte Carlo: they stop at
a tolerance, not at round-off.
"""

from __future__ import annotations

import numpy as np

from mechlib.reporting.tolerance import Tolerance

# --- iterative solvers: they stop at a tolerance, not at round-off -----------------------------

SOLVER = Tolerance(
    rtol=1e-6,
    atol=1e-6,
    why="an iterative solver (coordinate descent, cross-validated penalty) stopped at its "
    "convergence tolerance; another kernel may stop one iterate apart, well inside 1e-6",
)
SOLVER_NEAR_ZERO = Tolerance(
    atol=1e-6,
    why="a quantity an iterative solver leaves near 0 (an intercept of an exactly linear fit): "
    "bounded absolutely by the solver's tolerance",
)
SOLVER_DERIVED = Tolerance(
    rtol=1e-3,
    why="largest relative differences of fits from published numbers (2e-4 to 6.1e-3), one of "
    "them made of a penalized solver's coefficients, known to its tolerance (1e-6): that moves "
    "its 6.1e-3 by up to 1e-6, 1.6e-4 of itself, inside 1e-3; those of the least-squares fits "
    "move by round-off only",
)
ITERATIVE = Tolerance(
    rtol=1e-6,
    why="a fit or an estimate iterated to a stopping tolerance of 1e-8 or below (Gauss–Newton, "
    "Levenberg–Marquardt, a seeded Monte Carlo): another kernel stops within 1e-6 of it",
)
ITERATIVE_ABS = Tolerance(
    rtol=1e-6,
    atol=1e-12,
    why="as ITERATIVE, for arrays with entries near 0: an absolute floor of 1e-12",
)
MONTE_CARLO_RATIO = Tolerance(
    rtol=2e-6,
    why="a ratio of two seeded Monte Carlo RMS errors of iterated fits: measured 1e-7 of itself "
    "apart under another machine's BLAS kernel and SIMD paths; 2e-6 leaves a factor 20",
)
SHARE_OF_TRIALS = Tolerance(
    atol=1e-12,
    why="a share of paired Monte Carlo trials (a count over the number of trials): one "
    "division, the same on every machine while no trial's comparison flips; 1e-12 absolute "
    "allows the division's round-off only",
)
CONDITIONING = Tolerance(
    rtol=1e-6,
    why="an inverse condition number from an SVD (smallest over largest singular value, columns "
    "scaled) of a fixed set of poses: its relative round-off, ~1e-16 over the value, stays "
    "inside 1e-6 for any value above 1e-9",
)

BISECTION = Tolerance(
    atol=1e-6,
    why="a bisection and a golden-section search stopped at intervals of 1e-5 (the numeric MIW, "
    "in m): their steps are comparisons of round-off-exact kinematics, so a re-run repeats every "
    "one and returns the same numbers; a comparison that flipped would move the result by 3.8e-6 "
    "or more (a golden-section step; 5e-6, a bisection step), beyond 1e-6, and be reported",
)
SOLVERS_AGREE = Tolerance(
    atol=1e-8,
    why="the largest difference between two solvers' solutions of one least-squares problem "
    "(Gauss–Newton stopped at 1e-12 steps, Levenberg–Marquardt at 1e-14 tolerances): "
    "round-off-level, bounded absolutely at 1e-8, far below the measurement noise",
)
IDENTIFIED = Tolerance(
    atol=1e-9,
    why="parameters identified by Gauss–Newton iterations stopped at 1e-12 steps (m, rad, "
    "gain): another kernel stops at the same solution to far below 1e-9, and far below the "
    "noise of the measurements they are fitted to",
)


def grid_share(points: int) -> Tolerance:
    """The tolerance of a share of a deterministic ``points`` × ``points`` grid (a region's
    area share): only points within round-off of a boundary can flip, ``1 / points²`` each;
    ten of them are allowed.

    Raises
    ------
    ValueError
        ``points`` not an integer ≥ 1.
    """
    if isinstance(points, bool) or not isinstance(points, (int, np.integer)) or points < 1:
        raise ValueError(f"grid_share: points must be an integer >= 1, got {points!r}")
    return Tolerance(
        atol=10 / points**2,
        why="a share of a deterministic square grid's points: only points within round-off "
        "of a boundary can flip between machines, 1 / points² each; ten are allowed",
    )
