"""The scheduler of ``make test`` (:mod:`mechlib.pipeline.dag`) on graphs of fake commands, the
test graph's shape (:mod:`mechlib.pipeline.testgraph`) and the Makefile as a front door."""

from __future__ import annotations

import io
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

from mechlib.paths import REPO_ROOT
from mechlib.pipeline.dag import Step, check_graph, run_graph, summary
from mechlib.pipeline.testgraph import make_environment, steps, unit_halves

#: the Makefile is a front door, not a program (issue 60)
MAX_MAKEFILE_LINES = 120


def _log(path: Path, name: str, seconds: float = 0.0) -> tuple[str, ...]:
    """A command that appends ``start <name>``, sleeps, then appends ``end <name>``."""
    code = (
        "import sys, time; p = sys.argv[1]; open(p, 'a').write('start ' + sys.argv[2] + '\\n');"
        "time.sleep(float(sys.argv[3])); open(p, 'a').write('end ' + sys.argv[2] + '\\n')"
    )
    return (sys.executable, "-c", code, str(path), name, str(seconds))


def _fail(code: int = 3) -> tuple[str, ...]:
    return (sys.executable, "-c", f"print('broken'); raise SystemExit({code})")


def _run(graph: list[Step], jobs: int | None = None) -> tuple[dict, str]:
    out = io.StringIO()
    return run_graph(graph, jobs=jobs, out=out), out.getvalue()


def test_a_step_starts_after_its_dependencies_and_its_output_is_prefixed(tmp_path) -> None:
    log = tmp_path / "log"
    graph = [
        Step("c", [_log(log, "c")], after=("a", "b")),
        Step("a", [_log(log, "a", 0.2)]),
        Step("b", [_log(log, "b"), (sys.executable, "-c", "print('hello')")], after=("a",)),
    ]
    outcomes, text = _run(graph)
    lines = log.read_text().splitlines()
    assert lines == ["start a", "end a", "start b", "end b", "start c", "end c"]
    assert [o.status for o in outcomes.values()] == ["ok", "ok", "ok"]
    assert "[b] hello" in text.splitlines()
    assert summary(outcomes, 1.0)[0]


def test_independent_steps_run_at_once_and_jobs_caps_them(tmp_path) -> None:
    graph = [Step(n, [_log(tmp_path / "log", n, 1.5)]) for n in "abc"]
    _run(graph)
    # side by side: every step started before any ended (an order, not a time: a loaded machine
    # may start processes slowly, but not 1.5 s late)
    lines = (tmp_path / "log").read_text().splitlines()
    assert sorted(lines[:3]) == ["start a", "start b", "start c"]
    (tmp_path / "log").unlink()
    graph = [Step(n, [_log(tmp_path / "log", n, 0.1)]) for n in "abc"]
    _run(graph, jobs=1)
    lines = (tmp_path / "log").read_text().splitlines()
    assert lines == ["start a", "end a", "start b", "end b", "start c", "end c"]


def test_with_one_job_normal_priority_goes_before_low(tmp_path) -> None:
    log = tmp_path / "log"
    graph = [Step("side", [_log(log, "side")], low=True), Step("chain", [_log(log, "chain")])]
    outcomes, _ = _run(graph, jobs=1)
    assert log.read_text().splitlines() == ["start chain", "end chain", "start side", "end side"]
    assert all(o.status == "ok" for o in outcomes.values())  # the low wrapper runs the command


def test_a_failure_stops_the_graph_and_the_summary_names_it(tmp_path) -> None:
    log = tmp_path / "log"
    graph = [
        Step("slow", [_log(log, "slow", 30)]),
        Step("broken", [_fail(3)]),
        Step("after", [_log(log, "after")], after=("broken",)),
        Step("later", [_log(log, "later")], after=("slow",)),
    ]
    start = time.monotonic()
    outcomes, text = _run(graph)
    assert time.monotonic() - start < 15  # the slow sibling was stopped, not waited for
    status = {n: o.status for n, o in outcomes.items()}
    assert status == {"slow": "stopped", "broken": "FAILED", "after": "not run", "later": "not run"}
    # the slow step may be stopped before it writes its first line: it must never have ended
    assert not log.exists() or "end slow" not in log.read_text()
    assert "[broken] broken" in text
    ok, lines = summary(outcomes, 2.0)
    assert not ok and lines[-1].startswith("FAILED: broken")


