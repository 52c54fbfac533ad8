"""Meta-model families, scores, learning curves, budgets, designs and the inverse, on synthetic
maps."""

import numpy as np
import pytest

from mechlib.metamodels import designs, families, inverse, scoring, study

RNG_SEED = 3
EXACT = 1e-8  # max |error| as % of range for a family fitting a map of its own order exactly
AMP = 1.0  # N


def _map(order: int, seed: int = RNG_SEED, offset: float = 0.1):
    """A map of total degree ``order``: a linear part of unit scale plus 5 % higher terms."""
    rng = np.random.default_rng(seed)
    s = rng.normal(size=(6, 6)) + 3 * np.eye(6)  # well conditioned
    q = rng.normal(size=(6, 6, 6))
    c = rng.normal(size=(6, 6, 6, 6))

    def f(x: np.ndarray) -> np.ndarray:
        y = offset + x @ s.T
        if order >= 2:
            y = y + 0.05 * np.einsum("oij,ni,nj->no", q, x, x)
        if order >= 3:
            y = y + 0.01 * np.einsum("oijk,ni,nj,nk->no", c, x, x, x)
        return y * np.array([1, 10, 100, 1e3, 1e4, 1e5])  # µm and µrad scales

    return f


def _data(order: int, n: int, seed: int = 0):
    f = _map(order)
    x = designs.space_filling_design(n, AMP, seed)["forces"]
    xv = AMP * (2 * np.random.default_rng(seed + 100).random((200, 6)) - 1)
    return f, x, f(x), xv, f(xv)


@pytest.mark.parametrize(("family", "order"), [("quadratic", 2), ("cubic", 3), ("pce", 3)])
def test_each_family_recovers_a_polynomial_of_its_order(family: str, order: int) -> None:
    _, x, y, xv, yv = _data(order, 120)
    assert (
        scoring.score(families.fit_surrogate(family, x, y, amplitude=AMP), xv, yv)["worst_pct"]
        < EXACT
    )


def test_linear_recovers_st_and_cannot_fit_a_quadratic() -> None:
    rng = np.random.default_rng(RNG_SEED)
    s = rng.normal(size=(6, 6))
    x = designs.space_filling_design(30, AMP, 1)["forces"]
    fit = families.fit_surrogate("linear", x, x @ s.T, amplitude=AMP)
    np.testing.assert_allclose(fit.state["S"], s, rtol=1e-10, atol=1e-12)
    _, x, y, xv, yv = _data(2, 60)
    assert (
        scoring.score(families.fit_surrogate("linear", x, y, amplitude=AMP), xv, yv)["worst_pct"]
        > 1.0
    )


def test_gp_interpolates_and_beats_linear_on_a_quadratic() -> None:
    _, x, y, xv, yv = _data(2, 40)
    gp = families.fit_surrogate("gp", x, y, amplitude=AMP, seed=0)
    assert np.abs(families.predict(gp, x) - y).max() / np.abs(y).max() < 1e-3  # near interpolation
    lin = scoring.score(families.fit_surrogate("linear", x, y, amplitude=AMP), xv, yv)["worst_pct"]
    assert scoring.score(gp, xv, yv)["worst_pct"] < 0.5 * lin
    inv = inverse.invert(
        gp, families.predict(gp, 0.5 * xv[:5])
    )  # Newton stops at the GP's round-off
    assert inv["converged"].all() and np.abs(inv["forces"] - 0.5 * xv[:5]).max() < 1e-6


