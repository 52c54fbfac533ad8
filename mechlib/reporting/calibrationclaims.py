"""The claims of the thesis's chapter 3 on the 5R: the three advantages sec. 3.8 claims for divide
and conquer (D&C), and the speed of the active calibration algorithm (sec. 4).

(i) is a flop count and (ii) a conditioning that the block-diagonal structure of the traditional
matrix settles, each judged once (no budget changes them: both are consistent by construction);
(iii) is judged at every budget the thesis gives the traditional method (:data:`BUDGETS_5R`).
Gathered with chapter 2's in :mod:`mechlib.reporting.thesisclaims`.
"""

from __future__ import annotations

from mechlib.reporting import categories as cat
from mechlib.reporting.claimrules import exceeds, is_true, paired, timed_below, with_construction
from mechlib.reporting.claims import ClaimSpec, Test

THESIS = cat.SOURCE_THESIS
#: the page whose records the claims read
FB = "fivebar_identification"
#: the active algorithm "affords more candidate poses" when it selects the same postures in at
#: most this share of the plain implementation's time (both measured on one machine)
ACTIVE_TIME_SHARE = 0.5

#: chapter 3's budgets for the traditional method: record prefix, and how the verdict names it
BUDGETS_5R = (
    ("item10", "sec. 3.7 item 10's budget"),
    ("table8", "Table 8's printed budget"),
    ("equal", "equal measurements"),
)


#: why (i) cannot fail: arithmetic on the parameter counts of Tables 6 and 8
FLOPS_BY_CONSTRUCTION = (
    "a count of operations from the parameter counts (on the 5R 12³ against 2 · 6³): for any "
    "split of n parameters into legs the legs' cubes sum to less than n³, so D&C's inversion is "
    "cheaper on every mechanism, and no posture, budget or measurement enters it"
)
#: why (ii), as measured, cannot fail
CONDITIONING_BY_CONSTRUCTION = (
    "over shared postures the traditional matrix is block diagonal, diag(C₁, C₂), so its "
    "conditioning is at best its worst leg's and the measure favours D&C by construction"
)


def _conditioning_at_every_budget() -> Test:
    """(ii)'s evidence at the three budgets: D&C's worst leg against the traditional matrix."""
    refs = tuple((f"mc_{budget}.cond", k) for budget, _ in BUDGETS_5R for k in (0, 1))
    names = [name for _, name in BUDGETS_5R]

    def rule(*c: float) -> bool:
        return all(float(c[2 * i]) > float(c[2 * i + 1]) for i in range(len(names)))

    def describe(*c: float) -> str:
        return "; ".join(
            f"{name}: D&C's worst leg {float(c[2 * i]):.3g} against the traditional total "
            f"matrix {float(c[2 * i + 1]):.3g}"
            for i, name in enumerate(names)
        )

    return with_construction(
        Test(
            "inverse condition number of the column-scaled identification matrix",
            refs,
            rule,
            describe,
            kind="greater at every budget",
        ),
        CONDITIONING_BY_CONSTRUCTION,
    )


def chapter3_claims() -> list[ClaimSpec]:
    """Chapter 3's claims on the 5R: (i), (ii), the active algorithm's speed, (iii) per budget."""
    specs = [
        ClaimSpec(
            "ch3.i.5r",
            THESIS,
            "sec. 3.8 (i); Tables 6, 8",
            "(i) divide and conquer has a lower computational cost",
            FB,
            (
                with_construction(
                    exceeds(
                        "normal-matrix inversion flops, traditional / D&C",
                        "table6.inversion_cost_ratio",
                        1.0,
                        "ratio",
                    ),
                    FLOPS_BY_CONSTRUCTION,
                ),
            ),
        ),
        ClaimSpec(
            "ch3.ii.5r",
            THESIS,
            "sec. 3.8 (ii); Tables 6, 8",
            "(ii) divide and conquer has a better numerical efficiency (conditioning of the "
            "identification matrices)",
            FB,
            (_conditioning_at_every_budget(),),
        ),
        ClaimSpec(
            "ch3.active_speed",
            THESIS,
            "sec. 4; Fig 9",
            "the active robot calibration algorithm reduces the cost of computing the "
            "observability index, allowing more candidate poses in the optimal pose search",
            FB,
            (
                is_true(
                    "the active algorithm and the plain one select the same postures",
                    "selection.active_same_as_plain",
                    "the same postures",
                ),
                timed_below(
                    "greedy selection of a leg's postures among the chapter's candidates: the "
                    "active algorithm's time over the plain SVD implementation's",
                    "selection.active_over_plain",
                    ACTIVE_TIME_SHARE,
                    "",
                ),
            ),
        ),
    ]
    for budget, name in BUDGETS_5R:
        mc = f"mc_{budget}"
        setting = f"{name}: {{n:.0f}} shared postures, {{trad:.0f}} against {{dc:.0f}} measurements"
        refs = {
            "n": f"{mc}.n_shared",
            "trad": (f"{mc}.measurements", 1),
            "dc": (f"{mc}.measurements", 0),
        }
        specs.append(
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
                group="ch3.iii.5r",
            )
        )
    return specs
