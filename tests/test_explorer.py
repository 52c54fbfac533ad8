"""The explorer page's build: an exact model literal, a page whose numbers come from the record,
a drawing that moves as a rigid plate, and the browser check's comparisons (no browser here)."""

from __future__ import annotations

import json
import math
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from mechlib import published as pub
from mechlib.metamodels import evaluator, export, realtime
from mechlib.metamodels.families import Surrogate
from mechlib.metamodels.pce import total_degree_exponents
from mechlib.pipeline import pagecheck
from mechlib.pipeline.book import claimcheck, explorer, explorercheck, explorerdraw, explorerpage

OUTPUTS = ["x", "y", "z", "θx", "θy", "θz"]
UNITS = ["µm"] * 3 + ["µrad"] * 3


def _model(degree: int = 3, seed: int = 3) -> dict[str, Any]:
    """An exported model, through JSON text as recorded: S_T of Eq 8 plus small terms."""
    exps = total_degree_exponents(6, degree)
    coef = np.random.default_rng(seed).normal(scale=2.0, size=(len(exps), 6))
    coef[1:7] = pub.EQ8_ST.T / math.sqrt(3)  # the degree-1 terms: √3 u_i, u_i = f_i / 1 N
    model = Surrogate(realtime.DISTILLED, 1.0, 6, 6, {"exponents": exps, "coef": coef})
    validation = {
        "worst_pct": [0.05, 0.04, 0.03, 0.08, 0.06, 0.07],
        "worst_pct_max": 0.08,
        "heldout_runs": 1000,
        "range": [120.0, 110.0, 900.0, 80000.0, 70000.0, 9500.0],
        "S_T": pub.EQ8_ST.tolist(),
        "teacher": "Gaussian process",
        "degree": degree,
    }
    data = export.to_dict(model, list(pub.FACTORS), OUTPUTS, UNITS, validation)
    return json.loads(json.dumps(data))


def _record(folder: Path, model: dict[str, Any]) -> Path:
    path = explorer.model_path(folder)
    path.parent.mkdir(parents=True)
    path.write_text(json.dumps(model, ensure_ascii=False))
    return folder


def test_doubles_and_exponents_pack_exactly() -> None:
    values = np.array([0.1, -0.0, 5e-324, 1.7976931348623157e308, -1 / 3, 2.0**-1074 * 3])
    assert np.array_equal(explorer.unpack_doubles(explorer.pack_doubles(values)), values)
    assert np.signbit(explorer.unpack_doubles(explorer.pack_doubles(values))[1])
    exps = total_degree_exponents(6, 5).tolist()
    assert explorer.unpack_exponents(explorer.pack_exponents(exps), 6) == exps


def test_the_literal_carries_the_recorded_model_bit_for_bit() -> None:
    model = _model(degree=4)
    data = explorer.read_script(explorer.script_text(explorer.literal(model)))
    back = explorer.model_of(data)
    assert back["exponents"] == model["exponents"]
    assert np.array_equal(back["coef"], model["coef"])  # every double
    assert explorercheck.record_problems(data, model) == []
    # the page evaluates the same polynomial: the model's own check poses, exactly
    for forces, pose in zip(model["check"]["forces_n"], model["check"]["poses"], strict=True):
        assert np.allclose(evaluator.pose(back, forces), pose, rtol=0, atol=1e-9)
    changed = json.loads(json.dumps(model))
    changed["coef"][5][2] = math.nextafter(changed["coef"][5][2], math.inf)
    assert explorercheck.record_problems(data, changed) == [
        "the page's coefficients differ from the record's"
    ]


def test_a_literal_is_a_classic_script_safe_inside_a_script_element() -> None:
    model = _model(degree=2)
    model["outputs"][0] = "x</script>"
    text = explorer.script_text(explorer.literal(model))
    assert text.startswith("window.MECHLIB_EXPLORER = {") and text.endswith("};\n")
    assert "</script>" not in text
    assert explorer.read_script(f"<p>page</p><script>{text}</script>")["outputs"][0] == "x</script>"


