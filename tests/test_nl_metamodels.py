"""Pieces of the meta-model page on the non-linear HexFlex: Sobol' designs, a physics-based
model as a surrogate, cross-validation folds, snapshot fields, the page's figures."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
from matplotlib.figure import Figure
from test_hexflex import SMALL  # tests/ is on sys.path (pytest prepend import mode)

from mechlib.campaign import experiments as ex
from mechlib.hexflex.rom import snapshots
from mechlib.hexflex.spec import ModelSpec
from mechlib.metamodels import designs, families, inverse, scoring, study
from mechlib.plotting import metamodels as mmplot


def test_sobol_designs_are_nested_balanced_and_seeded() -> None:
    d = designs.sobol_design(64, 0.5, seed=3)
    f = d["forces"]
    assert f.shape == (64, 6) and np.abs(f).max() <= 0.5
    for n in (16, 32, 64):  # every power-of-two prefix: one point per 1/n slice of each axis
        u = (f[:n] / 0.5 + 1) / 2
        assert all(len(np.unique(np.floor(u[:, j] * n))) == n for j in range(6))
    assert np.array_equal(f, designs.sobol_design(64, 0.5, seed=3)["forces"])
    assert not np.array_equal(f, designs.sobol_design(64, 0.5, seed=4)["forces"])
    with pytest.raises(ValueError, match=r"n_runs must be a power of two.*got 48"):
        designs.sobol_design(48, 1.0, seed=0)
    with pytest.raises(ValueError, match="amplitude"):
        designs.sobol_design(16, 0.0, seed=0)


def _cubic_truth(x: np.ndarray) -> np.ndarray:
    return x @ np.diag([2.0, 1.0, 3.0, 1.5, 0.5, 1.0]) + 0.1 * x**3


def test_a_physics_model_is_scored_timed_and_inverted_like_a_fitted_one() -> None:
    model = families.wrap_model("cubic", _cubic_truth, amplitude=1.0)
    x = np.random.default_rng(0).uniform(-0.8, 0.8, (20, 6))
    s = scoring.score(model, x, _cubic_truth(x))
    assert s["worst_pct"] == 0.0
    lin = families.fit_surrogate("linear", x, _cubic_truth(x), amplitude=1.0)
    assert scoring.score(lin, x, _cubic_truth(x))["worst_pct"] > 0.1
    target = _cubic_truth(x[:3])
    forces = inverse.invert(model, target)["forces"]
    assert np.allclose(forces, x[:3], atol=1e-8)
    assert scoring.latency_us(model, x, repeats=2)["single"] > 0
    with pytest.raises(ValueError, match="validated range"):
        scoring.score(model, 1.5 * np.ones((1, 6)), np.zeros((1, 6)))
    with pytest.raises(ValueError, match="poses must be callable"):
        families.wrap_model("x", 3.0, amplitude=1.0)


def test_cv_folds_fall_back_to_leave_one_out_and_refuse_too_few_runs() -> None:
    assert scoring.cv_folds("linear", 30) == 5
    assert scoring.cv_folds("quadratic", 30) == 30  # 5 folds would leave 24 < 28 terms
    assert scoring.cv_folds("quadratic", 64) == 5
    with pytest.raises(ValueError, match="n_runs must exceed the quadratic family's 28 terms"):
        scoring.cv_folds("quadratic", 28)


def test_snapshot_fields_are_the_solver_s_and_cached(tmp_path) -> None:
    spec = ModelSpec(SMALL, element="q2", mesh_size=1.0)
    forces = np.array([[0.5, -0.3, 0.2, 0.4, -0.1, 0.3]])
    fields = snapshots.nonlinear_states(spec, forces, cache_dir=tmp_path)
    solver = ex.solver_for(spec)
    assert np.array_equal(fields[0], solver.solve(forces[0])[0])
    (cached,) = list(tmp_path.glob("*.state.npy"))
    np.save(cached, fields[:1] + 1.0)  # a cached field (1, n_dofs) is read, not solved again
    assert np.array_equal(snapshots.nonlinear_states(spec, forces, cache_dir=tmp_path), fields + 1)
    poses = ex.run_experiments(spec, forces, kind="nonlinear", progress=False)
    assert np.array_equal(solver.model.pose_of(fields[0]), poses[0])


def test_the_page_figures_draw() -> None:
    w = np.array([[5.0, 2.0, 1.0], [np.nan, 3.0, 0.5]])
    fig = mmplot.learning_curves([16, 32, 64], w, ["a", "b"], {"rom": (42, 0.3)}, 1.0)
    assert isinstance(fig, Figure) and len(fig.axes[0].lines) == 4  # 2 curves, 1 point, budget
    assert isinstance(mmplot.error_vs_range([0.25, 0.5, 1.0], w, ["a", "b"], 1.0), Figure)
    assert isinstance(mmplot.latency_accuracy([1.0, 2e3], [5.0, 0.3], ["a", "b"], 1.0, 1e3), Figure)


def test_budget_ranges_need_every_smaller_range_within_and_mark_unfitted() -> None:
    x = np.random.default_rng(1).uniform(-1, 1, (30, 6))
    exact = families.wrap_model("cubic", _cubic_truth, amplitude=1.0)
    cases = {a: (a * x, _cubic_truth(a * x)) for a in (0.25, 0.5, 1.0)}
    lin = {
        a: families.fit_surrogate("linear", a * x, _cubic_truth(a * x), amplitude=a)
        for a in (0.25, 1.0)  # not fitted at 0.5
    }
    out = study.budget_ranges({"exact": dict.fromkeys(cases, exact), "lin": lin}, cases, 1.0)
    assert out["amplitudes"].tolist() == [0.25, 0.5, 1.0]
    assert out["largest"][0] == 1.0 and np.all(out["worst_pct"][0] == 0.0)
    assert out["fitted"][1].tolist() == [True, False, True] and out["worst_pct"][1, 1] == 0.0
    assert out["largest"][1] == (0.25 if out["worst_pct"][1, 0] <= 1.0 else 0.0)
    assert out["worst_pct"][1, 2] > out["worst_pct"][1, 0]  # the cubic term grows with range
    with pytest.raises(ValueError, match="budget_pct"):
        study.budget_ranges({}, cases, 0.0)


def test_inverse_round_trip_applies_the_forces_and_leaves_unsolved_runs_out() -> None:
    exact = families.wrap_model("cubic", _cubic_truth, amplitude=1.0)
    x = np.random.default_rng(2).uniform(-0.5, 0.5, (3, 6))
    span = np.abs(_cubic_truth(x)).max(axis=0)

    def truth_missing_one(forces):  # a truth that could not solve run 1
        return np.array([0, 2]), _cubic_truth(forces[[0, 2]]) + 0.01, ["run 1 failed"]

    out = study.inverse_round_trip(exact, _cubic_truth(x), truth_missing_one, span)
    assert out["solved"].tolist() == [0, 2] and out["converged"].all()
    # 0.01 off by construction; the rounding of the forces to 1 µN adds ≈ 1e-6 of a pose
    np.testing.assert_allclose(out["error_pct"], 100 * 0.01 / span, rtol=1e-3)
    with pytest.raises(ValueError, match="span must be positive"):
        study.inverse_round_trip(exact, _cubic_truth(x), truth_missing_one, np.zeros(6))


def test_the_truth_is_given_rounded_forces_that_round_off_does_not_move() -> None:
    x = np.random.default_rng(3).uniform(-0.5, 0.5, (4, 6))
    given = []

    def truth(forces):
        given.append(forces.copy())
        return np.arange(len(forces)), _cubic_truth(forces)

    for wobble in (0.0, 3e-14):  # another processor's last digits in the model
        model = families.wrap_model("cubic", lambda f, w=wobble: _cubic_truth(f) * (1 + w), 1.0)
        out = study.inverse_round_trip(model, _cubic_truth(x), truth, np.ones(6))
        assert np.array_equal(out["forces"], given[-1])
    assert np.array_equal(given[0], np.round(given[0], study.FORCE_DECIMALS))
    assert np.array_equal(given[0], given[1])
    assert np.abs(given[0] - x).max() <= 0.5 * 10.0**-study.FORCE_DECIMALS + 1e-12
