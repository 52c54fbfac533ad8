"""The departure of a non-linear response from the linear one, split by parity in the load.

For dead loads on a Saint Venant–Kirchhoff body the equilibrium is an analytic function of the
load, ψ(f) = S f + Q(f) + C(f) + …, with Q quadratic, C cubic and so on. A load and its opposite
separate the orders by parity: the part of the departure d(f) = ψ(f) − S f that is *even* in f,
(d(f) + d(−f)) / 2 = Q(f) + (quartic …), is led by the second-order terms — the kinematics of
finite rotation (foreshortening of bent flexures, the coupling of tilt and lift) — and the *odd*
part, (d(f) − d(−f)) / 2 = C(f) + (quintic …), by the third-order ones — among them the
stiffening of flexures that stretch as they bend, beside third-order kinematic terms.
:func:`parity_split` computes both from runs at ±f; :func:`parity_summary` states them, like
Table 5's errors, in % of full scale. :func:`linear_poses` gives the linear counterpart of a
non-linear solve on the same mesh and quadrature, and :func:`relative_change` compares a
quantity between two discretisations.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from mechlib.params import check_matrix

if TYPE_CHECKING:
    from mechlib.fe.nonlinear import NonlinearSolver
    from mechlib.hexflex.spec import ModelSpec


def parity_split(plus: object, minus: object, linear_plus: object) -> dict[str, np.ndarray]:
    """Even and odd parts of the departure from linearity, from runs at f and at −f.

    Parameters
    ----------
    plus, minus : array_like (n, k)
        The non-linear responses at the loads f and −f (same units, e.g. µm and µrad).
    linear_plus : array_like (n, k)
        The linear response S f at the loads f (its value at −f is its opposite).

    Returns
    -------
    dict
        ``even`` and ``odd`` (n, k): (d(f) ± d(−f)) / 2 with d the departure ψ − S f;
        ``departure`` (n, k): d(f) = even + odd.

    Raises
    ------
    ValueError
        If the three arrays do not have one shape, or hold non-finite values.
    """
    p = check_matrix("plus", plus)
    m = check_matrix("minus", minus, shape=p.shape)
    lin = check_matrix("linear_plus", linear_plus, shape=p.shape)
    d_plus, d_minus = p - lin, m + lin
    return {
        "even": 0.5 * (d_plus + d_minus),
        "odd": 0.5 * (d_plus - d_minus),
        "departure": d_plus,
    }


def parity_summary(split: dict[str, np.ndarray], scale: object) -> dict[str, np.ndarray]:
    """Largest |part| per component as a share of ``scale`` [%], for each part of
    :func:`parity_split` (``even``, ``odd``, ``departure``).

    Parameters
    ----------
    split : dict
        A result of :func:`parity_split`.
    scale : array_like (k,)
        Each component's range (e.g. its largest |response| over the runs), > 0.

    Returns
    -------
    dict
        ``even``, ``odd`` and ``departure``, each (k,) [%]: the largest |part| over the runs,
        per component, as a percentage of that component's ``scale``.

    Raises
    ------
    ValueError
        If a scale is not positive and finite, or has the wrong length.
    """
    s = np.asarray(scale, dtype=float)
    k = split["departure"].shape[1]
    if s.shape != (k,) or not np.all(np.isfinite(s)) or np.any(s <= 0):
        raise ValueError(f"scale must be {k} positive finite values, got {s.tolist()}")
    return {
        name: 100 * np.abs(split[name]).max(axis=0) / s for name in ("even", "odd", "departure")
    }


def linear_poses(solver: NonlinearSolver, forces: object) -> np.ndarray:
    """Stage poses (n, 6) [µm, µrad] of the *linear* problem on the solver's mesh and with its
    quadrature: the loads solved with its tangent at u = 0 (the model's own factorisation when
    the quadrature is the model's), so that a departure ψ_nl − ψ_lin compares like with like.

    Parameters
    ----------
    solver : NonlinearSolver
        The non-linear solver whose linear counterpart is wanted.
    forces : array_like (n, 6)
        Actuator forces [N] within the model's bound.

    Returns
    -------
    numpy.ndarray (n, 6)
        The linear stage poses [µm, µrad], one row per force vector, as
        :meth:`mechlib.hexflex.fe.model.HexFlexModel.pose_of` fits them.

    Raises
    ------
    ValueError
        If ``forces`` is not (n, 6) (or (6,)) finite values within ±
        :data:`mechlib.hexflex.fe.model.MAX_FORCE_N`.
    """
    model = solver.model
    f = model.check_forces(forces)
    solve = solver.factorised_tangent(np.zeros(model.n_dofs))
    loads = model.load_vectors() @ f.T
    return np.array([model.pose_of(solve(loads[:, k])) for k in range(len(f))])


def relative_change(values: object, reference: object) -> np.ndarray:
    """max over runs |values − reference| / max over runs |reference|, per column [%].

    Parameters
    ----------
    values, reference : array_like (n, k)
        The quantity on two discretisations (runs by rows, components by columns), one shape.

    Returns
    -------
    numpy.ndarray (k,)
        Per column, the largest |values − reference| over the rows as a percentage of the
        largest |reference| over the rows.

    Raises
    ------
    ValueError
        If the shapes differ, or a reference column is all zero.
    """
    v = check_matrix("values", values)
    r = check_matrix("reference", reference, shape=v.shape)
    top = np.abs(r).max(axis=0)
    if np.any(top == 0):
        raise ValueError("reference must have a non-zero value in every column")
    return 100 * np.abs(v - r).max(axis=0) / top


def linear_poses_for(spec: ModelSpec, forces: object, cache_dir: Path | None = None) -> np.ndarray:
    """:func:`linear_poses` of the non-linear solve that ``spec`` defines (its mesh and
    quadrature): at the model's own quadrature the (cached) linear model's poses; at another one
    those of the process's solver of ``spec``
    (:func:`mechlib.campaign.experiments.solver_for`,
    the one an in-process run used; a Q2 solver of the identified model holds gigabytes, so
    none is built twice).

    Parameters
    ----------
    spec : ModelSpec
        The model and quadrature of the non-linear runs to compare with.
    forces : array_like (n, 6)
        Actuator forces [N] within the model's bound.
    cache_dir : Path, optional
        FE cache: at the model's own quadrature the poses are ``forces @ C.T`` with the model's
        compliance C read from it (:func:`mechlib.hexflex.compliance.compliance`, bit
        for bit what the model computes), so a build reading the cache builds no model.

    Returns
    -------
    numpy.ndarray (n, 6)
        The linear stage poses [µm, µrad] on ``spec``'s mesh, with its quadrature.
    """
    from mechlib.campaign.experiments import solver_for
    from mechlib.fe.sfepy_base import QUAD_ORDER
    from mechlib.hexflex.compliance import compliance
    from mechlib.hexflex.fe.model import check_forces

    if spec.quad_order == QUAD_ORDER:
        f = np.asarray(forces, dtype=float)
        f = check_forces("forces [N]", f[None, :] if f.ndim == 1 else f)
        return f @ compliance(spec, cache_dir).T
    return linear_poses(solver_for(spec), forces)
