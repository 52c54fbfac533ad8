"""What the non-linear solver (:mod:`mechlib.fe.nonlinear`) needs of a linear FE model.

The HexFlex's model (:class:`mechlib.hexflex.fe.model.HexFlexModel`), a compliant layout's
(:class:`mechlib.compliant.model.MechanismModel`) and the cantilever benchmark's
(:class:`mechlib.hexflex.studies.cantilever.Cantilever`) provide it; the solver, its tangent and
its SfePy reference term are written against this protocol alone, so that they import no
mechanism.
"""

from __future__ import annotations

from typing import Any, Protocol

import numpy as np


class SolidModel(Protocol):
    """A factorised linear Q2 model of one solid: its SfePy problem, material and loads.

    Attributes
    ----------
    fe : Any
        The SfePy problem and its mesh data: ``pb`` (the problem), ``field``, ``omega`` (the
        whole body's region), ``v`` and ``u`` (the variables), ``coors`` (vertex coordinates,
        mm), ``eq`` (each field DOF's equation, −1 where constrained) and ``n_comp``.
    element : str
        ``"q2"`` (the non-linear solve takes the solid element only).
    young, poisson : float
        The material [MPa, –].
    body_factor : float
        Stiffening of the moving body's parts (1: none).
    n_dofs : int
        Free degrees of freedom.
    """

    fe: Any
    element: str
    young: float
    poisson: float
    body_factor: float
    n_dofs: int

    def load_vectors(self) -> np.ndarray:
        """The unit load vectors, (n_dofs, n_loads)."""

    def check_forces(self, forces: object) -> np.ndarray:
        """A load vector of the model's ports, checked (finite, within its bounds)."""

    def back_substitute(self, rhs: np.ndarray) -> np.ndarray:
        """Solutions of the linear stiffness for right-hand sides ``rhs``."""

    def pose_of(self, u: np.ndarray) -> np.ndarray:
        """The stage's pose from free-DOF displacements ``u``."""
