"""Gaussian-process (Kriging) meta-models: the one implementation behind the thesis chapter's
non-polynomial meta-model (ordinary Kriging, ``trend="constant"``) and the ``gp`` family of
:mod:`mechlib.metamodels.families` (regression Kriging on a linear trend, ``trend="linear"``).

One scikit-learn process per output, on inputs scaled to the validated range (u = x / amplitude
∈ [−1, 1]) and normalised targets, with the kernel c · (RBF(ℓ) + η δ): a relative nugget η
rather than a free white-noise level. FE responses are noise-free, and with a free noise level
the likelihood drives it to its bound and the lengths to infinity, where the kernel matrix's
condition number passed 1e18 on the parallelogram's runs: its predictions then moved by 1.6 % of
themselves between two BLAS kernels of one machine (measured for commit e774242). With
η ≥ ``NUGGET_BOUNDS[0]`` the condition number is at most 1 + n / η (n runs), about 3e10 for 300
runs, and the parallelogram's fits agree to 2e-6 of themselves across the SkylakeX, Haswell and
Sandybridge kernels. A fit whose inputs carry round-off of their own (the indicator error model
of :mod:`.correction`) can still move more: see its record's tolerance.

The hyper-parameters (log c, log ℓ, log η) are the likelihood's optimum within the bounds below
(on noise-free linear runs ℓ ends on its upper bound and η on its floor), not wherever an
optimiser happened to stop: L-BFGS-B runs with no relative-decrease stop (``ftol = 0``) until its
projected gradient is below ``GTOL`` (or it can no longer decrease the objective in floating
point), from the unit start and ``RESTARTS`` seeded starts; the best likelihood wins. scikit-
learn's default stop (``ftol`` ≈ 2e-9) left two of the parallelogram's full-box fits on a
plateau of white noise, at 81 % of full scale where the optimum gives 11 % (commit e774242).
The optimiser evaluates the likelihood through :mod:`.gp_likelihood`: scikit-learn's values and
gradients bit for bit, at a third of the time on 256 runs.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from mechlib.blas import one_thread
from mechlib.metamodels import linear
from mechlib.metamodels.gp_likelihood import NegLogLikelihood
from mechlib.params import check_choice, check_float, check_int, check_matrix

TRENDS = ("constant", "linear")
"""Mean functions: ``constant`` (ordinary Kriging), ``linear`` (regression Kriging on a linear
least-squares trend with intercept)."""
RESTARTS = 2
"""Seeded optimiser starts per output besides the unit start."""
AMPLITUDE_BOUNDS = (1e-5, 1e5)
"""Bounds of the process variance c (normalised targets)."""
LENGTH_BOUNDS = (1e-2, 1e3)
"""Bounds of the RBF length scales, in units of the validated range."""
NUGGET = 1e-6
"""Initial relative nugget η."""
NUGGET_BOUNDS = (1e-8, 1e-1)
"""Bounds of the relative nugget η: its floor bounds the kernel matrix's condition number."""
GTOL = 1e-9
"""Projected-gradient stop of L-BFGS-B on the negative log marginal likelihood."""
MAXITER = 20_000
"""Largest number of L-BFGS-B iterations per start."""


@dataclass(frozen=True)
class GaussianProcess:
    """A fitted Gaussian-process meta-model (one process per output).

    Attributes
    ----------
    trend : str
        One of ``TRENDS``.
    amplitude : float
        Input scale: the processes see x / amplitude.
    S, b0 : numpy.ndarray
        Linear trend, poses ≈ b0 + (x / amplitude) @ S.T (zero for the constant trend, whose
        mean the processes' normalisation carries).
    models : list
        One fitted ``sklearn.gaussian_process.GaussianProcessRegressor`` per output.
    """

    trend: str
    amplitude: float
    S: np.ndarray
    b0: np.ndarray
    models: list

    def hyperparameters(self) -> np.ndarray:
        """(outputs, 2 + inputs) array of log c, log ℓ₁ … log ℓ_k, log η per output."""
        return np.array([m.kernel_.theta for m in self.models])


def _optimiser(obj_func, initial_theta: np.ndarray, bounds: np.ndarray):
    """L-BFGS-B to a projected gradient of ``GTOL`` (scikit-learn's ``optimizer`` protocol)."""
    from scipy.optimize import minimize

    res = minimize(
        obj_func,
        initial_theta,
        method="L-BFGS-B",
        jac=True,
        bounds=bounds,
        options={"ftol": 0.0, "gtol": GTOL, "maxiter": MAXITER, "maxfun": 2 * MAXITER},
    )
    return res.x, res.fun


