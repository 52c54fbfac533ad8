"""Parity split of the departure from linearity: exact on a polynomial response."""

import numpy as np
import pytest

from mechlib.hexflex.departure import parity_split, parity_summary


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
