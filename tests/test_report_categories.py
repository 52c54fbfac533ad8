"""Verdict categories of report rows: set from the numbers and the declared basis and source."""

from __future__ import annotations

import numpy as np
import pytest

from mechlib.reporting import categories as cat
from mechlib.reporting import report, verdicts
from mechlib.reporting.records import Recorder


def test_independent_agreement_is_reproduced_and_divergence_diverges() -> None:
    row = report.compare_row("Table 3", "q", [1.0, 2.0], [1.004, 2.0], resolution=0.005)
    assert row["category"] == cat.CAT_REPRODUCED and row["basis"] == "independent"
    assert (row["n_values"], row["n_agree"]) == (2, 2)
    row = report.compare_row("Table 3", "q", [1.0, 2.0], [1.0, 3.0], rtol=0.01, cause="why")
    assert row["category"] == cat.CAT_DIVERGES and row["cause"] == "why"
    assert (row["n_values"], row["n_agree"]) == (2, 1)


def test_construction_is_not_counted_as_reproduction_unless_it_fails() -> None:
    row = report.compare_row("Eq 8", "fitted", [57.53], [57.53], basis="construction")
    assert row["category"] == cat.CAT_CONSTRUCTION
    assert row["verdict"] == report.REPRODUCED  # today's report page keeps its verdict
    failed = report.compare_row(
        "Eq 8", "fitted", [57.53], [70.0], basis="construction", cause="the fit failed"
    )
    assert failed["category"] == cat.CAT_DIVERGES


def test_thesis_inconsistency_and_our_hypothesis() -> None:
    row = report.compare_row(
        "Table 3", "ν", [19.63, 3.1], [28763.8, 3.1], resolution=0.005, cause="copy error",
        basis="thesis-inconsistency",
    )  # fmt: skip
    assert row["category"] == cat.CAT_INCONSISTENT and row["n_agree"] == 1
    ours = report.compare_row("Table 3", "m = 7", [110.73], [110.85], rtol=0.002, source="ours")
    assert ours["category"] == cat.CAT_OURS


