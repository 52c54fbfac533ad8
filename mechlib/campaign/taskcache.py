"""The FE cache's files: task keys, the code fingerprint in them, atomic writes, the task log.

:func:`mechlib.campaign.experiments.run_experiments` caches each finished task as
``<key>.npy`` (its poses) under a key made of the cache format, the fingerprint of the sources
that define a result, the model specification, the kind, the load steps and the forces; the
results store (:mod:`mechlib.campaign.store`) and the cold checks
(:mod:`mechlib.campaign.cachecheck`) recompute the same keys.
"""

from __future__ import annotations

import ast
import concurrent.futures as cf
import hashlib
import importlib.util
import json
from functools import lru_cache
from pathlib import Path

import numpy as np

from mechlib.campaign.codedigest import closure_digests
from mechlib.campaign.solve import STATE
from mechlib.campaign.sources import model_modules
from mechlib.paths import fe_log_path

#: 2: a non-linear task stores its poses in the three conventions; 3: and its solve statistics;
#: 4: the fingerprint digests the FE code's normalised syntax trees, not its bytes and names;
#: 5: each module named by a digest of its code and of all it imports (transitively), the task
#: runner (:data:`SOLVE_MODULE`) and the specification's module in every closure
CACHE_VERSION = 5
#: the module every task runs, whatever its family (how a task is solved: in every closure)
SOLVE_MODULE = "mechlib.campaign.solve"


@lru_cache(maxsize=4)
def model_code_fingerprint(task_modules: tuple[str, ...]) -> str:
    """Digest of the code that defines a task's results (:func:`model_modules`: geometry,
    mesh, FE model, solver, pose fit …) of the tasks that run ``task_modules`` (a
    specification's ``TASK_MODULES``, :class:`mechlib.campaign.spec.Spec`).

    Part of every cache key, so that a change to the mesher or the solver can never return
    results computed by the old code. It digests each module's syntax tree without docstrings,
    annotations, typing-only imports and module paths
    (:func:`~mechlib.campaign.codedigest.code_digest`), and combines the modules'
    digests sorted, not their names: rewording a docstring or a comment, or moving or renaming a
    module (its importers updated), keeps the cache and the results store; changing a line of
    code does not. A package whose ``__init__.py`` holds only its docstring (what the package is
    for) defines nothing and is left out.

    Parameters
    ----------
    task_modules : tuple of str
        The modules a task runs (their closure is digested).

    Returns
    -------
    str
        16 hex digits.
    """
    sources = {name: _source(name) for name in model_modules((*task_modules, SOLVE_MODULE))}
    return fingerprint_sources(
        {name: (src, importlib.util.find_spec(name).parent) for name, src in sources.items()}
    )


def fingerprint_sources(modules: dict[str, tuple[bytes, str]]) -> str:
    """The fingerprint of a closure of modules (see :func:`model_code_fingerprint`).

    Parameters
    ----------
    modules : dict
        ``{name: (source, package)}``, ``package`` the module's ``__package__``; the names
        serve only to resolve the modules' imports of each other, and are not digested.

    Returns
    -------
    str
        16 hex digits.
    """
    deep = closure_digests(modules)
    digests = sorted(deep[name] for name, (src, _) in modules.items() if _defines_code(src))
    return hashlib.sha256("\n".join(digests).encode()).hexdigest()[:16]


def _source(name: str) -> bytes:
    return Path(importlib.util.find_spec(name).origin).read_bytes()


def _defines_code(source: bytes) -> bool:
    """True if a module's source has a statement besides its docstring and ``__future__``
    imports."""
    body = ast.parse(source).body
    return any(
        not (isinstance(s, ast.Expr) and isinstance(s.value, ast.Constant))
        and not (isinstance(s, ast.ImportFrom) and s.module == "__future__")
        for s in body
    )


def task_key(
    spec: str,
    kind: str,
    forces: np.ndarray,
    steps: int,
    fingerprint: str,
) -> str:
    """The cache key of a task: a digest of the cache format (:data:`CACHE_VERSION`), the code
    ``fingerprint`` (:func:`model_code_fingerprint`), the model ``spec`` (:meth:`ModelSpec.key`
    text), the ``kind``, the load ``steps`` and the ``forces`` (rows, 6) [N] as float64 bytes."""
    h = hashlib.sha256()
    h.update(f"{CACHE_VERSION}|{fingerprint}|{spec}|{kind}|{steps}|".encode())
    h.update(np.ascontiguousarray(forces, dtype=np.float64).tobytes())
    return h.hexdigest()[:32]


def cache_file(key: str, kind: str) -> str:
    """The name of a task's file in the FE cache: ``<key>.npy``, or ``<key>.state.npy`` for a
    :data:`STATE` task (a displacement field, 8 bytes a DOF, told apart by its name)."""
    return f"{key}.{STATE}.npy" if kind == STATE else f"{key}.npy"


def cache_result(path: Path, n_rows: int, fut: cf.Future) -> None:
    """Save a finished task's poses (n_rows, columns) to ``path``; a failed task saves nothing.

    Written to a temporary file and renamed, so a reader never sees a partial file (the
    done-callback and the collecting loop may both write it: same content, atomic rename).
    """
    import os
    import tempfile

    if fut.cancelled() or fut.exception() is not None:
        return
    res = np.asarray(fut.result(), dtype=float).reshape(n_rows, -1)
    fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".npy.tmp")
    with os.fdopen(fd, "wb") as fh:
        np.save(fh, res)
    os.replace(tmp, path)


def cached_result(path: Path, n_rows: int, width: int = 6) -> np.ndarray | None:
    """The cached poses (n_rows, width) at ``path``, or ``None`` if absent or unreadable (then
    the task runs again)."""
    if not path.exists():
        return None
    try:
        res = np.load(path)
    except (OSError, ValueError, EOFError):
        return None
    return res if res.shape == (n_rows, width) and np.all(np.isfinite(res)) else None


def log_task(path: Path, spec: str, kind: str, forces: np.ndarray, steps: int, hit: bool) -> None:
    """Append a task to ``$MECHLIB_FE_LOG`` (if set; one JSON line: the cache file, the task's
    inputs and whether it was read from the cache), so that
    :mod:`mechlib.campaign.cachecheck` can recompute a sample of the hits cold and
    :mod:`mechlib.campaign.store` can collect every task a build used."""
    log = fe_log_path()
    if log is not None:
        entry = {"file": path.name, "spec": spec, "kind": kind, "steps": steps, "hit": hit}
        with open(log, "a") as fh:
            fh.write(json.dumps({**entry, "forces": forces.tolist()}) + "\n")
