"""Record plan of "The DOE chapter re-run: virtual experiments on our SfePy HexFlex"
(``notebooks/virtual_experiments.ipynb``): every key the notebook records, with its tolerance,
glue and report rows (those made from the values: :mod:`._virtual_experiments_rows`)."""

from __future__ import annotations

from dataclasses import replace

from mechlib import published as pub
from mechlib.reporting import report
from mechlib.reporting.plans import Entry, Extremes
from mechlib.reporting.plans import _virtual_experiments_rows as made
from mechlib.reporting.tolerances import (
    CLOSED_FORM,
    EXACT,
    FE_FIT_RESIDUE,
    FE_LINEAR,
    FE_LINEAR_REL,
    FE_ROUNDOFF_PCT,
    FE_ROUNDOFF_RESPONSE,
    GAUSSIAN_PROCESS,
    INVERSE_RESIDUE,
    NONLINEAR_FE,
    NONLINEAR_FE_PCT,
    NONLINEAR_FE_PEAK,
    NONLINEAR_FE_RATIO,
    NONLINEAR_FE_REL,
    PENALIZED_FIT,
    POSE_ROUND_TRIP,
)

R = pub.RESPONSES
#: the artefacts of our own findings, beyond the thesis
NL_DESIGNS = "Beyond the thesis: Eq 6 on non-linear runs"
PARITY = "Beyond the thesis: sources of the departure"

