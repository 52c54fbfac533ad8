"""Geometrically non-linear solid (the HexFlex, a compliant layout): total-Lagrangian Saint
Venant–Kirchhoff, Newton with steps.

The material is the linear model's own elasticity tensor between Green–Lagrange strain and second
Piola–Kirchhoff stress — large displacements and rotations with a linear-elastic material, which
is what a "geometrically non-linear" analysis of a metal flexure means. The actuator loads are
dead loads (fixed direction) on the model's load faces, as in the linear model. The solve runs
over equal load steps; the first correction from the undeformed state reuses the linear
factorisation (the tangent at u = 0 *is* the linear stiffness). By default it is a modified Newton
method: a factorised tangent is kept while its (Anderson-accelerated) corrections converge fast
enough, and refactorised when they slow down — 3 factorisations per validation run on the
identified model instead of Newton's 5–6, for the same equilibrium (``make bench``). The tangent
and the residual are computed by :mod:`mechlib.fe.svk_tangent` (the same numbers as SfePy's
term, batched), and a tangent is factorised by CHOLMOD's Cholesky with the pattern's analysis
done once (:mod:`mechlib.fe.factor`). Q2 solid only.

``tangent="sfepy"`` assembles SfePy's TL term instead (its consistent variant, from
:mod:`mechlib.fe.sfepy_tl`): the reference the batched tangent is tested and benchmarked
against.
"""

from __future__ import annotations

import functools
import threading
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp

from mechlib.fe.anderson import Anderson
from mechlib.fe.factor import SOLVERS, PatternCholesky, factorise
from mechlib.fe.sfepy_base import QUAD_ORDER
from mechlib.fe.sfepy_tl import register_svk_term, tl_evaluator
from mechlib.fe.svk_tangent import SVKTangent
from mechlib.params import check_choice, check_float, check_int

if TYPE_CHECKING:
    from mechlib.fe.protocol import SolidModel

#: Newton stopping rule: ‖residual‖ ≤ NEWTON_TOL · ‖external load‖. The round-off floor of the
#: TL residual on these meshes is ≈ 3e-9 (measured), so tighter values cannot be met.
NEWTON_TOL = 1e-6
#: ... or when a correction is below this fraction of the displacement (small loads, where the
#: residual's round-off floor, relative to the load, rises above NEWTON_TOL).
INCREMENT_TOL = 1e-10
#: Modified Newton keeps the factorised tangent while the corrections it gives, accelerated by
#: Anderson mixing over the last ``ANDERSON_DEPTH`` of them, are predicted (from the last rate)
#: to reach the tolerance within ``MAX_CHORD_STEPS`` more: one correction costs a residual and a
#: back-substitution, a new tangent its assembly and Cholesky, about six corrections' worth on
#: the identified model (``make bench``). 4 and 8 were measured equally fast there.
MAX_CHORD_STEPS = 8
ANDERSON_DEPTH = 5
#: The modified method gives a load step up after this many factorisations, and the step is
#: solved again from its start by Newton (``SolveStats.restarts``). The identified model's
#: validation runs took 2–4 (16 traced); a 3 N linear-range sweep case was measured cycling
#: through more than 20 without converging, where Newton converges with 5–7 a step.
MODIFIED_MAX_FACTORISATIONS = 8
METHODS: tuple[str, ...] = ("modified", "newton")
TANGENTS: tuple[str, ...] = ("batched", "sfepy")


class ConvergenceError(RuntimeError):
    """A non-linear solve that did not converge; ``forces`` [N] and ``residual`` (the last
    relative residual reached, before the correction that inverted an element if one did;
    ``nan`` if the load step's starting point already inverts one) say which run and how far
    it got."""

    def __init__(self, message: str, forces: list[float], residual: float) -> None:
        super().__init__(message, forces, residual)  # args: picklable across processes
        self.forces, self.residual = forces, residual

    def __str__(self) -> str:
        return str(self.args[0])


