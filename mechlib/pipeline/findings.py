"""The main findings the landing page states: each a sentence quoting recorded values.

:class:`Finding` ties a sentence to the records it quotes and to the report row it rests on;
:data:`FINDINGS` lists them in reading order (:mod:`mechlib.pipeline.landing` writes them).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from mechlib.reporting import categories as cat

#: A recorded value: (notebook, record key, index into the value, or "max"/"min" of it, or None).
Quote = tuple[str, str, int | tuple[int, ...] | str | None]


@dataclass(frozen=True)
class Finding:
    """A main finding: one sentence quoting recorded values, linked to its evidence.

    Attributes
    ----------
    title : str
        A few words, shown in bold.
    text : str
        The sentence, a ``str.format`` template whose fields are the names of ``values``.
    values : mapping of str to Quote
        The recorded values the sentence quotes.
    row : (notebook, artefact, start of the quantity), or None
        The report row the sentence rests on; None for a finding that quotes registered claims'
        verdicts (``[[claim id]]`` in ``text``) and is stated whatever they are.
    shown_if : tuple of str
        The categories of that row for which ``text`` is true.
    otherwise : (title, text)
        Title and sentence for any other category (empty: the finding is left out).
    holds : bool, optional
        Also required of the row: that its values agree or its claim holds (True) or not
        (False); a finding of ours has one category whether it holds or not.
    evidence : (page, what)
        Where the book shows the evidence (a chapter page and the artefact its section names).
    """

    title: str
    text: str
    values: Mapping[str, Quote]
    row: tuple[str, str, str] | None
    shown_if: tuple[str, ...]
    evidence: tuple[str, str]
    otherwise: tuple[str, str] = ("", "")
    holds: bool | None = None


_THESIS_ERROR = (cat.CAT_DIVERGES, cat.CAT_INCONSISTENT)
_REALTIME_TEXT = (
    "A Legendre polynomial of degree {degree:.0f}, distilled from a model trained on {runs:.0f} "
    "full non-linear runs, misses {n:.0f} held-out non-linear runs at ±1 N by at most "
    "{worst:.3g} % of full scale (goal {goal:.2g} %), and takes {us:.2g} µs a "
    "pose, one at a time, on the machine that built this book (the deadline: {deadline:.0f} µs). "
    "That it stays within its accuracy goal and meets the deadline: [[ours.meta.realtime]]."
)
_REALTIME_VALUES: dict[str, Quote] = {
    "degree": ("nonlinear_metamodels", "realtime.best.degree", None),
    "runs": ("nonlinear_metamodels", "realtime.full_runs", -1),
    "n": ("nonlinear_metamodels", "compare.validation_runs", None),
    "worst": ("nonlinear_metamodels", "realtime.best.worst_pct", None),
    "goal": ("nonlinear_metamodels", "parameters.goals", 0),
    "us": ("nonlinear_metamodels", "realtime.best.single_us", None),
    "deadline": ("nonlinear_metamodels", "parameters.deadline_us", None),
}
#: The findings the landing page states, in reading order (their numbers come from the records).
FINDINGS: tuple[Finding, ...] = (
    Finding(
        "The screening tables carry printing errors.",
        "Table 2 is printed in nm and mrad although its header says µm and µrad (its x column is "
        "{ratio_x:.1f} times what Eq 8 predicts in µm), and Table 3's summary rows contradict its "
        "own effects (the median |effect| of x is {nu_x:.0f} nm, not the θx value printed there).",
        {
            "ratio_x": ("published_doe", "units.table2_over_eq8", 0),
            "nu_x": ("published_doe", "table3.lenth_nu", 0),
        },
        ("published_doe", "Table 2", "unit ratio"),
        _THESIS_ERROR,
        ("published_doe", "Table 3"),
    ),
    Finding(
        "Eq 8 was fitted to Table 2, not to Table 4.",
        "A linear fit to the screening runs of Table 2 gives Eq 8's entries to {t2:.1e} relative; "
        "a fit to the uniform design of Table 4, the data the text names, misses them by up to "
        "{t4:.2%}.",
        {
            "t2": ("published_doe", "eq8.max_rel_diff_nonzero", 2),
            "t4": ("published_doe", "eq8.max_rel_diff_nonzero", 0),
        },
        ("published_doe", "Eq 8", "S_T vs OLS fit to Table 4"),
        _THESIS_ERROR,
        ("published_doe", "Eq 8"),
    ),
    Finding(
        "Table 5 looks like a linear analysis (our reading).",
        "On our FE model, which has Eq 8's compliance, the linear meta-model misses the "
        "geometrically non-linear solution of {runs:.0f} random runs at ±1 N by {nl_lo:.2g} to "
        "{nl_hi:.3g} % of full scale over the {n_val:.0f} linear validation "
        "runs; Table 5's published errors are at most {pub:.1e} % of the same full scales, at "
        "least "
        "{gap:.0f} times less in every component. "
        "On members of the family of parts with Eq 8's compliance with plates from "
        "{t_thin:.2g} to {t_thick:.2g} mm, the worst departure is {fam_lo:.3g} to "
        "{fam_hi:.3g} % of full scale (of the same {n_val:.0f} linear runs) over {fam_runs:.0f} "
        "runs each; "
        "finer flexure meshes or more Gauss points change it by at most {mesh:.2g} % of itself. We "
        "read the gap as evidence that the thesis's validation runs were linear analyses "
        "([[ours.table5_linear_analysis]] on the DOE chapter's member, "
        "[[ours.family_linear_analysis]] across the family); the "
        "beam model finds no member of this layout with a plate of {t_out:.2g} mm or more, and "
        "other layouts are not tested.",
        {
            "nl_lo": (
                "virtual_experiments",
                "table5.nonlinear.maxabs_over_linear_range_pct",
                "min",
            ),
            "nl_hi": (
                "virtual_experiments",
                "table5.nonlinear.maxabs_over_linear_range_pct",
                "max",
            ),
            "pub": ("virtual_experiments", "table5.published_maxabs_over_range_pct", "max"),
            "runs": ("virtual_experiments", "table5.nonlinear.converged_runs", None),
            "t_thin": ("nonlinear_family", "family.thinnest_mm", None),
            "t_thick": ("nonlinear_family", "family.thickest_mm", None),
            "fam_lo": ("nonlinear_family", "family.worst_departure_pct", "min"),
            "fam_hi": ("nonlinear_family", "family.worst_departure_pct", "max"),
            "fam_runs": ("nonlinear_family", "parameters.family_runs", None),
            # the family page takes the DOE chapter's draw (chapters.CHAPTER_INPUTS)
            "n_val": ("virtual_experiments", "parameters.n_validation", None),
            "mesh": ("nonlinear_family", "mesh.departure_change_pct", "max"),
            "gap": ("virtual_experiments", "table5.nonlinear.over_published", "min"),
            "t_out": ("nonlinear_family", "reach.first_infeasible_mm", None),
        },
        ("virtual_experiments", "Table 5", "the published errors of Table 5 imply"),
        (cat.CAT_OURS, cat.CAT_SUPPORTED),
        ("virtual_experiments", "Table 5"),
        holds=True,
    ),
    Finding(
        "The thesis's method on non-linear runs (ours).",
        "Fitted to Table 4's 30 runs solved non-linearly, the linear S_T misses {n:.0f} "
        "held-out non-linear runs at ±1 N by up to {st:.3g} % of full scale "
        "(that it stays within the {budget:g} % budget: [[ours.meta.thesis_method]]), and the "
        "second-order Eq 6 by {eq6:.3g} %; the best model compared reaches {best:.3g} % "
        "(a reduced-order model built from {rom_runs:.0f} full runs: {rom:.3g} %).",
        {
            "n": ("nonlinear_metamodels", "compare.validation_runs", None),
            "st": ("nonlinear_metamodels", "compare.worst_pct", 0),
            "budget": ("nonlinear_metamodels", "parameters.budget_pct", None),
            "eq6": ("nonlinear_metamodels", "compare.worst_pct", 1),
            "best": ("nonlinear_metamodels", "compare.worst_pct", "min"),
            "rom": ("nonlinear_metamodels", "compare.worst_pct", -1),
            "rom_runs": ("nonlinear_metamodels", "compare.training_runs", -1),
        },
        None,
        (),
        ("nonlinear_metamodels", "Real time, re-judged"),
    ),
    Finding(
        "A real-time model of our non-linear FE of the HexFlex, not of the device (ours).",
        _REALTIME_TEXT,
        _REALTIME_VALUES,
        None,
        (),
        ("nonlinear_metamodels", "A real-time model: corrected, then distilled"),
    ),
    Finding(
        "Chapter 2's headline claims, judged on linear and on geometrically non-linear FE.",
        "The HexFlex is linear over ±1 N: [[ch2.linear]]; Eq 6's quadratic terms are "
        "negligible: [[ch2.eq6]]; the 6 × 6 matrix S_T is accurate by the thesis's own "
        "yardsticks: [[ch2.table5]]; it is simple enough for real-time control: "
        "[[ch2.realtime]]. The first three were tested on a geometrically non-linear FE model "
        "with Eq 8's compliance: the linear meta-model misses {n:.0f} runs at ±1 N by up to "
        "{worst:.3g} % of full scale (of those non-linear runs; of the linear validation runs, "
        "the same misses are {lo:.2g} to {hi:.3g} %), and Eq 6 fitted to non-linear runs has "
        "second-order terms up to {eq6:.2g} of its largest linear one. On a linear FE model they "
        "hold by construction, which is shown and not counted.",
        {
            "n": ("virtual_experiments", "table5.nonlinear.converged_runs", None),
            "worst": ("virtual_experiments", "table5.nonlinear.max_range_pct", "max"),
            "lo": ("virtual_experiments", "table5.nonlinear.maxabs_over_linear_range_pct", "min"),
            "hi": ("virtual_experiments", "table5.nonlinear.maxabs_over_linear_range_pct", "max"),
            "eq6": ("virtual_experiments", "nl_designs.eq6_second_order_over_linear", "max"),
        },
        None,
        (),
        ("virtual_experiments", "Table 5"),
    ),
    Finding(
        "Divide and conquer on the 5R, the thesis's three claims (sec. 3.8).",
        "(iii) Better identification results: [[ch3.iii.5r.item10]] with item 10's "
        "{n10:.0f} shared postures (workspace RMS {dc:.1f} µm by D&C against {trad:.1f} µm, D&C "
        "better in {share:.0%} of the paired trials); [[ch3.iii.5r.table8]] with Table 8's "
        "printed budget of {n8:.0f} shared postures (D&C better in {pshare8:.0%} of the trials "
        "in parameter error, p = {pp8:.1e}, and in {share8:.0%} in workspace error, "
        "p = {p8:.2g}); [[ch3.iii.5r.equal]] with equal measurements ({neq:.0f} shared "
        "postures, D&C better in {shareq:.0%} in workspace error). (i) Lower computational cost: "
        "[[ch3.i.5r]] (inversion flops {flops:.0f} times fewer, a count from the numbers of "
        "parameters; measured solve times do not follow it). (ii) Better numerical efficiency, "
        "judged on the conditioning of the identification matrices: [[ch3.ii.5r]] (the "
        "traditional matrix is block diagonal, so its conditioning is at best its worst leg's).",
        {
            "n10": ("fivebar_identification", "mc_item10.n_shared", None),
            "dc": ("fivebar_identification", "mc_item10.rms_mean_um", 0),
            "trad": ("fivebar_identification", "mc_item10.rms_mean_um", 1),
            "share": ("fivebar_identification", "mc_item10.share_dc_better", None),
            "n8": ("fivebar_identification", "mc_table8.n_shared", None),
            "pshare8": ("fivebar_identification", "mc_table8.param_share_dc_better", None),
            "pp8": ("fivebar_identification", "mc_table8.param_p_value", None),
            "share8": ("fivebar_identification", "mc_table8.share_dc_better", None),
            "p8": ("fivebar_identification", "mc_table8.p_value", None),
            "neq": ("fivebar_identification", "mc_equal.n_shared", None),
            "shareq": ("fivebar_identification", "mc_equal.share_dc_better", None),
            "flops": ("fivebar_identification", "table6.inversion_cost_ratio", None),
        },
        None,
        (),
        ("fivebar_identification", "Fig 14"),
    ),
)
