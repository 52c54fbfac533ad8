"""Studies built on the scoring functions (the meta-model page's learning-curve, budget and
control sections): error against the number of training runs, the force range each model keeps
within an error budget, and the inverse's forces checked against the truth."""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

import numpy as np

from mechlib.metamodels.families import FAMILIES, Surrogate, fit_surrogate, n_terms, predict
from mechlib.metamodels.inverse import invert
from mechlib.metamodels.metrics import error_metrics, full_scale_pct
from mechlib.metamodels.scoring import score
from mechlib.params import check_choice, check_float, check_int, check_matrix

FORCE_DECIMALS = 6
"""Decimals [N] an inverse's forces are rounded to before the truth runs them (a command
resolution of 1 µN). Newton's forces on a meta-model differ between processors by about its
own round-off amplified by the inversion: rounded to 1e-9 N, 32 of the 48 inverse runs of the
meta-model page (those of its Gaussian process and distilled polynomial) still differed between
OpenBLAS Haswell and Sandybridge kernels. Rounded to 1 µN they are the same runs unless a force
lies within that difference of a rounding boundary. Rounding moves a pose by at
most about 5e-7 of its range at ±1 N."""


def learning_curve(
    families: Sequence[str],
    forces: object,
    poses: object,
    val_forces: object,
    val_poses: object,
    sizes: Sequence[int],
    *,
    amplitude: float,
    seed: int = 0,
) -> dict[str, object]:
    """Validation error against the number of training runs: nested subsets (the first n runs).

    Parameters
    ----------
    families : sequence of str
        Names from ``FAMILIES``.
    forces, poses : array_like, shapes (runs, inputs), (runs, outputs)
        One training design (e.g. :func:`.designs.sobol_design`) and its poses; the first ``n``
        rows are the subset of size ``n``, so the subsets are nested.
    val_forces, val_poses : array_like
        Held-out runs, inside the validated range.
    sizes : sequence of int
        Training sizes, increasing, each at most the runs available.
    amplitude : float
        Validated range [N] of every fit (the design's half-width).
    seed : int
        Passed to :func:`fit_surrogate`.

    Returns
    -------
    dict
        ``sizes`` (m,); ``families`` list; ``max_range_pct`` and ``rmse`` (families, m,
        outputs) and ``worst_pct`` (families, m): NaN where a size is below the family's
        :func:`n_terms`; ``worst_run`` (families, m), the held-out run where the worst error
        lies (-1 where not fitted), and ``second_pct`` (families, m), the largest error over
        the other held-out runs (% of full scale, worst component): whether one run makes the
        worst.

    Raises
    ------
    ValueError
        Unknown family, a size larger than the runs available or not increasing, shapes.
    """
    x = check_matrix("forces", forces)
    y = check_matrix("poses", poses, shape=(x.shape[0], None))
    fams = [check_choice("families", f, FAMILIES) for f in families]
    n = np.array([check_int("sizes", s, low=1, high=len(x)) for s in sizes])
    if n.size == 0 or np.any(np.diff(n) <= 0):
        raise ValueError(f"sizes must be increasing, got {n.tolist()}")
    shape = (len(fams), len(n), y.shape[1])
    vy = check_matrix("val_poses", val_poses, shape=(None, y.shape[1]))
    out = {"max_range_pct": np.full(shape, np.nan), "rmse": np.full(shape, np.nan)}
    worst_run = np.full(shape[:2], -1)
    second = np.full(shape[:2], np.nan)
    for i, fam in enumerate(fams):
        for j, size in enumerate(n):
            if size < n_terms(fam, x.shape[1]):
                continue
            fit = fit_surrogate(fam, x[:size], y[:size], amplitude=amplitude, seed=seed)
            pred = predict(fit, val_forces)
            s = error_metrics(vy, pred)
            out["max_range_pct"][i, j] = s["max_range_pct"]
            out["rmse"][i, j] = s["rmse"]
            per_run = full_scale_pct(pred - vy, vy).max(axis=1)
            order = np.argsort(per_run, kind="stable")
            worst_run[i, j] = order[-1]
            second[i, j] = per_run[order[-2]] if len(order) > 1 else np.nan
    with np.errstate(all="ignore"):
        worst = np.max(out["max_range_pct"], axis=2)
    return {"sizes": n, "families": fams, "worst_pct": worst, "worst_run": worst_run,
            "second_pct": second, **out}  # fmt: skip