@dataclass
class SolveStats:
    """What a non-linear solve spent, per load step, and where it stopped."""

    #: corrections (one back-substitution each) per load step
    iterations: list[int] = field(default_factory=list)
    #: tangent assemblies and factorisations per load step
    factorisations: list[int] = field(default_factory=list)
    #: final ‖residual‖ / ‖load‖
    residual: float = 0.0
    #: load steps the modified method gave up on, solved again by Newton (their corrections
    #: and factorisations above are Newton's)
    restarts: int = 0


class _GaveUp(Exception):
    """The modified method's factorisation budget for a load step is spent."""


class NonlinearSolver:
    """Newton solver of the TL Saint Venant–Kirchhoff solid for one linear model.

    Parameters
    ----------
    model : SolidModel
        A Q2 model with ``body_factor`` 1 (its factorised stiffness is the first tangent).
    tangent : {"batched", "sfepy"}
        How the tangent is assembled: :class:`mechlib.fe.svk_tangent.SVKTangent` (default;
        built here, ≈ 0.4 s a tangent on the identified model) or SfePy's term (≈ 4.3 s); the
        same matrix to round-off (``make bench`` compares them). The choice also sets the
        residual: ``SVKTangent.internal_force`` or SfePy's (equal to round-off).
    factorisation : {"cholmod", "superlu"}
        How a tangent is factorised: a supernodal Cholesky with the pattern's analysis done once
        (:class:`mechlib.fe.factor.PatternCholesky`, default; an indefinite tangent falls
        back to LU) or SuperLU's LU of every tangent (``make bench`` compares them).
    quad_order : int
        Quadrature order of the batched tangent and residual (:class:`SVKTangent`'s ``order``;
        the default is the linear model's); another order needs ``tangent="batched"``.
    """

    def __init__(
        self,
        model: SolidModel,
        tangent: str = "batched",
        factorisation: str = "cholmod",
        quad_order: int = QUAD_ORDER,
    ) -> None:
        if model.element != "q2":
            raise ValueError(
                f"element must be 'q2' for the non-linear solve (SfePy's shell10x is linear), "
                f"got {model.element!r}"
            )
        if model.body_factor != 1.0:
            raise ValueError(
                f"body_factor must be 1 for the non-linear solve (its TL term has one material), "
                f"got {model.body_factor:g}"
            )
        self.model = model
        self.tangent = check_choice("tangent", tangent, TANGENTS)
        if self.tangent != "batched" and quad_order != QUAD_ORDER:  # SfePy's term: the model's
            raise ValueError(
                f"quad_order must be {QUAD_ORDER} with tangent='sfepy', got {quad_order!r}"
            )
        #: the batched tangent and residual (``None`` with ``tangent="sfepy"``)
        self.batched = SVKTangent(model, order=quad_order) if self.tangent == "batched" else None
        self.factorisation = check_choice("factorisation", factorisation, SOLVERS)
        #: the Cholesky of the tangent's pattern (``None`` until a CHOLMOD factorisation is
        #: needed with SfePy's tangent, and always with SuperLU); its ``fallbacks`` count the
        #: tangents that were not positive definite
        self.cholesky: PatternCholesky | None = None
        self._lock = threading.Lock()
        if self.batched is not None and self.factorisation == "cholmod":
            # the pattern's analysis (ordering, supernodes) once, before any run (≈ 2 s)
            self.cholesky = PatternCholesky(self.batched.pattern())

    @functools.cached_property
    def evaluator(self):
        """SfePy's evaluator of the consistent TL term (built on first use: the default solver
        needs it only for comparisons)."""
        return tl_evaluator(self.model, register_svk_term())

    def residual(self, u: np.ndarray, target: np.ndarray) -> np.ndarray | None:
        """Residual [N] (internal force minus ``target``) at the reduced displacements ``u``
        [mm], or ``None`` where an element inverts (SfePy's "warp violation") or ``u`` is not
        finite."""
        if not np.all(np.isfinite(u)):
            return None
        if self.batched is not None:  # the same vector as SfePy's, batched (make bench)
            force = self.batched.internal_force(u)
            return None if force is None else force - target
        try:
            return self.evaluator.eval_residual(u).copy() - target
        except ValueError:
            return None

    def tangent_matrix(self, u: np.ndarray) -> sp.csr_array:
        """The tangent stiffness [N/mm] at ``u`` [mm] (CSR, sorted indices), by the solver's
        ``tangent`` choice."""
        if self.batched is not None:
            return self.batched.matrix(u)
        matrix = sp.csr_array(self.evaluator.eval_tangent_matrix(u), copy=True)
        matrix.sort_indices()
        return matrix

    def factorised_tangent(self, u: np.ndarray):
        """A function ``rhs -> K(u)⁻¹ rhs`` for the tangent at ``u`` [mm], factorised as the
        solver's ``factorisation`` says (at ``u = 0`` the linear model's own factorisation).

        With CHOLMOD the factor is kept in one object: a later call invalidates the function
        returned before (it then raises ``RuntimeError``).
        """
        same_rule = self.batched is None or self.batched.order == QUAD_ORDER
        if not u.any() and same_rule:  # at u = 0: the linear stiffness, already factorised
            return self.model.back_substitute
        if self.batched is not None and self.cholesky is not None:  # the default
            return self.cholesky.factorise_upper(self.batched.upper_values(u))
        matrix = self.tangent_matrix(u)
        if self.factorisation == "superlu":
            return factorise(matrix).solve
        if self.cholesky is None:
            self.cholesky = PatternCholesky(matrix)
        return self.cholesky.factorise(matrix)

    def solve(
        self,
        forces: object,
        steps: int = 1,
        tol: float = NEWTON_TOL,
        max_iterations: int = 40,
        method: str = "modified",
    ) -> tuple[np.ndarray, SolveStats]:
        """Geometrically non-linear equilibrium under one actuator force vector (6,) [N].

        Parameters
        ----------
        forces : array_like (6,)
            Dead loads on the six ports [N], within the model's force bound.
        steps : int
            Equal load increments (1–100); each starts from the previous step's solution.
        tol : float
            Relative residual at which the iteration stops, in [1e-7, 1e-2].
        max_iterations : int
            Corrections (back-substitutions, kept or discarded) allowed per load step (1–100),
            and again for a Newton restart; the validation runs of the identified model take
            10–14 with the modified method.
        method : {"modified", "newton"}
            ``"newton"``: assemble and factorise the tangent at every iteration. ``"modified"``
            (default): keep the last factorised tangent while its Anderson-mixed corrections,
            at the rate of the last one, would reach ``tol`` within ``MAX_CHORD_STEPS`` more; a
            correction that raised the residual is discarded, and the tangent is refactorised
            at the current point. Both converge to the same equilibrium (the residual is the
            same); the modified method factorises about half as often. A load step that the
            modified method has not solved within ``MODIFIED_MAX_FACTORISATIONS``
            factorisations (or within ``max_iterations``) is solved again from its start by
            Newton, counted in ``stats.restarts``.

        Returns
        -------
        u : ndarray (n_dofs,)
            Reduced displacement vector [mm].
        stats : SolveStats
            Corrections and factorisations per load step, final relative residual.

        Raises
        ------
        ConvergenceError
            If the iteration does not converge within ``max_iterations`` or an element inverts
            under a fresh Newton correction; names the force vector, the load step and the last
            relative residual.
        """
        with self._lock:  # one solve at a time: the tangent buffers and the factor are shared
            return self._solve(forces, steps, tol, max_iterations, method)

    def pose(
        self, forces: object, steps: int = 1, method: str = "modified"
    ) -> tuple[np.ndarray, SolveStats]:
        """Stage pose (6,) [µm, µrad] of the non-linear equilibrium under ``forces`` (6,) [N]
        and what the solve spent (see :meth:`solve`)."""
        u, stats = self.solve(forces, steps=steps, method=method)
        return self.model.pose_of(u), stats

    def _solve(
        self, forces: object, steps: int, tol: float, max_iterations: int, method: str
    ) -> tuple[np.ndarray, SolveStats]:
        model = self.model
        f = model.check_forces(forces)
        if f.shape[0] != 1:
            raise ValueError(f"forces must be one vector of 6 forces, got shape {f.shape}")
        steps = check_int("steps", steps, low=1, high=100)
        tol = check_float("tol", tol, low=1e-7, high=1e-2)
        max_iterations = check_int("max_iterations", max_iterations, low=1, high=100)
        method = check_choice("method", method, METHODS)
        load = model.load_vectors() @ f[0]
        scale = np.linalg.norm(load)
        u = np.zeros(model.n_dofs)
        stats = SolveStats()
        if scale == 0.0:
            return u, stats
        forces_list = f[0].tolist()
        for k in range(1, steps + 1):
            target = load * (k / steps)
            where = (k, steps, forces_list, scale, tol, max_iterations)
            try:
                u_step, norm, used, facts = self._load_step(u, target, method, where)
            except (ConvergenceError, _GaveUp):
                if method == "newton":
                    raise
                # the chord went astray (far from equilibrium, an old tangent can lead where
                # Newton's corrections explode): this load step again, from its start, by Newton
                stats.restarts += 1
                u_step, norm, used, facts = self._load_step(u, target, "newton", where)
            u = u_step
            stats.iterations.append(used)
            stats.factorisations.append(facts)
        stats.residual = float(norm / scale)
        return u, stats

    def _load_step(
        self, u: np.ndarray, target: np.ndarray, method: str, where: tuple
    ) -> tuple[np.ndarray, float, int, int]:
        """Equilibrium under ``target`` from ``u``: (u, ‖residual‖, corrections, factorisations).
        ``where`` = (load step, steps, forces: naming the run in errors; ‖load‖, tol,
        max_iterations of :meth:`solve`). The modified method gives up (``_GaveUp``) rather than
        factorise more than ``MODIFIED_MAX_FACTORISATIONS`` tangents."""
        k, steps, forces_list, scale, tol, max_iterations = where
        res = self.residual(u, target)
        if res is None:
            raise ConvergenceError(
                f"an element inverted at the start of load step {k}/{steps} for forces "
                f"{forces_list} N; use more steps",
                forces_list,
                float("nan"),
            )
        norm = float(np.linalg.norm(res))
        solve, fresh, used, facts = None, False, 0, 0
        mixer = Anderson(ANDERSON_DEPTH if method == "modified" else 0)
        while norm > tol * scale:
            if used == max_iterations:
                raise ConvergenceError(
                    f"the non-linear solve did not converge in max_iterations = "
                    f"{max_iterations} at load step {k}/{steps} for forces {forces_list} N "
                    f"(relative residual {norm / scale:.2e} > tol = {tol:g}); use more steps",
                    forces_list,
                    norm / scale,
                )
            if solve is None or method == "newton":
                if method == "modified" and facts == MODIFIED_MAX_FACTORISATIONS:
                    raise _GaveUp
                linear = not u.any()  # the linear stiffness: no good beyond one step
                solve, fresh = self.factorised_tangent(u), True
                facts += int(not linear)
                mixer.reset()
            step = mixer.step(u, -solve(res))
            trial = u + step
            new = self.residual(trial, target)
            new_norm = np.inf if new is None else float(np.linalg.norm(new))
            if not np.isfinite(new_norm):  # inverted elements, or an overflow to inf/NaN
                new, new_norm = None, np.inf
            if new is None and fresh:
                raise ConvergenceError(
                    f"an element inverted in a Newton correction at load step {k}/{steps} "
                    f"for forces {forces_list} N (relative residual before it "
                    f"{norm / scale:.2e}); use more steps",
                    forces_list,
                    norm / scale,
                )
            used += 1
            rate = new_norm / norm
            if rate < 1.0 or fresh:  # keep it (a Newton correction is always kept)
                small = np.linalg.norm(step) <= INCREMENT_TOL * np.linalg.norm(trial)
                u, res, norm = trial, new, new_norm
                if small:
                    break  # at the round-off floor of the residual
                slow = rate >= 1.0 or (
                    norm > tol * scale
                    and np.log(tol * scale / norm) / np.log(rate) > MAX_CHORD_STEPS
                )
            else:
                slow = True
            if linear or (slow and not fresh):
                solve = None  # refactorise at the current point
            fresh = False
        return u, norm, used, facts
