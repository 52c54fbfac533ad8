"""Record plans and named tolerances: a chapter's keys, tolerances, glue and rows as data."""

from __future__ import annotations

import sys
import types
from pathlib import Path

import numpy as np
import pytest

from mechlib.reporting import plans, report, tolerances
from mechlib.reporting.records import Recorder, load
from mechlib.reporting.tolerances import EXACT, ROUNDOFF, Tolerance

PLAN = {
    "a.count": plans.Entry(tol=EXACT, glue="n_a"),
    "a.ratio": plans.Entry(
        tol=ROUNDOFF,
        glue={"r0": 0},
        rows=report.Comparison("Table 1", "ratio", [1.0, 2.0], rtol=0.01),
    ),
    "a.holds": plans.Entry(
        tol=EXACT,
        rows=lambda c: [
            report.Check("Table 1", "it holds", f"range: {c['span']}", basis="construction")
        ],
    ),
    "a.maybe": plans.Entry(tol=EXACT, optional=True),
}


def planned(**kwargs: object) -> Recorder:
    return Recorder("demo", paste=lambda name, value: None, plan=PLAN, **kwargs)


def test_a_plan_gives_the_same_record_as_the_literal_arguments(tmp_path: Path) -> None:
    literal = Recorder("demo", paste=lambda name, value: None)
    literal.value("a.count", 3, atol=0, glue="n_a")
    literal.value(
        "a.ratio",
        [1.0, 2.0],
        rtol=1e-9,
        glue={"r0": 0},
        row=report.Comparison("Table 1", "ratio", [1.0, 2.0], rtol=0.01),
    )
    literal.value(
        "a.holds",
        True,
        row=report.Check("Table 1", "it holds", "range: 1 to 2", basis="construction"),
    )
    rec = planned()
    rec.value("a.count", 3)
    rec.value("a.ratio", [1.0, 2.0])
    rec.value("a.holds", True, context={"span": "1 to 2"})
    one = load(literal.save(tmp_path / "literal"))
    two = load(rec.save(tmp_path / "plan"))
    assert one == two
    assert two["values"]["a.ratio"] == {"value": [1.0, 2.0], "rtol": 1e-9, "atol": 0.0}
    assert two["report"][1]["ours"] == "range: 1 to 2"


def test_an_unrecorded_plan_entry_is_refused_at_save_by_name(tmp_path: Path) -> None:
    rec = planned()
    rec.value("a.count", 3)
    with pytest.raises(ValueError, match=r"not recorded: a\.ratio, a\.holds \(") as error:
        rec.save(tmp_path)
    assert "a.maybe" not in str(error.value)  # optional
    assert not (tmp_path / "demo.json").exists()


def test_a_key_not_in_the_plan_and_literal_arguments_are_refused() -> None:
    rec = planned()
    with pytest.raises(ValueError, match=r"'a\.other' is not in demo's plan"):
        rec.value("a.other", 1)
    with pytest.raises(ValueError, match="drop rtol, glue= here"):
        rec.value("a.count", 3, rtol=1e-9, glue="n")
    assert rec.values == {}
    with pytest.raises(ValueError, match="context= is read by a plan"):
        Recorder("demo").value("a.count", 3, atol=0, context={"span": ""})


def test_rows_from_the_context_need_it_and_only_they_take_one() -> None:
    rec = planned()
    with pytest.raises(ValueError, match="pass them as context="):
        rec.value("a.holds", True)
    with pytest.raises(ValueError, match=r"reads 'span' from the context, which holds \['s'\]"):
        rec.value("a.holds", True, context={"s": "1"})
    with pytest.raises(ValueError, match="reads no context"):
        rec.value("a.count", 3, context={"span": "1"})
    rec.value("a.holds", False, context={"span": "0 to 1"})
    assert rec.report[0]["ours"] == "range: 0 to 1"


