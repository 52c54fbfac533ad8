"""Identify free dimensions of the HexFlex so that its compliance matches Eq 8's magnitudes.

Four independent magnitudes of Eq 8 — x←T1D1, z←T1D2, θx←T1D2 and |θz←T1D1| — fix, by the
three-fold symmetry and the zero pattern, all 16 non-zero entries (up to Eq 8's own regression
noise). They are matched on logarithms (relative errors, scale-free) over a few free dimensions
within :data:`mechlib.hexflex.geometry.DIMENSION_BOUNDS`.

Every FE evaluation builds and factorises a model (seconds), so the FE fit takes Newton steps
whose Jacobian comes from a cheap surrogate — the reduced beam model
(:mod:`mechlib.hexflex.frame`) — at the current geometry: one FE model per iteration, and the
iteration converges as long as the surrogate's sensitivities are close to the FE's
(:func:`log_sensitivity` of both is shown in the hexflex notebook). Where they are not, the
surrogate's Jacobian at the start can instead be corrected by Broyden's secant rule after every
FE model (``jacobian="secant"``), so that the FE's own sensitivities are learnt along the path.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from mechlib import progress
from mechlib.hexflex.geometry import DIMENSION_BOUNDS, HexFlexGeometry
from mechlib.params import check_choice, check_float, check_int, check_matrix

#: (row, column, sign) of the four independent magnitudes in the 6 × 6 compliance:
#: x←T1D1, z←T1D2, θx←T1D2, θz←T1D1 (sign: θz←T1D1 is negative in Eq 8).
TARGET_ENTRIES: tuple[tuple[int, int, int], ...] = ((0, 0, 1), (2, 1, 1), (3, 1, 1), (5, 0, -1))
TARGET_LABELS: tuple[str, ...] = (
    "x←T1D1 [µm/N]",
    "z←T1D2 [µm/N]",
    "θx←T1D2 [µrad/N]",
    "|θz←T1D1| [µrad/N]",
)
#: Largest Newton step of the FE fit in log-dimension (a factor e^0.3 ≈ 1.35 per iteration).
MAX_LOG_STEP = 0.3
#: Decimals [mm] of the dimensions the FE fit evaluates (1 nm, far below any machining
#: tolerance): round-off on another processor moves an identified dimension by ~1e-9 of itself,
#: and the mesher turns such a change into another element count; on the grid both see one
#: geometry. A grid step moves a flexure's compliance by < 2e-5 of itself (0.28 mm wide, cubed).
GRID_DECIMALS = 6
#: FE models :func:`identify` may build by default: measured, the fits of the book converge
#: in 3–8; the budget only ends a fit that does not converge, with an error.
MAX_EVALUATIONS = 20
#: The Jacobians :func:`identify` can steer by (its ``jacobian``).
JACOBIANS: tuple[str, ...] = ("surrogate", "secant")

ComplianceFn = Callable[[HexFlexGeometry], np.ndarray]


def target_values(compliance: np.ndarray) -> np.ndarray:
    """The four magnitudes of :data:`TARGET_ENTRIES` from a 6 × 6 compliance."""
    c = check_matrix("compliance", np.asarray(compliance, dtype=float), shape=(6, 6))
    return np.array([s * c[i, j] for i, j, s in TARGET_ENTRIES])


def check_free(free: Sequence[str]) -> list[str]:
    """The free dimension names, each a field of :class:`HexFlexGeometry`, without repeats."""
    names = [check_choice("free dimension", n, tuple(DIMENSION_BOUNDS)) for n in free]
    if len(set(names)) != len(names) or not names:
        raise ValueError(f"free dimensions must be distinct and at least one, got {list(free)}")
    return names


def check_target(target: object) -> np.ndarray:
    """Four positive magnitudes."""
    t = np.asarray(target, dtype=float)
    if t.shape != (4,) or not np.all(np.isfinite(t)) or np.any(t <= 0):
        raise ValueError(f"target must be 4 positive finite magnitudes, got {np.ravel(t).tolist()}")
    return t


def log_sensitivity(
    compliance_fn: ComplianceFn,
    g: HexFlexGeometry,
    names: Sequence[str],
    rel_step: float = 1e-3,
    central: bool = True,
) -> np.ndarray:
    """d log|magnitude_i| / d log(dimension_j) (4, k) by finite differences at ``g``.

    Its singular values say how many combinations of the dimensions the four magnitudes fix.

    Parameters
    ----------
    compliance_fn : callable
        Geometry → 6 × 6 compliance (the frame model, an FE model, ...).
    g : HexFlexGeometry
    names : sequence of str
        The dimensions to differentiate by.
    rel_step : float
        Step in log(dimension), in (0, 0.1].
    central : bool
        Central differences (two evaluations per dimension) or forward ones (one, plus one at
        ``g``). Where a step would leave the dimension's bounds or make an invalid geometry, the
        one-sided difference on the other side is used.

    Raises
    ------
    ValueError
        If a name is not a dimension, ``rel_step`` is outside (0, 0.1], or neither side of a
        dimension can be stepped.
    """
    names = check_free(names)
    rel_step = check_float("rel_step", rel_step, low=0.0, high=0.1, low_open=True)
    here: list[np.ndarray] = []

    def at(n: str, sign: float) -> np.ndarray | None:
        if sign == 0.0:
            if not here:
                here.append(np.log(np.abs(target_values(compliance_fn(g)))))
            return here[0]
        value = getattr(g, n) * np.exp(sign * rel_step)
        low, high = DIMENSION_BOUNDS[n]
        if not low <= value <= high:
            return None
        try:
            stepped = g.replace(**{n: value})
        except ValueError:
            return None
        return np.log(np.abs(target_values(compliance_fn(stepped))))

    out = np.empty((4, len(names)))
    for j, n in enumerate(names):
        up = at(n, 1.0)
        down = at(n, -1.0) if central or up is None else None
        if up is not None and down is not None:
            out[:, j] = (up - down) / (2 * rel_step)
        elif up is not None:
            out[:, j] = (up - at(n, 0.0)) / rel_step
        elif down is not None:
            out[:, j] = (at(n, 0.0) - down) / rel_step
        else:
            raise ValueError(f"{n} cannot be stepped by rel_step = {rel_step:g} on either side")
    return out


class IdentificationError(RuntimeError):
    """An identification that did not meet its tolerance; ``result`` holds the best fit."""

    def __init__(self, message: str, result: Identification) -> None:
        super().__init__(message)
        self.result = result


@dataclass(frozen=True)
class Identification:
    """Result of :func:`identify`: geometry, achieved and target magnitudes, the fit history.

    ``history`` has one row per FE evaluation: the free dimensions [mm], then the four
    magnitudes.
    """

    geometry: HexFlexGeometry
    achieved: np.ndarray
    target: np.ndarray
    n_evaluations: int
    history: np.ndarray

    @property
    def relative_error(self) -> np.ndarray:
        """achieved / target − 1 per magnitude."""
        return self.achieved / self.target - 1.0


def identify(
    start: HexFlexGeometry,
    target: np.ndarray,
    free: Sequence[str],
    compliance_fn: ComplianceFn,
    surrogate_fn: ComplianceFn,
    max_evaluations: int = MAX_EVALUATIONS,
    tol: float = 1e-3,
    grid_decimals: int | None = GRID_DECIMALS,
    jacobian: str = "surrogate",
    log_quantum: float | None = None,
) -> Identification:
    """Fit the ``free`` dimensions of ``start`` so that ``compliance_fn`` meets ``target``.

    Newton iterations on r(x) = log(achieved / target), x = log(free dimensions), with the
    Jacobian J of ``surrogate_fn`` at the current geometry (or, with ``jacobian="secant"``, at
    the start, corrected by the FE models' secants): the minimum-norm step ``−J⁺ r``
    (when more dimensions are free than magnitudes it leaves the directions they do not fix
    alone), capped at ``MAX_LOG_STEP`` and halved while the geometry is invalid or leaves its
    bounds. Every geometry evaluated has its free dimensions rounded to ``grid_decimals``
    decimals [mm], so that round-off (~1e-9 of a dimension on another processor) cannot change
    a geometry, a mesh, and with them the path: from the same start the fit takes the same steps
    and ends at the same geometry. (Stepping back towards the start along the unfixed
    directions, to make the end point independent of the path, was tried: with the beam model's
    Jacobian those directions are not the FE's, and the fit of the 0.45 mm member stalled at
    0.5 % after 20 FE models.) Converged when max |r| <= ``tol``: the stopping rule;
    ``max_evaluations`` only bounds a fit that does not converge, and then
    :class:`IdentificationError` is raised.

    Parameters
    ----------
    start : HexFlexGeometry
        Starting geometry; the dimensions not in ``free`` keep its values.
    target : array_like (4,)
        The magnitudes to meet, in the order of :data:`TARGET_LABELS`.
    free : sequence of str
        The dimensions to fit.
    compliance_fn, surrogate_fn : callable
        Geometry → 6 × 6 compliance: the model to fit (FE) and the one whose sensitivities
        steer the steps (the frame model).
    max_evaluations : int
        Calls of ``compliance_fn`` allowed, in [1, 100].
    tol : float
        Converged when every |log(achieved / target)| is at most this, in (0, 1].
    grid_decimals : int or None
        Decimals [mm] of the free dimensions evaluated, in [3, 12] (None: no rounding).
    jacobian : {"surrogate", "secant"}
        The steps' Jacobian (:data:`JACOBIANS`): the surrogate's at every geometry, or the
        surrogate's at the start updated after every FE model by Broyden's secant rule, so that
        it learns the FE's own sensitivities along the path (faster where the surrogate's are
        off: the 0.45 mm member of the family page took 10 FE models with it against 22 with
        the surrogate's, for one tolerance).
    log_quantum : float or None
        When given, in [1e-8, min(1e-2, tol / 2)]: every log(achieved / target) of the FE is
        rounded to a multiple of it before it steers or stops the fit, so that round-off far
        below it (another processor's) leaves the path unchanged except where a value lies
        within that round-off of a rounding boundary; the fit then stops when the rounded
        misfits are within ``tol - log_quantum / 2``, so that the true ones are within ``tol``.

    Returns
    -------
    Identification
        The first geometry evaluated that meets ``tol``.

    Raises
    ------
    ValueError
        On an unknown or repeated free dimension, a bad target, budget or grid.
    IdentificationError
        When no geometry within ``max_evaluations`` FE models meets ``tol``, or no admissible
        step is left (e.g. a bound holds the fit); it names the misfit reached, the
        evaluations, ``tol`` and the free dimensions on a bound, and carries the best fit.
    """
    free = check_free(free)
    target = check_target(target)
    max_evaluations = check_int("max_evaluations", max_evaluations, low=1, high=100)
    tol = check_float("tol", tol, low=0.0, high=1.0, low_open=True)
    if grid_decimals is not None:
        grid_decimals = check_int("grid_decimals", grid_decimals, low=3, high=12)
    jacobian = check_choice("jacobian", jacobian, JACOBIANS)
    if log_quantum is not None:
        log_quantum = check_float("log_quantum", log_quantum, low=1e-8, high=min(1e-2, tol / 2))
    # rounded misfits stop the fit within tol - q/2, so that the true ones are within tol
    stop = tol - (log_quantum / 2 if log_quantum is not None else 0.0)
    lo = np.log([DIMENSION_BOUNDS[n][0] for n in free])
    hi = np.log([DIMENSION_BOUNDS[n][1] for n in free])
    g = _on_grid(start, free, np.log([getattr(start, n) for n in free]), grid_decimals)
    if g is None:
        raise ValueError(
            f"start must stay valid rounded to {grid_decimals} decimals [mm], got {start}"
        )
    x = np.log([getattr(g, n) for n in free])
    history: list[np.ndarray] = []
    converged = False
    jac = previous = None
    while len(history) < max_evaluations:
        achieved = np.abs(target_values(compliance_fn(g)))  # a sign flip is a misfit, not NaN
        history.append(np.r_[[getattr(g, n) for n in free], achieved])
        r = np.log(achieved / target)
        if log_quantum is not None:
            r = np.round(r / log_quantum) * log_quantum
        progress.note(
            "identification",
            f"FE model {len(history)}: largest |log(achieved / target)| {np.abs(r).max():.3g} "
            f"(stops at {stop:.3g})",
        )
        if np.abs(r).max() <= stop:
            converged = True
            break
        if len(history) == max_evaluations:
            break
        if jac is None or jacobian == "surrogate":
            jac = log_sensitivity(surrogate_fn, g, free)
        elif np.any(x != previous[0]):  # Broyden: r's change along the step taken corrects jac
            s_x, s_r = x - previous[0], r - previous[1]
            jac = jac + np.outer(s_r - jac @ s_x, s_x) / (s_x @ s_x)
        previous = (x, r)
        step = -np.linalg.pinv(jac) @ r
        step *= min(1.0, MAX_LOG_STEP / np.abs(step).max())
        for _ in range(20):
            trial = x + step
            inside = np.all((trial >= lo) & (trial <= hi))
            candidate = _on_grid(start, free, trial, grid_decimals) if inside else None
            if candidate is not None:
                g = candidate
                x = np.log([getattr(g, n) for n in free])
                break
            step *= 0.5
        else:
            break  # no admissible step left
    hist = np.asarray(history)
    cost = np.max(np.abs(np.log(hist[:, len(free) :] / target)), axis=1)
    i = len(hist) - 1 if converged else int(np.argmin(cost))
    best = start.replace(**{n: float(v) for n, v in zip(free, hist[i, : len(free)], strict=True)})
    fit = Identification(best, hist[i, len(free) :], target, len(history), hist)
    if not converged:
        raise IdentificationError(
            f"the identification did not converge: max |log(achieved / target)| = "
            f"{cost[i]:.3g} at best after {len(hist)} FE models, more than tol = {tol:g} "
            f"(free dimensions on a bound: {at_bounds(best, free) or 'none'}); allow more "
            f"max_evaluations (got {max_evaluations}, at most 100), a larger tol, or other "
            f"free dimensions",
            fit,
        )
    return fit


def _on_grid(
    start: HexFlexGeometry, free: list[str], logdims: np.ndarray, decimals: int | None
) -> HexFlexGeometry | None:
    """``start`` with the ``free`` dimensions exp(``logdims``) rounded to ``decimals``
    decimals [mm], or None if that geometry is invalid."""
    dims = np.exp(logdims)
    if decimals is not None:
        dims = np.round(dims, decimals)
    try:
        return start.replace(**dict(zip(free, dims.tolist(), strict=True)))
    except ValueError:
        return None


def at_bounds(geometry: HexFlexGeometry, free: Sequence[str], rtol: float = 0.01) -> list[str]:
    """The ``free`` dimensions of ``geometry`` within ``rtol`` of one of their bounds."""
    return [
        n
        for n in free
        if min(abs(getattr(geometry, n) / b - 1.0) for b in DIMENSION_BOUNDS[n]) < rtol
    ]


def entry_ratios(compliance: np.ndarray, published: np.ndarray) -> np.ndarray:
    """compliance / published for every non-zero published entry (row-major order)."""
    c, p = np.asarray(compliance, dtype=float), np.asarray(published, dtype=float)
    nz = p != 0
    return c[nz] / p[nz]
