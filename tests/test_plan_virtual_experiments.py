"""The virtual-experiments chapter's record plan: the texts, glue and rows it makes from the
recorded values are those the notebook used to write by hand."""

from __future__ import annotations

import numpy as np
from pasting import planned  # tests/ is on sys.path (pytest prepend import mode)

from mechlib import published as pub
from mechlib import screening

R = list(pub.RESPONSES)


def test_the_new_dominant_factors_read_as_the_screening_lists_them() -> None:
    mask = np.zeros((6, 6), dtype=bool)
    mask[[0, 4], 2] = True  # z: T1D1 and T3D1
    mask[1, 5] = True  # θz: T1D2
    sets = screening.factor_sets(mask, list(pub.FACTORS))
    by_hand = "; ".join(f"{r}: {', '.join(sorted(s))}" for r, s in zip(R, sets, strict=True) if s)
    rec, pasted = planned("virtual_experiments")
    rec.value("nl_designs.table2_new_dominant", mask)
    assert pasted["new_dominant"] == by_hand == "z: T1D1, T3D1; θz: T1D2"
    assert rec.glued["new_dominant"] == {"text_of": "nl_designs.table2_new_dominant"}
    none, pasted = planned("virtual_experiments")
    none.value("nl_designs.table2_new_dominant", np.zeros((6, 6), dtype=bool))
    assert pasted["new_dominant"] == "none"


def test_the_sweep_glues_the_worst_components_exponents_and_the_first_amplitude_over() -> None:
    rel_pct = np.array([[0.1, 0.2, 0.3, 0.0, 0.0, 0.1], [0.5, 2.0, 1.5, 0.1, 0.1, 0.4]])
    exponent = np.array([[1.0, 1.9, 1.2, 2.1, 0.8, 1.0], [1.1, 2.4, 1.3, 1.5, 1.0, 1.2]])
    rec, pasted = planned("virtual_experiments")
    rec.value("sweep.rel_pct", rel_pct)
    rec.value("sweep.over_1pct", [False, True], context={"amplitudes": np.array([0.5, 1.0])})
    rec.value("sweep.exponent", exponent, context={"rel_pct": rel_pct})
    assert pasted["p_component"] == "y"  # the largest error at the largest amplitude
    assert pasted["first_over"] == "1 N"
    # indices as the hand-written glue stored them (the last row by its positive index)
    assert rec.glued["p_first"] == {"key": "sweep.exponent", "index": [0, 1]}
    assert rec.glued["p_last"] == {"key": "sweep.exponent", "index": [1, 1]}
    assert rec.glued["p_lo"]["index"] == [0, 4] and rec.glued["p_hi"]["index"] == [1, 1]
    assert rec.glued["p0_max"]["index"] == [0, 3]
    assert pasted["p0_component"] == "θx"
    never, pasted = planned("virtual_experiments")
    never.value("sweep.over_1pct", [False, False], context={"amplitudes": np.array([0.5, 3.0])})
    assert pasted["first_over"] == "none up to 3 N"


def test_the_mesh_of_the_nonlinear_runs_is_named_by_the_parameter() -> None:
    lean, pasted = planned("virtual_experiments")
    lean.value("model.nonlinear_n_dofs", 1234, context={"mesh": "lean", "fit_tol": 1e-4})
    assert "lean mesh of the family page (1234 free DOFs)" in pasted["nl_mesh_text"]
    assert "within 0.01 %" in pasted["nl_mesh_text"]
    own, pasted = planned("virtual_experiments")
    own.value("model.nonlinear_n_dofs", 1234, context={"mesh": "default", "fit_tol": 1e-4})
    assert pasted["nl_mesh_text"] == "this chapter's model itself, on the same mesh"


def test_eq6_is_better_where_its_error_is_below_s_ts() -> None:
    scores = np.array(
        [[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], [0, 0, 0, 0, 0, 0], [2.0, 1.0, 3.0, 1, 9, 1]]
    )
    rec, pasted = planned("virtual_experiments")
    rec.value("nl_designs.validation_max_range_pct", scores)
    assert pasted["eq6_better"] == "y, θx, θz"
    assert pasted["eq6_worse"] == "x, z, θy"
    assert rec.glued["eq6_nl_worst"]["index"] == [2, 4]
    assert rec.glued["st_nl_worst"]["index"] == [0, 5]


def test_the_table5_row_quotes_both_settings_largest_errors() -> None:
    rec, _ = planned("virtual_experiments")
    both = np.array([[1e-9, 2e-9, 0, 0, 0, 3e-9], [1.0, 2.5, 0.1, 0.2, 0.3, 0.4]])
    rec.value(
        "table5.max_rel_pct_linear_and_nonlinear",
        both,
        context={"runs": (1000, 998), "over": np.array([0.5, 1.25]), "tilt": 12.0},
    )
    row = rec.report[-1]
    assert "(1000 and 998 runs)" in row["quantity"]
    assert "linear FE ≤ 3.0e-09 %" in row["cause"]
    assert "misses by 0.5 to 1.25 % of full scale" in row["cause"]
    assert "up to 2.5 %" in row["cause"] and "up to 12 mrad" in row["cause"]


def test_lenths_margin_takes_its_floor_from_the_effects() -> None:
    rec, _ = planned("virtual_experiments")
    eff = np.array([[3.0, -0.5], [1e-12, 2.0]])
    rec.value("table3.me", [0.1, 0.2], context={"eff": eff})
    assert rec.values["table3.me"]["atol"] == 1e-6 * np.abs(eff).max()
    assert rec.values["table3.me"]["rtol"] == 1e-6