def test_a_plan_entry_and_a_plan_are_checked() -> None:
    with pytest.raises(TypeError, match="Tolerance or tol"):
        plans.Entry(tol=1e-9)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="report rows"):
        plans.Entry(tol=EXACT, rows=["a row"])  # type: ignore[list-item]
    with pytest.raises(TypeError, match="'x' must be a str mapped to an Entry"):
        Recorder("demo", plan={"x": EXACT})  # type: ignore[dict-item]
    with pytest.raises(ValueError, match="no record plan for 'no_such_notebook'"):
        plans.load("no_such_notebook")
    with pytest.raises(ValueError, match="notebook's name"):
        plans.load("../x")


def test_an_entry_refuses_texts_and_glue_of_another_kind() -> None:
    with pytest.raises(TypeError, match=r"Entry texts map glue names to .*: 3"):
        plans.Entry(tol=EXACT, texts={3: lambda v: "a"})  # type: ignore[dict-item]
    with pytest.raises(TypeError, match=r"Entry texts map glue names to .*: 'label'"):
        plans.Entry(tol=EXACT, texts={"label": "not a function"})  # type: ignore[dict-item]
    with pytest.raises(TypeError, match=r"Entry texts map glue names to .*: ''"):
        plans.Entry(tol=EXACT, texts={"": lambda v: "a"})
    with pytest.raises(ValueError, match=r"glue names \['n'\] twice \(in glue and in texts\)"):
        plans.Entry(tol=EXACT, glue="n", texts={"n": lambda v: "a"})
    with pytest.raises(TypeError, match="MadeOf keys must be a tuple of record keys"):
        plans.MadeOf(keys=["a.b"], text=lambda values: "a")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="MadeOf text must be text"):
        plans.MadeOf(keys=("a.b",), text="a")  # type: ignore[arg-type]


def test_a_plan_that_is_no_mapping_of_keys_to_entries_is_refused_naming_it() -> None:
    with pytest.raises(TypeError, match="demo's plan must be a mapping key -> Entry, got <class"):
        Recorder("demo", plan=[("a.count", PLAN["a.count"])])  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="demo's plan: 3 must be a str mapped to an Entry"):
        Recorder("demo", plan={3: PLAN["a.count"]})  # type: ignore[dict-item]
    with pytest.raises(TypeError, match=r"'a\.count' must be a str mapped to an Entry"):
        Recorder("demo", plan={"a.count": PLAN["a.count"].tol})  # type: ignore[dict-item]


def test_a_plan_is_loaded_by_a_notebooks_name_only(monkeypatch: pytest.MonkeyPatch) -> None:
    # a module starting with _ holds what several plans share, not a plan
    with pytest.raises(ValueError, match="got '_virtual_experiments_rows'"):
        plans.load("_virtual_experiments_rows")
    for name in ("Published_doe", "published-doe", ""):
        with pytest.raises(ValueError, match=f"notebook's name .*, got '{name}'"):
            plans.recorder(name)
    helper = types.ModuleType(f"{plans.__name__}.shared_rows")  # a module without PLAN
    monkeypatch.setitem(sys.modules, helper.__name__, helper)
    with pytest.raises(ValueError, match=r"plans\.shared_rows holds no PLAN"):
        plans.load("shared_rows")
    assert plans.load("published_doe") is plans.recorder("published_doe").plan


def test_a_tolerance_class_stores_the_literal_numbers() -> None:
    assert (ROUNDOFF.rtol, ROUNDOFF.atol) == (1e-9, 0.0)
    assert (EXACT.rtol, EXACT.atol) == (0.0, 0.0)
    named = [v for v in vars(tolerances).values() if isinstance(v, Tolerance)]
    assert len({(t.rtol, t.atol, t.peak, t.why) for t in named}) == len(named)
    assert all(t.why.strip() for t in named)
    scaled = Tolerance(rtol=1e-6, peak=1e-6, why="round-off of the largest entry")
    assert scaled.atol_for(np.array([-3.0, 2.0])) == 1e-6 * np.abs(np.array([-3.0, 2.0])).max()
    assert ROUNDOFF.atol_for([5.0]) == 0.0


