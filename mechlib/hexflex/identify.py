"""Identify free dimensions of the HexFlex so that its compliance matches Eq 8's magnitudes.

The four independent magnitudes of Eq 8 (issue specification) are matched in the least-squares
sense on log-compliance (relative errors, scale-free), over a few free dimensions with bounds
that keep the geometry physically sensible.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, fields

import numpy as np
from scipy.optimize import least_squares

from mechlib.hexflex.geometry import HexFlexGeometry
from mechlib.hexflex.model import HexFlexModel
from mechlib.params import check_choice, check_int

#: (row, column, sign) of the four independent magnitudes in the 6 × 6 compliance:
#: x←T1D1, z←T1D2, θx←T1D2, θz←T1D1 (sign: θz←T1D1 is negative in Eq 8).
TARGET_ENTRIES: tuple[tuple[int, int, int], ...] = ((0, 0, 1), (2, 1, 1), (3, 1, 1), (5, 0, -1))
TARGET_LABELS: tuple[str, ...] = (
    "x←T1D1 [µm/N]",
    "z←T1D2 [µm/N]",
    "θx←T1D2 [µrad/N]",
    "|θz←T1D1| [µrad/N]",
)
#: Allowed range [mm] of each dimension during the fit.
FIT_BOUNDS: dict[str, tuple[float, float]] = {
    "thickness": (0.3, 5.0),
    "beam_width": (0.3, 3.0),
    "link_width": (0.3, 3.0),
    "beam_length": (10.0, 40.0),
    "link_length": (3.0, 15.0),
    "tab_depth": (4.0, 20.0),
}


#: Ranges [mm] of the design-space sample (:func:`design_space_sample`), wider than the fit's
#: and including the links' radius ``arm_end``, the lever arm of the out-of-plane tilt.
DESIGN_SPACE: dict[str, tuple[float, float]] = {
    "thickness": (0.3, 3.0),
    "beam_width": (0.3, 3.0),
    "link_width": (0.3, 1.5),
    "beam_length": (10.0, 40.0),
    "link_length": (3.0, 15.0),
    "arm_end": (10.5, 16.0),
}


def target_values(compliance: np.ndarray) -> np.ndarray:
    """The four magnitudes of :data:`TARGET_ENTRIES` from a 6 × 6 compliance."""
    c = np.asarray(compliance, dtype=float)
    return np.array([s * c[i, j] for i, j, s in TARGET_ENTRIES])


@dataclass(frozen=True)
class Identification:
    """Result of :func:`identify`: geometry, achieved and target magnitudes, the fit history."""

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
    free: Sequence[str] = ("thickness", "beam_width", "link_width", "beam_length"),
    element: str = "q2",
    max_evaluations: int = 40,
) -> Identification:
    """Fit the ``free`` dimensions of ``start`` to the four target magnitudes (log least squares).

    At most ``max_evaluations`` FE models are solved (finite-difference Jacobians included); the
    best geometry seen is returned.

    Raises
    ------
    ValueError
        If a free dimension is unknown or has no bounds, or ``target`` is not 4 positive values.
    """
    names = [f.name for f in fields(HexFlexGeometry)]
    for name in free:
        check_choice("free dimension", name, tuple(n for n in names if n in FIT_BOUNDS))
    target = np.asarray(target, dtype=float)
    if target.shape != (4,) or np.any(target <= 0):
        raise ValueError(f"target must be 4 positive magnitudes, got {target.tolist()}")
    max_evaluations = check_int("max_evaluations", max_evaluations, low=1, high=1000)
    lo = np.log([FIT_BOUNDS[n][0] for n in free])
    hi = np.log([FIT_BOUNDS[n][1] for n in free])
    x0 = np.clip(np.log([getattr(start, n) for n in free]), lo, hi)
    history: list[np.ndarray] = []

    def residual(logdims: np.ndarray) -> np.ndarray:
        if len(history) >= max_evaluations:  # scipy does not count Jacobian evaluations
            raise _BudgetSpent
        g = start.replace(**dict(zip(free, np.exp(logdims), strict=True)))
        achieved = target_values(HexFlexModel(g, element=element).compliance())
        history.append(np.r_[np.exp(logdims), achieved])
        return np.log(achieved / target)

    try:
        least_squares(residual, x0, bounds=(lo, hi), diff_step=1e-3)
    except _BudgetSpent:
        pass
    hist = np.asarray(history)
    cost = np.sum(np.log(hist[:, len(free) :] / target) ** 2, axis=1)
    best_row = hist[int(np.argmin(cost))]
    best = start.replace(**dict(zip(free, best_row[: len(free)], strict=True)))
    return Identification(best, best_row[len(free) :], target, len(history), hist)


class _BudgetSpent(Exception):
    """Raised inside the residual when the evaluation budget is spent."""


@dataclass(frozen=True)
class DesignSample:
    """Result of :func:`design_space_sample`.

    ``dimensions`` (n, k) [mm] of the valid designs (columns ``names``), their ``achieved``
    magnitudes (n, 4) in the order of :data:`TARGET_LABELS`, and ``n_invalid``, the drawn
    designs the geometry rejected (overlapping legs).
    """

    names: tuple[str, ...]
    dimensions: np.ndarray
    achieved: np.ndarray
    n_invalid: int

    @property
    def tilt_ratio(self) -> np.ndarray:
        """θx←T1D2 / z←T1D2 of every design [µrad/µm = rad/m]."""
        return self.achieved[:, 2] / self.achieved[:, 1]


def design_space_sample(
    start: HexFlexGeometry,
    n: int,
    seed: int,
    space: dict[str, tuple[float, float]] | None = None,
    element: str = "shell",
    mesh_fraction: float = 1.0,
) -> DesignSample:
    """Compliance magnitudes over a seeded Latin hypercube of designs (log-uniform dimensions).

    Every other dimension is that of ``start``. Designs the geometry rejects are skipped and
    counted. The default element is the shell (about a second per design; within a few % of
    Q2, see the hexflex notebook's convergence table).

    Raises
    ------
    ValueError
        If ``n`` is outside [1, 2000], a range is empty or not positive, or a name is not a
        dimension.
    """
    from scipy.stats import qmc

    space = DESIGN_SPACE if space is None else space
    n = check_int("n", n, low=1, high=2000)
    names = tuple(space)
    dims = {f.name for f in fields(HexFlexGeometry)}
    for name, (lo, hi) in space.items():
        check_choice("design-space dimension", name, tuple(sorted(dims)))
        if not 0 < lo < hi:
            raise ValueError(
                f"design-space range of {name} must satisfy 0 < low < high, got {(lo, hi)}"
            )
    lo = np.log([space[k][0] for k in names])
    hi = np.log([space[k][1] for k in names])
    draws = np.exp(qmc.scale(qmc.LatinHypercube(d=len(names), seed=seed).random(n), lo, hi))
    kept, achieved, invalid = [], [], 0
    for x in draws:
        try:
            g = start.replace(**dict(zip(names, x, strict=True)))
        except ValueError:
            invalid += 1
            continue
        size = mesh_fraction * min(g.beam_width, g.link_width)
        model = HexFlexModel(g, element=element, mesh_size=size)
        achieved.append(target_values(model.compliance()))
        kept.append(x)
    return DesignSample(names, np.array(kept), np.array(achieved), invalid)


def at_bounds(geometry: HexFlexGeometry, free: Sequence[str], rtol: float = 0.01) -> list[str]:
    """The ``free`` dimensions of ``geometry`` within ``rtol`` of one of their ``FIT_BOUNDS``."""
    return [
        n for n in free if min(abs(getattr(geometry, n) / b - 1.0) for b in FIT_BOUNDS[n]) < rtol
    ]


def convergence_changes(
    rows: list[dict[str, object]], chosen_fraction: float, coarse_widths: float
) -> dict[str, object]:
    """Largest relative changes of the four target magnitudes in a mesh-convergence study.

    Parameters
    ----------
    rows : list of dict
        Output of :func:`mechlib.hexflex.model.convergence` (Q2 rows over flexure fractions at
        ``coarse_widths``; optionally Q2 rows with another ``coarse_widths`` and shell rows).
    chosen_fraction : float
        The flexure fraction of the model in use; must be one of the Q2 fractions.
    coarse_widths : float
        Largest element of the flexure-refinement series, in narrowest beam widths.

    Returns
    -------
    dict
        ``fractions`` (coarse to fine), ``steps`` (change at each refinement), ``next`` (chosen →
        next finer; NaN if the chosen mesh is the finest), ``finest`` (chosen → finest),
        ``coarse_region`` (chosen → same flexures with another free-region size; NaN if absent),
        ``shell_vs_q2`` (on the finest flexure mesh; NaN if no shell row).

    Raises
    ------
    ValueError
        If the chosen fraction is not in the Q2 series.
    """

    def mags(r: dict[str, object]) -> np.ndarray:
        return target_values(np.asarray(r["compliance"]))

    def change(a: np.ndarray, b: np.ndarray) -> float:
        return float(np.max(np.abs(a / b - 1.0)))

    series = sorted(
        (r for r in rows if r["element"] == "q2" and r["coarse_widths"] == coarse_widths),
        key=lambda r: -float(r["fraction"]),
    )
    fractions = [float(r["fraction"]) for r in series]
    match = [i for i, f in enumerate(fractions) if np.isclose(f, chosen_fraction, rtol=1e-9)]
    if not match:
        raise ValueError(
            f"chosen_fraction must be one of the Q2 fractions {fractions}, got {chosen_fraction}"
        )
    k = match[0]
    values = [mags(r) for r in series]
    steps = [change(values[i + 1], values[i]) for i in range(len(values) - 1)]
    others = [
        r
        for r in rows
        if r["element"] == "q2"
        and r["coarse_widths"] != coarse_widths
        and np.isclose(float(r["fraction"]), chosen_fraction, rtol=1e-9)
    ]
    shells = [
        r
        for r in rows
        if r["element"] == "shell"
        and r["coarse_widths"] == coarse_widths
        and np.isclose(float(r["fraction"]), fractions[-1], rtol=1e-9)
    ]
    nan = float("nan")
    return {
        "fractions": fractions,
        "steps": steps,
        "next": steps[k] if k < len(steps) else nan,
        "finest": change(values[k], values[-1]),
        "coarse_region": change(mags(others[0]), values[k]) if others else nan,
        "shell_vs_q2": change(mags(shells[0]), values[-1]) if shells else nan,
    }
