"""The claims of the thesis the book judges: chapter 2's on the HexFlex, chapter 3's on the 5R.

Chapter 2's are its headline statements (secs. 2.6.4–2.7), judged on the thesis's own yardsticks
where it states them (Table 5's ISO h6 tolerance and P. A. Petri's 3 %), else on one stated here
(:data:`NEGLIGIBLE_RATIO`, :data:`LINEAR_BUDGET_PCT`, :data:`CONTROL_PERIOD_US`); each has a part
on a linear FE model, where it holds by construction, and one on a geometrically non-linear model.
Chapter 3's are the three advantages sec. 3.8 claims for divide and conquer (D&C), each judged on
the 5R at every budget the thesis gives the traditional method (:data:`BUDGETS_5R`). Registered in
:mod:`mechlib.reporting.claimlist`.
"""

from __future__ import annotations

from mechlib import published as pub
from mechlib.doe import UNIFORM_SHARE_MAX
from mechlib.metamodels.metrics import SOLVER_PRECISION_PCT
from mechlib.reporting import categories as cat
from mechlib.reporting.claims import (
    ClaimSpec,
    at_most,
    exceeds,
    greater,
    is_true,
    paired,
    timed_below,
    with_construction,
)

THESIS = cat.SOURCE_THESIS
#: the pages whose records the claims read
VX, DOE, FB = "virtual_experiments", "published_doe", "fivebar_identification"

#: a second-order term of Eq 6 is "negligible" below this share of the largest linear one (ours)
NEGLIGIBLE_RATIO = 0.01
#: a linear model is "linear enough" while its worst error stays within this share of each pose
#: component's range (the meta-model page's accuracy budget)
LINEAR_BUDGET_PCT = 1.0
#: the period of a 10 kHz control loop, which a real-time model must evaluate well within [µs]
#: (piezo-driven nano-positioners are commonly controlled at 10–50 kHz)
CONTROL_PERIOD_US = 100.0

_RUNS = "{n:.0f} random runs at ±1 N"


def _chapter2() -> list[ClaimSpec]:
    linear_fe = "on a linear FE model (the thesis's analysis)"
    nonlinear_fe = "on a geometrically non-linear FE model with Eq 8's compliance (dead loads)"
    return [
        ClaimSpec(
            "ch2.linear",
            THESIS,
            "sec. 2.7; Table 5",
            "the HexFlex is linear for its range of movement (±1 N at each tab)",
            VX,
            (
                with_construction(
                    at_most(
                        linear_fe,
                        "table5.linear.max_rel_pct",
                        SOLVER_PRECISION_PCT,
                        "%",
                        "the linear meta-model's largest pointwise error",
                    )
                ),
                at_most(
                    nonlinear_fe,
                    "table5.nonlinear.max_range_pct",
                    LINEAR_BUDGET_PCT,
                    "% of range",
                    "the linear meta-model's worst error",
                ),
            ),
            _RUNS,
            {"n": "table5.nonlinear.converged_runs"},
        ),
        ClaimSpec(
            "ch2.eq6",
            THESIS,
            "sec. 2.6.4; Eq 6",
            "the quadratic and interaction terms of Eq 6 are negligible",
            VX,
            (
                with_construction(
                    at_most(
                        "Eq 6 fitted to Table 4's runs on the linear FE model",
                        "s_t.quadratic_terms_over_linear",
                        NEGLIGIBLE_RATIO,
                        "× the largest linear coefficient",
                        "largest second-order term",
                    )
                ),
                at_most(
                    "Eq 6 fitted to Table 4's runs on the geometrically non-linear FE model",
                    "nl_designs.eq6_second_order_over_linear",
                    NEGLIGIBLE_RATIO,
                    "× the largest linear coefficient",
                    "largest second-order term",
                ),
            ),
        ),
        ClaimSpec(
            "ch2.table5",
            THESIS,
            "sec. 2.7; Table 5",
            "the linear meta-model S_T is accurate: its largest absolute error is within an ISO h6 "
            "tolerance and its relative error below the 3 % of P. A. Petri's beam model",
            VX,
            (
                with_construction(
                    at_most(
                        f"{linear_fe}, MAXABS of x, y, z",
                        ("table5.linear.maxabs_rmse", (slice(0, 3), 0)),
                        pub.TABLE5_ACCEPTABLE_MAXABS_UM,
                        "µm",
                    )
                ),
                with_construction(
                    at_most(
                        f"{linear_fe}, relative error",
                        "table5.linear.max_rel_pct",
                        pub.TABLE5_PETRI_REL_ERROR_PCT,
                        "%",
                        "largest pointwise",
                    )
                ),
                at_most(
                    f"{nonlinear_fe}, MAXABS of x, y, z",
                    ("table5.nonlinear.maxabs", slice(0, 3)),
                    pub.TABLE5_ACCEPTABLE_MAXABS_UM,
                    "µm",
                ),
                at_most(
                    f"{nonlinear_fe}, error",
                    "table5.nonlinear.max_range_pct",
                    pub.TABLE5_PETRI_REL_ERROR_PCT,
                    "% of range",
                    "worst",
                ),
            ),
            _RUNS,
            {"n": "table5.nonlinear.converged_runs"},
        ),
        ClaimSpec(
            "ch2.realtime",
            THESIS,
            "secs. 2.5, 2.7; Eq 7",
            "the linear meta-model is simple enough for real-time control",
            VX,
            (
                timed_below(
                    "one forward evaluation of S_T (a 6 × 6 matrix times the forces), against a "
                    f"{1e3 / CONTROL_PERIOD_US:g} kHz control loop's period",
                    "latency.st_forward_us",
                    CONTROL_PERIOD_US,
                    "µs",
                ),
            ),
        ),
        ClaimSpec(
            "ch2.table4_uniform",
            THESIS,
            "sec. 2.6.3; Table 4",
            "the design of Table 4 is a uniform (low-discrepancy) design",
            DOE,
            (
                is_true("each level equally often in each column", "table4.balanced", "balanced"),
                at_most(
                    "random balanced designs of its size at least as uniform (centred L2 "
                    "discrepancy)",
                    "table4.share_random_at_least_as_uniform",
                    UNIFORM_SHARE_MAX,
                    "",
                    "share",
                    strict=True,
                ),
            ),
        ),
    ]


