"""Validation errors of force → pose meta-models (thesis Eqs 10–11), and one error of every fit
of the thesis chapter (:mod:`~mechlib.metamodels.linear`, :mod:`~mechlib.metamodels.quadratic`,
:mod:`~mechlib.metamodels.gaussian_process`) on every validation case.

The book's one relative measure of an error is :data:`FULL_SCALE` (:func:`full_scale_pct`),
defined here once and stated on the methods page (:data:`FULL_SCALE_DEFINITION`).
"""

from __future__ import annotations

import numpy as np

from mechlib.metamodels.gaussian_process import GaussianProcess, predict_gp
from mechlib.metamodels.linear import predict_linear
from mechlib.metamodels.quadratic import predict_quadratic
from mechlib.params import check_choice, check_matrix

SOLVER_PRECISION_PCT = 1e-5
"""Largest pointwise error [%] of a meta-model that agrees with its FE model "to solver
precision" (Table 5 against the linear FE model)."""
FULL_SCALE = "% of full scale"
"""The name of the book's one relative error measure (:func:`full_scale_pct`)."""
FULL_SCALE_DEFINITION = (
    "An error in % of full scale is 100 × |error| divided by the largest |value| that pose "
    "component takes over the runs the error is measured on (for a pose component ψ: "
    "100 · max |ψ − ψ̂| / max |ψ|). The largest |value|, not max − min, because it keeps its "
    "meaning for one-sided sweeps (a load from 0 up) and for symmetric ones (±1 N), where "
    "max − min is twice as large and would halve every percentage; the thesis does not define "
    "the denominator of its Table 5's MAX % error, so this is our choice, used on every page."
)
"""The measure's definition, as the methods page states it."""
DISTINCT_ERROR_FACTOR = 100.0
"""How many times smaller one error level must be than another to call them of different
origin (two orders of magnitude): Table 5's published errors against the non-linear FE's."""


def full_scale_pct(error: object, truth: object) -> np.ndarray:
    """``100 · |error| / max |truth|`` per column: an error in :data:`FULL_SCALE`.

    Parameters
    ----------
    error : array_like, shape (runs, outputs) or (outputs,)
        Differences from the truth (or their largest |value| per column).
    truth : array_like, shape (runs, outputs)
        The reference values whose largest |value| per column is the full scale.

    Returns
    -------
    numpy.ndarray
        The errors in % of full scale, ``error``'s shape.

    Raises
    ------
    ValueError
        When a column of ``truth`` is all zero (no full scale to divide by).

    Examples
    --------
    The full scale of each column is its largest |value| (40 and 4 here), whatever the sign:

    >>> truth = [[10.0, -2.0], [-40.0, 4.0]]
    >>> full_scale_pct([[1.0, 0.5], [2.0, 0.0]], truth).tolist()
    [[2.5, 12.5], [5.0, 0.0]]
    >>> full_scale_pct([1.0], [[0.0], [0.0]])
    Traceback (most recent call last):
    ...
    ValueError: full scale must be > 0 in every column, got [0.0]
    """
    t = np.atleast_2d(np.asarray(truth, dtype=float))
    scale = np.abs(t).max(axis=0)
    if np.any(scale == 0):
        raise ValueError(f"full scale must be > 0 in every column, got {scale.tolist()}")
    return 100.0 * np.abs(np.asarray(error, dtype=float)) / scale


def error_metrics(truth: object, predicted: object) -> dict[str, np.ndarray]:
    """Validation errors per output column (Eqs 10–11 and two relative errors).

    Parameters
    ----------
    truth, predicted : array_like, shape (runs, outputs)

    Returns
    -------
    dict
        ``maxabs`` max |ψ − ψ̂| (Eq 10); ``rmse`` (Eq 11); ``max_rel_pct`` max over runs of
        100 |ψ − ψ̂| / |ψ| (pointwise, runs with ψ = 0 excluded); ``max_range_pct``
        100 · MAXABS / max |ψ|, MAXABS in :data:`FULL_SCALE` (:func:`full_scale_pct`).

    Examples
    --------
    An error of 0.1 on a response that spans 40 is 0.25 % of full scale, but 1000 % of the
    run where the response is 0.01: why the book quotes the full-scale measure.

    >>> truth = np.array([[40.0], [0.01]])
    >>> m = error_metrics(truth, truth + 0.1)
    >>> round(float(m["max_range_pct"][0]), 6), round(float(m["max_rel_pct"][0]), 6)
    (0.25, 1000.0)
    >>> bool(np.allclose(m["max_range_pct"], full_scale_pct(m["maxabs"], truth)))
    True
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
        "max_range_pct": 100 * err.max(axis=0) / np.abs(t).max(axis=0),  # full_scale_pct
    }


def running_error_metrics(truth: object, predicted: object) -> dict[str, np.ndarray]:
    """The two relative errors of :func:`error_metrics` over the first k runs, for k = 1 … n.

    Shows how a validation statistic depends on the number of runs: a pointwise maximum keeps
    growing whenever a new run has a small value of some component, while the error relative
    to the response range settles once the range is explored.

    Parameters
    ----------
    truth, predicted : array_like, shape (runs, outputs)

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


def predict_fit(fit: object, design: object) -> np.ndarray:
    """Predictions (runs, outputs) of any fit of the thesis chapter.

    ``fit`` is what :func:`~mechlib.metamodels.linear.fit_linear` or
    :func:`~mechlib.metamodels.linear.fit_penalized` (a dict with ``S``),
    :func:`~mechlib.metamodels.quadratic.fit_quadratic` (a dict with ``coef``) or
    :func:`~mechlib.metamodels.gaussian_process.fit_gp` (a ``GaussianProcess``) returned.

    Parameters
    ----------
    fit : dict or GaussianProcess
    design : array_like, shape (runs, factors)

    Returns
    -------
    numpy.ndarray, shape (runs, outputs)

    Raises
    ------
    TypeError
        If ``fit`` is none of these.
    """
    if isinstance(fit, GaussianProcess):
        return predict_gp(fit, design)
    if isinstance(fit, dict) and "coef" in fit:
        return predict_quadratic(fit["coef"], design)
    if isinstance(fit, dict) and "S" in fit:
        return predict_linear(fit["S"], design, fit.get("b0"))
    raise TypeError(
        "fit must be a result of fit_linear, fit_penalized, fit_quadratic or fit_gp, got "
        f"{type(fit)}"
    )


def surrogate_errors(
    fits: dict[str, object], cases: dict[str, tuple[object, object]], metric: str = "max_range_pct"
) -> dict[tuple[str, str], np.ndarray]:
    """One :func:`error_metrics` metric of every fit on every validation case.

    Parameters
    ----------
    fits : dict
        Name → fit (see :func:`predict_fit`).
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
        (name, case): error_metrics(truth, predict_fit(fit, design))[metric]
        for name, fit in fits.items()
        for case, (design, truth) in cases.items()
    }
