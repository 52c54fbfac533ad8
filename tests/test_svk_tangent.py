"""The batched TL Saint Venant–Kirchhoff tangent against SfePy's consistent term."""

import hashlib
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from test_hexflex import SMALL  # tests/ is on sys.path (pytest prepend import mode)

from mechlib.fe import sfepy_tl
from mechlib.fe.factor import PatternCholesky
from mechlib.fe.svk_tangent import SVKTangent
from mechlib.hexflex.fe.model import HexFlexModel

#: Largest relative difference (max |ΔK| / max |K|) taken for "the same matrix": round-off.
SAME = 1e-12
#: The deformed state of the tests: a tilt of the stage (as in tests/test_hexflex.py).
TILT = np.array([[0.0, 0.0, 0.0, 3.0, -2.0, 0.0]])


@pytest.fixture(scope="module")
def model() -> HexFlexModel:
    return HexFlexModel(SMALL, element="q2", mesh_size=1.0)


@pytest.fixture(scope="module")
def tangent(model: HexFlexModel) -> SVKTangent:
    return SVKTangent(model)


@pytest.fixture(scope="module")
def deformed(model: HexFlexModel) -> np.ndarray:
    return model.solve_reduced(TILT)[:, 0]


def _relative_difference(a, b) -> float:
    """max |a − b| / max |b| of two sparse matrices."""
    return float(abs(a - b).max() / abs(b).max())


def _sfepy_tangent(model: HexFlexModel, term: str, u: np.ndarray):
    """SfePy's tangent at ``u``; the residual first, since SfePy's tangent reuses the stress of
    the last residual evaluation (HyperElasticBase.stress_cache)."""
    ev = sfepy_tl.tl_evaluator(model, term)
    ev.eval_residual(u)
    return ev.eval_tangent_matrix(u).copy()


def _turned_inside_out(model: HexFlexModel) -> np.ndarray:
    """Reduced displacements u = −2 X (F = −I away from the clamp)."""
    coors = np.asarray(model.fe.field.get_coor(), dtype=float)
    free = model.fe.eq.reshape(-1, 3)[:, 0] >= 0
    return -2.0 * coors[free].ravel()


def test_tangent_equals_sfepys_consistent_tangent(
    model: HexFlexModel, tangent: SVKTangent, deformed: np.ndarray
) -> None:
    term = sfepy_tl.register_svk_term()
    for u in (np.zeros(model.n_dofs), deformed):
        ours, ref = tangent.matrix(u), _sfepy_tangent(model, term, u)
        assert ours.shape == ref.shape == (model.n_dofs, model.n_dofs)
        assert np.array_equal(ours.indptr, ref.indptr) and np.array_equal(ours.indices, ref.indices)
        assert _relative_difference(ours, ref) < SAME
    # the small-strain limit is the linear stiffness (body_factor 1: one material)
    k0 = model.assembled_stiffness()
    assert _relative_difference(tangent.matrix(np.zeros(model.n_dofs)), k0) < SAME
    # the deformed state is far enough from u = 0 for the stress terms to matter
    assert _relative_difference(tangent.matrix(deformed), k0) > 1e-4


def test_tangent_is_the_derivative_of_sfepys_residual(
    model: HexFlexModel, tangent: SVKTangent, deformed: np.ndarray
) -> None:
    ev = sfepy_tl.tl_evaluator(model, sfepy_tl.register_svk_term())
    w = deformed * np.random.default_rng(0).standard_normal(deformed.size)
    kw = tangent.matrix(deformed) @ w
    errors = []
    for h in (1e-3, 1e-4):
        fd = (ev.eval_residual(deformed + h * w) - ev.eval_residual(deformed - h * w)) / (2 * h)
        errors.append(np.linalg.norm(fd - kw) / np.linalg.norm(kw))
    # central differences: the error falls like h² (to ≈ 1e-8 here, round-off of the residual)
    assert errors[1] < 1e-6 and errors[1] < 0.02 * errors[0]


