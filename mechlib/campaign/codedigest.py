"""A digest of a Python module's code, not of its text: what the FE cache's keys hold.

:func:`~mechlib.campaign.taskcache.model_code_fingerprint` digests the modules that define
an FE result. Were it to digest their bytes, fixing a typo in a docstring would throw away every
cached run and the results store. It digests each module's syntax tree instead, normalised by
:func:`normalise`:

- docstrings (of the module, its classes and functions, and any other statement that is a string
  alone) removed; comments and layout are not in a syntax tree, nor are line and column numbers
  in the digest (code that reads a ``__doc__`` would escape it: the FE code reads none);
- type annotations removed (of arguments and returns; ``x: T = v`` becomes ``x = v``, and a bare
  ``x: T`` keeps its name, a dataclass field, and marks only ``ClassVar``, ``InitVar`` and
  ``KW_ONLY``, which change what a dataclass is; a bare annotation inside a function stays);
- ``from __future__`` imports, and every statement under ``if TYPE_CHECKING:``, removed;
- the module path of a mechlib import (and the name of a mechlib module imported from its
  package) replaced by the digest of the imported module (:func:`closure_digests`: its
  normalised code with its own imports so named, all the way down), so that moving or renaming a
  module (its importers updated) changes no digest, while importing a name from another module,
  or a change anywhere below what a module imports, does.

The digest depends on the Python version's syntax tree (pinned by ``environment.lock``): fields a
later version adds empty are left out of it.
"""

from __future__ import annotations

import ast
import hashlib
import importlib.util

#: the package whose imports are named by their code, not their path
PACKAGE = "mechlib"
#: annotations that change what a dataclass makes of a class attribute (``_: KW_ONLY`` makes the
#: fields after it keyword-only)
DATACLASS_MARKERS = ("ClassVar", "InitVar", "KW_ONLY")


def is_typing_block(node: ast.AST) -> bool:
    """True for ``if TYPE_CHECKING:`` (or ``typing.TYPE_CHECKING``): code that never runs."""
    if not isinstance(node, ast.If):
        return False
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def internal_target(node: ast.AST, package: str = "") -> str | None:
    """The mechlib module an import statement reads from (``from X import …``: X, a relative
    one resolved against ``package``, the importer's ``__package__``; ``import X``: its first
    name), or ``None`` if it reads none."""
    if isinstance(node, ast.ImportFrom):
        name = node.module or ""
        if node.level:
            try:
                name = importlib.util.resolve_name("." * node.level + name, package)
            except (ImportError, ValueError):
                return None
    elif isinstance(node, ast.Import):
        name = node.names[0].name
    else:
        return None
    return name if is_internal(name) else None


def is_internal(name: str) -> bool:
    """True if the dotted ``name`` is :data:`PACKAGE` or inside it."""
    return name == PACKAGE or name.startswith(f"{PACKAGE}.")


def normalise(
    source: str | bytes, package: str = "", digests: dict[str, str] | None = None
) -> ast.Module:
    """The syntax tree of ``source`` without what cannot change a result: docstrings,
    annotations, typing-only imports, the paths of mechlib imports (see the module docstring).

    Parameters
    ----------
    source : str or bytes
        A module's source.
    package : str, optional
        The package it belongs to (its ``__package__``), against which a relative import is
        resolved.
    digests : dict, optional
        :func:`local_digest` of each mechlib module, by name: an import from one of them names
        that digest; an import from a module not in it, or without ``digests``, names nothing.

    Returns
    -------
    ast.Module
        The normalised tree.
    """
    tree = ast.parse(source)
    _Normaliser(package, digests or {}).visit(tree)
    return tree


def local_digest(source: str | bytes) -> str:
    """SHA-256 (hex) of a module's normalised code, its mechlib imports naming no module."""
    return hashlib.sha256(dump(normalise(source)).encode()).hexdigest()


def imported_modules(source: str | bytes, package: str = "") -> set[str]:
    """The mechlib modules and packages a module's code imports (module level or in a function;
    not under ``if TYPE_CHECKING:``), as dotted names: for ``from X import a``, X and ``X.a``
    (which is a module only if ``a`` is one: the caller keeps the names it knows)."""
    found: set[str] = set()
    todo = [ast.parse(source)]
    while todo:
        node = todo.pop()
        children = list(ast.iter_child_nodes(node))
        if is_typing_block(node):
            children = list(node.orelse)
        if isinstance(node, ast.Import):
            found |= {a.name for a in node.names if is_internal(a.name)}
        elif (base := internal_target(node, package)) is not None:
            found |= {base} | {f"{base}.{a.name}" for a in node.names}
        todo.extend(children)
    return found


