"""The claims registry: verdict rules, the recorder's claim, the build's judgement, page checks."""

from __future__ import annotations

import pytest

from mechlib.pipeline import chapters
from mechlib.pipeline.book import claimcheck, verdictrole
from mechlib.reporting import categories as cat
from mechlib.reporting import claimlist, claimrules, claims, thesisclaims
from mechlib.reporting.records import Recorder


def _spec(source: str = "thesis", informative: bool = True) -> claims.ClaimSpec:
    linear = claimrules.with_construction(
        claimrules.at_most("linear", "lin_pct", 1.0, "%"), "a linear model is linear"
    )
    nonlinear = claimrules.at_most("non-linear", "nl_pct", 1.0, "%")
    return claims.ClaimSpec(
        "t.claim",
        source,
        "Table 5",
        "the model is accurate",
        "nb",
        (linear, nonlinear) if informative else (linear,),
        "{n:.0f} runs",
        {"n": "runs"},
    )


def _values(lin: float, nl: float) -> dict:
    return {"lin_pct": {"value": [lin, 0.1]}, "nl_pct": {"value": nl}, "runs": {"value": 40}}


@pytest.mark.parametrize(
    ("source", "holds", "word"),
    [
        ("thesis", [True, True], "supported"),
        ("thesis", [False, False], "not supported"),
        ("thesis", [True, False], "mixed"),
        ("ours", [True], "holds"),
        ("ours", [False], "does not hold"),
        ("ours", [False, True], "mixed"),
    ],
)
def test_the_verdict_word_follows_the_parts(source: str, holds: list[bool], word: str) -> None:
    assert claims.verdict_word(source, holds) == word


@pytest.mark.parametrize(
    ("holds", "counted", "word"),
    [
        ([True, False], [False, True], "not supported"),  # the informative part decides
        ([True, True], [False, True], "supported"),
        ([True, True, False], [False, True, True], "mixed"),
        ([True], [False], "consistent by construction"),  # nothing could fail
    ],
)
def test_a_part_that_cannot_fail_is_never_counted(
    holds: list[bool], counted: list[bool], word: str
) -> None:
    assert claims.verdict_word("thesis", holds, counted) == word


def test_a_part_that_cannot_fail_but_fails_is_an_error_of_the_registry() -> None:
    with pytest.raises(ValueError, match="hold by construction, yet they fail"):
        claims.verdict_word("thesis", [False, True], [False, True])
    with pytest.raises(ValueError, match="say why"):
        claims.Test("x", ("k",), bool, str, by_construction=True)


def test_a_claim_whose_only_informative_part_fails_is_not_supported_and_shows_both() -> None:
    v = claims.evaluate(_spec(), _values(0.5, 41.9))
    assert (v.word, v.holds, v.setting) == ("not supported", (True, False), "40 runs")
    assert v.category == cat.CAT_NOT_SUPPORTED
    assert (
        "linear (by construction, not counted: a linear model is linear): largest 0.5 % "
        "(at most 1 %) (met)" in v.evidence
    )
    assert "non-linear: largest 41.9 % (at most 1 %) (not met)" in v.evidence
    row = v.row()
    assert row["claim"] == "t.claim" and row["quantity"].endswith("— 40 runs")
    assert (row["n_values"], row["n_agree"]) == (1, 0)  # only the part that could fail
    assert claims.evaluate(_spec(), _values(0.5, 0.9)).word == "supported"
    assert claims.evaluate(_spec("ours"), _values(0.5, 3.0)).category == cat.CAT_OURS
    alone = claims.evaluate(_spec(informative=False), _values(0.5, 41.9))
    assert alone.word == "consistent by construction"
    assert alone.category == cat.CAT_CLAIM_CONSTRUCTION


def test_the_registry_refuses_a_word_that_counts_a_by_construction_part() -> None:
    v = claims.evaluate(_spec(), _values(0.5, 41.9))
    # "mixed" would count the linear part (which holds by construction) as evidence
    with pytest.raises(ValueError, match=r"the word 'mixed' is refused.*'not supported'"):
        claims.Verdict(v.spec, "mixed", v.holds, v.evidence, v.setting)
    with pytest.raises(ValueError, match="the word 'supported' is refused"):
        claims.Verdict(v.spec, "supported", v.holds, v.evidence, v.setting)
    # and the build refuses a record that kept such a word
    record = {"values": {"claims.ch2.linear": {"value": "mixed"}}}
    with pytest.raises(ValueError, match=r"recorded 'mixed' for claim 'ch2\.linear'"):
        claimlist.judge({"virtual_experiments": _linear_record(record)})


