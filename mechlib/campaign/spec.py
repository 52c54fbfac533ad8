"""What a campaign needs of an FE model's specification (:class:`Spec`), and the registry of
the families of specifications whose tasks the FE cache and the results store hold.

A specification is a frozen dataclass (picklable, hashable) that builds its model and names the
code its results depend on; the runner (:mod:`.experiments`), the cache keys (:mod:`.taskcache`),
the results store (:mod:`.store`) and the cold checks (:mod:`.cachecheck`) use only what
:class:`Spec` lists. A store holds tasks of several families (the HexFlex's, a compliant
layout's …), each keyed on its own code's fingerprint: :func:`register` enters a family
(:class:`Family`: its name, specification class and key shape), and the store and the cold checks
find a task's family and specification from its key text through :func:`family_of` and
:func:`spec_from_key`, never by the family's name. :mod:`mechlib.fespecs` registers the
families of this repository; whatever reads or writes a store imports it.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from functools import lru_cache
from typing import Any, ClassVar, Protocol

import numpy as np


class Spec(Protocol):
    """An FE model's specification as a campaign uses it (a frozen dataclass)."""

    #: how a campaign's non-linear runs iterate (:meth:`NonlinearSolver.solve`'s ``method``)
    SOLVE_METHOD: ClassVar[str]
    #: the modules a task runs (its cache keys' code fingerprint follows their imports)
    TASK_MODULES: ClassVar[tuple[str, ...]]
    #: the non-linear solver class a campaign builds on the model (``solver(model,
    #: quad_order=…)``)
    SOLVER: ClassVar[type]

    @property
    def quad_order(self) -> int:
        """Quadrature order of the non-linear solve (a field of that name sets only the solve:
        the runner shares one model among specifications that differ in it alone)."""

    @property
    def n_loads(self) -> int:
        """A design's columns (load ports)."""

    @property
    def mesh(self) -> str:
        """The mesh's name in a campaign's progress lines."""

    def key(self) -> str:
        """Stable text of the specification (a cache key's ingredient)."""

    def digest(self) -> str:
        """A short name of the specification."""

    def build(self) -> Any:
        """A fresh model (``poses``, ``n_dofs``, ``pose_of``, ``stage_motion``)."""

    def check_design(self, design: object) -> np.ndarray:
        """``design`` as a float array (n, ``n_loads``), refused (ValueError) beyond its
        model's bounds."""

    @classmethod
    def from_key(cls, text: str) -> Spec:
        """The specification whose :meth:`key` is ``text``."""


@dataclass(frozen=True)
class Family:
    """A family of specifications in the FE cache and the results store.

    Attributes
    ----------
    name : str
        The family's name in a store's manifest (its ``fingerprints``).
    spec : type
        The specification class (:class:`Spec`).
    wrapped : bool
        True when a specification's key text is ``{name: fields}``; False when it is the fields
        themselves (at most one family: its keys are older than the registry).
    primary : bool
        True for the family whose fingerprint is also the store's ``fingerprint`` (exactly one):
        a store whose primary tasks were computed by other code is refused whole, and its entries
        are always checked against their bounds; another family's entries of other code are left
        out when the store seeds a cache.
    """

    name: str
    spec: type
    wrapped: bool = True
    primary: bool = False


_FAMILIES: dict[str, Family] = {}


def register(family: Family) -> Family:
    """Enter ``family`` in the registry (again: replaced).

    Raises
    ------
    ValueError
        A second unwrapped or primary family under another name.
    """
    for other in _FAMILIES.values():
        if other.name == family.name:
            continue
        if not family.wrapped and not other.wrapped:
            raise ValueError(f"family {family.name!r}: {other.name!r} already has unwrapped keys")
        if family.primary and other.primary:
            raise ValueError(f"family {family.name!r}: {other.name!r} is already the primary one")
    _FAMILIES[family.name] = family
    family_of.cache_clear()
    return family


def families() -> tuple[Family, ...]:
    """The registered families, by name.

    Raises
    ------
    LookupError
        None registered (import :mod:`mechlib.fespecs`).
    """
    if not _FAMILIES:
        raise LookupError("no FE specification family is registered: import mechlib.fespecs")
    return tuple(_FAMILIES[n] for n in sorted(_FAMILIES))


def primary() -> Family:
    """The primary family (see :class:`Family`)."""
    found = [f for f in families() if f.primary]
    if len(found) != 1:
        raise LookupError(f"one registered family must be primary, got {[f.name for f in found]}")
    return found[0]


@lru_cache(maxsize=256)
def family_of(text: str) -> str:
    """The name of the family whose specifications have the key text ``text``: the wrapped
    family named by its one field, else the unwrapped family.

    Raises
    ------
    LookupError
        When no registered family has such keys.
    """
    fields = json.loads(text)
    if len(fields) == 1 and (name := next(iter(fields))) in _FAMILIES and _FAMILIES[name].wrapped:
        return name
    bare = [f.name for f in families() if not f.wrapped]
    if not bare:
        raise LookupError(f"no registered family has keys like {text[:60]!r}")
    return bare[0]


def spec_from_key(text: str) -> Spec:
    """The specification (of its family's class) whose ``key()`` is ``text``."""
    return _FAMILIES[family_of(text)].spec.from_key(text)
