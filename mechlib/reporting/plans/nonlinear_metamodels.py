"""Record plan of "Meta-models of the non-linear HexFlex" (``notebooks/nonlinear_metamodels``):
every key the notebook records, with its tolerance, glue and report rows.

Every number of the page goes beyond the thesis: its rows are computed values, without a
published one to compare with.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from mechlib.hexflex.studies.leanmesh import FIT_TOL
from mechlib.reporting import report
from mechlib.reporting.recordplan import Entry, Extremes
from mechlib.reporting.tolerances import (
    EXACT,
    MULTIMODAL_FIT,
    NONLINEAR_FE,
    NONLINEAR_FE_FINE,
    NONLINEAR_FE_REL,
)

ARTEFACT = "Beyond the thesis: meta-models of the non-linear HexFlex"


def _compared_row(context: Mapping[str, Any]) -> list[report.RowSpec]:
    return [
        report.Computed(
            ARTEFACT,
            f"largest error over {context['n_val']} held-out non-linear runs at ±1 N [% of full "
            "scale, worst component], per model",
            labels=tuple(context["names"]),
        )
    ]


def _distilled_row(context: Mapping[str, Any]) -> list[report.RowSpec]:
    return [
        report.Computed(
            ARTEFACT,
            f"the distilled real-time model: largest error over {context['n_val']} held-out "
            "non-linear runs at ±1 N [% of full scale, worst component]",
        )
    ]


def _last(name: str) -> Callable[[Any], dict[str, int]]:
    """Glue ``name`` to the last element (stored as its positive index)."""
    return lambda value: {name: len(value) - 1}


def _best_model(worst: Any, context: Mapping[str, Any]) -> str:
    """The model the page chose as best (context: ``best``, the one its inverse uses)."""
    return str(context["best"])


def _mesh_words(n_dofs: Any, context: Mapping[str, Any]) -> str:
    """The mesh of the non-linear runs, in words (by the page's ``nonlinear_mesh``)."""
    if context["mesh"] == "lean":
        return (
            "the lean mesh of the family page, its free dimensions fitted to the model page's "
            f"model's four compliance magnitudes within {100 * FIT_TOL:g} %"
        )
    return "the model page's mesh"


PLAN: dict[str, Entry] = {
    # --- parameters and the non-linear model -------------------------------------------------
    "parameters.validation_runs": Entry(tol=EXACT),
    "model.nonlinear_n_dofs": Entry(tol=EXACT, glue="nl_n_dofs", texts={"nl_mesh": _mesh_words}),
    "parameters.rom_pod": Entry(tol=EXACT, glue="rom_pod"),
    "parameters.training_runs": Entry(
        tol=EXACT,
        glue={"n_train_max": -1},
        texts={"train_sizes": lambda sizes: ", ".join(str(n) for n in sizes)},
    ),
    "parameters.budget_amplitudes": Entry(
        tol=EXACT,  # the smaller ranges (the last is ±1 N)
        texts={"budget_amps": lambda amps: " and ".join(f"±{a:g}" for a in amps[:-1])},
    ),
    "parameters.budget_runs": Entry(tol=EXACT, glue={"n_budget_train": 0, "n_budget_val": 1}),
    "parameters.budget_pct": Entry(tol=EXACT, glue="budget"),
    "parameters.deadline_us": Entry(
        tol=EXACT, glue="deadline", texts={"loop_rate": lambda us: f"{1e3 / us:.3g} kHz"}
    ),
    "parameters.goals": Entry(tol=EXACT, glue={"goal_pct": 0}),
    "parameters.distill_degrees": Entry(tol=EXACT),
    # --- the full non-linear runs ------------------------------------------------------------
    "truth.failed_runs": Entry(tol=EXACT, glue="n_failed"),
    "truth.validation_asked": Entry(tol=EXACT, glue="n_val_asked"),
    "truth.converged_runs": Entry(tol=EXACT),
    "rom.basis_and_elements": Entry(tol=EXACT, glue={"rom_basis": 0, "rom_elements": 1}),
    # --- the meta-models compared at ±1 N ----------------------------------------------------
    "compare.max_range_pct": Entry(tol=NONLINEAR_FE),
    "compare.rmse": Entry(tol=NONLINEAR_FE_FINE),
    # S_T and Eq 6 first, the reduced-order model last
    "compare.worst_pct": Entry(
        tol=NONLINEAR_FE,
        glue=(
            Extremes(low="worst_best", fixed={"worst_st": 0, "worst_eq6": 1}),
            _last("worst_rom"),
        ),
        rows=_compared_row,
        texts={"best_model": _best_model},
    ),
    "compare.cv_worst_pct": Entry(tol=NONLINEAR_FE),  # the fitted models
    "compare.training_runs": Entry(tol=EXACT, glue=_last("n_rom_runs")),
    "compare.validation_runs": Entry(tol=EXACT, glue="n_val"),
    "curves.fitted": Entry(tol=EXACT),
    "curves.worst_pct": Entry(tol=NONLINEAR_FE),  # 0 where not fitted
    "budget.fitted": Entry(tol=EXACT),
    "budget.worst_pct": Entry(tol=NONLINEAR_FE),  # 0 where not fitted
    "budget.largest_range_n": Entry(tol=EXACT),
    # --- the inverse for control -------------------------------------------------------------
    "inverse.targets": Entry(tol=EXACT, glue="n_inv"),
    "inverse.margin_n": Entry(tol=EXACT, glue="inv_margin"),
    "inverse.force_resolution_n": Entry(tol=EXACT, glue="inv_resolution"),
    "inverse.not_converged": Entry(tol=EXACT, glue={"inv_nc_st": 0, "inv_nc_best": 1}),
    "inverse.failed_runs": Entry(tol=EXACT),
    "inverse.round_trip_pct": Entry(
        tol=NONLINEAR_FE,
        # the largest miss through S_T's inverse (row 0) and through the best model's (row 1)
        glue=(Extremes(row=0, high="inv_st"), Extremes(row=1, high="inv_best")),
        rows=report.Computed(
            ARTEFACT,
            "pose reached by the full non-linear FE under the inverse's forces, largest error "
            "vs the target [% of full scale], linear S_T and the best model",
        ),
    ),
    # --- real time -----------------------------------------------------------------------------
    "realtime.within_budget": Entry(tol=EXACT),
    "realtime.dwr_direct_worst_pct": Entry(tol=NONLINEAR_FE, glue="rt_dwr_direct"),
    "realtime.curve_runs": Entry(tol=EXACT),
    # 5e-6 of themselves apart across OpenBLAS's Haswell, Sandybridge and SkylakeX kernels
    "realtime.corrected_curve_pct": Entry(
        tol=NONLINEAR_FE, glue={"rt_corr_first": 0, "rt_corr_last": -1}
    ),
    # its likelihood has many optima: 30 % (see the class); the other curves hold to 1e-3
    "realtime.indicator_curve_pct": Entry(
        tol=MULTIMODAL_FIT, glue={"rt_ind_first": 0, "rt_ind_last": -1}
    ),
    "realtime.indicator_correlation": Entry(
        tol=NONLINEAR_FE, glue=Extremes(low="rt_dwr_corr_min", high="rt_dwr_corr_max")
    ),
    "realtime.newton_runs": Entry(tol=EXACT, glue="rt_newton_runs"),
    "realtime.newton_step_worst_pct": Entry(
        tol=NONLINEAR_FE, glue={"rt_newton_rom": 0, "rt_newton": 1}
    ),
    "realtime.gp_curve_pct": Entry(tol=NONLINEAR_FE, glue={"rt_gp_first": 0, "rt_gp_last": -1}),
    "realtime.curve_first_runs": Entry(tol=EXACT, glue="rt_n_first"),
    "realtime.curve_last_runs": Entry(tol=EXACT, glue="rt_n_last"),
    "realtime.teacher_cv_pct": Entry(tol=NONLINEAR_FE),
    "realtime.folds": Entry(tol=EXACT, glue="rt_folds"),
    "realtime.samples": Entry(tol=EXACT, glue={"rt_samples": 0, "rt_check": 1}),
    "realtime.distill_tol_pct": Entry(tol=NONLINEAR_FE_REL, glue="rt_distill_tol"),
    "realtime.distill_degrees_tried": Entry(tol=EXACT),
    "realtime.distill_error_pct": Entry(tol=NONLINEAR_FE),
    # exact: it would move only if a distillation error lay within round-off of its tolerance
    "realtime.best.degree": Entry(tol=EXACT, glue="rt_degree"),
    "realtime.best.terms": Entry(tol=EXACT, glue="rt_terms"),
    "realtime.worst_pct": Entry(tol=NONLINEAR_FE),
    "realtime.rmse_pct": Entry(tol=NONLINEAR_FE),
    "realtime.full_runs": Entry(tol=EXACT, glue={"rt_runs": 2}),
    "realtime.best.worst_pct": Entry(tol=NONLINEAR_FE, glue="rt_worst", rows=_distilled_row),
    "realtime.best.small_range_amplitudes_n": Entry(tol=EXACT),
    "realtime.best.small_range_worst_pct": Entry(tol=NONLINEAR_FE),
    "realtime.inverse.not_converged": Entry(tol=EXACT, glue="rt_inv_nc"),
    "realtime.inverse.failed_runs": Entry(tol=EXACT, glue="rt_inv_failed"),
    "realtime.inverse.round_trip_pct": Entry(tol=NONLINEAR_FE, glue=Extremes(high="rt_inv")),
}

#: the data kept for the book's bundle: a file's one-line description
DATA = {
    "learning_curves": lambda c: (
        f"learning curves at ±1 N: worst error over {c['n_val']} held-out non-linear runs, % of "
        "each pose component's largest |value|, worst component, per family and training size "
        "(empty: too few runs to fit)"
    ),
    "realtime_curves": lambda c: (
        f"the real-time section's learning curves: worst error over {c['n_val']} held-out runs "
        "at ±1 N, % of each component's largest |value|, worst component"
    ),
    "realtime_model": "the real-time model (distilled polynomial) as coefficients, with its "
    "validation and check values; evaluator.py evaluates it in plain Python",
}

#: the timings (machine-dependent, not compared) and their glue names
TIMINGS = {
    "realtime.best.single_us": "rt_single_us",
    "realtime.best.batched_us": "rt_batched_us",
}

#: why the texts quoting timings (or chosen by them) are not checked: a reason they share
TIMED = "a timing on the machine that built the page (not recorded)"
#: the texts not checked, by glue name, and why
UNCHECKED = dict.fromkeys(
    (
        "rom_build_s",
        "full_run_s",
        "realtime_ok",
        "rom_us",
        "rom_ratio",
        "rt_dwr_ms",
        "rt_newton_s",
        "rt_newton_share",
    ),
    TIMED,
)
