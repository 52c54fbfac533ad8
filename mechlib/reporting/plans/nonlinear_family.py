"""Record plan of "The non-linear HexFlex across the Eq 8 family"
(``notebooks/nonlinear_family.ipynb``): every key the chapter records, with its tolerance, glue
names and report rows.

Keys a parameter can switch off are optional: the other members' extremes (no other member),
the quadrature study (one quadrature order), a part of the lean comparison that no run of it
reached on both meshes, and the other members' lean comparison (no stand-in fitted).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from mechlib import published as pub
from mechlib.hexflex.studies.leanmesh import FIT_TOL
from mechlib.reporting import report
from mechlib.reporting.recordplan import Entry, Extremes, MadeOf
from mechlib.reporting.tolerances import (
    BEAM_REACH_FAR,
    BEAM_REACH_PCT,
    EXACT,
    FE_IDENTIFIED,
    FE_IDENTIFIED_PCT,
    LEAN_DEPARTURE_PCT,
    LEAN_FIT_CHANGE_PCT,
    MESH_STUDY_LINEAR_PCT,
    MESH_STUDY_PCT,
    NONLINEAR_FE,
    NONLINEAR_FE_REL,
    ROUNDED_THICKNESS,
    lean_pose_pct,
)

R = tuple(pub.RESPONSES)
#: the lean comparison's differences of poses: what a fit within the lean fit's tolerance moves
LEAN_POSE_PCT = lean_pose_pct(FIT_TOL)
#: the lean comparison's parts: the validation draw's runs and the sweep along its first run
LEAN_PARTS = ("runs", "sweep")
#: what the other members' summary quotes, in its order: their lean comparison's largest
#: differences, failed runs and fits' moves, then the identified member's fit's move
OTHER_SUMMARY_OF = (
    "lean.other_worst_pose_pct",
    "lean.other_worst_departure_pct",
    "lean.other_failed_runs",
    "lean.other_largest_dimension_change_pct",
    "lean.largest_dimension_change_pct",
)


def _nl_mesh_text(dofs: list[int], c: Mapping[str, Any]) -> str:
    """The mesh the members' non-linear runs were solved on (the ``nonlinear_mesh`` parameter)."""
    if c["mesh"] != "lean":
        return "the model page's mesh rule"
    return (
        "each member's lean stand-in: the lean mesh compared at the end of this page, its free "
        f"dimensions fitted to the member's own FE magnitudes within {100 * FIT_TOL:g} % "
        f"({min(dofs)} to {max(dofs)} free DOFs)"
    )


def _mesh_dep_component(change: np.ndarray, c: Mapping[str, Any]) -> str:
    """The component whose departure changes most on the finest mesh (the first row without a
    finer mesh)."""
    return R[int(np.argmax(change[max(c["n_mesh"] - 1, 0)]))]


def _lean_use(meets: bool) -> str:
    if meets:
        return (
            "the DOE chapter and the meta-model page solve their non-linear runs on this "
            "stand-in of the identified member by default"
        )
    return "it should not replace the chapter's mesh in the non-linear campaigns"


def _unfitted(members_mm: list[float], c: Mapping[str, Any]) -> str:
    """The members without a lean stand-in: ``c["unfitted"]`` maps each thickness to the fit's
    last misfit [%] and its number of FE models."""
    stopped = [
        f"the {t:.3g} mm member's lean fit stopped {m:.3g} % off its magnitudes after {n} lean "
        f"FE models (more than {100 * FIT_TOL:g} %), so it has no stand-in"
        for t, (m, n) in c["unfitted"].items()
    ]
    return "; ".join(stopped) or "every member's lean fit met its tolerance"


def _other_verdict(meet: np.ndarray, c: Mapping[str, Any]) -> str:
    """Each other member's stand-in against the criteria (``c["others"]``: their thicknesses)."""
    return "; ".join(
        f"the {t:.3g} mm member's stand-in "
        + ("cannot be fitted" if t in c["unfitted"] else "meets them" if m else "misses them")
        for t, m in zip(c["others"], meet, strict=True)
    )


def _other_use(meet: np.ndarray) -> str:
    if np.all(meet):
        return (
            "The stand-in meets the criteria on every member solved, so a reader may solve this "
            "page's members on it too (the nonlinear_mesh parameter)"
        )
    return (
        "Because it does not meet them on every member, this page solves its members on the "
        "chapter's mesh rule by default (the nonlinear_mesh parameter), while the DOE chapter and "
        "the meta-model page use the identified member's stand-in"
    )


def _other_summary_of(own_move: float, c: Mapping[str, Any]) -> tuple[str, ...]:
    """What the other members' summary is made of: their comparison when a stand-in was fitted
    (``c["fitted"]``: their thicknesses), else the list of the members without one."""
    return OTHER_SUMMARY_OF if c["fitted"] else ("lean.unfitted_members_mm",)


