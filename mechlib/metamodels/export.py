"""A distilled real-time model (:mod:`mechlib.metamodels.realtime`) as a plain data structure.

:func:`to_dict` turns a Legendre-polynomial model into a JSON-ready dict: the validated force
range, the exponents and coefficients, names and units, what it was validated on, and check
values (poses this library predicts for a few seeded force vectors). The book's data bundle
ships it as ``realtime_model.json`` with :mod:`mechlib.metamodels.evaluator` (plain Python),
and the book's explorer page evaluates the same dict in the browser. :func:`from_dict` gives
the model back as a :class:`~mechlib.metamodels.families.Surrogate`.

Coefficients are written as Python floats: JSON keeps every double exactly (shortest repr).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
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