#: the keys every run records
_ALWAYS: dict[str, Entry] = {
    # --- the model ---
    "model.n_dofs": Entry(tol=EXACT, glue="n_dofs"),
    "model.mesh_fraction": Entry(tol=EXACT, glue="mesh_fraction"),
    # context: ``mesh``, the parameter; ``fit_tol``, the lean stand-in's fitting tolerance
    "model.nonlinear_n_dofs": Entry(
        tol=EXACT, glue="nl_n_dofs", texts={"nl_mesh_text": made.nonlinear_mesh_text}
    ),
    # --- Tables 2 and 3 ---
    # context: ``ratio``, ours / published per response
    "table2.responses": Entry(
        tol=FE_LINEAR,
        rows=made.responses_rows(
            "Table 2",
            "responses on our FE model (µm, µrad; published in nm, mrad converted)",
            pub.table2_responses_um_urad(),
        ),
    ),
    "table2.ours_over_published": Entry(tol=FE_LINEAR_REL),
    "table3.effects": Entry(tol=FE_LINEAR),
    # Lenth's margin, its round-off floor that of the effects it is made of (context: ``eff``)
    "table3.me": Entry(tol=lambda c: FE_LINEAR.scaled(c["eff"])),
    "table3.dominant": Entry(tol=EXACT),
    "table3.same_dominant_as_published": Entry(
        tol=EXACT,
        rows=made.same_dominant_rows,
        texts={"same_dominant": lambda same: "the same" if same else "not the same"},
    ),
    # --- Table 4 and S_T ---
    "table4.responses": Entry(
        tol=FE_LINEAR,
        rows=made.responses_rows(
            "Table 4", "responses on our FE model (µm, µrad)", pub.TABLE4_RESPONSES
        ),
    ),
    "s_t.ols_vs_exact": Entry(tol=FE_FIT_RESIDUE, glue="ols_dev"),
    "s_t.penalized_vs_exact": Entry(tol=PENALIZED_FIT, glue="pen_dev"),
    "s_t.quadratic_terms_over_linear": Entry(tol=FE_FIT_RESIDUE, glue="second_order"),
    # S_T, its round-off floor that of the exact compliance (context: ``exact``; ``misfit``,
    # the entry ratios ours / Eq 8)
    "s_t.ols": Entry(tol=lambda c: FE_LINEAR.scaled(c["exact"]), rows=made.s_t_rows),
    "s_t.ols_over_eq8_range": Entry(tol=FE_LINEAR_REL, glue={"misfit_low": 0, "misfit_high": 1}),
    # --- Eq 9 ---
    "eq9.identity_error": Entry(tol=INVERSE_RESIDUE, glue="ident_err"),
    "eq9.round_trip": Entry(tol=POSE_ROUND_TRIP, glue="round_trip"),
    "eq9.cond_row_scaled": Entry(tol=FE_LINEAR_REL, glue="cond"),
    "eq9.exact_inverse": Entry(tol=EXACT, rows=made.exact_inverse_rows),
    # --- Table 5 (a): the linear FE model ---
    "table5.linear.max_rel_pct": Entry(tol=FE_ROUNDOFF_PCT, glue=Extremes(high="lin_max_rel")),
    "table5.linear.solver_precision": Entry(tol=EXACT, rows=made.solver_precision_rows),
    "table5.solver_precision_pct": Entry(tol=EXACT, glue="solver_pct"),
    "table5.published_worst_rel_pct": Entry(tol=EXACT, glue="pub_t5_max"),
    "table5.published_maxabs_over_range_pct": Entry(
        tol=FE_LINEAR_REL, glue=Extremes(low="pub_range_lo", high="pub_range_hi")
    ),
    # MAXABS and RMSE, round-off of the linear runs' responses (context: ``fe``, those responses;
    # ``m``, the error metrics)
    "table5.linear.maxabs_rmse": Entry(
        tol=lambda c: FE_ROUNDOFF_RESPONSE.scaled(c["fe"]), rows=made.maxabs_rmse_rows
    ),
    # --- Table 5 (b): the non-linear FE model ---
    "parameters.nonlinear_runs": Entry(tol=EXACT, glue="n_nl"),
    "parameters.seed": Entry(tol=EXACT),
    "eq8.published_thx_t1d2_mrad": Entry(tol=EXACT, glue="eq8_thx_mrad"),
    "table5.nonlinear.failed_runs": Entry(tol=EXACT, glue="n_nl_failed"),
    "table5.nonlinear.converged_runs": Entry(tol=EXACT, glue="n_nl_used"),
    # --- the linear range ---
    # the component with the largest error at the largest amplitude
    "sweep.rel_pct": Entry(
        tol=NONLINEAR_FE, glue=Extremes(row=-1, labels=R, high_label="p_component")
    ),
    # context: ``amplitudes``
    "sweep.over_1pct": Entry(tol=EXACT, texts={"first_over": made.first_over}),
    # the error's power law between amplitudes (context: ``rel_pct``, the sweep's errors)
    "sweep.exponent": Entry(
        tol=NONLINEAR_FE,
        glue=(
            Extremes(low="p_lo", high="p_hi"),
            Extremes(row=0, high="p0_max", labels=R, high_label="p0_component"),
            made.at_worst,
        ),
    ),
    "table2.pb_interaction_aliasing": Entry(
        tol=CLOSED_FORM,
        glue="pb_alias",
        rows=report.Computed(
            "Table 2",
            "largest |correlation| between a two-factor interaction and another factor's main "
            "effect in Table 2's 12-run design (0 for a resolution IV design)",
        ),
    ),
    # --- the elastica check of the non-linear solver ---
    "parameters.elastica_loads": Entry(
        tol=EXACT, texts={"el_alphas": lambda loads: ", ".join(f"{a:g}" for a in loads)}
    ),
    "elastica.beam_mm": Entry(tol=EXACT, glue={"el_length": 0, "el_side": 1}),
    "elastica.finest_max_abs_pct": Entry(
        tol=NONLINEAR_FE_PCT, glue={"el_obs_d": 0, "el_obs_s": 1, "el_obs_r": 2}
    ),
    "elastica.relative_pct": Entry(tol=NONLINEAR_FE_PCT),
    "elastica.tolerance_pct": Entry(tol=EXACT, glue={"el_tol_d": 0, "el_tol_s": 1, "el_tol_r": 2}),
    # --- surrogates and latency ---
    "parameters.n_validation": Entry(tol=EXACT, glue="n_val"),
    "surrogates.max_range_pct": Entry(tol=GAUSSIAN_PROCESS),
    "latency.control_period_us": Entry(tol=EXACT, glue={"control_us": 0, "control_khz": 1}),
    "table5.yardsticks": Entry(tol=EXACT, glue={"iso_h6_um": 0, "petri_pct": 1}),
}

