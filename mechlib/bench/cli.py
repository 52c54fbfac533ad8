"""``python -m mechlib.bench`` (``make bench``): run the benchmarks, all or ``--only`` some
sections, and print their ratios (measured in one run, never asserted in tests).
"""

from __future__ import annotations

from collections.abc import Callable

import mechlib.bench
from mechlib.bench import basics


def _nonlinear() -> None:
    from mechlib.bench import nonlinear as nlb
    from mechlib.fe.nonlinear import NEWTON_TOL

    nlb.print_nonlinear(NEWTON_TOL)


def _chapter() -> None:
    from mechlib.bench import nonlinear as nlb

    nlb.print_chapter()


def _reuse() -> None:
    from mechlib.bench.reuse import print_reuse

    print_reuse()


def _rom() -> None:
    from mechlib.bench import rom

    rom.print_rom()


def _lean() -> None:
    from mechlib.bench.lean import print_lean

    print_lean()


def _dask() -> None:
    from mechlib.bench import dask

    print("\n".join(dask.report(dask.dask_vs_local())))


def _book() -> None:
    from mechlib.bench.book import print_book

    print_book()


#: every section by name, in the order they run: what it prints (imported only when it runs)
RUNS: dict[str, Callable[[], None]] = {
    "postures": basics.print_postures,
    "load-cases": basics.print_load_cases,
    "orderings": basics.print_orderings,
    "nonlinear": _nonlinear,
    "chapter": _chapter,
    "reuse": _reuse,
    "calibration": basics.print_calibration,
    "rom": _rom,
    "lean": _lean,
    "dask": _dask,
    "book": _book,
}
#: Sections run only when named (``--only``): the book section clones and builds the book.
ON_REQUEST: tuple[str, ...] = ("book",)
#: the sections a plain ``make bench`` runs
SECTIONS: tuple[str, ...] = tuple(name for name in RUNS if name not in ON_REQUEST)


def main(argv: list[str] | None = None) -> int:
    """Run the benchmarks (all, or ``--only`` some sections) and print their ratios.

    Parameters
    ----------
    argv : list of str, optional
        The command line after ``python -m mechlib.bench`` (default: ``sys.argv``).

    Returns
    -------
    int
        0 (an unknown section exits with argparse's error, status 2).
    """
    import argparse

    parser = argparse.ArgumentParser(
        prog="python -m mechlib.bench", description=mechlib.bench.__doc__
    )
    parser.add_argument(
        "--only",
        default=",".join(SECTIONS),
        help=f"comma-separated sections of {tuple(RUNS)} (default all but {ON_REQUEST})",
    )
    only = [x for x in parser.parse_args(argv).only.split(",") if x]
    unknown = sorted(set(only) - set(RUNS))
    if unknown:
        parser.error(f"--only: unknown sections {unknown}; allowed: {', '.join(RUNS)}")
    for name, run in RUNS.items():
        if name in only:
            run()
    return 0
