"""Chapter 2's method on the parallelogram flexure (:mod:`mechlib.parallelogram.method`,
:mod:`mechlib.parallelogram.metamethod`): synthetic truths whose answers are known, bad input,
and one small run of the whole chain on the elastica stand-in."""

from __future__ import annotations

import numpy as np
import pytest

from mechlib.parallelogram import metamethod as mm
from mechlib.parallelogram import method as m

HALF = m.HALF_RANGE
#: a linear truth: pose per unit of scaled load u = load / HALF; its zeros are inactive loads
M = np.array([[0.5, 0.0, 0.0], [0.0, 2.0, -0.3], [0.0, 0.1, 1.0]])


def linear_truth(loads: np.ndarray) -> np.ndarray:
    return (loads / HALF) @ M.T


def quadratic_truth(loads: np.ndarray, eps: float) -> np.ndarray:
    """The linear truth plus ``eps`` times squares and a product of the scaled loads."""
    u = loads / HALF
    return u @ M.T + eps * np.column_stack([u[:, 1] ** 2, u[:, 0] * u[:, 1], u[:, 2] ** 2])


def smooth_truth(loads: np.ndarray) -> np.ndarray:
    """A smooth non-polynomial truth of the scaled loads."""
    u = loads / HALF
    return np.column_stack(
        [
            np.sin(1.2 * u[:, 1]) + 0.3 * u[:, 0] * u[:, 2],
            np.tanh(u[:, 0] + 0.5 * u[:, 1]),
            0.2 * u[:, 2] + 0.4 * np.exp(0.5 * u[:, 1]),
        ]
    )


# --- designs and screening -----------------------------------------------------------------


def test_screening_design_runs_a_full_factorial_of_the_loads_at_the_fraction() -> None:
    d = m.screening_design(0.5)
    assert d.coded.shape == (8, 7) and d.loads.shape == (8, 3)
    assert len(np.unique(d.loads, axis=0)) == 8  # no load combination run twice
    np.testing.assert_array_equal(d.loads, 0.5 * HALF * d.coded[:, :3])
    np.testing.assert_array_equal(d.coded.T @ d.coded, 8 * np.eye(7))  # orthogonal columns
    # B's column is not ± the product of A_x's and A_y's (as pyDOE3's columns 2, 0, 1 are)
    assert abs((d.coded[:, 0] * d.coded[:, 1]) @ d.coded[:, 2]) < 8
    assert len(np.unique(m.screening_design(1.0, 12).loads, axis=0)) == 8


def test_screening_finds_exactly_the_active_loads_of_a_linear_truth() -> None:
    d = m.screening_design(0.5)
    rng = np.random.default_rng(0)  # round-off on the truth: counted as 0 by zero_tol
    poses = linear_truth(d.loads) * (1 + 1e-14 * rng.standard_normal((8, 3)))
    sc = m.screen(d.coded, poses)
    np.testing.assert_array_equal(sc.active, M.T != 0)
    np.testing.assert_array_equal(sc.dummies_active, [0, 0, 0])
    np.testing.assert_allclose(sc.effects[:3], 2 * 0.5 * M.T, atol=1e-12)  # (+) minus (−)


def test_an_interaction_lands_on_a_dummy_not_on_a_load() -> None:
    d = m.screening_design(0.5)
    poses = quadratic_truth(d.loads, 0.0)
    u = d.loads / HALF
    poses[:, 2] += 0.8 * u[:, 0] * u[:, 1]  # an A_x·A_y interaction on φ
    sc = m.screen(d.coded, poses)
    np.testing.assert_allclose(sc.effects[:3], 2 * 0.5 * M.T, atol=1e-12)  # loads unchanged
    alias = [k for k in range(7) if np.array_equal(d.coded[:, k], d.coded[:, 0] * d.coded[:, 1])]
    assert len(alias) == 1 and alias[0] >= 3  # a dummy column
    assert sc.effects[alias[0], 2] == pytest.approx(2 * 0.8 * 0.5**2)
    np.testing.assert_array_equal(sc.dummies_active, [0, 0, 1])


