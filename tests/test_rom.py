"""The hyper-reduced ROM of the non-linear HexFlex (mechlib.hexflex.rom.model), on a small Q2
model."""

import numpy as np
import pytest
from test_hexflex import SMALL  # tests/ is on sys.path (pytest prepend import mode)

from mechlib.fe.nonlinear import NonlinearSolver
from mechlib.hexflex.fe.model import HexFlexModel
from mechlib.hexflex.rom import basis as rb
from mechlib.hexflex.rom import ecsw, indicators
from mechlib.hexflex.rom import model as rm

#: The ROMs' force range [N]: the small model departs from linear by ≈ 7 % of a pose
#: component's range at 10 N (≈ 0.1 % at 1 N), so 10 N exercises the non-linearity.
RANGE = 10.0
#: A looser ECSW tolerance than the default keeps the test fast (≈ 90 of 480 elements).
TEST_ECSW_TOL = 1e-4
#: Round-off of the TL residual relative to its size (nonlinear.py: floor ≈ 3e-9).
ROUND_OFF = 1e-8


@pytest.fixture(scope="module")
def solver() -> NonlinearSolver:
    return NonlinearSolver(HexFlexModel(SMALL, element="q2", mesh_size=1.0))


@pytest.fixture(scope="module")
def galerkin(solver: NonlinearSolver) -> rm.ReducedOrderModel:
    """Modes and derivatives, every element: the plain Galerkin ROM."""
    return rm.ReducedOrderModel.build(solver, hyper_reduction=False, force_range=RANGE)


@pytest.fixture(scope="module")
def hyper(solver: NonlinearSolver) -> rm.ReducedOrderModel:
    return rm.ReducedOrderModel.build(
        solver, force_range=RANGE, ecsw_tol=TEST_ECSW_TOL, n_training=12
    )


def _forces(n: int, amplitude: float, seed: int = 7) -> np.ndarray:
    return amplitude * np.random.default_rng(seed).uniform(-1.0, 1.0, (n, 6))


def test_basis_is_orthonormal_and_holds_the_static_modes(
    solver: NonlinearSolver, galerkin: rm.ReducedOrderModel
) -> None:
    v = galerkin.basis
    assert galerkin.n_basis == 27  # 6 modes + 21 derivatives, independent on this model
    assert np.abs(v.T @ v - np.eye(galerkin.n_basis)).max() < 1e-13
    modes, derivatives = rb.static_basis(solver)
    for vectors in (modes, derivatives):
        outside = vectors - v @ (v.T @ vectors)
        assert (np.linalg.norm(outside, axis=0) / np.linalg.norm(vectors, axis=0)).max() < 1e-10


def test_polynomial_force_is_the_galerkin_force(
    solver: NonlinearSolver, galerkin: rm.ReducedOrderModel
) -> None:
    v = galerkin.basis
    q = galerkin.coordinates(_forces(3, RANGE))
    exact = np.stack([v.T @ solver.batched.internal_force(v @ x) for x in q])
    ours = galerkin.force.force(q)
    assert np.abs(ours - exact).max() < ROUND_OFF * np.abs(exact).max()
    # the polynomial is the gradient of the energy: a central difference along a direction
    d, h = np.random.default_rng(3).standard_normal(galerkin.n_basis), 1e-4
    diff = (galerkin.force.energy(q[:1] + h * d) - galerkin.force.energy(q[:1] - h * d)) / (2 * h)
    assert abs(diff[0] - ours[0] @ d) < 1e-6 * np.abs(ours[0]).sum() * np.abs(d).max()


