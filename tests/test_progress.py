"""FE campaigns' progress: events to the build's channel, time estimates from the last
measurement on this machine, and the build's view of them (nothing drawn for a cached campaign)."""

from __future__ import annotations

import io
import json

import pytest

from mechlib import progress as pg
from mechlib.paths import PROGRESS_ENV
from mechlib.pipeline import progressview as pv


def _events(path):
    return [json.loads(x) for x in path.read_text().splitlines()]


def test_a_campaign_reports_start_ticks_end_and_remembers_its_time(tmp_path, monkeypatch) -> None:
    channel, cache = tmp_path / "p.jsonl", tmp_path / "cache"
    cache.mkdir()
    monkeypatch.setenv(PROGRESS_ENV, str(channel))
    meter = pg.Progress("runs", "nonlinear", "abcd1234", 10, 6, 2, cache)
    for _ in range(4):
        meter.update()
    meter.close()
    events = _events(channel)
    assert events[0]["event"] == "start" and events[0]["estimate_s"] is None  # nothing measured
    assert (events[0]["to_compute"], events[0]["cached"], events[0]["workers"]) == (4, 6, 2)
    assert events[-2]["event"] == "tick" and events[-2]["done"] == 4  # the last tick always
    assert events[-1]["event"] == "end" and events[-1]["per_task_s"] > 0
    measured = pg.measured_seconds(cache, "nonlinear", "abcd1234")
    assert measured["tasks"] == 4 and measured["workers"] == 2
    per = measured["per_task_s"]
    # the next estimate: 5 tasks on 2 workers take 3 rounds; another model of the kind falls back
    assert pg.estimate_s(cache, "nonlinear", 5, 2, "abcd1234") == pytest.approx(3 * per)
    assert pg.estimate_s(cache, "nonlinear", 5, 2, "other") == pytest.approx(3 * per)
    assert pg.estimate_s(cache, "linear", 5, 2) is None
    assert pg.estimate_s(cache, "nonlinear", 0, 2) == 0.0


def test_no_channel_no_file_and_a_corrupt_time_file_means_no_estimate(
    tmp_path, monkeypatch
) -> None:
    monkeypatch.delenv(PROGRESS_ENV, raising=False)
    meter = pg.Progress("runs", "linear", "x", 2, 2, 1, None)  # all cached, no cache folder
    meter.close()
    assert list(tmp_path.iterdir()) == []
    (tmp_path / pg.TIMES_FILE).write_text("{not json")
    assert pg.measured_seconds(tmp_path, "linear") is None


def test_the_view_draws_what_computes_and_stays_silent_for_the_cache(tmp_path) -> None:
    out = io.StringIO()  # not a terminal: lines, no bar
    view = pv.ProgressView(tmp_path / "p.jsonl", "nb", stream=out)
    base = {"desc": "non-linear FE runs", "total": 40, "cached": 30, "workers": 2, "done": 0}
    view.show({**base, "event": "start", "to_compute": 0, "cached": 40})  # all cached
    assert out.getvalue() == ""
    view.show({**base, "event": "start", "to_compute": 10, "estimate_s": 125.0,
               "per_task_s": 25.0, "measured_when": "2026-11-27T10:00:00+00:00"})  # fmt: skip
    view.show({**base, "event": "note", "text": "FE model 2: misfit 0.1"} | {"desc": "identify"})
    view.show({**base, "event": "end", "to_compute": 10, "done": 10, "elapsed_s": 130.0})
    lines = out.getvalue().splitlines()
    assert lines[0] == (
        "[nb] non-linear FE runs: 40 tasks, 30 in the cache, 10 to compute on 2 workers: about "
        "2.1 min (25 s a task on one worker, measured on this machine on 2026-11-27)"
    )
    assert lines[1] == "[nb] identify: FE model 2: misfit 0.1"
    assert (
        lines[2]
        == "[nb] non-linear FE runs: 10 computed in 2.2 min on 2 workers, 30 read from the cache"
    )


def test_the_view_follows_the_file_a_kernel_writes(tmp_path, monkeypatch) -> None:
    channel = tmp_path / "p.jsonl"
    out = io.StringIO()
    with pv.ProgressView(channel, "nb", stream=out):
        monkeypatch.setenv(PROGRESS_ENV, str(channel))
        meter = pg.Progress("linear FE runs", "linear", "x", 3, 1, 1, None)
        meter.update()
        meter.update()
        meter.close()
        with open(channel, "a") as fh:
            fh.write('not json\n{"half": ')  # ignored; a half-written line waits
    text = out.getvalue()
    assert "2 to compute on 1 worker; no time measured on this machine yet" in text
    assert "2 computed in" in text and "1 read from the cache" in text


def test_a_log_line_says_the_pace_of_all_workers_and_the_eta() -> None:
    e = {"desc": "runs", "done": 4, "to_compute": 10, "cached": 2, "workers": 2, "elapsed_s": 20.0}
    assert pv.tick_line("nb", e) == (
        "[nb] runs: 4/10 computed (2 cached) on 2 workers, one every 5 s, ETA 30 s"
    )
    assert pv.duration(4000) == "66.7 min" and pv.duration(7200) == "2.0 h"