#: chapter 3's budgets for the traditional method: record prefix, and how the verdict names it
BUDGETS_5R = (
    ("item10", "sec. 3.7 item 10's budget"),
    ("table8", "Table 8's printed budget"),
    ("equal", "equal measurements"),
)


def _chapter3() -> list[ClaimSpec]:
    specs = []
    for budget, name in BUDGETS_5R:
        mc = f"mc_{budget}"
        setting = f"{name}: {{n:.0f}} shared postures, {{trad:.0f}} against {{dc:.0f}} measurements"
        refs = {
            "n": f"{mc}.n_shared",
            "trad": (f"{mc}.measurements", 1),
            "dc": (f"{mc}.measurements", 0),
        }
        specs += [
            ClaimSpec(
                f"ch3.i.5r.{budget}",
                THESIS,
                "sec. 3.8 (i); Tables 6, 8",
                "(i) divide and conquer has a lower computational cost",
                FB,
                (
                    exceeds(
                        "normal-matrix inversion flops, traditional / D&C",
                        "table6.inversion_cost_ratio",
                        1.0,
                        "ratio",
                    ),
                ),
                setting,
                refs,
            ),
            ClaimSpec(
                f"ch3.ii.5r.{budget}",
                THESIS,
                "sec. 3.8 (ii); Tables 6, 8",
                "(ii) divide and conquer has a better numerical efficiency (conditioning of the "
                "identification matrices)",
                FB,
                (
                    greater(
                        "inverse condition number of the column-scaled identification matrix",
                        (f"{mc}.cond", 0),
                        (f"{mc}.cond", 1),
                        ("D&C's worst leg", "the traditional total matrix"),
                    ),
                ),
                setting,
                refs,
            ),
            ClaimSpec(
                f"ch3.iii.5r.{budget}",
                THESIS,
                "sec. 3.8 (iii); Figs 13–14",
                "(iii) divide and conquer gives better identification results",
                FB,
                (
                    paired(
                        "parameter RMS error", f"{mc}.param_share_dc_better", f"{mc}.param_p_value"
                    ),
                    paired(
                        "workspace RMS position error", f"{mc}.share_dc_better", f"{mc}.p_value"
                    ),
                ),
                setting,
                refs,
            ),
        ]
    return specs


def thesis_claims() -> list[ClaimSpec]:
    """The thesis's claims, chapter 2's then chapter 3's."""
    return [*_chapter2(), *_chapter3()]
