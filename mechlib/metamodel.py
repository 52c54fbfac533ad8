"""Force → pose meta-models: linear S_T (Eq 7), full quadratic (Eq 6), inverse (Eq 9), errors.

Conventions: designs ``X`` are ``(runs, factors)``, responses ``Y`` are ``(runs, outputs)`` and a
linear model is the matrix ``S`` of shape ``(outputs, factors)`` with ``Y ≈ X Sᵀ`` (Eq 7).
"""

from __future__ import annotations

import itertools
import warnings

import numpy as np
from sklearn.exceptions import ConvergenceWarning
from sklearn.linear_model import LassoCV, RidgeCV

from mechlib.params import check_choice, check_int, check_matrix

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
NEGLIGIBLE_SECOND_ORDER = 1e-6
"""Largest second-order / linear coefficient ratio (:func:`second_order_ratio`) for "the
quadratic and interaction terms of Eq 6 are negligible"."""
SOLVER_PRECISION_PCT = 1e-5
"""Largest pointwise error [%] of a meta-model that agrees with its FE model "to solver
precision" (Table 5 against the linear FE model)."""
DISTINCT_ERROR_FACTOR = 100.0
"""How many times smaller one error level must be than another to call them of different
origin (two orders of magnitude): Table 5's published errors against the non-linear FE's."""


def _xy(design: object, responses: object) -> tuple[np.ndarray, np.ndarray]:
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
    """
    x, y = _xy(design, responses)
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
    """
    check_choice("method", method, ("ridge", "lasso"))
    x, y = _xy(design, responses)
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


def quadratic_features(design: object) -> tuple[np.ndarray, list[str]]:
    """Columns of the full second-order model of Eq 6: 1, τ_i, τ_i², τ_i τ_j (i < j).

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


def predict_linear(s: object, design: object, b0: object | None = None) -> np.ndarray:
    """Pose predictions ``b0 + X Sᵀ`` for a design (runs, factors)."""
    s = check_matrix("S", s)
    x = check_matrix("design", design, shape=(None, s.shape[1]))
    return x @ s.T + (0.0 if b0 is None else np.asarray(b0, dtype=float))


def unit_ratio(observed: object, predicted: object) -> np.ndarray:
    """Least-squares factor ``c`` per column with ``observed ≈ c · predicted``.

    Used to find the units a table is really printed in: a ratio of 1000 means the table is
    in units a thousand times smaller than the model's.
    """
    o = check_matrix("observed", observed)
    p = check_matrix("predicted", predicted, shape=o.shape)
    return np.sum(o * p, axis=0) / np.sum(p * p, axis=0)


def inverse(s: object) -> dict[str, np.ndarray]:
    """Inverse model of Eq 9 and its conditioning.

    Returns
    -------
    dict
        ``S_inv``, ``cond`` (2-norm condition number in the units given), ``cond_scaled``
        (after scaling each row of S to unit 2-norm, which removes the µm-vs-µrad unit choice),
        and ``identity_error`` = max |S_inv S − I|.
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
    """max |S (S_inv ψ) − ψ| / max |ψ| over ``poses`` (runs, outputs): pose → force → pose."""
    p = check_matrix("poses", poses)
    back = predict_linear(s, predict_linear(s_inv, p))
    return float(np.abs(back - p).max() / np.abs(p).max())


def relative_to_rows(s: object, reference: object) -> np.ndarray:
    """|S − C| / max |C| of each row of ``reference`` C: entry errors on each response's scale."""
    c = check_matrix("reference", reference)
    return np.abs(check_matrix("S", s, shape=c.shape) - c) / np.abs(c).max(axis=1, keepdims=True)


def error_metrics(truth: object, predicted: object) -> dict[str, np.ndarray]:
    """Validation errors per output column (Eqs 10–11 and two relative errors).

    Returns
    -------
    dict
        ``maxabs`` max |ψ − ψ̂| (Eq 10); ``rmse`` (Eq 11); ``max_rel_pct`` max over runs of
        100 |ψ − ψ̂| / |ψ| (pointwise, runs with ψ = 0 excluded); ``max_range_pct``
        100 · MAXABS / max |ψ| (error relative to the response range).
    """
    t = check_matrix("truth", truth)
    p = check_matrix("predicted", predicted, shape=t.shape)
    err = np.abs(t - p)
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.where(t != 0, err / np.abs(t), 0.0)
    return {
        "maxabs": err.max(axis=0),
        "rmse": np.sqrt(np.mean(err**2, axis=0)),
        "max_rel_pct": 100 * rel.max(axis=0),
        "max_range_pct": 100 * err.max(axis=0) / np.abs(t).max(axis=0),
    }


