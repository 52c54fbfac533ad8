"""The FE campaigns' progress of a notebook being executed, shown on the build's terminal.

The kernel's FE campaigns report to a file (``$MECHLIB_PROGRESS``,
:mod:`mechlib.progress`); :class:`ProgressView` follows that file from the
process that runs papermill and draws what it says, so nothing of it lands in the executed
page. A campaign whose tasks are all in the cache says nothing. One that computes says, before
it starts, how many tasks it will compute on how many workers and how long that should take
(from the seconds a task took on this machine last time), then, on a terminal, keeps one tqdm
line up to date (tasks done / to compute, cached, workers, tasks a second, ETA); in a log (not
a terminal) it writes a line every :data:`LOG_EVERY_S` seconds. At its end: the tasks computed
and the time they took.
"""

from __future__ import annotations

import json
import sys
import threading
import time
from pathlib import Path
from typing import Any, TextIO

#: seconds between two progress lines in a log (not a terminal)
LOG_EVERY_S = 30.0
#: seconds between two reads of the progress file
POLL_S = 0.25
#: a campaign estimated to take longer than this says so before it starts, also on a terminal
ESTIMATE_FROM_S = 60.0


def duration(seconds: float) -> str:
    """``"42 s"``, ``"3.5 min"`` or ``"1.2 h"``."""
    if seconds < 90:
        return f"{seconds:.0f} s"
    if seconds < 5400:
        return f"{seconds / 60:.1f} min"
    return f"{seconds / 3600:.1f} h"


def start_line(name: str, e: dict[str, Any]) -> str:
    """What a campaign that computes says before it starts."""
    head = (
        f"[{name}] {e['desc']}: {e['total']} tasks, {e['cached']} in the cache, "
        f"{e['to_compute']} to compute on {e['workers']} worker{'s' * (e['workers'] > 1)}"
    )
    if e.get("estimate_s") is None:
        return f"{head}; no time measured on this machine yet (an ETA follows as tasks finish)"
    when = str(e.get("measured_when") or "")[:10]
    which = "" if e.get("same_model", True) else " on another model of this kind"
    return (
        f"{head}: about {duration(e['estimate_s'])} ({e['per_task_s']:.3g} s a task on one "
        f"worker, measured{which} on this machine{' on ' + when if when else ''})"
    )


def end_line(name: str, e: dict[str, Any]) -> str:
    """What a campaign that computed says at its end."""
    failed = f", {e['failed']} failed" if e.get("failed") else ""
    return (
        f"[{name}] {e['desc']}: {e['done'] - e.get('failed', 0)} computed{failed} in "
        f"{duration(e['elapsed_s'])} on {e['workers']} worker{'s' * (e['workers'] > 1)}, "
        f"{e['cached']} read from the cache"
    )


def tick_line(name: str, e: dict[str, Any]) -> str:
    """A log's progress line: done / to compute, seconds between two finished tasks (all
    workers together), ETA."""
    done, todo, elapsed = e["done"], e["to_compute"], e["elapsed_s"]
    rate = elapsed / done if done else float("nan")
    eta = f", ETA {duration(rate * (todo - done))}" if done else ""
    return (
        f"[{name}] {e['desc']}: {done}/{todo} computed ({e['cached']} cached) on "
        f"{e['workers']} workers, one every {rate:.3g} s{eta}"
    )


class ProgressView:
    """Follow a progress file in a thread and draw it on ``stream`` (see the module).

    Use as a context manager around the notebook's execution; the file is created empty.
    """

    def __init__(self, path: Path, name: str, stream: TextIO | None = None) -> None:
        self.path, self.name = Path(path), name
        self.stream = stream if stream is not None else sys.stderr
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._follow, daemon=True)
        self._bar = None
        self._last_log = 0.0
        self._offset = 0
        self.tasks = {"total": 0, "cached": 0}  # over the notebook's campaigns

    def __enter__(self) -> ProgressView:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.path.write_text("")
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join()
        self._read()  # what came after the last poll
        self._close_bar()

    def _follow(self) -> None:
        while not self._stop.wait(POLL_S):
            self._read()

    def _read(self) -> None:
        try:
            with open(self.path) as fh:
                fh.seek(self._offset)
                chunk = fh.read()
        except OSError:
            return
        complete = chunk[: chunk.rfind("\n") + 1]  # a line still being written waits
        self._offset += len(complete.encode())
        for line in complete.splitlines():
            try:
                self.show(json.loads(line))
            except (ValueError, KeyError, TypeError):
                continue  # not a progress event: ignored, never fatal

    def _print(self, text: str) -> None:
        print(text, file=self.stream, flush=True)

    def _close_bar(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None

    def show(self, e: dict[str, Any]) -> None:
        """Draw one event: a ``note``, or a ``start``, ``tick`` or ``end`` of a campaign that
        computes (every ``start`` is counted in :attr:`tasks`)."""
        if e["event"] == "start":
            self.tasks["total"] += int(e["total"])
            self.tasks["cached"] += int(e["cached"])
        if e["event"] == "note":
            if self._bar is not None:
                self._bar.write(f"[{self.name}] {e['desc']}: {e['text']}", file=self.stream)
            else:
                self._print(f"[{self.name}] {e['desc']}: {e['text']}")
            return
        if not e["to_compute"]:
            return
        if e["event"] == "start":
            self._close_bar()
            est = e.get("estimate_s")
            if est is None or est > ESTIMATE_FROM_S or not self.tty:
                self._print(start_line(self.name, e))
            if self.tty:
                from tqdm import tqdm

                self._bar = tqdm(
                    total=e["to_compute"],
                    desc=f"[{self.name}] {e['desc']}",
                    unit="task",
                    file=self.stream,
                    postfix=f"{e['cached']} cached, {e['workers']} workers",
                    leave=False,
                )
            self._last_log = time.monotonic()
        elif e["event"] == "tick":
            if self._bar is not None:
                self._bar.update(e["done"] - self._bar.n)
            elif time.monotonic() - self._last_log >= LOG_EVERY_S:
                self._last_log = time.monotonic()
                self._print(tick_line(self.name, e))
        elif e["event"] == "end":
            self._close_bar()
            self._print(end_line(self.name, e))
