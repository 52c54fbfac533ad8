"""The recorder's calls that do several things at once: each records what the separate calls
it replaces recorded."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from mechlib.reporting import claimrules, claims
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
