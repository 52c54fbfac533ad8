"""Polynomial bases of the meta-model families and the sparse polynomial-chaos fit.

Total-degree exponent sets, monomials (the ``cubic`` family) and products of scaled Legendre
polynomials (the ``pce`` family and a distilled real-time model; :mod:`.legendre` evaluates them
fast), and the hybrid-LARS fit of the ``pce`` family (:mod:`.families` describes it and holds
its degree, folds and iteration limit).
"""

from __future__ import annotations

import itertools
import warnings

import numpy as np


def total_degree_exponents(n_inputs: int, degree: int) -> np.ndarray:
    """Exponents (terms, inputs) of every monomial of total degree ≤ ``degree``, graded order."""
    rows = [np.zeros(n_inputs, dtype=int)]
    for d in range(1, degree + 1):
        for combo in itertools.combinations_with_replacement(range(n_inputs), d):
            rows.append(np.bincount(combo, minlength=n_inputs))
    return np.array(rows)


def monomials(u: np.ndarray, exps: np.ndarray) -> np.ndarray:
    """The monomials ``exps`` (terms, inputs) of the rows of ``u`` (runs, inputs): (runs, terms)."""
    return np.prod(u[:, None, :] ** exps[None, :, :], axis=2)


def legendre_products(u: np.ndarray, exps: np.ndarray) -> np.ndarray:
    """Products of Legendre polynomials √(2k+1) Pₖ (unit variance for uniform u in [-1, 1])."""
    deg = int(exps.max())
    vander = np.polynomial.legendre.legvander(u, deg)  # (runs, inputs, deg + 1)
    vander = vander * np.sqrt(2 * np.arange(deg + 1) + 1)
    cols = np.take_along_axis(vander, exps.T[None, :, :], axis=2)  # (runs, inputs, terms)
    return np.prod(cols, axis=1)


def fit_pce(
    u: np.ndarray, y: np.ndarray, seed: int, degree: int, folds: int, max_iter: int
) -> dict[str, object]:
    """A sparse Legendre chaos fitted to scaled forces ``u`` (runs, inputs) in [-1, 1] and poses
    ``y`` (runs, outputs): per output, the terms of total degree ≤ ``degree`` that entered
    scikit-learn's ``LassoLarsCV`` path (``folds``-fold cross-validation shuffled with ``seed``,
    at most ``max_iter`` LARS steps) up to its chosen penalty, refitted by least squares (LARS's
    own coefficients when they are as many as the runs).

    Returns
    -------
    dict
        ``exponents`` (terms, inputs) and ``coef`` (terms, outputs).
    """
    from sklearn.exceptions import ConvergenceWarning
    from sklearn.linear_model import LassoLarsCV
    from sklearn.model_selection import KFold

    exps = total_degree_exponents(u.shape[1], degree)
    a = legendre_products(u, exps)
    splits = KFold(folds, shuffle=True, random_state=seed)
    coef = np.zeros((len(exps), y.shape[1]))
    for j in range(y.shape[1]):
        scale = float(np.std(y[:, j])) or 1.0
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", category=ConvergenceWarning)
            model = LassoLarsCV(fit_intercept=False, cv=splits, max_iter=max_iter).fit(
                a, y[:, j] / scale
            )
        # the terms that entered the LARS path up to the chosen penalty; least squares fits them
        keep = np.flatnonzero(np.any(model.coef_path_ != 0, axis=1))
        if keep.size < len(u):
            coef[keep, j], *_ = np.linalg.lstsq(a[:, keep], y[:, j], rcond=None)
        else:  # as many terms as runs: least squares would interpolate; keep LARS's shrinkage
            coef[:, j] = model.coef_ * scale
    return {"exponents": exps, "coef": coef}
