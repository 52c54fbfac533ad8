"""Named tolerances of recorded numbers: how far a re-run may move a value, and why.

A record stores ``rtol`` and ``atol`` (``|a - b| <= atol + rtol * |b|``, see
:mod:`mechlib.reporting.records`). The chapters' record plans (:mod:`mechlib.reporting.plans`)
name one of the classes below for each key instead of writing the numbers: the class says which
kind of numerics produced the value and, in ``why``, why a re-run on another machine (another
BLAS kernel, another order of summation) stays within it.

The numbers are the ones the chapters used as literals: changing one changes the records.
"""

from __future__ import annotations

import numpy as np

from mechlib.reporting.tolerance import Tolerance

# --- exact -------------------------------------------------------------------------------------

EXACT = Tolerance(
    why="integers, booleans, texts, designs, parameters and published numbers carried over: "
    "no arithmetic in floating point, so every machine gives the same value"
)

# --- round-off of a fixed sequence of floating-point operations -------------------------------

CLOSED_FORM = Tolerance(
    rtol=1e-12,
    why="a closed-form expression of a few dozen operations: each rounds to 1e-16 relative, "
    "and another order of the operations moves the result by far less than 1e-12",
)
CLOSED_FORM_SUM = Tolerance(
    rtol=1e-10,
    why="a closed-form sum over a design's points (thousands of terms, e.g. a discrepancy): "
    "another summation order moves it by ~1e-13 relative",
)
ROUNDOFF = Tolerance(
    rtol=1e-9,
    why="least squares, medians and sums over printed numbers: a BLAS kernel changes the order "
    "of the sums and the factorisation, which moves a well-conditioned result by ~1e-13",
)
ROUNDOFF_OR_ZERO = Tolerance(
    rtol=1e-9,
    atol=1e-9,
    why="as ROUNDOFF, with an absolute floor for entries that are 0 in exact arithmetic (their "
    "residue, far below 1e-9, has no relative size)",
)
ROUNDOFF_OR_TINY = Tolerance(
    rtol=1e-9,
    atol=1e-12,
    why="as ROUNDOFF, for statistics of which some entries are themselves round-off (~1e-14): "
    "an absolute floor of 1e-12",
)
INVERSE_ROUNDOFF = Tolerance(
    rtol=1e-9,
    atol=1e-15,
    why="the inverse of a well-conditioned matrix with entries up to ~1e-2: round-off relative, "
    "its exact zeros get an absolute floor of 1e-15",
)
NEAR_ZERO = Tolerance(
    atol=1e-12,
    why="a quantity of order 1 or less that is 0 (or a small difference) in exact arithmetic: "
    "its round-off has no relative size, so it is bounded absolutely at 1e-12",
)
ROUND_TRIP = Tolerance(
    atol=1e-9,
    why="an input returned through a model and its inverse (±1 N forces): what is left is "
    "round-off, bounded absolutely at 1e-9 of the input's unit",
)
MAGNIFIED_ROUNDOFF = Tolerance(
    rtol=1e-6,
    atol=1e-9,
    why="round-off divided by a small number (a printed resolution, a difference of nearly "
    "equal values): relative 1e-6, with an absolute floor for values near 0",
)
CANCELLATION = Tolerance(
    rtol=1e-6,
    why="a difference of nearly equal numbers (residuals, small changes): round-off of the "
    "operands is magnified by the cancellation, up to ~1e-8 relative",
)
CANCELLATION_OR_TINY = Tolerance(
    rtol=1e-6,
    atol=1e-8,
    why="as CANCELLATION, for arrays with entries at round-off level (~1e-14) that differ "
    "between machines: an absolute floor of 1e-8",
)

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
    why="a small quantity derived from values known to a solver's tolerance (1e-6): a relative "
    "difference of ~1e-3 moves by up to ~1e-4 of itself",
)
ITERATIVE = Tolerance(
    rtol=1e-6,
    why="a fit or an estimate iterated to a stopping tolerance of 1e-8 or below (Gauss–Newton, "
    "Levenberg–Marquardt, a seeded Monte Carlo): another kernel stops within 1e-6 of it",
)
ITERATIVE_PCT = Tolerance(
    rtol=1e-6,
    atol=1e-9,
    why="as ITERATIVE, for a percentage: an absolute floor of 1e-9 percentage points for "
    "values that are 0 or near it",
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
    why="a bisection stopped at an interval of 1e-5 (the numeric MIW, in m): its steps are "
    "comparisons of round-off-exact kinematics, so a re-run repeats them; 1e-6 absolute allows "
    "a comparison that flips at round-off",
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


# --- finite-element solves ---------------------------------------------------------------------

FE_PCT = Tolerance(
    rtol=1e-5,
    atol=1e-9,
    why="a percentage made from sparse direct FE solves: their condition number costs digits, "
    "so kernels agree to ~1e-7 relative; a floor of 1e-9 points for values near 0",
)
FE_STUDY_PCT = Tolerance(
    rtol=1e-4,
    atol=1e-9,
    why="a small difference of two FE solves (a mesh or model change) in percent: the "
    "difference magnifies the solves' 1e-7 agreement; a floor of 1e-9 points near 0",
)
NONLINEAR_FE = Tolerance(
    rtol=1e-3,
    atol=1e-6,
    why="a non-linear FE solve (Newton iterations over load steps) stopped at its residual "
    "tolerance: another kernel can stop one iterate apart; a floor of 1e-6 near 0",
)
NONLINEAR_FE_REL = Tolerance(
    rtol=1e-3,
    why="as NONLINEAR_FE, for a value that is never near 0",
)

# --- the HexFlex's FE model, identified to Eq 8, and its beam model ----------------------------

BEAM_MODEL = Tolerance(
    rtol=1e-9,
    why="the HexFlex's beam model (mechlib.hexflex.frame): a dense solve of a few hundred "
    "unknowns, or a closed form of the geometry; round-off moves it by ~1e-14 relative",
)
BEAM_MODEL_SENSITIVITY = Tolerance(
    rtol=1e-4,
    why="singular values of central-difference sensitivities of the beam model (step 1e-3 in "
    "log dimension): each difference magnifies the solves' round-off a thousandfold, to "
    "~1e-11 relative, well inside 1e-4",
)
FE_IDENTIFIED = Tolerance(
    rtol=2e-3,
    why="a dimension or a compliance of the FE model identified to Eq 8: the identification "
    "stops within fit_tol (0.1 %) on a 1 nm grid of dimensions, so another kernel's last digits "
    "could end it one step apart; 0.2 % covers that step",
)
FE_IDENTIFIED_PEAK = Tolerance(
    rtol=2e-3,
    peak=1e-6,
    why="as FE_IDENTIFIED, for a compliance matrix or a pose with entries that are 0 by the "
    "part's symmetry: their residue (~1e-9 of the largest entry) gets a floor of 1e-6 of it",
)
FE_IDENTIFIED_PCT = Tolerance(
    atol=0.2,
    why="a worst relative difference, in percent, of FE results each held to FE_IDENTIFIED "
    "(0.2 %): 0.2 percentage points",
)
FE_IDENTIFIED_DIFF_PCT = Tolerance(
    atol=0.4,
    why="a difference, in percent, of two FE magnitudes each held to FE_IDENTIFIED (0.2 %): "
    "their errors add up to 0.4 percentage points",
)
FE_SENSITIVITY = Tolerance(
    rtol=0.02,
    why="singular values of forward differences (a step of 2 % in log dimension) of re-meshed "
    "FE models at the identified geometry, which is held to FE_IDENTIFIED only: a geometry one "
    "step apart re-meshes every model, moving the differences by up to ~2 %",
)
FE_OVER_THEORY = Tolerance(
    rtol=1e-4,
    why="a linear FE deflection of one flexure (a sparse direct solve of a small mesh) over its "
    "closed form: kernels agree to ~1e-8 relative on such a solve, well inside 1e-4",
)
FE_OVER_THEORY_PCT = Tolerance(
    atol=0.01,
    why="the worst departure from 1, in percent, of ratios held to FE_OVER_THEORY (1e-4): "
    "0.01 percentage points",
)
MESH_CHANGE_PCT = Tolerance(
    atol=0.1,
    why="a change of the FE magnitudes between two meshes, in percent: each mesh's solve is "
    "reproducible to ~1e-7, but the meshes follow the identified dimensions (FE_IDENTIFIED), "
    "which can move the change by up to 0.1 percentage points",
)
FE_DEFECT = Tolerance(
    atol=1e-6,
    why="a relative defect of the FE compliance that is 0 in exact arithmetic (three-fold "
    "symmetry, zero pattern, a pose returned through the inverse): measured 1e-13 to 5e-9, "
    "held below the model checks' threshold of 1e-6 (mechlib.hexflex.checks)",
)
FE_RECIPROCITY = Tolerance(
    atol=1e-9,
    why="the relative asymmetry of the FE port compliance (Maxwell–Betti), 0 in exact "
    "arithmetic: measured ~5e-11, held below the model check's threshold of 1e-9",
)
UNIT_VECTORS = Tolerance(
    atol=1e-12,
    why="unit vectors from sines and cosines of fixed angles: entries of order 1, some 0 in "
    "exact arithmetic, whose round-off (~1e-16) is bounded absolutely at 1e-12",
)
