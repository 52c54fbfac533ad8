"""The examples in the docstrings of the functions a reader calls first run, and say what they show.

Designs (Plackett–Burman, CD², space-filling), Lenth's method, the S_T meta-model (Eqs 6, 7, 9),
the full-scale error, the 5R kinematics, the real-time model's plain-Python evaluator and its
fast Legendre evaluation, and the parameter checks of :mod:`mechlib.params` (in the FE results
store's fingerprint, which digests code, not docstrings: its examples leave the store's keys);
the store comparison's bit test, the book's UTC times, its printed parameters and report cells.
The examples print integers, shapes, booleans and rounded floats, so that they hold on any BLAS
kernel and under any NumPy print options.
"""

from __future__ import annotations

import doctest
import importlib

import numpy as np
import pytest

#: the modules whose docstrings hold the examples (docstrings are not digested into FE keys)
MODULES = (
    "mechlib.doe",
    "mechlib.screening",
    "mechlib.metamodels.linear",
    "mechlib.metamodels.metrics",
    "mechlib.metamodels.designs",
    "mechlib.metamodels.evaluator",
    "mechlib.fivebar.kinematics",
    "mechlib.metamodels.legendre",
    "mechlib.params",
    "mechlib.campaign.compare",
    "mechlib.pipeline.provenance",
    "mechlib.pipeline.book.printparams",
    "mechlib.pipeline.book.reportpage",
)
#: at least this many examples, imports not counted (96 today: losing some is noticed)
MIN_EXAMPLES = 90


def _examples(module: str) -> list[doctest.Example]:
    tests = doctest.DocTestFinder().find(importlib.import_module(module))
    return [e for t in tests for e in t.examples if not e.source.startswith(("import ", "from "))]


#: NumPy print options the examples must not depend on (the default, and another)
PRINT_OPTIONS = ({}, {"precision": 3, "floatmode": "fixed", "legacy": "1.25"})


@pytest.mark.parametrize("options", PRINT_OPTIONS, ids=("default", "other-print-options"))
@pytest.mark.parametrize("module", MODULES)
def test_the_examples_of_a_module_run(module: str, options: dict) -> None:
    finder, runner = doctest.DocTestFinder(), doctest.DocTestRunner(verbose=False)
    report: list[str] = []
    with np.printoptions(**options):
        for test in finder.find(importlib.import_module(module)):
            runner.run(test, out=report.append)
    result = runner.summarize(verbose=False)
    assert result.attempted > 0, f"{module} has no examples"
    assert result.failed == 0, "".join(report)


def test_there_are_enough_examples() -> None:
    assert sum(len(_examples(m)) for m in MODULES) >= MIN_EXAMPLES


def test_every_example_in_the_library_is_run() -> None:
    """A module whose docstrings hold an example is in ``MODULES`` (none is left unrun)."""
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    found = {
        ".".join(p.relative_to(root).with_suffix("").parts)
        for p in (root / "mechlib").rglob("*.py")
        if ">>> " in p.read_text(encoding="utf-8")
    }
    assert found <= set(MODULES), f"examples never run: {sorted(found - set(MODULES))}"
