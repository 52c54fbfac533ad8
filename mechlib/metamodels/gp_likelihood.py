"""The log marginal likelihood that :mod:`.gaussian_process` maximises, computed without
scikit-learn's kernel objects — the same operations on the same arrays, so the same bits.

scikit-learn evaluates the likelihood of the kernel c · (RBF(ℓ) + η δ) (plus its regressor's
diagonal jitter ``alpha``) through a tree of kernel objects: each evaluation sets the
hyper-parameters through ``get_params``/``set_params``, recomputes the inputs' squared
differences (runs, runs, inputs), multiplies them by the kernel broadcast over their last axis
(a loop of six elements at a time), stacks every gradient into new arrays and allocates an
identity twice. On the meta-model page the kernels' ``__call__`` took 62 of the likelihood's
118 s (cProfile of commit d62e832; 27 s of it in the RBF gradient). :class:`NegLogLikelihood`
keeps the squared differences (one plane per input), the identity and the gradient's array of
one training set and does the remaining arithmetic in scikit-learn's order
(``sklearn.gaussian_process.kernels`` and ``GaussianProcessRegressor.log_marginal_likelihood``
of scikit-learn 1.9): each element is rounded as it is there, and the reductions (Cholesky
factor, solves, ``einsum``) receive equal arrays of equal layout. Its values and gradients equal
scikit-learn's bit for bit — a unit test compares them (``tests/test_gp_likelihood.py``; it
fails if a scikit-learn upgrade changes that order) — so the optimiser takes the same path and
the fits do not move.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import cho_solve, cholesky
from scipy.spatial.distance import pdist, squareform

LOG_2PI = np.log(2 * np.pi)
"""log(2π), as scikit-learn computes it (the likelihood's constant is n / 2 of it)."""


class NegLogLikelihood:
    """Negative log marginal likelihood of normalised targets under c · (RBF(ℓ) + η δ) + α δ,
    and its gradient in θ = (log c, log ℓ₁ … log ℓ_k, log η), as scikit-learn's ``obj_func``.

    Parameters
    ----------
    x : numpy.ndarray, shape (runs, inputs)
        Training inputs (the regressor's ``X_train_``).
    y : numpy.ndarray, shape (runs,)
        Training targets as the regressor sees them (its ``y_train_``: normalised).
    alpha : float
        The regressor's jitter added to the kernel matrix's diagonal (its ``alpha``).
    """

    def __init__(self, x: np.ndarray, y: np.ndarray, alpha: float) -> None:
        x = np.atleast_2d(x)
        if y.ndim != 1 or len(y) != len(x):
            raise ValueError(
                f"y must be one target a run ({len(x)},), got an array of shape {y.shape}"
            )
        self.x = x
        self.y = y[:, np.newaxis]
        self.alpha = alpha
        n, k = x.shape
        self.n_inputs = k
        # squared differences, one (runs, runs) plane per input: the elementwise products below
        # run along whole planes (scikit-learn's (runs, runs, inputs) layout broadcasts the
        # kernel over its last axis, a loop of six elements: 7 of its 8 ms at 256 runs)
        diff2 = (x[:, np.newaxis, :] - x[np.newaxis, :, :]) ** 2
        self.diff2 = np.ascontiguousarray(diff2.transpose(2, 0, 1))
        self.eye = np.eye(n)
        self.diag = np.diag_indices(n)
        self.grad = np.empty((n, n, k + 2))  # the gradient's kernel derivatives, reused
        self.const = n / 2 * LOG_2PI

    def __call__(self, theta: np.ndarray, eval_gradient: bool = True):
        """(−log likelihood, −gradient) at ``theta`` (−log likelihood alone without gradient);
        (inf, zeros) where the kernel matrix is not positive definite, as scikit-learn."""
        k = self.n_inputs
        # KernelOperator / Kernel ``theta`` setters: a scalar exp per scalar, one for ℓ
        c = np.exp(theta[0])
        ell = np.squeeze(np.exp(theta[1 : 1 + k])).astype(float)
        eta = np.exp(theta[1 + k])
        # RBF: pdist of the scaled inputs, exp, square form with a unit diagonal
        dists = pdist(self.x / ell, metric="sqeuclidean")
        r = squareform(np.exp(-0.5 * dists))
        np.fill_diagonal(r, 1)
        # Sum(RBF, White): r + η I, whose off-diagonal terms add an exact zero
        s = r.copy()
        s[self.diag] += eta
        kmat = c * s  # Product(Constant, Sum): np.full(c) * s, element by element
        if eval_gradient:
            # d/dθ in scikit-learn's order: c s; (D² / ℓ²) r c per input; (η I) c, zero off
            # the diagonal; one (runs, runs, parameters) array as ``np.dstack`` makes it
            grad = self.grad
            grad[:, :, 0] = kmat
            if k == 1:  # one length: scikit-learn's isotropic gradient, r times the distances
                grad[:, :, 1] = (r * squareform(dists)) * c
            else:
                rbf = self.diff2 / (ell**2)[:, np.newaxis, np.newaxis]
                rbf *= r
                rbf *= c
                grad[:, :, 1 : 1 + k] = rbf.transpose(1, 2, 0)
            grad[:, :, 1 + k] = 0.0
            grad[(*self.diag, 1 + k)] = eta * c
        kmat[self.diag] += self.alpha
        try:
            low = cholesky(kmat, lower=True, check_finite=False)
        except np.linalg.LinAlgError:
            return (np.inf, -np.zeros_like(theta)) if eval_gradient else np.inf
        a = cho_solve((low, True), self.y, check_finite=False)
        lml = -0.5 * np.einsum("ik,ik->k", self.y, a)
        lml -= np.log(np.diag(low)).sum()
        lml -= self.const
        lml = lml.sum(axis=-1)
        if not eval_gradient:
            return -lml
        inner = np.einsum("ik,jk->ijk", a, a)
        inner -= cho_solve((low, True), self.eye, check_finite=False)[..., np.newaxis]
        g = 0.5 * np.einsum("ijl,jik->kl", inner, grad)
        return -lml, -g.sum(axis=-1)
