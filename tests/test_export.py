"""The real-time model's export: exact coefficients, check values, and the plain-Python evaluator
computing what the library computes."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

from mechlib.metamodels import evaluator, export, realtime
from mechlib.metamodels.families import Surrogate, predict_array
from mechlib.metamodels.pce import total_degree_exponents
from mechlib.reporting.jsonready import plain_tree


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


def test_the_bundles_model_holds_the_validation_the_page_wrote_by_hand() -> None:
    model = _model(degree=3, amplitude=0.5)
    rng = np.random.default_rng(7)
    poses, worst, compliance = rng.normal(size=(20, 6)), rng.random(6), rng.normal(size=(6, 6))
    names = ("T1D1", "T1D2", "T2D1", "T2D2", "T3D1", "T3D2")
    outputs, units = ("x", "y", "z", "θx", "θy", "θz"), ("µm",) * 3 + ("µrad",) * 3
    by_hand = export.to_dict(  # the validation as the meta-model page wrote it
        model,
        names,
        outputs,
        units,
        validation={
            "heldout_runs": 20,
            "force_range_n": model.amplitude,
            "worst_pct": worst,
            "worst_pct_max": float(worst.max()),
            "range": np.abs(poses).max(axis=0),
            "range_means": "each component's largest |value| over the held-out runs",
            "teacher": "Gaussian process",
            "degree": 3,
            "full_runs": 64,
            "S_T": compliance,
            "S_T_means": "the linear compliance of the same FE model [µm/N, µrad/N], rows x y z "
            "θx θy θz, columns the forces",
        },
        seed=5,
    )
    made = export.realtime_model(
        model,
        names,
        outputs,
        units,
        worst_pct=worst,
        poses=poses,
        teacher="Gaussian process",
        full_runs=64,
        compliance=compliance,
        seed=5,
    )
    assert json.dumps(plain_tree(made)) == json.dumps(plain_tree(by_hand))  # key order too
    with pytest.raises(ValueError, match=r"worst_pct must have 6 entries .* \(5,\) and \(20, 6\)"):
        export.realtime_model(
            model, names, outputs, units, worst_pct=worst[:5], poses=poses, teacher="",
            full_runs=1, compliance=compliance,
        )  # fmt: skip


@pytest.mark.parametrize("fitted", [["linear", "cubic"], []])
def test_learning_curves_make_the_table_the_page_built_by_hand(fitted: list[str]) -> None:
    runs = [16, 32, 64]
    worst = np.random.default_rng(2).random((len(fitted), 3))
    if fitted:
        worst[1, 0] = np.nan  # too few runs for the cubic family at 16
    by_hand = pd.DataFrame(worst.T, columns=[f"{f} [% of full scale]" for f in fitted])
    by_hand.insert(0, "training runs", runs)
    table = export.curves_table(runs, worst, fitted)
    assert _csv(table) == _csv(by_hand)
    assert list(table.columns) == ["training runs", *(f"{f} [% of full scale]" for f in fitted)]
    with pytest.raises(ValueError, match=r"worst_pct must be \(2, 3\).* got shape \(2, 2\)"):
        export.curves_table(runs, np.zeros((2, 2)), ["linear", "cubic"])


def test_the_realtime_curves_make_the_table_the_page_built_by_hand() -> None:
    runs, (gp, corrected, indicator) = [16, 32], np.random.default_rng(4).random((3, 2))
    by_hand = pd.DataFrame(
        {
            "full runs": runs,
            "Gaussian process [% of full scale]": gp,
            "reduced-order model + correction of the forces [% of full scale]": corrected,
            "reduced-order model + error model on its indicators [% of full scale]": indicator,
        }
    )
    assert _csv(export.realtime_curves(runs, gp, corrected, indicator)) == _csv(by_hand)


def _csv(table: pd.DataFrame) -> str:
    return table.to_csv(index=False, lineterminator="\n")  # as the data bundle writes it
