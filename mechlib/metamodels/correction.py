"""Corrections of a low-fidelity force → pose model by few full runs, and their learning curves.

Correction of the forces (:func:`corrected`, :func:`cross_validate_corrected`,
:func:`corrected_curve`): the low-fidelity model (e.g. the hyper-reduced ROM,
:func:`mechlib.metamodels.families.wrap_model`) plus a Gaussian process fitted to what it misses
on the full runs, ``poses − low(forces)`` — the additive low-fidelity-plus-discrepancy form of
multi-fidelity Kriging (Kennedy and O'Hagan's model with a unit scale factor), fitted with this
package's ``gp`` family.

Error model on indicators (:func:`indicator_correction`, :func:`indicator_curve`,
:func:`indicator_correlation`): a Gaussian process from what the low-fidelity model computes
about its own error (e.g. its dual-weighted residuals,
:mod:`mechlib.hexflex.rom.indicators`) to its misses — the ROMES form (Drohmann & Carlberg
2015).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from mechlib.blas import one_thread
from mechlib.metamodels.families import (
    Surrogate,
    check_forces,
    fit_surrogate,
    name_of,
    predict_array,
    wrap_model,
)
from mechlib.metamodels.metrics import error_metrics
from mechlib.metamodels.scoring import CV_FOLDS, cross_validate
from mechlib.params import check_int, check_matrix


def corrected(low: Surrogate, forces: object, poses: object, seed: int = 0) -> Surrogate:
    """``low`` plus a Gaussian process fitted to its misses on full runs.

    Parameters
    ----------
    low : Surrogate
        The low-fidelity model; its validated range is the corrected model's.
    forces, poses : array_like, shapes (runs, inputs), (runs, outputs)
        Full runs inside ``low``'s range, at least two.
    seed : int
        Seed of the Gaussian process's optimiser restarts.

    Returns
    -------
    Surrogate
        Family ``physics`` (:func:`mechlib.metamodels.families.wrap_model`), predicting
        ``low(f) + gp(f)``.
    """
    x = check_forces(low, forces)
    y = check_matrix("poses", poses, shape=(x.shape[0], low.n_outputs))
    with one_thread():
        miss = y - predict_array(low, x)
    gp = fit_surrogate("gp", x, miss, amplitude=low.amplitude, seed=seed)

    def poses_of(f: np.ndarray) -> np.ndarray:
        return predict_array(low, f) + predict_array(gp, f)

    name = f"{name_of(low)} + Gaussian-process correction"
    return wrap_model(name, poses_of, amplitude=low.amplitude, n_inputs=low.n_inputs)


def cross_validate_corrected(
    low: Surrogate, forces: object, poses: object, folds: int = CV_FOLDS, seed: int = 0
) -> dict[str, np.ndarray]:
    """Seeded k-fold cross-validated errors of :func:`corrected` on its full runs.

    The correction of each fold is fitted on the other folds' misses; the errors are those of
    :func:`mechlib.metamodels.scoring.score` on the pooled out-of-fold predictions of
    ``low + correction``.

    Parameters
    ----------
    low : Surrogate
        The low-fidelity model.
    forces, poses : array_like, shapes (runs, inputs), (runs, outputs)
        The full runs, inside ``low``'s range.
    folds : int
        Number of folds, 2 to runs.
    seed : int
        Seed of the fold shuffle and of the corrections' optimiser.

    Returns
    -------
    dict
        The arrays (outputs,) of :func:`mechlib.metamodels.metrics.error_metrics` and
        ``worst_pct``, the largest ``max_range_pct`` (a float).
    """
    x = check_forces(low, forces)
    y = check_matrix("poses", poses, shape=(x.shape[0], low.n_outputs))
    with one_thread():
        base = predict_array(low, x)
    cv = cross_validate("gp", x, y - base, amplitude=low.amplitude, folds=folds, seed=seed)
    out = error_metrics(y, base + cv["predicted"])
    out["worst_pct"] = float(out["max_range_pct"].max())
    return out


def corrected_curve(
    sizes: Sequence[int],
    train: tuple[object, object, object],
    held_out: tuple[object, object, object],
    amplitude: float,
    seed: int = 0,
) -> np.ndarray:
    """:func:`corrected`'s learning curve from the low-fidelity poses computed once: the largest
    error (% of full scale, worst component) on held-out runs of the correction fitted on the first
    ``n`` training runs, per ``n`` of ``sizes``.

    The fits are those of ``corrected`` on the same runs, except that the low-fidelity poses come
    from one batch: a batched model (the ROM) can round them differently in the last digits,
    and that can move a correction's likelihood optimum (seen on the meta-model page, as
    between processors).

    Parameters
    ----------
    sizes : sequence of int
        Training runs used, each 2 to the number of training runs.
    train, held_out : tuple (low, forces, poses)
        Per run: the low-fidelity poses, the forces [N] and the full poses.
    amplitude : float
        The low-fidelity model's validated range [N] (that of the correction).
    seed : int
        As :func:`corrected`.

    Returns
    -------
    ndarray (len(sizes),)
        Worst-component largest error [% of full scale] per size.
    """
    low_t, x_t, y_t = _runs("train", train, "forces")
    low_v, x_v, y_v = _runs("held_out", held_out, "forces")
    out = []
    for n in sizes:
        n = check_int("sizes", n, low=2, high=len(y_t))
        gp = fit_surrogate("gp", x_t[:n], y_t[:n] - low_t[:n], amplitude=amplitude, seed=seed)
        with one_thread():
            guess = low_v + predict_array(gp, check_forces(gp, x_v))
        out.append(error_metrics(y_v, guess)["max_range_pct"].max())
    return np.array(out)


def _runs(name: str, parts: tuple[object, object, object], inputs: str) -> list[np.ndarray]:
    """``(low, inputs, poses)`` of one set of runs as float matrices with one row a run."""
    if len(parts) != 3:
        raise ValueError(f"{name} must be (low-fidelity poses, {inputs}, poses), got {len(parts)}")
    low, x, y = (
        check_matrix(f"{name} {what}", a)
        for what, a in zip(("low-fidelity poses", inputs, "poses"), parts, strict=True)
    )
    if not len(low) == len(x) == len(y) or low.shape[1] != y.shape[1]:
        raise ValueError(
            f"{name}: low-fidelity poses {low.shape}, {inputs} {x.shape} and poses {y.shape} "
            "must have one row a run and the poses the same columns"
        )
    return [low, x, y]


def indicator_correction(
    features: object, misses: object, seed: int = 0, scale: object | None = None
) -> Callable[[np.ndarray], np.ndarray]:
    """An error model on indicators: a Gaussian process from a low-fidelity model's error
    indicators (e.g. its dual-weighted residuals,
    :func:`mechlib.hexflex.rom.indicators.dual_weighted_residuals`) to its misses.

    The ROMES form (Drohmann & Carlberg 2015): the inputs are what the low-fidelity model
    computes about its own error, not the forces. Each indicator is divided by ``scale`` (by
    default its largest |value| on the training runs), and the ``gp`` family is fitted on those
    (its linear trend plus a process); new indicators beyond the training ones are extrapolated,
    not refused.

    Parameters
    ----------
    features : array_like (runs, k)
        Indicators at the full runs, at least two runs; no column all zero.
    misses : array_like (runs, outputs)
        Full poses minus the low-fidelity model's there.
    seed : int
        Seed of the Gaussian process's optimiser restarts.
    scale : array_like (k,), optional
        Positive divisor of each indicator, at least its largest |value| on these runs (e.g.
        over a larger pool of runs: indicators need no full run).

    Returns
    -------
    callable
        Indicators (n, k) → predicted misses (n, outputs).
    """
    x = check_matrix("features", features)
    y = check_matrix("misses", misses, shape=(x.shape[0], None))
    if x.shape[0] < 2:
        raise ValueError(f"features must have at least 2 runs, got {x.shape[0]}")
    largest = np.abs(x).max(axis=0)
    if not largest.all():
        raise ValueError(
            "features must have no all-zero column, got all zeros in columns "
            f"{np.flatnonzero(largest == 0).tolist()}"
        )
    if scale is None:
        scale = largest
    else:
        scale = check_matrix("scale", np.atleast_2d(scale), shape=(1, x.shape[1]))[0]
        if np.any(scale < largest):
            raise ValueError(
                f"scale must be at least each feature's largest |value| {largest.tolist()}, "
                f"got {scale.tolist()}"
            )
    gp = fit_surrogate("gp", x / scale, y, amplitude=1.0, seed=seed)

    def predicted(new: np.ndarray) -> np.ndarray:
        u = check_matrix("features", new, shape=(None, x.shape[1])) / scale
        with one_thread():
            return predict_array(gp, u)

    return predicted


def indicator_curve(
    sizes: Sequence[int],
    train: tuple[object, object, object],
    held_out: tuple[object, object, object],
    seed: int = 0,
) -> np.ndarray:
    """Largest error (% of full scale, worst component) on held-out runs of the low-fidelity model
    corrected by :func:`indicator_correction` fitted on the first ``n`` training runs, per
    ``n`` of ``sizes``.

    Parameters
    ----------
    sizes : sequence of int
        Training runs used, each 2 to the number of training runs.
    train, held_out : tuple (low, features, poses)
        Per run: the low-fidelity poses, the indicators and the full poses.
    seed : int
        As :func:`indicator_correction`.

    Returns
    -------
    ndarray (len(sizes),)
        Worst-component largest error [% of full scale] per size. Every fit divides the indicators
        by their largest |value| over all training runs (the same inputs at every size).
    """
    low_t, feat_t, y_t = _runs("train", train, "features")
    low_v, feat_v, y_v = _runs("held_out", held_out, "features")
    if feat_v.shape[1] != feat_t.shape[1]:
        raise ValueError(
            f"held_out features must have the training's {feat_t.shape[1]} columns, got "
            f"{feat_v.shape[1]}"
        )
    scale = np.abs(feat_t).max(axis=0)
    out = []
    for n in sizes:
        n = check_int("sizes", n, low=2, high=len(y_t))
        model = indicator_correction(feat_t[:n], y_t[:n] - low_t[:n], seed=seed, scale=scale)
        out.append(error_metrics(y_v, low_v + model(feat_v))["max_range_pct"].max())
    return np.array(out)


def indicator_correlation(indicators: object, misses: object) -> np.ndarray:
    """Pearson correlation of each indicator column with the miss of the same output column
    (an indicator that estimates its own component's miss scores near 1).

    Parameters
    ----------
    indicators, misses : array_like (runs, outputs)
        At least three runs; no constant column.

    Returns
    -------
    ndarray (outputs,)
        Correlations in [-1, 1].
    """
    a = check_matrix("indicators", indicators)
    b = check_matrix("misses", misses, shape=a.shape)
    if len(a) < 3:
        raise ValueError(f"indicators must have at least 3 runs, got {len(a)}")
    a, b = a - a.mean(axis=0), b - b.mean(axis=0)
    norms = np.linalg.norm(a, axis=0) * np.linalg.norm(b, axis=0)
    if not norms.all():
        raise ValueError("indicators and misses must have no constant column")
    return (a * b).sum(axis=0) / norms
