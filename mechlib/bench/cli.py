"""``python -m mechlib.bench`` (``make bench``): run the benchmarks, all or ``--only`` some
sections, and print their ratios (measured in one run, never asserted in tests).
"""

from __future__ import annotations

import mechlib.bench
from mechlib.bench import basics

SECTIONS: tuple[str, ...] = (
    "postures",
    "load-cases",
    "orderings",
    "nonlinear",
    "chapter",
    "reuse",
    "calibration",
    "rom",
    "lean",
    "dask",
)
#: Sections run only when named (``--only``): the book section clones and builds the book.
ON_REQUEST: tuple[str, ...] = ("book",)


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

    from mechlib.bench import nonlinear as nlb
    from mechlib.fe.nonlinear import NEWTON_TOL

    parser = argparse.ArgumentParser(
        prog="python -m mechlib.bench", description=mechlib.bench.__doc__
    )
    parser.add_argument(
        "--only",
        default=",".join(SECTIONS),
        help=f"comma-separated sections of {SECTIONS + ON_REQUEST} (default all but {ON_REQUEST})",
    )
    only = [x for x in parser.parse_args(argv).only.split(",") if x]
    unknown = sorted(set(only) - set(SECTIONS + ON_REQUEST))
    if unknown:
        allowed = ", ".join(SECTIONS + ON_REQUEST)
        parser.error(f"--only: unknown sections {unknown}; allowed: {allowed}")
    if "postures" in only:
        basics.print_postures()
    if "load-cases" in only:
        basics.print_load_cases()
    if "orderings" in only:
        basics.print_orderings()
    if "nonlinear" in only:
        nlb.print_nonlinear(NEWTON_TOL)
    if "chapter" in only:
        nlb.print_chapter()
    if "reuse" in only:
        from mechlib.bench.reuse import print_reuse

        print_reuse()
    if "calibration" in only:
        basics.print_calibration()
    if "rom" in only:
        from mechlib.bench import rom

        rom.print_rom()
    if "lean" in only:
        from mechlib.bench.lean import print_lean

        print_lean()
    if "dask" in only:
        from mechlib.bench import dask

        print("\n".join(dask.report(dask.dask_vs_local())))
    if "book" in only:
        from mechlib.bench.book import print_book

        print_book()
    return 0
