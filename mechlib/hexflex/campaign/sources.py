"""Which source files define an FE result: the modules a task runs and all they import.

:mod:`mechlib.hexflex.campaign.experiments` keys its disk cache on these sources, so that a change
to the mesher, the model or the solver can never return results computed by the old code.
"""

from __future__ import annotations

import ast
import importlib.util
from pathlib import Path

#: The modules a task runs (the linear model, the lean model, the non-linear solver, the
#: finite-rotation pose).
TASK_MODULES: tuple[str, ...] = (
    "mechlib.hexflex.fe.model",
    "mechlib.hexflex.fe.lean",
    "mechlib.fe.nonlinear",
    "mechlib.fe.finite_pose",
)


def model_modules(task_modules: tuple[str, ...] = TASK_MODULES) -> tuple[str, ...]:
    """The mechlib modules a task's results depend on: ``task_modules`` (default the HexFlex's
    ``TASK_MODULES``; a mechanism's spec names its own) and every mechlib module they import,
    directly or not, at module level or inside a function (read from the sources' import
    statements), sorted."""
    seen: set[str] = set()
    todo = list(task_modules)
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        seen.add(name)
        origin = importlib.util.find_spec(name).origin
        for node in ast.walk(ast.parse(Path(origin).read_text())):
            if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                targets = [node.module] + [f"{node.module}.{a.name}" for a in node.names]
            elif isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            else:
                continue
            todo.extend(t for t in targets if t.startswith("mechlib") and _is_module(t))
    return tuple(sorted(seen))


def _is_module(name: str) -> bool:
    """True if ``name`` is an importable module (not a name defined inside one)."""
    try:
        return importlib.util.find_spec(name) is not None
    except ModuleNotFoundError:  # "package.module.NAME": module is no package
        return False
