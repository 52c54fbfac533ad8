"""The recorder's calls that do several things at once: each records what the separate calls
it replaces recorded."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest

from mechlib.reporting import claimrules, claims, plans
from mechlib.reporting.records import Recorder, load

SPECS = {
    cid: claims.ClaimSpec(
        cid, "ours", "Table 5", f"{ref} is small", "demo", (claimrules.at_most("p", ref, 1.0, "%"),)
    )
    for cid, ref in (("t.a", "a_pct"), ("t.b", "b_pct"), ("t.c", "a_pct"))
}


def judged(*calls: tuple[str, ...]) -> dict[str, Any]:
    rec = Recorder("demo", paste=lambda name, value: None, registry=SPECS.__getitem__)
    rec.value("a_pct", 0.5, rtol=1e-9)
    rec.value("b_pct", 3.0, rtol=1e-9)
    words = [rec.claim(*ids) for ids in calls]
    return {"words": words, "values": rec.values, "report": rec.report}


def test_several_claims_in_one_call_record_as_the_separate_calls() -> None:
    one = judged(("t.a",), ("t.b",), ("t.c",))
    many = judged(("t.a", "t.b", "t.c"))
    assert one["values"] == many["values"] and one["report"] == many["report"]
    assert one["words"] == ["holds", "does not hold", "holds"]
    assert many["words"] == [["holds", "does not hold", "holds"]]
    assert [r["claim"] for r in many["report"][-3:]] == ["t.a", "t.b", "t.c"]


def test_claims_need_an_id_and_a_registry(tmp_path: Path) -> None:
    rec = Recorder("demo", paste=lambda name, value: None, registry=SPECS.__getitem__)
    with pytest.raises(ValueError, match="name at least one id"):
        rec.claim()
    with pytest.raises(ValueError, match=r"registry=claimlist\.claim"):
        Recorder("demo").claim("t.a")
    rec.value("a_pct", 0.5, rtol=1e-9)
    assert rec.claim("t.a") == "holds"
    assert load(rec.save(tmp_path))["values"]["claims.t.a"]["value"] == "holds"


def test_data_described_by_the_plan_as_by_the_call(tmp_path: Path) -> None:
    table = pd.DataFrame({"runs": [16, 32], "err [%]": [1.5, 0.25]})
    n = 12
    literal = Recorder("demo", paste=lambda name, value: None)
    literal.add_data("curves", table, about=f"learning curves over {n} held-out runs")
    literal.add_data("model", {"coef": np.eye(2)}, about="the model")
    data = {
        "curves": lambda c: f"learning curves over {c['n']} held-out runs",
        "model": "the model",
    }
    rec = Recorder("demo", paste=lambda name, value: None, about=data)
    rec.add_data("curves", table, context={"n": n})
    rec.add_data("model", {"coef": np.eye(2)})
    assert rec.data == literal.data
    one, two = literal.save(tmp_path / "a"), rec.save(tmp_path / "b")
    index = Path("data") / "demo" / "index.json"
    assert (one.parent / index).read_text() == (two.parent / index).read_text()


def test_data_descriptions_are_given_once() -> None:
    rec = Recorder("demo", about={"m": "the model", "c": lambda c: f"{c['n']} runs"})
    with pytest.raises(ValueError, match="both here and in the plan's DATA"):
        rec.add_data("m", {}, about="x")
    with pytest.raises(ValueError, match="nowhere"):
        rec.add_data("other", {})
    with pytest.raises(ValueError, match="read by an about"):
        rec.add_data("m", {}, context={"n": 1})
    with pytest.raises(ValueError, match=r"reads 'n' from context=\[\]"):
        rec.add_data("c", {})
    assert rec.data == {}


def test_timing_glue_from_the_plan_as_by_the_call() -> None:
    literal = Recorder("demo", paste=lambda name, value: None)
    literal.timing("realtime.best_us", 3.5, glue="t_best")
    literal.timing("solve.seconds", 2.0)
    rec = Recorder(
        "demo", paste=lambda name, value: None, timing_glue={"realtime.best_us": "t_best"}
    )
    rec.timing("realtime.best_us", 3.5)
    rec.timing("solve.seconds", 2.0)
    assert (rec.timings, rec.glued) == (literal.timings, literal.glued)
    again = Recorder("demo", timing_glue={"realtime.best_us": "t_best"})
    with pytest.raises(ValueError, match="drop glue= here"):
        again.timing("realtime.best_us", 1.0, glue="t")


def test_a_chapters_recorder_carries_its_plan_data_and_timings() -> None:
    rec = plans.recorder("published_doe", paste=lambda name, value: None)
    assert rec.plan is plans.load("published_doe")
    assert rec.notebook == "published_doe" and rec.about == {} and rec.timing_glue == {}
    assert rec.unchecked == {}
    with pytest.raises(ValueError, match="no record plan"):
        plans.recorder("no_such_notebook")


def test_timing_glue_is_the_plans_where_there_is_a_plan() -> None:
    rec = Recorder("demo", plan={}, timing_glue={"solve.seconds": "t_solve"})
    with pytest.raises(ValueError, match=r"timing 'other\.seconds': demo records by its plan"):
        rec.timing("other.seconds", 1.0, glue="t_other")
    assert rec.timings == {} and rec.glued == {}
    # the chapters that glued timings in the call now name the glue in TIMINGS, the same names
    assert plans.recorder("virtual_experiments").timing_glue == {
        "latency.st_forward_us": "latency_one_us",
        "latency.fe_case_ms": "latency_fe_ms",
    }
    timing_glue = plans.recorder("fivebar_identification").timing_glue
    assert timing_glue == {"selection.active_over_plain": "active_ratio"}


def test_a_reason_a_text_is_not_checked_said_once_in_the_plan_as_in_each_call() -> None:
    why = "a timing on the machine that built the page (not recorded)"
    literal = Recorder("demo", paste=lambda name, value: None)
    literal.text("run_s", "2.5", why=why)
    literal.text("rom_us", "40", why=why)
    rec = Recorder("demo", paste=lambda name, value: None, unchecked=dict.fromkeys(["run_s"], why))
    rec.text("run_s", "2.5")
    rec.text("rom_us", "40", why=why)  # a name the plan does not give: as before
    assert rec.glued == literal.glued == {"run_s": {"unchecked": why}, "rom_us": {"unchecked": why}}
    with pytest.raises(ValueError, match=r"text 'run_s': the plan's UNCHECKED .* drop why= here"):
        Recorder("demo", unchecked={"run_s": why}).text("run_s", "2.5", why="other")
    with pytest.raises(ValueError, match="drop of= here"):
        Recorder("demo", unchecked={"run_s": why}).text("run_s", "2.5", of="a.key")
    with pytest.raises(ValueError, match="made of"):
        rec.text("other", "1")  # neither of= nor why=, nor a reason in the plan
    # the meta-model page's timing texts, each with the reason it wrote in every call before
    unchecked = plans.recorder("nonlinear_metamodels").unchecked
    assert set(unchecked.values()) == {why} and {"full_run_s", "rt_newton_share"} <= set(unchecked)