def closure_digests(modules: dict[str, tuple[str | bytes, str]]) -> dict[str, str]:
    """The digest of each module of a closure: its normalised code, each mechlib import naming
    the digest of the module it reads, computed the same way — so a module's digest covers
    everything it imports, all the way down.

    Parameters
    ----------
    modules : dict
        ``{name: (source, package)}`` of every module of the closure; an import of a module not
        in it names nothing.

    Returns
    -------
    dict
        ``{name: 64 hex digits}``. Where modules import each other in a circle, the import that
        closes it names the imported module's :func:`local_digest` (its code without its imports'
        digests); modules are visited by sorted name, which decides where a circle is closed.
    """
    deps = {
        name: sorted(m for m in imported_modules(src, pkg) if m in modules and m != name)
        for name, (src, pkg) in modules.items()
    }
    done: dict[str, str] = {}
    busy: set[str] = set()

    def visit(name: str) -> str:
        if name in done:
            return done[name]
        busy.add(name)
        named = {}
        for dep in deps[name]:
            named[dep] = local_digest(modules[dep][0]) if dep in busy else visit(dep)
        busy.discard(name)
        src, pkg = modules[name]
        done[name] = code_digest(src, pkg, named)
        return done[name]

    for name in sorted(modules):
        visit(name)
    return done


def code_digest(
    source: str | bytes, package: str = "", digests: dict[str, str] | None = None
) -> str:
    """SHA-256 of a module's normalised code, each mechlib import naming the
    :func:`local_digest` of the module it reads.

    Parameters
    ----------
    source : str or bytes
        The module's source.
    package : str, optional
        Its ``__package__`` (resolves relative imports).
    digests : dict, optional
        :func:`local_digest` of each mechlib module by dotted name (see :func:`normalise`).

    Returns
    -------
    str
        64 hex digits.
    """
    return hashlib.sha256(dump(normalise(source, package, digests)).encode()).hexdigest()


def dump(node: object) -> str:
    """A canonical text of a syntax tree: node types and fields, without positions; fields that
    are ``None`` or empty are left out (so that a field a later Python adds empty changes
    nothing)."""
    if isinstance(node, ast.AST):
        fields = [
            f"{name}={dump(value)}"
            for name, value in ast.iter_fields(node)
            if value is not None and value != []
        ]
        return f"{type(node).__name__}({','.join(fields)})"
    if isinstance(node, list):
        return f"[{','.join(dump(x) for x in node)}]"
    return f"{type(node).__name__}:{node!r}"


def _is_text(statement: ast.stmt) -> bool:
    """True for a statement that is a string and nothing else: a docstring (of a module, class
    or function) or an attribute's docstring, which no code runs."""
    return (
        isinstance(statement, ast.Expr)
        and isinstance(statement.value, ast.Constant)
        and isinstance(statement.value.value, str)
    )


class _Normaliser(ast.NodeTransformer):
    """Removes docstrings, annotations, ``__future__`` imports and typing-only blocks; names a
    mechlib import by the digest of the module it reads."""

    def __init__(self, package: str, digests: dict[str, str]) -> None:
        self.package, self.digests = package, digests
        self.in_class = False

    def generic_visit(self, node: ast.AST) -> ast.AST:
        for name in ("body", "orelse", "finalbody"):
            body = getattr(node, name, None)
            if isinstance(body, list):  # ``if TYPE_CHECKING: … else: …`` runs its ``else``
                kept = [[s] if not is_typing_block(s) else s.orelse for s in body]
                setattr(node, name, [s for group in kept for s in group if not _is_text(s)])
        return super().generic_visit(node)

    def visit_ClassDef(self, node: ast.ClassDef) -> ast.AST:
        outer, self.in_class = self.in_class, True
        self.generic_visit(node)
        self.in_class = outer
        return node

    def visit_FunctionDef(self, node: ast.FunctionDef | ast.AsyncFunctionDef) -> ast.AST:
        outer, self.in_class = self.in_class, False
        node.returns = None
        self.generic_visit(node)
        self.in_class = outer
        return node

    visit_AsyncFunctionDef = visit_FunctionDef

    def visit_arg(self, node: ast.arg) -> ast.AST:
        node.annotation = None
        node.type_comment = None
        return node

    def visit_AnnAssign(self, node: ast.AnnAssign) -> ast.AST | None:
        if not self.in_class:  # ``x: T = v`` binds as ``x = v``; a bare ``x: T`` binds nothing
            if node.value is not None:
                return self.visit(ast.Assign(targets=[node.target], value=node.value))
            # but makes ``x`` local in a function: kept, without its annotation
            node.annotation = ast.Name(id="", ctx=ast.Load())
            return node
        # in a class body an annotation makes a dataclass field (unlike ``x = v``): kept as a mark
        marker = next((m for m in DATACLASS_MARKERS if m in ast.unparse(node.annotation)), "")
        node.annotation = ast.Name(id=marker, ctx=ast.Load())
        return self.generic_visit(node)

    def visit_ImportFrom(self, node: ast.ImportFrom) -> ast.AST | None:
        if node.module == "__future__":
            return None
        if node.module == "typing":
            node.names = [a for a in node.names if a.name != "TYPE_CHECKING"]
            if not node.names:
                return None
        target = internal_target(node, self.package)
        if target is not None:
            node.module, node.level = self.digests.get(target, ""), 0
            for alias in node.names:  # ``from package import module``: the module's digest
                sub = self.digests.get(f"{target}.{alias.name}")
                if sub is not None:
                    alias.name, alias.asname = sub, alias.asname or alias.name
        return node

    def visit_Import(self, node: ast.Import) -> ast.AST:
        for alias in node.names:
            target = internal_target(ast.Import(names=[alias]))
            if target is not None and alias.asname:
                alias.name = self.digests.get(target, "")
        return node
