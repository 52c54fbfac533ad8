"""The claims of the thesis the book judges: chapter 2's on the HexFlex, chapter 3's on the 5R.

Chapter 2's are its headline statements (secs. 2.6.4–2.7), judged on the thesis's own yardsticks
where it states them (Table 5's ISO h6 tolerance and P. A. Petri's 3 %), else on one stated here
(:data:`NEGLIGIBLE_RATIO`, :data:`LINEAR_BUDGET_PCT`, :data:`CONTROL_PERIOD_US`). Each of the
first three has a part on a linear FE model, where it holds by construction (shown, not counted),
and the part that could fail, on a geometrically non-linear model: its word is that part's, and
its setting says so. Chapter 2 also claims its method general enough for distributed compliance
(judged on the parallelogram flexure) and infers from its screening that interactions are
negligible. Chapter 3's, on the 5R, are in :mod:`mechlib.reporting.calibrationclaims`. Registered
in :mod:`mechlib.reporting.claimlist`.
"""

from __future__ import annotations

from mechlib import published as pub
from mechlib.doe import UNIFORM_SHARE_MAX
from mechlib.metamodels.metrics import FULL_SCALE, SOLVER_PRECISION_PCT
from mechlib.metamodels.realtime import DEADLINE_US
from mechlib.reporting import categories as cat
from mechlib.reporting.calibrationclaims import BUDGETS_5R, chapter3_claims
from mechlib.reporting.claimrules import (
    at_most,
    is_true,
    timed_below,
    with_construction,
    within,
)
from mechlib.reporting.claims import ClaimSpec

__all__ = ["BUDGETS_5R", "CONTROL_PERIOD_US", "UNTESTABLE", "thesis_claims"]

THESIS = cat.SOURCE_THESIS
#: the pages whose records the claims read
VX, DOE, FB = "virtual_experiments", "published_doe", "fivebar_identification"
PF = "parallelogram_fe"
#: claims of the thesis that no computation of this book can test, and why
UNTESTABLE = (
    (
        "sec. 2.4.4 item 3",
        "real experimentation is replaced by computer simulations, reducing costs in product "
        "development",
        "there is no physical HexFlex, no measurement and no cost to compare with here",
    ),
)

#: a second-order term of Eq 6 is "negligible" below this share of the largest linear one (ours)
NEGLIGIBLE_RATIO = 0.01
#: a linear model is "linear enough" while its worst error stays within this many % of full
#: scale (:data:`mechlib.metamodels.metrics.FULL_SCALE`; the meta-model page's accuracy budget)
LINEAR_BUDGET_PCT = 1.0
#: the book's one real-time deadline, the period of a 10 kHz control loop [µs]
#: (:data:`mechlib.metamodels.realtime.DEADLINE_US`, where its reason is given)
CONTROL_PERIOD_US = DEADLINE_US

#: why a part on the linear FE model cannot fail
LINEAR_BY_CONSTRUCTION = "a linear FE model is linear, and S_T is fitted to it"
#: the setting of a chapter-2 claim tested on the non-linear model
_NONLINEAR_SETTING = (
    "on a geometrically non-linear FE model with Eq 8's compliance (dead loads), {n:.0f} random "
    "runs at ±1 N; true only by construction on a linear FE model"
)


def _chapter2() -> list[ClaimSpec]:
    linear_fe = "on a linear FE model (the thesis's analysis)"
    nonlinear_fe = "on the non-linear FE model"  # the setting names it in full
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
                    ),
                    LINEAR_BY_CONSTRUCTION,
                ),
                at_most(
                    nonlinear_fe,
                    "table5.nonlinear.max_range_pct",
                    LINEAR_BUDGET_PCT,
                    FULL_SCALE,
                    "the linear meta-model's worst error",
                ),
            ),
            _NONLINEAR_SETTING,
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
                    ),
                    LINEAR_BY_CONSTRUCTION,
                ),
                at_most(
                    "Eq 6 fitted to Table 4's runs on the non-linear FE model",
                    "nl_designs.eq6_second_order_over_linear",
                    NEGLIGIBLE_RATIO,
                    "× the largest linear coefficient",
                    "largest second-order term",
                ),
            ),
            "Eq 6 fitted to Table 4's 30 runs solved on a geometrically non-linear FE model with "
            "Eq 8's compliance (dead loads); true only by construction on a linear FE model",
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
                    ),
                    LINEAR_BY_CONSTRUCTION,
                ),
                with_construction(
                    at_most(
                        f"{linear_fe}, relative error",
                        "table5.linear.max_rel_pct",
                        pub.TABLE5_PETRI_REL_ERROR_PCT,
                        "%",
                        "largest pointwise",
                    ),
                    LINEAR_BY_CONSTRUCTION,
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
                    FULL_SCALE,
                    "worst",
                ),
            ),
            _NONLINEAR_SETTING,
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
            "ch2.pb_interactions",
            THESIS,
            "sec. 2.6.4; Table 2; Eq 6",
            "from the Plackett–Burman analysis it is evident that interactions are not important "
            "and could be neglected from Eq 6",
            VX,
            (
                with_construction(
                    at_most(
                        "Eq 6 fitted to Table 4's runs on the linear FE model, all second-order "
                        "terms",
                        "s_t.quadratic_terms_over_linear",
                        NEGLIGIBLE_RATIO,
                        "× the largest linear coefficient",
                        "largest",
                    ),
                    LINEAR_BY_CONSTRUCTION,
                ),
                at_most(
                    "Eq 6 fitted to Table 4's runs on the non-linear FE model, interaction terms",
                    "nl_designs.eq6_interactions_over_linear",
                    NEGLIGIBLE_RATIO,
                    "× the largest linear coefficient",
                    "largest",
                ),
            ),
            "Eq 6 fitted to Table 4's 30 runs solved on a geometrically non-linear FE model with "
            "Eq 8's compliance (dead loads); true only by construction on a linear FE model, and "
            "Table 2's 12-run design aliases interactions with main effects whatever the runs "
            "give",
        ),
        ClaimSpec(
            "ch2.generality",
            THESIS,
            "sec. 2.4.4 item 1; Fig 1",
            "the methodology is general enough to cover both lumped and distributed compliant "
            "mechanisms",
            PF,
            (
                within(
                    "the thesis's linear meta-model S_T (Eq 7), fitted on a uniform design, on "
                    "held-out FE runs",
                    "method.st_worst_pct",
                    "method.goal_pct",
                    FULL_SCALE,
                    "worst error",
                ),
                within(
                    "the thesis's second-order meta-model (Eq 6), fitted on the same design",
                    "method.eq6_worst_pct",
                    "method.goal_pct",
                    FULL_SCALE,
                    "worst error",
                ),
            ),
            "on a distributed compliant mechanism, the parallelogram flexure in our non-linear "
            "FE, over its benchmark's load box |A_x| ≤ {ax:g}, |A_y| ≤ {ay:g}, |B| ≤ {b:g}; "
            "lumped mechanisms are not tested",
            {
                "ax": ("method.box_and_design", 0),
                "ay": ("method.box_and_design", 1),
                "b": ("method.box_and_design", 2),
            },
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


def thesis_claims() -> list[ClaimSpec]:
    """The thesis's claims, chapter 2's then chapter 3's."""
    return [*_chapter2(), *chapter3_claims()]