def test_scores_are_table5_metrics_and_seeded() -> None:
    _, x, y, xv, yv = _data(3, 40)
    fit = families.fit_surrogate("quadratic", x, y, amplitude=AMP)
    s = scoring.score(fit, xv, yv)
    pred = families.predict(fit, xv)
    want = 100 * np.abs(pred - yv).max(axis=0) / np.abs(yv).max(axis=0)
    np.testing.assert_allclose(s["max_range_pct"], want)
    np.testing.assert_allclose(s["rmse"], np.sqrt(np.mean((pred - yv) ** 2, axis=0)))
    a = scoring.cross_validate("quadratic", x, y, amplitude=AMP, folds=4, seed=7)
    b = scoring.cross_validate("quadratic", x, y, amplitude=AMP, folds=4, seed=7)
    c = scoring.cross_validate("quadratic", x, y, amplitude=AMP, folds=4, seed=8)
    np.testing.assert_array_equal(a["predicted"], b["predicted"])
    assert not np.array_equal(a["predicted"], c["predicted"])
    assert a["worst_pct"] > s["worst_pct"] * 0.1  # out-of-fold, not resubstitution (≈ 0)
    t = scoring.latency_us(fit, xv, repeats=3)
    assert set(t) == {"batched", "single"} and all(np.isfinite(v) for v in t.values())
    both = scoring.compare_families(
        ["linear", "quadratic"], x, y, xv, yv, amplitude=AMP, folds=4, seed=7
    )
    np.testing.assert_array_equal(both["quadratic"]["cv"]["predicted"], a["predicted"])
    np.testing.assert_array_equal(both["quadratic"]["validation"]["rmse"], s["rmse"])
    assert both["linear"]["validation"]["worst_pct"] > s["worst_pct"]
    table = scoring.summary_table(both, ["x", "y", "z", "tx", "ty", "tz"])
    assert list(table.index) == ["linear", "quadratic"]
    assert table.loc["quadratic", "max % tz"] == s["max_range_pct"][5]
    with pytest.raises(ValueError, match="outputs must name the 6 pose components"):
        scoring.summary_table(both, ["x"])


def test_seeded_fits_repeat_exactly() -> None:
    _, x, y, xv, _ = _data(3, 24)
    for fam in ("gp", "pce"):
        a = families.predict(families.fit_surrogate(fam, x, y, amplitude=AMP, seed=2), xv)
        np.testing.assert_array_equal(
            a, families.predict(families.fit_surrogate(fam, x, y, amplitude=AMP, seed=2), xv)
        )


def test_learning_curve_is_nested_and_monotone_for_exact_quadratic_data() -> None:
    _, x, y, xv, yv = _data(2, 60)
    terms = families.n_terms("quadratic", 6)
    lc = study.learning_curve(
        ["linear", "quadratic"], x, y, xv, yv, [10, terms, 40, 60], amplitude=AMP
    )
    quad = lc["worst_pct"][1]
    assert np.isnan(quad[0]) and np.all(quad[1:] < EXACT)
    assert np.all(np.diff(quad[1:]) <= EXACT)  # non-increasing up to round-off
    assert np.all(lc["worst_pct"][0] > 1.0)  # linear never fits a quadratic
    again = study.learning_curve(
        ["linear", "quadratic"], x, y, xv, yv, [10, terms, 40, 60], amplitude=AMP
    )
    np.testing.assert_array_equal(lc["rmse"][0], again["rmse"][0])


def test_design_is_seeded_scaled_and_reports_cd() -> None:
    a = designs.space_filling_design(30, 0.5, 4)
    b = designs.space_filling_design(30, 0.5, 4)
    np.testing.assert_array_equal(a["forces"], b["forces"])
    assert a["forces"].shape == (30, 6) and np.abs(a["forces"]).max() <= 0.5
    # every column is a Latin hypercube: one run in each of the 30 strata of [-0.5, 0.5]
    strata = np.floor((a["forces"] / 0.5 + 1) / 2 * 30).astype(int)
    assert all(sorted(col) == list(range(30)) for col in strata.T)
    assert 0 < a["cd2"] < 0.05


def test_budget_ranges_on_a_linear_fit_of_a_quadratic_map() -> None:
    # S_T of the linear part, validated against the map with its quadratic part (as the thesis
    # validates the linear meta-model against non-linear FE): the error relative to the range
    # grows like the amplitude, so the small range meets the budget and the full one does not
    linear, full = _map(1, offset=0.0), _map(2, offset=0.0)
    x = designs.space_filling_design(20, AMP, 0)["forces"]
    fit = families.fit_surrogate("linear", x, linear(x), amplitude=AMP)
    rng = np.random.default_rng(9)
    cases = [(a, a * (2 * rng.random((100, 6)) - 1)) for a in (AMP, 0.05 * AMP)]
    r = study.budget_ranges(
        {"linear": dict.fromkeys((AMP, 0.05 * AMP), fit)},
        {a: (xa, full(xa)) for a, xa in cases},
        budget_pct=1.0,
    )
    assert r["amplitudes"].tolist() == [0.05 * AMP, AMP]
    assert (r["worst_pct"][0] <= 1.0).tolist() == [True, False] and r["largest"][0] == 0.05 * AMP
    with pytest.raises(ValueError, match="validated range"):  # forces beyond the fit's range
        study.budget_ranges({"linear": {2.0: fit}}, {2.0: (2 * x, full(2 * x))}, budget_pct=1.0)