class _LeanOptimiser:
    """:func:`_optimiser` on :class:`.gp_likelihood.NegLogLikelihood` (the same values and
    gradients as the ``obj_func`` scikit-learn passes, without its kernel objects' bookkeeping):
    set ``regressor`` before fitting; its training data are read when the optimiser is called."""

    def __init__(self) -> None:
        self.regressor = None

    def __call__(self, obj_func, initial_theta: np.ndarray, bounds: np.ndarray):
        gp = self.regressor
        if gp is None:
            raise RuntimeError("the optimiser's regressor must be set before fitting, got None")
        objective = NegLogLikelihood(gp.X_train_, gp.y_train_, gp.alpha)
        return _optimiser(objective, initial_theta, bounds)


def fit_gp(
    design: object,
    responses: object,
    *,
    seed: int = 0,
    trend: str = "constant",
    amplitude: float | None = None,
) -> GaussianProcess:
    """Fit one Gaussian process per output.

    Parameters
    ----------
    design : array_like, shape (runs, inputs)
    responses : array_like, shape (runs, outputs)
    seed : int
        Seed of the optimiser's restarts (non-negative).
    trend : str
        One of ``TRENDS``.
    amplitude : float, optional
        Input scale (> 0); default max |design|.

    Returns
    -------
    GaussianProcess

    Raises
    ------
    ValueError
        Mismatched shapes, an unknown trend, a negative seed or a non-positive amplitude.
    """
    from sklearn.exceptions import ConvergenceWarning
    from sklearn.gaussian_process import GaussianProcessRegressor
    from sklearn.gaussian_process.kernels import RBF, ConstantKernel, WhiteKernel

    x = check_matrix("design", design)
    y = check_matrix("responses", responses, shape=(x.shape[0], None))
    seed = check_int("seed", seed, low=0)
    trend = check_choice("trend", trend, TRENDS)
    top = float(np.abs(x).max()) or 1.0
    amplitude = check_float("amplitude", top if amplitude is None else amplitude, low=0.0,
                            low_open=True)  # fmt: skip
    u = x / amplitude
    if trend == "linear":
        fit = linear.fit_linear(u, y, intercept=True)
        s, b0, target = fit["S"], fit["b0"], fit["residuals"]
    else:
        s, b0, target = np.zeros((y.shape[1], x.shape[1])), np.zeros(y.shape[1]), y
    models = []
    for j in range(y.shape[1]):
        kernel = ConstantKernel(1.0, AMPLITUDE_BOUNDS) * (
            RBF(np.ones(x.shape[1]), LENGTH_BOUNDS) + WhiteKernel(NUGGET, NUGGET_BOUNDS)
        )
        optimiser = _LeanOptimiser()
        gp = GaussianProcessRegressor(
            kernel,
            optimizer=optimiser,
            normalize_y=True,
            n_restarts_optimizer=RESTARTS,
            random_state=seed,
        )
        optimiser.regressor = gp
        # one BLAS thread: the same digits whatever the machine's cores (threaded BLAS moved the
        # predictions of a 128-run fit by 2 % of full scale, through the optimiser's path)
        with one_thread(), warnings.catch_warnings():  # an optimum on a bound: expected
            warnings.filterwarnings("ignore", category=ConvergenceWarning)
            models.append(gp.fit(u, target[:, j]))
        optimiser.regressor = None  # no cycle kept in the fitted model
    return GaussianProcess(trend, amplitude, s, b0, models)


def predict_gp(gp: GaussianProcess, design: object) -> np.ndarray:
    """Predictions of a :func:`fit_gp` model.

    Parameters
    ----------
    gp : GaussianProcess
    design : array_like, shape (runs, inputs)

    Returns
    -------
    numpy.ndarray, shape (runs, outputs)
    """
    x = check_matrix("design", design, shape=(None, gp.S.shape[1]))
    return predict_scaled(gp, x / gp.amplitude)


def predict_scaled(gp: GaussianProcess, u: np.ndarray) -> np.ndarray:
    """Predictions for inputs already divided by ``gp.amplitude`` (no checks: the fast path)."""
    with one_thread():
        return gp.b0 + u @ gp.S.T + np.column_stack([m.predict(u) for m in gp.models])
