"""Scores of a meta-model: validation errors (Table 5's convention), k-fold CV, latency per pose."""

from __future__ import annotations

import time
from collections.abc import Sequence

import numpy as np
from sklearn.model_selection import KFold

from mechlib.blas import one_thread
from mechlib.metamodels.families import (
    FAMILIES,
    Surrogate,
    check_forces,
    fit_surrogate,
    n_terms,
    predict,
    predict_array,
)
from mechlib.metamodels.metrics import error_metrics
from mechlib.params import check_choice, check_int, check_matrix

CV_FOLDS = 5
"""Default number of folds of :func:`cross_validate`."""
LATENCY_REPEATS = 21
"""Default number of timed repeats of :func:`latency_us` (the median is returned)."""
SINGLE_CALLS = 20
"""One-pose calls :func:`latency_us` times back to back in each repeat."""
US_PER_S = 1e6
"""Microseconds per second."""


def score(surrogate: Surrogate, forces: object, poses: object) -> dict[str, np.ndarray]:
    """Errors of a meta-model on held-out runs, per pose component.

    Parameters
    ----------
    surrogate : Surrogate
    forces : array_like, shape (runs, inputs)
        Validation forces [N], inside the validated range.
    poses : array_like, shape (runs, outputs)
        Their true poses.

    Returns
    -------
    dict
        The arrays (outputs,) of :func:`.metrics.error_metrics` — ``max_range_pct``
        (max |error| as % of the component's largest |value| over the set, Table 5's
        convention), ``maxabs`` (Eq 10), ``rmse`` (Eq 11), ``max_rel_pct`` — and ``worst_pct``,
        the largest ``max_range_pct`` over the components (a float).

    Raises
    ------
    ValueError
        Mismatched shapes or forces outside the validated range.
    """
    x = check_forces(surrogate, forces)
    y = check_matrix("poses", poses, shape=(x.shape[0], surrogate.n_outputs))
    out = error_metrics(y, predict(surrogate, x))
    out["worst_pct"] = float(out["max_range_pct"].max())
    return out


def cross_validate(
    family: str,
    forces: object,
    poses: object,
    *,
    amplitude: float,
    folds: int = CV_FOLDS,
    seed: int = 0,
) -> dict[str, np.ndarray]:
    """Seeded k-fold cross-validated errors of a family on its training runs.

    Each fold's held-out runs are predicted by the family fitted on the other runs (with the
    same validated range); the errors are those of :func:`score` on the pooled out-of-fold
    predictions.

    Parameters
    ----------
    family : str
        One of :data:`mechlib.metamodels.families.FAMILIES`.
    forces, poses : array_like, shapes (runs, inputs), (runs, outputs)
    folds : int
        Number of folds, 2 to runs.
    seed : int
        Seed of the fold shuffle and of the family's own randomness.
    amplitude : float
        Validated force range [N] of every fold's fit (the design's half-width).

    Returns
    -------
    dict
        As :func:`score`, plus ``predicted`` (runs, outputs), the out-of-fold predictions.

    Raises
    ------
    ValueError
        As :func:`mechlib.metamodels.families.fit_surrogate` (a fold's training runs must be at
        least the family's number of terms), or ``folds`` out of range.
    """
    x = check_matrix("forces", forces)
    y = check_matrix("poses", poses, shape=(x.shape[0], None))
    folds = check_int("folds", folds, low=2, high=len(x))
    seed = check_int("seed", seed, low=0)
    predicted = np.zeros_like(y)
    for train, test in KFold(folds, shuffle=True, random_state=seed).split(x):
        fit = fit_surrogate(family, x[train], y[train], amplitude=amplitude, seed=seed)
        predicted[test] = predict(fit, x[test])
    out = error_metrics(y, predicted)
    out["worst_pct"] = float(out["max_range_pct"].max())
    out["predicted"] = predicted
    return out


