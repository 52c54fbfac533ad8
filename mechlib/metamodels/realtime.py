"""Real-time force → pose models: a low-fidelity model corrected by few full runs, and a slow,
accurate model distilled into a polynomial that evaluates a pose in microseconds.

Correction (:func:`corrected`, :func:`cross_validate_corrected`): the low-fidelity model (e.g.
the hyper-reduced ROM, :func:`mechlib.metamodels.families.wrap_model`) plus a Gaussian process
fitted to what it misses on the full runs, ``poses − low(forces)`` — the additive
low-fidelity-plus-discrepancy form of multi-fidelity Kriging (Kennedy and O'Hagan's model with a
unit scale factor), fitted with this package's ``gp`` family. The other kind of correction,
an error model on the low-fidelity model's own error indicators instead of the forces
(:func:`indicator_correction`, :func:`indicator_curve`; ROMES), is compared with it.
:func:`choose_teacher` picks the model to distil and the tolerance of its distillation.

Distillation (:func:`distill`, :func:`distill_to`): the teacher evaluated on a scrambled Sobol'
sample of its validated box (cheap: no FE), and a Legendre polynomial of total degree ``d``
(the ``pce`` family's orthonormal basis) fitted to those evaluations by least squares. The
student's error against its teacher is measured on a second, independent Sobol' sample; the
smallest degree within a tolerance is kept. A pose costs one basis evaluation and one small
matrix product.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence

import numpy as np
from scipy.stats import qmc
from threadpoolctl import threadpool_limits

from mechlib.metamodels.families import (
    Surrogate,
    check_forces,
    fit_surrogate,
    legendre_products,
    predict_array,
    total_degree_exponents,
    wrap_model,
)
from mechlib.metamodels.metrics import error_metrics
from mechlib.metamodels.scoring import CV_FOLDS, cross_validate
from mechlib.params import check_float, check_int, check_matrix

DISTILLED = "distilled"
"""Family of a distilled model (a Legendre polynomial; predicted as the ``pce`` family is)."""
DISTILL_SAMPLES = 2**14
"""Teacher evaluations a distillation fits to (a power of two: a balanced Sobol' sample)."""
DISTILL_CHECK = 2**12
"""Teacher evaluations, on an independent Sobol' sample, its student is checked against."""
MAX_DEGREE = 8
"""Largest total degree :func:`distill` accepts (six forces: 3003 terms)."""


def corrected(low: Surrogate, forces: object, poses: object, seed: int = 0) -> Surrogate:
    """``low`` plus a Gaussian process fitted to its misses on full runs.

    Parameters
    ----------
    low : Surrogate
        The low-fidelity model; its validated range is the corrected model's.
    forces, poses : array_like, shapes (runs, inputs), (runs, outputs)
        Full runs inside ``low``'s range, at least two.
    seed : int
        Seed of the Gaussian process's optimiser restarts.

    Returns
    -------
    Surrogate
        Family ``physics`` (:func:`mechlib.metamodels.families.wrap_model`), predicting
        ``low(f) + gp(f)``.
    """
    x = check_forces(low, forces)
    y = check_matrix("poses", poses, shape=(x.shape[0], low.n_outputs))
    with threadpool_limits(limits=1, user_api="blas"):
        miss = y - predict_array(low, x)
    gp = fit_surrogate("gp", x, miss, amplitude=low.amplitude, seed=seed)

    def poses_of(f: np.ndarray) -> np.ndarray:
        return predict_array(low, f) + predict_array(gp, f)

    name = f"{low.state.get('name', low.family)} + Gaussian-process correction"
    return wrap_model(name, poses_of, amplitude=low.amplitude, n_inputs=low.n_inputs)


def cross_validate_corrected(
    low: Surrogate, forces: object, poses: object, folds: int = CV_FOLDS, seed: int = 0
) -> dict[str, np.ndarray]:
    """Seeded k-fold cross-validated errors of :func:`corrected` on its full runs.

    The correction of each fold is fitted on the other folds' misses; the errors are those of
    :func:`mechlib.metamodels.scoring.score` on the pooled out-of-fold predictions of
    ``low + correction``.

    Parameters
    ----------
    low : Surrogate
        The low-fidelity model.
    forces, poses : array_like, shapes (runs, inputs), (runs, outputs)
        The full runs, inside ``low``'s range.
    folds : int
        Number of folds, 2 to runs.
    seed : int
        Seed of the fold shuffle and of the corrections' optimiser.

    Returns
    -------
    dict
        The arrays (outputs,) of :func:`mechlib.metamodels.metrics.error_metrics` and
        ``worst_pct``, the largest ``max_range_pct`` (a float).
    """
    x = check_forces(low, forces)
    y = check_matrix("poses", poses, shape=(x.shape[0], low.n_outputs))
    with threadpool_limits(limits=1, user_api="blas"):
        base = predict_array(low, x)
    cv = cross_validate("gp", x, y - base, amplitude=low.amplitude, folds=folds, seed=seed)
    out = error_metrics(y, base + cv["predicted"])
    out["worst_pct"] = float(out["max_range_pct"].max())
    return out


def indicator_correction(
    features: object, misses: object, seed: int = 0
) -> Callable[[np.ndarray], np.ndarray]:
    """An error model on indicators: a Gaussian process from a low-fidelity model's error
    indicators (e.g. its dual-weighted residuals,
    :func:`mechlib.hexflex.rom.indicators.dual_weighted_residuals`) to its misses.

    The ROMES form (Drohmann & Carlberg 2015): the inputs are what the low-fidelity model
    computes about its own error, not the forces. Each indicator is divided by its largest
    |value| on the training runs, and the ``gp`` family is fitted on those (its linear trend plus
    a process); new indicators beyond the training ones are extrapolated, not refused.

    Parameters
    ----------
    features : array_like (runs, k)
        Indicators at the full runs, at least two runs; no column all zero.
    misses : array_like (runs, outputs)
        Full poses minus the low-fidelity model's there.
    seed : int
        Seed of the Gaussian process's optimiser restarts.

    Returns
    -------
    callable
        Indicators (n, k) → predicted misses (n, outputs).
    """
    x = check_matrix("features", features)
    y = check_matrix("misses", misses, shape=(x.shape[0], None))
    if x.shape[0] < 2:
        raise ValueError(f"features must have at least 2 runs, got {x.shape[0]}")
    scale = np.abs(x).max(axis=0)
    if not scale.all():
        raise ValueError(
            "features must have no all-zero column, got all zeros in columns "
            f"{np.flatnonzero(scale == 0).tolist()}"
        )
    gp = fit_surrogate("gp", x / scale, y, amplitude=1.0, seed=seed)

    def predicted(new: np.ndarray) -> np.ndarray:
        u = check_matrix("features", new, shape=(None, x.shape[1])) / scale
        with threadpool_limits(limits=1, user_api="blas"):
            return predict_array(gp, u)

    return predicted


def indicator_curve(
    sizes: Sequence[int],
    train: tuple[object, object, object],
    held_out: tuple[object, object, object],
    seed: int = 0,
) -> np.ndarray:
    """Largest error (% of range, worst component) on held-out runs of the low-fidelity model
    corrected by :func:`indicator_correction` fitted on the first ``n`` training runs, per
    ``n`` of ``sizes``.

    Parameters
    ----------
    sizes : sequence of int
        Training runs used, each 2 to the number of training runs.
    train, held_out : tuple (low, features, poses)
        Per run: the low-fidelity poses, the indicators and the full poses.
    seed : int
        As :func:`indicator_correction`.
    """
    low_t, feat_t, y_t = (check_matrix(n, a) for n, a in zip(_PARTS, train, strict=True))
    low_v, feat_v, y_v = (check_matrix(n, a) for n, a in zip(_PARTS, held_out, strict=True))
    out = []
    for n in sizes:
        n = check_int("sizes", n, low=2, high=len(y_t))
        model = indicator_correction(feat_t[:n], y_t[:n] - low_t[:n], seed=seed)
        out.append(error_metrics(y_v, low_v + model(feat_v))["max_range_pct"].max())
    return np.array(out)


_PARTS = ("low-fidelity poses", "features", "poses")


def indicator_correlation(indicators: object, misses: object) -> np.ndarray:
    """Pearson correlation of each indicator column with the miss of the same output column
    (an indicator that estimates its own component's miss scores near 1).

    Parameters
    ----------
    indicators, misses : array_like (runs, outputs)
        At least three runs; no constant column.
    """
    a = check_matrix("indicators", indicators)
    b = check_matrix("misses", misses, shape=a.shape)
    if len(a) < 3:
        raise ValueError(f"indicators must have at least 3 runs, got {len(a)}")
    a, b = a - a.mean(axis=0), b - b.mean(axis=0)
    norms = np.linalg.norm(a, axis=0) * np.linalg.norm(b, axis=0)
    if not norms.all():
        raise ValueError("indicators and misses must have no constant column")
    return (a * b).sum(axis=0) / norms


def choose_teacher(cv_pct: dict[str, float], goal_pct: float) -> tuple[str, float]:
    """The model to distil, and how far its student may stray from it.

    The teacher is the candidate with the smallest cross-validated error (chosen without
    held-out runs). Its student may spend what that error leaves of the accuracy goal, so that
    teacher and student together stay within it; if the teacher alone uses the goal up, a tenth
    of its own error.

    Parameters
    ----------
    cv_pct : dict
        Candidate name → cross-validated worst error [% of range], at least one, finite ≥ 0.
    goal_pct : float
        Accuracy goal [% of range], in (0, 100].

    Returns
    -------
    name : str
    tol_pct : float
        The distillation tolerance [% of range] for :func:`distill_to`.
    """
    goal_pct = check_float("goal_pct", goal_pct, low=0.0, high=100.0, low_open=True)
    if not cv_pct:
        raise ValueError("cv_pct must name at least one candidate, got none")
    for name, e in cv_pct.items():
        check_float(f"cv_pct[{name!r}]", e, low=0.0)
    name = min(cv_pct, key=cv_pct.get)
    room = goal_pct - cv_pct[name]
    return name, room if room > 0 else 0.1 * cv_pct[name]


def _sample(n_inputs: int, n: int, seed: int) -> np.ndarray:
    """A scrambled Sobol' sample of ``n`` (a power of two) points in [-1, 1]^n_inputs."""
    n = check_int("n_samples", n, low=2, high=2**20)
    if n & (n - 1):
        raise ValueError(f"n_samples must be a power of two, got {n}")
    u = qmc.Sobol(d=n_inputs, scramble=True, seed=seed).random_base2(n.bit_length() - 1)
    return 2 * u - 1


def _fit_legendre(teacher: Surrogate, u: np.ndarray, y: np.ndarray, degree: int) -> Surrogate:
    """The least-squares Legendre polynomial of total ``degree`` through teacher values ``y``
    at the points ``u`` (scaled to [-1, 1])."""
    degree = check_int("degree", degree, low=1, high=MAX_DEGREE)
    exps = total_degree_exponents(teacher.n_inputs, degree)
    if len(exps) >= len(u):
        raise ValueError(
            f"n_samples must exceed the {len(exps)} terms of degree {degree}, got {len(u)}"
        )
    with threadpool_limits(limits=1, user_api="blas"):
        coef, *_ = np.linalg.lstsq(legendre_products(u, exps), y, rcond=None)
    name = teacher.state.get("name", teacher.family)
    state = {"exponents": exps, "coef": coef, "teacher": name}
    return Surrogate(DISTILLED, teacher.amplitude, teacher.n_inputs, teacher.n_outputs, state)


def _teach(teacher: Surrogate, n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """A Sobol' sample of ``n`` points of the teacher's box (scaled) and its poses there."""
    u = _sample(teacher.n_inputs, n, check_int("seed", seed, low=0))
    with threadpool_limits(limits=1, user_api="blas"):
        return u, predict_array(teacher, teacher.amplitude * u)


def _error_pct(student: Surrogate, u: np.ndarray, y: np.ndarray) -> float:
    with threadpool_limits(limits=1, user_api="blas"):
        guess = predict_array(student, student.amplitude * u)
    return float(error_metrics(y, guess)["max_range_pct"].max())


def distill(
    teacher: Surrogate, degree: int, n_samples: int = DISTILL_SAMPLES, seed: int = 0
) -> Surrogate:
    """A Legendre polynomial of total ``degree`` fitted to ``teacher`` on ``n_samples`` points.

    Parameters
    ----------
    teacher : Surrogate
        Any model (fitted or wrapped); evaluated on a scrambled Sobol' sample of its box.
    degree : int
        Total degree, 1 to :data:`MAX_DEGREE`; the basis must have fewer terms than samples.
    n_samples : int
        Teacher evaluations, a power of two.
    seed : int
        Seed of the Sobol' scrambling.

    Returns
    -------
    Surrogate
        Family :data:`DISTILLED`, state ``exponents``, ``coef`` and ``teacher`` (its name).
    """
    check_int("degree", degree, low=1, high=MAX_DEGREE)
    u, y = _teach(teacher, n_samples, seed)
    return _fit_legendre(teacher, u, y, degree)


def distillation_error_pct(
    student: Surrogate, teacher: Surrogate, n_check: int = DISTILL_CHECK, seed: int = 1
) -> float:
    """Largest |student − teacher| over a Sobol' sample scrambled with ``seed`` (use another
    seed than the distillation's, so that the points are new), as % of the teacher's largest
    |pose component| there, worst component."""
    return _error_pct(student, *_teach(teacher, n_check, seed))


def distill_to(
    teacher: Surrogate,
    tol_pct: float,
    degrees: tuple[int, ...] = (3, 4, 5, 6),
    n_samples: int = DISTILL_SAMPLES,
    seed: int = 0,
) -> tuple[Surrogate, dict[int, float]]:
    """The lowest of ``degrees`` whose student stays within ``tol_pct`` of its teacher.

    The teacher is evaluated once on the fitting sample and once on the check sample
    (:data:`DISTILL_CHECK` points, ``seed + 1``), whatever the number of degrees tried.

    Parameters
    ----------
    teacher : Surrogate
        The model to distil (fitted or wrapped).
    tol_pct : float
        Largest distillation error allowed (:func:`distillation_error_pct`), in (0, 100].
    degrees : tuple of int
        Candidate total degrees, increasing.
    n_samples, seed
        As :func:`distill`.

    Returns
    -------
    student : Surrogate
        The first student within ``tol_pct``, or the most accurate if none is.
    errors : dict
        Degree → distillation error [%] of every degree tried (in order, up to the one kept).
    """
    tol_pct = check_float("tol_pct", tol_pct, low=0.0, high=100.0, low_open=True)
    if not degrees or any(b <= a for a, b in itertools.pairwise(degrees)):
        raise ValueError(f"degrees must be increasing and not empty, got {list(degrees)}")
    for d in degrees:
        check_int("degrees", d, low=1, high=MAX_DEGREE)
    fit_u, fit_y = _teach(teacher, n_samples, seed)
    check_u, check_y = _teach(teacher, DISTILL_CHECK, seed + 1)
    errors: dict[int, float] = {}
    best: tuple[float, Surrogate] | None = None
    for d in degrees:
        student = _fit_legendre(teacher, fit_u, fit_y, d)
        errors[d] = _error_pct(student, check_u, check_y)
        if errors[d] <= tol_pct:
            return student, errors
        if best is None or errors[d] < best[0]:
            best = (errors[d], student)
    return best[1], errors