#: the keys a parameter can switch off: ``nonlinear_runs = 0``, ``nonlinear_designs = False``
#: (or a design run that did not converge)
_SWITCHABLE: dict[str, Entry] = {
    "table5.nonlinear.max_rel_pct": Entry(
        tol=NONLINEAR_FE, glue=Extremes(high="nl_worst", labels=R, high_label="nl_worst_component")
    ),
    "table5.nonlinear.rmse": Entry(tol=NONLINEAR_FE),
    "table5.nonlinear.maxabs": Entry(tol=NONLINEAR_FE),
    "table5.nonlinear.maxabs_over_linear_range_pct": Entry(tol=NONLINEAR_FE),
    "table5.nonlinear.max_range_pct": Entry(
        tol=NONLINEAR_FE, glue=Extremes(low="nl_range_min", high="nl_worst_range")
    ),
    "table5.nonlinear.lift_over_thickness": Entry(tol=NONLINEAR_FE_REL, glue="nl_lift"),
    "table5.nonlinear.tilt_mrad": Entry(tol=NONLINEAR_FE_REL, glue="nl_tilt"),
    "table5.nonlinear.follower_share_pct": Entry(tol=NONLINEAR_FE_REL, glue="follower_pct"),
    "table5.nonlinear.orders_above_published": Entry(tol=EXACT, glue="nl_orders"),
    "table5.nonlinear.over_published": Entry(tol=NONLINEAR_FE_REL),
    "table5.max_rel_pct_linear_and_nonlinear": Entry(
        tol=NONLINEAR_FE, rows=made.table5_nonlinear_rows
    ),
    "table5.nonlinear.early_runs": Entry(tol=EXACT, glue="nl_k_early"),
    "table5.nonlinear.early_worst_pct": Entry(
        tol=NONLINEAR_FE, glue={"nl_rel_early": 0, "nl_range_early": 1}
    ),
    # --- the departure split by parity ---
    "parity.mirrored_runs": Entry(tol=EXACT, glue="n_mirror"),
    "parity.failed_runs": Entry(tol=EXACT, glue="n_mirror_failed"),
    **{
        f"parity.{part}_pct": Entry(
            tol=NONLINEAR_FE,
            glue=Extremes(
                low=f"{part}_min", high=f"{part}_max", labels=R, high_label=f"{part}_max_component"
            ),
            rows=report.Computed(
                PARITY,
                f"{part} ({order}) part of the non-linear departure from the linear model, "
                "largest over the mirrored runs [% of full scale]",
            ),
        )
        for part, order in (("even", "second-order"), ("odd", "third-order"))
    },
    "parity.even_share": Entry(
        tol=NONLINEAR_FE, glue=Extremes(low="even_share_min", high="even_share_max")
    ),
    # --- pose conventions ---
    # the largest differences, their round-off floor that of the poses (context: ``poses``)
    "pose.convention_max_abs": Entry(
        tol=lambda c: NONLINEAR_FE_PEAK.scaled(c["poses"]),
        glue={"conv_thz_small_rotvec": (0, 5), "conv_thz_rotvec_euler": (2, 5)},
        rows=report.Computed(
            "Beyond the thesis: pose convention",
            "largest difference between the small-rotation fit, the rotation vector and the "
            "Euler XYZ angles over the non-linear runs [µm, µrad]",
        ),
    ),
    "pose.convention_rel_pct": Entry(tol=NONLINEAR_FE),
    "pose.meta_error_by_convention_pct": Entry(
        tol=NONLINEAR_FE,
        glue={
            "meta_thz_small": (0, 5),
            "meta_thz_rotvec": (1, 5),
            "meta_thz_euler": (2, 5),
            "meta_thx_small": (0, 3),
            "meta_thx_rotvec": (1, 3),
            "meta_thy_small": (0, 4),
            "meta_thy_rotvec": (1, 4),
        },
    ),
    # --- the thesis's designs on the non-linear model ---
    "nl_designs.failed_runs": Entry(tol=EXACT, glue="nld_failed"),
    "nl_designs.table2_effects": Entry(tol=NONLINEAR_FE_PEAK),
    "nl_designs.table2_effect_change_pct": Entry(
        tol=NONLINEAR_FE_PCT,
        glue=Extremes(high="eff_change_max", labels=R, high_label="eff_change_component"),
    ),
    "nl_designs.table2_active_counts": Entry(tol=EXACT, glue={"n_active_lin": 0, "n_active_nl": 1}),
    "nl_designs.table2_new_dominant": Entry(tol=EXACT, texts={"new_dominant": made.new_factors}),
    # rows: the published Tables 2 and 4 against Eq 8, our non-linear Tables 2 and 4 runs
    # against our linear model
    "nl_designs.departure_pct": Entry(
        tol=NONLINEAR_FE,
        glue=(
            Extremes(row=0, high="dep_pub_t2"),
            Extremes(row=1, high="dep_pub_t4"),
            Extremes(
                row=3,
                low="dep_nl_t4_min",
                high="dep_nl_t4",
                labels=R,
                high_label="dep_nl_t4_component",
            ),
        ),
    ),
    "nl_designs.ours_over_table4": Entry(
        tol=NONLINEAR_FE_REL,
        glue=Extremes(
            low="ratio_lo",
            high="ratio_hi",
            labels=R,
            low_label="ratio_lo_component",
            high_label="ratio_hi_component",
        ),
    ),
    "nl_designs.eq6_second_order_over_linear": Entry(
        tol=NONLINEAR_FE_RATIO,
        glue=Extremes(low="second_nl_min", high="second_nl_max"),
        rows=report.Computed(
            NL_DESIGNS,
            "largest second-order coefficient over largest linear one, Eq 6 fitted to the "
            "non-linear Table 4 runs, per response",
        ),
    ),
    "nl_designs.eq6_interactions_over_linear": Entry(
        tol=NONLINEAR_FE_RATIO, glue=Extremes(high="inter_nl_max")
    ),
    # rows: linear S_T, the linear fit and Eq 6 fitted to the non-linear Table 4 runs
    "nl_designs.validation_max_range_pct": Entry(
        tol=NONLINEAR_FE,
        glue=(Extremes(row=2, high="eq6_nl_worst"), Extremes(row=0, high="st_nl_worst")),
        texts={
            "eq6_better": lambda scores: made.labels_where(scores[2] < scores[0]),
            "eq6_worse": lambda scores: made.labels_where(~(scores[2] < scores[0])),
        },
    ),
    "nl_designs.eq6_better_than_st": Entry(tol=EXACT),
}