def test_a_later_command_of_a_failed_step_does_not_run(tmp_path) -> None:
    log = tmp_path / "log"
    outcomes, _ = _run([Step("two", [_fail(1), _log(log, "second")])])
    assert outcomes["two"].status == "FAILED" and not log.exists()


def test_a_skipped_step_lets_those_after_it_run(tmp_path) -> None:
    log = tmp_path / "log"
    graph = [
        Step("tool", [_fail()], skip=lambda: "no such tool here"),
        Step("next", [_log(log, "next")], after=("tool",)),
    ]
    outcomes, text = _run(graph)
    assert [o.status for o in outcomes.values()] == ["skipped", "ok"]
    assert "[tool] skipped: no such tool here" in text


def test_a_command_that_does_not_exist_fails_its_step() -> None:
    outcomes, _ = _run([Step("gone", [("/nonexistent/command",)])])
    assert outcomes["gone"].status == "FAILED"


@pytest.mark.parametrize(
    ("graph", "message"),
    [
        ([Step("a", []), Step("a", [])], "unique"),
        ([Step("a", [], after=("z",))], "unknown steps"),
        ([Step("a", [], after=("b",)), Step("b", [], after=("a",))], "cycle"),
    ],
)
def test_a_graph_that_is_no_dag_is_refused(graph, message) -> None:
    with pytest.raises(ValueError, match=message):
        check_graph(graph)


def test_the_test_graph_keeps_make_tests_order() -> None:
    graph = {s.name: s for s in steps("Sandybridge")}
    check_graph(list(graph.values()))
    assert graph["notebooks"].env == {"OPENBLAS_CORETYPE": "Sandybridge"}
    assert graph["rerun"].env == {"OPENBLAS_CORETYPE": "Sandybridge"}
    assert graph["check-records"].env == {"MECHLIB_TEST_KERNEL": "Sandybridge"}
    assert graph["rerun"].after == ("check-records",) and graph["book"].after == ("check-records",)
    assert graph["determinism"].after == ("rerun",)
    assert {n for n, s in graph.items() if s.low} == {"unit-a", "unit-b", "store-check"}
    assert "MALLOC_MMAP_MAX_" in graph["store-check"].env


def test_the_unit_tests_are_split_in_two_without_the_other_steps_files() -> None:
    a, b = unit_halves()
    assert not set(a) & set(b) and abs(len(a) - len(b)) <= 1
    assert "tests/test_records.py" not in a + b and "tests/test_testgraph.py" in a + b


def test_a_calling_makes_job_server_is_not_passed_on() -> None:
    flags = " -j4 --jobserver-auth=3,4 -- BOOK_JOBS=1"
    env = make_environment({"MAKEFLAGS": flags, "MFLAGS": "-j4"})
    assert env["MAKEFLAGS"] == "-- BOOK_JOBS=1" and "MFLAGS" not in env


def test_the_makefile_is_a_short_front_door_whose_help_lists_every_target() -> None:
    makefile = (REPO_ROOT / "Makefile").read_text()
    assert len(makefile.splitlines()) <= MAX_MAKEFILE_LINES
    phony = re.search(r"^\.PHONY:(.*)$", makefile, re.M)
    assert phony
    targets = set(phony.group(1).split()) - {"help"}
    rules = set(re.findall(r"^([a-z][a-z-]*):", makefile, re.M)) - {"help"}
    assert rules == targets  # every target by name is phony (and so listed below)
    helped = subprocess.run(
        ["make", "--no-print-directory", "help"], cwd=REPO_ROOT, capture_output=True, text=True
    )
    assert helped.returncode == 0, helped.stderr
    listed = set(re.findall(r"make ([a-z][a-z-]*)", helped.stdout))
    assert sorted(targets - listed) == []


def test_a_terminated_test_graph_stops_its_steps_and_exits_130(tmp_path) -> None:
    script = (
        "import sys; from mechlib.pipeline import dag, testgraph;"
        "testgraph.steps = lambda kernel: [dag.Step('sleep', [('sleep', '60')])];"
        "sys.exit(testgraph.main(['--kernel', 'Haswell']))"
    )
    proc = subprocess.Popen(
        [sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True
    )
    assert proc.stdout is not None
    for line in proc.stdout:
        if line.startswith("[sleep] $"):
            break
    start = time.monotonic()
    proc.terminate()
    rest = proc.stdout.read()
    assert proc.wait(timeout=30) == 130 and time.monotonic() - start < 15
    assert "interrupted" in rest
