"""Our claims about the parallelogram flexure in our own FE (the page "The parallelogram in our own
FE"): the mesh study and the published sweep. Thresholds are fixed from the benchmark's own
numbers before ours are measured: 1 % for a converged mesh; the published meshes' own spread at
the mesh study's load, per component (their 10 mm mesh against their 3 mm one); 2 % of full
scale for the sweep (a round figure above the largest relative change their mesh study shows,
1.72 %: a share of full scale and a change relative to a value are different measures, so this
bound is a judgement, stated here before measuring); for chapter 2's method, the 1 % error
budget of our meta-model chapter. Registered in :mod:`mechlib.reporting.claimlist` through
:func:`mechlib.reporting.ourclaims.our_claims`.
"""

from __future__ import annotations

from mechlib.parallelogram.metamethod import BUDGET_PCT
from mechlib.reporting import categories as cat
from mechlib.reporting.claimrules import at_least, at_most, each_within, greater, within
from mechlib.reporting.claims import ClaimSpec

#: the page's notebook
PF = "parallelogram_fe"
#: our mesh has converged when its two finest meshes differ by at most this [%]
MESH_CONVERGED_PCT = 1.0
#: our FE reproduces the published sweep within this share of full scale [%]
SWEEP_AGREEMENT_PCT = 2.0


def parallelogram_fe_claims() -> list[ClaimSpec]:
    """The six claims of the page, in its order."""
    where = "Our FE of the parallelogram flexure"
    return [
        ClaimSpec(
            "ours.parallelogram_fe.mesh_converged",
            cat.SOURCE_OURS,
            where,
            f"our FE of the parallelogram has converged in its mesh at the published mesh "
            f"study's load: its two finest meshes give poses within {MESH_CONVERGED_PCT:g} %",
            PF,
            (
                at_most(
                    "largest change between our two finest meshes",
                    "mesh.last_step_pct",
                    MESH_CONVERGED_PCT,
                    "%",
                ),
            ),
        ),
        ClaimSpec(
            "ours.parallelogram_fe.mesh_case",
            cat.SOURCE_OURS,
            where,
            "at the published mesh study's load our finest mesh lies as close to their finest "
            "mesh, in each of x, y and φ, as their coarsest mesh lies to it",
            PF,
            (
                each_within(
                    "|ours − their finest| / their finest, per component",
                    "mesh.ours_vs_their_finest_pct",
                    "mesh.their_spread_pct",
                    "%",
                ),
            ),
        ),
        ClaimSpec(
            "ours.parallelogram_fe.sweep_within",
            cat.SOURCE_OURS,
            where,
            f"our non-linear FE reproduces the published non-linear 3-D FE sweep within "
            f"{SWEEP_AGREEMENT_PCT:g} % of full scale, on the page's mesh and, where the two "
            f"differ most, on our finest mesh",
            PF,
            (
                at_most(
                    "largest |our FE − published FE| over the sweep, on the page's mesh, % of "
                    "full scale",
                    "sweep.ours_vs_published_worst_pct",
                    SWEEP_AGREEMENT_PCT,
                    "%",
                ),
                at_most(
                    "at the row where it is largest, on our finest mesh of the mesh study",
                    "corner.fine_vs_published_pct",
                    SWEEP_AGREEMENT_PCT,
                    "%",
                ),
            ),
        ),
        *parallelogram_method_claims(),
    ]


def parallelogram_method_claims() -> list[ClaimSpec]:
    """The three claims of chapter 2's method run on the parallelogram (the same page)."""
    where = "Our FE of the parallelogram flexure: chapter 2's method"
    return [
        ClaimSpec(
            "ours.parallelogram_method.st_over_box",
            cat.SOURCE_OURS,
            where,
            f"over the benchmark's load box the thesis's linear S_T, fitted on a uniform design, "
            f"misses the non-linear FE by more than a {BUDGET_PCT:g} % budget in some pose "
            f"component",
            PF,
            (
                at_least(
                    "S_T's largest held-out error, worst component",
                    "method.st_worst_pct",
                    BUDGET_PCT,
                    "%",
                    what="largest",
                    reduce="max",
                ),
            ),
        ),
        ClaimSpec(
            "ours.parallelogram_method.nonlinear_range",
            cat.SOURCE_OURS,
            where,
            "a non-linear meta-model family keeps the error budget over a larger fraction of "
            "the load box than the linear map",
            PF,
            (
                greater(
                    "largest fraction of the box within the budget",
                    ("method.budget_best_and_linear", 0),
                    ("method.budget_best_and_linear", 1),
                    ("best family", "linear family"),
                    fmt="g",
                ),
            ),
        ),
        ClaimSpec(
            "ours.parallelogram_method.realtime",
            cat.SOURCE_OURS,
            where,
            "a distilled real-time polynomial keeps the error budget on held-out FE runs at the "
            "largest fraction of the box the best family keeps it",
            PF,
            (
                within(
                    "the real-time model's largest held-out error",
                    "method.realtime_worst_pct",
                    "method.goal_pct",
                    "%",
                ),
            ),
        ),
    ]