def test_a_tolerance_with_a_bad_bound_or_no_reason_is_refused() -> None:
    with pytest.raises(ValueError, match="rtol must be finite and >= 0, got -1"):
        Tolerance(rtol=-1, why="x")
    with pytest.raises(ValueError, match="atol must be a number"):
        Tolerance(atol=True, why="x")
    with pytest.raises(ValueError, match="why= is empty"):
        Tolerance(rtol=1e-9)


def test_a_tolerance_from_the_context() -> None:
    plan = {
        "b.x": plans.Entry(
            tol=lambda c: Tolerance(atol=c["floor"], why="a floor the notebook computes")
        )
    }
    rec = Recorder("demo", paste=lambda name, value: None, plan=plan)
    rec.value("b.x", 2.0, context={"floor": 0.5})
    assert rec.values["b.x"] == {"value": 2.0, "rtol": 0.0, "atol": 0.5}


def test_extremes_glue_the_same_indices_and_labels_as_argmin_argmax(tmp_path: Path) -> None:
    value = np.array([3.0, 1.0, 5.0, 5.0])
    labels = ["x", "y", "z", "w"]
    literal = Recorder("demo", paste=lambda name, value: None)
    literal.value("e.v", value, rtol=1e-9, glue={"v_lo": 1, "v_hi": 2, "v0": 0})
    literal.text("v_hi_label", labels[int(value.argmax())], of="e.v")
    pasted: dict[str, object] = {}
    plan = {
        "e.v": plans.Entry(
            tol=ROUNDOFF,
            glue=plans.Extremes(
                low="v_lo", high="v_hi", labels=labels, high_label="v_hi_label", fixed={"v0": 0}
            ),
        )
    }
    rec = Recorder("demo", paste=pasted.__setitem__, plan=plan)
    rec.value("e.v", value)
    assert load(literal.save(tmp_path / "a")) == load(rec.save(tmp_path / "b"))
    assert pasted == {"v_lo": 1.0, "v_hi": 5.0, "v0": 3.0, "v_hi_label": "z"}
    grid = plans.Extremes(low="g_lo", high="g_hi").glue(np.array([[1.0, -2.0], [7.0, 0.0]]))
    assert grid == ({"g_lo": (0, 1), "g_hi": (1, 0)}, {})


def test_extremes_refuse_what_they_cannot_glue() -> None:
    with pytest.raises(ValueError, match="glues nothing"):
        plans.Extremes()
    with pytest.raises(ValueError, match="needs labels"):
        plans.Extremes(low_label="lo")
    with pytest.raises(ValueError, match="names a glue twice"):
        plans.Extremes(low="a", high="a")
    with pytest.raises(ValueError, match=r"2 labels for a value of shape \(3,\)"):
        plans.Extremes(low_label="lo", labels=["a", "b"]).glue([1.0, 2.0, 3.0])


def test_a_mapping_records_one_key_per_name() -> None:
    rec = Recorder("demo", paste=lambda name, value: None)
    geometry = {"width": 2.0, "depth": 3.0}
    assert rec.mapping("geometry", geometry, rtol=1e-6) is geometry
    assert rec.values == {
        "geometry.width": {"value": 2.0, "rtol": 1e-6, "atol": 0.0},
        "geometry.depth": {"value": 3.0, "rtol": 1e-6, "atol": 0.0},
    }


