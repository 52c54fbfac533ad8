"""The exact polynomial reduced internal force of weighted Saint Venant–Kirchhoff Q2 elements.

With a reduced basis ``V`` the displacement gradient at a quadrature point is linear in the
reduced coordinates, ``H(q) = G q``, so the Green strain ``E = ε(q) + Q(q)`` (``ε = sym H``,
``Q = ½ HᵀH``) is quadratic and the SVK strain energy ``½ E:D:E`` quartic. Summed with weights
``w_e`` over elements (all of them, or an ECSW sample, :mod:`mechlib.hexflex.rom.ecsw`), the reduced
energy is

    W(q) = ½ qᵀ K q + b(q, q, q) + ½ c(q, q, q, q),

with ``b`` and ``c`` fully symmetric (``b`` from ``ε:D:Q``, ``c`` from ``Q:D:Q``); its gradient is
the reduced internal force ``Kq + 3 b(q,q,·) + 2 c(q,q,q,·)`` — the same numbers as
``Σ_e w_e V_eᵀ f_e(V_e q)`` from the element kernels, to round-off — and its Hessian the reduced
tangent ``K + 6 b(q,·,·) + 6 c(q,q,·,·)``. ``c`` is stored on the ``n(n+1)/2`` pairs ``i ≤ j``
(both of its index pairs), so one Newton iteration costs one product with an ``n(n+1)/2``-square
matrix, whatever the number of elements.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from scipy.linalg.blas import dsymv, dsyrk

from mechlib.blas import one_thread
from mechlib.hexflex.rom.ecsw import element_basis

if TYPE_CHECKING:
    from mechlib.fe.svk_tangent import SVKTangent

#: Elements per batch when the tensors are accumulated (temporaries ∝ CHUNK · n²).
CHUNK = 8
#: Voigt pairs (j, l) of the symmetric strain, in tensor (not engineering) components.
PAIRS = ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))


class PolynomialForce:
    """Reduced SVK internal force as an exact polynomial in the reduced coordinates.

    Parameters
    ----------
    stiffness : ndarray (n, n)
        ``K`` [N/mm] (symmetric).
    cubic : ndarray (n, n²)
        ``b`` reshaped, row ``i`` the matrix ``b(e_i, ·, ·)``.
    quartic : ndarray (n(n+1)/2, n(n+1)/2)
        ``c`` on index pairs ``i ≤ j`` (row pair, column pair; symmetric).
    """

    def __init__(self, stiffness: np.ndarray, cubic: np.ndarray, quartic: np.ndarray) -> None:
        self.stiffness, self.cubic, self.quartic = stiffness, cubic, quartic
        n = self.size
        self._iu, self._ju = np.triu_indices(n)
        full = np.empty((n, n), dtype=np.int64)
        full[self._iu, self._ju] = np.arange(len(self._iu))
        full[self._ju, self._iu] = full[self._iu, self._ju]
        self._full = full.ravel()
        self._mult = np.where(self._iu == self._ju, 1.0, 2.0)
        self._quartic_f = np.asfortranarray(quartic)

    @property
    def size(self) -> int:
        """Number of reduced coordinates."""
        return self.stiffness.shape[0]

    def terms(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``b(q,·,·)`` and ``c(q,q,·,·)`` for a stack of states ``q`` (N, n): two (N, n, n)."""
        n = self.size
        pairs = (q[:, self._iu] * q[:, self._ju]) * self._mult
        if len(q) == 1:  # a symmetric product reads half the matrix: ≈ 2× faster (measured)
            packed = dsymv(1.0, self._quartic_f, pairs[0])[None]
        else:
            packed = pairs @ self.quartic
        zc = packed[:, self._full].reshape(len(q), n, n)
        bq = (q @ self.cubic).reshape(len(q), n, n)
        return bq, zc

    def force(self, q: np.ndarray) -> np.ndarray:
        """Reduced internal force (N, n) [N] at states ``q`` (N, n) [mm]."""
        bq, zc = self.terms(q)
        return q @ self.stiffness + ((3.0 * bq + 2.0 * zc) @ q[:, :, None])[:, :, 0]

    def energy(self, q: np.ndarray) -> np.ndarray:
        """Reduced strain energy (N,) [mJ] at states ``q`` (N, n) [mm]."""
        bq, zc = self.terms(q)
        quad = 0.5 * self.stiffness + bq + 0.5 * zc
        return (q[:, None, :] @ quad @ q[:, :, None])[:, 0, 0]


