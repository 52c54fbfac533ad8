"""Reader tables: digits, zeros below a precision, units in headers, the thesis beside ours."""

from __future__ import annotations

import numpy as np
import pytest

from mechlib import published as pub
from mechlib.reporting import tables


@pytest.mark.parametrize(
    ("value", "kwargs", "text"),
    [
        (57.5312, {}, "57.53"),
        (-28.76, {}, "−28.76"),
        (39313.03, {}, "39313"),
        (39313.03, {"digits": 7}, "39313.03"),
        (1.19e-8, {}, "1.19e−08"),
        (-2.86e-8, {"zero_below": 1e-6}, "0"),
        (0.000123456, {}, "0.0001235"),
    ],
)
def test_number_gives_significant_digits_and_zero_below_a_precision(value, kwargs, text) -> None:
    assert tables.number(value, **kwargs) == text


def test_labels_carry_units_and_refuse_a_length_mismatch() -> None:
    assert tables.labels(["x", "k1"], ["µm", ""]) == ["x [µm]", "k1"]
    assert tables.labels(["a", "b"], "N") == ["a [N]", "b [N]"]
    with pytest.raises(ValueError, match="2 names need as many units"):
        tables.labels(["a", "b"], ["N"])


def test_round_off_of_exact_zeros_is_shown_as_zero_per_column() -> None:
    values = np.array([[100.0, 1e-9], [3e-5, 2.0]])
    cells = tables.formatted(values, rel_zero=1e-6)  # 3e-5 is below 1e-6 × 100 in its column
    assert cells.tolist() == [["100", "0"], ["0", "2"]]
    by_column = tables.formatted(values, rel_zero=1e-7)
    assert by_column.tolist() == [["100", "0"], ["3e−05", "2"]]
    whole = tables.formatted(values, rel_zero=1e-8, axis=None)  # floor 1e-6 for every entry
    assert whole[1, 0] == "3e−05" and whole[0, 1] == "0"
    absolute = tables.formatted(values, zero_below=np.array([0.0, 1e-3]))
    assert absolute[0, 1] == "0" and absolute[1, 0] == "3e−05"


def test_side_by_side_pairs_each_quantity_with_both_sources() -> None:
    frame = tables.side_by_side(
        {tables.THESIS: pub.EQ8_ST, tables.OURS: pub.EQ8_ST * 1.001 + 1e-12},
        list(pub.RESPONSES),
        tables.labels(pub.RESPONSES, pub.RESPONSE_UNITS),
        rel_zero={tables.OURS: 1e-6},
        lead=tables.table(np.ones((6, 1)), list(pub.RESPONSES), ["force [N]"]),
    )
    assert list(frame.columns[:3]) == [("force [N]", ""), ("x [µm]", "thesis"), ("x [µm]", "ours")]
    assert frame.loc["x", ("x [µm]", "thesis")] == "57.53"
    assert frame.loc["x", ("y [µm]", "ours")] == "0"  # 1e-12 is round-off of an exact 0
    with pytest.raises(ValueError, match="shape"):
        tables.side_by_side({"a": np.ones((2, 2))}, ["r"], ["c"])


def test_stacked_matrices_and_printed_text_tables() -> None:
    frame = tables.stacked({"Eq 8": pub.EQ8_ST, "ours": pub.EQ8_ST}, pub.RESPONSES, pub.FACTORS)
    assert frame.shape == (12, 6) and frame.index[6] == ("ours", "x")
    t8 = tables.printed_vs_ours(
        pub.TABLE8_ROWS, pub.TABLE8_PRINTED, {k: ("a", "b", "c") for k in pub.TABLE8_PRINTED}
    )
    assert t8.loc["Measurement cost", ("traditional", "thesis")] == "2 · 18 · 2 = 72"
    with pytest.raises(ValueError, match="same columns"):
        tables.printed_vs_ours(["r"], {"a": ["x"]}, {"b": ["y"]})


def test_latex_matrix_equation_shows_printed_values_and_the_tag() -> None:
    tex = tables.latex_matrix_equation("S_T", pub.EQ8_ST, tag="8")
    assert tex.startswith(r"S_T = \begin{bmatrix} 57.53 & 0 & 28.76")
    assert "39313.03" in tex and "-19633.3" in tex and tex.endswith(r"\tag{8}")
    assert "\\\\" not in tex  # rows end with \cr: no split environment around a tag
