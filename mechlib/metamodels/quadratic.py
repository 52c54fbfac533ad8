"""The thesis's full second-order force → pose meta-model (Eq 6): features, fit, its parts.

Designs ``X`` are ``(runs, factors)`` and responses ``Y`` ``(runs, outputs)``, as in
:mod:`mechlib.metamodels.linear`.
"""

from __future__ import annotations

import itertools

import numpy as np

from mechlib.params import check_matrix

NEGLIGIBLE_SECOND_ORDER = 1e-6
"""Largest second-order / linear coefficient ratio (:func:`second_order_ratio`) for "the
quadratic and interaction terms of Eq 6 are negligible"."""


def quadratic_features(design: object) -> tuple[np.ndarray, list[str]]:
    """Columns of the full second-order model of Eq 6: 1, τ_i, τ_i², τ_i τ_j (i < j).

    Parameters
    ----------
    design : array_like, shape (runs, k)

    Returns
    -------
    features : numpy.ndarray, shape (runs, 1 + 2k + k(k-1)/2)
    names : list of str
        ``"1"``, ``"t0"``, ``"t0^2"``, ``"t0*t1"`` …
    """
    x = check_matrix("design", design)
    k = x.shape[1]
    cols, names = [np.ones(len(x))], ["1"]
    cols += [x[:, i] for i in range(k)]
    names += [f"t{i}" for i in range(k)]
    cols += [x[:, i] ** 2 for i in range(k)]
    names += [f"t{i}^2" for i in range(k)]
    for i, j in itertools.combinations(range(k), 2):
        cols.append(x[:, i] * x[:, j])
        names.append(f"t{i}*t{j}")
    return np.column_stack(cols), names


def fit_quadratic(design: object, responses: object) -> dict[str, object]:
    """Least-squares fit of the full second-order model of Eq 6 (see :func:`quadratic_features`).

    Parameters
    ----------
    design : array_like, shape (runs, factors)
    responses : array_like, shape (runs, outputs)

    Returns
    -------
    dict
        ``coef`` (features, outputs), ``names`` of the features, ``residuals`` (runs, outputs).

    Raises
    ------
    ValueError
        If the design has fewer runs than the model has coefficients (28 for six factors).
    """
    a, names = quadratic_features(design)
    y = check_matrix("responses", responses, shape=(a.shape[0], None))
    if a.shape[0] < a.shape[1]:
        raise ValueError(
            f"design needs at least {a.shape[1]} runs for the quadratic model, got {a.shape[0]}"
        )
    coef, *_ = np.linalg.lstsq(a, y, rcond=None)
    return {"coef": coef, "names": names, "residuals": y - a @ coef}


def predict_quadratic(coef: object, design: object) -> np.ndarray:
    """Predictions of a :func:`fit_quadratic` model.

    Parameters
    ----------
    coef : array_like, shape (features, outputs)
        ``fit_quadratic(...)["coef"]``.
    design : array_like, shape (runs, factors)

    Returns
    -------
    numpy.ndarray, shape (runs, outputs)
    """
    a, _ = quadratic_features(design)
    return a @ check_matrix("coef", coef, shape=(a.shape[1], None))


def quadratic_parts(fit: dict[str, object]) -> dict[str, np.ndarray]:
    """The terms of a :func:`fit_quadratic` model by order.

    Parameters
    ----------
    fit : dict
        From :func:`fit_quadratic`.

    Returns
    -------
    dict
        ``b0`` (outputs,); ``S`` (outputs, factors), the linear terms as a linear model's
        matrix; ``second`` (terms, outputs), the squares and products.
    """
    names = list(fit["names"])
    coef = check_matrix("coef", fit["coef"], shape=(len(names), None))
    k = sum("^" not in n and "*" not in n for n in names) - 1  # "1", then "t0" … "t<k-1>"
    return {"b0": coef[0], "S": coef[1 : 1 + k].T, "second": coef[1 + k :]}


def second_order_ratio(fit: dict[str, object]) -> np.ndarray:
    """Largest |second-order coefficient| over largest |linear one| of a :func:`fit_quadratic`
    result ``fit``, per output: an array (outputs,), below ``NEGLIGIBLE_SECOND_ORDER`` where Eq 6's
    quadratic and interaction terms are negligible."""
    parts = quadratic_parts(fit)
    return np.abs(parts["second"]).max(axis=0) / np.abs(parts["S"]).max(axis=1)


def interaction_ratio(fit: dict[str, object]) -> np.ndarray:
    """Largest |two-factor interaction coefficient| (the ``t_i*t_j`` terms, squares left out)
    over largest |linear one| of a :func:`fit_quadratic` result ``fit``, per output: an array
    (outputs,)."""
    names = list(fit["names"])
    coef = check_matrix("coef", fit["coef"], shape=(len(names), None))
    parts = quadratic_parts(fit)
    products = np.array(["*" in n for n in names])
    if not products.any():
        raise ValueError(f"fit has no interaction term among {names}")
    return np.abs(coef[products]).max(axis=0) / np.abs(parts["S"]).max(axis=1)
