"""Chapter 2's design-of-computer-experiments method on the parallelogram flexure: its designs,
the screening (main effects, Lenth) and the thesis's meta-models, S_T (Eq 7) and Eq 6.

Loads are rows (A_x, A_y, B) of normalised loads (A_x = F_x L²/EI along the beams, A_y = F_y L²/EI
across them, B = M_z L/EI) inside the box ±:data:`HALF_RANGE` (the published sweep's extremes:
A_x ∈ [−10, 10], A_y ∈ [−20, 20], B ∈ [−3, 3]); a design over ``scale`` × the box stays inside
±``scale`` · HALF_RANGE. Poses are rows (u_x/L, u_y/L, φ [rad]), as :mod:`.elastica` and the 3-D
FE give them. Nothing here runs a model: the truth enters as data, the poses a notebook obtained
for the loads these functions designed (``poses = truth(loads)``).

Scaling: every meta-model sees the loads scaled per load to [−1, 1], u = load / HALF_RANGE
(:func:`to_unit`), so a design over ``scale`` × the box has u ∈ [−scale, scale]. A fitted S_T is a
matrix per unit of u (``S``, shape (poses, loads)) and, divided column by column by HALF_RANGE,
per unit of normalised load (``S_per_load``). Errors follow :mod:`mechlib.metamodels.metrics`:
max |error| as % of each pose component's largest |value| over the held-out runs (Table 5's
convention).
"""

from __future__ import annotations

import itertools
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from mechlib import doe, screening
from mechlib.metamodels import designs, linear, metrics, quadratic
from mechlib.metamodels.families import RANGE_RTOL
from mechlib.parallelogram import published as pub
from mechlib.params import check_float, check_int, check_matrix

LOAD_NAMES: tuple[str, ...] = ("A_x", "A_y", "B")
"""The loads, in column order."""
POSE_NAMES: tuple[str, ...] = ("u_x/L", "u_y/L", "phi")
"""The pose components, in column order (φ in rad)."""
N_LOADS = len(LOAD_NAMES)
HALF_RANGE = np.array(
    [np.abs(levels).max() for levels in (pub.A_X_LEVELS, pub.A_Y_LEVELS, pub.B_LEVELS)]
)
"""Half-width of each load's range (10, 20, 3): the published sweep's largest |A_x|, |A_y|, |B|."""
SCREENING_RUNS = 8
"""Runs of the default screening design: the smallest Plackett–Burman design with columns
beyond the three loads (four dummies), so that Lenth has inactive effects to estimate from."""
ZERO_EFFECT = 1e-6
"""Effects at most this share of a pose component's largest |effect| count as 0 before Lenth's
method: round-off of exact zeros (a noise-free truth), which would otherwise set its PSE (the
same threshold as the HexFlex's screening on FE data)."""


def _box_text(scale: float) -> str:
    pairs = zip(LOAD_NAMES, scale * HALF_RANGE, strict=True)
    bounds = ", ".join(f"{n} in [{-h:g}, {h:g}]" for n, h in pairs)
    return f"{scale:g} × the box ({bounds})"


def check_scale(scale: float) -> float:
    """Return ``scale`` (a fraction of the load box) as a float in (0, 1], else ValueError."""
    return check_float("scale", scale, low=0.0, high=1.0, low_open=True)


def check_loads(loads: ArrayLike, *, scale: float = 1.0, name: str = "loads") -> np.ndarray:
    """Return ``loads`` as a finite (runs, 3) float array inside ``scale`` × the box.

    ``loads`` are rows (A_x, A_y, B), at least one; ``scale`` in (0, 1] bounds |load j| by
    scale · HALF_RANGE[j] (to a relative 1e-12); ``name`` is the parameter named in the error.

    Raises
    ------
    ValueError
        Not (runs, 3), no run, non-finite, or a load outside the range (named with its value and
        run, and the range allowed).
    """
    scale = check_scale(scale)
    x = check_matrix(name, loads, shape=(None, N_LOADS))
    if len(x) == 0:
        raise ValueError(f"{name} must hold at least one run (A_x, A_y, B), got none")
    over = np.abs(x) > scale * HALF_RANGE * (1 + RANGE_RTOL)
    if over.any():
        i, j = np.argwhere(over)[0]
        raise ValueError(
            f"{name} must lie within {_box_text(scale)}, got {LOAD_NAMES[j]} = {x[i, j]:g} in "
            f"run {i}"
        )
    return x


