"""Glue specs of a record plan that read the recorded value (and the notebook's context): each
records what the hand-written glue it replaces recorded."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
from pasting import pasting_recorder  # tests/ is on sys.path (pytest prepend import mode)

from mechlib.reporting import plans, report
from mechlib.reporting.records import Recorder, load
from mechlib.reporting.tolerances import EXACT, ROUNDOFF, Tolerance


def same(tmp_path: Path, literal: Recorder, planned: Recorder) -> dict[str, Any]:
    one = load(literal.save(tmp_path / "literal"))
    two = load(planned.save(tmp_path / "plan"))
    assert one == two
    return two


def recorder(plan: dict[str, plans.Entry] | None = None) -> tuple[Recorder, dict[str, Any]]:
    return pasting_recorder("demo", plan)


def test_glue_of_the_value_stores_the_indices_written_by_hand(tmp_path: Path) -> None:
    worst = np.array([4.0, 2.0, 9.0, 1.5, 3.0, 8.0, 6.0, 7.0])
    literal, by_hand = recorder()
    literal.value(
        "w.worst",
        worst,
        rtol=1e-9,
        glue={"worst_best": int(worst.argmin()), "worst_rom": len(worst) - 1, "first": 0},
    )
    plan = {
        "w.worst": plans.Entry(
            tol=ROUNDOFF,
            glue=lambda v: {"worst_best": v.argmin(), "worst_rom": -1, "first": 0},
        )
    }
    rec, pasted = recorder(plan)
    rec.value("w.worst", worst)
    stored = same(tmp_path, literal, rec)
    assert stored["glue"]["worst_rom"] == {"key": "w.worst", "index": 7}  # -1 as numpy reads it
    assert stored["glue"]["worst_best"] == {"key": "w.worst", "index": 3}
    assert pasted == by_hand == {"worst_best": 1.5, "worst_rom": 7.0, "first": 4.0}


def test_a_fixed_negative_index_is_stored_as_written(tmp_path: Path) -> None:
    literal, _ = recorder()
    literal.value("n.runs", [10, 20, 40], atol=0, glue={"n_max": -1})
    rec, _ = recorder({"n.runs": plans.Entry(tol=ROUNDOFF, glue={"n_max": -1})})
    rec.value("n.runs", [10, 20, 40])
    assert rec.glued["n_max"] == {"key": "n.runs", "index": -1}  # as the records hold today
    assert rec.glued == literal.glued


def test_glue_of_the_value_and_the_context(tmp_path: Path) -> None:
    exponent = np.arange(12.0).reshape(4, 3)
    worst = 2
    literal, _ = recorder()
    literal.value(
        "s.exponent",
        exponent,
        rtol=1e-9,
        glue={"p_first": (0, worst), "p_last": (len(exponent) - 1, worst)},
    )
    glue = lambda v, c: {"p_first": (0, c["worst"]), "p_last": (-1, c["worst"])}  # noqa: E731
    rec, _ = recorder({"s.exponent": plans.Entry(tol=ROUNDOFF, glue=glue)})
    with pytest.raises(ValueError, match=r"reads 'worst' from the context.*pass them as context="):
        rec.value("s.exponent", exponent)
    rec.value("s.exponent", exponent, context={"worst": worst})
    stored = same(tmp_path, literal, rec)
    assert stored["glue"]["p_last"] == {"key": "s.exponent", "index": [3, 2]}


def test_a_glue_function_may_glue_nothing() -> None:
    plan = {
        "m.change": plans.Entry(
            tol=ROUNDOFF,
            glue=lambda v, c: {"mesh_change": c["n"] - 1} if c["n"] else {},
        )
    }
    rec, pasted = recorder(plan)
    rec.value("m.change", np.zeros(0), context={"n": 0})
    assert rec.glued == {} and pasted == {}


def test_extremes_within_a_row_as_argmax_of_that_row(tmp_path: Path) -> None:
    dep = np.array([[1.0, 5.0, 2.0], [7.0, 0.0, 3.0], [2.0, 2.0, 2.0], [4.0, 9.0, -1.0]])
    R = ["x", "y", "z"]
    literal, by_hand = recorder()
    literal.value(
        "d.dep",
        dep,
        rtol=1e-9,
        glue={
            "dep_pub_t2": (0, int(dep[0].argmax())),
            "dep_nl_min": (3, int(dep[3].argmin())),
            "dep_nl": (3, int(dep[3].argmax())),
            "dep_x0": (0, 0),
        },
    )
    literal.text("dep_nl_component", R[int(dep[3].argmax())], of="d.dep")
    glue = (
        plans.Extremes(row=0, high="dep_pub_t2"),
        plans.Extremes(
            row=-1, low="dep_nl_min", high="dep_nl", labels=R, high_label="dep_nl_component"
        ),
        {"dep_x0": (0, 0)},
    )
    rec, pasted = recorder({"d.dep": plans.Entry(tol=ROUNDOFF, glue=glue)})
    rec.value("d.dep", dep)
    stored = same(tmp_path, literal, rec)
    assert stored["glue"]["dep_nl"] == {"key": "d.dep", "index": [3, 1]}
    assert pasted == by_hand and pasted["dep_nl_component"] == "y"


def test_glue_specs_naming_a_glue_twice_are_refused() -> None:
    with pytest.raises(ValueError, match=r"names \['a'\] twice"):
        plans.Entry(tol=ROUNDOFF, glue=("a", plans.Extremes(high="a")))
    plan = {"t.v": plans.Entry(tol=ROUNDOFF, glue=(plans.Extremes(high="a"), lambda v: {"a": 0}))}
    rec, _ = recorder(plan)
    with pytest.raises(ValueError, match=r"names \['a'\] twice"):
        rec.value("t.v", [1.0, 2.0])
    assert rec.values == {}


def test_glue_specs_that_cannot_glue_are_refused() -> None:
    with pytest.raises(TypeError, match="takes 3 required arguments"):
        plans.Entry(tol=ROUNDOFF, glue=lambda v, c, d: {})
    with pytest.raises(TypeError, match="plan glue must be"):
        plans.Entry(tol=ROUNDOFF, glue=(3,))  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="row must be an integer"):
        plans.Extremes(high="a", row=1.0)  # type: ignore[arg-type]
    rec, _ = recorder(
        {
            "t.far": plans.Entry(tol=ROUNDOFF, glue=lambda v: {"far": 3}),
            "t.row": plans.Entry(tol=ROUNDOFF, glue=plans.Extremes(high="hi", row=2)),
        }
    )
    with pytest.raises(ValueError, match=r"index 3 outside a value of shape \(3,\)"):
        rec.value("t.far", [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match=r"row=2 of a value of shape \(2, 2\)"):
        rec.value("t.row", np.eye(2))
    assert rec.values == {}


def test_texts_from_the_plan_are_glued_as_made_of_the_key(tmp_path: Path) -> None:
    R = np.array(["x", "y", "z"])
    pct = np.array([[3.0, 1.0, 2.0], [2.0, 4.0, 1.0]])
    mask = np.array([True, False, True])
    literal, by_hand = recorder()
    literal.value("v.range_pct", pct, rtol=1e-9, glue={"worst": (1, 1)})
    literal.text("better", ", ".join(R[mask]) or "none", of="v.range_pct")
    literal.text("worse", ", ".join(R[pct[1] > 5]) or "none", of="v.range_pct")
    literal.value("v.same", True)
    literal.text("same_dominant", "the same" if True else "not the same", of="v.same")
    plan = {
        "v.range_pct": plans.Entry(
            tol=ROUNDOFF,
            glue={"worst": (1, 1)},
            texts={
                "better": lambda v, c: ", ".join(R[c["mask"]]) or "none",
                "worse": lambda v: ", ".join(R[v[1] > 5]) or "none",
            },
        ),
        "v.same": plans.Entry(
            tol=EXACT, texts={"same_dominant": lambda v: "the same" if v else "not the same"}
        ),
    }
    rec, pasted = recorder(plan)
    rec.value("v.range_pct", pct, context={"mask": mask})
    rec.value("v.same", True)
    stored = same(tmp_path, literal, rec)
    assert stored["glue"]["better"] == {"text_of": "v.range_pct"}
    assert pasted == by_hand and pasted["better"] == "x, z" and pasted["worse"] == "none"


def test_texts_that_are_not_text_or_name_a_glue_twice_are_refused() -> None:
    with pytest.raises(ValueError, match=r"names \['a'\] twice"):
        plans.Entry(tol=EXACT, glue="a", texts={"a": str})
    with pytest.raises(TypeError, match="texts map glue names"):
        plans.Entry(tol=EXACT, texts={"a": "not a function"})  # type: ignore[dict-item]
    plan = {
        "t.n": plans.Entry(tol=EXACT, texts={"n_text": lambda v: v + 1}),
        "t.m": plans.Entry(tol=EXACT, glue=lambda v: {"m": ()}, texts={"m": str}),
    }
    rec, pasted = recorder(plan)
    with pytest.raises(ValueError, match=r"text 'n_text' must be a str or NaN, got 4"):
        rec.value("t.n", 3)
    with pytest.raises(ValueError, match=r"glues \['m'\] twice"):
        rec.value("t.m", 3)
    assert rec.values == {} and rec.glued == {} and pasted == {}


def test_a_text_made_of_several_keys_is_glued_as_made_of_them(tmp_path: Path) -> None:
    def keys(v: float, c: dict[str, Any]) -> tuple[str, ...]:
        return ("m.worst", "m.failed", "m.own") if c["some"] else ("m.none",)

    def text(v: dict[str, Any], c: dict[str, Any]) -> str:
        if not c["some"]:
            return "none compared"
        return f"up to {max(v['m.worst']):.2g} % ({v['m.failed']} failed), own {v['m.own']:.2g} %"

    plan = {
        "m.none": plans.Entry(tol=EXACT),
        "m.worst": plans.Entry(tol=ROUNDOFF, optional=True),
        "m.failed": plans.Entry(tol=EXACT, optional=True),
        "m.own": plans.Entry(tol=ROUNDOFF, texts={"summary": plans.MadeOf(keys, text)}),
    }
    worst = np.array([0.5, 0.25])
    literal, by_hand = recorder()
    literal.value("m.none", [], atol=0)
    literal.value("m.worst", worst, rtol=1e-9)
    literal.value("m.failed", 0, atol=0)
    literal.value("m.own", 0.23, rtol=1e-9)
    literal.text(
        "summary",
        f"up to {worst.max():.2g} % ({0} failed), own {0.23:.2g} %",
        of="m.worst,m.failed,m.own",
    )
    rec, pasted = recorder(plan)
    rec.value("m.none", [])
    rec.value("m.worst", worst)
    rec.value("m.failed", 0)
    rec.value("m.own", 0.23, context={"some": True})
    stored = same(tmp_path, literal, rec)
    assert stored["glue"]["summary"] == {"text_of": "m.worst,m.failed,m.own"}
    assert pasted == by_hand and pasted["summary"] == "up to 0.5 % (0 failed), own 0.23 %"
    none, pasted = recorder(plan)
    none.value("m.none", [])
    none.value("m.own", 0.23, context={"some": False})
    assert none.glued["summary"] == {"text_of": "m.none"} and pasted["summary"] == "none compared"


def test_a_text_made_of_keys_not_recorded_or_badly_given_is_refused() -> None:
    plan = {
        "u.a": plans.Entry(tol=EXACT, optional=True),
        "u.b": plans.Entry(tol=EXACT, texts={"ab": plans.MadeOf(("u.a", "u.b"), str)}),
    }
    rec, pasted = recorder(plan)
    with pytest.raises(ValueError, match=r"u\.b: its plan text is made of \['u\.a'\], which were"):
        rec.value("u.b", 1)
    assert rec.values == {} and rec.glued == {} and pasted == {}
    for keys in ((), "u.a", ("u.a", 3)):
        with pytest.raises(TypeError, match="MadeOf keys must be a tuple"):
            plans.MadeOf(keys, str)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="MadeOf text must be"):
        plans.MadeOf(("u.a",), "u.a")  # type: ignore[arg-type]


def test_skipped_gives_a_planned_keys_texts_the_label() -> None:
    plan = {"s.v": plans.Entry(tol=EXACT, glue="s_n", texts={"s_list": str}, optional=True)}
    rec, pasted = recorder(plan)
    rec.skipped("s.v", why="not computed: no runs")
    assert pasted["s_list"] == "none" and np.isnan(pasted["s_n"])
    assert rec.glued["s_list"] == {"unchecked": "not computed: no runs"}
    rec2, _ = recorder({"f.v": plans.Entry(tol=EXACT, glue=lambda v: {}, optional=True)})
    with pytest.raises(ValueError, match=r"skipped 'f\.v': its plan entry glues by a function"):
        rec2.skipped("f.v", why="not computed")


def test_rows_and_tolerance_read_the_value_from_the_context(tmp_path: Path) -> None:
    rmse = np.array([[0.5, 2.0], [1.5, 0.25]])
    literal, _ = recorder()
    literal.value(
        "t5.same",
        False,
        row=report.Check("Table 3", "same dominant", "equal: no", basis="construction"),
    )
    literal.value(
        "t5.rmse",
        rmse,
        rtol=1e-6,
        atol=1e-6 * float(np.abs(rmse).max()) + 1e-3,
        row=report.NotReproduced("Table 5", "worst RMSE", 1.0, f"tried: {rmse.max(axis=0)}"),
    )
    plan = {
        "t5.same": plans.Entry(
            tol=EXACT,
            rows=lambda c: [
                report.Check(
                    "Table 3",
                    "same dominant",
                    f"equal: {'yes' if c['value'] else 'no'}",
                    basis="construction",
                )
            ],
        ),
        "t5.rmse": plans.Entry(
            tol=lambda c: Tolerance(
                rtol=1e-6, atol=1e-6 * float(np.abs(c["value"]).max()) + c["floor"], why="test"
            ),
            rows=lambda c: [
                report.NotReproduced(
                    "Table 5", "worst RMSE", 1.0, f"tried: {c['value'].max(axis=0)}"
                )
            ],
        ),
    }
    rec, _ = recorder(plan)
    rec.value("t5.same", False)  # reads the value alone: no context needed
    with pytest.raises(ValueError, match="may not hold 'value'"):
        rec.value("t5.rmse", rmse, context={"value": rmse, "floor": 1e-3})
    rec.value("t5.rmse", rmse, context={"floor": 1e-3})
    stored = same(tmp_path, literal, rec)
    assert stored["report"][0]["ours"] == "equal: no"


def test_constants_are_recorded_as_the_calls_they_replace(tmp_path: Path) -> None:
    literal, by_hand = recorder()
    literal.value("pub.width_mm", 12.5, atol=0, glue="pub_width")
    literal.value("n.levels", 7, atol=0)
    literal.value(
        "pub.bound",
        [0.1, 0.2],
        rtol=1e-9,
        glue={"bound_hi": 1},
        row=report.Comparison("Table 1", "bound", [0.1, 0.2], rtol=0.01),
    )
    literal.value("measured", 3.5, rtol=1e-9)
    plan = {
        "pub.width_mm": plans.Entry(tol=EXACT, glue="pub_width", value=12.5),
        "measured": plans.Entry(tol=ROUNDOFF),
        "n.levels": plans.Entry(tol=EXACT, value=7),
        "pub.bound": plans.Entry(
            tol=ROUNDOFF,
            glue={"bound_hi": 1},
            rows=report.Comparison("Table 1", "bound", [0.1, 0.2], rtol=0.01),
            value=[0.1, 0.2],
        ),
    }
    rec, pasted = recorder(plan)
    assert rec.constants() == {"pub.width_mm": 12.5, "n.levels": 7, "pub.bound": [0.1, 0.2]}
    assert list(rec.values) == ["pub.width_mm", "n.levels", "pub.bound"]  # the plan's order
    rec.value("measured", 3.5)
    same(tmp_path, literal, rec)
    assert pasted == by_hand
    with pytest.raises(ValueError, match="no plan"):
        recorder()[0].constants()
    with pytest.raises(ValueError, match="no entry with value="):
        recorder({"m": plans.Entry(tol=EXACT)})[0].constants()


def test_constants_by_prefix_and_a_mapping_of_full_keys_as_the_loops_they_replace() -> None:
    quoted = {"design.published": [1.0, 2.0], "mesh.case": 3, "sweep.small": 0.5}
    literal, _ = recorder()
    for prefix, values in {"design": {"published": [1.0, 2.0]}, "mesh": {"case": 3}}.items():
        literal.mapping(prefix, values, atol=0)
    literal.value("sweep.small", 0.5, atol=0)
    literal.value("other", 1, atol=0)
    by_keys, _ = recorder()
    assert by_keys.mapping(quoted, atol=0) is quoted
    by_keys.value("other", 1, atol=0)
    assert by_keys.values == literal.values
    plan = {k: plans.Entry(tol=EXACT, value=v) for k, v in quoted.items()}
    rec, _ = recorder(plan | {"other": plans.Entry(tol=EXACT)})
    assert list(rec.constants("design.", "mesh.")) == ["design.published", "mesh.case"]
    rec.value("other", 1)
    rec.constants("sweep.")
    assert rec.values == literal.values
    with pytest.raises(ValueError, match=r"no entry with value= under \('x\.',\)"):
        rec.constants("x.")
    with pytest.raises(TypeError, match="a prefix and its values"):
        rec.mapping("design")
    with pytest.raises(TypeError, match="a prefix and its values"):
        rec.mapping(quoted, quoted)
