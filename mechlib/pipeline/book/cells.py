"""Rules that turn an executed notebook into a readable chapter page.

The notebooks stay plain (no presentation tags to maintain by hand); the book build applies, by
rule, what each cell shows:

* the ``parameters`` cell stays visible: readers change it; papermill's injected cell (the values
  a chapter takes from another's record) is merged into it, each injected value replacing its
  default on the same line, so the page shows one parameters cell with the values it ran with;
  the print shows a compact table of them instead (:mod:`mechlib.pipeline.book.printparams`);
* a p-value below 1e-10, quoted by the text from a glued value or shown in a data frame's
  p-value row or column, reads "p < 1e-10", and a data frame's times have two significant
  digits (:mod:`mechlib.pipeline.book.pvalues`);
* formatter directives (``# fmt: off``, ``# fmt: skip``) are dropped from every cell shown;
* a cell whose every statement is bookkeeping — ``rec.value(...)`` (with or without
  ``context=``), ``rec.text(...)``, ``rec.mapping(...)``, ``rec.skipped(...)``,
  ``rec.constants()``, ``rec.save()``, ``glue(..., display=False)``, prints of what those
  return, and the named tolerances of the records (assignments to UPPER_CASE names) — is
  removed (``remove-cell``);
  its glued values still reach the text;
* every other code cell is folded (``hide-input``): figures and tables stay visible;
* outputs lose lines of known library warnings and have absolute machine paths neutralised;
* a figure cell gets its numbered caption and alt text (:mod:`mechlib.pipeline.book.figures`);
* every heading gets a MyST label, so the report and the method pages can link to sections.
"""

from __future__ import annotations

import ast
import copy
import re
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from mechlib.pipeline.book import figures, printparams, pvalues
from mechlib.reporting.artefacts import Section, parse

#: Tags that show a reader-facing cell as written (papermill's parameter cells).
KEEP_VISIBLE = frozenset({"parameters", "injected-parameters"})
#: Tags that already decide what a cell shows: the rules leave such a cell alone.
PRESENTATION_TAGS = frozenset(
    {"hide-input", "hide-output", "hide-cell", "remove-input", "remove-output", "remove-cell"}
)
#: Lines of library chatter that are not part of any result (matched anywhere in a line).
KNOWN_WARNINGS = (
    re.compile(r"install jax and jaxlib"),  # sfepy.terms.terms_jax, printed when sfepy loads terms
)
#: An absolute POSIX path with at least two components, not part of a longer word or URL.
ABSOLUTE_PATH = re.compile(r"(?<![\w.~/:-])/(?:[\w.+-]+/)+[\w.+-]*")
RECORDER_METHODS = frozenset({"value", "text", "save", "mapping", "skipped", "constants"})
_HEADING = re.compile(r"^(#{1,6})\s+(.+?)\s*#*\s*$")
#: a formatter directive: a whole line ``# fmt: off`` or a trailing ``  # fmt: skip``
_FMT_LINE = re.compile(r"^\s*#\s*fmt:\s*(off|on|skip)\s*$")
_FMT_TRAIL = re.compile(r"\s*#\s*fmt:\s*skip\s*$")
#: ``name = value`` at the start of a parameters line
_ASSIGNED = re.compile(r"^([A-Za-z_]\w*)\s*=")
_FENCE = re.compile(r"^\s*(```|~~~)")


def recorder_names(sources: Iterable[str]) -> set[str]:
    """Names bound to ``Recorder(...)`` or ``plans.recorder(...)`` in any cell (``{"rec"}`` if
    none is found)."""
    names: set[str] = set()
    for source in sources:
        try:
            tree = ast.parse(source)
        except SyntaxError:
            continue
        for node in ast.walk(tree):
            if (
                isinstance(node, ast.Assign)
                and isinstance(node.value, ast.Call)
                and _makes_recorder(node.value.func)
            ):
                names |= {t.id for t in node.targets if isinstance(t, ast.Name)}
    return names or {"rec"}


def _makes_recorder(func: ast.expr) -> bool:
    if isinstance(func, ast.Name):  # Recorder(...), or recorder(...) imported from plans
        return func.id in ("Recorder", "recorder")
    return isinstance(func, ast.Attribute) and func.attr == "recorder"  # plans.recorder(...)


def _bookkeeping_call(node: ast.AST, recorders: set[str]) -> bool:
    if not isinstance(node, ast.Call):
        return False
    func = node.func
    if isinstance(func, ast.Name) and func.id == "glue":
        return any(k.arg == "display" and _is_false(k.value) for k in node.keywords)
    return (
        isinstance(func, ast.Attribute)
        and isinstance(func.value, ast.Name)
        and func.value.id in recorders
        and func.attr in RECORDER_METHODS
    )


def _named_constant(stmt: ast.Assign) -> bool:
    """``TOL = ...``: every target an UPPER_CASE name (a record's named tolerance)."""
    return all(isinstance(t, ast.Name) and t.id.isupper() for t in stmt.targets)


def _is_false(node: ast.AST) -> bool:
    return isinstance(node, ast.Constant) and node.value is False


