"""Record plan of "The HexFlex finite-element model, identified from Eq 8"
(``notebooks/hexflex_model.ipynb``): every key the notebook records, with its tolerance, glue and
report rows; the rows set the identified model against Eq 8 (:mod:`mechlib.published`).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from mechlib import published as pub
from mechlib.hexflex.identify import TARGET_LABELS, target_values
from mechlib.reporting import report
from mechlib.reporting.recordplan import Entry
from mechlib.reporting.tolerances import (
    BEAM_MODEL,
    BEAM_MODEL_SENSITIVITY,
    CANCELLATION,
    CLOSED_FORM,
    EXACT,
    FE_DEFECT,
    FE_IDENTIFIED,
    FE_IDENTIFIED_DIFF_PCT,
    FE_IDENTIFIED_PCT,
    FE_IDENTIFIED_PEAK,
    FE_OVER_THEORY,
    FE_OVER_THEORY_PCT,
    FE_RECIPROCITY,
    FE_SENSITIVITY,
    ITERATIVE,
    MESH_CHANGE_PCT,
    ROUNDOFF,
    UNIT_VECTORS,
)

# --- how close Eq 8 must come to the identified model (report rows, not record tolerances) ---
# the four fitted magnitudes: 1 %, above the identification's stopping tolerance
EQ8_FIT_RTOL = 0.01
# every non-zero entry of Eq 8: the fit's 1 % on the four fitted magnitudes, plus Eq 8's own
# three-fold symmetry defect (the other twelve follow from the model's symmetry), plus the mesh
# error (convergence study)
ENTRY_RTOL = 0.05
#: Eq 8's non-zero entries, the ones the compliance row compares
NONZERO = pub.EQ8_ST != 0
#: the dimensions of the HexFlex geometry, as ``geometry.<name>`` keys spell them
DIMENSIONS = (
    "stage_radius",
    "tab_half_width",
    "tab_outer",
    "beam_radius",
    "beam_width",
    "beam_length",
    "radial_width",
    "radial_length",
    "thickness",
)


def _listed(values: Any) -> str:
    """Numbers as the prose lists them: two decimals, comma-separated (as many as a parameter
    makes: the free dimensions' singular values, the mesh study's refinements)."""
    return ", ".join(f"{v:.2f}" for v in values)


def _fit_rows(context: Mapping[str, Any]) -> list[report.RowSpec]:
    """Eq 8's four fitted magnitudes against the model; the tolerance says how it was made
    (context: ``fit_tol`` and ``n_fe``, the FE models the identification built, 0 when the
    geometry was given rather than identified)."""
    if context["n_fe"]:
        tolerance = (
            f"{100 * EQ8_FIT_RTOL:g} %, above the identification's stopping tolerance "
            f"(fit_tol = {100 * context['fit_tol']:g} %, met after {context['n_fe']} FE models)"
        )
    else:
        tolerance = f"{100 * EQ8_FIT_RTOL:g} % (the given geometry, not identified)"
    return [
        report.Comparison(
            "Eq 8",
            f"{label} (identified FE model)",
            published,
            tolerance=tolerance,
            rtol=EQ8_FIT_RTOL,
            part=i,
            basis="construction",  # the model is identified on these four magnitudes
        )
        for i, (label, published) in enumerate(
            zip(TARGET_LABELS, target_values(pub.EQ8_ST), strict=True)
        )
    ]


def _free_dimensions_row(context: Mapping[str, Any]) -> list[report.RowSpec]:
    """The identified free dimensions (context: ``free_dimensions``, their names)."""
    names = ", ".join(context["free_dimensions"])
    return [report.Computed("Fig 2", f"identified dimensions [mm] ({names})")]


def _compliance_row(context: Mapping[str, Any]) -> list[report.RowSpec]:
    """All of Eq 8's non-zero entries against the model (context: ``sym_eq8``, Eq 8's own
    three-fold symmetry defect)."""
    return [
        report.Comparison(
            "Eq 8",
            "all 16 non-zero entries of S_T (identified FE model)",
            pub.EQ8_ST[NONZERO],
            tolerance=f"{100 * ENTRY_RTOL:g} %: the fit's {100 * EQ8_FIT_RTOL:g} %, plus Eq 8's "
            f"own three-fold symmetry defect ({100 * context['sym_eq8']:.2g} % of a row's "
            "largest entry), plus the mesh's discretisation error",
            rtol=ENTRY_RTOL,
            part=NONZERO,
            basis="construction",  # 4 magnitudes fitted, the other 12 entries follow by symmetry
        )
    ]


PLAN: dict[str, Entry] = {
    # --- the layout's tilt-to-lift argument and the beam model's pre-fit
    "eq8.tilt_per_lift": Entry(tol=CLOSED_FORM, glue="ratio_eq8"),
    "hinged_links.max_radius_mm": Entry(tol=CLOSED_FORM, glue="r_eq8"),
    "frame.start_magnitudes": Entry(tol=BEAM_MODEL),
    "frame.start_worst_pct": Entry(tol=CANCELLATION, glue="frame_start_worst"),
    "frame.point_support_ratio_start": Entry(tol=BEAM_MODEL, glue="bound_start"),
    "frame.prefit_magnitudes": Entry(tol=ITERATIVE),
    # --- the identification in FE
    **{f"geometry.{name}": Entry(tol=FE_IDENTIFIED) for name in DIMENSIONS},
    "fit.achieved": Entry(tol=FE_IDENTIFIED, rows=_fit_rows),
    "fit.evaluations": Entry(tol=EXACT, glue="fit_evaluations"),
    "fit.worst_pct": Entry(tol=FE_IDENTIFIED_PCT, glue="fit_worst"),
    "model.n_dofs": Entry(tol=EXACT),
    "model.mesh_fraction": Entry(tol=EXACT),
    "model.element": Entry(tol=EXACT),
    "fit.free_dimensions_mm": Entry(tol=FE_IDENTIFIED, rows=_free_dimensions_row),
    # --- which dimensions Eq 8 determines
    "sensitivity.fe_singular_values": Entry(tol=FE_SENSITIVITY, texts={"sv_fe": _listed}),
    "sensitivity.frame_singular_values": Entry(
        tol=BEAM_MODEL_SENSITIVITY,
        glue={"sv_frame_0": 0, "sv_frame_1": 1, "sv_frame_2": 2, "sv_frame_3": 3},
    ),
    "sensitivity.fe_amplification": Entry(tol=FE_SENSITIVITY, glue="sv_amplify"),
    # --- the beam model against FE
    "frame.tolerances_pct": Entry(tol=EXACT, glue={"frame_tol": 0, "frame_tol_stiff": 1}),
    "frame.vs_fe": Entry(tol=FE_IDENTIFIED),
    "frame.vs_fe_stiff_body": Entry(tol=FE_IDENTIFIED),
    "frame.worst_vs_fe_pct": Entry(
        tol=FE_IDENTIFIED_PCT, glue={"frame_vs_fe": 0, "frame_vs_rigid": 1}
    ),
    "frame.within_tolerance_of_fe": Entry(tol=EXACT),
    "frame.within_tolerance_of_stiff_body_fe": Entry(tol=EXACT),
    "fe.stiff_body_lowers_thx_pct": Entry(tol=FE_IDENTIFIED_DIFF_PCT, glue="thx_body"),
    # --- the full compliance against Eq 8
    "compliance": Entry(tol=FE_IDENTIFIED_PEAK, rows=_compliance_row),
    "compliance.worst_entry_vs_eq8_pct": Entry(tol=FE_IDENTIFIED_PCT, glue="entries_worst"),
    # --- evidence that the model is right
    "checks.symmetry_defect": Entry(tol=FE_DEFECT, glue="ev_sym"),
    "checks.zero_pattern_defect": Entry(tol=FE_DEFECT, glue="ev_zero"),
    "checks.reciprocity_defect": Entry(tol=FE_RECIPROCITY, glue="ev_recip"),
    "checks.symmetry_defect_below_1e-6": Entry(tol=EXACT),
    "checks.zero_pattern_below_1e-6": Entry(tol=EXACT),
    "checks.reciprocity_below_1e-9": Entry(tol=EXACT),
    "checks.symmetry_defect_eq8": Entry(tol=ROUNDOFF, glue="ev_sym_eq8"),
    "eq8.half_thx_t1d2": Entry(tol=EXACT, glue="eq8_half"),
    "beam.fe_over_theory": Entry(tol=FE_OVER_THEORY),
    "beam.worst_pct": Entry(tol=FE_OVER_THEORY_PCT, glue="beam_worst"),
    "beam.elements_across": Entry(tol=EXACT, glue={"beam_n_lo": 0, "beam_n_hi": 1}),
    # --- mesh and element convergence
    "mesh.settings": Entry(tol=EXACT, glue={"beam_aspect": 0, "mid_widths": 1, "coarse_widths": 2}),
    "convergence.q2_chosen_vs_next_pct": Entry(tol=MESH_CHANGE_PCT, glue="conv_next"),
    "convergence.q2_chosen_vs_finest_pct": Entry(tol=MESH_CHANGE_PCT, glue="conv_finest"),
    "convergence.q2_coarse_region_pct": Entry(tol=MESH_CHANGE_PCT, glue="conv_coarse"),
    "convergence.shell_vs_q2_pct": Entry(tol=MESH_CHANGE_PCT, glue="shell_vs_q2"),
    # the largest change of the four magnitudes at each flexure refinement (as many as the study's
    # refinements: a list in the prose)
    "convergence.steps_pct": Entry(tol=MESH_CHANGE_PCT, texts={"conv_steps": _listed}),
    # the fit's worst miss plus the larger change of refining the flexures or the free region
    "convergence.compliance_band_pct": Entry(tol=MESH_CHANGE_PCT, glue="compliance_band"),
    # --- figures 3, 4, 5 and 8
    "inverse.roundtrip": Entry(
        tol=FE_DEFECT,
        glue="roundtrip",
        rows=report.Computed(
            "Fig 3", "largest |FE pose − requested pose| of the six unit motions [µm, µrad]"
        ),
    ),
    "fig4.actuator_directions": Entry(
        tol=UNIT_VECTORS,
        rows=report.Computed("Fig 4", "unit actuator directions (x, y, z) of T1D1 … T3D2"),
    ),
    "fig5.mesh": Entry(
        tol=EXACT,
        rows=report.Computed("Fig 5", "free DOFs of the whole model; quads of the meshed sixth"),
    ),
    "fig8.pose": Entry(
        tol=FE_IDENTIFIED_PEAK,
        rows=report.Computed("Fig 8", "stage pose of the drawn shape (x, y, z [µm], θ [µrad])"),
    ),
    "inverse.roundtrip_below_1e-6": Entry(tol=EXACT),
}
