"""The specification of a HexFlex FE model for campaigns (:class:`mechlib.campaign.spec.Spec`):
everything that defines it, picklable and hashable, with a stable text for cache keys
(:meth:`ModelSpec.key`) — what :class:`mechlib.compliant.spec.MechanismSpec` is for a compliant
layout. :mod:`mechlib.fespecs` registers it as the family ``hexflex``."""

from __future__ import annotations

import hashlib
import json
from dataclasses import asdict, dataclass
from typing import ClassVar

import numpy as np

from mechlib.fe.nonlinear import NonlinearSolver
from mechlib.fe.sfepy_base import QUAD_ORDER
from mechlib.hexflex.fe.lean import lean_model
from mechlib.hexflex.fe.model import HexFlexModel, check_forces
from mechlib.hexflex.geometry import AL7075_POISSON, AL7075_YOUNG_MPA, HexFlexGeometry
from mechlib.params import check_choice, check_float, check_int

#: FE mesh recipes a :class:`ModelSpec` names
MESHES: tuple[str, ...] = ("default", "lean")
#: The modules a HexFlex task runs (this specification, which builds the model and names the solve
#: method, the linear model, the lean model, the non-linear solver, the finite-rotation pose): its
#: cache keys' code fingerprint follows their imports.
TASK_MODULES: tuple[str, ...] = (
    "mechlib.hexflex.spec",
    "mechlib.hexflex.fe.model",
    "mechlib.hexflex.fe.lean",
    "mechlib.fe.nonlinear",
    "mechlib.fe.finite_pose",
)


@dataclass(frozen=True)
class ModelSpec:
    """Everything that defines an FE model (picklable, hashable, JSON-serialisable)."""

    geometry: HexFlexGeometry
    young: float = AL7075_YOUNG_MPA
    poisson: float = AL7075_POISSON
    mesh_size: float | None = None
    element: str = "q2"
    #: quadrature order of the non-linear solve (:class:`NonlinearSolver`'s ``quad_order``); the
    #: linear model always uses :data:`mechlib.fe.sfepy_base.QUAD_ORDER`
    quad_order: int = QUAD_ORDER
    #: the mesh recipe: ``"default"`` (:class:`HexFlexModel`, flexure elements ``mesh_size``) or
    #: ``"lean"`` (:func:`mechlib.hexflex.fe.lean.lean_model`, Q2 only: its own element sizes, its
    #: pose fitted at the stage vertices of the default mesh of size ``mesh_size``, the default
    #: model it stands for; its geometry should be fitted to that model's magnitudes by
    #: :func:`mechlib.hexflex.studies.leanmesh.fit_lean`, or it is a few % off them)
    mesh: str = "default"
    #: the default mesh's growth away from the flexures (:class:`HexFlexModel`'s ``coarsening``;
    #: None: its default)
    coarsening: float | None = None
    #: how a campaign's non-linear runs iterate (:meth:`NonlinearSolver.solve`'s ``method``)
    SOLVE_METHOD: ClassVar[str] = "modified"
    #: the modules a task runs (its cache keys' code fingerprint follows their imports)
    TASK_MODULES: ClassVar[tuple[str, ...]] = TASK_MODULES
    #: the non-linear solver a campaign builds on the model
    SOLVER: ClassVar[type] = NonlinearSolver
    #: a design's columns: the six actuator forces
    n_loads: ClassVar[int] = 6

    def check_design(self, design: object) -> np.ndarray:
        """A design of actuator forces: (n, 6) finite values within ±``MAX_FORCE_N`` N."""
        return check_forces_design(design)

    def __post_init__(self) -> None:
        check_int("quad_order", self.quad_order, low=2, high=10)
        check_choice("mesh", self.mesh, MESHES)
        if self.mesh == "lean" and self.element != "q2":
            raise ValueError(f"mesh 'lean' is Q2: element must be 'q2', got {self.element!r}")
        if self.coarsening is not None:  # a float (2 and 2.0: one key), in its range
            c = check_float("coarsening", self.coarsening, low=1.0, high=64.0)
            object.__setattr__(self, "coarsening", c)
            if self.mesh == "lean":
                raise ValueError(f"mesh 'lean' sets its own grading: coarsening must be None, "
                                 f"got {self.coarsening!r}")  # fmt: skip

    @classmethod
    def from_key(cls, text: str) -> ModelSpec:
        """The specification whose :meth:`key` is ``text``."""
        fields = json.loads(text)
        return cls(geometry=HexFlexGeometry(**fields.pop("geometry")), **fields)

    def key(self) -> str:
        """Stable text of the specification (cache key ingredient; a ``coarsening`` of None is
        left out, so the keys of specifications without it are those they had before it)."""
        d = asdict(self)
        if d["coarsening"] is None:
            del d["coarsening"]
        return json.dumps(d, sort_keys=True)

    def digest(self) -> str:
        """A short name of the specification (8 hex digits of :meth:`key`'s SHA-256)."""
        return hashlib.sha256(self.key().encode()).hexdigest()[:8]

    def build(self) -> HexFlexModel:
        """A fresh model (assembly and factorisation)."""
        if self.mesh == "lean":
            return lean_model(
                self.geometry, young=self.young, poisson=self.poisson, pose_mesh_size=self.mesh_size
            )
        return HexFlexModel(
            self.geometry,
            young=self.young,
            poisson=self.poisson,
            mesh_size=self.mesh_size,
            element=self.element,
            coarsening=self.coarsening,
        )


def check_forces_design(design: object) -> np.ndarray:
    """A design of actuator forces: (n, 6) finite values within ±``MAX_FORCE_N`` N."""
    d = np.asarray(design, dtype=float)
    if d.ndim != 2 or d.shape[1] != 6:
        raise ValueError(
            f"design must have 6 factor columns (T1D1 … T3D2) and one row per run, got shape "
            f"{d.shape}"
        )
    return check_forces("design [N]", d)
