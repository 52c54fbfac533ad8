"""The factorised linear FE model of a mechanism: assemble and factorise once, solve many cases.

:class:`MechanismModel` answers what the HexFlex's model answers, for any :class:`Layout`: load
vectors of unit loads at its ports, reduced displacements by back-substitution, the stage pose
[µm, µrad] about the origin, and the compliance (pose per unit load, 6 × k). It offers the
interface that :class:`mechlib.fe.nonlinear.NonlinearSolver` and the finite-rotation
pose read (``fe``, ``young``, ``poisson``, ``element``, ``body_factor``, ``load_vectors``,
``back_substitute``, ``pose_of``, ``stage_motion``, ``check_forces``), so the same
total-Lagrangian Saint Venant–Kirchhoff solve runs on it. A layout with material regions is
solved by :class:`mechlib.compliant.solver.MechanismSolver`; the HexFlex's own solver refuses
it (its ``body_factor``, the ratio of its moduli, is then not 1).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from mechlib.compliant.layout import Layout, check_load_design
from mechlib.compliant.planform import Planform, mesh_planform
from mechlib.compliant.problem import MechanismProblem, build
from mechlib.fe.linear import FactorisedModel
from mechlib.fe.sfepy_base import assemble_stiffness
from mechlib.params import check_int


@dataclass
class MechanismModel(FactorisedModel):
    """A linear FE model of one :class:`Layout`, with its factorised stiffness.

    Parameters
    ----------
    layout : Layout
    mesh_size : float
        Element size of the planform's quads [mm], > 0 (a part's own size in
        ``layout.mesh_sizes`` takes precedence).
    layers : int
        Q2 hexahedra through the extrusion, 1–64.
    """

    layout: Layout
    mesh_size: float
    layers: int = 1
    element: str = field(default="q2", init=False)
    timings: dict[str, float] = field(default_factory=dict, init=False)

    def __post_init__(self) -> None:
        self.layers = check_int("layers", self.layers, low=1, high=64)
        t0 = time.perf_counter()
        self.planform: Planform = mesh_planform(self.layout, self.mesh_size)
        t1 = time.perf_counter()
        self.fe: MechanismProblem = build(self.layout, self.planform, self.layers)
        t2 = time.perf_counter()
        self.set_stiffness(assemble_stiffness(self.fe.pb, self.n_dofs))
        t3 = time.perf_counter()
        self.timings.update(mesh=t1 - t0, setup=t2 - t1, factorisation=t3 - t2)

    @property
    def young(self) -> float:
        """Young's modulus [MPa] of the layout's base material."""
        return float(self.layout.young)

    @property
    def poisson(self) -> float:
        """Poisson's ratio of the layout."""
        return float(self.layout.poisson)

    @property
    def body_factor(self) -> float:
        """Largest over smallest Young's modulus of the parts: 1 for one material."""
        moduli = [self.layout.young_of(n) for n in self.layout.names]
        return max(moduli) / min(moduli)

    @property
    def n_loads(self) -> int:
        """Number of load ports."""
        return len(self.layout.loads)

    def check_forces(self, forces: object) -> np.ndarray:
        """Loads as an (n, k) array in the ports' units, each within its port's bound."""
        return check_load_design(self.layout, forces)

    def stage_motion(self, reduced: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The stage's vertices (m, 3) [mm] and their displacements (m, 3) [mm]."""
        points = self.fe.coors[self.fe.stage_vertices]
        return points, np.asarray(reduced)[self.fe.stage_idx].reshape(-1, 3)

    def deformed_planform(self, forces: object, scale: float = 1.0) -> np.ndarray:
        """Mid-plane node positions (n_nodes, 2) [mm] of the planform under one load vector,
        displacements times ``scale`` (linear)."""
        red = self.solve_reduced(forces)[:, 0]
        full = self.fe.pb.get_variables().make_full_vec(red).reshape(-1, 3)
        n = len(self.planform.nodes)
        disp = np.mean([full[k * n : (k + 1) * n, :2] for k in range(self.layers + 1)], axis=0)
        return self.planform.nodes + scale * disp
