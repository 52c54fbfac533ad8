"""Named tolerances of exact values and of round-off in a fixed sequence of floating-point
operations (closed forms, sums, least squares over printed numbers, cancellation).
"""

from __future__ import annotations

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
