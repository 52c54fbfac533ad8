"""``make test`` as a graph of steps: ``python -m mechlib.pipeline test``.

The steps (docs/testing.md), each after those in its ``after`` column, run by
:func:`mechlib.pipeline.dag.run_graph`::

    lint ─ store-seed ┬ notebooks ─ check-records ┬ rerun ─ determinism
                      │                           └ book ─ check-book ─ check-browser ─ pdf
                      │                                                           ─ check-pdf
                      └ unit-a, unit-b, store-check   (low priority)

The chapters' chain (notebooks, their records against the references, the determinism re-run,
the records compared) is the longest path; the book and its checks start once the first run's
records are checked; the work nothing waits on — the unit tests in two processes and the store's
cold sample — runs beside them at a low priority and fills the cores the chain leaves idle. The
notebooks run with a BLAS kernel other than this machine's own and the references'
(:mod:`mechlib.pipeline.kernels`), both times. Steps that are one make target run it (``make
notebooks`` executes only what changed, in the order of the chapters' inputs), so each can also
be run alone; the first failing step stops the graph, and a summary names it.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
import time
from dataclasses import replace
from pathlib import Path

from mechlib.paths import REPO_ROOT
from mechlib.pipeline.dag import Step, run_graph, summary

BUILD = Path("build")
STORE = Path("store")
REFERENCES = Path("tests/references")
#: the notebooks' FE cache, seeded from the store (mechlib.paths.fe_cache_dir)
FE_CACHE = BUILD / "cache" / "experiments"
#: the test files of other steps than the unit tests (records, the built HTML)
NOT_UNIT = ("test_records.py", "test_book_html.py", "test_explorer_browser.py")
#: glibc keeps freed memory for reuse in the store's cold sample: its model builds otherwise
#: spend a third of their time in the kernel mapping and unmapping large arrays (measured 82 s
#: of system time against 49 s)
MALLOC_REUSE = {"MALLOC_MMAP_MAX_": "0", "MALLOC_TRIM_THRESHOLD_": "17179869184"}
#: the notebooks of make test run two at a time (one per core of the machines we measure on)
NOTEBOOK_JOBS = 2


def unit_halves(tests: Path = REPO_ROOT / "tests") -> tuple[list[str], list[str]]:
    """The unit test files, every other one each (by name), for two pytest processes."""
    files = sorted(p.name for p in tests.glob("test_*.py") if p.name not in NOT_UNIT)
    paths = [f"tests/{f}" for f in files]
    return paths[0::2], paths[1::2]


def _browser_missing() -> str | None:
    from mechlib.pipeline.book.browser import find_browser

    return None if find_browser() else "no Chromium on this machine (apt-get install chromium)"


def _pdf_tools_missing() -> str | None:
    from mechlib.pipeline.pdf import missing_tools

    missing = missing_tools()
    hint = "(apt-get install chromium poppler-utils)"
    return f"missing {', '.join(missing)} {hint}" if missing else None


def steps(kernel: str, python: str = sys.executable) -> list[Step]:
    """The steps of ``make test``, the notebooks run with the OpenBLAS ``kernel``."""
    bindir = Path(python).parent
    pipeline = (python, "-m", "mechlib.pipeline")
    pytest = (str(bindir / "pytest"), "-q", "-p", "no:cacheprovider")
    make = ("make", "--no-print-directory")
    forget = (python, "-m", "mechlib.pipeline.kernels", "forget")
    rerun = [*pipeline, "rerun", "--out", str((BUILD / "rerun").absolute())]
    rerun += ["--fe-cache-from", str(FE_CACHE), "--first-run", str(BUILD)]
    blas = {"OPENBLAS_CORETYPE": kernel}
    determinism = [*pipeline, "determinism", "--records", str(BUILD / "records")]
    determinism += ["--rerun", str(BUILD / "rerun" / "records")]
    if (STORE / "manifest.json").exists():  # its entries: left to the store's own cold sample
        determinism += ["--store-checked", str(STORE)]
    half_a, half_b = unit_halves()
    seeded = str(FE_CACHE / ".store-seeded")
    return [
        Step("lint", [(*make, "lint")]),
        Step("store-seed", [(*make, seeded)], after=("lint",)),
        Step(
            "notebooks",
            [
                # notebooks executed with another kernel (a make book) are executed again
                (*forget, str(BUILD / "records"), str(BUILD / "executed"), kernel),
                (*make, f"-j{NOTEBOOK_JOBS}", "notebooks"),
            ],
            after=("store-seed",),
            env=blas,
        ),
        Step(
            "check-records",
            [(*pytest, "tests/test_records.py")],
            after=("notebooks",),
            env={"MECHLIB_TEST_KERNEL": kernel},
        ),
        Step(
            "rerun",
            [rerun],
            after=("check-records",),
            env=blas,
        ),
        Step("determinism", [determinism], after=("rerun",)),
        Step("book", [(*make, "book")], after=("check-records",)),
        Step("check-book", [(*make, "check-book")], after=("book",)),
        Step(
            "check-browser",
            [(*make, "check-browser")],
            after=("check-book",),
            skip=_browser_missing,
        ),
        Step("pdf", [(*make, "pdf")], after=("check-browser",), skip=_pdf_tools_missing),
        Step("check-pdf", [(*make, "check-pdf")], after=("pdf",), skip=_pdf_tools_missing),
        Step("unit-a", [(*pytest, f"--basetemp={BUILD}/pytest-a", *half_a)], ("store-seed",), True),
        Step("unit-b", [(*pytest, f"--basetemp={BUILD}/pytest-b", *half_b)], ("store-seed",), True),
        Step("store-check", [(*make, "store-check")], ("store-seed",), True, MALLOC_REUSE),
    ]


def make_environment(environ: dict[str, str]) -> dict[str, str]:
    """``environ`` for the steps' make commands: the job-server options of a calling make left
    out of ``MAKEFLAGS`` (its descriptors are not passed on; each step sets its own ``-j``),
    its variables (``make test BOOK_JOBS=1``) kept."""
    env = dict(environ)
    flags = env.get("MAKEFLAGS", "").split()
    kept = [f for f in flags if not f.startswith(("--jobserver", "-j"))]
    if kept and not kept[0].startswith("-") and "j" in kept[0] and "=" not in kept[0]:
        kept[0] = kept[0].replace("j", "")  # "ij" style single-letter flags
    env["MAKEFLAGS"] = " ".join(f for f in kept if f)
    env.pop("MFLAGS", None)
    return env


def main(argv: list[str] | None = None) -> int:
    """Run the graph (or ``--only`` some of its steps, without their dependencies); exit 0 when
    every step passed, 1 otherwise; ``--list`` prints the steps and what each waits for."""
    top = argparse.ArgumentParser(prog="python -m mechlib.pipeline test", description=__doc__)
    top.add_argument("--only", help="comma-separated steps, run without their dependencies")
    top.add_argument("--list", action="store_true", help="print the steps and their order")
    top.add_argument("--jobs", type=int, help="at most this many steps at once (default: all)")
    top.add_argument("--kernel", help="OpenBLAS kernel of the notebooks (default: kernels other)")
    args = top.parse_args(argv)
    os.chdir(REPO_ROOT)
    if args.kernel:
        kernel = args.kernel
    elif args.list or args.only:
        kernel = "(other)"
    else:
        kernel = _other_kernel()
    graph = steps(kernel)
    if args.list:
        for s in graph:
            print(f"{s.name:<14} after {', '.join(s.after) or '(start)'}{' [low]' * s.low}")
        return 0
    if args.only:
        wanted = args.only.split(",")
        unknown = sorted(set(wanted) - {s.name for s in graph})
        if unknown:
            top.error(f"unknown steps {unknown}; have {[s.name for s in graph]}")
        graph = [replace(s, after=()) for s in graph if s.name in wanted]
    start = time.monotonic()
    signal.signal(signal.SIGTERM, _terminated)  # a CI time-out: stop the steps' process groups
    try:
        outcomes = run_graph(graph, jobs=args.jobs, env=make_environment(dict(os.environ)))
    except KeyboardInterrupt:
        print(f"make test: interrupted after {time.monotonic() - start:.0f} s", flush=True)
        return 130
    ok, lines = summary(outcomes, time.monotonic() - start)
    print("\n".join(["", "make test:", *lines]), flush=True)
    return 0 if ok else 1


def _terminated(signum: int, frame: object) -> None:
    """SIGTERM as Ctrl-C: :func:`~mechlib.pipeline.dag.run_graph` then stops every step."""
    raise KeyboardInterrupt


def _other_kernel() -> str:
    """The kernel of :func:`mechlib.pipeline.kernels.other_kernel`, announced."""
    import numpy  # noqa: F401  (loads OpenBLAS, so threadpoolctl finds it)
    import scipy.linalg  # noqa: F401

    from mechlib.blasinfo import openblas_kernel
    from mechlib.pipeline.kernels import other_kernel, reference_kernels

    own = openblas_kernel()
    kernel = other_kernel(own, reference_kernels(REFERENCES))
    print(f"make test: the notebooks run with OpenBLAS's {kernel} kernel (this machine's: {own})")
    return kernel
