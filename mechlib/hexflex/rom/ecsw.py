"""Energy-conserving sampling and weighting (ECSW) of the HexFlex's Q2 elements for a reduced basis.

Hyper-reduction of the Galerkin-projected internal force ``Vᵀ f(V q)`` (Farhat, Avery, Chapman &
Cortial 2014; Farhat, Chapman & Avery 2015): the sum over all elements of their projected forces
``V_eᵀ f_e(V_e q)`` is replaced by a weighted sum over a few elements, ``Σ_e w_e V_eᵀ f_e(V_e q)``
with ``w_e ≥ 0``, the weights fitted on training states ``q_s`` by a greedy non-negative least
squares that stops at a relative tolerance. Non-negative weights keep the reduced model the
gradient of a (positive) weighted strain energy, hence symmetric and stable.

Only the *non-linear* part of the element forces, ``f_e(x) − K_e x``, is fitted here: the reduced
model keeps the exact reduced linear stiffness ``Vᵀ K₀ V`` (:mod:`mechlib.hexflex.rom.model`), so
that it reproduces the linear model to round-off at small loads whatever the sampled elements.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from scipy.optimize import nnls

from mechlib.blas import one_thread
from mechlib.params import check_float, check_int

if TYPE_CHECKING:
    from mechlib.fe.svk_tangent import SVKTangent

#: Elements per batch when the element contributions are computed (temporaries ∝ CHUNK).
CHUNK = 64
#: Elements added per greedy step, as a fraction of those already selected (≥ 1 a step): the
#: NNLS solve of the active set dominates the fit, and one element a step needs one solve per
#: element.
GROWTH = 0.05


def element_basis(tangent: SVKTangent, basis: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """The basis restricted to the elements ``cells``: (m, 3 n_ep, n), element DOFs ordered
    (component, node) as the element forces of :class:`SVKTangent`, zero rows at clamped nodes.

    Parameters
    ----------
    tangent : SVKTangent
        The model's batched SVK kernels (connectivity ``_nodes``).
    basis : ndarray (n_dofs, n)
        Reduced basis, node-major reduced DOFs.
    cells : ndarray of int (m,)
        Element indices.
    """
    n = basis.shape[1]
    nodal = np.concatenate([basis.reshape(-1, 3, n), np.zeros((1, 3, n))])  # row −1: clamped
    ve = nodal[tangent.element_nodes[cells]]  # (m, n_ep, 3, n)
    return np.ascontiguousarray(ve.transpose(0, 2, 1, 3)).reshape(len(cells), -1, n)


def nonlinear_contributions(
    tangent: SVKTangent, basis: np.ndarray, states: np.ndarray, chunk: int = CHUNK
) -> np.ndarray:
    """Projected non-linear element forces ``V_eᵀ (f_e(V_e q_s) − K_e V_e q_s)`` [N].

    Parameters
    ----------
    tangent : SVKTangent
    basis : ndarray (n_dofs, n)
    states : ndarray (n_s, n)
        Reduced coordinates of the training states [mm].
    chunk : int
        Elements per batch, in [1, 5000].

    Returns
    -------
    ndarray (n_s, 2, n, n_el)
        Column ``e`` holds element ``e``'s contribution at every state, split by degree: its
        quadratic part ``(f_e(x) + f_e(−x)) / 2`` and its cubic part ``(f_e(x) − f_e(−x)) / 2 −
        K_e x`` (the SVK force is an exact cubic), so that a fit matches both, whatever the
        states' amplitudes. The sum over the columns is the projected non-linear internal force
        of the whole model.

    Raises
    ------
    ValueError
        If a state inverts an element (det F ≤ 0).
    """
    chunk = check_int("chunk", chunk, low=1, high=5000)
    n_el, n_ep = tangent.element_nodes.shape
    n_s, n = states.shape
    out = np.empty((n_s, 2, n, n_el))
    disp = basis @ states.T  # (n_dofs, n_s)
    nodal = np.concatenate([disp.reshape(-1, 3, n_s), np.zeros((1, 3, n_s))])
    with one_thread():
        for start in range(0, n_el, chunk):
            stop = min(start + chunk, n_el)
            cells = np.arange(start, stop)
            ve = element_basis(tangent, basis, cells)
            k0 = np.empty((len(cells), 3 * n_ep, 3 * n_ep))
            tangent.element_matrices(np.zeros((len(cells), n_ep, 3)), cells, k0)
            local = nodal[tangent.element_nodes[cells]]  # (m, n_ep, 3, n_s)
            for s in range(n_s):
                x = local[..., s]
                plus = tangent.element_forces(x, cells)
                minus = tangent.element_forces(-x, cells)
                if plus is None or minus is None:
                    raise ValueError(f"training state {s} inverts an element (det F <= 0)")
                flat = x.transpose(0, 2, 1).reshape(len(cells), -1)  # (component, node)
                quadratic = 0.5 * (plus + minus)
                cubic = 0.5 * (plus - minus) - np.einsum("eij,ej->ei", k0, flat)
                out[s, 0, :, start:stop] = np.einsum("ein,ei->ne", ve, quadratic)
                out[s, 1, :, start:stop] = np.einsum("ein,ei->ne", ve, cubic)
    return out


def greedy_nnls(
    matrix: np.ndarray, target: np.ndarray, tol: float, max_elements: int
) -> tuple[np.ndarray, np.ndarray]:
    """Sparse non-negative weights ``w`` with ``‖matrix w − target‖ ≤ tol ‖target‖``.

    Farhat et al.'s greedy variant of Lawson–Hanson: the column most correlated with the
    residual joins the active set (here the ``GROWTH`` fraction of the active set's size most
    correlated, at least one: fewer NNLS solves), the weights of the active set are the
    non-negative least squares solution, until the tolerance is met.

    Parameters
    ----------
    matrix : ndarray (m, n_el)
        Element contributions (one column per element).
    target : ndarray (m,)
        What their weighted sum must reproduce.
    tol : float
        Relative residual, in (0, 1).
    max_elements : int
        Largest number of elements selected, in [1, n_el].

    Returns
    -------
    cells : ndarray of int
        Selected elements, sorted.
    weights : ndarray
        Their weights (> 0).

    Raises
    ------
    ValueError
        If the tolerance is not met with ``max_elements`` elements (names both).
    """
    tol = check_float("ecsw_tol", tol, low=0.0, high=1.0, low_open=True)
    max_elements = check_int("max_elements", max_elements, low=1, high=matrix.shape[1])
    scale = float(np.linalg.norm(target))
    active: list[int] = []
    weights = np.zeros(0)
    residual = target.copy()
    with one_thread():
        while np.linalg.norm(residual) > tol * scale:
            if len(active) >= max_elements:
                raise ValueError(
                    f"ECSW: relative residual {np.linalg.norm(residual) / scale:.2e} > ecsw_tol "
                    f"= {tol:g} with max_elements = {max_elements} elements; raise max_elements "
                    f"or ecsw_tol"
                )
            score = matrix.T @ residual
            score[active] = -np.inf
            grow = min(max(1, int(GROWTH * len(active))), max_elements - len(active))
            best = np.argsort(-score, kind="stable")[:grow]
            best = best[score[best] > 0.0]
            if len(best) == 0:
                raise ValueError(
                    f"ECSW: no element reduces the residual {np.linalg.norm(residual) / scale:.2e}"
                    f" further (ecsw_tol = {tol:g}); raise ecsw_tol"
                )
            active.extend(int(e) for e in best)
            weights, _ = nnls(matrix[:, active], target, maxiter=50 * len(active))
            residual = target - matrix[:, active] @ weights
    keep = weights > 0.0
    cells = np.asarray(active, dtype=np.int64)[keep]
    order = np.argsort(cells)
    return cells[order], weights[keep][order]


def fit_weights(
    contributions: np.ndarray, tol: float, max_elements: int
) -> tuple[np.ndarray, np.ndarray, float]:
    """ECSW weights from :func:`nonlinear_contributions` (n_s, 2, n, n_el): the rows of every
    state and degree are scaled by their own target's norm (each counts alike, whatever the
    load).

    Returns
    -------
    cells, weights : ndarray
        As :func:`greedy_nnls`.
    error : float
        The largest relative error ``‖Σ w_e c_e − Σ_e c_e‖ / ‖Σ_e c_e‖`` over the states and
        degrees.
    """
    n_el = contributions.shape[-1]
    contributions = contributions.reshape(-1, contributions.shape[-2], n_el)
    target = contributions.sum(axis=2)  # (n_s · 2, n)
    norms = np.linalg.norm(target, axis=1)
    if np.any(norms == 0.0):
        raise ValueError("ECSW: a training state has no non-linear force (zero state?)")
    scaled = contributions / norms[:, None, None]
    cells, weights = greedy_nnls(
        scaled.reshape(-1, n_el), (target / norms[:, None]).ravel(), tol, max_elements
    )
    fitted = contributions[:, :, cells] @ weights
    error = float((np.linalg.norm(fitted - target, axis=1) / norms).max())
    return cells, weights, error
