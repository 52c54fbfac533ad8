"""Error indicators of the reduced-order model, from the full model's residual at its solution.

The ROM's Galerkin equilibrium (its equations are the full ones projected on its basis ``V``)
leaves the full residual ``r = f(V q) − L F`` orthogonal to ``V`` — up to the hyper-reduction's
approximation of the internal force — but not zero; what is left estimates the ROM's error.
To first order the full displacement misses ``V q`` by ``−K⁻¹ r`` (one Newton correction), so
the pose misses by the dual-weighted residual (DWR) ``δ = −P K⁻¹ r``, ``P`` the model's linear
pose fit: the indicators of ROM error models (ROMES: Drohmann & Carlberg 2015; for non-linear
problems with sampled residuals, Freno & Carlberg 2019) are of this kind. Two tangents ``K``:

* ``"linear"``: the linear stiffness ``K₀`` — its adjoint ``K₀⁻¹ Pᵀ`` is six back-substitutions
  done once, after which an indicator costs one full internal-force evaluation;
* ``"exact"``: the tangent at ``V q`` — a full Newton correction from the ROM's state (one
  tangent assembly and factorisation a force vector: the cost of one iteration of a full run).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from mechlib.params import check_choice

if TYPE_CHECKING:
    from mechlib.fe.nonlinear import NonlinearSolver
    from mechlib.hexflex.rom.model import ReducedOrderModel

TANGENTS: tuple[str, ...] = ("linear", "exact")


def pose_adjoint(solver: NonlinearSolver) -> np.ndarray:
    """The adjoint of the pose: ``K₀⁻¹ Pᵀ``, so that ``P K₀⁻¹ r = r @ K₀⁻¹ Pᵀ`` (``K₀``
    symmetric) for any residual ``r``.

    Parameters
    ----------
    solver : NonlinearSolver
        The full model (its factorised linear stiffness ``K₀`` and pose fit ``P``: ``P u`` is
        the fitted stage pose [µm, µrad] of the displacements ``u`` [mm]).

    Returns
    -------
    ndarray (n_dofs, 6)
        The linear model's responses [mm] to the six rows of ``P`` applied as loads (six
        back-substitutions).
    """
    model = solver.model
    rows = np.zeros((model.n_dofs, 6))
    rows[model.fe.stage_idx, :] = model.fe.fit.T
    return np.column_stack([model.back_substitute(rows[:, j]) for j in range(6)])


def dual_weighted_residuals(
    rom: ReducedOrderModel,
    solver: NonlinearSolver,
    forces: object,
    tangent: str = "linear",
) -> np.ndarray:
    """The ROM's pose-error indicators ``δ = −P K⁻¹ r(V q)`` [µm, µrad] under force vectors.

    Parameters
    ----------
    rom : ReducedOrderModel
        Built on ``solver``'s model.
    solver : NonlinearSolver
        The full model (its internal force, and for ``"exact"`` its tangent).
    forces : array_like (n, 6) or (6,)
        Actuator forces [N] within the ROM's ``force_range``.
    tangent : {"linear", "exact"}
        ``K``: the linear stiffness (one internal force a vector) or the tangent at ``V q``
        (also one factorisation a vector).

    Returns
    -------
    ndarray (n, 6)
        ``rom.poses(forces) + δ`` is the pose after one correction with ``K``.

    Raises
    ------
    ValueError
        On forces out of range, a bad ``tangent``, a basis of another model, or a ROM state
        that inverts an element (names the force vector).
    """
    tangent = check_choice("tangent", tangent, TANGENTS)
    f = rom.check_design(forces)
    if rom.basis.shape[0] != solver.model.n_dofs:
        raise ValueError(
            f"rom has {rom.basis.shape[0]} DOFs, solver's model {solver.model.n_dofs}: "
            "build the ROM on this solver"
        )
    model = solver.model
    adjoint = pose_adjoint(solver) if tangent == "linear" else None
    loads = model.load_vectors()
    q = rom.coordinates(f)
    out = np.empty((len(f), 6))
    for i in range(len(f)):
        u = rom.basis @ q[i]
        residual = solver.residual(u, loads @ f[i])
        if residual is None:
            raise ValueError(f"the ROM's state inverts an element under forces [N] {f[i].tolist()}")
        if adjoint is not None:
            out[i] = -(residual @ adjoint)
        else:
            out[i] = -model.pose_of(solver.factorised_tangent(u)(residual))
    return out
