"""The build wing's one command line: ``python -m mechlib.pipeline <command> …`` (the Makefile's).

=============  ================================================================================
execute        one notebook of a build, its chapter inputs filled from the build's records
run            ``make run``: one notebook with new parameters into ``build/runs/`` (names checked)
rerun          ``make rerun``: every notebook again, cold, into a folder of its own
determinism    the re-run's records byte-identical to the first run's (or re-run now and compare)
update         ``make references``: a build's records to ``tests/references``, saying what changed
book           the book's generated pages from the executed notebooks and their records
check-browser  every built page in headless Chromium, network off
store          the FE results store (``store/``): seed a build's cache, pack a build, check cold
test           ``make test``: lint, notebooks, records, determinism, book, checks, unit tests, store
=============  ================================================================================
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path

from mechlib.paths import REPO_ROOT
from mechlib.pipeline import bookbuild, runs, storecmd, testgraph
from mechlib.pipeline.book import browser
from mechlib.pipeline.coldsample import COLD_SAMPLE, cold_sample
from mechlib.pipeline.execute import execute
from mechlib.pipeline.references import update_references
from mechlib.pipeline.rerun import HIT_LOG, rerun, rerun_differences, rerun_identical

NOTEBOOKS = REPO_ROOT / "notebooks"


def _execute(args: argparse.Namespace) -> int:
    return execute(args.notebook, args.out, args.records, [a for a in args.papermill if a != "--"])


def _update(args: argparse.Namespace) -> int:
    import numpy  # noqa: F401  (loads both OpenBLAS builds, as kernels.main does)
    import scipy.linalg  # noqa: F401

    from mechlib.blasinfo import openblas_kernel
    from mechlib.pipeline.kernels import check_own_kernel

    foreign = check_own_kernel(args.records, openblas_kernel())
    if foreign:  # e.g. make test's runs, with another kernel: then nothing would be cross-checked
        print("references come from this machine's own BLAS kernel; remove build/executed and "
              "run make references again:\n" + "\n".join(foreign))  # fmt: skip
        return 2
    for line in update_references(args.records, args.references):
        print(line)
    return 0


def _rerun(args: argparse.Namespace) -> int:
    try:
        rerun(args.notebooks, args.out, fe_cache_from=args.fe_cache_from, first_run=args.first_run)
    except RuntimeError as err:
        print(err, file=sys.stderr)
        return 1
    print(f"re-run: every notebook executed again into {args.out}")
    return 0


def _determinism(args: argparse.Namespace) -> int:
    if args.rerun is None:
        problems = rerun_identical(args.records, args.notebooks)
    else:
        problems = rerun_differences(args.records, args.rerun, args.notebooks)
    for p in problems:
        print("NOT DETERMINISTIC:", p)
    print("determinism: " + ("FAILED" if problems else "records identical on a second run"))
    cold_failed = False
    if args.rerun is not None and (args.rerun.parent / HIT_LOG).exists():
        cold_failed = cold_sample(args.rerun.parent, args.cold, args.store_checked)
    return 1 if problems or cold_failed else 0


#: commands whose own modules parse their arguments
DELEGATED: dict[str, tuple[Callable[[list[str]], int], str]] = {
    "run": (runs.main, "one notebook with new parameters into build/runs (make run)"),
    "book": (bookbuild.main, "the book's generated pages from executed notebooks and records"),
    "check-browser": (browser.main, "every built page in headless Chromium, network off"),
    "store": (storecmd.main, "the FE results store: seed a cache, pack a build, check cold"),
    "test": (testgraph.main, "make test: its steps as a graph (docs/testing.md)"),
}


def parser() -> argparse.ArgumentParser:
    """The argument parser of every command that is parsed here."""
    top = argparse.ArgumentParser(prog="python -m mechlib.pipeline")
    sub = top.add_subparsers(dest="cmd", required=True)
    ex = sub.add_parser("execute", help="one notebook of a build, its chapter inputs filled")
    ex.add_argument("--notebook", type=Path, required=True)
    ex.add_argument("--out", type=Path, required=True)
    ex.add_argument("--records", type=Path, required=True, help="the build's records folder")
    ex.add_argument("papermill", nargs=argparse.REMAINDER, help="-- and papermill arguments")
    ex.set_defaults(func=_execute)
    up = sub.add_parser("update", help="re-record references from a build's records")
    up.add_argument("--records", type=Path, required=True)
    up.add_argument("--references", type=Path, required=True)
    up.set_defaults(func=_update)
    det = sub.add_parser("determinism", help="re-run notebooks and require identical records")
    det.add_argument("--records", type=Path, required=True)
    det.add_argument("--notebooks", type=Path, default=NOTEBOOKS)
    det.add_argument(
        "--rerun", type=Path, help="records of a re-run already made (`rerun`): compare only"
    )
    det.add_argument(
        "--cold",
        type=int,
        default=COLD_SAMPLE,
        help="non-linear FE tasks of a re-run from a copied cache recomputed cold (seeded sample)",
    )
    det.add_argument(
        "--store-checked",
        type=Path,
        help="results store whose entries a store check recomputes: left out of the cold sample",
    )
    det.set_defaults(func=_determinism)
    again = sub.add_parser("rerun", help="execute every notebook again, cold, into a folder")
    again.add_argument("--out", type=Path, required=True)
    again.add_argument("--notebooks", type=Path, default=NOTEBOOKS)
    again.add_argument(
        "--fe-cache-from",
        type=Path,
        help="start from a copy of this FE cache (FE tasks read, logged, not solved)",
    )
    again.add_argument(
        "--first-run",
        type=Path,
        help="the first run's build folder: chapters' inputs from its records/ (none waits for "
        "another), longest first by its executed/ notebooks' times",
    )
    again.set_defaults(func=_rerun)
    for name, (_, what) in DELEGATED.items():
        sub.add_parser(name, help=what, add_help=False)
    return top


def main(argv: list[str] | None = None) -> int:
    """Run one command; its exit code."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] in DELEGATED:
        return DELEGATED[argv[0]][0](argv[1:])
    args = parser().parse_args(argv)
    return args.func(args)
