"""The transcription of the thesis's printed values parses as printed."""

import numpy as np
import pytest

from mechlib import published as pub


def test_shapes_of_the_printed_tables() -> None:
    assert pub.TABLE2.shape == (12, 12)
    assert pub.TABLE3_EFFECTS.shape == (6, 6) and pub.TABLE3_SUMMARY.shape == (4, 6)
    assert pub.TABLE4.shape == (30, 12)
    assert pub.EQ8_ST.shape == (6, 6) and pub.TABLE5.shape == (6, 3)
    assert len(pub.TABLE7_NOMINAL) == 12


def test_decimal_commas_and_exponents() -> None:
    assert pub.parse_printed("0,6 -4,01E-04\n1 2").tolist() == [[0.6, -4.01e-4], [1.0, 2.0]]
    np.testing.assert_allclose(pub.printed_resolution("0,17 575314 4,01E-04"), [[0.005, 0.5, 5e-7]])


def test_spot_values_as_printed() -> None:
    assert pub.TABLE2[0, 6] == 115056 and pub.TABLE2[1, 7] == 99636.5
    assert pub.TABLE4[29, 9] == -47356.81
    assert pub.EQ8_ST[3, 1] == 39313.03 and pub.EQ8_ST[5, 0] == -3101.84
    assert pub.TABLE5[4, 1] == pytest.approx(0.621)
    assert pub.TABLE7_REAL["gamma2"] == 3.1418 and pub.TABLE7_NOMINAL["k2"] == -1.0


def test_ragged_or_non_numeric_blocks_are_refused() -> None:
    with pytest.raises(ValueError, match="equal length"):
        pub.parse_printed("1 2\n3")
    with pytest.raises(ValueError, match="not a number"):
        pub.parse_printed("1 x")


def test_printed_designs_use_the_table1_levels() -> None:
    for design in (pub.TABLE2_DESIGN, pub.TABLE4_DESIGN):
        assert design.min() == pub.TABLE1_LOW_N and design.max() == pub.TABLE1_HIGH_N
    assert np.all(np.isin(pub.TABLE2_DESIGN, (-1, 1)))


def test_the_claimed_main_factors_are_the_non_zero_pattern_of_eq8() -> None:
    """Sec. 2.6.2's items 1–4 name, per response, exactly the factors with a non-zero Eq 8
    entry: the transcription agrees with the thesis's own matrix."""
    assert len(pub.SEC262_MAIN_FACTORS) == len(pub.RESPONSES)
    for row, claimed in zip(pub.EQ8_ST, pub.SEC262_MAIN_FACTORS, strict=True):
        assert claimed == {f for f, c in zip(pub.FACTORS, row, strict=True) if c != 0}


def test_one_spelling_of_the_response_labels_and_units() -> None:
    from mechlib.fe import pose

    # one spelling: the pose module keeps no labels of its own
    assert not hasattr(pose, "POSE_LABELS") and not hasattr(pose, "POSE_UNITS")


def test_table2_is_converted_to_the_units_of_its_header() -> None:
    # e.g. x printed 57529 (nm) is 57.529 µm; θz printed 3.10183 (mrad) is 3101.83 µrad
    converted = pub.table2_responses_um_urad()
    assert converted.shape == (12, 6)
    np.testing.assert_allclose(converted * pub.TABLE2_PRINTED_PER_HEADER_UNIT, pub.TABLE2_RESPONSES)
    np.testing.assert_allclose(converted[:, :3], pub.TABLE2_RESPONSES[:, :3] / 1e3)
    np.testing.assert_allclose(converted[:, 3:], pub.TABLE2_RESPONSES[:, 3:] * 1e3)