def _linear_record(record: dict) -> dict:
    """``record`` with the values ch2.linear reads: holds on linear FE, fails on non-linear."""
    record["values"] |= {
        "table5.linear.max_rel_pct": {"value": [2e-10] * 6},
        "table5.nonlinear.max_range_pct": {"value": [31.0, 41.9, 3.5, 5.6, 5.4, 1.5]},
        "table5.nonlinear.converged_runs": {"value": 1000},
    }
    return record


def test_no_registered_claim_counts_a_part_that_cannot_fail() -> None:
    """For every claim, every outcome of its parts that could fail: the word is theirs alone."""
    for spec in claimlist.CLAIMS.values():
        assert all(p.why for p in spec.parts if p.by_construction), spec.id
        informative = [i for i, c in enumerate(spec.counted) if c]
        for outcome in range(2 ** len(informative)):
            holds = [True] * len(spec.parts)
            for bit, i in enumerate(informative):
                holds[i] = bool(outcome >> bit & 1)
            word = claims.verdict_word(spec.source, holds, spec.counted)
            alone = [holds[i] for i in informative]
            assert word == (
                claims.verdict_word(spec.source, alone) if alone else claims.BY_CONSTRUCTION
            ), spec.id


def test_a_value_the_rule_reads_must_have_been_recorded() -> None:
    with pytest.raises(KeyError, match=r"t\.claim.*nl_pct"):
        claims.evaluate(_spec(), {"lin_pct": {"value": 0.1}, "runs": {"value": 3}})


def test_paired_needs_a_majority_and_a_significant_test() -> None:
    test = claimrules.paired("workspace", "s", "p")
    assert test.rule(0.6, 0.01) and not test.rule(0.6, 0.2) and not test.rule(0.4, 1e-9)
    assert (
        test.describe(0.24, 8.4e-18)
        == "D&C better in 24 % of the paired trials, Wilcoxon p = 8.4e-18"
    )


def test_a_boolean_test_says_yes_or_no_of_one_value_and_counts_several() -> None:
    test = claimrules.is_true("balanced", "b", "each level equally often")
    assert test.rule(True) and not test.rule([True, False])
    assert test.describe(True) == "each level equally often: yes"
    assert test.describe([True, False, True]) == "each level equally often: 2 of 3 true"


def test_a_thesis_claim_judged_at_several_budgets_counts_once() -> None:
    budgets = [c for c in claimlist.CLAIMS if c.startswith("ch3.iii.5r.")]
    assert len(budgets) == 3  # (iii) on the 5R at each measurement budget
    ids = [*budgets, "ch3.i.5r", "ch3.ii.5r"]
    assert claimlist.thesis_claims_judged(ids) == (5, 3, 1)
    assert claimlist.thesis_claims_judged([]) == (0, 0, 0)
    assert {claimlist.claim_group(claimlist.claim(c)) for c in budgets} == {"ch3.iii.5r"}
    # claims with the same setting are not one claim (ch2.linear and ch2.table5 both name it)
    assert claimlist.thesis_claims_judged(["ch2.linear", "ch2.table5"]) == (2, 2, 0)
    with pytest.raises(KeyError):
        claimlist.thesis_claims_judged(["ch3.nonsense"])
    ours = next(c for c in claimlist.CLAIMS if c.startswith("ours."))
    with pytest.raises(ValueError, match="claims of ours"):
        claimlist.thesis_claims_judged([*budgets, ours])
    assert claimlist.group_word(["not supported", "mixed", "not supported"]) == "mixed"
    assert claimlist.group_word(["not supported"] * 3) == "not supported"
    with pytest.raises(ValueError):
        claimlist.group_word(["perhaps"])


def test_chapter_3s_arithmetic_claims_are_judged_once_and_by_construction() -> None:
    for cid in ("ch3.i.5r", "ch3.ii.5r"):
        spec = claimlist.claim(cid)
        assert not spec.setting and not any(spec.counted), cid
    values = {
        "table6.inversion_cost_ratio": {"value": 4},
        **{f"mc_{b}.cond": {"value": [0.0066, 0.0058]} for b, _ in thesisclaims.BUDGETS_5R},
    }
    for cid in ("ch3.i.5r", "ch3.ii.5r"):
        v = claims.evaluate(claimlist.claim(cid), values)
        assert v.word == "consistent by construction" and v.row()["n_values"] == 0


