"""Named tolerances of values from finite-element solves, linear and non-linear, and of the
meta-models and studies made from them.
"""

from __future__ import annotations

from mechlib.reporting.tolerance import Tolerance

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
FE_LINEAR = Tolerance(
    rtol=1e-6,
    peak=1e-6,
    why="responses of linear FE solves (a sparse direct factorisation) and least-squares fits "
    "or main effects of them: kernels agree to ~1e-8 relative on every entry away from 0; "
    "the entries that the structure's symmetry makes 0 are round-off, bounded at 1e-6 of the "
    "largest entry",
)
FE_LINEAR_REL = Tolerance(
    rtol=1e-6,
    why="a ratio, a range of ratios or a condition number made from linear FE responses, "
    "never near 0: the solves' ~1e-8 relative agreement between kernels stays inside 1e-6",
)
FE_FIT_RESIDUE = Tolerance(
    atol=1e-6,
    why="a relative deviation that is 0 in exact arithmetic (a least-squares fit to exactly "
    "linear FE responses against the model's own compliance, the second-order terms of such a "
    "fit): round-off near 1e-10 without a relative size, bounded absolutely at 1e-6",
)
FE_ROUNDOFF_PCT = Tolerance(
    atol=1e-5,
    why="a relative error in percent that is 0 in exact arithmetic (a linear meta-model against "
    "the linear FE runs whose compliance it is): round-off near 1e-8 %, bounded absolutely at "
    "1e-5 points",
)
FE_ROUNDOFF_RESPONSE = Tolerance(
    peak=1e-6,
    why="errors in µm and µrad that are 0 in exact arithmetic (a linear meta-model against the "
    "linear FE runs whose compliance it is): round-off, bounded at 1e-6 of the largest FE "
    "response they are errors of (a plan takes the peak of those responses)",
)
PENALIZED_FIT = Tolerance(
    rtol=0.05,
    atol=1e-6,
    why="the bias of a penalized least-squares fit whose penalty cross-validation picks from a "
    "grid: where two penalties nearly tie, another kernel can pick the neighbour and move the "
    "bias by a few percent; 5 %, with a floor of 1e-6 for a bias near 0",
)
INVERSE_RESIDUE = Tolerance(
    atol=1e-8,
    why="the largest entry of S⁻¹S − I for a 6 × 6 matrix and its computed inverse: 0 in exact "
    "arithmetic, round-off of ~1e-16 times the condition number, bounded absolutely at 1e-8",
)
POSE_ROUND_TRIP = Tolerance(
    atol=1e-10,
    why="poses sent through a 6 × 6 inverse and back, relative to their size: 0 in exact "
    "arithmetic, round-off of ~1e-16 times the condition number, bounded absolutely at 1e-10",
)
GAUSSIAN_PROCESS = Tolerance(
    rtol=1e-2,
    atol=1e-4,
    why="errors of Gaussian processes fitted to noise-free data by a seeded optimiser with "
    "restarts on the log-likelihood: its stopping point moves between kernels, and the "
    "errors with it; 1 %, with a floor of 1e-4 points for errors near 0",
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
NONLINEAR_FE_FINE = Tolerance(
    rtol=1e-3,
    atol=1e-9,
    why="as NONLINEAR_FE, for root-mean-square errors of meta-models in µm and µrad: relative "
    "1e-3, with a floor of 1e-9 in those units that only an error near 0 would reach",
)
MULTIMODAL_FIT = Tolerance(
    rtol=0.3,
    atol=1e-6,
    why="a Gaussian process fitted to inputs with round-off of 3e-6 of themselves (dual-weighted "
    "residuals, a cancellation) whose likelihood has many optima: its best of three starts "
    "moves between kernels (at 128 runs 0.887, 0.901 and 0.912 % under OpenBLAS's "
    "Sandybridge, Haswell and SkylakeX; eight starts: 0.46 % apart at 256 runs), within 30 %",
)
NONLINEAR_FE_PEAK = Tolerance(
    rtol=1e-3,
    peak=1e-6,
    why="as NONLINEAR_FE, for arrays in µm and µrad (main effects, pose differences) whose "
    "entries near 0 are round-off of a large whole: a floor of 1e-6 of the largest entry (a "
    "plan may take the peak of the poses they are made of)",
)
NONLINEAR_FE_PCT = Tolerance(
    rtol=1e-3,
    atol=1e-5,
    why="as NONLINEAR_FE, for a percentage difference of non-linear FE results (from the linear "
    "ones, from a closed form) that can be 0: a floor of 1e-5 points",
)
NONLINEAR_FE_RATIO = Tolerance(
    rtol=1e-3,
    atol=1e-9,
    why="as NONLINEAR_FE, for ratios of fitted coefficients (second-order over linear) that "
    "can be as small as 1e-7: a floor of 1e-9",
)
BEAM_REACH_PCT = Tolerance(
    rtol=2e-4,
    atol=1e-6,
    why="the reduced beam model's worst misfit of Eq 8 in %, from a bounded least-squares fit: "
    "1.4e-5 of itself apart under another machine's BLAS kernel and SIMD paths (measured); a "
    "floor of 1e-6 points for the misfits of reachable thicknesses, near 0",
)
BEAM_REACH_FAR = Tolerance(
    rtol=1e-4,
    why="the beam model's worst misfit of Eq 8 at a thickness it cannot reach (tens of %): far "
    "from 0, moved by ~1e-5 of itself where the bounded fit stops on another machine",
)
ROUNDED_THICKNESS = Tolerance(
    rtol=1e-5,
    why="a plate thickness in mm, a parameter or the identified member's, rounded by its fit to "
    "a 1e-6 mm grid: a re-run lands on the same grid point or the next, under 1e-5 of itself",
)
MESH_STUDY_PCT = Tolerance(
    rtol=1e-2,
    atol=5e-4,
    why="a change of the non-linear departure between two meshes or quadratures, in % of the "
    "departure: 2.7e-5 points apart across three BLAS kernels (measured); 1 % of itself, and "
    "5e-4 points (18 times that spread) for a change near 0",
)
MESH_STUDY_LINEAR_PCT = Tolerance(
    rtol=1e-2,
    atol=5e-5,
    why="the change of the linear poses between two meshes or quadratures, in % of full scale: "
    "1e-6 points apart across three BLAS kernels (measured); 1 % of itself, and 5e-5 points "
    "(50 times that spread) for a change near 0",
)
LEAN_FIT_CHANGE_PCT = Tolerance(
    atol=1e-3,
    why="the change, in %, of a dimension by a lean model's fit, which rounds every geometry to "
    "a 1e-6 mm grid: the same steps and stop on any processor",
)
LEAN_DEPARTURE_PCT = Tolerance(
    rtol=1e-2,
    atol=0.05,
    why="the difference of two models' departures from linearity, in % of the departure: to 1 % "
    "of itself, and absolutely to what a lean fit stopping elsewhere within its tolerance "
    "could move it (0.05 points)",
)


def lean_pose_pct(fit_tol: float) -> Tolerance:
    """The tolerance of the difference of two models' non-linear poses in % of full scale, the
    lean model fitted to relative tolerance ``fit_tol``: 1 % of itself, and ``100 * fit_tol``
    points absolutely (what a fit stopping elsewhere within ``fit_tol`` could move it).

    Raises
    ------
    ValueError
        ``fit_tol`` not a number in (0, 1].
    """
    if isinstance(fit_tol, bool) or not isinstance(fit_tol, (int, float)) or not 0 < fit_tol <= 1:
        raise ValueError(f"lean_pose_pct: fit_tol must be a number in (0, 1], got {fit_tol!r}")
    return Tolerance(
        rtol=1e-2,
        atol=100 * fit_tol,
        why="the difference of two models' non-linear poses in % of full scale: to 1 % of "
        "itself, and absolutely to what a lean fit stopping elsewhere within its tolerance "
        "could move it (100 fit_tol points)",
    )
