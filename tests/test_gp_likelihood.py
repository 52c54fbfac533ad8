"""The lean likelihood of mechlib.metamodels.gp_likelihood against scikit-learn's, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest
from sklearn.gaussian_process import GaussianProcessRegressor
from sklearn.gaussian_process.kernels import RBF, ConstantKernel, WhiteKernel

from mechlib.blas import one_thread
from mechlib.metamodels import gaussian_process as gpm
from mechlib.metamodels.gp_likelihood import NegLogLikelihood

THETAS = 25  # random hyper-parameters compared per training set


def _regressor(x: np.ndarray, y: np.ndarray) -> GaussianProcessRegressor:
    """scikit-learn's regressor with fit_gp's kernel, fitted without optimising."""
    kernel = ConstantKernel(1.0, gpm.AMPLITUDE_BOUNDS) * (
        RBF(np.ones(x.shape[1]), gpm.LENGTH_BOUNDS) + WhiteKernel(gpm.NUGGET, gpm.NUGGET_BOUNDS)
    )
    return GaussianProcessRegressor(kernel, optimizer=None, normalize_y=True).fit(x, y)


@pytest.mark.parametrize(("runs", "inputs"), [(5, 1), (30, 6), (97, 3), (160, 6)])
def test_values_and_gradients_equal_scikit_learns_bit_for_bit(runs: int, inputs: int) -> None:
    rng = np.random.default_rng(runs)
    x = rng.uniform(-1, 1, (runs, inputs))
    y = np.sin(x @ rng.normal(size=inputs)) + 0.1 * x[:, 0] ** 2
    gp = _regressor(x, y)
    lean = NegLogLikelihood(gp.X_train_, gp.y_train_, gp.alpha)
    bounds = gp.kernel_.bounds
    with one_thread():
        for theta in rng.uniform(bounds[:, 0], bounds[:, 1], (THETAS, len(bounds))):
            value, grad = gp.log_marginal_likelihood(theta, eval_gradient=True)
            got_value, got_grad = lean(theta)
            np.testing.assert_array_equal(got_value, -value)
            np.testing.assert_array_equal(got_grad, -grad)
            np.testing.assert_array_equal(lean(theta, eval_gradient=False), -value)


def test_a_matrix_that_is_not_positive_definite_gives_scikit_learns_answer() -> None:
    x = np.zeros((4, 2))  # identical runs: a kernel matrix of rank one without the nugget
    gp = _regressor(x, np.array([0.0, 1.0, 2.0, 3.0]))
    lean = NegLogLikelihood(gp.X_train_, gp.y_train_, alpha=-1.0)  # a jitter that breaks it
    theta = np.array([0.0, 0.0, 0.0, np.log(1e-8)])
    value, grad = lean(theta)
    assert value == np.inf
    np.testing.assert_array_equal(grad, np.zeros(4))
    assert lean(theta, eval_gradient=False) == np.inf


def test_a_target_per_run_is_required() -> None:
    with pytest.raises(ValueError, match="one target a run"):
        NegLogLikelihood(np.zeros((3, 2)), np.zeros((3, 1)), 1e-10)


def test_fit_gp_reaches_the_same_hyperparameters_as_with_scikit_learns_objective(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    rng = np.random.default_rng(7)
    x = rng.uniform(-1, 1, (40, 6))
    y = x @ rng.normal(size=(6, 2)) + 0.05 * np.sin(3 * x[:, :2])
    lean = gpm.fit_gp(x, y, seed=3, trend="linear")

    class SklearnObjective(gpm._LeanOptimiser):
        """The optimiser on the objective scikit-learn passes (its kernel objects)."""

        def __call__(self, obj_func, initial_theta, bounds):
            return gpm._optimiser(obj_func, initial_theta, bounds)

    monkeypatch.setattr(gpm, "_LeanOptimiser", SklearnObjective)
    plain = gpm.fit_gp(x, y, seed=3, trend="linear")
    np.testing.assert_array_equal(lean.hyperparameters(), plain.hyperparameters())
    fresh = rng.uniform(-1, 1, (50, 6))
    np.testing.assert_array_equal(gpm.predict_gp(lean, fresh), gpm.predict_gp(plain, fresh))
