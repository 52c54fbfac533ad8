"""Record plan of "Divide-and-conquer identification of the planar 5R"
(``notebooks/fivebar_identification.ipynb``): every key the chapter records, with its tolerance,
glue names and report rows.

The Monte Carlo comparison of the two strategies is recorded once per budget of the traditional
method (``mc_<budget>.<quantity>``); its glue names carry the budget's suffix in the prose.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from mechlib import published as pub
from mechlib.reporting import report
from mechlib.reporting.recordplan import Entry, Extremes
from mechlib.reporting.tolerances import (
    BISECTION,
    CLOSED_FORM,
    EXACT,
    IDENTIFIED,
    ITERATIVE,
    ROUNDOFF,
    SHARE_OF_TRIALS,
    SOLVERS_AGREE,
    grid_share,
)

#: the chapter's budgets of the traditional method, and the suffix of their glue names
BUDGET_SUFFIX = {"item10": "", "table8": "_b", "equal": "_eq"}


def _budget(name: str, x: str) -> dict[str, Entry]:
    """The keys of one budget's comparison of D&C with the traditional method."""
    pair = {  # [D&C, traditional] pairs glued by name
        "measurements": (EXACT, f"meas_dc_{name}", f"meas_trad_{name}"),
        "rms_mean_um": (ITERATIVE, f"rms_dc{x}", f"rms_trad{x}"),
        "rms_median_um": (ITERATIVE, f"rms_med_dc{x}", f"rms_med_trad{x}"),
        "param_rms": (ITERATIVE, f"param_dc{x}", f"param_trad{x}"),
        "cond": (ROUNDOFF, f"cond_dc_{name}", f"cond_trad_{name}"),
    }
    single = {
        "n_shared": (EXACT, f"n_sh{x}"),
        "share_dc_better": (SHARE_OF_TRIALS, f"share_dc_better{x}"),
        "p_value": (ITERATIVE, f"p{x}" if x else "p_dc_trad"),
        "param_share_dc_better": (SHARE_OF_TRIALS, f"param_share_dc_better{x}"),
        "param_p_value": (ITERATIVE, f"param_p{x}"),
        "failed_trials": (EXACT, f"failed{x}" if x else "mc_failed"),
    }
    return {
        **{
            f"mc_{name}.{q}": Entry(tol=t, glue={dc: 0, trad: 1})
            for q, (t, dc, trad) in pair.items()
        },
        **{f"mc_{name}.{q}": Entry(tol=t, glue=g) for q, (t, g) in single.items()},
    }


def _identified_row(context: Mapping[str, Any]) -> list[report.RowSpec]:
    return [
        report.Computed(
            "Fig 13",
            "parameters identified by D&C, one seeded draw (Fig 13: minus the real ones) [m, rad, "
            "gain]",
            labels=tuple(context["names"]),
        )
    ]


def _nominal_row(context: Mapping[str, Any]) -> list[report.RowSpec]:
    return [
        report.Comparison(
            "Table 7",
            "nominal parameters as used",
            [pub.TABLE7_NOMINAL[n] for n in context["names"]],
            basis="construction",  # an input taken from Table 7
        )
    ]


def _measurements_row(context: Mapping[str, Any]) -> list[report.RowSpec]:
    return [
        report.Comparison(
            "Table 8",
            "measurement cost (coordinates + readings), traditional and D&C",
            [pub.TABLE8_MEASUREMENTS_TRADITIONAL, pub.TABLE8_MEASUREMENTS_DC],
            part=[1, 0],
            cause=f"the printed 2·18·2 counts 18 shared postures; the traditional setup of item "
            f"10 has n_shared = {context['n_shared']} shared postures",
            basis="thesis-inconsistency",  # Table 8 against item 10
        )
    ]


