"""Fast exact tangent stiffness of a total-Lagrangian Saint Venant–Kirchhoff Q2 solid.

The same matrix as SfePy's ``dw_tl_he_svk_consistent`` term (:mod:`mechlib.fe.nonlinear`),
built with batched BLAS instead of SfePy's C loop over quadrature points. With ``F = I + ∇u``
(∇ in the reference configuration), the Green strain ``E = ½ (FᵀF − I)`` and the second
Piola–Kirchhoff stress ``S = λ tr(E) I + 2 μ E`` (λ, μ read from SfePy's isotropic
``stiffness_from_youngpoisson``; the constructor checks that it is isotropic), the element
tangent is

    K_e = Σ_q w_q [B_qᵀ D B_q + I₃ ⊗ (∇N_qᵀ S_q ∇N_q)]   (DOFs ordered component, node),

where ``B_q`` maps nodal displacement increments to increments of the Voigt strain and ``w_q``
is the quadrature weight times det J. For an isotropic ``D`` the material term needs no B: with
``h_a = F ∇N_a`` and ``b = F Fᵀ`` its block (components c, d; nodes a, b) is
``Σ_q w (λ h_ac h_bd + μ h_ad h_bc + μ b_cd ∇N_a·∇N_b)`` — one product over the stacked ``h``
and six small ones over ∇N, half the multiplications of ``Bᵀ (D B)``. The element matrices
are summed into the CSR pattern (or its upper triangle, what a Cholesky reads) by one
``np.bincount`` over an index computed once. Like :func:`mechlib.fe.sfepy_tl.tl_evaluator`,
one ``D`` acts on the whole domain (the model's ``body_factor`` is not applied), and the clamp
holds the ground at zero displacement.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp

from mechlib.blas import one_thread
from mechlib.fe import sfepy_base as fe
from mechlib.params import check_int

if TYPE_CHECKING:
    from mechlib.fe.protocol import SolidModel

#: Elements per batch of matrix products: small batches keep the temporaries (≤ 1.7 MB each at
#: 32 Q2 elements) in cache; 16–64 were measured within 5 %, 8 and 128 6–12 % slower.
CHUNK = 32


class SVKTangent:
    """Tangent stiffness of the TL Saint Venant–Kirchhoff model of one Q2 solid model.

    Built once per model: it holds the basis-function gradients in physical coordinates at the
    quadrature points and their weights (weight · det J), the elements' free-node connectivity,
    the CSR pattern of the reduced matrix and the scatter index of every element-matrix entry.

    Parameters
    ----------
    model : SolidModel
        A model with ``element="q2"``.
    chunk : int, optional
        Elements per batch of matrix products, in [1, 5000] (temporaries ∝ ``chunk``).
    order : int, optional
        Quadrature order (SfePy's, on the hexahedron), in [2, 10]: the default
        :data:`mechlib.fe.sfepy_base.QUAD_ORDER` (3 × 3 × 3 Gauss points) is the linear
        model's; a higher one checks the quadrature error of the non-linear integrands.

    Raises
    ------
    ValueError
        If the model is not Q2, or ``chunk`` or ``order`` is out of range.

    Notes
    -----
    The element matrices are kept between calls of :meth:`matrix` (n_el · 81² floats, 260 MB on
    the 5004-element model, beside a scatter index of the same size; :meth:`upper_values` adds
    two indices and a buffer of half that size each, ≈ 400 MB): not thread-safe.
    """

    def __init__(self, model: SolidModel, chunk: int = CHUNK, order: int = fe.QUAD_ORDER) -> None:
        if model.element != "q2":
            raise ValueError(
                f"element must be 'q2' for the TL Saint Venant–Kirchhoff tangent (SVKTangent), "
                f"got {model.element!r}"
            )
        from sfepy.mechanics.matcoefs import stiffness_from_youngpoisson

        p = model.fe
        self.order = check_int("order", order, low=2, high=10)
        vg, _ = p.field.get_mapping(p.omega, fe.integral(self.order), "cell")
        self._grad = np.array(vg.bfg, dtype=float)  # (n_el, n_qp, 3, n_ep): dN/dX
        self._weight = np.array(vg.det[..., 0, 0], dtype=float)  # (n_el, n_qp): w · det J
        elastic = np.asarray(stiffness_from_youngpoisson(3, model.young, model.poisson))
        #: Lamé's λ and μ of SfePy's (isotropic) elasticity matrix in Voigt order
        self._lame, self._shear = float(elastic[0, 1]), float(elastic[3, 3])
        normal = np.arange(6) < 3
        shear_part = self._shear * np.diag(np.where(normal, 2.0, 1.0))
        isotropic = self._lame * np.outer(normal, normal) + shear_part
        if not np.allclose(elastic, isotropic, rtol=1e-12, atol=0.0):
            raise RuntimeError("the elasticity matrix is not isotropic in SfePy's Voigt order")
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
        #: element entries summed into the upper triangle, their positions there, its size and
        #: a buffer of their values (built by the first :meth:`upper_values`)
        self._upper: tuple[np.ndarray, np.ndarray, int, np.ndarray] | None = None

    # per-element data, read-only (for a hyper-reduction, its indicators, material regions)
    @property
    def element_nodes(self) -> np.ndarray:
        """Free-node index of every element node, −1 where clamped (n_el, n_ep)."""
        return _read_only(self._nodes)

    @property
    def gradients(self) -> np.ndarray:
        """Basis-function gradients dN/dX at the quadrature points (n_el, n_qp, 3, n_ep)."""
        return _read_only(self._grad)

    @property
    def weights(self) -> np.ndarray:
        """Quadrature weight times det J of every element's points (n_el, n_qp) [mm³]."""
        return _read_only(self._weight)

    @property
    def lame(self) -> float:
        """Lamé's first parameter λ [MPa] of the (isotropic) material."""
        return self._lame

    @property
    def shear(self) -> float:
        """The shear modulus μ [MPa] of the material."""
        return self._shear

    def scale_weights(self, factors: object) -> None:
        """Multiply each element's quadrature weights by its factor (n_el,) > 0: a stiffer or
        softer material region (Young's modulus times the factor, Poisson's ratio the same).

        Raises ``ValueError`` if ``factors`` is not one finite positive number per element.
        """
        f = np.asarray(factors, dtype=float)
        if f.shape != (self._weight.shape[0],) or not np.all(np.isfinite(f) & (f > 0)):
            raise ValueError(
                f"factors must be {self._weight.shape[0]} finite positive numbers (one per "
                f"element), got shape {f.shape}"
            )
        self._weight = self._weight * f[:, None]

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
        :meth:`pattern` (no index arrays built); raises as :meth:`matrix`."""
        elements = self._element_stack(u)
        data = np.bincount(self._scatter, weights=elements.ravel(), minlength=self.nnz + 1)
        return data[:-1]

    def upper_values(self, u: object) -> np.ndarray:
        """The upper triangle (column ≥ row) of :meth:`values`, in CSR order: row by row,
        columns increasing — the lower triangle of the symmetric matrix in column-major order,
        which is what :meth:`mechlib.fe.factor.PatternCholesky.factorise_upper` of
        :meth:`pattern` takes. Only the element-matrix entries that land there are summed; the
        same numbers, bit for bit, as ``values(u)`` at those positions. Raises as :meth:`matrix`.
        """
        elements = self._element_stack(u)
        if self._upper is None:
            rows = np.repeat(np.arange(self.n_dofs), np.diff(self._indptr))
            upper = np.append(self._indices >= rows, False)  # the clamped entries' bin: no
            rank = np.cumsum(upper) - 1
            select = np.flatnonzero(upper[self._scatter])
            gathered = np.empty(len(select))  # kept, like the element matrices
            self._upper = (select, rank[self._scatter[select]], int(upper.sum()), gathered)
        select, scatter, count, gathered = self._upper
        np.take(elements.ravel(), select, out=gathered)
        return np.bincount(scatter, weights=gathered, minlength=count)

    def _element_stack(self, u: object) -> np.ndarray:
        """The element tangents (n_el, 3 n_ep, 3 n_ep) at ``u``, in a buffer kept between
        calls (writing fresh pages costs ≈ 0.3 s a call)."""
        arr = self._check_state(u)
        nodal = np.vstack([arr.reshape(-1, 3), np.zeros((1, 3))])  # row −1: clamped nodes
        n_el, n_ep = self._nodes.shape
        if self._values is None:
            self._values = np.empty((n_el, 3 * n_ep, 3 * n_ep))
        with one_thread():
            for start in range(0, n_el, self.chunk):
                cells = slice(start, start + self.chunk)
                self.element_matrices(nodal[self._nodes[cells]], cells, self._values[cells])
        return self._values

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
        with one_thread():
            for start in range(0, n_el, self.chunk):
                cells = slice(start, start + self.chunk)
                out = self.element_forces(nodal[self._nodes[cells]], cells)
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

    def _deformation(self, disp: np.ndarray, cells: slice) -> np.ndarray | None:
        """Fᵀ of the elements ``cells`` at their quadrature points (m, n_qp, 3, 3), with
        ``ft[..., j, c] = ∂x_c/∂X_j``, or ``None`` if one inverts (det F ≤ 0)."""
        ft = self._grad[cells] @ disp[:, None] + np.eye(3)
        return None if np.any(_det3(ft) <= 0.0) else ft

    def _stress(self, ft: np.ndarray) -> np.ndarray:
        """Second Piola–Kirchhoff stress tensor (m, n_qp, 3, 3) from Fᵀ:
        ``S = λ tr(E) I + 2 μ E = μ C + (λ (tr C − 3) / 2 − μ) I`` with ``C = FᵀF``."""
        c = ft @ ft.swapaxes(-1, -2)  # right Cauchy–Green tensor FᵀF
        shift = 0.5 * self._lame * (np.trace(c, axis1=-2, axis2=-1) - 3.0) - self._shear
        c *= self._shear
        for i in range(3):
            c[..., i, i] += shift
        return c

    def element_forces(self, disp: np.ndarray, cells: slice) -> np.ndarray | None:
        """Internal forces (m, 3 n_ep), DOFs ordered (component, node), or ``None`` if an
        element inverts: ``Σ_q w_q P_q ∇N_q`` with the first Piola–Kirchhoff stress P = F S
        (the same as ``Σ_q w_q B_qᵀ S_q``, without forming B)."""
        ft = self._deformation(disp, cells)
        if ft is None:
            return None
        grad = self._grad[cells]
        m, n_qp, _, n_ep = grad.shape
        stress = self._stress(ft) * self._weight[cells][..., None, None]
        p = ft.swapaxes(-1, -2) @ stress  # w F S: p[q, c, j]
        # Σ over (q, j) as one product: (3, n_qp 3) @ (n_qp 3, n_ep) per element
        flat = p.transpose(0, 2, 1, 3).reshape(m, 3, 3 * n_qp)
        return (flat @ grad.reshape(m, 3 * n_qp, n_ep)).reshape(m, 3 * n_ep)

    def element_matrices(self, disp: np.ndarray, cells: slice, out: np.ndarray) -> None:
        """Write into ``out`` (m, 3 n_ep, 3 n_ep) the tangents, DOFs ordered (component, node),
        of the elements ``cells`` with nodal displacements ``disp`` (m, n_ep, 3).

        With ``h_a = F ∇N_a``, the left Cauchy–Green tensor ``b = F Fᵀ`` and isotropic ``D``,
        the block (c, d) of the tangent, over nodes (a, b), is

            Σ_q w [λ h_ac h_bd + μ h_ad h_bc + μ b_cd ∇N_a·∇N_b + δ_cd ∇N_aᵀ S ∇N_b],

        the material term ``Bᵀ D B`` written without B (half the multiplications).
        """
        ft = self._deformation(disp, cells)
        if ft is None:
            raise ValueError("u must not invert an element (det F <= 0 at a quadrature point)")
        grad, weight = self._grad[cells], self._weight[cells]
        m, n_qp, _, n_ep = grad.shape
        f = ft.swapaxes(-1, -2)  # F
        h = f @ grad  # (m, q, c, a): h_ac
        wh = h * weight[..., None, None]
        dofs = 3 * n_ep
        # x[(c, a), (d, b)] = Σ_q w h_ac h_bd
        x = np.matmul(h.reshape(m, n_qp, dofs).swapaxes(1, 2), wh.reshape(m, n_qp, dofs))
        xb = x.reshape(m, 3, n_ep, 3, n_ep)
        blocks = out.reshape(m, 3, n_ep, 3, n_ep)
        np.multiply(xb, self._lame, out=blocks)
        blocks += self._shear * xb.transpose(0, 3, 2, 1, 4)  # block (c, d) of x is (d, c)'s
        # Σ_q ∇Nᵀ A ∇N with A = w μ b_cd I (+ w S on the diagonal blocks)
        rows = grad.reshape(m, 3 * n_qp, n_ep).swapaxes(1, 2)  # (m, a, (q, i))
        geometric = rows @ (self._stress(ft) * weight[..., None, None] @ grad).reshape(
            m, 3 * n_qp, n_ep
        )
        left = f @ ft  # b = F Fᵀ
        for c in range(3):
            for d in range(c, 3):
                coef = (self._shear * weight) * left[..., c, d]  # (m, q)
                block = rows @ (grad * coef[..., None, None]).reshape(m, 3 * n_qp, n_ep)
                if c == d:
                    blocks[:, c, :, c, :] += block + geometric
                else:
                    blocks[:, c, :, d, :] += block
                    blocks[:, d, :, c, :] += block


def _read_only(a: np.ndarray) -> np.ndarray:
    view = a.view()
    view.flags.writeable = False
    return view


def _det3(a: np.ndarray) -> np.ndarray:
    """Determinants of a stack of 3 × 3 matrices (..., 3, 3), by cofactors (faster than LAPACK
    on many small matrices)."""
    return (
        a[..., 0, 0] * (a[..., 1, 1] * a[..., 2, 2] - a[..., 1, 2] * a[..., 2, 1])
        - a[..., 0, 1] * (a[..., 1, 0] * a[..., 2, 2] - a[..., 1, 2] * a[..., 2, 0])
        + a[..., 0, 2] * (a[..., 1, 0] * a[..., 2, 1] - a[..., 1, 1] * a[..., 2, 0])
    )


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