def test_the_page_is_written_from_the_record_and_reads_as_book_text(tmp_path: Path) -> None:
    model = _model()
    book = tmp_path / "book"
    assert explorer.write_explorer(_record(tmp_path / "records", model), book, "\nmade\n") == []
    page, script, widget, figure = explorer.outputs(book)
    text = page.read_text()
    assert text.endswith("\nmade\n") and f":file: {explorer.WIDGET_FILE}" in text
    assert f"```{{figure}} {explorer.FIGURE_FILE}\n:name: explorer-preset" in text
    assert "fitted to the Gaussian process" in text and "at most 0.08 %" in text
    assert "1000 held-out" in text and "degree 3 (84 terms" in text
    assert pagecheck.markdown_problems(text, "explorer.md") == []
    assert not claimcheck.VERDICT_WORD.search(text + widget.read_text())
    # the preset's pose in the table is the model's, shown to the component's decimals
    forces, pose, linear = explorer.preset(model)
    places = explorer.decimals(model["validation"]["range"])
    assert f"  - {explorerpage._fmt(pose[2], places[2])}\n" in text
    assert explorer.read_script(widget.read_text()) == explorer.read_script(script.read_text())
    for i, name in enumerate(pub.FACTORS):
        assert f'<label for="mx-f{i}">{name}</label><input type="range" id="mx-f{i}"' in (
            widget.read_text()
        )
    assert ET.fromstring(figure.read_text()).tag.endswith("svg")
    assert np.allclose(linear, pub.EQ8_ST @ forces)


def test_a_missing_or_broken_record_names_the_file_and_leaves_no_stale_page(
    tmp_path: Path,
) -> None:
    book = tmp_path / "book"
    records = _record(tmp_path / "records", _model())
    assert explorer.write_explorer(records, book) == []
    explorer.model_path(records).unlink()
    problems = explorer.write_explorer(records, book)
    assert len(problems) == 1 and str(explorer.model_path(records)) in problems[0]
    assert not any(p.exists() for p in explorer.outputs(book))
    broken = _model()
    del broken["validation"]["S_T"]
    explorer.model_path(records).write_text(json.dumps(broken))
    assert "missing ['S_T']" in explorer.write_explorer(records, book)[0]
    broken = _model()
    broken["check"]["poses"][0][1] += 1.0
    explorer.model_path(records).write_text(json.dumps(broken))
    assert "misses its check pose" in explorer.write_explorer(records, book)[0]


def test_check_model_names_what_is_wrong() -> None:
    model = _model(degree=2)
    with pytest.raises(ValueError, match="format must be"):
        explorer.check_model({**model, "format": "other"})
    exps = [[10, 0, 0, 0, 0, 0], *model["exponents"][1:]]
    with pytest.raises(ValueError, match=r"integers in 0 \.\. 9 .*range 0 \.\. 10"):
        explorer.check_model({**model, "exponents": exps})
    with pytest.raises(ValueError, match="finite and > 0"):
        explorer.check_model({**model, "validation": {**model["validation"], "range": [0.0] * 6}})


def test_the_drawing_moves_the_outline_as_a_rigid_plate() -> None:
    shape = explorerdraw.outline()
    assert shape.shape == (12, 2)
    turn = np.array([[-0.5, -math.sqrt(3) / 2], [math.sqrt(3) / 2, -0.5]])  # 120°
    assert np.allclose(
        np.sort_complex((shape @ turn.T) @ [1, 1j]), np.sort_complex(shape @ [1, 1j])
    )
    p = np.array([[10.0, 0.0], [0.0, 20.0]])
    moved = explorerdraw.displaced(p, [1000.0, 0, 500.0, 0, 0, 0], 1.0)  # 1 mm in x, 0.5 in z
    assert np.allclose(moved, [[11, 0, 0.5], [1, 20, 0.5]])
    moved = explorerdraw.displaced(p, [0, 0, 0, 0, 0, 1000.0], 2.0)  # θz = 1 mrad, ×2
    assert np.allclose(moved[:, :2], [[10, 0.02], [-0.04, 20]])
    moved = explorerdraw.displaced(p, [0, 0, 0, 1000.0, 1000.0, 0], 1.0)  # θx, θy tilt z only
    assert np.allclose(moved[:, 2], [-0.01, 0.02])