def check_poses(poses: ArrayLike, n_runs: int, *, name: str = "poses") -> np.ndarray:
    """Return ``poses`` as a finite (n_runs, 3) float array (u_x/L, u_y/L, φ), else ValueError."""
    return check_matrix(name, poses, shape=(n_runs, len(POSE_NAMES)))


def to_unit(loads: ArrayLike, *, scale: float = 1.0) -> np.ndarray:
    """Loads scaled per load to [−1, 1]: u = load / HALF_RANGE (loads checked within ``scale`` ×
    the box, so |u| ≤ scale). Returns an array (runs, 3)."""
    return check_loads(loads, scale=scale) / HALF_RANGE


# --- Screening -----------------------------------------------------------------------------


class ScreeningDesign(NamedTuple):
    """A two-level screening design of the three loads."""

    coded: np.ndarray
    """(runs, runs − 1) levels ±1: the loads on columns 0, 1, 2, dummy columns after them."""
    loads: np.ndarray
    """(runs, 3) the loads to run: ± ``fraction`` · HALF_RANGE from the first three columns."""
    fraction: float
    """The fraction of each load's range its two levels stand at."""


def load_columns(coded: ArrayLike) -> tuple[int, ...]:
    """The first three columns (in lexicographic order) of a two-level design on which the loads
    form a full 2³ factorial (8 distinct level combinations), or as many as the runs allow.

    In pyDOE3's 8-run Plackett–Burman design column 2 is the product of columns 0 and 1: loads on
    the first three columns would run only 4 combinations (each twice), alias B's effect with the
    A_x·A_y interaction and leave every dummy exactly 0; on columns (0, 1, 3) they run all 8.

    Raises
    ------
    RuntimeError
        If no triple does (not seen for a Plackett–Burman design).
    """
    x = doe.check_design(coded, two_level=True)
    want = min(len(x), 2**N_LOADS)
    for cols in itertools.combinations(range(x.shape[1]), N_LOADS):
        if len(np.unique(x[:, cols], axis=0)) == want:
            return cols
    raise RuntimeError(f"no three columns of the {x.shape} design run {want} distinct loads")


def screening_design(fraction: float = 1.0, n_runs: int = SCREENING_RUNS) -> ScreeningDesign:
    """Plackett–Burman screening design of the three loads at ± ``fraction`` of their ranges.

    The saturated design of :func:`mechlib.doe.plackett_burman`, its columns reordered so that
    A_x, A_y and B lie on columns 0, 1, 2: the design's first three columns on which they form a
    full factorial (:func:`load_columns`), the other columns after them in their order. Those are
    dummies: their effects (the aliased interactions, or 0) give Lenth's method inactive effects
    to estimate its pseudo standard error from.

    Parameters
    ----------
    fraction : float
        Where the two levels stand, as a fraction of each load's half-range, in (0, 1]; 1, the
        range's ends, is the thesis's choice (Table 2 at ±1 N, its whole range).
    n_runs : int
        Runs, a multiple of 4 from 8 (four dummy columns) to 48.

    Returns
    -------
    ScreeningDesign
        ``coded`` (runs, runs − 1), ``loads`` (runs, 3) and ``fraction``.

    Raises
    ------
    ValueError
        ``fraction`` or ``n_runs`` out of range.
    """
    fraction = check_float("fraction", fraction, low=0.0, high=1.0, low_open=True)
    n_runs = check_int("n_runs", n_runs, low=SCREENING_RUNS, high=48)
    full = doe.plackett_burman(n_runs)
    cols = load_columns(full)
    coded = full[:, [*cols, *(c for c in range(full.shape[1]) if c not in cols)]]
    return ScreeningDesign(coded, fraction * HALF_RANGE * coded[:, :N_LOADS], fraction)