def test_inverse_round_trips_on_a_nonlinear_polynomial() -> None:
    f, x, y, *_ = _data(3, 120)
    fit = families.fit_surrogate("cubic", x, y, amplitude=AMP)
    want = designs.space_filling_design(20, 0.8 * AMP, 11)["forces"]
    poses = f(want)
    inv = inverse.invert(fit, poses)
    assert inv["converged"].all() and np.abs(inv["start"] - want).max() > 1e-4  # Newton did work
    np.testing.assert_allclose(inv["forces"], want, atol=1e-8)
    back = families.predict(fit, inv["forces"])  # pose -> forces -> the meta-model's pose
    assert (np.abs(back - poses).max(axis=0) / np.abs(poses).max(axis=0)).max() < 1e-8
    span = np.abs(poses).max(axis=0)
    cmp = study.inverse_round_trip(fit, poses, lambda t: (np.arange(len(t)), f(t)), span)
    # the forces are applied rounded to 1 µN, which alone moves these poses by ≈ 1e-4 %
    assert cmp["converged"].all() and cmp["error_pct"].max() < 1e-3
    assert np.array_equal(cmp["forces"], np.round(inv["forces"], study.FORCE_DECIMALS))


def test_bad_inputs_are_refused_with_their_name() -> None:
    _, x, y, xv, yv = _data(2, 40)
    with pytest.raises(ValueError, match=r"family must be one of \['linear', 'quadratic', 'cub"):
        families.fit_surrogate("kriging", x, y, amplitude=AMP)
    with pytest.raises(ValueError, match=r"cubic family needs at least 84 training runs.*got 40"):
        families.fit_surrogate("cubic", x, y, amplitude=AMP)
    with pytest.raises(ValueError, match=r"poses must have shape \(40, any\)"):
        families.fit_surrogate("linear", x, y[:-1], amplitude=AMP)
    with pytest.raises(ValueError, match=r"sizes must be in \[1, 40\], got 41"):
        study.learning_curve(["linear"], x, y, xv, yv, [10, 41], amplitude=AMP)
    with pytest.raises(ValueError, match=r"families must be one of"):
        study.learning_curve(["spline"], x, y, xv, yv, [10], amplitude=AMP)
    fit = families.fit_surrogate("linear", x, y, amplitude=AMP)
    with pytest.raises(ValueError, match=r"forces must be within the validated range \[-1.0, 1"):
        families.predict(fit, 1.5 * xv)
    with pytest.raises(ValueError, match=r"forces must have shape \(any, 6\)"):
        scoring.score(fit, xv[:, :5], yv)
    with pytest.raises(ValueError, match=r"amplitude must be >= max \|forces\|"):
        families.fit_surrogate("linear", x, y, amplitude=0.5)
    with pytest.raises(ValueError, match=r"poses\[0\] needs a force of .* outside the validated"):
        inverse.invert(fit, 3 * families.predict(fit, xv[:1] / np.abs(xv[:1]).max()))
    with pytest.raises(ValueError, match="n_runs must be in"):
        designs.space_filling_design(1, AMP, 0)


def test_blas_threads_do_not_change_the_digits() -> None:
    from threadpoolctl import threadpool_limits

    _, x, y, xv, _ = _data(3, 90)
    with threadpool_limits(limits=1, user_api="blas"):
        one = families.predict(families.fit_surrogate("cubic", x, y, amplitude=AMP), xv)
    with threadpool_limits(limits=2, user_api="blas"):
        two = families.predict(families.fit_surrogate("cubic", x, y, amplitude=AMP), xv)
    np.testing.assert_array_equal(one, two)


def test_the_fast_legendre_evaluation_agrees_with_the_recurrence_up_to_the_largest_degree() -> None:
    from mechlib.metamodels import legendre
    from mechlib.metamodels.pce import legendre_products, total_degree_exponents
    from mechlib.metamodels.realtime import MAX_DEGREE

    rng = np.random.default_rng(3)
    u = rng.uniform(-1.0, 1.0, (50, 6))
    u[0] = 1.0  # the range's corners, where a power basis cancels most
    u[1] = -1.0
    for degree in (1, 5, MAX_DEGREE):
        exps = total_degree_exponents(6, degree)
        coef = rng.normal(size=(len(exps), 3))
        want = legendre_products(u, exps) @ coef
        got = legendre.evaluate(u, exps, coef)
        assert np.abs(got - want).max() <= 1e-11 * np.abs(want).max()
        assert not exps.flags.writeable
