"""The reduced basis of the non-linear HexFlex ROM (:mod:`mechlib.hexflex.rom.model`).

Static modes and their static modal derivatives, POD of given displacement fields (Euclidean or
energy inner product), third-order corrections of the second-order responses, the seeded
training forces and the second-order training states of the ECSW fit.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp

if TYPE_CHECKING:
    from mechlib.fe.nonlinear import NonlinearSolver

#: Basis vectors whose Gram–Schmidt remainder is below this fraction of their norm are dropped.
RANK_TOL = 1e-8
#: POD vectors whose singular value is below this fraction of the first are dropped.
POD_TOL = 1e-6
#: Seed of the training forces.
SEED = 2010

_PAIR_I, _PAIR_J = np.triu_indices(6)
#: ½ f_i² θ_ii and f_i f_j θ_ij (i < j): the second-order term ½ Σ_ij f_i f_j θ_ij on pairs i ≤ j
PRODUCT_FACTOR = np.where(_PAIR_I == _PAIR_J, 0.5, 1.0)


_TRIPLES = np.array(
    [(i, j, k) for i in range(6) for j in range(i, 6) for k in range(j, 6)], dtype=np.int64
).T
#: Monomials of the six forces of degree 1 to 3: f_i, f_i f_j (i ≤ j), f_i f_j f_k (i ≤ j ≤ k)
#: (no constant: zero forces give exactly zero).
N_MONOMIALS = 6 + 21 + 56


def monomials(forces: np.ndarray) -> np.ndarray:
    """The force monomials (n, 83) of degree 1 to 3, in the order of ``N_MONOMIALS``."""
    i, j, k = _TRIPLES
    return np.hstack(
        [
            forces,
            products(forces),
            forces[:, i] * forces[:, j] * forces[:, k],
        ]
    )


def products(forces: np.ndarray) -> np.ndarray:
    """Force products ``f_i f_j``, i ≤ j (n, 21)."""
    return forces[:, _PAIR_I] * forces[:, _PAIR_J]


def unit(vectors: np.ndarray) -> np.ndarray:
    """The columns scaled to unit Euclidean norm."""
    return vectors / np.linalg.norm(vectors, axis=0)


def static_basis(solver: NonlinearSolver) -> tuple[np.ndarray, np.ndarray]:
    """Static modes (n_dofs, 6) [mm/N] and modal derivatives (n_dofs, 21) [mm/N²], i ≤ j.

    ``θ_ij = −K₀⁻¹ 2 N₂(φ_i, φ_j)`` of the unit-force modes, ``N₂`` from 4 + 2 internal-force
    evaluations per pair (by polarisation of the exact cubic), one multi-vector solve.
    """
    model, fint = solver.model, solver.batched.internal_force
    phi = model.back_substitute(model.load_vectors())

    def quadratic(x: np.ndarray) -> np.ndarray:
        plus, minus = fint(x), fint(-x)
        if plus is None or minus is None:
            raise ValueError("a static mode inverts an element: no modal derivative")
        return 0.5 * (plus + minus)

    diag = [quadratic(phi[:, i]) for i in range(6)]
    rhs = []
    for i in range(6):
        for j in range(i, 6):
            if i == j:
                n2 = diag[i]
            else:
                n2 = 0.5 * (quadratic(phi[:, i] + phi[:, j]) - diag[i] - diag[j])
            rhs.append(-2.0 * n2)
    theta = model.back_substitute(np.stack(rhs, axis=1))
    return phi, theta


def orthonormal(vectors: np.ndarray) -> np.ndarray:
    """Orthonormal basis of the columns (in order; twice-iterated Gram–Schmidt by QR), dropping
    columns whose remainder is below ``RANK_TOL`` of their norm."""
    q, r = np.linalg.qr(vectors)
    norms = np.linalg.norm(vectors, axis=0)
    keep = np.abs(np.diag(r)) > RANK_TOL * norms
    q = q[:, keep]
    q, r = np.linalg.qr(q)  # re-orthogonalise
    return q * np.sign(np.diag(r))


def pod(
    basis: np.ndarray,
    snapshots: np.ndarray,
    n_pod: int,
    stiffness: sp.sparray | sp.spmatrix | None = None,
) -> np.ndarray:
    """The ``n_pod`` leading POD vectors of the snapshots' part outside ``basis`` (columns
    scaled to unit norm): in the Euclidean inner product, or with ``stiffness`` in the energy
    one (``xᵀ K₀ y``, by the method of snapshots), which ranks a part by the strain energy it
    carries rather than by its size."""
    if stiffness is None:
        x = snapshots / np.linalg.norm(snapshots, axis=0)
        x = x - basis @ (basis.T @ x)
        u, s, _ = np.linalg.svd(x, full_matrices=False)
        n_pod = min(n_pod, int(np.count_nonzero(s > POD_TOL * s[0])))
        return u[:, :n_pod]
    kx = stiffness @ snapshots
    x = snapshots / np.sqrt(np.einsum("ij,ij->j", snapshots, kx))
    x = x - basis @ (basis.T @ x)
    gram = x.T @ (stiffness @ x)
    values, vectors = np.linalg.eigh(0.5 * (gram + gram.T))
    values, vectors = values[::-1], vectors[:, ::-1]
    n_pod = min(n_pod, int(np.count_nonzero(values > POD_TOL**2 * values[0])))
    return x @ (vectors[:, :n_pod] / np.sqrt(values[:n_pod]))


def training_forces(force_range: float, n_training: int, seed: int = SEED) -> np.ndarray:
    """Seeded training force vectors (n_training, 6) [N], uniform in ±force_range."""
    return np.random.default_rng(seed).uniform(-force_range, force_range, (n_training, 6))


def third_order(
    solver: NonlinearSolver, modes: np.ndarray, derivatives: np.ndarray, forces: np.ndarray
) -> np.ndarray:
    """``K₀⁻¹ r`` (n_dofs, n) of the second-order responses at ``forces``: ≈ minus their
    third-order terms ``−K₀⁻¹ (2 N₂(u₁, u₂) + N₃(u₁))``."""
    model = solver.model
    second = modes @ forces.T + derivatives @ (products(forces) * PRODUCT_FACTOR).T
    loads = model.load_vectors() @ forces.T
    residuals = np.empty_like(second)
    for k in range(len(forces)):
        res = solver.residual(second[:, k], loads[:, k])
        if res is None:
            raise ValueError(
                f"the second-order response to {forces[k].tolist()} N inverts an element"
            )
        residuals[:, k] = res
    return model.back_substitute(residuals)


def training_states(
    basis: np.ndarray,
    modes: np.ndarray,
    derivatives: np.ndarray,
    snapshots: np.ndarray | None,
    forces: np.ndarray,
) -> np.ndarray:
    """Reduced states the ECSW weights are fitted on: the second-order static response
    ``Φ f + ½ Σ_ij f_i f_j θ_ij`` at the training forces, and the snapshots."""
    second = (basis.T @ derivatives) * PRODUCT_FACTOR
    states = forces @ (basis.T @ modes).T + products(forces) @ second.T
    if snapshots is not None:
        states = np.vstack([states, snapshots @ basis])
    return states