def polynomial_force(
    tangent: SVKTangent,
    basis: np.ndarray,
    cells: np.ndarray,
    weights: np.ndarray,
    chunk: int = CHUNK,
) -> PolynomialForce:
    """The reduced energy's tensors, summed over the elements ``cells`` with ``weights``.

    Parameters
    ----------
    tangent : SVKTangent
        The model's batched kernels (its ``gradients``, ``weights``, ``lame`` and ``shear``).
    basis : ndarray (n_dofs, n)
        Reduced basis.
    cells : ndarray of int (m,)
        Elements summed.
    weights : ndarray (m,)
        Their weights (1 for the plain Galerkin sum).
    chunk : int
        Elements per batch.

    Returns
    -------
    PolynomialForce
    """
    n = basis.shape[1]
    iu, ju = np.triu_indices(n)
    d6 = tangent.lame * np.outer(np.arange(6) < 3, np.arange(6) < 3) + 2.0 * tangent.shear * (
        np.diag([1.0, 1.0, 1.0, 2.0, 2.0, 2.0])
    )
    root = np.linalg.cholesky(d6)  # D = R Rᵀ: Σ Qᵀ D Q as one symmetric rank-k update
    stiff = np.zeros((n, n))
    cubic = np.zeros((n, n * n))
    quartic = np.zeros((len(iu), len(iu)), order="F")
    with one_thread():
        for start in range(0, len(cells), chunk):
            sel = cells[start : start + chunk]
            ve = element_basis(tangent, basis, sel).reshape(len(sel), 3, -1, n)  # (m, c, a, n)
            # G[m, q, c, j, k] = Σ_a dN_a/dX_j V[a, c, k]: displacement gradient per basis vector
            grad = np.einsum("mqja,mcak->mqcjk", tangent.gradients[sel], ve)
            w = (tangent.weights[sel] * weights[start : start + chunk, None]).reshape(-1)
            g = grad.reshape(-1, 3, 3, n)  # (P, c, j, k)
            lin = np.stack([0.5 * (g[:, j, m] + g[:, m, j]) for j, m in PAIRS], axis=1)
            quad = np.stack(
                [0.5 * np.einsum("pck,pcm->pkm", g[:, :, j], g[:, :, m]) for j, m in PAIRS],
                axis=1,
            )  # (P, 6, n, n): Q_jl = ½ Σ_c H_cj H_cl, not yet symmetric in (k, m)
            quad = 0.5 * (quad + quad.swapaxes(-1, -2))
            dlin = np.einsum("uv,pvk->puk", d6, lin) * w[:, None, None]
            stiff += lin.reshape(-1, n).T @ dlin.reshape(-1, n)
            cubic += dlin.reshape(-1, n).T @ quad.reshape(-1, n * n)
            packed = quad[:, :, iu, ju]  # (P, 6, n(n+1)/2)
            scaled = np.einsum("vu,pvk->puk", root, packed) * np.sqrt(w)[:, None, None]
            # upper triangle of quartic += scaledᵀ scaled (half the flops of a product)
            quartic = dsyrk(1.0, scaled.reshape(-1, len(iu)), 1.0, quartic, trans=1,
                            overwrite_c=1)  # fmt: skip
    quartic = np.triu(quartic) + np.triu(quartic, 1).T
    return PolynomialForce(0.5 * (stiff + stiff.T), *_symmetrise(cubic, quartic, n))


def _symmetrise(cubic: np.ndarray, quartic: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Fully symmetric ``b`` (n, n²) and packed ``c`` from the raw sums ``Σ ε D Q`` (symmetric in
    its last two indices) and ``Σ Q D Q`` on packed pairs."""
    b0 = cubic.reshape(n, n, n)
    b = (b0 + b0.transpose(2, 0, 1) + b0.transpose(1, 2, 0)) / 3.0
    iu, ju = np.triu_indices(n)
    full = np.empty((n, n), dtype=np.int64)
    full[iu, ju] = np.arange(len(iu))
    full[ju, iu] = full[iu, ju]
    t4 = quartic[full[:, :, None, None], full[None, None, :, :]]  # (n, n, n, n)
    c = (t4 + t4.transpose(0, 2, 1, 3) + t4.transpose(0, 2, 3, 1)) / 3.0
    packed = c[iu, ju][:, iu, ju]
    return b.reshape(n, n * n), 0.5 * (packed + packed.T)