def test_small_loads_give_the_linear_model(
    solver: NonlinearSolver, galerkin: rm.ReducedOrderModel
) -> None:
    f = _forces(4, 1e-6)
    linear = solver.model.poses(f)
    # the non-linearity at 1e-6 N is ≈ 1e-9 of the pose (≈ 1e-3 at 1 N), round-off ≈ 1e-12
    assert np.abs(galerkin.poses(f) - linear).max() < 1e-8 * np.abs(linear).max()
    # ... and depart from it quadratically: the relative difference grows ∝ amplitude
    gaps = []
    for a in (1e-2, 2e-2):
        lin = solver.model.poses(f * a / 1e-6)
        gaps.append(np.abs(galerkin.poses(f * a / 1e-6) - lin).max() / np.abs(lin).max())
    assert 1.9 < gaps[1] / gaps[0] < 2.1


def test_rom_matches_the_full_nonlinear_solve_at_large_loads(
    solver: NonlinearSolver, galerkin: rm.ReducedOrderModel, hyper: rm.ReducedOrderModel
) -> None:
    f = _forces(3, RANGE)
    full = np.array([solver.model.pose_of(solver.solve(x)[0]) for x in f])
    span = np.abs(full).max(axis=0)
    linear_error = (np.abs(solver.model.poses(f) - full).max(axis=0) / span).max()
    galerkin_error = (np.abs(galerkin.poses(f) - full).max(axis=0) / span).max()
    hyper_error = (np.abs(hyper.poses(f) - full).max(axis=0) / span).max()
    assert linear_error > 0.03  # the loads are non-linear enough to matter
    assert galerkin_error < 0.01 and galerkin_error < 0.2 * linear_error
    assert hyper_error < 0.02 and hyper.n_elements < 0.5 * len(solver.batched._nodes)


