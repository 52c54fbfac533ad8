"""The parallelogram pages' records: the comparison's statistics by name (what the elastica page
records with ``rec.mapping``) and the plans' texts and glue, against the code they replace."""

from __future__ import annotations

import numpy as np
import pytest

from mechlib.parallelogram import comparison as cmp
from mechlib.parallelogram import published as pub
from mechlib.reporting import plans


def test_the_statistics_are_the_summary_s_fields_but_the_row() -> None:
    fe = cmp.fe_poses(pub.SWEEP_SUBSET[:20])
    model = fe * 1.01 + 1e-4
    summary = cmp.summarise(model, fe, cmp.applied_loads(pub.SWEEP_SUBSET[:20]))
    statistics = summary.statistics()
    assert list(statistics) == list(summary._fields[:-1])
    for name, value in statistics.items():
        assert value is getattr(summary, name)


def test_the_excess_ranges_are_the_nan_ignoring_extremes_per_component() -> None:
    excess = np.array([[5.0, np.nan, -4.0], [16.5, 2.0, 32.9], [np.nan, 5.1, 1.0]])
    ranges = cmp.excess_ranges(excess)
    assert list(ranges) == ["ux_pct", "uy_pct", "phi_pct", "abs_max_pct"]
    assert ranges["ux_pct"] == [np.nanmin(excess[:, 0]), np.nanmax(excess[:, 0])] == [5.0, 16.5]
    assert ranges["phi_pct"] == [-4.0, 32.9]
    np.testing.assert_array_equal(ranges["abs_max_pct"], [16.5, 5.1, 32.9])
    with pytest.raises(ValueError, match=r"excess must be an \(n, 3\) array"):
        cmp.excess_ranges(excess[:, :2])


def test_the_elastica_page_glues_the_lines_and_the_rows_along_a_x() -> None:
    plan = plans.load("beyond_hexflex")
    texts = plan["sweep.lines"].texts
    lines = [[-5.0, 0.0, 5.0], [-3.0, 0.0, 3.0]]
    assert texts["lines_ax"](lines) == "{−5, 0, 5}"
    assert texts["lines_b"](lines) == "{−3, 0, 3}"
    glue = plan["growth.by_a_x_rel_pct"].glue(np.zeros((5, 3)), {"pull": 3, "push": 1})
    assert glue["uy_rel_pull"] == (3, 1) and glue["phi_rel_push"] == (1, 2)
    assert glue["ux_rel_corner_push"] == (0, 0) and glue["ux_rel_corner_pull"] == (4, 0)


def test_the_fe_page_names_the_best_family_and_the_teacher() -> None:
    plan = plans.load("parallelogram_fe")
    families = ["linear", "quadratic", "cubic", "gp", "pce"]
    assert plan["method.curve_best_index"].texts["curve_best"](3, {"families": families}) == "gp"
    teacher = plan["method.realtime_teacher_index"].texts["rt_teacher"]
    assert teacher(4, {"families": families}) == "pce"
