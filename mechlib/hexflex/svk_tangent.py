"""Fast exact tangent stiffness of the total-Lagrangian Saint Venant–Kirchhoff HexFlex (Q2).

The same matrix as SfePy's ``dw_tl_he_svk_consistent`` term (:mod:`mechlib.hexflex.nonlinear`),
built with batched BLAS instead of SfePy's C loop over quadrature points. With ``F = I + ∇u``
(∇ in the reference configuration), the Green strain ``E = ½ (FᵀF − I)`` in Voigt order
(xx, yy, zz, xy, xz, yz) with engineering shears ``2 E_ij``, and the second Piola–Kirchhoff stress
``S = D e`` (``D`` from ``stiffness_from_youngpoisson``, SfePy's own Voigt order), the element
tangent is

    K_e = Σ_q w_q [B_qᵀ D B_q + (∇N_qᵀ S_q ∇N_q) ⊗ I₃],

where ``B_q`` (6 × 81) maps nodal displacement increments to increments of the engineering
Voigt strain and ``w_q`` is the quadrature weight times det J. The element matrices of a batch of
elements are one stacked product ``Bᵀ (W B)`` (B stacked over the 27 quadrature points) and
are summed into the CSR pattern by one ``np.bincount`` over an index computed once. Like
:func:`mechlib.hexflex.nonlinear.tl_evaluator`, one ``D`` acts on the whole domain (the model's
``body_factor`` is not applied), and the clamp holds the ground at zero displacement.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp
from threadpoolctl import threadpool_limits

from mechlib.hexflex import problem as fe
from mechlib.params import check_int

if TYPE_CHECKING:
    from mechlib.hexflex.model import HexFlexModel

#: Elements per batch of matrix products: small batches keep the temporaries (≈ 3 MB each at
#: 32 Q2 elements) in cache, 1.4× faster than batches of 500 (measured).
CHUNK = 32
#: Index pairs (i, j) of the shear entries of the Voigt order (xx, yy, zz, xy, xz, yz).
_SHEAR = ((0, 1), (0, 2), (1, 2))


class SVKTangent:
    """Tangent stiffness of the TL Saint Venant–Kirchhoff model of one Q2 HexFlex model.

    Built once per model: it holds the basis-function gradients in physical coordinates at the
    quadrature points and their weights (weight · det J), the elements' free-node connectivity,
    the CSR pattern of the reduced matrix and the scatter index of every element-matrix entry.

    Parameters
    ----------
    model : HexFlexModel
        A model with ``element="q2"``.
    chunk : int, optional
        Elements per batch of matrix products, in [1, 5000] (temporaries ∝ ``chunk``).

    Raises
    ------
    ValueError
        If the model is not Q2 or ``chunk`` is out of range.

    Notes
    -----
    The element matrices are kept between calls of :meth:`matrix` (n_el · 81² floats, 260 MB on
    the 5004-element model, beside a scatter index of the same size): not thread-safe.
    """

    def __init__(self, model: HexFlexModel, chunk: int = CHUNK) -> None:
        if model.element != "q2":
            raise ValueError(
                f"element must be 'q2' for the TL Saint Venant–Kirchhoff tangent (SVKTangent), "
                f"got {model.element!r}"
            )
        from sfepy.mechanics.matcoefs import stiffness_from_youngpoisson

        p = model.fe
        vg, _ = p.field.get_mapping(p.omega, fe.integral(), "cell")
        self._grad = np.array(vg.bfg, dtype=float)  # (n_el, n_qp, 3, n_ep): dN/dX
        self._weight = np.array(vg.det[..., 0, 0], dtype=float)  # (n_el, n_qp): w · det J
        self._elastic = np.asarray(stiffness_from_youngpoisson(3, model.young, model.poisson))
        self.chunk = check_int("chunk", chunk, low=1, high=5000)
        dofs = np.asarray(p.eq).reshape(-1, 3)  # reduced DOF of (field node, component) or -1
        free = dofs[:, 0] >= 0
        n_free = int(free.sum())
        layout = 3 * np.arange(n_free)[:, None] + np.arange(3)
        if np.any((dofs >= 0) != free[:, None]) or not np.array_equal(dofs[free], layout):
            raise RuntimeError("reduced DOFs are not node-major with whole nodes clamped")
        if np.any(p.pb.get_variables().make_full_vec(np.zeros(model.n_dofs))):
            raise RuntimeError("the clamp prescribes non-zero displacements")
        rank = np.full(len(dofs), -1, dtype=np.int64)
        rank[free] = np.arange(n_free)
        econn = np.asarray(p.field.get_econn("cell", p.omega), dtype=np.int64)
        #: Free-node index of every element node, −1 where clamped (n_el, n_ep).
        self._nodes = rank[econn]
        self.n_dofs = 3 * n_free
        self._indptr, self._indices, self._scatter = _pattern(self._nodes, n_free)
        self.nnz = len(self._indices)
        self._values: np.ndarray | None = None  # element matrices (n_el, 3 n_ep, 3 n_ep)
        self._dof_index: np.ndarray | None = None  # reduced DOF of each element force entry

    def pattern(self) -> sp.csr_array:
        """The CSR pattern of :meth:`matrix` (symmetric), with every stored value 1."""
        shape = (self.n_dofs, self.n_dofs)
        return sp.csr_array(
            (np.ones(self.nnz), self._indices.copy(), self._indptr.copy()), shape=shape
        )

    def matrix(self, u: object) -> sp.csr_array:
        """Reduced tangent stiffness [N/mm] at the reduced displacement vector ``u`` [mm].

        Parameters
        ----------
        u : array_like (n_dofs,)
            Reduced displacements (free DOFs, the order of ``model.eq``), finite.

        Returns
        -------
        scipy.sparse.csr_array (n_dofs, n_dofs)
            The derivative of the TL residual at ``u`` (sorted indices, one BLAS thread).

        Raises
        ------
        ValueError
            If ``u`` has the wrong shape, holds NaN/inf or inverts an element (det F ≤ 0).
        """
        shape = (self.n_dofs, self.n_dofs)
        data = self.values(u)
        return sp.csr_array((data, self._indices.copy(), self._indptr.copy()), shape=shape)

    def values(self, u: object) -> np.ndarray:
        """The stored values (nnz,) of :meth:`matrix` at ``u``, in the order of
        :meth:`pattern` (no index arrays built: what a factoriser of the pattern needs)."""
        arr = self._check_state(u)
        nodal = np.vstack([arr.reshape(-1, 3), np.zeros((1, 3))])  # row −1: clamped nodes
        n_el, n_ep = self._nodes.shape
        if self._values is None:  # kept: writing fresh pages costs ≈ 0.3 s a call
            self._values = np.empty((n_el, 3 * n_ep, 3 * n_ep))
        with threadpool_limits(limits=1, user_api="blas"):
            for start in range(0, n_el, self.chunk):
                cells = slice(start, start + self.chunk)
                self._element_matrices(nodal[self._nodes[cells]], cells, self._values[cells])
        data = np.bincount(self._scatter, weights=self._values.ravel(), minlength=self.nnz + 1)
        return data[:-1]

    def internal_force(self, u: object) -> np.ndarray | None:
        """Reduced internal force [N] at ``u`` [mm]: the TL residual without the load.

        The same vector as SfePy's evaluator of the consistent term (``eval_residual``), from
        the same strain and stress as :meth:`matrix`: ``Σ_q w_q B_qᵀ S_q`` per element, summed
        into the free DOFs. Returns ``None`` where ``u`` inverts an element (det F ≤ 0), as
        SfePy refuses such a state.

        Parameters
        ----------
        u : array_like (n_dofs,)
            Reduced displacements, finite.
        """
        arr = self._check_state(u)
        nodal = np.vstack([arr.reshape(-1, 3), np.zeros((1, 3))])
        n_el, n_ep = self._nodes.shape
        if self._dof_index is None:
            node = np.where(self._nodes >= 0, self._nodes, self.n_dofs // 3)
            # (n_el, component, node) → reduced DOF, one bin past the end for clamped nodes
            dof = 3 * node[:, None, :] + np.arange(3)[None, :, None]
            self._dof_index = np.where(self._nodes[:, None, :] >= 0, dof, self.n_dofs).ravel()
        forces = np.empty((n_el, 3 * n_ep))
        with threadpool_limits(limits=1, user_api="blas"):
            for start in range(0, n_el, self.chunk):
                cells = slice(start, start + self.chunk)
                out = self._element_forces(nodal[self._nodes[cells]], cells)
                if out is None:
                    return None
                forces[cells] = out
        return np.bincount(self._dof_index, weights=forces.ravel(), minlength=self.n_dofs + 1)[:-1]

    def _check_state(self, u: object) -> np.ndarray:
        arr = np.asarray(u, dtype=float)
        if arr.shape != (self.n_dofs,):
            raise ValueError(f"u must have shape ({self.n_dofs},) (n_dofs), got {arr.shape}")
        if not np.all(np.isfinite(arr)):
            raise ValueError("u must hold only finite numbers (found NaN or inf)")
        return arr

    def _kinematics(self, disp: np.ndarray, cells: slice):
        """Fᵀ, the second Piola–Kirchhoff stress (Voigt) and B of the elements ``cells``, or
        ``None`` if one inverts."""
        grad = self._grad[cells]
        m, n_qp, _, n_ep = grad.shape
        ft = grad @ disp[:, None] + np.eye(3)  # Fᵀ: ft[..., j, c] = ∂x_c/∂X_j
        if np.any(np.linalg.det(ft) <= 0.0):
            return None
        stress = self._stress(ft)  # second Piola–Kirchhoff, Voigt (m, n_qp, 6)
        # b[:, k, q, c, a]: Voigt strain increment k at point q per displacement (node a, comp. c)
        b = np.empty((m, 6, n_qp, 3, n_ep))
        for i in range(3):
            np.multiply(grad[:, :, i, None, :], ft[:, :, i, :, None], out=b[:, i])
        for k, (i, j) in enumerate(_SHEAR, start=3):
            np.multiply(grad[:, :, i, None, :], ft[:, :, j, :, None], out=b[:, k])
            b[:, k] += grad[:, :, j, None, :] * ft[:, :, i, :, None]
        return ft, stress, b

    def _element_forces(self, disp: np.ndarray, cells: slice) -> np.ndarray | None:
        """Internal forces (m, 3 n_ep), DOFs ordered (component, node), or ``None`` if an
        element inverts: ``Σ_q w_q P_q ∇N_q`` with the first Piola–Kirchhoff stress P = F S
        (the same as ``Σ_q w_q B_qᵀ S_q``, without forming B)."""
        grad = self._grad[cells]
        m, n_qp, _, n_ep = grad.shape
        ft = grad @ disp[:, None] + np.eye(3)  # Fᵀ: ft[..., j, c] = ∂x_c/∂X_j
        if np.any(np.linalg.det(ft) <= 0.0):
            return None
        stress = self._stress(ft)
        s = np.empty((m, n_qp, 3, 3))
        for i in range(3):
            s[..., i, i] = stress[..., i]
        for k, (i, j) in enumerate(_SHEAR, start=3):
            s[..., i, j] = s[..., j, i] = stress[..., k]
        p = ft.swapaxes(-1, -2) @ (s * self._weight[cells][..., None, None])  # w F S
        return np.einsum("mqcj,mqja->mca", p, grad, optimize=True).reshape(m, 3 * n_ep)

    def _stress(self, ft: np.ndarray) -> np.ndarray:
        """Second Piola–Kirchhoff stress (Voigt, (m, n_qp, 6)) from Fᵀ."""
        c = ft @ ft.swapaxes(-1, -2)  # right Cauchy–Green tensor FᵀF
        strain = np.stack(
            [0.5 * (c[..., i, i] - 1.0) for i in range(3)] + [c[..., i, j] for i, j in _SHEAR],
            axis=-1,
        )  # engineering Voigt strain (m, n_qp, 6)
        return strain @ self._elastic.T

    def _element_matrices(self, disp: np.ndarray, cells: slice, out: np.ndarray) -> None:
        """Write into ``out`` (m, 3 n_ep, 3 n_ep) the tangents, DOFs ordered (component, node),
        of the elements ``cells`` with nodal displacements ``disp`` (m, n_ep, 3)."""
        grad, weight = self._grad[cells], self._weight[cells]
        m, n_qp, _, n_ep = grad.shape
        kin = self._kinematics(disp, cells)
        if kin is None:
            raise ValueError("u must not invert an element (det F <= 0 at a quadrature point)")
        _, stress, b = kin
        wdb = np.matmul(self._elastic, b.reshape(m, 6, -1)).reshape(b.shape)
        wdb *= weight[:, None, :, None, None]
        stack = (m, 6 * n_qp, 3 * n_ep)  # rows (k, q): the sum over points is the product's
        np.matmul(b.reshape(stack).swapaxes(1, 2), wdb.reshape(stack), out=out)
        # geometric (initial-stress) term: Σ_q w ∇Nᵀ S ∇N on each displacement component
        s = np.empty((m, n_qp, 3, 3))
        for i in range(3):
            s[..., i, i] = stress[..., i]
        for k, (i, j) in enumerate(_SHEAR, start=3):
            s[..., i, j] = s[..., j, i] = stress[..., k]
        sg = (s * weight[..., None, None]) @ grad  # (m, q, 3, n_ep)
        kgeo = np.matmul(
            grad.reshape(m, n_qp * 3, n_ep).swapaxes(1, 2), sg.reshape(m, n_qp * 3, n_ep)
        )
        blocks = out.reshape(m, 3, n_ep, 3, n_ep)
        for comp in range(3):
            blocks[:, comp, :, comp, :] += kgeo


def _pattern(nodes: np.ndarray, n_free: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """CSR pattern of the reduced matrix and the scatter index of the element entries.

    Parameters
    ----------
    nodes : ndarray (n_el, n_ep)
        Free-node index of each element node, −1 where clamped.
    n_free : int
        Number of free nodes (3 DOFs each, DOF ``3 node + component``).

    Returns
    -------
    indptr, indices : ndarray of int32
        CSR structure (sorted column indices) of the (3 n_free)² matrix.
    scatter : ndarray of int64 (n_el · (3 n_ep)²,)
        Position in ``indices`` of each element-matrix entry (element, c, a, d, b); ``nnz``
        (one past the end) for entries of clamped DOFs.
    """
    row, col = nodes[:, :, None], nodes[:, None, :]
    ok = (row >= 0) & (col >= 0)
    keys, inverse = np.unique((row * n_free + col)[ok], return_inverse=True)
    brow, bcol = np.divmod(keys, n_free)  # 3 × 3 blocks, row-major order
    start = np.searchsorted(brow, np.arange(n_free + 1))
    degree = np.diff(start)
    nnzb = len(keys)
    three = np.arange(3)
    # entry (component c, d) of block k sits in row 3 brow + c at 3 (k − start) + d
    first = start[brow]
    pos = (
        9 * first[:, None, None]
        + 3 * three[:, None] * degree[brow][:, None, None]
        + 3 * (np.arange(nnzb) - first)[:, None, None]
        + three
    )
    indices = np.empty(9 * nnzb, dtype=np.int32)
    indices[pos] = 3 * bcol[:, None, None] + three
    indptr = np.append(9 * start[:-1, None] + 3 * three * degree[:, None], 9 * nnzb)
    pos = np.concatenate([pos, np.full((1, 3, 3), 9 * nnzb)])  # the clamped entries' bin
    block = np.full(ok.shape, nnzb, dtype=np.int64)
    block[ok] = inverse.ravel()
    # (n_el, c, a, d, b): the element matrices' order
    scatter = pos[block[:, None, :, None, :], three[:, None, None, None], three[:, None]]
    return indptr.astype(np.int32), indices, scatter.ravel()
