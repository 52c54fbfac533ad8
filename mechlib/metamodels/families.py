"""Named force → pose meta-model families: fit, predict, size rules.

A fitted meta-model is a :class:`Surrogate`: the family's name, the validated force range (the
half-width of the training box, N) and the family's fitted state. ``predict`` refuses forces
outside the validated range unless told to extrapolate.

Families (``FAMILIES``): ``linear``, S_T of Eq 7 (least squares, no intercept,
:func:`.linear.fit_linear`); ``quadratic``, Eq 6 (second order with interactions and intercept,
:func:`.quadratic.fit_quadratic`); ``cubic``, every monomial of total degree ≤ 3 (84 terms for six
forces), least squares on the forces divided by the validated range; ``gp``, a Gaussian process
(Kriging) per output on the residual of a linear trend (regression Kriging,
:func:`.gaussian_process.fit_gp`); ``pce``, sparse polynomial chaos: a Legendre basis (orthonormal
for uniform forces on the validated range) of total degree ≤ ``PCE_DEGREE``, whose terms
scikit-learn's ``LassoLarsCV`` (LARS stopped by seeded k-fold cross-validation) selects per output
— those that entered its path up to the chosen penalty — and least squares fits (hybrid LARS, as
OpenTURNS's ``LeastSquaresMetaModelSelection``), unless they are as many as the runs (then LARS's
own coefficients are kept); degree 4 or 5 was measured worse below 300 runs.

A model not fitted here (a physics-based reduced-order model) joins the scoring, timing and
inversion as family ``PHYSICS`` through :func:`wrap_model`.

Libraries: scikit-learn's GP and LARS (already locked), chosen by measurement against SMT 2.15,
OpenTURNS 1.27 and chaospy 4.3 (a one-off script, not kept in the repository): Eq 8's S_T with
2 % on every entry plus ~3 % quadratic, ~1 % cubic and a 1 % sine term; LHS random-cd training
of 30 / 100 / 300 runs, 1000 uniform validation runs; worst max |error| as % of full scale; times on
a shared, loaded 2-core machine, one BLAS thread (compare them only as ratios); µs per pose
batched for the GPs, for one pose for the PCEs (total degree 3):

=========================================  ====================  ==================  ==============
model                                      error % (30/100/300)  fit s (30/100/300)  µs/pose
=========================================  ====================  ==================  ==============
sklearn GP on a linear trend (``gp``) †   2.6 / 0.56 / 0.089    0.4 / 1.9 / 82      3 / 16 / 44
sklearn GP, constant mean                  2.5 / 2.7 / 0.23      1.6 / 5.9 / 66      7 / 23 / 101
OpenTURNS GP, linear basis                 3.1 / 0.69 / 0.11     1.3 / 3.5 / 27      41 / 156 / 137
SMT KRG, linear trend                      4.1 / 0.96 / —        19 / 29 / > 600     15 / 83 / —
SMT KRG, constant trend                    5.0 / 3.1 / 0.37      46 / 42 / 538       88 / 84 / 515
Legendre + sklearn LassoLarsCV (``pce``)   1.9 / 3.2 / 1.7       0.5 / 0.6 / 0.4     66 – 165
chaospy + sklearn LarsCV                   3.1 / 1.0 / 1.4       2.5 / 2.0 / 2.4     94k – 207k
OpenTURNS FunctionalChaos, LARS + LOO      4.4 / 4.3 / 1.7       4.9 / 0.5 / 6.8     380 – 3600
=========================================  ====================  ==================  ==============

† measured with a free white-noise level and scikit-learn's default optimiser stop, before the
kernel and stop of :mod:`.gaussian_process` (a relative nugget, a projected-gradient stop).

For reference: ``linear`` 2.8 / 3.0 / 2.7, ``quadratic`` 7.4 / 2.7 / 2.8, ``cubic`` — / 3.3 / 1.8.
No other library was clearly better (OpenTURNS's GP is close to scikit-learn's, slower to
predict; chaospy's PCE is better at 100 runs, worse at 30, a thousand times slower per pose).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from mechlib.blas import one_thread
from mechlib.memo import array_memo
from mechlib.metamodels import gaussian_process, legendre, linear, pce, quadratic
from mechlib.params import check_choice, check_float, check_int, check_matrix

FAMILIES = ("linear", "quadratic", "cubic", "gp", "pce")
"""Names accepted by :func:`fit_surrogate`."""
LABELS = {
    "linear": "linear (Eq 7)",
    "quadratic": "quadratic (Eq 6)",
    "cubic": "cubic",
    "gp": "Gaussian process",
    "pce": "polynomial chaos",
}
"""Each family's name on a page."""
PHYSICS = "physics"
"""Family of a model given as a function (:func:`wrap_model`), not fitted here."""
CUBIC_DEGREE = 3
"""Total degree of the ``cubic`` family."""
PCE_DEGREE = 3
"""Largest total degree of the ``pce`` basis (its LARS path selects among these terms)."""
PCE_CV_FOLDS = 5
"""Folds of the cross-validation that stops the LARS path of each ``pce`` output."""
PCE_MAX_ITER = 500
"""Largest number of LARS steps per ``pce`` output (more than the 84 basis terms of degree 3)."""
RANGE_RTOL = 1e-12
"""Relative slack of the validated-range check (round-off of scaled designs)."""