def test_magnifications_are_round_and_keep_the_drawing_in_its_view() -> None:
    floors = [explorerdraw.nice_floor(v) for v in (1.0, 1.9, 2.0, 4.99, 7.0, 0.03)]
    assert floors == [1, 1, 2, 2, 5, 0.02]
    with pytest.raises(ValueError, match="value must be a finite number > 0, got 0"):
        explorerdraw.nice_floor(0.0)
    ranges = [120.0, 110.0, 900.0, 80000.0, 70000.0, 9500.0]
    mags = explorerdraw.magnifications(ranges, 50.0)
    in_plane = 0.12 + 9500e-6 * 50
    out_of_plane = 0.9 + math.hypot(0.08, 0.07) * 50
    for key, extent in (("in_plane", in_plane), ("out_of_plane", out_of_plane)):
        assert mags[key] * extent <= explorerdraw.VIEW_SHARE * 50
        assert 2.5 * mags[key] * extent > explorerdraw.VIEW_SHARE * 50  # the next 1–2–5 step
    _, dirs = explorerdraw.actuators()
    assert explorerdraw.shown_forces(dirs, 1) == [0, 2, 4]  # D1 in the top view
    assert explorerdraw.shown_forces(dirs, 2) == [1, 3, 5]  # D2 in the side views


def _jacobian(model: dict[str, Any], forces: np.ndarray) -> np.ndarray:
    """d pose / d forces (outputs, inputs) of an exported model, from NumPy's legder."""
    exps, coef = np.asarray(model["exponents"]), np.asarray(model["coef"])
    u = np.asarray(forces) / model["amplitude_n"]
    deg = int(exps.max())
    norm = np.sqrt(2 * np.arange(deg + 1) + 1)
    eye = np.eye(deg + 1)
    vals = np.array([[np.polynomial.legendre.legval(x, eye[k]) for k in range(deg + 1)] for x in u])
    ders = np.array(
        [
            [
                np.polynomial.legendre.legval(x, np.polynomial.legendre.legder(eye[k]))
                for k in range(deg + 1)
            ]
            for x in u
        ]
    )
    vals, ders = vals * norm, ders * norm / model["amplitude_n"]
    jac = np.zeros((coef.shape[1], len(u)))
    for e, c in zip(exps, coef, strict=True):
        for i in range(len(u)):
            factors = [ders[j, k] if j == i else vals[j, k] for j, k in enumerate(e)]
            jac[:, i] += np.prod(factors) * c
    return jac


def test_the_browser_checks_comparison_finds_a_wrong_pose_and_a_missed_target() -> None:
    model = _model()
    data = explorer.literal(model)
    forces, target_forces = explorercheck.samples(1.0, 6)
    assert forces.shape == (1024, 6) and np.abs(forces).max() <= 1.0
    assert target_forces.shape == (16, 6) and np.abs(target_forces).max() <= 0.9
    forces, target_forces = forces[:32], target_forces[:4]
    back = explorer.model_of(data)
    jacobians = [  # the polynomial's exact derivative (NumPy's Legendre derivative)
        _jacobian(back, f) for f in forces[: explorercheck.N_JACOBIANS]
    ]
    result = {
        "poses": [evaluator.pose(back, f) for f in forces.tolist()],
        "jacobians": [j.tolist() for j in jacobians],
        "inverse": [
            {"forces": f, "converged": True, "iterations": 3} for f in target_forces.tolist()
        ],
        "us_per_pose": 5.0,
        "timed_poses": 1000,
        "errors": [],
        "bad_input": "x [µm] must be a number within ±240.0 µm, got 'abc'",
    }
    measured, problems = explorercheck.compare(data, result, forces, target_forces)
    assert problems == [] and measured["max_rel_diff_vs_plain_python"] == 0.0
    assert measured["max_rel_diff_vs_numpy"] < 1e-13
    result["poses"][7][3] += 1e-6 * data["range"][3]
    result["inverse"][1]["forces"][0] += 1e-6
    result["bad_input"] = ""
    result["jacobians"][0][2][1] *= 1.001
    _, problems = explorercheck.compare(data, result, forces, target_forces)
    assert "differ from the plain-Python evaluation by 1e-06 of a range (θx)" in problems[0]
    assert any(p.startswith("round trip misses") for p in problems)
    assert any("forces are off by 1e-06 N" in p for p in problems)
    assert any("gave no clear error" in p for p in problems)
    assert any(p.startswith("the page's Jacobian differs") for p in problems)


def test_the_built_pages_dom_shows_whether_its_script_ran() -> None:
    ran = (
        '<html class="mx-on"><body><td id="mx-nl-0">1.00</td>'
        '<p id="mx-timing" class="mx-timing">Measured in your browser: 5 µs</p>'
    )
    assert explorercheck.page_problems(ran) == []
    assert len(explorercheck.page_problems("<html><body></body></html>")) == 3
