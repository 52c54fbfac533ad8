"""The determinism check: every notebook executed again, cold, and its record compared byte for
byte with the first run's (``make rerun``, then the last step of ``make test``).
"""

from __future__ import annotations

import concurrent.futures as cf
import json
import os
import shutil
import subprocess
import sys
import tempfile
import threading
from pathlib import Path

from mechlib.params import check_int
from mechlib.paths import FE_CACHE_ENV, FE_LOG_ENV, RECORDS_ENV, RECORDS_STRICT_ENV
from mechlib.pipeline.chapters import in_order, upstream
from mechlib.pipeline.execute import (
    KERNEL_START_ATTEMPTS,
    chapter_inputs,
    input_arguments,
    kernel_died_at_start,
    papermill_command,
)
from mechlib.pipeline.references import compare
from mechlib.reporting.records import load

#: file of the re-run's folder that logs its FE cache hits (``$MECHLIB_FE_LOG``)
HIT_LOG = "fe-cache-hits.jsonl"
#: the re-run's copy of the first run's FE cache, in its output folder
FE_CACHE_COPY = "fe-cache"


#: notebooks the re-run executes at a time (each after the chapters it reads): two, like
#: ``make -j2 notebooks``, so that both cores work while one chapter waits on its kernel
JOBS = 2


def rerun(
    notebooks: Path,
    out: Path,
    python: str = sys.executable,
    fe_cache_from: Path | None = None,
    jobs: int = JOBS,
    first_run: Path | None = None,
) -> None:
    """Execute every notebook again into ``out`` (emptied first).

    The executed notebooks go to ``out/<name>.ipynb``, their records to ``out/records``
    (``$MECHLIB_RECORDS``), and their FE results to a cache of their own, ``out/fe-cache``
    (``$MECHLIB_FE_CACHE``). That cache starts empty — the re-run computes everything again and
    shares nothing with a first run, so the two can run at the same time — or, with
    ``fe_cache_from``, as a copy of the first run's FE cache: then every FE task it finds there
    is read, not solved, and logged to ``out/fe-cache-hits.jsonl`` (``$MECHLIB_FE_LOG``), so that
    a sample of them can be recomputed cold
    (:func:`mechlib.campaign.cachecheck.check_sample`;
    ``make test`` does both, and saves the second run's FE solves). Notebooks
    run ``jobs`` at a time in chapter order (:data:`~mechlib.pipeline.chapters.CHAPTERS`), each
    after the chapters whose records give it inputs, read strictly from the re-run's own records
    (``$MECHLIB_RECORDS_STRICT``).

    With ``first_run`` (the first run's build folder, holding ``records/`` and ``executed/``), a
    chapter's inputs are read strictly from the first run's records instead, so no chapter waits
    for another: the comparison that follows requires those records identical to the re-run's
    own, so every chapter is still checked on the inputs the re-run computed. The chapters then
    start longest first, by the time papermill recorded for each in the first run's executed
    notebooks (:func:`longest_first`), which keeps both cores busy to the end.

    Raises
    ------
    RuntimeError
        If a notebook fails, naming it and its executed copy (which holds the traceback), with
        the end of papermill's error output.
    """
    jobs = check_int("jobs", jobs, low=1, high=16)
    out = Path(out).resolve()  # absolute: the kernels run in the notebooks' folder
    pending = in_order(Path(notebooks).glob("*.ipynb"))
    inputs = out / "records"
    if first_run is not None:  # checked before anything is removed or started
        inputs = Path(first_run).resolve() / "records"
        if not inputs.is_dir():
            raise RuntimeError(f"first_run must hold the first run's records/, got {first_run}")
        for nb in pending:  # every chapter's inputs there, before the longest ones start
            try:
                chapter_inputs(nb.stem, inputs, strict=True)
            except (OSError, KeyError) as err:
                raise RuntimeError(
                    f"the first run's records lack an input of {nb.stem}: {err}"
                ) from err
        pending = longest_first(pending, Path(first_run) / "executed")
    shutil.rmtree(out, ignore_errors=True)
    (out / "records").mkdir(parents=True)
    variables = {
        RECORDS_ENV: str(out / "records"),
        FE_CACHE_ENV: str(out / FE_CACHE_COPY),
        RECORDS_STRICT_ENV: "1",
    }
    if fe_cache_from is not None:
        if not Path(fe_cache_from).is_dir():
            raise RuntimeError(f"fe_cache_from must be an FE cache folder, got {fe_cache_from}")
        shutil.copytree(fe_cache_from, out / FE_CACHE_COPY)
        variables[FE_LOG_ENV] = str(out / HIT_LOG)
    env = dict(os.environ, **variables)
    # an input chapter not in the folder is not waited for, nor any when the inputs are given
    here = {nb.stem for nb in pending} if first_run is None else set()
    done: set[str] = set()
    procs: dict[str, subprocess.Popen] = {}  # the chapters executing, to stop on a failure
    stop = threading.Event()  # set on a failure: a chapter not yet started does not start
    with cf.ThreadPoolExecutor(max_workers=jobs) as pool:
        running: dict[cf.Future, Path] = {}
        while pending or running:
            for nb in [n for n in pending if set(upstream(n.stem)) & here <= done]:
                if len(running) >= jobs:
                    break
                pending.remove(nb)
                running[pool.submit(_execute, nb, out, inputs, env, python, procs, stop)] = nb
            finished, _ = cf.wait(running, return_when=cf.FIRST_COMPLETED)
            for fut in finished:
                nb = running.pop(fut)
                if fut.exception() is not None:  # a failed notebook stops the re-run at once:
                    with _STARTING:
                        stop.set()
                        for proc in list(procs.values()):  # its sibling: stopped, not awaited
                            proc.kill()
                    fut.result()  # RuntimeError, naming the chapter
                done.add(nb.stem)


