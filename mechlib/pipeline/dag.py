"""A small scheduler of command-line steps: a DAG with dependencies and priorities.

A :class:`Step` is a named list of commands (run one after another) with the steps it waits
for; :func:`run_graph` starts every step whose dependencies succeeded as soon as it is ready
(normal-priority steps before low-priority ones when ``jobs`` caps how many run at once), streams
each step's output line by line with its name as a prefix, and fails fast: after the first
failure it starts no other step and stops those running. It returns one :class:`Outcome` per
step, which :func:`summary` prints. Standard library only; ``make test`` runs its graph
(:mod:`mechlib.pipeline.testgraph`) with it.

A low-priority step runs in a session of its own whose scheduling group is made nicer as well
as its processes (``nice``): Linux shares the cores fairly between sessions (autogroups, on by
default), and every notebook kernel starts a session of its own, so ``nice`` alone would not rank
the step below the notebooks (:data:`LOW_PRIORITY`).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TextIO

#: How a low-priority step's command starts: in its new session (``start_new_session``) the shell
#: lowers the session's autogroup where the machine has autogroups, then runs the command niced.
#: Each low-priority step has a session of its own, so each is made nicer (10) than the one
#: session the three shared under make (5): three autogroups of weight 110 weigh about what one
#: of 335 did against the notebooks' sessions (1024 each).
LOW_PRIORITY = (
    "sh",
    "-c",
    "if test -w /proc/self/autogroup; then echo 10 > /proc/self/autogroup; fi; "
    'exec nice -n 10 "$@"',
    "low",
)
#: Seconds a stopped step has between SIGTERM and SIGKILL.
STOP_GRACE_S = 10.0


@dataclass(frozen=True)
class Step:
    """One step of a graph.

    Parameters
    ----------
    name : str
        Its name: the prefix of its output lines and its row in the summary.
    commands : sequence of sequence of str
        Command lines (argv) run one after another; the step fails with the first that fails.
    after : tuple of str
        Names of the steps that must succeed before it starts.
    low : bool
        Run at a low priority (:data:`LOW_PRIORITY`): work nothing waits on.
    env : mapping of str to str
        Variables set for its commands on top of the scheduler's environment.
    skip : callable returning str or None, optional
        Asked when the step is ready: a reason to skip it (the step then counts as done, and the
        steps after it run), or None to run it.
    """

    name: str
    commands: Sequence[Sequence[str]]
    after: tuple[str, ...] = ()
    low: bool = False
    env: Mapping[str, str] = field(default_factory=dict)
    skip: Callable[[], str | None] | None = None


@dataclass
class Outcome:
    """What became of a step: ``status`` is one of ``ok``, ``skipped``, ``FAILED``, ``stopped``
    (stopped after another step failed) or ``not run``; ``seconds`` its wall time."""

    name: str
    status: str = "not run"
    seconds: float = 0.0
    detail: str = ""


def check_graph(steps: Sequence[Step]) -> None:
    """Raise ``ValueError`` on a duplicate name, an unknown dependency or a cycle."""
    names = [s.name for s in steps]
    if len(set(names)) != len(names):
        raise ValueError(f"step names must be unique, got {names}")
    for s in steps:
        unknown = sorted(set(s.after) - set(names))
        if unknown:
            raise ValueError(f"step {s.name!r} waits for unknown steps {unknown}; have {names}")
    done: set[str] = set()
    left = list(steps)
    while left:
        ready = [s for s in left if set(s.after) <= done]
        if not ready:
            raise ValueError(f"the steps {[s.name for s in left]} wait for each other (a cycle)")
        done.update(s.name for s in ready)
        left = [s for s in left if s.name not in done]


class _Printer:
    """Writes whole lines to one stream from several threads."""

    def __init__(self, out: TextIO) -> None:
        self.out, self.lock = out, threading.Lock()

    def line(self, text: str) -> None:
        with self.lock:
            self.out.write(text.rstrip("\n") + "\n")
            self.out.flush()


def _run_step(
    step: Step, env: Mapping[str, str], printer: _Printer, procs: dict, stop: threading.Event
) -> int:
    """Run a step's commands one after another; the exit code of the first that fails, or 0
    (-1 when ``stop`` was set before a command started)."""
    for argv in step.commands:
        if stop.is_set():
            return -1
        printer.line(f"[{step.name}] $ {' '.join(argv)}")
        command = [*LOW_PRIORITY, *argv] if step.low else list(argv)
        with subprocess.Popen(
            command,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
            env={**env, **step.env},
            text=True,
            errors="replace",
            bufsize=1,
            # a group of its own, so a stop reaches every process it started; a low step a
            # session of its own as well (its autogroup)
            start_new_session=step.low,
            process_group=None if step.low else 0,
        ) as proc:
            procs[step.name] = proc
            if stop.is_set():
                _stop(proc)
            assert proc.stdout is not None
            for text in proc.stdout:
                printer.line(f"[{step.name}] {text}")
            code = proc.wait()
        if code != 0:
            return code
    return 0


def _stop(proc: subprocess.Popen) -> None:
    """SIGTERM a step's process group; SIGKILL it after :data:`STOP_GRACE_S`."""
    for sig, wait in ((signal.SIGTERM, STOP_GRACE_S), (signal.SIGKILL, None)):
        try:
            os.killpg(proc.pid, sig)
        except (ProcessLookupError, PermissionError):
            return
        if wait is None:
            return
        try:
            proc.wait(timeout=wait)
            return
        except subprocess.TimeoutExpired:
            continue


