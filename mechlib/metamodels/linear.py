"""The thesis's linear force → pose meta-model S_T (Eq 7), its inverse (Eq 9) and their checks.

Conventions: designs ``X`` are ``(runs, factors)``, responses ``Y`` are ``(runs, outputs)`` and a
linear model is the matrix ``S`` of shape ``(outputs, factors)`` with ``Y ≈ X Sᵀ`` (Eq 7).
"""

from __future__ import annotations

import warnings

import numpy as np
from sklearn.exceptions import ConvergenceWarning
from sklearn.linear_model import LassoCV, RidgeCV

from mechlib.params import check_choice, check_matrix

RIDGE_ALPHAS = np.logspace(-8, 4, 49)
"""Penalty grid for ridge regression (leave-one-out selection per response)."""
LASSO_MAX_ITER = 200_000
"""Iteration cap of the coordinate-descent lasso (the data are nearly noise-free)."""

# Thresholds of the claims the book checks on noise-free linear FE data (double precision, a
# compliance of condition number ~10 with unit-norm rows): far above round-off, far below any
# modelling error.
EXACT_INVERSE_TOL = 1e-8
"""Largest max |S⁻¹S − I| for "S_T⁻¹ S_T = I" (Eq 9)."""
ROUND_TRIP_TOL = 1e-10
"""Largest relative pose → force → pose error of :func:`round_trip_error` for an exact inverse."""


def design_and_responses(design: object, responses: object) -> tuple[np.ndarray, np.ndarray]:
    """``design`` (runs, factors) and ``responses`` (runs, outputs) as checked float arrays."""
    x = check_matrix("design", design)
    y = check_matrix("responses", responses, shape=(x.shape[0], None))
    return x, y


def fit_linear(
    design: object, responses: object, *, intercept: bool = False
) -> dict[str, np.ndarray]:
    """Ordinary least-squares fit of ``Y ≈ b0 + X Sᵀ``.

    Parameters
    ----------
    design : array_like, shape (runs, factors)
    responses : array_like, shape (runs, outputs)
    intercept : bool
        Fit ``b0`` too (Eq 6 has β0; Eq 7 has none).

    Returns
    -------
    dict
        ``S`` (outputs, factors), ``b0`` (outputs,), ``residuals`` (runs, outputs), ``rank``.

    Raises
    ------
    ValueError
        If there are fewer runs than coefficients.

    Examples
    --------
    Noise-free responses of a known S (Eq 7) on three columns of a 12-run Plackett–Burman design
    give S back; with an offset, the fit of Eq 6 gives β0 too:

    >>> from mechlib.doe import plackett_burman
    >>> x = plackett_burman(12)[:, :3]
    >>> s_true = np.array([[2.0, 0.0, 1.0], [0.0, 3.0, 0.0], [0.5, 0.0, 4.0]])
    >>> fit = fit_linear(x, x @ s_true.T)
    >>> bool(np.allclose(fit["S"], s_true)), int(fit["rank"])
    (True, 3)
    >>> fit = fit_linear(x, 7.0 + x @ s_true.T, intercept=True)
    >>> bool(np.allclose(fit["b0"], 7.0)), bool(np.allclose(fit["S"], s_true))
    (True, True)
    >>> fit_linear(x[:2], x[:2] @ s_true.T)
    Traceback (most recent call last):
    ...
    ValueError: design needs at least 3 runs for this fit, got 2
    """
    x, y = design_and_responses(design, responses)
    a = np.c_[np.ones(len(x)), x] if intercept else x
    if a.shape[0] < a.shape[1]:
        raise ValueError(f"design needs at least {a.shape[1]} runs for this fit, got {a.shape[0]}")
    coef, _, rank, _ = np.linalg.lstsq(a, y, rcond=None)
    b0 = coef[0] if intercept else np.zeros(y.shape[1])
    s = coef[1:].T if intercept else coef.T
    return {"S": s, "b0": b0, "residuals": y - a @ coef, "rank": np.int64(rank)}


def fit_penalized(
    design: object, responses: object, *, method: str = "ridge"
) -> dict[str, np.ndarray]:
    """Penalized least squares (no intercept), one penalty per response chosen by cross-validation.

    Parameters
    ----------
    design : array_like, shape (runs, factors)
    responses : array_like, shape (runs, outputs)
    method : {"ridge", "lasso"}
        ``ridge``: scikit-learn ``RidgeCV`` with efficient leave-one-out over ``RIDGE_ALPHAS``;
        ``lasso``: ``LassoCV`` with 5-fold cross-validation (gives exact zeros).

    Returns
    -------
    dict
        ``S`` (outputs, factors) and ``alpha`` (outputs,) the selected penalties.

    Raises
    ------
    ValueError
        If ``method`` is not one of the two, or the arrays' shapes do not fit.

    Examples
    --------
    >>> fit_penalized(np.eye(3), np.eye(3), method="elastic")
    Traceback (most recent call last):
    ...
    ValueError: method must be one of ['ridge', 'lasso'], got 'elastic'
    """
    check_choice("method", method, ("ridge", "lasso"))
    x, y = design_and_responses(design, responses)
    s = np.zeros((y.shape[1], x.shape[1]))
    alphas = np.zeros(y.shape[1])
    for j in range(y.shape[1]):
        scale = float(np.std(y[:, j])) or 1.0  # penalties act on standardised responses
        if method == "ridge":
            model = RidgeCV(alphas=RIDGE_ALPHAS, fit_intercept=False).fit(x, y[:, j] / scale)
        else:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ConvergenceWarning)
                model = LassoCV(fit_intercept=False, cv=5, max_iter=LASSO_MAX_ITER).fit(
                    x, y[:, j] / scale
                )
        s[j] = model.coef_ * scale
        alphas[j] = model.alpha_
    return {"S": s, "alpha": alphas}