@dataclass(frozen=True)
class Surrogate:
    """A fitted meta-model.

    Attributes
    ----------
    family : str
        One of ``FAMILIES``.
    amplitude : float
        Validated force range [N]: the training design's half-width; inputs are in ±amplitude.
    n_inputs, n_outputs : int
        Number of forces and of pose components.
    state : object
        The family's fitted state (coefficients or the library's models).
    """

    family: str
    amplitude: float
    n_inputs: int
    n_outputs: int
    state: object


def n_terms(family: str, n_inputs: int) -> int:
    """Smallest number of training runs a family accepts for ``n_inputs`` forces.

    For the polynomial families this is the number of coefficients per output (``linear`` k,
    ``quadratic`` 1 + 2k + k(k−1)/2, ``cubic`` C(k+3, 3)); ``gp`` needs its linear trend (k + 1)
    and ``pce`` its k-fold LARS (two runs per fold).

    Parameters
    ----------
    family : str
        One of ``FAMILIES``.
    n_inputs : int
        Number of forces, ≥ 1.

    Returns
    -------
    int

    Raises
    ------
    ValueError
        Unknown family or ``n_inputs`` < 1.
    """
    check_choice("family", family, FAMILIES)
    k = check_int("n_inputs", n_inputs, low=1)
    return {
        "linear": k,
        "quadratic": 1 + 2 * k + k * (k - 1) // 2,
        "cubic": math.comb(k + CUBIC_DEGREE, CUBIC_DEGREE),
        "gp": k + 1,
        "pce": 2 * PCE_CV_FOLDS,
    }[family]


@array_memo(maxsize=32)  # a chapter fits some families to the same runs twice
def fit_surrogate(
    family: str,
    forces: object,
    poses: object,
    *,
    amplitude: float,
    seed: int = 0,
) -> Surrogate:
    """Fit a named meta-model family to training runs.

    Parameters
    ----------
    family : str
        One of ``FAMILIES``.
    forces : array_like, shape (runs, inputs)
        Training forces [N].
    poses : array_like, shape (runs, outputs)
        Training poses (µm, µrad).
    amplitude : float
        Validated force range [N]: the training design's half-width (at least max |forces|);
        predictions are refused outside ±amplitude.
    seed : int
        Seed of the ``gp`` optimiser restarts and of the ``pce`` cross-validation folds.

    Returns
    -------
    Surrogate

    Raises
    ------
    ValueError
        Unknown family (the allowed ones are listed), mismatched shapes, fewer runs than the
        family's :func:`n_terms`, an amplitude below max |forces|.
    """
    check_choice("family", family, FAMILIES)
    x = check_matrix("forces", forces)
    y = check_matrix("poses", poses, shape=(x.shape[0], None))
    seed = check_int("seed", seed, low=0)
    need = n_terms(family, x.shape[1])
    if len(x) < need:
        raise ValueError(
            f"the {family} family needs at least {need} training runs (its number of terms for "
            f"{x.shape[1]} forces), got {len(x)}"
        )
    top = float(np.abs(x).max())
    amplitude = check_float("amplitude", amplitude, low=0.0, low_open=True)
    if top > amplitude * (1 + RANGE_RTOL):
        raise ValueError(f"amplitude must be >= max |forces| = {top} N, got {amplitude}")
    u = x / amplitude
    with one_thread():  # same digits with any BLAS threads
        if family == "linear":
            state = {"S": linear.fit_linear(x, y)["S"]}
        elif family == "quadratic":
            state = {"coef": quadratic.fit_quadratic(x, y)["coef"]}
        elif family == "cubic":
            exps = pce.total_degree_exponents(x.shape[1], CUBIC_DEGREE)
            coef, *_ = np.linalg.lstsq(pce.monomials(u, exps), y, rcond=None)
            state = {"exponents": exps, "coef": coef}
        elif family == "gp":
            state = gaussian_process.fit_gp(u, y, seed=seed, trend="linear", amplitude=1.0)
        else:
            state = pce.fit_pce(u, y, seed, PCE_DEGREE, PCE_CV_FOLDS, PCE_MAX_ITER)
    return Surrogate(family, amplitude, x.shape[1], y.shape[1], state)


