"""The real-time model's export: exact coefficients, check values, and the plain-Python evaluator
computing what the library computes."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from mechlib.metamodels import evaluator, export, realtime
from mechlib.metamodels.families import Surrogate, predict_array, total_degree_exponents


def _model(degree: int = 4, amplitude: float = 1.0) -> Surrogate:
    exps = total_degree_exponents(6, degree)
    coef = np.random.default_rng(3).normal(scale=50.0, size=(len(exps), 6))
    return Surrogate(realtime.DISTILLED, amplitude, 6, 6, {"exponents": exps, "coef": coef})


def _export(model: Surrogate) -> dict:
    names = ["a", "b", "c", "d", "e", "f"]
    data = export.to_dict(model, names, names, ["µm"] * 6, {"worst_pct": 0.1}, seed=5)
    return json.loads(json.dumps(data))  # through JSON text, as shipped


@pytest.mark.parametrize("amplitude", [1.0, 0.5])
def test_exported_model_round_trips_exactly_and_the_evaluator_agrees(amplitude) -> None:
    model = _model(amplitude=amplitude)
    data = _export(model)
    back = export.from_dict(data)
    assert np.array_equal(back.state["coef"], model.state["coef"])  # every double kept
    assert np.array_equal(back.state["exponents"], model.state["exponents"])
    forces = np.array(data["check"]["forces_n"])
    assert np.abs(forces).max() <= amplitude and len(forces) == export.CHECK_VECTORS
    assert np.array_equal(predict_array(back, forces), np.array(data["check"]["poses"]))
    scale = np.abs(data["check"]["poses"]).max(axis=0)
    for f, p in zip(forces, data["check"]["poses"], strict=True):
        # another summation order than the library's matrix product: round-off only
        assert np.all(np.abs(np.array(evaluator.pose(data, list(f))) - p) <= 1e-13 * scale)


def test_evaluator_runs_as_a_script(tmp_path) -> None:
    path = tmp_path / "realtime_model.json"
    path.write_text(json.dumps(_export(_model(degree=3))))
    out = subprocess.run(
        [sys.executable, evaluator.__file__, str(path)], capture_output=True, text=True, check=True
    )
    assert float(out.stdout) < 1e-9  # the largest difference over the check values


def test_evaluator_refuses_a_force_beyond_the_validated_range() -> None:
    data = _export(_model(degree=2, amplitude=0.5))
    with pytest.raises(ValueError, match=r"force c must be within ±0.5 N, got 0.7"):
        evaluator.pose(data, [0.0, 0.1, 0.7, 0.0, 0.0, 0.0])


def test_export_refuses_other_models_and_wrong_names() -> None:
    model = _model(degree=2)
    with pytest.raises(ValueError, match="outputs must name 6"):
        export.to_dict(model, list("abcdef"), list("xyz"), ["µm"] * 6, {})
    other = Surrogate("linear", 1.0, 6, 6, {"S": np.eye(6)})
    with pytest.raises(ValueError, match="'distilled' polynomial"):
        export.to_dict(other, list("abcdef"), list("abcdef"), ["µm"] * 6, {})
    with pytest.raises(ValueError, match="format must be"):
        export.from_dict({"format": "other"})