PLAN: dict[str, Entry] = {
    # --- the MIW (Fig 10) and the leg's loop (Fig 11) ---
    "miw.closed_form": Entry(
        tol=CLOSED_FORM,
        glue={"miw_cy": 0, "miw_r": 1},
        rows=report.Computed(
            "Fig 10", "MIW centre height, radius [m] (closed form; numeric agrees)"
        ),
    ),
    "miw.numeric": Entry(tol=BISECTION, glue={"miw_num_cy": 0, "miw_num_r": 1}),
    "miw.y_parallel": Entry(tol=CLOSED_FORM, glue="miw_yp"),
    "fig11.active_angle_rad": Entry(
        tol=CLOSED_FORM,
        rows=report.Computed(
            "Fig 11", "left leg's active angle θ₁ at the drawn pose [rad] (Eq 23)"
        ),
    ),
    "fig10.window_shares": Entry(
        tol=lambda c: grid_share(c["fig10_points"]),
        glue={"fig10_reachable": 0, "fig10_working": 1},
    ),
    # --- posture selection (Fig 12) ---
    "postures.n_candidates": Entry(tol=EXACT, glue="n_cand"),
    "parameters.n_per_leg": Entry(tol=EXACT, glue="n_leg"),
    "postures.o1": Entry(  # products of singular values: round-off
        tol=ROUNDOFF,
        rows=lambda c: [
            report.Computed("Fig 12", "O₁ (Eq 18) of the selected sets", labels=tuple(c["labels"]))
        ],
    ),
    "postures.leg1": Entry(tol=EXACT),
    "postures.leg2": Entry(tol=EXACT),
    "postures.trad": Entry(tol=EXACT),
    "selection.active_same_as_plain": Entry(tol=EXACT),
    # --- one seeded draw (Table 7, Fig 13) ---
    "identification.gauss_newton_vs_scipy_max": Entry(tol=SOLVERS_AGREE, glue="gn_vs_scipy"),
    "table7.dc": Entry(tol=IDENTIFIED, rows=_identified_row),
    "table7.trad": Entry(tol=IDENTIFIED),
    "table7.nominal": Entry(tol=EXACT, rows=_nominal_row),
    "table7.disturbance_rms": Entry(tol=ROUNDOFF, glue="table7_spread"),
    # --- the Monte Carlo study, per budget ---
    "parameters.n_trials": Entry(tol=EXACT, glue="n_trials_g"),
    "parameters.disturbance": Entry(tol=EXACT, glue="sigma_dist"),
    **{k: e for name, x in BUDGET_SUFFIX.items() for k, e in _budget(name, x).items()},
    "mc.param_rms_dc": Entry(tol=ITERATIVE),
    "mc.param_rms_trad": Entry(tol=ITERATIVE),
    "mc.rms_before_um": Entry(tol=ROUNDOFF, glue="rms_before"),
    # --- Tables 6 and 8 ---
    "table6.inversion_cost_ratio": Entry(tol=EXACT, glue="cost_ratio"),
    "table8.measurements": Entry(tol=EXACT, rows=_measurements_row),
    # --- the sensitivity sweep ---
    "parameters.sensitivity_trials": Entry(tol=EXACT, glue="sens_trials"),
    "sensitivity.ratio": Entry(
        tol=ITERATIVE, glue=Extremes(low="sens_ratio_min", high="sens_ratio_max")
    ),
    "sensitivity.share_dc_better": Entry(tol=SHARE_OF_TRIALS, glue=Extremes(high="sens_share_max")),
    "sensitivity.failed_trials": Entry(tol=EXACT),
    "identification.parameters_per_leg": Entry(tol=EXACT, glue="n_par_leg_g"),
    "table8.regressor_size": Entry(
        tol=EXACT,
        rows=lambda c: [
            report.Comparison(
                "Tables 6, 8",
                "regressor CᵀC size, traditional and D&C",
                [pub.TABLE8_REGRESSOR_TRADITIONAL[0], pub.TABLE8_REGRESSOR_DC[0]],
                cause="CᵀC is parameters × parameters ("
                + ", ".join(f"{n:g} × {n:g}" for n in c["value"])
                + "), not postures × postures",
                basis="thesis-inconsistency",  # against the thesis's own Eqs 21, 25 and 26
            )
        ],
    ),
}

#: the timings (machine-dependent, not compared) and their glue names
TIMINGS = {"selection.active_over_plain": "active_ratio"}
