"""Which source files define an FE result: the modules a task runs and all they import.

:mod:`mechlib.campaign.experiments` keys its disk cache on these sources' code
(:func:`~mechlib.campaign.taskcache.model_code_fingerprint`), so that a change to the
mesher, the model or the solver can never return results computed by the old code.
"""

from __future__ import annotations

import ast
import importlib.util
from pathlib import Path

from mechlib.campaign.codedigest import internal_target, is_internal, is_typing_block


def model_modules(task_modules: tuple[str, ...]) -> tuple[str, ...]:
    """The mechlib modules a task's results depend on: ``task_modules`` (a specification's
    ``TASK_MODULES``) and every mechlib module they import,
    directly or not, at module level or inside a function (read from the sources' import
    statements), with the packages that hold them (importing a module runs its packages'
    ``__init__``), sorted. An import under ``if TYPE_CHECKING:`` never runs and is not followed.

    Parameters
    ----------
    task_modules : tuple of str
        The modules a task runs.

    Returns
    -------
    tuple of str
        The modules' dotted names.
    """
    seen: set[str] = set()
    todo = list(task_modules)
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        seen.add(name)
        spec = importlib.util.find_spec(name)
        # importing a module runs the __init__ of every package that holds it
        todo.extend(name.rsplit(".", k)[0] for k in range(1, name.count(".") + 1))
        for node in _imports(ast.parse(Path(spec.origin).read_text())):
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif (base := internal_target(node, spec.parent)) is not None:
                targets = [base] + [f"{base}.{a.name}" for a in node.names]
            else:
                continue
            todo.extend(t for t in targets if is_internal(t) and _is_module(t))
    return tuple(sorted(seen))


def _imports(tree: ast.Module) -> list[ast.Import | ast.ImportFrom]:
    """The import statements of ``tree``, anywhere in it, but those under ``if TYPE_CHECKING:``
    (which never run)."""
    found, todo = [], [tree]
    while todo:
        node = todo.pop()
        if isinstance(node, ast.Import | ast.ImportFrom):
            found.append(node)
        children = list(ast.iter_child_nodes(node))
        if is_typing_block(node):
            children = [c for c in children if c in node.orelse]
        todo.extend(children)
    return found


def _is_module(name: str) -> bool:
    """True if ``name`` is an importable module (not a name defined inside one)."""
    try:
        return importlib.util.find_spec(name) is not None
    except ModuleNotFoundError:  # "package.module.NAME": module is no package
        return False
