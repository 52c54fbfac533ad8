"""Where the linear model stops holding: a departure level's crossing, a sweep on a small model."""

from pathlib import Path

import numpy as np
import pytest
from test_hexflex import SMALL  # tests/ is on sys.path (pytest prepend import mode)

from mechlib.campaign import experiments as ex
from mechlib.hexflex.spec import ModelSpec
from mechlib.hexflex.studies import linearity

SPEC = ModelSpec(SMALL, element="shell", mesh_size=1.0)


def test_linear_range_recovers_a_power_law_crossing() -> None:
    amps = np.array([0.1, 0.3, 1.0, 3.0])
    # component 0: err = 2 a (passes 1 % at 0.5 N); 1: err = 4 a² (at 0.5 N, exponent 2);
    # 2: never reaches 1 %; 3: already above 1 % at the smallest amplitude
    err = np.column_stack([2 * amps, 4 * amps**2, 0.1 * amps, 20 * amps])
    out = linearity.linear_range(amps, err, level=1.0)
    np.testing.assert_allclose(out["exponent"][:, 0], 1.0, rtol=1e-12)
    np.testing.assert_allclose(out["exponent"][:, 1], 2.0, rtol=1e-12)
    np.testing.assert_allclose(out["crossing"][:2], [0.5, 0.5], rtol=1e-12)
    assert out["crossing"][2] == np.inf and not out["below_sweep"][2]
    assert out["crossing"][3] == 0.1 and out["below_sweep"][3]


def test_linearity_sweep_on_a_small_q2_model(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    model = ex.model_for(ModelSpec(SMALL, element="q2", mesh_size=1.0))
    f = np.array([0.3, -0.5, 0.2, 1.0, -0.7, 0.1])  # largest |component| is 1 N
    amps = np.array([0.1, 0.2, 0.4])
    solver = ex.solver_for(ModelSpec(SMALL, element="q2", mesh_size=1.0))
    sweep = linearity.linearity_sweep(solver, 5.0 * f, amps)  # the direction is rescaled to 1 N
    np.testing.assert_array_equal(sweep["amplitude"], amps)
    # the linear poses are the model's linear solve, exactly proportional to the amplitude
    np.testing.assert_allclose(sweep["linear"], model.poses(amps[:, None] * f), rtol=1e-12)
    np.testing.assert_allclose(sweep["linear"], amps[:, None] * sweep["linear"][0] / amps[0])
    # the non-linear poses are the model's own non-linear solve (one load step below 1 N)
    nl, stats = solver.pose(amps[1] * f, steps=1)
    np.testing.assert_allclose(sweep["nonlinear"][1], nl, rtol=1e-10)
    assert sweep["iterations"][1] == sum(stats.iterations) >= 1
    assert np.all(sweep["factorisations"] >= 1)
    lin, nonlin = sweep["linear"], sweep["nonlinear"]
    np.testing.assert_allclose(sweep["rel_pct"], 100 * np.abs(nonlin - lin) / np.abs(nonlin))
    # the departure is of second order, so the relative error of the translations grows like
    # the load: exponent 1 between consecutive amplitudes (measured within 0.015 of 1; a
    # first-order departure would give 0, a third-order one 2)
    exponent = linearity.linear_range(amps, sweep["rel_pct"])["exponent"]
    np.testing.assert_allclose(exponent[:, :3], 1.0, atol=0.05)
    # the same sweep as cached FE experiments: identical poses and solver statistics, and a
    # second call with the cache solves nothing (its tasks are read)
    cases = np.r_[amps, 1.5]  # 1.5 N: two load steps, a group of its own
    direct = linearity.linearity_sweep(solver, f, cases)
    for cache in (None, tmp_path):
        runs = linearity.sweep_runs(ModelSpec(SMALL, element="q2", mesh_size=1.0), f, cases,
                                    cache_dir=cache)  # fmt: skip
        for key, value in direct.items():
            np.testing.assert_array_equal(runs[key], value, err_msg=key)
    assert len(list(tmp_path.glob("*.npy"))) == len(cases) + 1  # + the compliance's task

    def no_solve(*args: object) -> None:
        raise AssertionError("a cached sweep solved a case")

    monkeypatch.setattr(ex, "_task", no_solve)
    again = linearity.sweep_runs(ModelSpec(SMALL, element="q2", mesh_size=1.0), f, cases,
                                 cache_dir=tmp_path)  # fmt: skip
    np.testing.assert_array_equal(again["nonlinear"], direct["nonlinear"])
    with pytest.raises(ValueError, match="direction must have a non-zero component"):
        linearity.sweep_runs(SPEC, np.zeros(6), amps)
    with pytest.raises(ValueError, match="direction must have a non-zero component"):
        linearity.linearity_sweep(model, np.zeros(6), amps)
    with pytest.raises(ValueError, match=r"amplitudes must lie in \(0, 50\] N"):
        linearity.linearity_sweep(model, f, [0.0, 1.0])
    with pytest.raises(ValueError, match=r"amplitudes must lie in \(0, 50\] N"):
        linearity.linearity_sweep(model, f, [60.0])
    with pytest.raises(ValueError, match="steps must be"):
        linearity.linearity_sweep(model, f, amps, steps=0)


def test_crossing_labels_say_above_below_or_where() -> None:
    lin = {
        "crossing": np.array([np.inf, 0.1, 0.456]),
        "below_sweep": np.array([False, True, False]),
    }
    assert linearity.crossing_labels(lin, [0.1, 1.0, 3.0]) == ["> 3", "≤ 0.1", "0.46"]


def test_linear_range_refuses_bad_input_by_name() -> None:
    err = np.ones((2, 6))
    with pytest.raises(ValueError, match=r"amplitude \[N\] must list at least 2 strictly incr"):
        linearity.linear_range([1.0, 0.1], err)
    with pytest.raises(ValueError, match=r"amplitude \[N\] must list at least 2"):
        linearity.linear_range([1.0], err[:1])
    with pytest.raises(ValueError, match=r"amplitude \[N\] must be > 0"):
        linearity.linear_range([-0.1, 1.0], err)
    with pytest.raises(ValueError, match="rel_pct must be > 0"):
        linearity.linear_range([0.1, 1.0], np.zeros((2, 6)))
    with pytest.raises(ValueError, match="rel_pct must have shape"):
        linearity.linear_range([0.1, 0.3, 1.0], err)
    with pytest.raises(ValueError, match="level"):
        linearity.linear_range([0.1, 1.0], err, level=0.0)
