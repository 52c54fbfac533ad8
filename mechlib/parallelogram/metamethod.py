"""Beyond the thesis on the parallelogram flexure: non-linear meta-model families, their learning
curves on held-out runs, the largest load range each keeps within an error budget, and a
real-time polynomial distilled from the best of them.

The functions of :mod:`mechlib.metamodels` (``families``, ``scoring``, ``study``, ``realtime``)
on the three loads, with the conventions of :mod:`.method`: loads (runs, 3) rows (A_x, A_y, B)
inside ``scale`` × the box ±HALF_RANGE, poses (runs, 3) rows (u_x/L, u_y/L, φ), the truth given as
data. Every family is fitted on the loads scaled per load, u = load / HALF_RANGE ∈ [−scale, scale]
(:func:`.method.to_unit`), with the validated range ``amplitude = scale`` of its
:class:`~mechlib.metamodels.families.Surrogate` (so the polynomial bases and the Gaussian
process's lengths see u / scale ∈ [−1, 1]); :func:`predict_family` takes loads, not u. Errors:
max |error| as % of each pose component's largest |value| over the held-out runs, worst
component (:func:`mechlib.metamodels.scoring.score`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from mechlib.metamodels import designs, realtime, scoring, study
from mechlib.metamodels.families import FAMILIES, Surrogate, fit_surrogate, n_terms, predict
from mechlib.parallelogram.method import (
    HALF_RANGE,
    N_LOADS,
    check_loads,
    check_poses,
    check_scale,
    to_unit,
)
from mechlib.params import check_choice, check_float, check_int

BUDGET_PCT = 1.0
"""Default error budget: largest error as % of full scale."""


def check_families(families: Sequence[str]) -> list[str]:
    """``families`` as a list of distinct names from ``FAMILIES`` (at least one), else
    ValueError naming the allowed ones."""
    fams = [check_choice("families", f, FAMILIES) for f in families]
    if not fams or len(set(fams)) != len(fams):
        raise ValueError(
            f"families must list distinct names from {list(FAMILIES)}, at least one, got "
            f"{list(families)}"
        )
    return fams


def check_enough_runs(family: str, n_runs: int, *, name: str = "loads") -> None:
    """ValueError unless ``n_runs`` training runs are enough for ``family`` on three loads
    (:func:`mechlib.metamodels.families.n_terms`)."""
    need = n_terms(family, N_LOADS)
    if n_runs < need:
        raise ValueError(
            f"{name} must have at least {need} runs for the {family} family (its minimum for 3 "
            f"loads), got {n_runs}"
        )


def _training(
    loads: ArrayLike, poses: ArrayLike, scale: float, name: str = "loads"
) -> tuple[np.ndarray, np.ndarray]:
    """Scaled loads u (runs, 3) within ``scale`` and poses (runs, 3); ``name`` names the loads
    (and, its last word made "poses", the poses) in an error."""
    u = check_loads(loads, scale=scale, name=name) / HALF_RANGE
    return u, check_poses(poses, len(u), name=name.removesuffix("loads") + "poses")


def nested_design(n_runs: int, seed: int, *, scale: float = 1.0) -> np.ndarray:
    """Scrambled Sobol' loads over ``scale`` × the box, whose first 2^k runs are balanced designs
    themselves (:func:`mechlib.metamodels.designs.sobol_design`): the training runs of a learning
    curve.

    Parameters
    ----------
    n_runs : int
        Runs, a power of two from 2 to 100 000.
    seed : int
        Seed of the scrambling, ≥ 0.
    scale : float
        Fraction of the box, in (0, 1].

    Returns
    -------
    numpy.ndarray, shape (n_runs, 3)
    """
    scale = check_scale(scale)
    return designs.sobol_design(n_runs, scale, seed, n_forces=N_LOADS)["forces"] * HALF_RANGE


def fit_family(
    family: str, loads: ArrayLike, poses: ArrayLike, *, scale: float = 1.0, seed: int = 0
) -> Surrogate:
    """A named meta-model family fitted on training runs over ``scale`` × the box.

    Parameters
    ----------
    family : str
        One of :data:`mechlib.metamodels.families.FAMILIES` (``linear`` is S_T without
        intercept, ``quadratic`` Eq 6, then ``cubic``, ``gp``, ``pce``).
    loads : array_like, shape (runs, 3)
        Training loads within ``scale`` × the box; runs at least the family's minimum
        (``n_terms(family, 3)``: 3, 10, 20, 4, 10).
    poses : array_like, shape (runs, 3)
        Their true poses.
    scale : float
        The validated range, a fraction of the box in (0, 1]: predictions are refused beyond it.
    seed : int
        Seed of the ``gp`` restarts and the ``pce`` folds.

    Returns
    -------
    Surrogate
        Inputs the scaled loads u, ``amplitude`` = ``scale``.

    Raises
    ------
    ValueError
        Unknown family, shapes, loads outside ``scale`` × the box, too few runs.
    """
    check_choice("family", family, FAMILIES)
    scale = check_scale(scale)
    u, y = _training(loads, poses, scale)
    check_enough_runs(family, len(u))
    return fit_surrogate(family, u, y, amplitude=scale, seed=seed)


def predict_family(surrogate: Surrogate, loads: ArrayLike) -> np.ndarray:
    """Poses (runs, 3) a :func:`fit_family` (or distilled) model predicts at loads (runs, 3),
    which must lie within its validated ``surrogate.amplitude`` × the box."""
    return predict(surrogate, to_unit(loads, scale=surrogate.amplitude))


def score_family(
    surrogate: Surrogate, loads: ArrayLike, poses: ArrayLike
) -> dict[str, np.ndarray | float]:
    """Errors of a fitted model on held-out runs within its validated range:
    :func:`mechlib.metamodels.scoring.score` (``max_range_pct`` (3,), ``rmse`` (3,), ``maxabs``,
    ``max_rel_pct``, and ``worst_pct`` the worst component's % of full scale)."""
    u = to_unit(loads, scale=surrogate.amplitude)
    return scoring.score(surrogate, u, check_poses(poses, len(u)))


def learning_curves(
    families: Sequence[str],
    loads: ArrayLike,
    poses: ArrayLike,
    val_loads: ArrayLike,
    val_poses: ArrayLike,
    sizes: Sequence[int],
    *,
    scale: float = 1.0,
    seed: int = 0,
) -> dict[str, object]:
    """Held-out error of each family against its number of training runs (nested subsets).

    :func:`mechlib.metamodels.study.learning_curve` on scaled loads: the first ``n`` training
    runs are the subset of size ``n`` (use a :func:`nested_design`, whose power-of-two
    prefixes are balanced).

    Parameters
    ----------
    families : sequence of str
        Distinct names from ``FAMILIES``.
    loads, poses : array_like, shape (runs, 3)
        The training design within ``scale`` × the box and its poses.
    val_loads, val_poses : array_like, shape (runs, 3)
        Held-out runs within ``scale`` × the box.
    sizes : sequence of int
        Training sizes, increasing, each at most the training runs; the largest at least every
        family's minimum (a smaller size gives NaN for a family that needs more).
    scale : float
        The validated range of every fit, a fraction of the box in (0, 1].
    seed : int
        Seed of the families' own randomness.

    Returns
    -------
    dict
        ``sizes`` (m,), ``families``, ``worst_pct`` (families, m), ``max_range_pct`` and
        ``rmse`` (families, m, 3): NaN where a size is below the family's minimum.

    Raises
    ------
    ValueError
        Unknown or repeated families, shapes, loads out of range, sizes not increasing or beyond
        the runs, or a family that cannot be fitted even at the largest size.
    """
    fams = check_families(families)
    scale = check_scale(scale)
    u, y = _training(loads, poses, scale)
    vu, vy = _training(val_loads, val_poses, scale, name="val_loads")
    n = [check_int("sizes", s, low=1, high=len(u)) for s in sizes]
    if not n:
        raise ValueError("sizes must list at least one training size, got none")
    for fam in fams:
        check_enough_runs(fam, max(n), name="sizes (the largest)")
    return study.learning_curve(fams, u, y, vu, vy, n, amplitude=scale, seed=seed)


def budget_scales(
    families: Sequence[str],
    training: Mapping[float, tuple[ArrayLike, ArrayLike]],
    held_out: Mapping[float, tuple[ArrayLike, ArrayLike]],
    *,
    budget_pct: float = BUDGET_PCT,
    seed: int = 0,
) -> dict[str, object]:
    """The largest load range (a scale of the box) each family keeps within an error budget.

    At each scale s every family able to (enough runs) is fitted on that scale's training runs
    and scored on its held-out runs; :func:`mechlib.metamodels.study.budget_ranges` then finds
    the largest s within the budget at that scale and at every smaller one.

    Parameters
    ----------
    families : sequence of str
        Distinct names from ``FAMILIES``.
    training : mapping
        Scale s in (0, 1] → (loads (runs, 3) within s × the box, their poses (runs, 3)).
    held_out : mapping
        The same scales → held-out (loads, poses) within s × the box.
    budget_pct : float
        Largest error allowed, % of full scale, in (0, 100].
    seed : int
        Seed of the families' own randomness.

    Returns
    -------
    dict
        ``scales`` (m,) increasing; ``families``; ``worst_pct`` (families, m), 0 where not
        fitted; ``fitted`` (families, m) bool; ``largest`` (families,) the largest scale within
        the budget, 0.0 where the smallest already misses it.

    Raises
    ------
    ValueError
        Unknown families, scales that differ between the mappings or lie outside (0, 1], runs
        outside their scale's box, shapes, ``budget_pct`` out of range.
    """
    fams = check_families(families)
    budget_pct = check_float("budget_pct", budget_pct, low=0.0, high=100.0, low_open=True)
    scales = sorted(check_scale(s) for s in training)
    if not scales or scales != sorted(check_scale(s) for s in held_out):
        raise ValueError(
            f"held_out must hold the same scales as training, at least one; got "
            f"{sorted(held_out)} and {sorted(training)}"
        )
    models: dict[str, dict[float, Surrogate]] = {f: {} for f in fams}
    cases = {}
    for s in scales:
        u, y = _training(*training[s], s, name=f"training[{s:g}] loads")
        cases[s] = _training(*held_out[s], s, name=f"held_out[{s:g}] loads")
        for fam in (f for f in fams if n_terms(f, N_LOADS) <= len(u)):
            models[fam][s] = fit_surrogate(fam, u, y, amplitude=s, seed=seed)
    out = study.budget_ranges(models, cases, budget_pct)
    return {
        "scales": out.pop("amplitudes"),
        "families": fams,
        **out,
    }


def cv_errors(
    families: Sequence[str],
    loads: ArrayLike,
    poses: ArrayLike,
    *,
    scale: float = 1.0,
    seed: int = 0,
) -> dict[str, float]:
    """Seeded cross-validated worst error [% of full scale] of each family on its training runs
    within ``scale`` × the box (:func:`mechlib.metamodels.scoring.cross_validate`, ``CV_FOLDS``
    folds, or leave-one-out when a fold would leave fewer runs than the family needs, as
    :func:`mechlib.metamodels.scoring.cv_folds` decides for 3 loads). Chooses a model without
    held-out runs.

    Returns
    -------
    dict
        Family → worst component's cross-validated error [% of full scale].

    Raises
    ------
    ValueError
        As :func:`fit_family`; a family needing more runs than leave-one-out leaves.
    """
    fams = check_families(families)
    scale = check_scale(scale)
    u, y = _training(loads, poses, scale)
    out = {}
    for fam in fams:
        check_enough_runs(fam, len(u) - 1, name="loads (minus one, for a cross-validation)")
        folds = scoring.cv_folds(fam, len(u), n_inputs=N_LOADS)
        cv = scoring.cross_validate(fam, u, y, amplitude=scale, folds=folds, seed=seed)
        out[fam] = cv["worst_pct"]
    return out


class RealTime(NamedTuple):
    """A real-time model distilled from the best family."""

    teacher: str
    """The family distilled: the smallest cross-validated error."""
    teacher_model: Surrogate
    """That family fitted on every training run."""
    tol_pct: float
    """How far the student may stray from its teacher [% of full scale] (goal minus CV error)."""
    student: Surrogate
    """The Legendre polynomial of the lowest degree within ``tol_pct`` (family ``distilled``)."""
    degree: int
    """Its total degree."""
    distill_errors: dict[int, float]
    """Degree → distillation error [% of full scale] of every degree tried."""


def realtime_model(
    loads: ArrayLike,
    poses: ArrayLike,
    cv_pct: Mapping[str, float],
    *,
    goal_pct: float = BUDGET_PCT,
    scale: float = 1.0,
    degrees: tuple[int, ...] = (3, 4, 5, 6),
    seed: int = 0,
) -> RealTime:
    """A polynomial real-time model distilled from the family with the smallest CV error.

    :func:`mechlib.metamodels.realtime.choose_teacher` picks the teacher among ``cv_pct`` and
    the student's tolerance; the teacher is fitted on the training runs and
    :func:`~mechlib.metamodels.realtime.distill_to` fits Legendre polynomials in u / scale on
    a Sobol' sample of the teacher (no truth runs), the lowest degree within the tolerance kept.

    Parameters
    ----------
    loads, poses : array_like, shape (runs, 3)
        Training runs within ``scale`` × the box (those ``cv_pct`` was computed on).
    cv_pct : mapping
        Family → cross-validated worst error [%] (:func:`cv_errors`), at least one.
    goal_pct : float
        Accuracy goal of teacher and student together [% of full scale], in (0, 100].
    scale : float
        Validated range, a fraction of the box in (0, 1].
    degrees : tuple of int
        Candidate total degrees, increasing, 1 to ``realtime.MAX_DEGREE``.
    seed : int
        Seed of the teacher's fit and of the distillation's Sobol' samples.

    Returns
    -------
    RealTime

    Raises
    ------
    ValueError
        Unknown families in ``cv_pct``, as :func:`fit_family` and ``distill_to``.
    """
    for fam in cv_pct:
        check_choice("cv_pct (its families)", fam, FAMILIES)
    teacher, tol = realtime.choose_teacher(dict(cv_pct), goal_pct)
    model = fit_family(teacher, loads, poses, scale=scale, seed=seed)
    student, errors = realtime.distill_to(model, tol, degrees=tuple(degrees), seed=seed)
    degree = int(student.state["exponents"].max())
    return RealTime(teacher, model, tol, student, degree, errors)