def test_skipped_glue_nan_with_the_reason_as_the_loop_it_replaces() -> None:
    literal = Recorder("demo", paste=lambda name, value: None)
    for name in ("q_dep", "q_lin"):
        literal.text(name, float("nan"), why="not computed: one order")
    literal.text("q_label", "none", why="not computed: one order")
    plan = {
        "q.v": plans.Entry(
            tol=ROUNDOFF,
            glue=plans.Extremes(high="q_lin", labels=["a"], high_label="q_label"),
            optional=True,
        ),
        "q.empty": plans.Entry(tol=EXACT, optional=True),
    }
    pasted: dict[str, object] = {}
    rec = Recorder("demo", paste=pasted.__setitem__, plan=plan)
    rec.skipped("q_dep", why="not computed: one order")
    rec.skipped(["q.v"], why="not computed: one order")
    assert rec.glued == literal.glued
    assert np.isnan(pasted["q_dep"]) and pasted["q_label"] == "none"
    with pytest.raises(ValueError, match="glues nothing"):
        rec.skipped("q.empty", why="x")
    with pytest.raises(ValueError, match="say why"):
        rec.skipped("other", why=" ")


def test_a_tolerance_scaled_by_a_reference_is_the_float_written_by_hand(tmp_path: Path) -> None:
    eff = np.array([[0.3, -7.25], [1e-9, 2.0]])
    value = np.array([1e-3, 4.0])
    literal = Recorder("demo", paste=lambda name, value: None)
    literal.value("s.me", value, rtol=1e-6, atol=1e-6 * np.abs(eff).max())
    literal.value("s.pose", eff, rtol=2e-3, atol=1e-6 * np.abs(eff).max())
    peaked = Tolerance(rtol=1e-6, peak=1e-6, why="round-off of the largest effect")
    plan = {
        "s.me": plans.Entry(tol=lambda c: peaked.scaled(c["eff"])),
        "s.pose": plans.Entry(tol=Tolerance(rtol=2e-3, peak=1e-6, why="of the largest entry")),
    }
    rec = Recorder("demo", paste=lambda name, value: None, plan=plan)
    rec.value("s.me", value, context={"eff": eff})
    rec.value("s.pose", eff)
    assert load(literal.save(tmp_path / "a")) == load(rec.save(tmp_path / "b"))
    scaled = peaked.scaled(eff)
    assert (scaled.atol, scaled.peak, scaled.why) == (7.25e-6, 0.0, peaked.why)
    assert ROUNDOFF.scaled(eff) is ROUNDOFF  # no peak: nothing to scale
    with pytest.raises(ValueError, match="reference must be finite numbers"):
        peaked.scaled([np.nan])


def test_each_named_tolerance_is_defined_in_one_module_and_reexported() -> None:
    import importlib
    import pkgutil

    modules = [
        importlib.import_module(f"{tolerances.__name__}.{m.name}")
        for m in pkgutil.iter_modules(tolerances.__path__)
    ]
    owners: dict[str, list[str]] = {}
    for module in modules:
        for name, v in vars(module).items():
            if isinstance(v, Tolerance) or getattr(v, "__module__", None) == module.__name__:
                owners.setdefault(name, []).append(module.__name__)
    assert {n: m for n, m in owners.items() if len(m) > 1} == {}  # a star import would hide one
    assert all(
        getattr(tolerances, n) is getattr(importlib.import_module(m[0]), n)
        for n, m in owners.items()
    )
    assert "ROUNDOFF" in owners and "EXACT" in owners


def test_the_levels_row_quotes_the_designs_ranges_as_the_page_wrote_them() -> None:
    span = {"Table 2": (-1.0, 1.0), "Table 4": (-0.5, 1.0)}
    by_hand = "; ".join(  # the text the page built and passed before
        f"{name}: {lo:g} to {hi:g} N".replace("-", "−") for name, (lo, hi) in span.items()
    )
    rec = plans.recorder("published_doe", paste=lambda name, value: None)
    rec.value("table1.designs_span_the_levels", False, context={"span": span})
    assert rec.report[0]["ours"] == f"level ranges: {by_hand}"
    assert by_hand == "Table 2: −1 to 1 N; Table 4: −0.5 to 1 N"