def run_graph(
    steps: Sequence[Step],
    jobs: int | None = None,
    env: Mapping[str, str] | None = None,
    out: TextIO | None = None,
) -> dict[str, Outcome]:
    """Run ``steps``, each once its dependencies succeeded, and return their outcomes.

    Parameters
    ----------
    steps : sequence of Step
        The graph (checked by :func:`check_graph`); the order breaks ties between ready steps.
    jobs : int, optional
        At most this many steps at once (normal priority first); None: every ready step.
    env : mapping, optional
        The commands' environment (default: this process's).
    out : text stream, optional
        Where the prefixed output goes (default: ``sys.stdout``).

    Returns
    -------
    dict of str to Outcome
        By step name, in the order of ``steps``.

    Raises
    ------
    ValueError
        If the graph is not a DAG of uniquely named steps, or ``jobs`` < 1.
    """
    check_graph(steps)
    if jobs is not None and jobs < 1:
        raise ValueError(f"jobs must be >= 1 or None, got {jobs}")
    env = dict(os.environ if env is None else env)
    printer = _Printer(sys.stdout if out is None else out)
    outcomes = {s.name: Outcome(s.name) for s in steps}
    done: set[str] = set()
    running: dict[str, tuple[threading.Thread, float]] = {}
    procs: dict[str, subprocess.Popen] = {}
    codes: dict[str, int] = {}
    finished = threading.Condition()
    stop = threading.Event()
    failed = False

    def work(step: Step) -> None:
        try:
            code = _run_step(step, env, printer, procs, stop)
        except OSError as err:  # a command that does not exist
            printer.line(f"[{step.name}] {err}")
            code = 127
        with finished:
            codes[step.name] = code
            finished.notify()

    try:
        while True:
            ready = [
                s
                for s in steps
                if outcomes[s.name].status == "not run"
                and s.name not in running
                and set(s.after) <= done
            ]
            ready.sort(key=lambda s: s.low)  # stable: the graph's order within a priority
            for step in ready:
                if failed or (jobs is not None and len(running) >= jobs):
                    break
                reason = step.skip() if step.skip else None
                if reason is not None:
                    outcomes[step.name] = Outcome(step.name, "skipped", detail=reason)
                    printer.line(f"[{step.name}] skipped: {reason}")
                    done.add(step.name)
                    continue
                printer.line(f"==> {step.name} started" + (" (low priority)" if step.low else ""))
                thread = threading.Thread(target=work, args=(step,), daemon=True)
                running[step.name] = (thread, time.monotonic())
                thread.start()
            if not running:
                if not failed and any(
                    outcomes[s.name].status == "not run" and set(s.after) <= done for s in steps
                ):
                    continue  # a skipped step made others ready
                break
            with finished:
                while not codes:
                    finished.wait()
                name, code = codes.popitem()
            thread, start = running.pop(name)
            thread.join()
            seconds = time.monotonic() - start
            if outcomes[name].status == "stopped":
                outcomes[name].seconds = seconds
                printer.line(f"<== {name} stopped ({seconds:.0f} s)")
            elif code == 0:
                outcomes[name] = Outcome(name, "ok", seconds)
                done.add(name)
                printer.line(f"<== {name} ok ({seconds:.0f} s)")
            else:
                outcomes[name] = Outcome(name, "FAILED", seconds, f"exit code {code}")
                printer.line(f"<== {name} FAILED (exit code {code}, {seconds:.0f} s)")
                if not failed:
                    failed = True
                    stop.set()
                    for other in running:
                        outcomes[other].status = "stopped"
                        if other in procs:
                            printer.line(f"==> stopping {other}: {name} failed")
                            _stop(procs[other])
    except KeyboardInterrupt:
        stop.set()
        for name in running:
            outcomes[name].status = "stopped"
            if name in procs:
                _stop(procs[name])
        raise
    return outcomes


def summary(outcomes: Mapping[str, Outcome], wall_s: float) -> tuple[bool, list[str]]:
    """Whether every step succeeded (or was skipped), and the summary's lines."""
    ok = all(o.status in ("ok", "skipped") for o in outcomes.values())
    width = max(len(n) for n in outcomes)
    lines = [f"{'step':<{width}}  status   seconds  detail"]
    for o in outcomes.values():
        lines.append(f"{o.name:<{width}}  {o.status:<7}  {o.seconds:7.0f}  {o.detail}".rstrip())
    failed = [o.name for o in outcomes.values() if o.status == "FAILED"]
    lines.append(
        f"all {len(outcomes)} steps passed in {wall_s:.0f} s"
        if ok
        else f"FAILED: {', '.join(failed) or 'interrupted'} (after {wall_s:.0f} s); "
        "the steps marked 'stopped' or 'not run' did not finish"
    )
    return ok, lines
