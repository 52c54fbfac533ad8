"""The specification of a mechanism's FE model for campaigns: everything that defines it,
picklable and hashable, with a stable text for cache keys (:meth:`MechanismSpec.key`) — what
:class:`mechlib.hexflex.spec.ModelSpec` is for the HexFlex."""

from __future__ import annotations

import hashlib
import json
from dataclasses import asdict, dataclass
from typing import ClassVar

import numpy as np

from mechlib.compliant.layout import Layout, Load, check_load_design
from mechlib.compliant.model import MechanismModel
from mechlib.compliant.solver import MechanismSolver
from mechlib.params import check_float, check_int

#: The modules a task of this kind runs (its cache keys' code fingerprint follows their imports).
TASK_MODULES: tuple[str, ...] = (
    "mechlib.compliant.spec",
    "mechlib.compliant.model",
    "mechlib.compliant.solver",
    "mechlib.fe.finite_pose",
)


@dataclass(frozen=True)
class MechanismSpec:
    """A :class:`MechanismModel`'s layout, element size and layers (picklable, hashable)."""

    layout: Layout
    mesh_size: float
    layers: int = 1
    #: how a campaign's non-linear runs iterate (:meth:`NonlinearSolver.solve`'s ``method``):
    #: full Newton, measured 2.5–3 × faster than the modified method on the parallelogram,
    #: whose large rotations make every load step's kept tangent go stale
    SOLVE_METHOD: ClassVar[str] = "newton"
    TASK_MODULES: ClassVar[tuple[str, ...]] = TASK_MODULES
    #: the non-linear solver a campaign builds on the model (material regions included)
    SOLVER: ClassVar[type] = MechanismSolver

    def __post_init__(self) -> None:
        object.__setattr__(self, "mesh_size", check_float("mesh_size [mm]", self.mesh_size,
                                                          low=0.0, low_open=True))  # fmt: skip
        check_int("layers", self.layers, low=1, high=64)

    @property
    def mesh(self) -> str:
        """The mesh's name in a campaign's progress lines (not part of the key)."""
        return f"{self.mesh_size:g} mm × {self.layers}-layer"

    @property
    def n_loads(self) -> int:
        """Number of load ports (a design's columns)."""
        return len(self.layout.loads)

    @property
    def quad_order(self) -> int:
        """Quadrature order of the non-linear solve: the linear model's."""
        from mechlib.fe.sfepy_base import QUAD_ORDER

        return QUAD_ORDER

    def check_design(self, design: object) -> np.ndarray:
        """A design of loads: (n, k) finite values, each port within its bound."""
        d = np.asarray(design, dtype=float)
        if d.ndim != 2:
            raise ValueError(f"design must be one row of loads per run, got shape {d.shape}")
        return check_load_design(self.layout, d)

    @classmethod
    def from_key(cls, text: str) -> MechanismSpec:
        """The specification whose :meth:`key` is ``text``."""
        fields = json.loads(text)["mechanism"]
        lay = fields.pop("layout")
        layout = Layout(
            parts=tuple((n, tuple(map(tuple, v))) for n, v in lay["parts"]),
            thickness=lay["thickness"],
            clamp=tuple(tuple(map(tuple, s)) for s in lay["clamp"]),
            stage=tuple(lay["stage"]),
            loads=tuple(Load(**{**ld, "segment": tuple(map(tuple, ld["segment"])),
                                "direction": tuple(ld["direction"])}) for ld in lay["loads"]),
            young=lay["young"],
            poisson=lay["poisson"],
            part_young=tuple(map(tuple, lay["part_young"])),
            mesh_sizes=tuple(map(tuple, lay["mesh_sizes"])),
        )  # fmt: skip
        return cls(layout=layout, **fields)

    def key(self) -> str:
        """Stable text of the specification (cache key ingredient)."""
        return json.dumps({"mechanism": asdict(self)}, sort_keys=True)

    def digest(self) -> str:
        """A short name of the specification (8 hex digits of :meth:`key`'s SHA-256)."""
        return hashlib.sha256(self.key().encode()).hexdigest()[:8]

    def build(self) -> MechanismModel:
        """A fresh model (mesh, assembly and factorisation)."""
        return MechanismModel(self.layout, self.mesh_size, self.layers)
