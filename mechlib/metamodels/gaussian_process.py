"""A Gaussian process per output on the raw forces: the thesis chapter's non-polynomial
meta-model (the virtual-experiments page). The ``gp`` family of :mod:`mechlib.metamodels.families`
is a different model (regression Kriging on a linear trend, scaled forces, bounded kernel).
"""

from __future__ import annotations

import warnings

import numpy as np
from sklearn.exceptions import ConvergenceWarning

from mechlib.metamodels.linear import design_and_responses
from mechlib.params import check_int, check_matrix


def fit_gp(design: object, responses: object, seed: int = 0) -> list[object]:
    """One scikit-learn Gaussian process per output (constant × RBF + white noise kernel,
    normalised targets, seeded optimiser restarts).

    On noise-free responses that are linear in the factors the optimal RBF length scales are
    infinite and the optimal noise level zero, so the optimiser ends on those bounds, where
    L-BFGS-B's line search may also stop with status ABNORMAL; scikit-learn's
    ConvergenceWarnings saying either are expected here and not shown (any other warning is):
    the fitted processes are judged by their errors on validation data.

    Parameters
    ----------
    design : array_like, shape (runs, factors)
    responses : array_like, shape (runs, outputs)
    seed : int
        Seed of the optimiser restarts.

    Returns
    -------
    list
        One fitted ``GaussianProcessRegressor`` per output.
    """
    from sklearn.gaussian_process import GaussianProcessRegressor
    from sklearn.gaussian_process.kernels import RBF, ConstantKernel, WhiteKernel

    x, y = design_and_responses(design, responses)
    seed = check_int("seed", seed, low=0)
    out = []
    for j in range(y.shape[1]):
        kernel = ConstantKernel(1.0) * RBF(length_scale=np.ones(x.shape[1])) + WhiteKernel(1e-6)
        gp = GaussianProcessRegressor(
            kernel, normalize_y=True, n_restarts_optimizer=2, random_state=seed
        )
        with warnings.catch_warnings():
            for message in (".*close to the specified (upper|lower) bound", "lbfgs failed to"):
                warnings.filterwarnings("ignore", message=message, category=ConvergenceWarning)
            out.append(gp.fit(x, y[:, j]))
    return out


def predict_gp(models: list[object], design: object) -> np.ndarray:
    """Predictions of :func:`fit_gp` models.

    Parameters
    ----------
    models : list
        From :func:`fit_gp`.
    design : array_like, shape (runs, factors)

    Returns
    -------
    numpy.ndarray, shape (runs, outputs)
    """
    x = check_matrix("design", design)
    return np.column_stack([m.predict(x) for m in models])