def test_the_recorder_records_the_word_and_the_row_of_its_own_claims_only() -> None:
    rec = Recorder("virtual_experiments", paste=lambda name, value: None, registry=claimlist.claim)
    rec.timing("latency.st_forward_us", 0.8)
    assert rec.claim("ch2.realtime") == "supported"
    assert rec.values["claims.ch2.realtime"]["value"] == "supported"
    assert rec.report[-1]["claim"] == "ch2.realtime"
    assert rec.report[-1]["category"] == cat.CAT_SUPPORTED
    with pytest.raises(ValueError, match="already recorded"):
        rec.claim("ch2.realtime")
    with pytest.raises(ValueError, match="judged on fivebar_identification"):
        rec.claim("ch3.iii.5r.table8")
    with pytest.raises(KeyError, match="no registered claim"):
        rec.claim("ch2.nonsense")


def test_the_build_judges_again_and_refuses_a_word_its_values_do_not_give() -> None:
    record = {
        "values": {"claims.ch2.realtime": {"value": "supported"}},
        "timings": {"latency.st_forward_us": 0.8},
    }
    judged = claimlist.judge({"virtual_experiments": record})
    assert judged["ch2.realtime"].word == "supported"
    assert claimlist.verdict_table(judged)["ch2.realtime"]["page"] == "virtual_experiments"
    record["timings"]["latency.st_forward_us"] = 500.0
    with pytest.raises(ValueError, match=r"recorded 'supported' for claim 'ch2\.realtime'"):
        claimlist.judge({"virtual_experiments": record})


def test_the_registry_judges_each_claim_on_a_chapter_and_chapter_3s_iii_at_every_budget() -> None:
    for spec in claimlist.CLAIMS.values():
        assert spec.page in chapters.CHAPTERS, spec.id
    for budget, _ in thesisclaims.BUDGETS_5R:
        assert claimlist.claim(f"ch3.iii.5r.{budget}").source == cat.SOURCE_THESIS
    assert all(c.source == cat.SOURCE_OURS for c in claimlist.CLAIMS.values() if ".b5r." in c.id)
    classes = [verdictrole.claim_class(c) for c in claimlist.CLAIMS]
    assert len(set(classes)) == len(classes)  # one HTML class per claim


def _span(claim_id: str, word: str) -> str:
    return f'<span class="claim-verdict {verdictrole.claim_class(claim_id)}">{word}</span>'


def test_the_page_check_names_both_pages_of_a_claim_read_two_ways() -> None:
    judged = {"ch2.eq6": {"word": "mixed"}}
    a = f"<p>Eq 6: {_span('ch2.eq6', 'mixed')}.</p>"
    b = f"<p>Eq 6: {_span('ch2.eq6', 'supported')}.</p>"
    assert claimcheck.claim_problems({"a.html": a, "c.html": a}, judged) == []
    problems = claimcheck.claim_problems({"a.html": a, "b.html": b}, judged)
    assert any("'mixed' on a.html and 'supported' on b.html" in p for p in problems)
    assert any("b.html" in p and "this build judged 'mixed'" in p for p in problems)


def test_the_page_check_finds_verdict_words_outside_a_quoted_claim() -> None:
    page = (
        '<p>Claim (iii) does not hold here. <span class="verdict-category">thesis claim '
        "supported</span></p><pre>holds = True</pre>"
    )
    problems = claimcheck.stray_words(page, "x.html")
    assert len(problems) == 1 and "'does not hold'" in problems[0] and "x.html:1" in problems[0]
    unknown = claimcheck.claim_problems({"x.html": _span("ch9.none", "mixed")}, {})
    assert "a verdict of no registered claim" in unknown[0]


def test_the_active_algorithms_speed_is_judged_against_a_plain_implementation() -> None:
    spec = claimlist.claim("ch3.active_speed")
    fast = {"selection.active_same_as_plain": {"value": True}, "selection.active_over_plain": 0.01}
    assert claims.evaluate(spec, fast).word == "supported"
    slow = {**fast, "selection.active_over_plain": 0.9}
    assert claims.evaluate(spec, slow).word == "mixed"
    assert all(spec.counted)  # a measured time can fail: it counts
