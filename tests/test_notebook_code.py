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


#: Recorder methods that return something a cell would print (``save``: the record's path)
RETURNING = ("value", "text", "claim", "timing", "save")


def _silenced(source: str, node: ast.stmt) -> bool:
    """Whether a ``;`` follows the statement ``node`` on its last line (IPython shows nothing)."""
    line = source.splitlines()[node.end_lineno - 1].encode()  # type: ignore[operator]
    return line[node.end_col_offset :].decode().lstrip().startswith(";")  # offsets in bytes


def echoed_records(cells: list[str]) -> list[str]:
    """Code cells whose last statement is a bare call on the Recorder (``rec.value(...)``,
    ``rec.claim(...)``): the kernel would print what it returns on the page."""
    found = []
    for i, source in enumerate(cells):
        body = ast.parse(source).body
        last = body[-1] if body else None
        if (
            isinstance(last, ast.Expr)
            and isinstance(last.value, ast.Call)
            and isinstance(last.value.func, ast.Attribute)
            and isinstance(last.value.func.value, ast.Name)
            and last.value.func.value.id == "rec"
            and last.value.func.attr in RETURNING
            and not _silenced(source, last)
        ):
            found.append(f"code cell {i + 1}: ends with rec.{last.value.func.attr}(...)")
    return found


def test_the_echo_check_finds_a_cell_ending_with_a_record() -> None:
    cells = [
        "x = 1\nrec.value('k', x,\n          atol=0)  # c",
        "rec.claim('c');  # c",
        "path = rec.save()",
        "",
        "rec.text('µ', 'µm');  # a silenced line with multi-byte characters",
        "rec.save()",
    ]
    assert echoed_records(cells) == [
        "code cell 1: ends with rec.value(...)",
        "code cell 6: ends with rec.save(...)",
    ]


@pytest.mark.parametrize("notebook", NOTEBOOKS, ids=lambda p: p.stem)
def test_no_cell_prints_what_a_record_returns(notebook) -> None:
    cells = json.loads(notebook.read_text())["cells"]
    code = ["".join(c["source"]) for c in cells if c["cell_type"] == "code"]
    assert echoed_records(code) == []


def test_no_markdown_line_starts_with_a_percent_sign() -> None:
    """MyST reads a line that starts with ``%`` as a comment: its text, glued values included,
    would vanish from the page (a reflowed "… 41.9\\n% of full scale" did)."""
    import json

    from mechlib.paths import REPO_ROOT

    bad = []
    for path in sorted((REPO_ROOT / "notebooks").glob("*.ipynb")):
        for i, cell in enumerate(json.loads(path.read_text())["cells"]):
            if cell["cell_type"] == "markdown":
                lines = "".join(cell["source"]).split("\n")
                bad += [
                    f"{path.name} cell {i}: {ln[:60]}" for ln in lines if ln.lstrip()[:1] == "%"
                ]
    for path in sorted((REPO_ROOT / "book").glob("*.md")):
        bad += [f"{path.name}: {ln[:60]}" for ln in path.read_text().split("\n") if ln[:1] == "%"]
    assert not bad, "\n".join(bad)
