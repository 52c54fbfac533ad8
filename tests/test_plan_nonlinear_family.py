"""The non-linear family chapter's record plan: the texts and glue it makes from the recorded
values are those the notebook used to write by hand, on the branches its default run does not
take too (no other member, one mesh, the lean mesh for the members)."""

from __future__ import annotations

import numpy as np
import pytest
from pasting import planned  # tests/ is on sys.path (pytest prepend import mode)

from mechlib import published as pub
from mechlib.hexflex.studies import leanmesh
from mechlib.reporting.tolerances import lean_pose_pct

R = list(pub.RESPONSES)


def test_the_lean_pose_tolerance_is_the_fit_tolerance_in_points() -> None:
    assert lean_pose_pct(leanmesh.FIT_TOL).atol == 100 * leanmesh.FIT_TOL == 0.01
    assert lean_pose_pct(leanmesh.FIT_TOL).rtol == 1e-2
    for bad in (0.0, 1.5, True, "1e-4"):
        with pytest.raises(ValueError, match="fit_tol must be a number in"):
            lean_pose_pct(bad)


def test_the_mesh_text_names_the_lean_stand_ins_and_their_sizes() -> None:
    dofs = [192843, 46935, 113787]
    by_hand = (
        "each member's lean stand-in: the lean mesh compared at the end of this page, its free "
        f"dimensions fitted to the member's own FE magnitudes within {100 * leanmesh.FIT_TOL:g} % "
        f"({min(dofs)} to {max(dofs)} free DOFs)"
    )
    for mesh, text in (("lean", by_hand), ("default", "the model page's mesh rule")):
        rec, pasted = planned("nonlinear_family")
        rec.value("family.nonlinear_n_dofs", dofs, context={"mesh": mesh})
        assert pasted["nl_mesh_text"] == text
        assert rec.glued["nl_mesh_text"] == {"text_of": "family.nonlinear_n_dofs"}
    assert "46935 to 192843 free DOFs" in by_hand


def test_the_thinnest_and_thickest_members_parts_are_glued_by_their_rows() -> None:
    even_odd = np.array([[3.0, 1.0], [5.0, 2.0], [4.0, 0.5]])
    rec, pasted = planned("nonlinear_family")
    rec.value("family.even_odd_pct", even_odd, context={"thin": 1, "thick": 2})
    assert rec.glued["even_thin"] == {"key": "family.even_odd_pct", "index": [1, 0]}
    assert rec.glued["odd_thick"] == {"key": "family.even_odd_pct", "index": [2, 1]}
    assert (pasted["odd_thin"], pasted["even_thick"]) == (2.0, 4.0)


def test_the_mesh_study_glues_the_finest_mesh_row_only_when_there_is_one() -> None:
    change = np.array([[0.1, 0.3, 0.2], [0.2, 0.1, 0.4], [0.05, 0.02, 0.01]])
    rec, pasted = planned("nonlinear_family")
    rec.value("mesh.departure_change_pct", change, context={"n_mesh": 2})
    rec.value("mesh.linear_change_pct", np.array([0.3, 0.4, 1e-4]), context={"n_mesh": 2})
    rec.value("mesh.quadrature_worst_pct", change[2:].max(axis=1))
    assert rec.glued["mesh_dep_change"] == {"key": "mesh.departure_change_pct", "index": [1, 2]}
    assert pasted["mesh_dep_component"] == R[int(change[1].argmax())]
    assert rec.glued["mesh_lin_change"] == {"key": "mesh.linear_change_pct", "index": 1}
    assert rec.glued["quad_dep_change"] == {"key": "mesh.quadrature_worst_pct", "index": 0}
    one, pasted = planned("nonlinear_family")
    one.value("mesh.departure_change_pct", change[2:], context={"n_mesh": 0})
    assert "mesh_dep_change" not in one.glued
    assert pasted["mesh_dep_component"] == R[int(change[2].argmax())]


