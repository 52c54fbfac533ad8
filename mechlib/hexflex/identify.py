"""Identify free dimensions of the HexFlex so that its compliance matches Eq 8's magnitudes.

Four independent magnitudes of Eq 8 — x←T1D1, z←T1D2, θx←T1D2 and |θz←T1D1| — fix, by the
three-fold symmetry and the zero pattern, all 16 non-zero entries (up to Eq 8's own regression
noise). They are matched on logarithms (relative errors, scale-free) over a few free dimensions
within :data:`mechlib.hexflex.geometry.DIMENSION_BOUNDS`.

Every FE evaluation builds and factorises a model (seconds), so the FE fit takes Newton steps
whose Jacobian comes from a cheap surrogate — the reduced beam model
(:mod:`mechlib.hexflex.frame`) — at the current geometry: one FE model per iteration, and the
iteration converges as long as the surrogate's sensitivities are close to the FE's
(:func:`log_sensitivity` of both is shown in the hexflex notebook).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

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
    max_evaluations: int = 8,
    tol: float = 1e-3,
) -> Identification:
    """Fit the ``free`` dimensions of ``start`` so that ``compliance_fn`` meets ``target``.

    Newton iterations on r(x) = log(achieved / target), x = log(free dimensions), with the
    Jacobian of ``surrogate_fn`` at the current geometry (minimum-norm step when more dimensions
    are free than magnitudes, steps capped at ``MAX_LOG_STEP``, halved while the geometry is
    invalid or leaves its bounds). Stops at max |r| <= ``tol`` or after ``max_evaluations`` calls
    of ``compliance_fn``; returns the best geometry seen.

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
        Stop when every |log(achieved / target)| is at most this, in (0, 1].

    Returns
    -------
    Identification

    Raises
    ------
    ValueError
        On an unknown or repeated free dimension, a bad target or budget.
    """
    free = check_free(free)
    target = check_target(target)
    max_evaluations = check_int("max_evaluations", max_evaluations, low=1, high=100)
    tol = check_float("tol", tol, low=0.0, high=1.0, low_open=True)
    lo = np.log([DIMENSION_BOUNDS[n][0] for n in free])
    hi = np.log([DIMENSION_BOUNDS[n][1] for n in free])
    x = np.log([getattr(start, n) for n in free])
    g = start
    history: list[np.ndarray] = []
    for _ in range(max_evaluations):
        achieved = np.abs(target_values(compliance_fn(g)))  # a sign flip is a misfit, not NaN
        history.append(np.r_[[getattr(g, n) for n in free], achieved])
        r = np.log(achieved / target)
        if np.abs(r).max() <= tol or len(history) == max_evaluations:
            break
        step = -np.linalg.lstsq(log_sensitivity(surrogate_fn, g, free), r, rcond=None)[0]
        step *= min(1.0, MAX_LOG_STEP / np.abs(step).max())
        for _ in range(20):
            trial = x + step
            inside = np.all((trial >= lo) & (trial <= hi))
            candidate = _valid(start, free, trial) if inside else None
            if candidate is not None:
                x, g = trial, candidate
                break
            step *= 0.5
        else:
            break  # no admissible step: stay at the best point
    hist = np.asarray(history)
    cost = np.max(np.abs(np.log(hist[:, len(free) :] / target)), axis=1)
    best_row = hist[int(np.argmin(cost))]
    best = start.replace(**{n: float(v) for n, v in zip(free, best_row[: len(free)], strict=True)})
    return Identification(best, best_row[len(free) :], target, len(history), hist)


def _valid(start: HexFlexGeometry, free: list[str], logdims: np.ndarray) -> HexFlexGeometry | None:
    try:
        return start.replace(**dict(zip(free, np.exp(logdims), strict=True)))
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
