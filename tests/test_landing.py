"""The landing page and the per-artefact roll-up, generated from the committed reference records."""

from __future__ import annotations

import copy
import json
from pathlib import Path
from typing import Any

import pytest

from mechlib.pipeline import landing, outcome, pagecheck
from mechlib.reporting import categories as cat
from mechlib.reporting import claimlist, report, verdicts

REFERENCES = Path(__file__).parent / "references"


@pytest.fixture(scope="module")
def records() -> dict[str, dict[str, Any]]:
    return copy.deepcopy(verdicts.load_records(REFERENCES))


@pytest.fixture(scope="module")
def page(records: dict[str, dict[str, Any]]) -> str:
    return landing.landing_markdown(records, "ci")


def test_landing_lists_every_thesis_artefact_with_its_verdict(page: str) -> None:
    table = [line for line in page.splitlines() if line.startswith("| ")]
    for kind, number, _, _ in verdicts.THESIS_ARTEFACTS:
        name = verdicts.artefact_name(kind, number)
        assert any(f"{name} " in line or f"{name}`" in line for line in table), name
    assert f"| {verdicts.NO_ROW} |" not in page  # every artefact has a row
    fig1 = next(line for line in page.splitlines() if line.startswith("| {doc}`Fig 1 "))
    assert f"| {{category}}`{cat.CAT_REDRAWN}` |" in fig1


def test_landing_counts_equal_the_records_and_a_report_with_the_same_table(
    records: dict[str, dict[str, Any]], page: str
) -> None:
    rows = verdicts.all_rows(records)
    counts = verdicts.category_counts(rows)
    assert pagecheck.count_table(page) == counts
    assert counts[cat.CAT_REDRAWN] == len(verdicts.REDRAWN)
    # Table 4's units against Eq 8, Table 1's levels against Tables 2 and 4, Figs 6-7's list
    # against Table 2's effects, Table 3's |main effects| recomputed from the printed Table 2
    assert counts[cat.CAT_CONSISTENT_THESIS] == 4
    assert counts[cat.CAT_REPRODUCED] == 0  # no independent reproduction: no drawing, no files
    assert (
        counts[cat.CAT_CONSTRUCTION] == 13 and counts[cat.CAT_OURS] == 30
    )  # five on Beyond the HexFlex, six on our FE of the parallelogram; (iii) on the 3-RRR and
    # the 6-UPS counted once each, whatever the budget; O1 against O3 on its paired values
    report_page = "# Report\n\n" + verdicts.counts_table(counts) + "\n"
    assert pagecheck.counts_problems(page, report_page, rows) == []
    group = verdicts.COUNT_GROUPS[0][0]
    wrong = report_page.replace(f"| reproduced | {group} | {counts['reproduced']} |",
                                f"| reproduced | {group} | 99 |")  # fmt: skip
    assert pagecheck.counts_problems(page, wrong, rows) == [
        f"report page: 'reproduced' shows 99 rows, the records have {counts['reproduced']}"
    ]
    assert "no table of counts" in pagecheck.counts_problems(page, "# Report", rows)[0]


def test_our_hypothesis_is_not_counted_among_the_thesis_claims(page: str) -> None:
    assert "({category}`our finding beyond the thesis`). On our FE model, which has Eq 8" in page
    claims = pagecheck.count_table(page)
    # the claims of the thesis the records judge, each counted once: chapter 2's seven (the
    # screening's interactions among them) and chapter 3's four on the 5R ((iii) judged at three
    # budgets; the active calibration's speed); findings of ours apart
    judged = claimlist.judge(verdicts.load_records(REFERENCES))
    thesis = {claimlist.claim_group(v.spec) for v in judged.values() if v.spec.source == "thesis"}
    assert sum(claims[c] for c in cat.CLAIM_CATEGORIES) == len(thesis) == 11
    registered = {claimlist.claim_group(c) for c in claimlist.CLAIMS.values()}
    assert thesis <= registered and {"ch2.pb_interactions", "ch3.active_speed"} <= thesis
    # (i) and (ii) are arithmetic or settled by construction: counted apart from the tested
    assert claims[cat.CAT_CLAIM_CONSTRUCTION] == 2
    assert sum(claims[c] for c in cat.TESTED_CLAIM_CATEGORIES) == 9