def predict_linear(s: object, design: object, b0: object | None = None) -> np.ndarray:
    """Pose predictions ``b0 + X Sᵀ`` of a linear model (Eq 7).

    Parameters
    ----------
    s : array_like, shape (outputs, factors)
        The model's matrix, e.g. S_T.
    design : array_like, shape (runs, factors)
    b0 : array_like, shape (outputs,), optional
        Intercepts (none: zero).

    Returns
    -------
    numpy.ndarray, shape (runs, outputs)

    Examples
    --------
    A unit force on the first factor gives the first column of S:

    >>> s = [[2.0, 0.0, 1.0], [0.0, 3.0, 0.0], [0.5, 0.0, 4.0]]
    >>> predict_linear(s, [[1.0, 0.0, 0.0]]).tolist()
    [[2.0, 0.0, 0.5]]
    """
    s = check_matrix("S", s)
    x = check_matrix("design", design, shape=(None, s.shape[1]))
    return x @ s.T + (0.0 if b0 is None else np.asarray(b0, dtype=float))


def unit_ratio(observed: object, predicted: object) -> np.ndarray:
    """Least-squares factor ``c`` per column with ``observed ≈ c · predicted``.

    Used to find the units a table is really printed in: a ratio of 1000 means the table is
    in units a thousand times smaller than the model's.

    Parameters
    ----------
    observed, predicted : array_like, shape (runs, outputs)

    Returns
    -------
    numpy.ndarray, shape (outputs,)
    """
    o = check_matrix("observed", observed)
    p = check_matrix("predicted", predicted, shape=o.shape)
    return np.sum(o * p, axis=0) / np.sum(p * p, axis=0)


def inverse(s: object) -> dict[str, np.ndarray]:
    """Inverse model of Eq 9 and its conditioning.

    Parameters
    ----------
    s : array_like, shape (n, n)
        A square linear model, e.g. S_T.

    Returns
    -------
    dict
        ``S_inv``, ``cond`` (2-norm condition number in the units given), ``cond_scaled``
        (after scaling each row of S to unit 2-norm, which removes the µm-vs-µrad unit choice),
        and ``identity_error`` = max |S_inv S − I|.

    Raises
    ------
    ValueError
        If ``s`` is not square.

    Examples
    --------
    >>> s = np.array([[2.0, 0.0, 1.0], [0.0, 3.0, 0.0], [0.5, 0.0, 4.0]])
    >>> inv = inverse(s)
    >>> bool(inv["identity_error"] < EXACT_INVERSE_TOL)  # S⁻¹ S = I (Eq 9)
    True
    >>> poses = np.array([[1.0, -2.0, 0.5], [0.0, 3.0, -1.0]])
    >>> round_trip_error(s, inv["S_inv"], poses) < ROUND_TRIP_TOL  # pose → force → pose
    True
    >>> inverse(np.ones((2, 3)))
    Traceback (most recent call last):
    ...
    ValueError: S must be square to invert, got shape (2, 3)
    """
    s = check_matrix("S", s)
    if s.shape[0] != s.shape[1]:
        raise ValueError(f"S must be square to invert, got shape {s.shape}")
    s_inv = np.linalg.inv(s)
    rows = s / np.linalg.norm(s, axis=1, keepdims=True)
    return {
        "S_inv": s_inv,
        "cond": np.float64(np.linalg.cond(s)),
        "cond_scaled": np.float64(np.linalg.cond(rows)),
        "identity_error": np.float64(np.max(np.abs(s_inv @ s - np.eye(len(s))))),
    }


def round_trip_error(s: object, s_inv: object, poses: object) -> float:
    """Pose → force → pose error of a linear model and its inverse: max |S (S_inv ψ) − ψ| / max |ψ|.

    Parameters
    ----------
    s, s_inv : array_like, shape (n, n)
        The model (forces → poses) and its inverse (poses → forces), e.g. from :func:`inverse`.
    poses : array_like, shape (runs, n)

    Returns
    -------
    float
        The largest error over every run and component, relative to the largest |pose|.
    """
    p = check_matrix("poses", poses)
    back = predict_linear(s, predict_linear(s_inv, p))
    return float(np.abs(back - p).max() / np.abs(p).max())


def relative_to_rows(s: object, reference: object) -> np.ndarray:
    """|S − C| / max |C| of each row of ``reference`` C: entry errors on each response's scale.

    Parameters
    ----------
    s, reference : array_like, shape (outputs, factors)

    Returns
    -------
    numpy.ndarray, shape (outputs, factors)
    """
    c = check_matrix("reference", reference)
    return np.abs(check_matrix("S", s, shape=c.shape) - c) / np.abs(c).max(axis=1, keepdims=True)
