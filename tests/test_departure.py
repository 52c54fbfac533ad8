"""Parity split of the departure from linearity: exact on a polynomial response."""

import numpy as np
import pytest

from mechlib.hexflex.spec import ModelSpec
from mechlib.hexflex.studies.departure import parity_split, parity_summary


def _response(f: np.ndarray) -> np.ndarray:
    s = np.array([[2.0, -1.0], [0.5, 3.0]])
    quad = np.stack([f[:, 0] * f[:, 1], f[:, 0] ** 2], axis=1)
    cubic = np.stack([f[:, 1] ** 3, -0.2 * f[:, 0] ** 2 * f[:, 1]], axis=1)
    return f @ s.T + 0.1 * quad + 0.03 * cubic, f @ s.T, 0.1 * quad, 0.03 * cubic


def test_parity_split_recovers_the_quadratic_and_cubic_terms():
    f = np.random.default_rng(0).uniform(-1, 1, (20, 2))
    plus, lin, quad, cubic = _response(f)
    minus, *_ = _response(-f)
    split = parity_split(plus, minus, lin)
    np.testing.assert_allclose(split["even"], quad, atol=1e-14)
    np.testing.assert_allclose(split["odd"], cubic, atol=1e-14)
    np.testing.assert_allclose(split["even"] + split["odd"], plus - lin, atol=1e-14)


def test_parity_summary_is_a_share_of_the_scale():
    f = np.random.default_rng(1).uniform(-1, 1, (10, 2))
    plus, lin, quad, _ = _response(f)
    minus, *_ = _response(-f)
    scale = np.abs(plus).max(axis=0)
    out = parity_summary(parity_split(plus, minus, lin), scale)
    np.testing.assert_allclose(out["even"], 100 * np.abs(quad).max(axis=0) / scale)
    with pytest.raises(ValueError, match="scale must be 2 positive"):
        parity_summary(parity_split(plus, minus, lin), [1.0, 0.0])


def test_parity_split_refuses_mismatched_shapes():
    with pytest.raises(ValueError, match="minus"):
        parity_split(np.zeros((3, 6)), np.zeros((2, 6)), np.zeros((3, 6)))


def test_relative_change_is_per_column_and_refuses_a_zero_reference():
    from mechlib.hexflex.studies.departure import relative_change

    ref = np.array([[1.0, -2.0], [0.5, 4.0]])
    out = relative_change(ref + np.array([[0.01, 0.0], [0.0, -0.2]]), ref)
    np.testing.assert_allclose(out, [1.0, 5.0])
    with pytest.raises(ValueError, match="non-zero"):
        relative_change(ref, np.zeros_like(ref))


def test_linear_poses_at_the_models_quadrature_are_the_linear_models():
    from test_hexflex import SMALL  # tests/ is on sys.path (pytest prepend import mode)

    from mechlib.fe.nonlinear import NonlinearSolver
    from mechlib.hexflex.fe.model import HexFlexModel
    from mechlib.hexflex.studies.departure import linear_poses

    model = HexFlexModel(SMALL, element="q2", mesh_size=1.0)
    forces = np.array([[0.3, -0.2, 0.1, 0.0, 0.5, -0.4]])
    want = model.poses(forces)  # forces @ C.T: the same solves, combined after the pose fit
    np.testing.assert_allclose(
        linear_poses(NonlinearSolver(model), forces), want, atol=1e-12 * np.abs(want).max()
    )
    # with another quadrature the linear problem is factorised anew: close, not equal
    other = linear_poses(NonlinearSolver(model, quad_order=6), forces)
    change = np.abs(other - model.poses(forces)).max() / np.abs(model.poses(forces)).max()
    assert 1e-12 < change < 1e-2


def test_linear_poses_for_a_spec_uses_the_processs_model_and_solver():
    from test_hexflex import SMALL

    from mechlib.campaign import experiments as ex
    from mechlib.hexflex.studies.departure import linear_poses, linear_poses_for

    forces = np.array([[0.3, -0.2, 0.1, 0.0, 0.5, -0.4], [-0.1, 0.6, 0.0, 0.2, -0.3, 0.1]])
    ex.release_models()
    try:
        spec = ModelSpec(SMALL, element="q2", mesh_size=1.0)
        # at the model's quadrature: the cached linear model's own poses, bit for bit
        np.testing.assert_array_equal(
            linear_poses_for(spec, forces), ex.model_for(spec).poses(forces)
        )
        assert ex.solver_for.cache_info().currsize == 0  # no solver built for it
        # at another quadrature: the process's solver of that spec (built once, then reused)
        other = ModelSpec(SMALL, element="q2", mesh_size=1.0, quad_order=6)
        got = linear_poses_for(other, forces)
        assert ex.solver_for.cache_info().currsize == 1
        np.testing.assert_array_equal(got, linear_poses(ex.solver_for(other), forces))
        assert ex.solver_for.cache_info().hits == 1
        assert not np.array_equal(got, ex.model_for(spec).poses(forces))
    finally:
        ex.release_models()
