"""Geometrically non-linear HexFlex: total-Lagrangian Saint Venant–Kirchhoff, Newton with steps.

The material is the linear model's own elasticity tensor between Green–Lagrange strain and second
Piola–Kirchhoff stress — large displacements and rotations with a linear-elastic material, which
is what a "geometrically non-linear" analysis of a metal flexure means. The actuator loads are
dead loads (fixed direction) on the tabs' external edges, as in the linear model. Newton's
method runs over equal load steps; the first iteration from the undeformed state reuses the
linear factorisation (the tangent at u = 0 *is* the linear stiffness). Q2 solid only.

SfePy 2026.3's ``dw_tl_he_svk`` term doubles the shear *rows* of its tangent modulus, so its
tangent is not the derivative of its residual (Newton then converges only linearly, at rate ½).
:func:`register_svk_term` adds ``dw_tl_he_svk_consistent``, the same residual with the consistent
tangent; ``tests/test_hexflex.py`` checks it against finite differences of the residual.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from mechlib.hexflex import problem as fe
from mechlib.params import check_float, check_int

if TYPE_CHECKING:
    from mechlib.hexflex.model import HexFlexModel

#: Newton stopping rule: ‖residual‖ ≤ NEWTON_TOL · ‖external load‖. The round-off floor of the
#: TL residual on these meshes is ≈ 3e-8 (measured), so tighter values cannot be met.
NEWTON_TOL = 1e-6
#: ... or when a Newton correction is below this fraction of the displacement (small loads, where
#: the residual's round-off floor, relative to the load, rises above NEWTON_TOL).
INCREMENT_TOL = 1e-10


def tl_evaluator(model: HexFlexModel, term: str):
    """SfePy evaluator (residual, tangent) of one total-Lagrangian term taking the linear
    model's elasticity tensor, ``term(s.D, v, u)``, on the model's field and clamp.

    Parameters
    ----------
    model : HexFlexModel
        A Q2 model.
    term : str
        SfePy term name, e.g. ``"dw_tl_he_svk"`` (the stock term) or the consistent one.
    """
    from sfepy.discrete import Equation, Equations, Material, Problem
    from sfepy.mechanics.matcoefs import stiffness_from_youngpoisson
    from sfepy.terms import Term

    if model.element != "q2":
        raise ValueError(f"element must be 'q2' for a TL term, got {model.element!r}")
    p = model.fe
    mat = Material("s", D=stiffness_from_youngpoisson(3, model.young, model.poisson))
    t = Term.new(f"{term}(s.D, v, u)", fe.integral(), p.omega, s=mat, v=p.v, u=p.u)
    pb = Problem("hexflex_tl", equations=Equations([Equation("balance", t)]))
    pb.set_bcs(ebcs=p.pb.ebcs)
    pb.time_update(create_matrix=True)
    pb.get_variables().init_state()
    pb.update_materials()
    return pb.get_evaluator()


class NonlinearSolver:
    """Newton solver of the TL Saint Venant–Kirchhoff HexFlex for one linear model."""

    def __init__(self, model: HexFlexModel) -> None:
        if model.element != "q2":
            raise ValueError(
                f"element must be 'q2' for the non-linear solve (SfePy's shell10x is linear), "
                f"got {model.element!r}"
            )
        self.model = model
        self.evaluator = tl_evaluator(model, register_svk_term())

    def solve(
        self,
        forces: object,
        steps: int = 1,
        tol: float = NEWTON_TOL,
        max_iterations: int = 25,
    ) -> tuple[np.ndarray, list[int]]:
        """Geometrically non-linear equilibrium under one actuator force vector (6,) [N].

        Parameters
        ----------
        forces : array_like (6,)
            Dead loads on the six ports [N], within the model's force bound.
        steps : int
            Equal load increments (1–100); Newton restarts from the previous step's solution.
        tol : float
            Relative residual at which Newton stops, in [1e-7, 1e-2].
        max_iterations : int
            Newton iterations allowed per step (1–100).

        Returns
        -------
        u : ndarray (n_dofs,)
            Reduced displacement vector [mm].
        iterations : list of int
            Newton iterations used in each load step.

        Raises
        ------
        RuntimeError
            If Newton does not converge (naming the force vector, the step and the last
            residual) or an element inverts.
        """
        model = self.model
        f = model.check_forces(forces)
        if f.shape[0] != 1:
            raise ValueError(f"forces must be one vector of 6 forces, got shape {f.shape}")
        steps = check_int("steps", steps, low=1, high=100)
        tol = check_float("tol", tol, low=1e-7, high=1e-2)
        max_iterations = check_int("max_iterations", max_iterations, low=1, high=100)
        from mechlib.hexflex.model import factorise

        ev = self.evaluator
        load = model.load_vectors() @ f[0]
        scale = np.linalg.norm(load)
        u = np.zeros(model.n_dofs)
        used: list[int] = []
        if scale == 0.0:
            return u, used
        for k in range(1, steps + 1):
            target = load * (k / steps)
            for it in range(max_iterations + 1):
                try:
                    res = ev.eval_residual(u).copy() - target
                except ValueError as err:  # SfePy's "warp violation": inverted elements
                    raise RuntimeError(
                        f"non-linear solve failed at load step {k}/{steps} for forces "
                        f"{f[0].tolist()} N ({err}); use more steps"
                    ) from err
                if np.linalg.norm(res) <= tol * scale:
                    used.append(it)
                    break
                if it == max_iterations:
                    raise RuntimeError(
                        f"Newton did not converge in max_iterations = {max_iterations} at load "
                        f"step {k}/{steps} for forces {f[0].tolist()} N (relative residual "
                        f"{np.linalg.norm(res) / scale:.2e} > tol = {tol:g}); use more steps"
                    )
                if not u.any():
                    du = model.back_substitute(res)
                else:
                    du = factorise(ev.eval_tangent_matrix(u).copy()).solve(res)
                u = u - du
                if np.linalg.norm(du) <= INCREMENT_TOL * np.linalg.norm(u):
                    used.append(it + 1)  # at the round-off floor of the residual
                    break
        return u, used


def register_svk_term() -> str:
    """Register (once) and name SfePy's TL Saint Venant–Kirchhoff term with a consistent tangent.

    The stress is SfePy's own (``S = D : E`` with the Voigt-shear convention of its Green strain).
    SfePy's element tangent already accounts for that convention, so the tangent modulus is ``D``
    itself; the stock term doubles its shear rows again (see the module docstring).
    """
    from sfepy.terms import term_table
    from sfepy.terms.terms_hyperelastic_tl import SaintVenantKirchhoffTLTerm

    name = "dw_tl_he_svk_consistent"
    if name not in term_table:

        class ConsistentSVKTerm(SaintVenantKirchhoffTLTerm):
            def tan_mod_function(self, out, mat, *fargs, **kwargs):
                out[:] = mat
                return out

        ConsistentSVKTerm.name = name
        term_table[name] = ConsistentSVKTerm
    return name
