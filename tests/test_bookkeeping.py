"""Chapters of science: in every notebook at most a quarter of the code lines are bookkeeping.

The measure: the lines spanned by calls on the recorder (``rec.…(…)``, found in the syntax tree)
over the non-blank, non-comment lines of the code cells (IPython magics left out). A chapter's
record keys, tolerances, glue and report rows are data in its plan
(:mod:`mechlib.reporting.plans`), not code in the notebook.
"""

from __future__ import annotations

import ast
import json

import pytest

from mechlib.paths import REPO_ROOT
from mechlib.pipeline.book.cells import recorder_names

#: the largest share of a notebook's code lines that may record
MAX_SHARE = 0.25
NOTEBOOKS = sorted((REPO_ROOT / "notebooks").glob("*.ipynb"))


def bookkeeping(source: str, recorders: frozenset[str] = frozenset({"rec"})) -> tuple[int, int]:
    """(lines spanned by calls on a name in ``recorders``, non-blank non-comment lines) of one
    cell."""
    lines = source.splitlines()
    code = [i for i, line in enumerate(lines, 1) if _is_code(line)]
    tree = ast.parse("\n".join("" if line.strip().startswith("%") else line for line in lines))
    spanned: set[int] = set()
    for node in ast.walk(tree):
        if (
            isinstance(node, ast.Call)
            and isinstance(node.func, ast.Attribute)
            and isinstance(node.func.value, ast.Name)
            and node.func.value.id in recorders
        ):
            spanned.update(range(node.lineno, node.end_lineno + 1))
    return len(spanned & set(code)), len(code)


def _is_code(line: str) -> bool:
    text = line.strip()
    return bool(text) and not text.startswith(("#", "%"))


def test_the_measure_counts_a_call_over_its_lines() -> None:
    cell = "x = f(1)\n# a comment\n\nrec.value(\n    'k',\n    x,\n)\ny = x + 1\n"
    assert bookkeeping(cell) == (4, 6)
    assert bookkeeping("%matplotlib inline\nrec.value('k', 1)\n") == (1, 1)
    renamed = "r = plans.recorder('x')\nr.value('k', 1)\ny = 2\n"
    assert bookkeeping(renamed, frozenset(recorder_names([renamed]))) == (1, 3)


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_a_notebook_is_at_most_a_quarter_bookkeeping(path) -> None:
    cells = [c for c in json.loads(path.read_text())["cells"] if c["cell_type"] == "code"]
    sources = ["".join(c["source"]) for c in cells]
    names = frozenset(recorder_names(sources))  # whatever the notebook calls its recorder
    counts = [bookkeeping(source, names) for source in sources]
    spent, total = sum(a for a, _ in counts), sum(b for _, b in counts)
    assert spent <= MAX_SHARE * total, f"{path.stem}: {spent}/{total} = {spent / total:.0%}"