def test_published_values_that_agree_are_consistent_inside_the_thesis_not_reproduced() -> None:
    # Table 4's unit ratio against Eq 8: two published values, no computation of ours
    row = report.compare_row(
        "Table 4", "unit ratio", [1.0, 1.0], [1.002, 0.999], rtol=0.01, cause="units",
        basis="thesis-inconsistency",
    )  # fmt: skip
    assert row["category"] == cat.CAT_CONSISTENT_THESIS != cat.CAT_REPRODUCED


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [({"basis": "fitted"}, "basis must be one of"), ({"source": "me"}, "source must be one of")],
)
def test_unknown_basis_or_source_is_refused(kwargs: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        report.compare_row("T", "q", [1.0], [1.0], **kwargs)


def test_difference_is_relative_to_the_largest_published_value() -> None:
    # the old column printed the largest relative difference of any entry: 1e+02 % here
    row = report.compare_row(
        "Table 2", "responses", [1000.0, 0.001], [1010.0, 0.002], rtol=0.05, atol=0.01
    )
    assert row["max_rel_diff"] == pytest.approx(1.0)
    assert row["difference"] == pytest.approx(0.01)
    assert row["difference_text"] == "1 % of max |published|"
    assert row["tolerance_used"] == pytest.approx(10.0 / 50.01, rel=1e-6)
    big = report.compare_row("Table 5", "err", [0.5, 0.1], [1000.0, 3.0], cause="non-linear")
    assert big["difference_text"] == "3 orders of magnitude (× 2e+03)"
    printed = report.compare_row("Table 3", "q", [0.17], [0.166667], resolution=0.005)
    assert (
        printed["difference_text"]
        == "1.96 % of max |published|; 0.667 × half the last printed digit"
    )
    zero = report.compare_row("Table 3", "q", [0.0], [1e-12], atol=1e-9)
    assert zero["difference"] is None and "published values all 0" in zero["difference_text"]


def test_difference_text_refuses_negative_input() -> None:
    with pytest.raises(ValueError, match="must be >= 0"):
        cat.difference_text(-1.0, 1.0)


def test_difference_text_says_round_off_and_orders_of_magnitude_not_huge_ratios() -> None:
    assert cat.difference_text(2e-18, 0.0279, 4.37) == "round-off (2e-18)"
    assert cat.difference_text(1.68e4 * 19, 19, 3.71e6) == "4 orders of magnitude (× 1.7e+04)"
    # a factor printed as 1e+03 is 3 orders, even when it lies just below 1000
    assert cat.difference_text(999.7, 1.0) == "3 orders of magnitude (× 1e+03)"
    assert cat.difference_text(16.8, 1.0) == "16.8 × max |published|"
    assert (
        cat.difference_text(0.3, 1.0, 2.0)
        == "30 % of max |published|; 2 × half the last printed digit"
    )


def test_long_arrays_are_summarised_not_truncated_lists() -> None:
    design = np.tile([1.0, -1.0, 1.0], (12, 2))
    text = cat.summarise(design)
    assert text == "72 values (12 × 6) from -1 to 1, max |x| = 1"
    assert cat.summarise(np.array([1.5, -2.0])) == "1.5, -2"
    assert "…" not in report.compare_row("T", "q", design, design)["ours"]


def test_a_check_is_consistent_by_construction_or_inside_the_thesis_never_a_claim() -> None:
    held = report.check_row("Eq 9", "S⁻¹S = I", "e", True, basis="construction")
    assert held["category"] == cat.CAT_CONSTRUCTION and held["published"] == "(check)"
    failed = report.check_row("Eq 9", "S⁻¹S = I", "e", False, basis="construction")
    assert failed["category"] == cat.CAT_DIVERGES
    assert failed["verdict"].startswith(cat.CAT_DIVERGES)
    table1 = report.check_row("Table 1", "±1 N", "e", [True, True], basis="thesis-inconsistency")
    assert table1["category"] == cat.CAT_CONSISTENT_THESIS
    split = report.check_row("Figs 6–7", "c", "e", [True, False], basis="thesis-inconsistency")
    assert split["category"] == cat.CAT_INCONSISTENT and (split["n_values"], split["n_agree"]) == (
        2,
        1,
    )
    with pytest.raises(ValueError, match="claimlist"):
        report.check_row("Table 5", "(ours) h", "e", True, basis="independent")
    assert cat.CAT_DIVERGES not in cat.CLAIM_CATEGORIES


def test_not_reproduced_needs_what_was_tried() -> None:
    row = report.not_reproduced_row(
        "Table 5", "MAX % error", [1e-3, 0.62], [[2e-8, 3e-8], [10.3, 1031.8]], tried="both"
    )
    assert row["category"] == cat.CAT_NOT_REPRODUCED
    assert row["verdict"] == "not reproduced in any setting — both"  # not "diverges"
    assert not verdicts.row_holds(row)
    with pytest.raises(ValueError, match="tried"):
        report.not_reproduced_row("Table 5", "q", [1.0], [2.0], tried=" ")


def test_specs_pass_basis_and_source_through_the_recorder() -> None:
    rec = Recorder("nb", paste=lambda name, value: None)
    rec.value(
        "a", [57.53], rtol=0, row=report.Comparison("Eq 8", "x", [57.53], basis="construction")
    )
    rec.value("c", [True, False], row=report.Check("Figs 6–7", "c", "e", "thesis-inconsistency"))
    rec.value("d", [1e-8, 10.0], rtol=0, row=report.NotReproduced("Table 5", "q", [1e-3], "x"))
    assert [r["category"] for r in rec.report] == [
        cat.CAT_CONSTRUCTION,
        cat.CAT_INCONSISTENT,
        cat.CAT_NOT_REPRODUCED,
    ]


def test_category_lists_are_consistent() -> None:
    assert set(cat.CLAIM_CATEGORIES) < set(cat.CATEGORIES)
    assert cat.CAT_OURS not in cat.CLAIM_CATEGORIES
    assert len(set(cat.CATEGORIES)) == len(cat.CATEGORIES)


def test_report_cells_give_category_tolerance_or_cause_and_a_bounded_difference() -> None:
    from mechlib.reporting import verdicts

    agree = report.compare_row("Table 3", "q", [0.17], [0.166667], resolution=0.005)
    cells = verdicts.report_cells(agree)
    assert cells["verdict"] == "reproduced: within half a unit of the last printed digit"
    assert cells["difference"].startswith("1.96 % of max |published|")
    fitted = report.compare_row("Eq 8", "x", [57.53], [57.6], rtol=0.01, tolerance="1 %: fit_tol",
                                basis="construction")  # fmt: skip
    assert (
        verdicts.report_cells(fitted)["verdict"]
        == "consistent by construction: within 1 %: fit_tol"
    )
    off = report.compare_row(
        "Table 3", "ν", [19.63], [28763.8], cause="x repeats θx", basis="thesis-inconsistency"
    )
    assert verdicts.report_cells(off)["verdict"] == "inconsistency inside the thesis: x repeats θx"
    legacy = {"published": "1, 2", "ours": "1, 3", "max_abs_diff": 1.0, "verdict": "diverges: c"}
    with pytest.raises(ValueError, match="unknown category None"):
        verdicts.report_cells(legacy)  # a row without a category is refused, never parsed
    check = verdicts.report_cells(
        report.check_row("Eq 6", "c", "ratio 2e-8", True, basis="construction")
    )
    assert check == {"published": "(check)", "ours": "ratio 2e-8", "difference": "—",
                     "verdict": "consistent by construction"}  # fmt: skip


def test_a_vector_is_listed_by_name_when_its_entries_are_named() -> None:
    text = cat.summarise(np.array([0.0921, 41.59]), labels=("GP, 256 runs", "linear S_T"))
    assert text == "GP, 256 runs: 0.0921; linear S_T: 41.59"
    row = report.Computed("T", "worst [%]", labels=("a", "b", "c")).row([1.0, 2.0, 3.0])
    assert row["ours"] == "a: 1; b: 2; c: 3"
    with pytest.raises(ValueError, match="labels must name each of the 2 values"):
        cat.summarise(np.array([1.0, 2.0]), labels=("one",))