def cv_folds(family: str, n_runs: int, n_inputs: int = 6, folds: int = CV_FOLDS) -> int:
    """Folds of :func:`cross_validate` for a family on ``n_runs`` runs: ``folds`` if every
    fold's training runs (n − ⌈n / folds⌉) are at least the family's :func:`n_terms`, else
    leave-one-out (``n_runs`` folds).

    Returns
    -------
    int

    Raises
    ------
    ValueError
        If even leave-one-out leaves fewer runs than the family's number of terms.
    """
    n_runs = check_int("n_runs", n_runs, low=2)
    need = n_terms(family, n_inputs)
    if n_runs - 1 < need:
        raise ValueError(
            f"n_runs must exceed the {family} family's {need} terms for a cross-validation, "
            f"got {n_runs}"
        )
    return folds if n_runs - -(-n_runs // folds) >= need else n_runs


def latency_us(
    surrogate: Surrogate, forces: object, *, repeats: int = LATENCY_REPEATS
) -> dict[str, float]:
    """Measured prediction time per pose [µs] (median over repeats; wall clock, machine-dependent).

    Parameters
    ----------
    surrogate : Surrogate
    forces : array_like, shape (runs, inputs)
        Poses to predict, inside the validated range.
    repeats : int
        Timed repeats, 1 to 10 000.

    Returns
    -------
    dict
        ``batched``: one call on all runs, divided by the number of runs; ``single``: calls of
        one pose each, back to back as in a control loop (:data:`SINGLE_CALLS` consecutive
        poses a repeat), divided by the number of calls. Both in µs per pose, the median over
        ``repeats``; the batched and single calls are timed in separate loops, so that a large
        batch does not leave the caches cold for a single call.
    """
    x = check_forces(surrogate, forces)
    repeats = check_int("repeats", repeats, low=1, high=10_000)
    n_single = min(len(x), SINGLE_CALLS)
    batched, single = [], []
    with one_thread():
        predict_array(surrogate, x[:1])  # warm-up (imports, caches)
        for _ in range(repeats):
            t0 = time.perf_counter()
            predict_array(surrogate, x)
            batched.append((time.perf_counter() - t0) / len(x))
        rows = [x[i % len(x)][None, :] for i in range(repeats * n_single)]
        for r in range(repeats):
            t0 = time.perf_counter()
            for one in rows[r * n_single : (r + 1) * n_single]:
                predict_array(surrogate, one)
            single.append((time.perf_counter() - t0) / n_single)
    return {
        "batched": float(np.median(batched) * US_PER_S),
        "single": float(np.median(single) * US_PER_S),
    }


def compare_families(
    families: Sequence[str],
    forces: object,
    poses: object,
    val_forces: object,
    val_poses: object,
    *,
    amplitude: float,
    folds: int = CV_FOLDS,
    seed: int = 0,
    repeats: int = LATENCY_REPEATS,
) -> dict[str, dict[str, object]]:
    """Fit, validate, cross-validate and time several families on the same runs.

    Parameters
    ----------
    families : sequence of str
        Names from ``FAMILIES``.
    forces, poses : array_like, shapes (runs, inputs), (runs, outputs)
        Training runs.
    val_forces, val_poses : array_like
        Held-out runs inside ±amplitude.
    amplitude : float
        Validated force range [N] (the training design's half-width).
    folds, seed : int
        Of :func:`cross_validate` (and the families' own seeds).
    repeats : int
        Of :func:`latency_us`.

    Returns
    -------
    dict
        Family → ``{"surrogate", "validation" (:func:`score`), "cv" (:func:`cross_validate`),
        "latency_us" (:func:`latency_us`), "fit_s"}``; ``fit_s`` and ``latency_us`` are measured
        wall-clock times (machine-dependent), every other number is seeded.

    Raises
    ------
    ValueError
        As :func:`~mechlib.metamodels.families.fit_surrogate`, :func:`score` and
        :func:`cross_validate`.
    """
    fams = [check_choice("families", f, FAMILIES) for f in families]
    out = {}
    for fam in fams:
        t0 = time.perf_counter()
        fit = fit_surrogate(fam, forces, poses, amplitude=amplitude, seed=seed)
        fit_s = time.perf_counter() - t0
        out[fam] = {
            "surrogate": fit,
            "validation": score(fit, val_forces, val_poses),
            "cv": cross_validate(fam, forces, poses, amplitude=amplitude, folds=folds, seed=seed),
            "latency_us": latency_us(fit, val_forces, repeats=repeats),
            "fit_s": fit_s,
        }
    return out


def summary_table(results: dict[str, dict[str, object]], outputs: Sequence[str]) -> object:
    """One row per family of a :func:`compare_families` result, for a notebook table.

    Parameters
    ----------
    results : dict
        From :func:`compare_families`.
    outputs : sequence of str
        Names of the pose components, e.g. ``["x", "y", "z", "θx", "θy", "θz"]``.

    Returns
    -------
    pandas.DataFrame
        Index the families; columns ``max % <output>`` (validation, Table 5's convention),
        ``rmse <output>``, ``worst %``, ``CV worst %``, ``fit s``, ``µs/pose batched``,
        ``µs/pose single``.

    Raises
    ------
    ValueError
        If ``outputs`` does not name every pose component.
    """
    import pandas as pd

    rows = {}
    for fam, r in results.items():
        val = r["validation"]
        if len(outputs) != len(val["rmse"]):
            raise ValueError(
                f"outputs must name the {len(val['rmse'])} pose components, got {list(outputs)}"
            )
        row = {f"max % {o}": float(v) for o, v in zip(outputs, val["max_range_pct"], strict=True)}
        row |= {f"rmse {o}": float(v) for o, v in zip(outputs, val["rmse"], strict=True)}
        row |= {
            "worst %": val["worst_pct"],
            "CV worst %": r["cv"]["worst_pct"],
            "fit s": r["fit_s"],
            "µs/pose batched": r["latency_us"]["batched"],
            "µs/pose single": r["latency_us"]["single"],
        }
        rows[fam] = row
    return pd.DataFrame.from_dict(rows, orient="index")