def test_the_comparison_catches_a_wrong_tangent(
    model: HexFlexModel, tangent: SVKTangent, deformed: np.ndarray
) -> None:
    ours = tangent.matrix(deformed)
    ref = _sfepy_tangent(model, sfepy_tl.register_svk_term(), deformed)
    wrong = ours.copy()
    wrong.data[wrong.nnz // 2] += 1e-10 * abs(wrong.data).max()  # one entry, by 1e-10
    assert _relative_difference(wrong, ref) > 10 * SAME
    # SfePy's stock term (shear rows of its tangent modulus doubled) is another matrix
    stock = _sfepy_tangent(model, "dw_tl_he_svk", deformed)
    assert _relative_difference(ours, stock) > 1e-2
    # ... and so is the tangent at another state
    assert _relative_difference(tangent.matrix(1.01 * deformed), ref) > 1e-6
    # ... and so is SfePy's stock tangent taking the stress of its last residual (at u = 0)
    ev = sfepy_tl.tl_evaluator(model, "dw_tl_he_svk")
    ev.eval_residual(np.zeros(model.n_dofs))
    assert _relative_difference(stock, ev.eval_tangent_matrix(deformed)) > 1e-5


def test_internal_force_equals_sfepys_residual(
    model: HexFlexModel, tangent: SVKTangent, deformed: np.ndarray
) -> None:
    ev = sfepy_tl.tl_evaluator(model, sfepy_tl.register_svk_term())
    for u in (deformed, 5.0 * deformed):
        ref = ev.eval_residual(u).copy()
        ours = tangent.internal_force(u)
        assert np.abs(ours - ref).max() <= SAME * np.abs(ref).max()
    # the comparison can fail: a residual of another state is far off
    assert np.abs(tangent.internal_force(0.5 * deformed) - ref).max() > 1e-3 * np.abs(ref).max()
    assert not tangent.internal_force(np.zeros(model.n_dofs)).any()
    assert tangent.internal_force(_turned_inside_out(model)) is None  # SfePy refuses it too
    with pytest.raises(ValueError, match="u must have shape"):
        tangent.internal_force(np.zeros(5))


def test_upper_values_are_the_half_a_cholesky_reads(
    model: HexFlexModel, tangent: SVKTangent, deformed: np.ndarray
) -> None:
    full = tangent.matrix(deformed)
    upper = tangent.upper_values(deformed)
    rows = np.repeat(np.arange(model.n_dofs), np.diff(full.indptr))
    half = full.indices >= rows  # column ≥ row, in CSR order
    assert upper.shape == (int(half.sum()),)
    np.testing.assert_array_equal(upper, full.data[half])  # the same sums, bit for bit
    # the factoriser of the pattern takes them as the matrix: the same solution
    chol = PatternCholesky(tangent.pattern())
    b = np.linspace(-1.0, 1.0, model.n_dofs)
    x = chol.factorise_upper(upper)(b)
    x_full = chol.factorise(full)(b)
    np.testing.assert_array_equal(x, x_full)  # factorise reads that half too
    assert np.linalg.norm(full @ x - b) < 1e-7 * np.linalg.norm(b)
    assert chol.fallbacks == 0  # CHOLMOD's Cholesky, not the LU fallback
    # the comparison can fail: the lower triangle in CSR order (the same numbers, in another
    # order) is not it
    lower = full.data[full.indices <= rows]
    assert lower.shape == upper.shape and np.abs(lower - upper).max() > 1e-3 * abs(upper).max()
    # ... and the comparison can fail: the other state's half differs
    assert np.abs(tangent.upper_values(0.5 * deformed) - upper).max() > 1e-4 * abs(upper).max()


def test_tangent_is_bit_identical_between_calls_and_processes(
    model: HexFlexModel, tangent: SVKTangent, deformed: np.ndarray
) -> None:
    first = tangent.matrix(deformed)
    kept = first.data.copy()
    tangent.matrix(np.zeros(model.n_dofs))  # the element-matrix buffer is reused ...
    assert np.array_equal(first.data, kept)  # ... but not shared with a returned matrix
    assert np.array_equal(tangent.matrix(deformed).data, kept)
    code = (
        "import sys, hashlib; sys.path.insert(0, 'tests'); import numpy as np; "
        "from test_hexflex import SMALL; from test_svk_tangent import TILT; "
        "from mechlib.hexflex.fe.model import HexFlexModel; "
        "from mechlib.fe.svk_tangent import SVKTangent; "
        "m = HexFlexModel(SMALL, element='q2', mesh_size=1.0); "
        "k = SVKTangent(m).matrix(m.solve_reduced(TILT)[:, 0]); "
        "print(hashlib.sha256(k.data.tobytes()).hexdigest())"
    )
    root = Path(__file__).resolve().parents[1]
    out = subprocess.run(
        [sys.executable, "-c", code], cwd=root, capture_output=True, text=True, check=True
    )
    assert out.stdout.split()[-1] == hashlib.sha256(first.data.tobytes()).hexdigest()


def test_bad_input_gets_clear_errors(model: HexFlexModel, tangent: SVKTangent) -> None:
    n = model.n_dofs
    with pytest.raises(ValueError, match=rf"u must have shape \({n},\) \(n_dofs\), got \(5,\)"):
        tangent.matrix(np.zeros(5))
    with pytest.raises(ValueError, match=rf"u must have shape \({n},\) \(n_dofs\), got \(1, {n}\)"):
        tangent.matrix(np.zeros((1, n)))
    for bad in (np.nan, np.inf):
        u = np.zeros(n)
        u[7] = bad
        with pytest.raises(ValueError, match="u must hold only finite numbers"):
            tangent.matrix(u)
    with pytest.raises(ValueError, match=r"u must not invert an element \(det F <= 0"):
        tangent.matrix(_turned_inside_out(model))
    with pytest.raises(ValueError, match="chunk must be"):
        SVKTangent(model, chunk=0)
    shell = HexFlexModel(SMALL, element="shell", mesh_size=1.0)
    with pytest.raises(ValueError, match=r"element must be 'q2' .*SVKTangent.*got 'shell'"):
        SVKTangent(shell)


def test_the_stiffness_converges_with_the_quadrature_order(
    model: HexFlexModel, tangent: SVKTangent
) -> None:
    # 3 × 3 × 3 Gauss points (order 4, the model's) do not integrate these mapped Q2 elements
    # exactly: 4 × 4 × 4 (order 6) changes the largest entries by a fraction of a percent,
    # 5 × 5 × 5 (order 8) far less again
    zero = np.zeros(model.n_dofs)
    k4, k6, k8 = (SVKTangent(model, order=o).matrix(zero) for o in (4, 6, 8))
    assert SVKTangent(model, order=6)._weight.shape[1] == 64
    step_46, step_68 = _relative_difference(k6, k4), _relative_difference(k8, k6)
    assert step_46 < 1e-2
    assert step_68 < 0.1 * step_46
    assert _relative_difference(tangent.matrix(zero), k4) == 0.0
    with pytest.raises(ValueError, match="order"):
        SVKTangent(model, order=11)