def test_findings_quote_the_records_and_the_registry_not_typed_words(
    records: dict[str, dict[str, Any]],
) -> None:
    changed = copy.deepcopy(records)
    changed["fivebar_identification"]["values"]["mc_item10.rms_mean_um"]["value"] = [42.04, 17.0]
    text = landing.landing_markdown(changed, "ci")
    assert "workspace RMS 42.0 µm by D&C against 17.0 µm" in text
    # verdict words are quoted from the claims registry by id, never written into a finding
    for claim_id in ("ch2.linear", "ch2.eq6", "ch3.iii.5r.table8", "ch3.ii.5r"):
        assert f"{{verdict}}`{claim_id}`" in text
    assert pagecheck.markdown_problems(text, "intro.md") == []


def test_a_finding_whose_values_were_not_recorded_is_left_out(
    records: dict[str, dict[str, Any]],
) -> None:
    title = "**Table 5 looks like a linear analysis (our reading)**"
    assert title in landing.landing_markdown(records, "ci")
    smoke = copy.deepcopy(records)
    del smoke["virtual_experiments"]["values"]["table5.nonlinear.maxabs_over_linear_range_pct"]
    text = landing.landing_markdown(smoke, "smoke")
    assert title not in text
    assert "built with the **smoke** profile" in text
    # our hypothesis that does not hold is not stated as holding
    failed = copy.deepcopy(records)
    for row in failed["virtual_experiments"]["report"]:
        if row.get("claim") == "ours.table5_linear_analysis":
            row["n_values"], row["n_agree"] = 1, 0
    assert title not in landing.landing_markdown(failed, "ci")


def test_landing_page_passes_its_own_text_checks(page: str) -> None:
    assert pagecheck.markdown_problems(page, "intro.md") == []


def test_write_landing_reads_a_records_folder_and_names_a_bad_profile(tmp_path: Path) -> None:
    out = tmp_path / "intro.md"
    landing.write_landing(REFERENCES, out, "ci")
    assert out.read_text().startswith("# An executable reproduction")
    assert "`n_validation` = 1000" in out.read_text()
    with pytest.raises(ValueError, match="profile must be a name"):
        landing.write_landing(REFERENCES, out, "../full")
    with pytest.raises(FileNotFoundError, match=r"no <notebook>\.json"):
        landing.write_landing(tmp_path, out, "ci")


def test_rollup_counts_each_named_artefact_and_summarises_values() -> None:
    rows = [
        verdicts.ReportRow("nb", report.compare_row("Table 3", "effects", [1.0] * 36, [1.0] * 36)),
        verdicts.ReportRow(
            "nb",
            report.compare_row(
                "Table 3",
                "ν",
                [19.6, 3.1],
                [28763.8, 3.1],
                rtol=0.01,
                cause="copy error",
                basis="thesis-inconsistency",
            ),
        ),
        verdicts.ReportRow("nb", report.compare_row("Tables 6, 8", "size", [36], [12], cause="c")),
    ]
    by_name = {entry["artefact"]: entry for entry in verdicts.rollup(rows)}
    assert by_name["Table 3"]["summary"] == (
        "Table 3: 1 row reproduced (36/36 values agree); "
        "1 row inconsistency inside the thesis (1/2 values agree)"
    )
    assert by_name["Table 3"]["verdict"] == "inconsistency inside the thesis"
    assert by_name["Table 3"]["counts"] == {"reproduced": 1, "inconsistency inside the thesis": 1}
    # a row naming two artefacts counts under the first only; the other names where
    assert (by_name["Table 6"]["rows"], by_name["Table 8"]["rows"]) == (1, 0)
    assert by_name["Table 8"]["counted_under"] == ["Table 6"]
    assert by_name["Fig 1"]["verdict"] == verdicts.NO_ROW
    assert "Fig 1: no report row" in pagecheck.artefact_problems(rows)
    assert "Table 3: no report row" not in pagecheck.artefact_problems(rows)


