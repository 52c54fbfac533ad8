"""A distilled real-time model (:mod:`mechlib.metamodels.realtime`) as a plain data structure,
and learning curves as tables: what the book's data bundle ships of the meta-models.

:func:`to_dict` turns a Legendre-polynomial model into a JSON-ready dict: the validated force
range, the exponents and coefficients, names and units, what it was validated on, and check
values (poses this library predicts for a few seeded force vectors). The book's data bundle
ships it as ``realtime_model.json`` (:func:`realtime_model`: with the validation the book
reports) with :mod:`mechlib.metamodels.evaluator` (plain Python), and the book's explorer page
evaluates the same dict in the browser. :func:`from_dict` gives the model back as a
:class:`~mechlib.metamodels.families.Surrogate`. :func:`curves_table` and
:func:`realtime_curves` give learning curves as tables.

Coefficients are written as Python floats: JSON keeps every double exactly (shortest repr).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd
from scipy.stats import qmc

from mechlib.blas import one_thread
from mechlib.metamodels.families import Surrogate, predict_array
from mechlib.metamodels.realtime import DISTILLED
from mechlib.params import check_int

FORMAT = "mechlib-legendre-total-degree/1"
"""Name and version of the format :func:`to_dict` writes."""
CHECK_VECTORS = 8
"""Seeded force vectors (scrambled Sobol', within the validated range) whose poses are shipped."""


def to_dict(
    model: Surrogate,
    inputs: Sequence[str],
    outputs: Sequence[str],
    units: Sequence[str],
    validation: Mapping[str, Any],
    seed: int = 0,
) -> dict[str, Any]:
    """The exported form of a distilled model.

    Parameters
    ----------
    model : Surrogate
        Family :data:`~mechlib.metamodels.realtime.DISTILLED` (a Legendre polynomial).
    inputs : sequence of str
        Force names (N), one per input.
    outputs, units : sequence of str
        Pose component names and their units, one per output.
    validation : mapping
        What the model was validated on (numbers and text, JSON-ready), copied as it is.
    seed : int
        Seed of the check vectors' Sobol' scrambling.

    Returns
    -------
    dict
        ``format``, ``amplitude_n``, ``inputs``, ``outputs``, ``units``, ``basis`` (text),
        ``exponents`` (terms × inputs), ``coef`` (terms × outputs), ``validation``, ``check``
        (``forces_n`` and ``poses``, :data:`CHECK_VECTORS` of each).
    """
    if model.family != DISTILLED:
        raise ValueError(f"model must be a {DISTILLED!r} polynomial, got family {model.family!r}")
    for name, seq, n in (
        ("inputs", inputs, model.n_inputs),
        ("outputs", outputs, model.n_outputs),
        ("units", units, model.n_outputs),
    ):
        if len(seq) != n:
            raise ValueError(f"{name} must name {n} entries, got {len(seq)}: {list(seq)}")
    seed = check_int("seed", seed, low=0)
    exps = np.asarray(model.state["exponents"], dtype=int)
    coef = np.asarray(model.state["coef"], dtype=float)
    u = qmc.Sobol(d=model.n_inputs, scramble=True, seed=seed).random(CHECK_VECTORS)
    forces = np.round(model.amplitude * (2 * u - 1), 6)
    with one_thread():
        poses = predict_array(model, forces)
    return {
        "format": FORMAT,
        "amplitude_n": float(model.amplitude),
        "inputs": list(inputs),
        "outputs": list(outputs),
        "units": list(units),
        "basis": "products of sqrt(2k+1) P_k(u), P_k Legendre, u = force / amplitude_n; "
        "pose = sum over terms of product_i basis(u_i, exponents[t][i]) * coef[t]",
        "exponents": exps.tolist(),
        "coef": coef.tolist(),
        "validation": dict(validation),
        "check": {"forces_n": forces.tolist(), "poses": poses.tolist()},
    }


def realtime_model(
    model: Surrogate,
    inputs: Sequence[str],
    outputs: Sequence[str],
    units: Sequence[str],
    *,
    worst_pct: object,
    poses: object,
    teacher: str,
    full_runs: int,
    compliance: object,
    seed: int = 0,
) -> dict[str, Any]:
    """:func:`to_dict` of a distilled model with the validation the book reports: the bundle's
    ``realtime_model.json``.

    Parameters
    ----------
    model, inputs, outputs, units, seed
        As :func:`to_dict`.
    worst_pct : array_like, shape (outputs,)
        Its largest held-out error per pose component, % of the component's largest |value|
        over the held-out runs (``max_range_pct`` of :func:`~mechlib.metamodels.scoring.score`).
    poses : array_like, shape (runs, outputs)
        The held-out runs' poses: their number and each component's largest |value|.
    teacher : str
        The model it was distilled from.
    full_runs : int
        The full non-linear runs it rests on.
    compliance : array_like, shape (outputs, inputs)
        The linear compliance of the same FE model (Eq 8's form), rows the outputs.

    Returns
    -------
    dict
        As :func:`to_dict`; ``validation`` holds ``heldout_runs``, ``force_range_n``,
        ``worst_pct``, ``worst_pct_max``, ``range`` (and ``range_means``), ``teacher``,
        ``degree``, ``full_runs``, ``S_T`` (and ``S_T_means``).

    Raises
    ------
    ValueError
        Poses or errors not of the model's outputs, and what :func:`to_dict` refuses.
    """
    worst = np.asarray(worst_pct, dtype=float)
    held = np.asarray(poses, dtype=float)
    if worst.shape != (model.n_outputs,) or held.ndim != 2 or held.shape[1] != model.n_outputs:
        raise ValueError(
            f"worst_pct must have {model.n_outputs} entries and poses {model.n_outputs} columns, "
            f"got shapes {worst.shape} and {held.shape}"
        )
    per_force = ", ".join(dict.fromkeys(f"{u}/N" for u in units))
    validation = {
        "heldout_runs": len(held),
        "force_range_n": model.amplitude,
        "worst_pct": worst_pct,
        "worst_pct_max": float(worst.max()),
        "range": np.abs(held).max(axis=0),
        "range_means": "each component's largest |value| over the held-out runs",
        "teacher": teacher,
        "degree": int(np.asarray(model.state["exponents"]).max()),
        "full_runs": full_runs,
        "S_T": compliance,
        "S_T_means": f"the linear compliance of the same FE model [{per_force}], rows "
        f"{' '.join(outputs)}, columns the forces",
    }
    return to_dict(model, inputs, outputs, units, validation, seed=seed)


def curves_table(
    runs: Sequence[int],
    worst_pct: object,
    labels: Sequence[str],
    *,
    runs_name: str = "training runs",
) -> pd.DataFrame:
    """Learning curves as a table: a column ``runs_name`` of the training sizes, then one per
    curve, ``"<label> [% of full scale]"``, its worst error at each size (empty where a family
    was not fitted; no curve column when no family was).

    Parameters
    ----------
    runs : sequence of int
        The training sizes.
    worst_pct : array_like, shape (curves, sizes)
        Each curve's worst error [% of full scale] (NaN: not fitted).
    labels : sequence of str
        One label per curve.

    Raises
    ------
    ValueError
        ``worst_pct`` not of one row per label and one column per size.
    """
    worst = np.asarray(worst_pct, dtype=float)
    if not labels and not worst.size:  # no family fitted: the sizes alone
        worst = worst.reshape(0, len(runs))
    if worst.shape != (len(labels), len(runs)):
        raise ValueError(
            f"worst_pct must be ({len(labels)}, {len(runs)}): one row per label, one column per "
            f"training size, got shape {worst.shape}"
        )
    table = pd.DataFrame(worst.T, columns=[f"{label} [% of full scale]" for label in labels])
    table.insert(0, runs_name, list(runs))
    return table


def realtime_curves(
    runs: Sequence[int], gp: object, corrected: object, indicator: object
) -> pd.DataFrame:
    """The real-time section's learning curves as a table (:func:`curves_table`, sizes in a
    ``full runs`` column): a Gaussian process's, the reduced-order model's corrected on the
    forces (:func:`~mechlib.metamodels.correction.corrected_curve`) and with an error model on
    its indicators (:func:`~mechlib.metamodels.correction.indicator_curve`)."""
    return curves_table(
        runs,
        np.vstack([gp, corrected, indicator]),
        [
            "Gaussian process",
            "reduced-order model + correction of the forces",
            "reduced-order model + error model on its indicators",
        ],
        runs_name="full runs",
    )


def from_dict(data: Mapping[str, Any]) -> Surrogate:
    """The :class:`Surrogate` of an exported model (the inverse of :func:`to_dict`)."""
    if data.get("format") != FORMAT:
        raise ValueError(f"format must be {FORMAT!r}, got {data.get('format')!r}")
    exps = np.asarray(data["exponents"], dtype=int)
    coef = np.asarray(data["coef"], dtype=float)
    if exps.ndim != 2 or coef.shape[0] != exps.shape[0]:
        raise ValueError(
            f"exponents and coef must have one row per term, got {exps.shape} and {coef.shape}"
        )
    state = {"exponents": exps, "coef": coef, "teacher": data["validation"].get("teacher", "")}
    return Surrogate(DISTILLED, float(data["amplitude_n"]), exps.shape[1], coef.shape[1], state)
