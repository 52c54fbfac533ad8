"""Real-time force → pose models: a slow, accurate model distilled into a polynomial that
evaluates a pose in microseconds.

:func:`choose_teacher` picks the model to distil (e.g. among the corrections of
:mod:`mechlib.metamodels.correction`) and the tolerance of its distillation.

Distillation (:func:`distill`, :func:`distill_to`): the teacher evaluated on a scrambled Sobol'
sample of its validated box (cheap: no FE), and a Legendre polynomial of total degree ``d``
(the ``pce`` family's orthonormal basis) fitted to those evaluations by least squares. The
student's error against its teacher is measured on a second, independent Sobol' sample; the
smallest degree within a tolerance is kept. A pose costs one basis evaluation and one small
matrix product.
"""

from __future__ import annotations

import itertools

import numpy as np
from scipy.stats import qmc

from mechlib.blas import one_thread
from mechlib.metamodels.families import Surrogate, name_of, predict_array
from mechlib.metamodels.metrics import error_metrics
from mechlib.metamodels.pce import legendre_products, total_degree_exponents
from mechlib.params import check_float, check_int

DISTILLED = "distilled"
"""Family of a distilled model (a Legendre polynomial; predicted as the ``pce`` family is)."""
DISTILL_SAMPLES = 2**14
"""Teacher evaluations a distillation fits to (a power of two: a balanced Sobol' sample)."""
DISTILL_CHECK = 2**12
"""Teacher evaluations, on an independent Sobol' sample, its student is checked against."""
DEADLINE_US = 100.0
"""The book's one real-time deadline [µs a pose]: the period of a 10 kHz control loop. The thesis
names no rate; 10 kHz is our choice of a feedback rate for a nano-positioner, not a figure of the
thesis or of the HexFlex's controller. Every timing judgement of the book uses it."""
MAX_DEGREE = 8
"""Largest total degree :func:`distill` accepts (six forces: 3003 terms)."""


def choose_teacher(cv_pct: dict[str, float], goal_pct: float) -> tuple[str, float]:
    """The model to distil, and how far its student may stray from it.

    The teacher is the candidate with the smallest cross-validated error (chosen without
    held-out runs). Its student may spend what that error leaves of the accuracy goal, so that
    teacher and student together stay within it, but at least a tenth of the teacher's own error
    (a teacher at or beyond the goal is still distilled, to within a tenth of its error).

    Parameters
    ----------
    cv_pct : dict
        Candidate name → cross-validated worst error [% of full scale], at least one, finite ≥ 0.
    goal_pct : float
        Accuracy goal [% of full scale], in (0, 100].

    Returns
    -------
    name : str
    tol_pct : float
        The distillation tolerance [% of full scale] for :func:`distill_to`:
        ``max(goal_pct - cv, cv / 10)``, ``cv`` the teacher's error.
    """
    goal_pct = check_float("goal_pct", goal_pct, low=0.0, high=100.0, low_open=True)
    if not cv_pct:
        raise ValueError("cv_pct must name at least one candidate, got none")
    for name, e in cv_pct.items():
        check_float(f"cv_pct[{name!r}]", e, low=0.0)
    name = min(cv_pct, key=cv_pct.get)
    return name, max(goal_pct - cv_pct[name], 0.1 * cv_pct[name])


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
    with one_thread():
        coef, *_ = np.linalg.lstsq(legendre_products(u, exps), y, rcond=None)
    name = name_of(teacher)
    state = {"exponents": exps, "coef": coef, "teacher": name}
    return Surrogate(DISTILLED, teacher.amplitude, teacher.n_inputs, teacher.n_outputs, state)


def _teach(teacher: Surrogate, n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """A Sobol' sample of ``n`` points of the teacher's box (scaled) and its poses there."""
    u = _sample(teacher.n_inputs, n, check_int("seed", seed, low=0))
    with one_thread():
        return u, predict_array(teacher, teacher.amplitude * u)


def _error_pct(student: Surrogate, u: np.ndarray, y: np.ndarray) -> float:
    with one_thread():
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