def running_error_metrics(truth: object, predicted: object) -> dict[str, np.ndarray]:
    """The two relative errors of :func:`error_metrics` over the first k runs, for k = 1 … n.

    Shows how a validation statistic depends on the number of runs: a pointwise maximum keeps
    growing whenever a new run has a small value of some component, while the error relative
    to the response range settles once the range is explored.

    Returns
    -------
    dict
        ``runs`` (n,) = 1 … n; ``max_rel_pct`` and ``max_range_pct`` (n, outputs), row k − 1
        over the first k runs (a zero response, or a zero range so far, counts as 0 %). The last
        row equals :func:`error_metrics`.
    """
    t = check_matrix("truth", truth)
    p = check_matrix("predicted", predicted, shape=t.shape)
    err = np.abs(t - p)
    mag = np.abs(t)
    rel = np.divide(err, mag, out=np.zeros_like(err), where=mag != 0)
    top_err = np.maximum.accumulate(err, axis=0)
    top_mag = np.maximum.accumulate(mag, axis=0)
    rng = np.divide(100 * top_err, top_mag, out=np.zeros_like(err), where=top_mag != 0)
    return {
        "runs": np.arange(1, len(t) + 1),
        "max_rel_pct": 100 * np.maximum.accumulate(rel, axis=0),
        "max_range_pct": rng,
    }


def fit_quadratic(design: object, responses: object) -> dict[str, object]:
    """Least-squares fit of the full second-order model of Eq 6 (see :func:`quadratic_features`).

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
    """Predictions of a :func:`fit_quadratic` model for a design (runs, factors)."""
    a, _ = quadratic_features(design)
    return a @ check_matrix("coef", coef, shape=(a.shape[1], None))


def fit_gp(design: object, responses: object, seed: int = 0) -> list[object]:
    """One scikit-learn Gaussian process per output (constant × RBF + white noise kernel,
    normalised targets, seeded optimiser restarts).

    On noise-free responses that are linear in the factors the optimal RBF length scales are
    infinite and the optimal noise level zero, so the optimiser ends on those bounds, where
    L-BFGS-B's line search may also stop with status ABNORMAL; scikit-learn's
    ConvergenceWarnings saying either are expected here and not shown (any other warning is):
    the fitted processes are judged by their errors on validation data.
    """
    import warnings

    from sklearn.exceptions import ConvergenceWarning
    from sklearn.gaussian_process import GaussianProcessRegressor
    from sklearn.gaussian_process.kernels import RBF, ConstantKernel, WhiteKernel

    x, y = _xy(design, responses)
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
    """Predictions (runs, outputs) of :func:`fit_gp` models."""
    x = check_matrix("design", design)
    return np.column_stack([m.predict(x) for m in models])


def quadratic_parts(fit: dict[str, object]) -> dict[str, np.ndarray]:
    """The terms of a :func:`fit_quadratic` model by order.

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
    """Largest |second-order coefficient| over largest |linear one|, per output (outputs,)."""
    parts = quadratic_parts(fit)
    return np.abs(parts["second"]).max(axis=0) / np.abs(parts["S"]).max(axis=1)


def predict(fit: object, design: object) -> np.ndarray:
    """Predictions (runs, outputs) of any fit of this module.

    ``fit`` is what :func:`fit_linear` or :func:`fit_penalized` (a dict with ``S``),
    :func:`fit_quadratic` (a dict with ``coef``) or :func:`fit_gp` (a list) returned.
    """
    if isinstance(fit, list):
        return predict_gp(fit, design)
    if isinstance(fit, dict) and "coef" in fit:
        return predict_quadratic(fit["coef"], design)
    if isinstance(fit, dict) and "S" in fit:
        return predict_linear(fit["S"], design, fit.get("b0"))
    raise TypeError(f"fit must be a result of a fit_* function of this module, got {type(fit)}")


def surrogate_errors(
    fits: dict[str, object], cases: dict[str, tuple[object, object]], metric: str = "max_range_pct"
) -> dict[tuple[str, str], np.ndarray]:
    """One :func:`error_metrics` metric of every fit on every validation case.

    Parameters
    ----------
    fits : dict
        Name → fit (see :func:`predict`).
    cases : dict
        Name → ``(design, truth)``.
    metric : str
        A key of :func:`error_metrics`.

    Returns
    -------
    dict
        ``(fit name, case name)`` → the metric per output, fits in the outer order.
    """
    metric = check_choice("metric", metric, ("maxabs", "rmse", "max_rel_pct", "max_range_pct"))
    return {
        (name, case): error_metrics(truth, predict(fit, design))[metric]
        for name, fit in fits.items()
        for case, (design, truth) in cases.items()
    }
