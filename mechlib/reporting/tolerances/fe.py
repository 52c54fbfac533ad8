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