def longest_first(notebooks: list[Path], executed: Path) -> list[Path]:
    """``notebooks`` ordered by the seconds papermill recorded for each in the executed copies
    of folder ``executed``, longest first (one without a recorded time first of all, in the
    given order: its length is unknown)."""

    def seconds(nb: Path) -> float:
        try:
            meta = json.loads((Path(executed) / nb.name).read_text())["metadata"]["papermill"]
            return float(meta["duration"])
        except (OSError, ValueError, KeyError, TypeError):
            return float("inf")

    return sorted(notebooks, key=seconds, reverse=True)


def _execute(
    nb: Path,
    out: Path,
    inputs_from: Path,
    env: dict[str, str],
    python: str,
    procs: dict[str, subprocess.Popen],
    stop: threading.Event,
) -> None:
    inputs = input_arguments(nb.stem, inputs_from, strict=True)
    cmd = papermill_command(nb, out / nb.name, inputs, python=python)
    for _attempt in range(KERNEL_START_ATTEMPTS):
        with _STARTING:  # a failure seen meanwhile stops this chapter before its process starts
            if stop.is_set():
                return
            print(f"re-run: executing {nb.name}", flush=True)
            proc = subprocess.Popen(
                cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
            )
            procs[nb.stem] = proc
        _, stderr = proc.communicate()
        del procs[nb.stem]
        done = subprocess.CompletedProcess(cmd, proc.returncode, "", stderr)
        if done.returncode == 0 or stop.is_set() or not kernel_died_at_start(stderr):
            break
        print(f"re-run: the kernel of {nb.name} died before it started; starting it again")
    if done.returncode != 0:
        tail = "\n".join(done.stderr.splitlines()[-20:])
        raise RuntimeError(
            f"the re-run of {nb.name} failed (exit {done.returncode}; traceback in "
            f"{out / nb.name}):\n{tail}"
        )


#: held while a chapter's process starts or while a failure stops the others
_STARTING = threading.Lock()


def _untimed(path: Path) -> bytes:
    """A record's bytes, or, when it holds ``timings``, its canonical text without them."""
    raw = path.read_bytes()
    data = json.loads(raw)
    if "timings" not in data:
        return raw
    del data["timings"]
    return (json.dumps(data, indent=1, sort_keys=True) + "\n").encode()


def rerun_differences(records: Path, rerun_records: Path, notebooks: Path) -> list[str]:
    """Each notebook whose re-run record is not byte-identical to its first one, with the
    values that differ (empty: the two runs agree)."""
    problems = []
    for nb in sorted(Path(notebooks).glob("*.ipynb")):
        first, second = Path(records) / f"{nb.stem}.json", Path(rerun_records) / f"{nb.stem}.json"
        missing = [
            f"{which} record at {path}"
            for which, path in (("first-run", first), ("re-run", second))
            if not path.exists()
        ]
        if missing:
            problems.append(f"{nb.stem}: no " + " and no ".join(missing))
        elif _untimed(second) != _untimed(first):  # timings differ run to run, by nature
            diffs = compare(load(second), load(first))
            problems.append(f"{nb.stem}: second run differs: {diffs or 'formatting only'}")
    return problems


def rerun_identical(records: Path, notebooks: Path, python: str = sys.executable) -> list[str]:
    """Execute every notebook again (:func:`rerun`, in a temporary folder) and check its record
    is byte-identical to the one in ``records`` (:func:`rerun_differences`).

    The second run starts from an empty FE cache (``$MECHLIB_FE_CACHE`` in a temporary folder),
    so it checks that two cold computations agree, not merely that cached results are returned.
    """
    with tempfile.TemporaryDirectory() as tmp:
        rerun(notebooks, Path(tmp), python=python)
        return rerun_differences(records, Path(tmp) / "records", notebooks)
