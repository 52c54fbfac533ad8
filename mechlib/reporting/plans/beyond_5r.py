"""Record plan of "Beyond the 5R" (``notebooks/beyond_5r.ipynb``): every key the notebook
records, with its tolerance, glue and report rows."""

from __future__ import annotations

from mechlib import mechanism_catalog as catalog
from mechlib.calibration import statistics as cs
from mechlib.fivebar import mechanism as fivebar
from mechlib.mechanisms import gough_stewart, rrr3
from mechlib.reporting import report
from mechlib.reporting.plans import Entry
from mechlib.reporting.tolerances import (
    CLOSED_FORM,
    CONDITIONING,
    EXACT,
    ITERATIVE,
    ITERATIVE_ABS,
    MONTE_CARLO_RATIO,
    ROUNDOFF,
    SHARE_OF_TRIALS,
    SOLVER_NEAR_ZERO,
)

ARTEFACT = "Beyond the 5R"
#: the mechanisms (5R, 3-RRR, 6-UPS) and the traditional budgets, as the accuracy keys spell them
#: (``<mechanism>_<budget>.…``)
MECHANISMS = ("5r", "3rrr", "6ups")
BUDGETS = ("thesis", "matched")

#: one comparison of D&C with the traditional method (a mechanism, a budget): its keys
COMPARISON: dict[str, Entry] = {
    "pos_rms_um": Entry(tol=ITERATIVE),
    "param_rms": Entry(tol=ITERATIVE),
    "share_dc_better": Entry(tol=SHARE_OF_TRIALS),
    "p_value": Entry(tol=ITERATIVE),
    "param_share_dc_better": Entry(tol=SHARE_OF_TRIALS),
    "param_p_value": Entry(tol=ITERATIVE),
}

PLAN: dict[str, Entry] = {
    # the designs' constants (rec.constants())
    "design.dimensions_m": Entry(
        tol=EXACT,
        value=[
            *(rrr3.BASE_RADIUS, rrr3.PLATFORM_RADIUS, rrr3.PROXIMAL, rrr3.DISTAL),
            *(gough_stewart.BASE_RADIUS, gough_stewart.PLATFORM_RADIUS, gough_stewart.HOME_Z),
        ],
        glue={
            "design_rrr_base": 0,
            "design_rrr_platform": 1,
            "design_rrr_proximal": 2,
            "design_rrr_distal": 3,
            "design_ups_base": 4,
            "design_ups_platform": 5,
            "design_ups_height": 6,
        },
    ),
    "design.fivebar_miw_share_pct": Entry(
        tol=EXACT, glue="design_5r_pct", value=100 * catalog.FIVEBAR_FRACTION
    ),
    "design.fivebar_spacing_m": Entry(
        tol=EXACT,
        glue={"design_5r_spacing": 0, "design_5r_grid": 1},
        value=[fivebar.CANDIDATE_SPACING, fivebar.GRID_SPACING],
    ),
    "design.claim_max_p_pct": Entry(tol=EXACT, glue="claim_p_pct", value=100 * cs.CLAIM_MAX_P),
    "mechanisms.identifiable_rank": Entry(
        tol=EXACT,
        rows=report.Computed(
            ARTEFACT, "rank of each leg's identification matrix (5R, 3-RRR, 6-UPS)"
        ),
    ),
    "mechanisms.n_leg": Entry(tol=EXACT),
    "mechanisms.n_candidates": Entry(tol=EXACT),
    "budgets.shared": Entry(tol=EXACT),
    "postures.o1_dc_min": Entry(tol=ROUNDOFF),
    "parameters.index_trials": Entry(tol=EXACT, glue="index_trials_g"),
    "indices.pos_rms_um": Entry(tol=ITERATIVE),
    "indices.o1_best_count": Entry(tol=EXACT, glue="o1_best_count"),
    "indices.random_worst_count": Entry(tol=EXACT, glue="random_worst_count"),
    "indices.o1_best": Entry(tol=EXACT),
    "indices.o1_vs_o3": Entry(tol=ITERATIVE_ABS),
    "mc.all_converged": Entry(tol=EXACT),
    # two solvers stopping at the same least-squares solution: far below 1e-6
    "solvers.fivebar_lm_vs_gn_rel": Entry(tol=SOLVER_NEAR_ZERO, glue="solver_rel_gap"),
    "parameters.n_trials": Entry(tol=EXACT, glue="n_trials_g"),
    "parameters.n_trials_5r": Entry(tol=EXACT, glue="n_trials_5r_g"),
    **{
        f"{m}_{b}.{what}": (
            Entry(tol=entry.tol, glue=f"share_{m}_{b}") if what == "share_dc_better" else entry
        )
        for m in MECHANISMS
        for b in BUDGETS
        for what, entry in COMPARISON.items()
    },
    "maps.before_rms_um": Entry(tol=ROUNDOFF),
    "parameters.curve_trials": Entry(tol=EXACT, glue="curve_trials_g"),
    "curves.ratio": Entry(tol=MONTE_CARLO_RATIO),
    "curves.dc_wins_any": Entry(tol=EXACT),
    "curves.ratio_range": Entry(tol=ITERATIVE, glue={"curve_ratio_min": 0, "curve_ratio_max": 1}),
    "cost.measurement_penalty": Entry(
        tol=CLOSED_FORM,
        glue={"penalty_5r": 0, "penalty_3rrr": 1, "penalty_6ups": 2},
        rows=report.Computed(
            ARTEFACT,
            "measurements of D&C / traditional with equal equations per leg (5R, 3-RRR, 6-UPS)",
        ),
    ),
    "cost.flop_ratio": Entry(
        tol=EXACT,
        glue={"flop_5r": 0, "flop_3rrr": 1, "flop_6ups": 2},
        rows=report.Computed(
            ARTEFACT, "normal-matrix inversion flops, traditional / D&C (5R, 3-RRR, 6-UPS)"
        ),
    ),
    "cost.flop_law_holds": Entry(tol=EXACT),
    "cost.conditioning": Entry(tol=CONDITIONING),
    "cost.dc_better_conditioned": Entry(tol=EXACT),
}

#: the measured solve-time ratios, traditional / D&C (machine-dependent, not compared), glued
TIMINGS = {f"cost.time_ratio_{m}": f"time_ratio_{m}" for m in MECHANISMS}