class Screening(NamedTuple):
    """Main effects of a screening design and Lenth's analysis, per pose component."""

    effects: np.ndarray
    """(columns, 3): mean pose at the + level minus at the − level, loads first, then dummies."""
    lenth: list[screening.Lenth]
    """Lenth's analysis of each pose component (over every column's effect)."""
    active: np.ndarray
    """(3, 3) bool: load i is active on pose component j (|effect| > Lenth's ME)."""
    dominant: np.ndarray
    """(3, 3) bool: load i's |effect| is at least 1 % of component j's largest (any column)."""
    dummies_active: np.ndarray
    """(3,) int: dummy columns found active per pose component (interactions, or false alarms)."""


def screen(
    coded: ArrayLike, poses: ArrayLike, *, alpha: float = 0.05, zero_tol: float = ZERO_EFFECT
) -> Screening:
    """Main effects and Lenth's method for the poses of a :func:`screening_design`.

    Parameters
    ----------
    coded : array_like, shape (runs, columns)
        The design's ``coded`` levels (±1, balanced columns), the loads on columns 0, 1, 2 and at
        least one dummy after them.
    poses : array_like, shape (runs, 3)
        The truth's poses for the design's ``loads``.
    alpha : float
        Two-sided level of Lenth's margin of error, in (0, 0.5].
    zero_tol : float
        Effects at most ``zero_tol`` × a component's largest |effect| count as 0 (round-off of a
        noise-free truth's exact zeros), in [0, 1).

    Returns
    -------
    Screening

    Raises
    ------
    ValueError
        A design that is not two-level and balanced, has fewer than 4 columns, or whose run count
        differs from the poses'; ``alpha`` or ``zero_tol`` out of range.
    """
    x = doe.check_design(coded, two_level=True)
    if x.shape[1] < N_LOADS + 1:
        raise ValueError(
            f"coded must have at least {N_LOADS + 1} columns (the 3 loads and a dummy), got "
            f"{x.shape[1]}"
        )
    y = check_poses(poses, len(x))
    zero_tol = check_float("zero_tol", zero_tol, low=0.0, high=1.0)
    if zero_tol == 1.0:
        raise ValueError(f"zero_tol must be in [0, 1), got {zero_tol!r}")
    eff = screening.main_effects(x, y)
    eff = np.where(np.abs(eff) <= zero_tol * np.abs(eff).max(axis=0), 0.0, eff)
    lenths = screening.lenth_columns(eff, alpha=alpha)
    active = screening.active_columns(eff, lenths)
    return Screening(
        effects=eff,
        lenth=lenths,
        active=active[:N_LOADS],
        dominant=screening.dominant_columns(eff)[:N_LOADS],
        dummies_active=active[N_LOADS:].sum(axis=0),
    )


# --- Space-filling designs -----------------------------------------------------------------


def uniform_design(n_runs: int, seed: int, *, scale: float = 1.0) -> np.ndarray:
    """A uniform (space-filling) design of the loads over ``scale`` × the box.

    The Latin hypercube of :func:`mechlib.metamodels.designs.space_filling_design` (optimised on
    the centred L2 discrepancy), three columns, mapped to ± ``scale`` · HALF_RANGE.

    Parameters
    ----------
    n_runs : int
        Runs, 2 to 100 000.
    seed : int
        Seed of the design, ≥ 0.
    scale : float
        Fraction of the box, in (0, 1].

    Returns
    -------
    numpy.ndarray, shape (n_runs, 3)
        Loads (A_x, A_y, B).
    """
    scale = check_scale(scale)
    unit = designs.space_filling_design(n_runs, scale, seed, n_forces=N_LOADS)["forces"]
    return unit * HALF_RANGE


def held_out_design(n_runs: int, seed: int, *, scale: float = 1.0) -> np.ndarray:
    """Random validation loads, uniform over ``scale`` × the box (:func:`mechlib.doe.random_design`,
    run by run: the first k runs are the design of k runs). Use another seed than the training
    design's.

    Returns
    -------
    numpy.ndarray, shape (n_runs, 3)
    """
    scale = check_scale(scale)
    return scale * HALF_RANGE * doe.random_design(n_runs, N_LOADS, seed)


# --- The thesis's meta-models --------------------------------------------------------------


