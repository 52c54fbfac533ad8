"""Error indicators of the reduced-order model, from the full model's residual at its solution.

The ROM's Galerkin equilibrium (its equations are the full ones projected on its basis ``V``)
leaves the full residual ``r = f(V q) − L F`` orthogonal to ``V`` — up to the hyper-reduction's
approximation of the internal force — but not zero; what is left estimates the ROM's error.
To first order the full displacement misses ``V q`` by ``−K⁻¹ r`` (one Newton correction), so
the pose misses by the dual-weighted residual (DWR) ``δ = −P K⁻¹ r``, ``P`` the model's linear
pose fit: the indicators of ROM error models (ROMES: Drohmann & Carlberg 2015; for non-linear
problems with sampled residuals, Freno & Carlberg 2019) are of this kind. Two tangents ``K``:

* ``"linear"``: the linear stiffness ``K₀`` — its adjoint ``A = K₀⁻¹ Pᵀ`` is six
  back-substitutions done once, after which ``r · A`` needs no assembled residual: it is the sum
  over quadrature points of the weighted first Piola–Kirchhoff stress at ``V q`` contracted with
  the gradients of ``A``'s six fields (the internal force's virtual work on them), computed for
  every force vector at once (:func:`projected_internal_force`: the displacement gradients of
  all states at a batch of elements are one matrix product with the basis's gradients);
* ``"exact"``: the tangent at ``V q`` — a full Newton correction from the ROM's state (one
  tangent assembly and factorisation a force vector: the cost of one iteration of a full run).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from mechlib.blas import one_thread
from mechlib.hexflex.rom.ecsw import element_basis
from mechlib.params import check_choice, check_int

if TYPE_CHECKING:
    from mechlib.fe.nonlinear import NonlinearSolver
    from mechlib.fe.svk_tangent import SVKTangent
    from mechlib.hexflex.rom.model import ReducedOrderModel

TANGENTS: tuple[str, ...] = ("linear", "exact")
#: Elements per batch of :func:`projected_internal_force` (its temporaries hold ≈ 10 floats per
#: quadrature point of the batch and force vector: 16 elements, 1000 vectors ≈ 35 MB each).
CHUNK = 16


def _gradients(grad: np.ndarray, fields: np.ndarray) -> np.ndarray:
    """Displacement gradients ``∂u_c/∂X_j`` (m, n_qp, 3 c, 3 j, k) at the quadrature points of
    elements whose shape-function gradients are ``grad`` (m, n_qp, 3, n_ep), of the fields
    ``fields`` restricted to them ((m, 3 n_ep, k), as :func:`.ecsw.element_basis` gives)."""
    m, _, _, n_ep = grad.shape
    return np.einsum("mqja,mcak->mqcjk", grad, fields.reshape(m, 3, n_ep, -1))


def _first_piola(g: np.ndarray, lame: float, shear: float, inverted: np.ndarray) -> np.ndarray:
    """The SVK first Piola–Kirchhoff stress ``P = F S`` (points, 3, 3, states) from displacement
    gradients ``g`` (points, 3, 3, states), component by component: each of the 9 + 6 + 9 sums of
    three products is one operation on whole (points, states) planes, not a 3 × 3 product per
    point and state (which took three quarters of :func:`projected_internal_force`). Marks in
    ``inverted`` (states,) the states with det F ≤ 0 at a point."""
    f = [[g[:, c, j] + (1.0 if c == j else 0.0) for j in range(3)] for c in range(3)]
    det = (
        f[0][0] * (f[1][1] * f[2][2] - f[1][2] * f[2][1])
        - f[0][1] * (f[1][0] * f[2][2] - f[1][2] * f[2][0])
        + f[0][2] * (f[1][0] * f[2][1] - f[1][1] * f[2][0])
    )
    inverted |= np.any(det <= 0.0, axis=0)
    # C = FᵀF (symmetric); S = λ tr(E) I + 2 μ E = μ C + (λ (tr C − 3) / 2 − μ) I
    c = {(a, b): f[0][a] * f[0][b] + f[1][a] * f[1][b] + f[2][a] * f[2][b]
         for a in range(3) for b in range(a, 3)}  # fmt: skip
    shift = 0.5 * lame * (c[0, 0] + c[1, 1] + c[2, 2] - 3.0) - shear
    s = [[shear * c[min(a, b), max(a, b)] + (shift if a == b else 0.0) for b in range(3)]
         for a in range(3)]  # fmt: skip
    p = np.empty_like(g)
    for a in range(3):
        for b in range(3):
            p[:, a, b] = f[a][0] * s[0][b] + f[a][1] * s[1][b] + f[a][2] * s[2][b]
    return p


def projected_internal_force(
    tangent: SVKTangent,
    basis: np.ndarray,
    coordinates: np.ndarray,
    tests: np.ndarray,
    chunk: int = CHUNK,
) -> tuple[np.ndarray, np.ndarray]:
    """The full internal force at the states ``V q``, projected on test fields: ``f(V q) · A``.

    The Saint Venant–Kirchhoff internal force of :class:`mechlib.fe.svk_tangent.SVKTangent`
    (``Σ_q w_q P_q ∇N_q`` per element, ``P = F S``), contracted with each test field by its
    virtual work, ``Σ_qp w P : ∇A``; per batch of elements, the deformation gradients of every
    state are one matrix product of the basis's gradients with the coordinates. The same
    numbers as ``internal_force(V q) @ A`` to round-off.

    Parameters
    ----------
    tangent : SVKTangent
        The model's batched SVK kernels (gradients, weights, Lamé constants, connectivity).
    basis : ndarray (n_dofs, n)
        Reduced basis ``V`` (free DOFs, node-major).
    coordinates : ndarray (N, n)
        Reduced coordinates ``q`` [mm] of the states.
    tests : ndarray (n_dofs, k)
        Test fields ``A`` (free DOFs).
    chunk : int
        Elements per batch, ≥ 1.

    Returns
    -------
    projected : ndarray (N, k)
        ``f(V q) · A`` [N · unit of A], where ``inverted`` is False.
    inverted : ndarray of bool (N,)
        States that invert an element (det F ≤ 0 at a quadrature point).
    """
    chunk = check_int("chunk", chunk, low=1)
    q = np.asarray(coordinates, dtype=float)
    n_el = tangent.element_nodes.shape[0]
    out = np.zeros((len(q), tests.shape[1]))
    inverted = np.zeros(len(q), dtype=bool)
    with one_thread():
        for start in range(0, n_el, chunk):
            sel = np.arange(start, min(start + chunk, n_el))
            grad = tangent.gradients[sel]
            h = _gradients(grad, element_basis(tangent, basis, sel))  # (m, n_qp, 3, 3, n)
            ga = _gradients(grad, element_basis(tangent, tests, sel))  # (m, n_qp, 3, 3, k)
            points = h.shape[0] * h.shape[1]
            # ∂u_c/∂X_j of every state: (points, 3 c, 3 j, state), one row a (point, c, j)
            g = (h.reshape(-1, h.shape[-1]) @ q.T).reshape(points, 3, 3, len(q))
            p = _first_piola(g, tangent.lame, tangent.shear, inverted)
            p *= tangent.weights[sel].reshape(-1)[:, None, None, None]  # w F S
            out += p.reshape(points * 9, len(q)).T @ ga.reshape(points * 9, -1)
    return out, inverted


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
    if adjoint is not None and solver.batched is not None:  # every force vector at once
        projected, inverted = projected_internal_force(solver.batched, rom.basis, q, adjoint)
        if inverted.any():
            bad = f[int(np.argmax(inverted))]
            raise ValueError(f"the ROM's state inverts an element under forces [N] {bad.tolist()}")
        return -(projected - f @ (loads.T @ adjoint))
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
