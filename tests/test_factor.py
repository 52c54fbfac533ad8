"""Repeated Cholesky factorisations of one pattern, and the non-linear solve that uses them."""

import numpy as np
import pytest
import scipy.sparse as sp
from test_hexflex import SMALL  # tests/ is on sys.path (pytest prepend import mode)

from mechlib.fe import nonlinear
from mechlib.fe.factor import PatternCholesky
from mechlib.hexflex.fe.model import HexFlexModel


def _spd(n: int = 300, seed: int = 0, shift: float = 1.0) -> sp.csr_array:
    """A sparse symmetric matrix: a random pattern (symmetrised) with a dominant diagonal
    (positive definite for shift > 0)."""
    rng = np.random.default_rng(seed)
    a = sp.random_array((n, n), density=0.02, rng=rng, format="csr")
    a = a + a.T
    d = np.asarray(abs(a).sum(axis=1)).ravel()
    m = sp.csr_array(a + sp.diags_array(d + shift))
    m.sort_indices()
    return m


def test_solves_and_refactorises_with_the_pattern_kept() -> None:
    m = _spd()
    b = np.arange(m.shape[0], dtype=float)
    chol = PatternCholesky(m)
    x = chol.factorise(m)(b)
    np.testing.assert_allclose(m @ x, b, rtol=1e-12, atol=1e-12 * np.abs(b).max())
    # same pattern, new numbers: the analysis is reused and the answer follows the numbers
    m2 = m.copy()
    m2.data = m2.data * np.linspace(1.0, 2.0, m2.nnz)
    m2 = (m2 + m2.T) / 2
    m2.sort_indices()
    solve2 = chol.factorise(m2)
    np.testing.assert_allclose(m2 @ solve2(b), b, rtol=1e-12, atol=1e-12 * np.abs(b).max())
    assert chol.fallbacks == 0
    # the values alone, in the pattern's order, give the same factorisation
    x2 = solve2(b)
    np.testing.assert_array_equal(chol.factorise_values(m2.data)(b), x2)
    # ... and so does its upper triangle (column ≥ row) alone, in CSR order, after another
    # matrix was factorised (its numbers must not linger in the buffer)
    chol.factorise(m)
    rows = np.repeat(np.arange(m2.shape[0]), np.diff(m2.indptr))
    upper = m2.data[m2.indices >= rows]
    np.testing.assert_array_equal(chol.factorise_upper(upper)(b), x2)
    # the upper triangle is what is read: twice the numbers, half the solution
    np.testing.assert_allclose(chol.factorise_upper(2.0 * upper)(b), x2 / 2, rtol=1e-12)
    assert chol.fallbacks == 0


def test_an_overwritten_factor_refuses_to_solve() -> None:
    m = _spd()
    chol = PatternCholesky(m)
    first = chol.factorise(m)
    chol.factorise(2.0 * m)
    with pytest.raises(RuntimeError, match="overwritten"):
        first(np.ones(m.shape[0]))


def test_an_indefinite_matrix_falls_back_to_lu() -> None:
    m = _spd()
    indefinite = sp.csr_array(m - sp.diags_array(np.full(m.shape[0], 0.5 * m.diagonal().max())))
    indefinite.sort_indices()
    chol = PatternCholesky(m)
    b = np.ones(m.shape[0])
    lu_solve = chol.factorise(indefinite)
    x = lu_solve(b)
    assert chol.fallbacks == 1
    np.testing.assert_allclose(indefinite @ x, b, rtol=1e-9, atol=1e-9)
    # a Cholesky after the failure is sound, and the LU solve is not touched by it
    y = chol.factorise(m)(b)
    np.testing.assert_allclose(m @ y, b, rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(lu_solve(b), x)
    # the fallback rebuilds the whole matrix from the upper triangle it was given
    rows = np.repeat(np.arange(m.shape[0]), np.diff(indefinite.indptr))
    upper = indefinite.data[indefinite.indices >= rows]
    np.testing.assert_allclose(chol.factorise_upper(upper)(b), x, rtol=1e-12, atol=1e-12)
    assert chol.fallbacks == 2


def test_bad_input_gets_clear_errors() -> None:
    m = _spd()
    chol = PatternCholesky(m)
    with pytest.raises(ValueError, match="sparsity pattern"):
        chol.factorise(_spd(seed=1))
    with pytest.raises(ValueError, match="data must have shape"):
        chol.factorise_values(m.data[:-1])
    with pytest.raises(ValueError, match="upper must have shape"):
        chol.factorise_upper(m.data)
    with pytest.raises(ValueError, match="rhs must have shape"):
        chol.factorise(m)(np.ones(3))
    dup = sp.csr_array((np.ones(2), np.array([0, 0]), np.array([0, 2, 2])), shape=(2, 2))
    with pytest.raises(ValueError, match="no duplicates"):
        PatternCholesky(dup)
    with pytest.raises(ValueError, match="square"):
        PatternCholesky(sp.csr_array(np.ones((2, 3))))


def test_cholmod_and_superlu_reach_the_same_equilibrium() -> None:
    model = HexFlexModel(SMALL, element="q2", mesh_size=1.0)
    f = 3.0 * np.array([0.3, -0.5, 0.2, 1.0, -0.7, 0.1])
    u_lu, _ = nonlinear.NonlinearSolver(model, factorisation="superlu").solve(f)
    solver = nonlinear.NonlinearSolver(model)  # cholmod
    u_ch, stats = solver.solve(f)
    # the Cholesky path ran (not a silent LU), with no fallback
    assert solver.cholesky is not None and solver.cholesky.factorisations >= 1
    assert solver.cholesky.fallbacks == 0
    assert solver.residual(np.full(model.n_dofs, np.nan), np.zeros(model.n_dofs)) is None
    assert stats.residual <= nonlinear.NEWTON_TOL
    np.testing.assert_allclose(model.pose_of(u_ch), model.pose_of(u_lu), rtol=1e-8)
    with pytest.raises(ValueError, match="factorisation must be one of"):
        nonlinear.NonlinearSolver(model, factorisation="pardiso")