def test_a_row_without_a_known_category_is_refused_never_parsed() -> None:
    with pytest.raises(ValueError, match="unknown category None"):
        verdicts.row_category({"verdict": "within tolerance (1 %)"})
    with pytest.raises(ValueError, match="unknown category"):
        verdicts.row_category({"verdict": "reproduced", "category": "fine"})
    assert json.loads(json.dumps(verdicts.rollup(verdicts.load_rows(REFERENCES))))


def test_headline_order_ranks_every_category_once() -> None:
    assert sorted(verdicts.HEADLINE_ORDER) == sorted(cat.CATEGORIES)


def test_the_landing_page_says_what_made_the_build(records: dict[str, dict[str, Any]]) -> None:
    import datetime as dt

    from mechlib.pipeline import provenance

    made = provenance.text(dt.datetime(2026, 1, 2, 3, 4, tzinfo=dt.UTC))
    assert "built 2026-01-02 03:04 UTC" in made and "numpy " in made and "processor: " in made
    # the build's profile in the reader's words: the default one is the chapters' own defaults
    when = dt.datetime(2026, 1, 2, tzinfo=dt.UTC)
    assert "each chapter's default parameters" in provenance.text(when, "ci")
    assert "with the parameters of profile `full`" in provenance.text(when, "full")
    page = landing.landing_markdown(records, "ci", provenance=made)
    assert made in page and page.index(made) > page.index("## This build")
    assert provenance.commit(Path("/")) == provenance.UNKNOWN  # not a repository
    assert provenance.versions(("no-such-package-xyz",)) == {"no-such-package-xyz": "unknown"}


def test_a_quote_reads_a_timing_when_no_value_has_its_key() -> None:
    from mechlib.pipeline.landing import quote

    records = {"nb": {"values": {"a": {"value": [1.0, 3.0]}}, "timings": {"t_us": 42.0}}}
    assert quote(records, ("nb", "t_us", None)) == 42.0
    assert quote(records, ("nb", "a", "max")) == 3.0
    with pytest.raises(KeyError, match="recorded no value 'b'"):
        quote(records, ("nb", "b", None))


def test_a_chapter_says_how_long_it_ran_and_how_to_run_it_again() -> None:
    from mechlib.pipeline import provenance

    lines = provenance.rerun_lines("virtual_experiments", 22.4)
    assert "default run took 22 s on this machine" in lines
    assert "`make run NB=virtual_experiments ARGS='-p <name> <value>'`" in lines
    assert "not recorded" in provenance.rerun_lines("x", None)


def test_a_chapter_says_how_many_fe_tasks_it_read_and_its_main_parameters() -> None:
    from mechlib.pipeline import provenance

    lines = provenance.rerun_lines(
        "virtual_experiments", 20.0, {"total": 2046, "cached": 2000}, ("seed", "workers")
    )
    assert "of its 2,046 finite-element tasks, 2,000 (98 %) were read from the FE cache" in lines
    assert "names and ranges in its first code cell: `seed`, `workers` first" in lines
    assert "runs no finite-element task" in provenance.rerun_lines("x", 3.0, {"total": 0})


def test_every_main_parameter_is_a_parameter_of_its_chapter() -> None:
    from mechlib.pipeline.chapters import CHAPTERS, MAIN_PARAMETERS
    from mechlib.pipeline.parameters import notebook_parameters

    root = Path(__file__).resolve().parents[1] / "notebooks"
    assert set(MAIN_PARAMETERS) == set(CHAPTERS)
    for name, main in MAIN_PARAMETERS.items():
        assert set(main) <= set(notebook_parameters(root / f"{name}.ipynb")), name


