"""The factorised linear FE model every mechanism's model extends: assemble once, factorise once,
answer load cases by back-substitution.

:class:`FactorisedStiffness` holds a reduced stiffness matrix and its factorisation (what the
non-linear solver, :class:`mechlib.fe.nonlinear.NonlinearSolver`, reads of any model: the
cantilever benchmark of :mod:`mechlib.hexflex.studies.cantilever` extends it);
:class:`FactorisedModel` adds a rigid stage's pose — the load vectors of unit loads at a model's
ports, the stage pose of a displacement field [µm, µrad] and the compliance (pose per unit load,
6 × k), which the HexFlex's :class:`mechlib.hexflex.fe.model.HexFlexModel` and a compliant
layout's :class:`mechlib.compliant.model.MechanismModel` extend. A subclass builds its SfePy
problem, hands its stiffness to :meth:`FactorisedStiffness.set_stiffness`, and says which loads it
accepts (``check_forces``).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechlib.blas import one_thread
from mechlib.fe.factor import factorise


class FactorisedStiffness:
    """A reduced stiffness matrix (free DOFs) and its sparse LU factorisation.

    A subclass calls :meth:`set_stiffness` once its matrix is assembled; the factorisation is
    made then (``factorise_now``) or by the first :meth:`back_substitute`.
    """

    _matrix: Any = None
    _lu: Any = None

    def set_stiffness(self, matrix: Any, *, factorise_now: bool = True) -> None:
        """Keep ``matrix`` (SciPy sparse, free DOFs) [N/mm] as the model's stiffness and, with
        ``factorise_now``, factorise it (SuperLU, :func:`mechlib.fe.factor.factorise`)."""
        self._matrix, self._lu = matrix, None
        if factorise_now:
            self._lu = factorise(matrix)

    def assembled_stiffness(self) -> Any:
        """The reduced stiffness matrix (free DOFs, SciPy sparse) [N/mm]."""
        return self._matrix

    def back_substitute(self, rhs: np.ndarray) -> np.ndarray:
        """Solve ``K x = rhs`` with the stored factorisation (rhs (n_dofs,) or (n_dofs, n)).

        BLAS runs on one thread here: SuperLU's multi-right-hand-side solve goes through BLAS,
        whose multi-threaded kernels change the last bits with the thread count, and a worker
        process (one thread) must return the same numbers as the main process.
        """
        if self._lu is None:
            self._lu = factorise(self._matrix)
        with one_thread():
            return self._lu.solve(np.ascontiguousarray(rhs))


class FactorisedModel(FactorisedStiffness):
    """A factorised linear model with a rigid stage whose pose it fits.

    A subclass sets ``fe``, its SfePy problem's pieces: ``n_dofs`` (free DOFs), ``loads``
    (reduced load vectors of unit loads at the ports, (n_dofs, k)), ``fit`` (the least-squares
    pose of the stage nodes' displacements, (6, 3 m)) and ``stage_idx`` (those nodes' reduced
    DOFs); and defines ``check_forces`` (loads as an (n, k) array, each within its bound).
    """

    fe: Any
    _compliance: np.ndarray | None = None

    def check_forces(self, forces: object) -> np.ndarray:  # pragma: no cover - abstract
        """Loads as an (n, k) array in the ports' units, each within its port's bound."""
        raise NotImplementedError

    @property
    def n_dofs(self) -> int:
        """Number of free degrees of freedom (after clamping the ground)."""
        return self.fe.n_dofs

    @property
    def n_loads(self) -> int:
        """Number of load ports (k)."""
        return self.fe.loads.shape[1]

    def load_vectors(self) -> np.ndarray:
        """Reduced load vectors (n_dofs, k) of unit loads at the ports."""
        return self.fe.loads

    def solve_reduced(self, forces: object) -> np.ndarray:
        """Reduced displacement vectors (n_dofs, n) for loads (n, k)."""
        return self.back_substitute(self.fe.loads @ self.check_forces(forces).T)

    def pose_of(self, reduced: np.ndarray) -> np.ndarray:
        """Stage pose(s) [µm, µrad] of reduced displacement vector(s): (6,) or (6, n)."""
        with one_thread():  # see back_substitute
            return self.fe.fit @ reduced[self.fe.stage_idx]

    def compliance(self) -> np.ndarray:
        """Pose per unit load (6, k): rows x y z θx θy θz [µm, µrad], columns the ports."""
        if self._compliance is None:
            self._compliance = self.pose_of(self.solve_reduced(np.eye(self.n_loads)))
        return self._compliance.copy()

    def poses(self, forces: object) -> np.ndarray:
        """Stage poses (n, 6) [µm, µrad] of loads (n, k): ``forces @ C.T`` with the
        :meth:`compliance` C (the pose is linear in the loads, so k back-substitutions serve any
        number of load cases)."""
        return self.check_forces(forces) @ self.compliance().T