def name_of(surrogate: Surrogate) -> str:
    """What a surrogate is: its ``PHYSICS`` model's name, else its family's."""
    if surrogate.family == PHYSICS:
        return str(surrogate.state["name"])
    return surrogate.family


def wrap_model(
    name: str, poses: Callable[[np.ndarray], np.ndarray], amplitude: float, n_inputs: int = 6
) -> Surrogate:
    """A forward model given as a function, as a :class:`Surrogate` of family ``PHYSICS``
    (scored, timed and inverted as the fitted families are).

    Parameters
    ----------
    name : str
        What the model is (kept in ``state["name"]``).
    poses : callable
        ``poses(forces (runs, n_inputs)) -> (runs, n_inputs)`` poses; it must accept any force
        within ±amplitude.
    amplitude : float
        Force range [N] the model is valid in, > 0.
    n_inputs : int
        Number of forces (= pose components), ≥ 1.

    Returns
    -------
    Surrogate
    """
    if not callable(poses):
        raise ValueError(f"poses must be callable (forces -> poses), got {type(poses).__name__}")
    amplitude = check_float("amplitude", amplitude, low=0.0, low_open=True)
    n_inputs = check_int("n_inputs", n_inputs, low=1)
    return Surrogate(PHYSICS, amplitude, n_inputs, n_inputs, {"name": str(name), "poses": poses})


def check_forces(surrogate: Surrogate, forces: object, *, extrapolate: bool = False) -> np.ndarray:
    """Return ``forces`` as a (runs, inputs) array inside the surrogate's validated range.

    Parameters
    ----------
    surrogate : Surrogate
    forces : array_like, shape (runs, inputs)
        Forces [N].
    extrapolate : bool
        Accept forces outside ±amplitude.

    Returns
    -------
    numpy.ndarray, shape (runs, inputs)

    Raises
    ------
    ValueError
        Wrong number of columns, or (unless ``extrapolate``) a force outside ±amplitude.
    """
    x = check_matrix("forces", forces, shape=(None, surrogate.n_inputs))
    if not extrapolate and x.size:
        top = float(np.abs(x).max())
        if top > surrogate.amplitude * (1 + RANGE_RTOL):
            raise ValueError(
                f"forces must be within the validated range [-{surrogate.amplitude}, "
                f"{surrogate.amplitude}] N of this {surrogate.family} meta-model, got a force of "
                f"{top} N in absolute value"
            )
    return x


def predict_array(surrogate: Surrogate, x: np.ndarray) -> np.ndarray:
    """Predictions for an already checked (runs, inputs) float array (no range check).

    The fast path of :func:`predict`, for latency measurements and Newton iterations; call it
    inside ``one_thread()`` for thread-independent digits.

    Parameters
    ----------
    surrogate : Surrogate
    x : numpy.ndarray, shape (runs, inputs)
        Forces [N], as :func:`check_forces` returns them.

    Returns
    -------
    numpy.ndarray, shape (runs, outputs)
    """
    s = surrogate.state
    if surrogate.family == PHYSICS:
        return np.asarray(s["poses"](x), dtype=float)
    u = x / surrogate.amplitude
    if surrogate.family == "linear":
        return x @ s["S"].T
    if surrogate.family == "quadratic":
        return quadratic.quadratic_features(x)[0] @ s["coef"]
    if surrogate.family == "cubic":
        return pce.monomials(u, s["exponents"]) @ s["coef"]
    if surrogate.family == "gp":
        return gaussian_process.predict_scaled(s, u)
    return legendre.evaluate(u, s["exponents"], s["coef"])


def predict(surrogate: Surrogate, forces: object, *, extrapolate: bool = False) -> np.ndarray:
    """Poses (runs, outputs) a meta-model predicts for forces (runs, inputs) [N].

    Parameters
    ----------
    surrogate : Surrogate
        From :func:`fit_surrogate`.
    forces : array_like, shape (runs, inputs)
    extrapolate : bool
        Allow forces outside the validated range (default: refuse them).

    Returns
    -------
    numpy.ndarray, shape (runs, outputs)

    Raises
    ------
    ValueError
        Wrong shape, or a force outside the validated range (see :func:`check_forces`).
    """
    x = check_forces(surrogate, forces, extrapolate=extrapolate)
    with one_thread():
        return predict_array(surrogate, x)