def test_the_view_counts_every_campaign_of_a_notebook(tmp_path) -> None:
    import io

    from mechlib.pipeline.progressview import ProgressView

    view = ProgressView(tmp_path / "p.jsonl", "nb", stream=io.StringIO())
    base = {"event": "start", "desc": "runs", "workers": 1, "done": 0, "estimate_s": None}
    view.show({**base, "total": 10, "cached": 10, "to_compute": 0})
    view.show({**base, "total": 5, "cached": 2, "to_compute": 3})
    assert view.tasks == {"total": 15, "cached": 12}


def test_the_counts_sentence_weighs_claims_not_rows(records: dict[str, dict[str, Any]]) -> None:
    rows = verdicts.all_rows(records)
    ids = verdicts.thesis_claim_ids(rows)
    counts = verdicts.category_counts(rows)
    n_rows, distinct, several = claimlist.thesis_claims_judged(ids)
    # the counts table counts the distinct claims the rows judge
    assert distinct == sum(counts[c] for c in cat.CLAIM_CATEGORIES) == 11
    assert n_rows > distinct >= several == 1  # (iii): a row per budget
    text = landing.counts_sentence(ids)
    assert f"The report's {n_rows} rows on the thesis's claims judge {distinct} distinct" in text
    assert "distinct claims" not in landing.counts_sentence()


def test_the_roll_up_lists_claims_apart_and_never_under_two_artefacts(
    records: dict[str, dict[str, Any]],
) -> None:
    rows = verdicts.all_rows(records)
    entries = verdicts.rollup(rows)
    named = [r for r in rows if r.artefacts]  # rows of the thesis's artefacts
    assert sum(e["rows"] for e in entries) == len(named)  # each under one artefact
    by_name = {e["artefact"]: e for e in entries}
    # Eq 7's verdict is its values' (S_T fitted against Eq 8), the real-time claim is quoted apart
    assert by_name["Eq 7"]["verdict"] == cat.CAT_CONSTRUCTION
    assert by_name["Eq 7"]["claims"] == {"ch2.realtime": ["ch2.realtime"]}
    assert by_name["Fig 14"]["counted_under"] == ["Fig 13"]


def test_the_landing_opens_with_the_outcome_generated_from_the_registry(
    records: dict[str, dict[str, Any]], page: str
) -> None:
    heads = [line for line in page.splitlines() if line.startswith("## ")]
    assert heads[:2] == [outcome.HEADING, "## Main findings"]
    assert page.index(outcome.HEADING) < page.index("| Artefact |")
    text = page[page.index(outcome.HEADING) : page.index("## Main findings")]
    assert "No published value was reproduced independently" in text
    # each judged claim of the thesis once, under the head its word gives it
    judged = claimlist.judge(records).values()
    groups = {claimlist.claim_group(v.spec) for v in judged if v.spec.source == "thesis"}
    for group in groups:
        assert text.count(f"{{verdict}}`{group}") >= 1, group
    by_construction = text[text.index("true only by construction") : text.index("borne out when")]
    assert "{verdict}`ch3.i.5r`" in by_construction and "{verdict}`ch3.ii.5r`" in by_construction
    failing = text[text.index("fail when tested") :]
    assert "{verdict}`ch2.linear`, on a geometrically non-linear FE model" in failing
    assert "41.9 % of full scale (at most 1 % of full scale)" in failing
    assert "  - Table 2: Table 2 is printed in nm and mrad" in text
    assert "{verdict}`ch2.generality`, on a distributed compliant mechanism" in failing
    assert "**Not testable here:** *real experimentation is replaced" in text
    # a claim that fails in another build moves to the failing list, from the records alone
    changed = copy.deepcopy(records)
    changed["virtual_experiments"]["timings"]["latency.st_forward_us"] = 5e3
    changed["virtual_experiments"]["values"]["claims.ch2.realtime"]["value"] = "not supported"
    moved = landing.landing_markdown(changed, "ci")
    moved = moved[moved.index("fail when tested") : moved.index("## Main findings")]
    assert "{verdict}`ch2.realtime`" in moved