def _loaded_names(node: ast.AST) -> set[str]:
    return {n.id for n in ast.walk(node) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}


def _bookkeeping_block(body: list[ast.stmt], recorders: set[str], derived: set[str]) -> bool:
    for stmt in body:
        if isinstance(stmt, ast.Pass):
            continue
        if isinstance(stmt, ast.Expr) and _bookkeeping_call(stmt.value, recorders):
            continue
        if isinstance(stmt, ast.Assign) and _bookkeeping_call(stmt.value, recorders):
            derived |= {n.id for t in stmt.targets for n in ast.walk(t) if isinstance(n, ast.Name)}
            continue
        if isinstance(stmt, ast.Assign) and _named_constant(stmt):
            continue
        if (
            isinstance(stmt, ast.Expr)
            and isinstance(stmt.value, ast.Call)
            and isinstance(stmt.value.func, ast.Name)
            and stmt.value.func.id == "print"
            and _loaded_names(stmt.value) - {"print"} <= derived
        ):
            continue
        if isinstance(stmt, (ast.For, ast.If)) and _bookkeeping_block(
            stmt.body + stmt.orelse, recorders, derived
        ):
            continue
        return False
    return True


def is_bookkeeping(source: str, recorders: set[str] | None = None) -> bool:
    """Whether every statement of a code cell only records, glues or reports that it did.

    Parameters
    ----------
    source : str
        The cell's code.
    recorders : set of str, optional
        Names of the notebook's ``Recorder`` objects (default ``{"rec"}``).

    Returns
    -------
    bool
        True for e.g. ``path = rec.save()`` followed by ``print(f"written to {path}")``, or a
        ``for`` loop of ``glue(key, value, display=False)``; False as soon as one statement
        computes, displays or cannot be parsed.
    """
    try:
        tree = ast.parse(source)
    except SyntaxError:
        return False
    if not tree.body:
        return False
    return _bookkeeping_block(tree.body, recorders or {"rec"}, set())


def _shows_something(outputs: list[dict[str, Any]]) -> bool:
    """Whether outputs hold a displayed result (glue records with a MIME prefix are not shown)."""
    for out in outputs:
        if out.get("output_type") not in ("display_data", "execute_result"):
            continue
        if out.get("metadata", {}).get("scrapbook", {}).get("mime_prefix"):
            continue
        return True
    return False


def cell_tags(cell: dict[str, Any], recorders: set[str]) -> list[str]:
    """Tags a code cell gets in the book (markdown cells keep theirs).

    A notebook's own presentation tag is kept, except that a bookkeeping cell the notebook only
    folded (``hide-input``) is removed like any other.
    """
    tags = list(cell.get("metadata", {}).get("tags", []))
    if cell.get("cell_type") != "code" or KEEP_VISIBLE & set(tags):
        return tags
    decided = PRESENTATION_TAGS & set(tags)
    if decided - {"hide-input"}:
        return tags
    source = "".join(cell.get("source", ""))
    if is_bookkeeping(source, recorders) and not _shows_something(cell.get("outputs", [])):
        return [t for t in tags if t != "hide-input"] + ["remove-cell"]
    return tags if decided else [*tags, "hide-input"]


def neutralise(text: str, repo_root: Path) -> str:
    """Drop lines of known warnings; show paths inside the repository relative to it and any
    other absolute path by its file name only."""
    root = str(Path(repo_root).resolve()).rstrip("/") + "/"
    lines = [
        ln for ln in text.splitlines(keepends=True) if not any(w.search(ln) for w in KNOWN_WARNINGS)
    ]
    kept = "".join(lines).replace(root, "")
    return ABSOLUTE_PATH.sub(lambda m: m.group(0).rsplit("/", 1)[-1] or "…", kept)


def _clean_text(value: Any, repo_root: Path) -> Any:
    if isinstance(value, list):
        value = "".join(value)
    return neutralise(value, repo_root) if isinstance(value, str) else value


def clean_outputs(outputs: list[dict[str, Any]], repo_root: Path) -> list[dict[str, Any]]:
    """Outputs without known warnings or machine paths; streams left empty are dropped."""
    cleaned = []
    for out in copy.deepcopy(outputs):
        kind = out.get("output_type")
        if kind == "stream":
            out["text"] = _clean_text(out.get("text", ""), repo_root)
            if not out["text"].strip():
                continue
        elif kind in ("display_data", "execute_result"):
            data = out.get("data", {})
            for mime in [m for m in data if m.startswith("text/") or m.endswith("text/plain")]:
                data[mime] = _clean_text(data[mime], repo_root)
        elif kind == "error":
            out["traceback"] = [_clean_text(t, repo_root) for t in out.get("traceback", [])]
        cleaned.append(out)
    return cleaned


