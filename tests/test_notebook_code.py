"""What the notebooks' code may hold: parameters, calls, figures and records — no definitions,
and no glue that bypasses the Recorder (read statically, nothing is executed)."""

from __future__ import annotations

import ast
import json

import pytest

from mechlib.paths import REPO_ROOT

NOTEBOOKS = sorted((REPO_ROOT / "notebooks").glob("*.ipynb"))
DEFINITIONS = (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef)


def _code(nb: object) -> str:
    cells = json.loads(nb.read_text())["cells"]  # type: ignore[attr-defined]
    return "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "code")


def definitions_and_glue(source: str) -> list[str]:
    """Function, lambda and class definitions, and imports of myst-nb's ``glue``, by line."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, DEFINITIONS):
            found.append((node.lineno, type(node).__name__))
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("myst_nb"):
            found.append((node.lineno, "glue imported (glue through Recorder.value/text)"))
    return [f"line {line}: {what}" for line, what in sorted(found)]


def test_the_check_finds_what_it_looks_for() -> None:
    source = (
        "f = lambda x: x\ndef g():\n    pass\nfrom myst_nb import glue\nrec.value('k', 1, atol=0)"
    )
    assert [p.split(": ")[1] for p in definitions_and_glue(source)] == [
        "Lambda",
        "FunctionDef",
        "glue imported (glue through Recorder.value/text)",
    ]


@pytest.mark.parametrize("notebook", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebooks_define_nothing_and_glue_only_through_the_recorder(notebook) -> None:
    assert definitions_and_glue(_code(notebook)) == []