PLAN: dict[str, Entry] = {
    **_ALWAYS,
    **{key: replace(entry, optional=True) for key, entry in _SWITCHABLE.items()},
}

#: the keys whose glue a run leaves out, by what switches them off (``Recorder.skipped``)
NL_VALIDATION = (
    "table5.nonlinear.max_rel_pct",
    "table5.nonlinear.max_range_pct",
    "table5.nonlinear.lift_over_thickness",
    "table5.nonlinear.tilt_mrad",
    "table5.nonlinear.follower_share_pct",
    "table5.nonlinear.orders_above_published",
)
NL_EARLY = ("table5.nonlinear.early_runs", "table5.nonlinear.early_worst_pct")
NL_PARITY = tuple(k for k in PLAN if k.startswith("parity."))
NL_POSE = ("pose.convention_max_abs", "pose.meta_error_by_convention_pct")
NL_SCREENING = ("nl_designs.table2_effect_change_pct", "nl_designs.table2_active_counts")
NL_NEW_DOMINANT = ("nl_designs.table2_new_dominant",)
NL_DEPARTURE = ("nl_designs.departure_pct", "nl_designs.ours_over_table4")
NL_VS_EQ6 = ("nl_designs.validation_max_range_pct",)
NL_EQ6 = (
    "nl_designs.eq6_second_order_over_linear",
    "nl_designs.eq6_interactions_over_linear",
    *NL_VS_EQ6,
)

#: the timings (machine-dependent, not compared) and their glue names
TIMINGS = {
    "latency.st_forward_us": "latency_one_us",
    "latency.fe_case_ms": "latency_fe_ms",
}