def label_headings(source: str, prefix: str, start: int) -> tuple[str, list[Section]]:
    """Insert a MyST label ``(<prefix>-s<k>)=`` before every heading of a markdown cell.

    Parameters
    ----------
    source : str
        Markdown text; headings inside fenced code are left alone.
    prefix : str
        Unique per page (the notebook's name).
    start : int
        Number of headings labelled so far on the page (labels count on across cells).

    Returns
    -------
    str, list of Section
        The labelled markdown and its sections.
    """
    out, sections, fenced = [], [], False
    for line in source.splitlines():
        if _FENCE.match(line):
            fenced = not fenced
        match = None if fenced else _HEADING.match(line)
        if match:
            label = f"{prefix}-s{start + len(sections) + 1}"
            title = match.group(2)
            sections.append(Section(label, title, tuple(parse(title))))
            out.append(f"({label})=")
        out.append(line)
    return "\n".join(out), sections


def prepare_notebook(nb: dict[str, Any], name: str, repo_root: Path) -> tuple[dict, list[Section]]:
    """A copy of an executed notebook ready for the book, and its labelled sections.

    Parameters
    ----------
    nb : dict
        The executed notebook (nbformat 4 JSON).
    name : str
        The page's name (notebook stem), used as the label prefix.
    repo_root : Path
        Paths below it are shown relative to it.
    """
    nb = copy.deepcopy(nb)
    cells = merge_injected(nb.get("cells", []))
    pvalues.floor_glued_p_values(cells)
    recorders = recorder_names(
        "".join(c.get("source", "")) for c in cells if c.get("cell_type") == "code"
    )
    sections: list[Section] = []
    prefix = re.sub(r"[^a-z0-9]+", "-", name.lower()).strip("-")
    out_cells = []
    for cell in cells:
        out_cells.append(cell)
        if cell.get("cell_type") == "markdown":
            text, found = label_headings("".join(cell.get("source", "")), prefix, len(sections))
            cell["source"] = text
            sections += found
            continue
        if cell.get("cell_type") != "code":
            continue
        cell["source"] = strip_formatter_directives("".join(cell.get("source", "")))
        cell.setdefault("metadata", {})["tags"] = cell_tags(cell, recorders)
        cell["outputs"] = clean_outputs(cell.get("outputs", []), repo_root)
        pvalues.print_output_frames(cell["outputs"])
        if "parameters" in cell["metadata"]["tags"]:
            printed = printparams.print_cell(cell)
            out_cells += [printed] if printed else []
        figure = figures.figure_metadata(name, cell)
        if figure is not None:
            cell["metadata"]["mystnb"] = figure
            rest = split_figure(cell)
            out_cells += [rest] if rest else []
    nb["cells"] = out_cells
    return nb, sections


def strip_formatter_directives(source: str) -> str:
    """A cell's source without ``# fmt: off/on`` lines and trailing ``# fmt: skip`` comments."""
    lines = [_FMT_TRAIL.sub("", line) for line in source.splitlines() if not _FMT_LINE.match(line)]
    return "\n".join(lines) + ("\n" if source.endswith("\n") else "")


def merge_injected(cells: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """The cells with papermill's injected parameters merged into the ``parameters`` cell: each
    injected ``name = value`` replaces that name's default line (its comment kept, marked as
    passed by the build); a name the cell does not define is appended. Without an injected cell,
    the cells as given."""
    tags = [c.get("metadata", {}).get("tags", []) for c in cells]
    injected = [i for i, t in enumerate(tags) if "injected-parameters" in t]
    defaults = [i for i, t in enumerate(tags) if "parameters" in t]
    if not injected or not defaults:
        return cells
    values = {}
    for line in "".join(cells[injected[0]].get("source", "")).splitlines():
        m = _ASSIGNED.match(line)
        if m:
            values[m.group(1)] = line.strip()
    lines = "".join(cells[defaults[0]].get("source", "")).splitlines()
    for k, line in enumerate(lines):
        m = _ASSIGNED.match(line)
        if m and m.group(1) in values:
            comment = line.split("  # ", 1)[1] if "  # " in line else ""
            note = "passed by the build" + (f"; {comment}" if comment else "")
            lines[k] = f"{values.pop(m.group(1))}  # {note}"
    lines += [f"{v}  # passed by the build" for v in values.values()]
    merged = copy.deepcopy(cells[defaults[0]])
    merged["source"] = "\n".join(lines) + "\n"
    return [merged if i == defaults[0] else c for i, c in enumerate(cells) if i != injected[0]]


def split_figure(cell: dict[str, Any]) -> dict[str, Any] | None:
    """Keep only a figure cell's image outputs (and text streams) in it, so that its caption
    goes to the figure alone; return a cell showing its other outputs (a table shown beside the
    figure), without input, or None when it has none."""
    images, others = [], []
    for out in cell.get("outputs", []):
        shown = out.get("output_type") in ("display_data", "execute_result")
        is_image = shown and set(out.get("data", {})) & {"image/png", "image/svg+xml", "image/jpeg"}
        (others if shown and not is_image else images).append(out)
    if not others:
        return None
    cell["outputs"] = images
    return {
        "cell_type": "code",
        "execution_count": None,
        "id": f"{cell.get('id', 'cell')}-shown",
        "metadata": {"tags": ["remove-input"]},
        "outputs": others,
        "source": "",
    }