def test_the_lean_verdicts_read_as_written_by_hand() -> None:
    for meets in (True, False):
        rec, pasted = planned("nonlinear_family")
        rec.value("lean.meets_criteria", meets)
        assert pasted["lean_verdict"] == (
            "meets the criteria" if meets else "does not meet the criteria"
        )
        assert pasted["lean_use"] == (
            "the DOE chapter and the meta-model page solve their non-linear runs on this stand-in "
            "of the identified member by default"
            if meets
            else "it should not replace the chapter's mesh in the non-linear campaigns"
        )


def test_the_other_members_verdicts_read_as_written_by_hand() -> None:
    others, unfitted = [0.35, 0.45, 0.55], {0.35: (1.234, 20)}
    meet = np.array([False, False, True])
    rec, pasted = planned("nonlinear_family")
    rec.value("lean.unfitted_members_mm", list(unfitted), context={"unfitted": unfitted})
    rec.value("lean.other_meet_criteria", meet, context={"others": others, "unfitted": unfitted})
    assert pasted["lean_unfitted"] == (
        "the 0.35 mm member's lean fit stopped 1.23 % off its magnitudes after 20 lean FE models "
        f"(more than {100 * leanmesh.FIT_TOL:g} %), so it has no stand-in"
    )
    assert pasted["lean_other_verdict"] == (
        "the 0.35 mm member's stand-in cannot be fitted; the 0.45 mm member's stand-in misses "
        "them; the 0.55 mm member's stand-in meets them"
    )
    assert pasted["lean_other_use"].startswith("Because it does not meet them on every member")
    every, pasted = planned("nonlinear_family")
    every.value("lean.unfitted_members_mm", [], context={"unfitted": {}})
    every.value(
        "lean.other_meet_criteria", np.ones(2, bool), context={"others": [1, 2], "unfitted": {}}
    )
    assert pasted["lean_unfitted"] == "every member's lean fit met its tolerance"
    assert pasted["lean_other_use"].startswith("The stand-in meets the criteria on every member")


def test_the_other_members_summary_reads_as_written_by_hand_on_every_branch() -> None:
    pose, dep, moves, own_move = np.array([0.5, 0.31]), np.array([5.4, 2.0]), [1.9, 0.7], 0.0023
    fitted, pasted = planned("nonlinear_family")
    fitted.value("lean.other_failed_runs", 0)
    fitted.value("lean.other_worst_pose_pct", pose)
    fitted.value("lean.other_worst_departure_pct", dep)
    fitted.value("lean.other_largest_dimension_change_pct", np.array(moves))
    fitted.value(
        "lean.largest_dimension_change_pct",
        100 * own_move,
        context={"fitted": [0.45, 0.55], "others": [0.35, 0.45, 0.55]},
    )
    assert pasted["lean_other_summary"] == (
        f"On the other members whose stand-in was fitted the lean stand-in's poses differ from "
        f"the chapter's mesh by up to {pose.max():.2g} % of full scale and its "
        f"departures by up to {dep.max():.2g} % of themselves ({0} runs "
        f"did not converge). The lean fits moved a free dimension by up to {max(moves):.2g} % "
        f"on those members, against {100 * own_move:.2g} % on the identified one."
    )
    assert "up to 0.5 % of full scale" in pasted["lean_other_summary"]
    assert fitted.glued["lean_other_summary"] == {
        "text_of": "lean.other_worst_pose_pct,lean.other_worst_departure_pct,"
        "lean.other_failed_runs,lean.other_largest_dimension_change_pct,"
        "lean.largest_dimension_change_pct"
    }
    for others, text in (
        ([0.35], "No other member's stand-in was fitted, so none was compared."),
        ([], "No other member was solved."),
    ):
        rec, pasted = planned("nonlinear_family")
        unfitted = {t: (1.2, 20) for t in others}
        rec.value("lean.unfitted_members_mm", others, context={"unfitted": unfitted})
        rec.value(
            "lean.largest_dimension_change_pct",
            100 * own_move,
            context={"fitted": [], "others": others},
        )
        assert pasted["lean_other_summary"] == text
        assert rec.glued["lean_other_summary"] == {"text_of": "lean.unfitted_members_mm"}