def test_uniform_design_is_seeded_space_filling_and_inside_its_scale() -> None:
    x = m.uniform_design(20, 3, scale=0.5)
    assert x.shape == (20, 3) and np.all(np.abs(x) <= 0.5 * HALF)
    np.testing.assert_array_equal(x, m.uniform_design(20, 3, scale=0.5))
    assert not np.array_equal(x, m.uniform_design(20, 4, scale=0.5))
    strata = np.floor((x / (0.5 * HALF) + 1) / 2 * 20).astype(int)  # a Latin hypercube
    np.testing.assert_array_equal(np.sort(strata, axis=0), np.tile(np.arange(20)[:, None], 3))
    nested = mm.nested_design(32, 1, scale=0.25)
    prefix = np.floor((nested[:16] / (0.25 * HALF) + 1) / 2 * 16).astype(int)
    np.testing.assert_array_equal(np.sort(prefix, axis=0), np.tile(np.arange(16)[:, None], 3))
    held = m.held_out_design(10, 5, scale=0.1)
    assert np.all(np.abs(held) <= 0.1 * HALF)
    np.testing.assert_array_equal(m.held_out_design(4, 5, scale=0.1), held[:4])


# --- the thesis's meta-models --------------------------------------------------------------


def test_st_recovers_a_known_linear_map_with_and_without_intercept() -> None:
    x, val = m.uniform_design(10, 0), m.held_out_design(50, 1)
    per_load = M / HALF  # pose per unit of normalised load
    st = m.fit_st(x, linear_truth(x))
    np.testing.assert_allclose(st["S_per_load"], per_load, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(st["S"], M, rtol=1e-12, atol=1e-14)
    assert m.holdout_errors(st, val, linear_truth(val))["worst_pct"] < 1e-9
    b0 = np.array([0.1, -0.2, 0.3])
    st1 = m.fit_st(x, linear_truth(x) + b0, intercept=True)
    np.testing.assert_allclose(st1["b0"], b0, rtol=1e-12)
    np.testing.assert_allclose(st1["S_per_load"], per_load, rtol=1e-12, atol=1e-15)


def test_eq6_recovers_a_known_quadratic_that_st_misses() -> None:
    x, val = m.uniform_design(15, 0), m.held_out_design(50, 1)
    y, vy = quadratic_truth(x, 0.5), quadratic_truth(val, 0.5)
    eq6 = m.fit_eq6(x, y)
    assert m.holdout_errors(eq6, val, vy)["worst_pct"] < 1e-9
    names = eq6["names"]
    assert eq6["coef"][names.index("t1^2"), 0] == pytest.approx(0.5)
    assert eq6["coef"][names.index("t0*t1"), 1] == pytest.approx(0.5)
    assert m.holdout_errors(m.fit_st(x, y), val, vy)["worst_pct"] > 10.0


# --- the non-linear families ---------------------------------------------------------------


def test_learning_curve_errors_fall_with_size_on_a_smooth_truth() -> None:
    x, val = mm.nested_design(128, 0), m.held_out_design(100, 1)
    sizes = [16, 32, 64, 128]
    curve = mm.learning_curves(
        ["cubic", "pce", "gp"], x, smooth_truth(x), val, smooth_truth(val), sizes
    )
    worst = curve["worst_pct"]
    assert np.isnan(worst[0, 0]) and np.all(np.isfinite(worst[:, 1:]))  # cubic: 20 terms
    for row in worst:
        fitted = row[np.isfinite(row)]
        assert fitted[-1] < fitted[0]
    # a fixed-degree polynomial falls to its bias; the GP interpolates the smooth truth
    assert worst[2, -1] < worst[2, 0] / 100 and worst[2, -1] < worst[:2, -1].min()


def test_budget_range_shrinks_as_the_truth_gets_more_nonlinear() -> None:
    scales = [1 / 16, 1 / 8, 1 / 4, 1 / 2, 1.0]
    largest = {}
    for eps in (1e-4, 1e-2, 1.0):
        train = {s: mm.nested_design(16, 0, scale=s) for s in scales}
        held = {s: m.held_out_design(16, 1, scale=s) for s in scales}
        study = mm.budget_scales(
            ["linear", "quadratic"],
            {s: (x, quadratic_truth(x, eps)) for s, x in train.items()},
            {s: (x, quadratic_truth(x, eps)) for s, x in held.items()},
            budget_pct=1.0,
        )
        np.testing.assert_array_equal(study["scales"], scales)
        assert study["largest"][1] == 1.0  # Eq 6 is exact on a quadratic truth
        largest[eps] = study["largest"][0]
    assert largest[1e-4] == 1.0 and largest[1e-4] >= largest[1e-2] > largest[1.0]


def test_realtime_model_distils_the_family_with_the_smallest_cv_error() -> None:
    x, val = mm.nested_design(64, 0, scale=0.5), m.held_out_design(50, 1, scale=0.5)
    y, vy = smooth_truth(x), smooth_truth(val)
    cv = mm.cv_errors(["quadratic", "cubic", "gp"], x, y, scale=0.5)
    rt = mm.realtime_model(x, y, cv, goal_pct=1.0, scale=0.5, degrees=(2, 3, 4, 5))
    assert rt.teacher == min(cv, key=cv.get)
    assert rt.student.family == "distilled" and rt.student.amplitude == 0.5
    assert rt.degree in (2, 3, 4, 5) and rt.distill_errors[rt.degree] <= rt.tol_pct
    assert list(rt.distill_errors)[-1] == rt.degree  # the lowest degree within tolerance
    student = mm.score_family(rt.student, val, vy)["worst_pct"]
    teacher = mm.score_family(rt.teacher_model, val, vy)["worst_pct"]
    assert student <= teacher + 2 * rt.tol_pct
    assert mm.predict_family(rt.student, val).shape == (50, 3)


# --- bad input -----------------------------------------------------------------------------


def test_bad_input_names_the_parameter_its_value_and_the_range() -> None:
    x = m.uniform_design(10, 0)
    y = linear_truth(x)
    with pytest.raises(ValueError, match=r"loads must have shape \(any, 3\), got \(10, 2\)"):
        m.fit_st(x[:, :2], y)
    bad = x.copy()
    bad[4, 1] = 25.0
    with pytest.raises(ValueError, match=r"loads must lie within 1 × the box .*A_y in \[-20, 20\]"):
        m.fit_st(bad, y)
    with pytest.raises(ValueError, match=r"got A_y = 25 in run 4"):
        m.fit_eq6(bad, y)
    with pytest.raises(ValueError, match=r"poses must have shape \(10, 3\), got \(9, 3\)"):
        m.fit_st(x, y[:9])
    with pytest.raises(ValueError, match=r"at least 10 runs for Eq 6 .* got 9"):
        m.fit_eq6(x[:9], y[:9])
    with pytest.raises(ValueError, match=r"at least 20 runs for the cubic family .* got 10"):
        mm.fit_family("cubic", x, y)
    with pytest.raises(ValueError, match=r"family must be one of \['linear'"):
        mm.fit_family("spline", x, y)
    with pytest.raises(ValueError, match=r"scale must be in \(0.0, 1.0\], got 1.5"):
        mm.fit_family("linear", x, y, scale=1.5)
    with pytest.raises(ValueError, match=r"loads must lie within 0.5 × the box"):
        mm.fit_family("linear", x, y, scale=0.5)
    small = m.uniform_design(10, 0, scale=0.5)
    fit = mm.fit_family("linear", small, linear_truth(small), scale=0.5)
    with pytest.raises(ValueError, match=r"loads must lie within 0.5 × the box .*A_x in \[-5, 5\]"):
        mm.predict_family(fit, x)
    with pytest.raises(ValueError, match=r"fraction must be in \(0.0, 1.0\], got 1.5"):
        m.screening_design(1.5)
    with pytest.raises(ValueError, match=r"n_runs must be in \[8, 48\], got 4"):
        m.screening_design(1.0, 4)
    with pytest.raises(ValueError, match=r"coded must have at least 4 columns"):
        m.screen(m.screening_design().coded[:, :3], y[:8])
    with pytest.raises(ValueError, match=r"sizes \(the largest\) must have at least 20 runs"):
        mm.learning_curves(["cubic"], x, y, x, y, [5, 10])
    with pytest.raises(ValueError, match=r"val_poses must have shape \(10, 3\), got \(10, 2\)"):
        mm.learning_curves(["linear"], x, y, x, y[:, :2], [5, 10])
    with pytest.raises(ValueError, match=r"val_loads must lie within 0.5 × the box"):
        mm.learning_curves(["linear"], small, linear_truth(small), x, y, [5, 10], scale=0.5)
    with pytest.raises(ValueError, match=r"held_out must hold the same scales as training"):
        mm.budget_scales(["linear"], {0.5: (small, y)}, {1.0: (x, y)})
    with pytest.raises(ValueError, match=r"families must list distinct names"):
        mm.cv_errors(["linear", "linear"], x, y)


# --- the elastica stand-in -----------------------------------------------------------------


def test_the_method_on_the_elastica_stand_in() -> None:
    """40 elastica runs: screening (8), S_T at small loads (12), S_T and Eq 6 at a quarter of
    the ranges (12 + 8 held out)."""
    from mechlib.parallelogram import published as pub
    from mechlib.parallelogram.elastica import solve_pose

    def truth(loads: np.ndarray) -> np.ndarray:
        sols = [solve_pose(*row, axial_compliance=pub.AXIAL_COMPLIANCE) for row in loads]
        return np.array([(s.u_x, s.u_y, s.phi) for s in sols])

    d = m.screening_design(0.1)
    sc = m.screen(d.coded, truth(d.loads))
    # mirror symmetry about x: (A_y, B) → (−A_y, −B) maps (u_x, u_y, φ) to (u_x, −u_y, −φ); in
    # the full factorial the effects of A_y, B on u_x and of A_x on u_y, φ cancel
    np.testing.assert_array_equal(sc.effects[1:3, 0], 0.0)
    np.testing.assert_array_equal(sc.effects[0, 1:], 0.0)
    assert sc.active[0, 0] and sc.active[1, 1] and sc.active[2, 2]
    # two fixed-guided beams: u_y/L = A_y/24 at small loads (here A_y = ±2)
    assert sc.effects[1, 1] == pytest.approx(2 * 0.1 * HALF[1] / 24, rel=0.01)
    # S_T at a hundredth of the ranges: u_y per A_y 1/24; φ per B c/(2w²) (the beams' axial
    # stretch turns the stage)
    x = m.uniform_design(12, 1, scale=0.01)
    s = m.fit_st(x, truth(x))["S_per_load"]
    assert s[1, 1] == pytest.approx(1 / 24, rel=0.01)
    w = pub.SEPARATION_MM / 2 / pub.LENGTH_MM
    assert s[2, 2] == pytest.approx(pub.AXIAL_COMPLIANCE / (2 * w**2), rel=0.02)
    # a quarter of the ranges: the shortening u_x (even in (A_y, B), one-signed) escapes S_T
    # (through the origin, odd in the loads) but not Eq 6
    x, val = m.uniform_design(12, 2, scale=0.25), m.held_out_design(8, 3, scale=0.25)
    y, vy = truth(x), truth(val)
    st = m.holdout_errors(m.fit_st(x, y), val, vy)["max_range_pct"]
    eq6 = m.holdout_errors(m.fit_eq6(x, y), val, vy)["max_range_pct"]
    assert st[0] > 50.0 and eq6[0] < st[0] / 3
