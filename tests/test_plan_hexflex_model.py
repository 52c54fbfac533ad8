"""The HexFlex model chapter's record plan: its named tolerances follow the model checks'
thresholds and the relative tolerances its percentages are made of."""

from __future__ import annotations

from mechlib.hexflex import checks
from mechlib.reporting import plans
from mechlib.reporting.tolerances import (
    FE_DEFECT,
    FE_IDENTIFIED,
    FE_IDENTIFIED_DIFF_PCT,
    FE_IDENTIFIED_PCT,
    FE_OVER_THEORY,
    FE_OVER_THEORY_PCT,
    FE_RECIPROCITY,
)


def test_the_defects_are_held_to_the_model_checks_thresholds() -> None:
    assert FE_DEFECT.atol == checks.SYMMETRY_TOL == checks.ZERO_PATTERN_TOL
    assert FE_DEFECT.atol == checks.ROUNDTRIP_TOL
    assert FE_RECIPROCITY.atol == checks.RECIPROCITY_TOL


def test_a_percentage_is_held_to_its_ratios_tolerance_in_points() -> None:
    assert FE_IDENTIFIED_PCT.atol == 100 * FE_IDENTIFIED.rtol
    assert FE_IDENTIFIED_DIFF_PCT.atol == 2 * FE_IDENTIFIED_PCT.atol
    assert FE_OVER_THEORY_PCT.atol == 100 * FE_OVER_THEORY.rtol


def test_the_fit_rows_say_whether_the_geometry_was_identified() -> None:
    entry = plans.load("hexflex_model")["fit.achieved"]
    identified = entry.rows({"fit_tol": 0.001, "n_fe": 4})
    given = entry.rows({"fit_tol": 0.001, "n_fe": 0})
    assert len(identified) == len(given) == 4
    assert "met after 4 FE models" in identified[0].tolerance
    assert given[0].tolerance == "1 % (the given geometry, not identified)"