def _parts(force, q: np.ndarray, stiffness: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Quadratic and cubic parts of a reduced force function at states ``q``."""
    plus, minus = force(q), force(-q)
    return 0.5 * (plus + minus), 0.5 * (plus - minus) - q @ stiffness


def test_ecsw_weights_reproduce_the_reduced_force_on_training_states(
    solver: NonlinearSolver, galerkin: rm.ReducedOrderModel, hyper: rm.ReducedOrderModel
) -> None:
    modes, derivatives = rb.static_basis(solver)
    forces = rb.training_forces(RANGE, 12)
    states = rb.training_states(hyper.basis, modes, derivatives, None, forces)
    v = hyper.basis

    def exact(q: np.ndarray) -> np.ndarray:
        return np.stack([v.T @ solver.batched.internal_force(v @ x) for x in q])

    for ours, ref in zip(
        _parts(hyper.force.force, states, hyper.force.stiffness),
        _parts(exact, states, hyper.force.stiffness),
        strict=True,
    ):
        errors = np.linalg.norm(ours - ref, axis=1) / np.linalg.norm(ref, axis=1)
        # the greedy fit bounds the stacked residual of 2 × 12 unit blocks by tol · √24
        assert errors.max() < TEST_ECSW_TOL * np.sqrt(24)
        assert errors.max() > 0  # a sample, not every element
    assert np.all(hyper.weights > 0) and np.all(np.diff(hyper.cells) > 0)


def test_greedy_nnls_finds_a_sparse_exact_combination() -> None:
    rng = np.random.default_rng(0)
    matrix = np.abs(rng.standard_normal((40, 30)))
    target = matrix[:, [3, 11, 17]] @ np.array([0.5, 2.0, 1.0])
    cells, weights = ecsw.greedy_nnls(matrix, target, 1e-10, 30)
    assert np.linalg.norm(matrix[:, cells] @ weights - target) <= 1e-10 * np.linalg.norm(target)
    assert np.all(weights > 0) and len(cells) <= 30
    with pytest.raises(ValueError, match="max_elements = 1"):
        ecsw.greedy_nnls(matrix, target, 1e-10, 1)


def test_two_builds_are_bit_identical(solver: NonlinearSolver, hyper: rm.ReducedOrderModel) -> None:
    again = rm.ReducedOrderModel.build(
        solver, force_range=RANGE, ecsw_tol=TEST_ECSW_TOL, n_training=12
    )
    f = _forces(5, RANGE, seed=11)
    np.testing.assert_array_equal(again.basis, hyper.basis)
    np.testing.assert_array_equal(again.cells, hyper.cells)
    np.testing.assert_array_equal(again.weights, hyper.weights)
    np.testing.assert_array_equal(again.poses(f), hyper.poses(f))
    np.testing.assert_array_equal(again.displacement(f[0]), hyper.displacement(f[0]))


def test_equilibrium_solves_the_reduced_equations(hyper: rm.ReducedOrderModel) -> None:
    f = _forces(5, RANGE, seed=17)
    q = hyper.coordinates(f)
    load = f @ hyper.loads.T
    residual = hyper.force.force(q) - load
    assert (np.linalg.norm(residual, axis=1) / np.linalg.norm(load, axis=1)).max() < 1e-9


def test_one_pose_at_a_time_equals_the_batch(hyper: rm.ReducedOrderModel) -> None:
    f = _forces(4, RANGE, seed=13)
    batch = hyper.poses(f)
    single = np.vstack([hyper.poses(x) for x in f])
    assert np.abs(single - batch).max() < 1e-10 * np.abs(batch).max()


def test_snapshots_add_pod_vectors(solver: NonlinearSolver) -> None:
    f = _forces(2, RANGE, seed=5)
    snaps = np.array([solver.solve(x)[0] for x in f])
    rom = rm.ReducedOrderModel.build(
        solver, snaps, hyper_reduction=False, force_range=RANGE, n_pod=2
    )
    assert rom.n_basis == 29
    # a snapshot lies in the basis, so the ROM reproduces that full solution
    full = solver.model.pose_of(snaps[0])
    assert np.abs(rom.poses(f[0])[0] - full).max() < 1e-6 * np.abs(full).max()


def test_bad_input_is_refused(
    solver: NonlinearSolver, hyper: rm.ReducedOrderModel, monkeypatch: pytest.MonkeyPatch
) -> None:
    with pytest.raises(ValueError, match=r"force_range\), got \|force\| = 12"):
        hyper.poses([12.0, 0, 0, 0, 0, 0])
    with pytest.raises(ValueError, match="shape"):
        hyper.poses(np.zeros((2, 5)))
    with pytest.raises(ValueError, match="shape"):
        hyper.displacement(np.zeros(7))
    with pytest.raises(ValueError):
        hyper.poses([np.nan, 0, 0, 0, 0, 0])
    with pytest.raises(ValueError, match="force_range"):
        rm.ReducedOrderModel.build(solver, force_range=60.0)
    with pytest.raises(ValueError, match="ecsw_tol"):
        rm.ReducedOrderModel.build(solver, ecsw_tol=0.0)
    with pytest.raises(ValueError, match="n_pod"):
        rm.ReducedOrderModel.build(solver, n_pod=3)
    with pytest.raises(ValueError, match="snapshots"):
        rm.ReducedOrderModel.build(solver, np.zeros((2, 10)))
    with pytest.raises(TypeError):
        rm.ReducedOrderModel.build(solver, method="deim")  # unknown option
    with pytest.raises(TypeError, match="modal_derivatives"):
        rm.ReducedOrderModel.build(solver, modal_derivatives="yes")
    with pytest.raises(ValueError, match="n_third"):
        rm.ReducedOrderModel.build(solver, n_third=30, n_training=12)
    monkeypatch.setattr(rm, "MAX_ITERATIONS", 1)
    with pytest.raises(ValueError, match="did not converge in 1 iterations"):
        hyper.poses(_forces(1, RANGE))
    assert np.array_equal(hyper.poses(np.zeros(6)), np.zeros((1, 6)))  # no iteration needed


def test_one_exact_newton_correction_from_the_rom_state_nearly_reaches_the_full_solve(
    solver: NonlinearSolver, hyper: rm.ReducedOrderModel
) -> None:
    f = _forces(3, RANGE, seed=11)
    full = np.array([solver.model.pose_of(solver.solve(x)[0]) for x in f])
    span = np.abs(full).max(axis=0)
    rom = hyper.poses(f)
    exact = indicators.dual_weighted_residuals(hyper, solver, f, tangent="exact")
    linear = indicators.dual_weighted_residuals(hyper, solver, f)
    before = (np.abs(rom - full).max(axis=0) / span).max()
    # a Newton step from the ROM's state: the error squared (quadratic convergence), measured
    # 7e-3 of the ROM's here; its sign flipped it would double the error
    assert (np.abs(rom + exact - full).max(axis=0) / span).max() < 0.02 * before
    # through K₀ the same residual gives a rougher estimate (measured 0.64 of the ROM's error)
    assert (np.abs(rom + linear - full).max(axis=0) / span).max() < 0.8 * before
    # the linear indicator is −P K₀⁻¹ r, computed here without the adjoint
    model, v = solver.model, hyper.basis
    q = hyper.coordinates(f[0])[0]
    r = solver.batched.internal_force(v @ q) - model.load_vectors() @ f[0]
    np.testing.assert_allclose(linear[0], -model.pose_of(model.back_substitute(r)), rtol=1e-8,
                               atol=1e-12 * np.abs(linear[0]).max())  # fmt: skip


def test_batched_linear_indicators_equal_the_residual_of_each_run(
    solver: NonlinearSolver, hyper: rm.ReducedOrderModel
) -> None:
    # every force vector at once (projected_internal_force) against one assembled residual a run
    f = _forces(5, RANGE, seed=3)
    batched = indicators.dual_weighted_residuals(hyper, solver, f)
    adjoint = indicators.pose_adjoint(solver)
    loads = solver.model.load_vectors()
    one_by_one = np.array([
        -(solver.residual(hyper.basis @ q, loads @ x) @ adjoint)
        for q, x in zip(hyper.coordinates(f), f, strict=True)
    ])  # fmt: skip
    np.testing.assert_allclose(batched, one_by_one, rtol=1e-9,
                               atol=1e-12 * np.abs(one_by_one).max())  # fmt: skip
    # any chunk of elements gives the same sums, to round-off
    q = hyper.coordinates(f)
    a = indicators.projected_internal_force(solver.batched, hyper.basis, q, adjoint, chunk=1)[0]
    b = indicators.projected_internal_force(solver.batched, hyper.basis, q, adjoint, chunk=500)[0]
    np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-12 * np.abs(b).max())


def test_a_state_that_inverts_an_element_is_named(
    solver: NonlinearSolver, hyper: rm.ReducedOrderModel
) -> None:
    q = np.zeros((3, hyper.n_basis))
    q[1] = -1e3 * hyper.loads[:, 0] / np.linalg.norm(hyper.loads[:, 0])  # far beyond any load
    adjoint = indicators.pose_adjoint(solver)
    _, inverted = indicators.projected_internal_force(solver.batched, hyper.basis, q, adjoint)
    assert inverted.tolist() == [False, True, False]


def test_indicators_refuse_bad_input(solver: NonlinearSolver, hyper: rm.ReducedOrderModel) -> None:
    with pytest.raises(ValueError, match="tangent must be one of"):
        indicators.dual_weighted_residuals(hyper, solver, np.zeros(6), tangent="secant")
    with pytest.raises(ValueError, match="force_range"):
        indicators.dual_weighted_residuals(hyper, solver, [12.0, 0, 0, 0, 0, 0])
    other = rm.ReducedOrderModel(hyper.basis[:-3], *[getattr(hyper, n) for n in _REST])
    with pytest.raises(ValueError, match="build the ROM on this solver"):
        indicators.dual_weighted_residuals(other, solver, np.zeros(6))
    assert np.array_equal(indicators.dual_weighted_residuals(hyper, solver, np.zeros(6)),
                          np.zeros((1, 6)))  # fmt: skip


_REST = ("force", "loads", "pose_map", "predictor", "cells", "weights", "force_range")