def _other_summary(v: Mapping[str, Any], c: Mapping[str, Any]) -> str:
    """The other members' lean comparison in a sentence, or why there is none (``c["others"]``:
    the other members' thicknesses)."""
    if not c["fitted"]:
        if c["others"]:
            return "No other member's stand-in was fitted, so none was compared."
        return "No other member was solved."
    pose, dep, failed, moves, own = (v[k] for k in OTHER_SUMMARY_OF)
    return (
        f"On the other members whose stand-in was fitted the lean stand-in's poses differ from "
        f"the chapter's mesh by up to {max(pose):.2g} % of full scale and its departures by up to "
        f"{max(dep):.2g} % of themselves ({failed} runs did not converge). The lean fits moved a "
        f"free dimension by up to {max(moves):.2g} % on those members, against {own:.2g} % on "
        f"the identified one."
    )


PLAN: dict[str, Entry] = {
    # --- which thicknesses the beam model reaches ---
    "reach.worst_pct": Entry(tol=BEAM_REACH_PCT),
    "parameters.reach_thicknesses": Entry(tol=EXACT),
    "reach.thickest_feasible_mm": Entry(tol=EXACT, glue="reach_thickest"),
    "reach.first_infeasible_mm": Entry(tol=EXACT, glue="reach_first_out"),
    "reach.thickest_shown_mm": Entry(tol=EXACT, glue="reach_last_t"),
    "reach.thickest_shown_worst_pct": Entry(tol=BEAM_REACH_FAR, glue="reach_last"),
    # --- the members, identified in FE ---
    "members.start_grid_mm": Entry(tol=EXACT, glue="start_grid_mm"),
    "members.fit_log_quantum": Entry(tol=EXACT, glue="fit_quantum"),
    "members.thickness_mm": Entry(tol=ROUNDED_THICKNESS),
    "members.fit_evaluations": Entry(
        tol=EXACT, glue=Extremes(low="fit_evals_min", high="fit_evals_max"), optional=True
    ),
    "members.free_dimensions_mm": Entry(tol=FE_IDENTIFIED),
    "members.fit_worst_pct": Entry(tol=FE_IDENTIFIED_PCT, glue=Extremes(high="fit_worst_max")),
    # --- the same runs, non-linear, on every member ---
    "parameters.family_runs": Entry(tol=EXACT, glue="n_runs"),
    "parameters.n_validation": Entry(tol=EXACT, glue="n_val"),
    "family.failed_runs": Entry(tol=EXACT, glue="n_failed"),
    "family.nonlinear_n_dofs": Entry(tol=EXACT, texts={"nl_mesh_text": _nl_mesh_text}),
    "family.runs_per_member": Entry(tol=EXACT),
    "family.departure_pct": Entry(
        tol=NONLINEAR_FE,
        rows=report.Computed(
            "Beyond the thesis: the Eq 8 family",
            "departure of the non-linear poses from each member's linear model, per component "
            "[% of full scale], members by plate thickness",
        ),
    ),
    "family.worst_departure_pct": Entry(
        tol=NONLINEAR_FE, glue=Extremes(low="worst_lo", high="worst_hi")
    ),
    "family.tilt_mrad": Entry(tol=NONLINEAR_FE_REL, glue=Extremes(low="tilt_lo", high="tilt_hi")),
    # the even and odd parts of the thinnest and the thickest member (their rows: context)
    "family.even_odd_pct": Entry(
        tol=NONLINEAR_FE,
        glue=lambda value, c: {
            "even_thin": (c["thin"], 0),
            "odd_thin": (c["thin"], 1),
            "even_thick": (c["thick"], 0),
            "odd_thick": (c["thick"], 1),
        },
    ),
    "family.thinnest_mm": Entry(tol=ROUNDED_THICKNESS, glue="t_thin"),
    "family.thickest_mm": Entry(tol=ROUNDED_THICKNESS, glue="t_thick"),
    "family.departure_thin_over_thick": Entry(tol=NONLINEAR_FE_REL, glue="thin_over_thick"),
    "family.min_departure_over_published": Entry(
        tol=NONLINEAR_FE_REL,
        glue=Extremes(low="gap_min", labels=R, low_label="gap_component"),
    ),
    # --- the mesh and quadrature study ---
    "parameters.mesh_runs": Entry(tol=EXACT, glue="n_mesh_runs"),
    "mesh.failed_runs": Entry(tol=EXACT, glue="n_mesh_failed"),
    "mesh.dofs": Entry(tol=EXACT),
    # the finest mesh's row (n_mesh - 1) glued, when there is a finer mesh (context: n_mesh)
    "mesh.departure_change_pct": Entry(
        tol=MESH_STUDY_PCT,
        glue=lambda value, c: (
            {"mesh_dep_change": (c["n_mesh"] - 1, int(value[c["n_mesh"] - 1].argmax()))}
            if c["n_mesh"]
            else {}
        ),
        texts={"mesh_dep_component": _mesh_dep_component},
        rows=report.Computed(
            "Beyond the thesis: non-linear mesh study",
            "change of the departure from linearity with a finer flexure mesh and with more Gauss "
            "points, largest per component [% of the departure]",
        ),
    ),
    "mesh.linear_change_pct": Entry(
        tol=MESH_STUDY_LINEAR_PCT,
        glue=lambda value, c: {"mesh_lin_change": c["n_mesh"] - 1} if c["n_mesh"] else {},
    ),
    # the highest quadrature order's change (the last entry)
    "mesh.quadrature_worst_pct": Entry(
        tol=MESH_STUDY_PCT,
        glue=lambda value, c: {"quad_dep_change": len(value) - 1},
        optional=True,
    ),
    "mesh.quadrature_linear_pct": Entry(
        tol=MESH_STUDY_LINEAR_PCT,
        glue=lambda value, c: {"quad_lin_change": len(value) - 1},
        optional=True,
    ),
    # --- the lean mesh, on the identified member ---
    "parameters.lean_runs": Entry(tol=EXACT, glue="n_lean_runs"),
    "parameters.lean_sweep": Entry(tol=EXACT),
    "lean.settings": Entry(
        tol=EXACT, glue={"lean_fraction": 0, "lean_mid_widths": 1, "lean_coarse_widths": 2}
    ),
    "lean.criteria_pct": Entry(
        tol=EXACT, glue={"lean_pose_limit": 0, "lean_dep_limit": 1, "lean_fit_tol_pct": 2}
    ),
    "lean.dofs": Entry(tol=EXACT, glue={"lean_default_dofs": 0, "lean_dofs": 1}),
    "lean.fit_evaluations": Entry(tol=EXACT, glue="lean_fit_evals"),
    "lean.free_dimension_change_pct": Entry(tol=LEAN_FIT_CHANGE_PCT, glue={"lean_dim_change": 0}),
    "lean.failed_runs": Entry(tol=EXACT, glue="n_lean_failed"),
    "lean.failed_on_lean_only": Entry(tol=EXACT),
    **{f"lean.pose_pct_{p}": Entry(tol=LEAN_POSE_PCT, optional=True) for p in LEAN_PARTS},
    **{f"lean.departure_pct_{p}": Entry(tol=LEAN_DEPARTURE_PCT, optional=True) for p in LEAN_PARTS},
    "lean.worst_pose_pct": Entry(
        tol=LEAN_POSE_PCT,
        glue="lean_pose_worst",
        rows=report.Computed(
            "Beyond the thesis: lean mesh",
            "largest non-linear pose difference, lean mesh vs the chapter's, after "
            "re-identification [% of full scale]",
        ),
    ),
    "lean.worst_departure_pct": Entry(tol=LEAN_DEPARTURE_PCT, glue="lean_dep_worst"),
    "lean.meets_criteria": Entry(
        tol=EXACT,
        texts={
            "lean_verdict": lambda meets: (
                "meets the criteria" if meets else "does not meet the criteria"
            ),
            "lean_use": _lean_use,
        },
    ),
    # --- the lean mesh, on the other members ---
    "parameters.lean_other_runs": Entry(tol=EXACT, glue="n_lean_other_runs"),
    # recorded last: the other members' summary quotes it with their comparison's numbers
    "lean.largest_dimension_change_pct": Entry(
        tol=LEAN_FIT_CHANGE_PCT,
        texts={"lean_other_summary": MadeOf(_other_summary_of, _other_summary)},
    ),
    "lean.unfitted_members_mm": Entry(tol=ROUNDED_THICKNESS, texts={"lean_unfitted": _unfitted}),
    "lean.other_meet_criteria": Entry(
        tol=EXACT,
        texts={"lean_other_verdict": _other_verdict, "lean_other_use": _other_use},
        optional=True,
    ),
    "lean.other_members_mm": Entry(tol=ROUNDED_THICKNESS, optional=True),
    "lean.other_dofs": Entry(tol=EXACT, optional=True),
    "lean.other_failed_runs": Entry(tol=EXACT, optional=True),
    "lean.other_worst_pose_pct": Entry(tol=LEAN_POSE_PCT, optional=True),
    "lean.other_worst_departure_pct": Entry(tol=LEAN_DEPARTURE_PCT, optional=True),
    "lean.other_largest_dimension_change_pct": Entry(tol=LEAN_FIT_CHANGE_PCT, optional=True),
}
