"""The geometrically non-linear solve of a mechanism with material regions.

:class:`MechanismSolver` is the HexFlex's total-Lagrangian Saint Venant–Kirchhoff solver
(:class:`mechlib.fe.nonlinear.NonlinearSolver`, batched tangent, Newton or modified
Newton) on a :class:`~mechlib.compliant.model.MechanismModel`, with each element's quadrature
weights multiplied by its part's Young's modulus over the base one. With one Poisson's ratio
that is exact: Lamé's λ and μ are both proportional to E, so an element's internal force and
tangent are too. The first tangent is the linear model's factorised stiffness, which has the
same regions.
"""

from __future__ import annotations

import numpy as np

from mechlib.compliant.model import MechanismModel
from mechlib.fe.nonlinear import NonlinearSolver
from mechlib.fe.sfepy_base import QUAD_ORDER


class _OneModulus:
    """A view of a model whose regions the solver handles itself (see :class:`MechanismSolver`)."""

    body_factor = 1.0

    def __init__(self, model: MechanismModel) -> None:
        self._model = model

    def __getattr__(self, name: str):
        return getattr(self._model, name)


class MechanismSolver(NonlinearSolver):
    """Non-linear solver of a :class:`MechanismModel`, material regions included.

    Parameters
    ----------
    model : MechanismModel
    quad_order : int
        Quadrature order of the batched tangent and residual.
    """

    def __init__(self, model: MechanismModel, quad_order: int = QUAD_ORDER) -> None:
        super().__init__(_OneModulus(model), tangent="batched", quad_order=quad_order)
        self.model = model
        layout = model.layout
        moduli = np.array([layout.young_of(n) for n in layout.names]) / layout.young
        factors = moduli[model.fe.cell_parts]
        groups = model.fe.pb.domain.mesh.cmesh.cell_groups
        if len(factors) != self.batched.weights.shape[0] or not np.array_equal(
            groups, 1 + model.fe.cell_parts
        ):
            raise RuntimeError("the mesh's cells and the tangent's elements differ")
        self.batched.scale_weights(factors)

    @property
    def evaluator(self):
        """Not available: SfePy's TL term has one material (the batched tangent is used)."""
        raise ValueError("tangent must be 'batched' for a mechanism with material regions")
