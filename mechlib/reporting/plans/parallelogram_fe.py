"""Record plan of "The parallelogram in our own FE" (``notebooks/parallelogram_fe.ipynb``): every
key the notebook records, with its tolerance, glue and report rows, and the description of the
data it keeps. Its claims are judged by the claims registry (:mod:`mechlib.reporting.claimlist`).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from mechlib.parallelogram import published as pub
from mechlib.parallelogram.comparison import SMALL_A_Y
from mechlib.parallelogram.metamethod import BUDGET_PCT
from mechlib.reporting import report
from mechlib.reporting.mechanismclaims import MESH_CONVERGED_PCT, SWEEP_AGREEMENT_PCT
from mechlib.reporting.recordplan import Entry
from mechlib.reporting.tolerances import (
    CACHED_FE_POSE,
    CANCELLATION,
    CLOSED_FORM,
    DESIGN_POINT,
    DISTILLED_PCT,
    EXACT,
    FE_EFFECTS,
    FE_FIT_ERROR_PCT,
    FE_PCT,
    FE_STUDY_PCT,
    LINEAR_FE_CHANGE_PCT,
    LINEAR_FE_RATIO,
    META_CURVE_PCT,
    META_CURVE_PCT_REL,
    META_FIT_PCT,
)

ARTEFACT = "Our FE of the parallelogram flexure"
#: the pose components of the report rows
COMPONENTS = ("u_x/L", "u_y/L", "φ")
#: the data the page keeps for the book's bundle: its one-line description
DATA = {
    "parallelogram_fe_sweep": (
        "the computed rows of Su & Survey's 3-D FE sweep solved by our non-linear FE and by "
        "our stretchable elastica: loads F L^2/EI and M L/EI, stage displacement over L, rotation "
        "[rad]"
    ),
}


def _budget_row(context: Mapping[str, Any]) -> list[report.RowSpec]:
    """The largest fraction within the budget of each family (context: ``families``)."""
    return [
        report.Computed(
            ARTEFACT,
            f"largest fraction of the load box within the {BUDGET_PCT:g} % budget, per meta-model "
            "family",
            tuple(context["families"]),
        )
    ]


PLAN: dict[str, Entry] = {
    # --- the model
    "model.stage_young_gpa": Entry(tol=EXACT, glue="stage_e"),
    # the couple's strip [mm], the beams' H/T, and a plate's bending compliance over a beam's
    "design.published": Entry(
        tol=CLOSED_FORM,
        glue={"strip_mm": 0, "h_over_t": 1, "plate_ratio": 2},
        value=[pub.MOMENT_STRIP_MM, pub.HEIGHT_MM / pub.THICKNESS_MM, 1 - pub.POISSON**2],
    ),
    "model.dofs": Entry(tol=EXACT, glue="dofs"),
    "model.mesh": Entry(tol=EXACT, glue={"mesh_size": 0, "layers": 1, "elements": 2}),
    "model.c_yy_over_guided": Entry(
        tol=LINEAR_FE_RATIO,
        glue="c_over_guided",
        rows=report.Computed(
            ARTEFACT,
            "linear compliance u_y/F_y over two guided Euler–Bernoulli beams' L³/(24EI)",
        ),
    ),
    "model.steel_stage_excess_pct": Entry(
        tol=LINEAR_FE_CHANGE_PCT, glue={"steel_ux": 0, "steel_uy": 1, "steel_phi": 2}
    ),
    # --- our mesh study beside theirs
    # the published mesh study's load (A_x, A_y, B), its coarsest and finest mesh [mm]
    "mesh.published_case": Entry(
        tol=EXACT,
        glue={"case_ax": 0, "case_ay": 1, "case_b": 2, "their_coarse": 3, "their_fine": 4},
        value=[*pub.MESH_STUDY_LOADS, pub.MESH_STUDY[0, 0], pub.MESH_STUDY[-1, 0]],
    ),
    "design.claim_thresholds_pct": Entry(
        tol=EXACT,
        glue={"converged_pct": 0, "agreement_pct": 1},
        value=[MESH_CONVERGED_PCT, SWEEP_AGREEMENT_PCT],
    ),
    "mesh.ours": Entry(tol=CACHED_FE_POSE),
    "mesh.ours_finest": Entry(
        tol=CACHED_FE_POSE,
        rows=report.Computed(
            ARTEFACT,
            "our FE at the published mesh study's load, finest of our meshes: load point x, y "
            "[mm], rotation [rad]",
            ("x [mm]", "y [mm]", "φ [rad]"),
        ),
    ),
    "mesh.last_step_pct": Entry(tol=FE_STUDY_PCT, glue={"step_x": 0, "step_y": 1, "step_phi": 2}),
    "mesh.ours_vs_their_finest_pct": Entry(
        tol=FE_STUDY_PCT, glue={"vs_fine_x": 0, "vs_fine_y": 1, "vs_fine_phi": 2}
    ),
    # their coarsest mesh against their finest: arithmetic on printed numbers
    "mesh.their_spread_pct": Entry(
        tol=CANCELLATION, glue={"spread_x": 0, "spread_y": 1, "spread_phi": 2}
    ),
    # --- our FE against the published sweep
    "sweep.rows": Entry(tol=EXACT, glue="n_rows"),
    "sweep.ours_vs_published_worst_pct": Entry(
        tol=FE_PCT,
        glue={"w_ux": 0, "w_uy": 1, "w_phi": 2},
        rows=report.Computed(
            ARTEFACT,
            "largest |our FE − published FE| over the rows solved, % of the published FE's "
            "full scale",
            COMPONENTS,
        ),
    ),
    "sweep.ours_vs_published_median_pct": Entry(
        tol=FE_PCT, glue={"m_ux": 0, "m_uy": 1, "m_phi": 2}
    ),
    # the smallest (0–2) and the largest (3–5) relative difference per component
    "sweep.ours_over_published_pct": Entry(
        tol=FE_PCT, glue={"ex_min_uy": 1, "ex_max_uy": 4, "ex_min_phi": 2, "ex_max_phi": 5}
    ),
    "sweep.elastica_vs_ours_worst_pct": Entry(tol=FE_PCT, glue={"b_ux": 0, "b_uy": 1, "b_phi": 2}),
    "sweep.worst_loads": Entry(tol=EXACT, glue={"worst_ax": 0, "worst_ay": 1, "worst_b": 2}),
    "growth.a_x_levels": Entry(tol=EXACT),
    "growth.by_a_x_pct": Entry(tol=FE_PCT),
    "growth.a_y_levels": Entry(tol=EXACT),
    "growth.by_a_y_pct": Entry(tol=FE_PCT),
    "growth.small_and_top_pct": Entry(tol=FE_PCT, glue={"g_small": 0, "g_top": 1, "g_top_ay": 2}),
    "sweep.small_a_y": Entry(tol=EXACT, glue="small_a_y", value=SMALL_A_Y),
    "corner.fine_mesh": Entry(tol=EXACT, glue={"fine_size": 0, "fine_layers": 1}),
    "corner.fine_minus_default_pct": Entry(
        tol=FE_STUDY_PCT, glue={"c_move_ux": 0, "c_move_uy": 1, "c_move_phi": 2}
    ),
    "corner.fine_vs_published_pct": Entry(
        tol=FE_STUDY_PCT, glue={"c_fine_ux": 0, "c_fine_uy": 1, "c_fine_phi": 2}
    ),
    # --- chapter 2's method: screening
    "method.screening_fraction": Entry(tol=EXACT, glue="screen_fraction"),
    "method.box_and_design": Entry(
        tol=EXACT,
        glue={
            "half_ax": 0,
            "half_ay": 1,
            "half_b": 2,
            "screen_runs": 3,
            "n_dummy_cols": 4,
            "n_load_effects": 5,
            "n_dummy_effects": 6,
        },
    ),
    "method.screening_effects": Entry(tol=FE_EFFECTS),
    "method.screening_active": Entry(tol=EXACT),
    "method.screening_zero_me": Entry(tol=EXACT, glue="n_zero_me"),
    "method.screening_counts": Entry(tol=EXACT, glue={"n_active": 0, "n_dummies": 1}),
    # --- the thesis's models over the whole box
    "method.runs": Entry(tol=EXACT, glue={"n_uniform": 0, "n_held": 1, "n_held_failed": 2}),
    "method.thesis_models_worst_pct": Entry(tol=FE_FIT_ERROR_PCT),
    "method.st_worst_pct": Entry(
        tol=FE_FIT_ERROR_PCT,
        glue={"st_ux": 0, "st_uy": 1, "st_phi": 2},
        rows=report.Computed(
            ARTEFACT,
            "S_T (Eq 7) fitted on a uniform design over the whole load box: largest held-out "
            "error, % of full scale",
            COMPONENTS,
        ),
    ),
    "method.eq6_worst_pct": Entry(
        tol=FE_FIT_ERROR_PCT, glue={"eq6_ux": 0, "eq6_uy": 1, "eq6_phi": 2}
    ),
    # the error budget of chapter 2's meta-model page
    "method.goal_pct": Entry(tol=EXACT, glue="goal", value=BUDGET_PCT),
    # --- learning curves
    "method.curve_sizes": Entry(tol=EXACT),
    "method.curve_n_max": Entry(tol=EXACT, glue="curve_n_max"),
    "method.curve_failed": Entry(tol=EXACT, glue="curve_failed"),
    "method.curve_fitted": Entry(tol=EXACT),
    "method.curve_worst_pct": Entry(tol=META_CURVE_PCT),
    "method.curve_best_index": Entry(
        tol=EXACT, texts={"curve_best": lambda v, c: str(c["families"][v])}
    ),
    "method.curve_best_pct": Entry(tol=META_CURVE_PCT_REL, glue="curve_best_pct"),
    # what the worst error rests on: the held-out run where it lies at the largest design, and
    # the largest error over the other held-out runs
    "method.curve_second_pct": Entry(tol=META_CURVE_PCT),
    "method.curve_worst_loads": Entry(tol=DESIGN_POINT, glue={"cw_ax": 0, "cw_ay": 1, "cw_b": 2}),
    "method.curve_one_run": Entry(
        tol=META_CURVE_PCT,
        glue={"cw_same": 0, "cw_fams": 1, "cw_fall": 2, "cw_from": 3, "cw_to": 4},
    ),
    # --- the range within the budget
    "method.budget_runs": Entry(
        tol=EXACT, glue={"budget_train": 0, "budget_held": 1, "budget_failed": 2}
    ),
    "method.budget_worst_pct": Entry(tol=META_FIT_PCT),
    "method.budget_largest": Entry(tol=EXACT, rows=_budget_row),
    "method.budget_best_and_linear": Entry(tol=EXACT, glue={"budget_best": 0, "budget_linear": 1}),
    # --- a real-time model
    "method.realtime_scale": Entry(tol=EXACT, glue="rt_scale"),
    "method.realtime_teacher_index": Entry(
        tol=EXACT, texts={"rt_teacher": lambda v, c: str(c["families"][v])}
    ),
    "method.realtime_degree": Entry(tol=EXACT, glue="rt_degree"),
    "method.realtime_worst_pct": Entry(tol=DISTILLED_PCT, glue="rt_worst"),
    "method.failed_runs": Entry(tol=EXACT, glue="n_failed"),
}