def _check_runs(loads: np.ndarray, need: int, model: str) -> None:
    if len(loads) < need:
        raise ValueError(
            f"loads must have at least {need} runs for {model} ({need} coefficients per pose "
            f"component for 3 loads), got {len(loads)}"
        )


def fit_st(loads: ArrayLike, poses: ArrayLike, *, intercept: bool = False) -> dict[str, np.ndarray]:
    """The linear load → pose model S_T (Eq 7) fitted by least squares on scaled loads.

    :func:`mechlib.metamodels.linear.fit_linear` on u = load / HALF_RANGE: ψ ≈ b0 + S u.

    Parameters
    ----------
    loads : array_like, shape (runs, 3)
        Training loads inside the box; runs ≥ 3 (≥ 4 with ``intercept``).
    poses : array_like, shape (runs, 3)
        Their true poses.
    intercept : bool
        Fit b0 too (Eq 6 has β0; Eq 7 has none).

    Returns
    -------
    dict
        ``S`` (3, 3) per unit of scaled load; ``S_per_load`` (3, 3) = S / HALF_RANGE per unit of
        normalised load; ``b0`` (3,); ``residuals`` (runs, 3); ``rank``.

    Raises
    ------
    ValueError
        Shapes, loads outside the box, or too few runs.
    """
    u = to_unit(loads)
    y = check_poses(poses, len(u))
    _check_runs(u, N_LOADS + int(intercept), "S_T" + (" with intercept" if intercept else ""))
    fit = linear.fit_linear(u, y, intercept=intercept)
    return {**fit, "S_per_load": fit["S"] / HALF_RANGE}


def fit_eq6(loads: ArrayLike, poses: ArrayLike) -> dict[str, object]:
    """The full second-order model of Eq 6 fitted by least squares on scaled loads.

    :func:`mechlib.metamodels.quadratic.fit_quadratic` on u = load / HALF_RANGE: 1, u_i, u_i²,
    u_i u_j (10 terms for 3 loads); :func:`mechlib.metamodels.quadratic.quadratic_parts` and
    ``second_order_ratio`` read the result.

    Parameters
    ----------
    loads : array_like, shape (runs, 3)
        Training loads inside the box, runs ≥ 10.
    poses : array_like, shape (runs, 3)

    Returns
    -------
    dict
        ``coef`` (10, 3) on scaled loads, ``names`` ("1", "t0" … for u_0 = A_x/10 …),
        ``residuals`` (runs, 3).

    Raises
    ------
    ValueError
        Shapes, loads outside the box, or fewer than 10 runs.
    """
    u = to_unit(loads)
    y = check_poses(poses, len(u))
    _check_runs(u, quadratic.quadratic_features(u[:1])[0].shape[1], "Eq 6")
    return quadratic.fit_quadratic(u, y)


def predict_fit(fit: dict[str, object], loads: ArrayLike) -> np.ndarray:
    """Poses (runs, 3) of a :func:`fit_st` or :func:`fit_eq6` fit at loads (runs, 3) in the box."""
    return metrics.predict_fit(fit, to_unit(loads))


def holdout_errors(
    fit: dict[str, object], loads: ArrayLike, poses: ArrayLike
) -> dict[str, np.ndarray | float]:
    """Errors of a :func:`fit_st` or :func:`fit_eq6` fit on held-out runs, per pose component.

    Parameters
    ----------
    fit : dict
        The fit.
    loads : array_like, shape (runs, 3)
        Held-out loads inside the box (not the training runs).
    poses : array_like, shape (runs, 3)
        Their true poses.

    Returns
    -------
    dict
        The arrays (3,) of :func:`mechlib.metamodels.metrics.error_metrics` — ``max_range_pct``
        (max |error| as % of the component's largest |value| over these runs), ``maxabs``,
        ``rmse``, ``max_rel_pct`` — and ``worst_pct``, the largest ``max_range_pct`` (a float).
    """
    x = check_loads(loads)
    out = metrics.error_metrics(check_poses(poses, len(x)), predict_fit(fit, x))
    out["worst_pct"] = float(out["max_range_pct"].max())
    return out
