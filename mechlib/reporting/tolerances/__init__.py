"""Named tolerances of recorded numbers: how far a re-run may move a value, and why.

A record stores ``rtol`` and ``atol`` (``|a - b| <= atol + rtol * |b|``, see
:mod:`mechlib.reporting.records`). The chapters' record plans (:mod:`mechlib.reporting.plans`)
name one of the classes below for each key instead of writing the numbers: the class says which
kind of numerics produced the value and, in ``why``, why a re-run on another machine (another
BLAS kernel, another order of summation) stays within it.

The numbers are the ones the chapters used as literals: changing one changes the records.

The classes live in one module per kind of numerics, all importable from here
(``from mechlib.reporting.tolerances import ROUNDOFF``): :mod:`.arithmetic` (exact values and
round-off), :mod:`.iterative` (solvers, fits, Monte Carlo), :mod:`.fe` (finite-element solves),
:mod:`.hexflex` and :mod:`.parallelogram` (those mechanisms' models). A new class goes into the
module of its kind (each stays under 400 lines); the class itself is
:class:`mechlib.reporting.tolerance.Tolerance`.
"""

# ruff: noqa: F403
# (the package re-exports every module's classes and functions)

from __future__ import annotations

from mechlib.reporting.tolerance import Tolerance as Tolerance
from mechlib.reporting.tolerances.arithmetic import *
from mechlib.reporting.tolerances.fe import *
from mechlib.reporting.tolerances.hexflex import *
from mechlib.reporting.tolerances.iterative import *
from mechlib.reporting.tolerances.parallelogram import *
