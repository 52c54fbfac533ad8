"""Real-time models: the ROM-plus-correction form and the distilled polynomial."""

import numpy as np
import pytest

from mechlib.metamodels import realtime as rt
from mechlib.metamodels.families import predict, wrap_model
from mechlib.metamodels.scoring import latency_us, score

RNG = np.random.default_rng(2010)
S = RNG.normal(size=(6, 6))


def _truth(f: np.ndarray) -> np.ndarray:
    """A smooth non-linear force → pose map: linear plus cubic and a sine."""
    return f @ S.T + 0.05 * (f**3) @ S.T + 0.02 * np.sin(2 * f[:, [0]]) * np.ones(6)


def _cubic(f: np.ndarray) -> np.ndarray:
    return f @ S.T + 0.05 * (f**3) @ S.T


def test_a_polynomial_teacher_is_distilled_exactly_at_its_degree() -> None:
    teacher = wrap_model("cubic", _cubic, amplitude=1.0)
    low = rt.distill(teacher, 2, n_samples=2**10)
    exact = rt.distill(teacher, 3, n_samples=2**10)
    assert rt.distillation_error_pct(exact, teacher) < 1e-9
    assert rt.distillation_error_pct(low, teacher) > 1.0
    student, errors = rt.distill_to(teacher, 1e-6, degrees=(2, 3, 4), n_samples=2**10)
    assert list(errors) == [2, 3] and student.state["exponents"].max() == 3
    x = RNG.uniform(-1, 1, (50, 6))
    np.testing.assert_allclose(predict(student, x), _cubic(x), atol=1e-9)
    assert latency_us(student, x, repeats=3)["single"] > 0


def test_no_degree_within_tol_keeps_the_most_accurate() -> None:
    teacher = wrap_model("truth", _truth, amplitude=1.0)
    student, errors = rt.distill_to(teacher, 1e-12, degrees=(1, 3), n_samples=2**10)
    assert list(errors) == [1, 3] and errors[3] < errors[1]
    assert student.state["exponents"].max() == 3


def test_a_correction_learns_what_the_low_fidelity_model_misses() -> None:
    low = wrap_model("linear part", lambda f: f @ S.T, amplitude=1.0)
    x = 2 * RNG.random((64, 6)) - 1
    held = 2 * RNG.random((200, 6)) - 1
    fixed = rt.corrected(low, x, _truth(x), seed=1)
    before, after = score(low, held, _truth(held)), score(fixed, held, _truth(held))
    assert after["worst_pct"] < before["worst_pct"] / 2
    cv = rt.cross_validate_corrected(low, x, _truth(x), folds=4, seed=1)
    assert 0 < cv["worst_pct"] < before["worst_pct"]


def test_bad_distillation_settings_are_refused_by_name() -> None:
    teacher = wrap_model("cubic", _cubic, amplitude=1.0)
    with pytest.raises(ValueError, match="degree"):
        rt.distill(teacher, rt.MAX_DEGREE + 1)
    with pytest.raises(ValueError, match="power of two"):
        rt.distill(teacher, 2, n_samples=1000)
    with pytest.raises(ValueError, match="must exceed the 462 terms"):
        rt.distill(teacher, 5, n_samples=256)
    with pytest.raises(ValueError, match="degrees must be increasing"):
        rt.distill_to(teacher, 1.0, degrees=(4, 3))
