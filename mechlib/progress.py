"""Progress and time of an FE campaign, reported where the person who started it can see them
(and one-line notes of iterative steps such as an identification).

A campaign (:func:`~mechlib.campaign.experiments.run_experiments`) opens a
:class:`Progress` once it knows how many of its tasks are cached and how many must be computed.
It reports, as JSON lines to the file ``$MECHLIB_PROGRESS`` names (the build sets it for each
notebook it executes and draws one updating line on its own terminal, so nothing lands in the
page): a ``start`` event with the counts, the workers and an estimate of the time (tasks to
compute × the seconds a task took on this machine last time ÷ workers), ``tick`` events as
tasks finish (at most a few a second), and an ``end`` event; :func:`note` reports one line
of an iterative step (an identification's misfit after each FE model). Optionally
(``bar=True``) it also draws a tqdm bar on the caller's standard error.

The seconds a task takes are measured by each campaign that computes something (its wall time
× workers ÷ tasks computed) and kept per kind of analysis in the FE cache folder
(:data:`TIMES_FILE`), for the next campaign's estimate.
"""

from __future__ import annotations

import json
import math
import os
import threading
import time
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from mechlib.paths import progress_path

#: the measured seconds a task takes, per kind of analysis, kept in the FE cache folder
TIMES_FILE = ".task-seconds.json"
#: fewest seconds between two ``tick`` events
TICK_S = 0.5


def measured_seconds(cache_dir: Path | None, kind: str, model: str = "") -> dict[str, Any] | None:
    """The last measurement of a task's seconds on this machine (``per_task_s``, ``workers``,
    ``tasks``, ``when``, and ``same_model``: whether it is this model's): of this ``model`` (a
    short name of its specification) if there is one, else of the last model of this ``kind``;
    ``None`` when there is none (or it is unreadable)."""
    if cache_dir is None:
        return None
    try:
        times = json.loads((Path(cache_dir) / TIMES_FILE).read_text())
        own = times.get(f"{kind}:{model}")
        entry = own or times.get(kind)
    except (OSError, ValueError, AttributeError):
        return None
    if not isinstance(entry, dict) or not isinstance(entry.get("per_task_s"), int | float):
        return None
    return {**entry, "same_model": bool(own)}


def estimate_s(
    cache_dir: Path | None, kind: str, tasks: int, workers: int, model: str = ""
) -> float | None:
    """Seconds that ``tasks`` tasks should take on ``workers`` workers, from the last
    measurement on this machine (:func:`measured_seconds`); ``None`` without one."""
    entry = measured_seconds(cache_dir, kind, model)
    if entry is None:
        return None
    if tasks == 0:
        return 0.0
    return float(entry["per_task_s"]) * math.ceil(tasks / max(1, min(workers, tasks)))


def note(desc: str, text: str) -> None:
    """Report one line of an iterative step (an identification's FE model count and misfit) to
    ``$MECHLIB_PROGRESS`` when it is set; nothing otherwise."""
    channel = progress_path()
    if channel is not None:
        with open(channel, "a") as fh:
            fh.write(json.dumps({"event": "note", "desc": desc, "text": text}) + "\n")


class Progress:
    """One campaign's progress (see the module's docstring); thread-safe.

    Parameters
    ----------
    desc : str
        What the campaign is ("non-linear FE runs").
    kind : str
        Kind of analysis (the key of the time measurements).
    model : str
        A short name of the model's specification (a key of the time measurements too).
    total, cached : int
        Tasks in all, and those read from the cache.
    workers : int
        Workers the tasks to compute run on.
    cache_dir : Path or None
        The FE cache folder (where the time measurements are kept), ``None``: none kept.
    bar : bool
        Also draw a tqdm bar on standard error.
    """

    def __init__(
        self,
        desc: str,
        kind: str,
        model: str,
        total: int,
        cached: int,
        workers: int,
        cache_dir: Path | None,
        bar: bool = False,
    ) -> None:
        self.desc, self.kind, self.model = desc, kind, model
        self.total, self.cached = total, cached
        self.workers, self.cache_dir = max(1, workers), cache_dir
        self.to_compute = total - cached
        self.done = 0
        self._closed = False
        self._lock = threading.Lock()
        self._start = time.perf_counter()
        self._last_tick = 0.0
        self._channel = progress_path()
        self._bar = None
        if bar and self.to_compute:
            from tqdm.auto import tqdm

            self._bar = tqdm(total=self.to_compute, desc=desc, unit="task")
        measured = measured_seconds(cache_dir, kind, model)
        self._emit(
            {
                "event": "start",
                "estimate_s": estimate_s(cache_dir, kind, self.to_compute, self.workers, model),
                "per_task_s": measured["per_task_s"] if measured else None,
                "measured_when": measured["when"] if measured else None,
                "same_model": measured["same_model"] if measured else None,
            }
        )

    def _emit(self, event: dict[str, Any]) -> None:
        if self._channel is None:
            return
        line = {
            "desc": self.desc,
            "kind": self.kind,
            "total": self.total,
            "cached": self.cached,
            "to_compute": self.to_compute,
            "workers": self.workers,
            "done": self.done,
            "elapsed_s": round(time.perf_counter() - self._start, 3),
            **event,
        }
        with open(self._channel, "a") as fh:
            fh.write(json.dumps(line) + "\n")

    def update(self, n: int = 1) -> None:
        """Count ``n`` more tasks done (computed or failed); nothing once closed."""
        with self._lock:
            if self._closed:
                return
            self.done += n
            if self._bar is not None:
                self._bar.update(n)
            now = time.perf_counter()
            if now - self._last_tick >= TICK_S or self.done == self.to_compute:
                self._last_tick = now
                self._emit({"event": "tick"})

    def close(self, done: int | None = None, failed: int = 0) -> None:
        """End the campaign (``done`` tasks finished, as the caller counted them: a future's
        callback may still be on its way): report it, and keep the seconds a task took (when
        any was computed) for the next estimate."""
        with self._lock:
            self._closed = True
            if done is not None:
                self.done = done
            elapsed = time.perf_counter() - self._start
            if self._bar is not None:
                self._bar.close()
            per_task = None
            computed = self.done - failed
            if computed > 0 and elapsed > 0:
                per_task = elapsed * min(self.workers, self.done) / self.done
                self._remember(per_task)
            self._emit({"event": "end", "failed": failed, "per_task_s": per_task})

    def _remember(self, per_task: float) -> None:
        if self.cache_dir is None:
            return
        path = Path(self.cache_dir) / TIMES_FILE
        try:
            times = json.loads(path.read_text())
        except (OSError, ValueError):
            times = {}
        if not isinstance(times, dict):
            times = {}
        when = datetime.now(UTC).isoformat(timespec="seconds")
        entry = {"per_task_s": per_task, "workers": self.workers, "tasks": self.done, "when": when}
        times[self.kind] = times[f"{self.kind}:{self.model}"] = entry
        tmp = path.with_suffix(f".{os.getpid()}.{threading.get_ident()}.tmp")
        try:  # a measurement that cannot be kept costs the next estimate, never the campaign
            tmp.write_text(json.dumps(times, indent=1, sort_keys=True))
            tmp.replace(path)
        except OSError:
            tmp.unlink(missing_ok=True)
