"""The house's import graph, read statically from the sources and drawn as Mermaid.

``python -m mechlib.pipeline.housegraph`` prints the drawings; ``--write ARCHITECTURE.md`` redraws
them in place, between the file's ``<!-- housegraph NAME -->`` and ``<!-- /housegraph -->``
markers. A room is a module or a package one level below the drawn package, an arrow an import
(anywhere in a module: at its top, inside a function or under ``if TYPE_CHECKING:``), and the
rooms are grouped by wing. No line counts are drawn, so a drawing changes only when an import
between rooms does; ``tests/test_housegraph.py`` requires ARCHITECTURE.md's to be current and
``tests/test_wings.py`` holds the graph to the house's rules.
"""

from __future__ import annotations

import argparse
import ast
import re
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from mechlib.paths import REPO_ROOT

MECHLIB = REPO_ROOT / "mechlib"
#: the build wing: notebook execution, the book and its checks (the science wing never imports it)
BUILD_WING = "mechlib.pipeline"
#: beside both wings: ``make bench`` times the science wing and may read what the build wing wrote
TOOLS = ("mechlib.bench",)
#: where the drawings sit between their markers
MARKED = re.compile(r"(<!-- housegraph (\w[\w-]*) -->\n)(.*?)(<!-- /housegraph -->)", re.S)


def module_name(path: Path, root: Path = REPO_ROOT) -> str:
    """Dotted name of a source file (a package's ``__init__.py`` is the package)."""
    parts = path.relative_to(root).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def modules(package_dir: Path = MECHLIB) -> dict[str, Path]:
    """Every module under ``package_dir``, by dotted name, in name order."""
    found = {module_name(p, package_dir.parent): p for p in package_dir.rglob("*.py")}
    return dict(sorted(found.items()))


def imports_of(module: str, known: dict[str, Path]) -> set[str]:
    """The modules of ``known`` that ``module`` imports, anywhere in its source.

    ``from pkg import mod`` counts as an import of ``pkg.mod`` when that is a module, else of
    ``pkg``; the module itself is left out.
    """
    found = set()
    for node in ast.walk(ast.parse(known[module].read_text())):
        if isinstance(node, ast.Import):
            found |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.module:
            for alias in node.names:
                sub = f"{node.module}.{alias.name}"
                found.add(sub if sub in known else node.module)
    return {m for m in found if m in known and m != module}


def import_graph(known: dict[str, Path]) -> dict[str, set[str]]:
    """Each module of ``known`` → the modules of ``known`` it imports."""
    return {m: imports_of(m, known) for m in known}


def inside(module: str, package: str) -> bool:
    """Whether ``module`` is ``package`` or lies below it."""
    return module == package or module.startswith(package + ".")


def wing(module: str) -> str:
    """The wing of a mechlib module: ``"build"``, ``"tools"`` or ``"science"``."""
    if inside(module, BUILD_WING):
        return "build"
    return "tools" if any(inside(module, t) for t in TOOLS) else "science"


@dataclass(frozen=True)
class Drawing:
    """What one drawing shows: the rooms of ``package``, grouped by ``group`` (a room → its
    group's title, one of ``groups``, drawn in that order), and with ``outside`` the rooms
    elsewhere in mechlib that they import."""

    package: str
    group: Callable[[str], str]
    groups: tuple[str, ...]
    outside: bool = False


WINGS = {"science": "science wing", "build": "build wing", "tools": "beside both wings"}


HEXFLEX_GROUPS = ("mechlib/hexflex/", "elsewhere in mechlib/")


def _hexflex_group(room: str) -> str:
    return HEXFLEX_GROUPS[0 if inside(room, "mechlib.hexflex") else 1]


#: the drawings of ARCHITECTURE.md, by marker name
DRAWINGS = {
    "house": Drawing("mechlib", lambda room: WINGS[wing(room)], tuple(WINGS.values())),
    "hexflex": Drawing("mechlib.hexflex", _hexflex_group, HEXFLEX_GROUPS, outside=True),
}


def room(module: str, package: str) -> str | None:
    """The room of ``package`` that holds ``module``: the module or package one level below
    ``package`` (``None`` for ``package``'s own ``__init__`` and modules outside it)."""
    if module == package or not inside(module, package):
        return None
    return ".".join(module.split(".")[: package.count(".") + 2])


def rooms_and_arrows(
    graph: dict[str, set[str]], drawing: Drawing
) -> tuple[list[str], list[tuple[str, str]]]:
    """The rooms of a drawing (sorted) and its arrows (importer, imported; sorted, one per pair)."""
    rooms, arrows = set(), set()
    for module, imported in graph.items():
        source = room(module, drawing.package)
        if source is None:
            continue
        rooms.add(source)
        for target_module in imported:
            target = room(target_module, drawing.package)
            if target is None and drawing.outside:
                target = room(target_module, "mechlib")
            if target is not None and target != source:
                rooms.add(target)
                arrows.add((source, target))
    return sorted(rooms), sorted(arrows)


def _node(name: str, known: dict[str, Path]) -> str:
    path = known[name]
    label = name.split(".")[-1] + ("/" if path.name == "__init__.py" else ".py")
    return f'{name.replace(".", "_")}["{label}"]'


def mermaid(name: str, known: dict[str, Path] | None = None) -> str:
    """The drawing ``name`` of :data:`DRAWINGS` as a Mermaid flowchart (importers above)."""
    known = modules() if known is None else known
    drawing = DRAWINGS[name]
    rooms, arrows = rooms_and_arrows(import_graph(known), drawing)
    lines = ["flowchart TD"]
    for i, title in enumerate(drawing.groups):
        lines.append(f'  subgraph g{i}["{title}"]')
        lines += [f"    {_node(r, known)}" for r in rooms if drawing.group(r) == title]
        lines.append("  end")
    lines += [f"  {a.replace('.', '_')} --> {b.replace('.', '_')}" for a, b in arrows]
    return "\n".join(lines) + "\n"


def redraw(text: str, known: dict[str, Path] | None = None) -> str:
    """``text`` with every marked drawing replaced by the current one (a fenced Mermaid block).

    Raises
    ------
    ValueError
        If a marker names no drawing of :data:`DRAWINGS`.
    """
    known = modules() if known is None else known

    def block(match: re.Match) -> str:
        name = match.group(2)
        if name not in DRAWINGS:
            raise ValueError(f"no drawing {name!r}; have {sorted(DRAWINGS)}")
        return f"{match.group(1)}```mermaid\n{mermaid(name, known)}```\n{match.group(4)}"

    return MARKED.sub(block, text)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m mechlib.pipeline.housegraph",
        description="Draw mechlib's import graph as Mermaid (print one, or redraw a file's).",
    )
    parser.add_argument("drawing", nargs="?", choices=sorted(DRAWINGS), default="house")
    parser.add_argument("--write", type=Path, help="redraw every marked drawing of this file")
    args = parser.parse_args(argv)
    if args.write is None:
        sys.stdout.write(mermaid(args.drawing))
        return 0
    text = args.write.read_text()
    new = redraw(text)
    if new != text:
        args.write.write_text(new)
    state = "redrawn" if new != text else "current"
    print(f"{args.write}: {len(MARKED.findall(new))} drawings, {state}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