def budget_ranges(
    models: Mapping[str, Mapping[float, Surrogate]],
    cases: Mapping[float, tuple[object, object]],
    budget_pct: float,
) -> dict[str, np.ndarray]:
    """Each model's largest error at each force range, and the largest range it keeps within
    the budget (that range and every smaller one).

    Parameters
    ----------
    models : mapping
        Model name → {range [N]: the model to score at that range}; a range a model has no
        entry for was not fitted (e.g. fewer runs than terms).
    cases : mapping
        Range [N] → (forces (runs, 6), true poses (runs, 6)), the held-out runs at that range.
    budget_pct : float
        Largest allowed error, % of full scale, > 0.

    Returns
    -------
    dict
        ``amplitudes`` (m,) sorted; ``worst_pct`` (models, m) the worst component's error, 0
        where not fitted; ``fitted`` (models, m) bool; ``largest`` (models,) the largest range
        within the budget, 0.0 where the smallest already misses it or is not fitted.
    """
    budget_pct = check_float("budget_pct", budget_pct, low=0.0, low_open=True)
    amps = sorted(cases)
    if not amps:
        raise ValueError("cases must hold at least one force range")
    worst = np.zeros((len(models), len(amps)))
    fitted = np.zeros((len(models), len(amps)), dtype=bool)
    for i, by_range in enumerate(models.values()):
        for j, a in enumerate(amps):
            if a in by_range:
                worst[i, j] = score(by_range[a], *cases[a])["worst_pct"]
                fitted[i, j] = True
    ok = np.cumprod(fitted & (worst <= budget_pct), axis=1).astype(bool)
    amp = np.array(amps, dtype=float)
    largest = np.array([amp[row][-1] if row.any() else 0.0 for row in ok])
    return {"amplitudes": amp, "worst_pct": worst, "fitted": fitted, "largest": largest}


def inverse_round_trip(
    surrogate: Surrogate,
    targets: object,
    truth: Callable[[np.ndarray], tuple],
    span: Sequence[float],
) -> dict[str, np.ndarray]:
    """Forces for desired poses from a model's inverse, applied to the truth.

    Parameters
    ----------
    surrogate : Surrogate
        The model inverted (Newton from its linear part, :func:`invert`).
    targets : array_like (runs, 6)
        Desired poses.
    truth : callable
        ``truth(forces) -> (ok, poses, ...)``: the indices of the runs the truth solved and their
        poses, then anything (as :func:`mechlib.campaign.experiments.run_keeping_failures`
        returns; a run it could not solve is left out, not averaged in).
    span : sequence of 6 floats
        Each component's range [µm, µrad] that errors are divided by, > 0.

    Returns
    -------
    dict
        ``forces`` (runs, 6) [N], the inverse's rounded to ``FORCE_DECIMALS`` decimals (what the
        truth was given); ``converged`` (runs,) Newton within its tolerance; ``solved``
        the indices the truth solved; ``error_pct`` (6,) the largest |reached − target| as % of
        ``span`` over the solved runs.
    """
    psi = check_matrix("targets", targets, shape=(None, surrogate.n_outputs))
    s = check_matrix("span", np.asarray(span, dtype=float)[None, :], shape=(1, psi.shape[1]))[0]
    if np.any(s <= 0):
        raise ValueError(f"span must be positive in every component, got {s.tolist()}")
    inv = invert(surrogate, psi)
    # Newton's last digits differ between processors (their BLAS kernels round differently);
    # rounded, the forces are the same runs everywhere, so their stored results are found
    forces = np.round(inv["forces"], FORCE_DECIMALS)
    ok, reached = truth(forces)[:2]
    ok = np.asarray(ok, dtype=int)
    if len(ok) == 0:
        raise ValueError("the truth solved none of the inverse's force vectors")
    err = 100 * np.abs(np.asarray(reached) - psi[ok]).max(axis=0) / s
    return {"forces": forces, "converged": inv["converged"], "solved": ok, "error_pct": err}
