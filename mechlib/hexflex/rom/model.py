"""A physics-based, hyper-reduced reduced-order model (ROM) of the geometrically non-linear HexFlex.

**Basis** (:mod:`mechlib.hexflex.rom.basis`). The six static modes ``φ_j = K₀⁻¹ L e_j`` (the
linear responses to unit actuator forces) and their 21 static modal derivatives
``θ_ij = −K₀⁻¹ 2 N₂(φ_i, φ_j)`` (Idelsohn & Cardona 1985; Jain & Tiso 2017), with ``N₂`` the
quadratic part of the Saint Venant–Kirchhoff (SVK) internal force ``f``, which is an exact cubic:
``N₂(x, x) = (f(x) + f(−x)) / 2`` and, by polarisation,
``N₂(a, b) = (N₂(a+b) − N₂(a) − N₂(b)) / 2``. Optional additions: a POD of converged full
non-linear solutions given by the caller (``snapshots``, ``n_pod``), and a POD of third-order
corrections of the second-order responses at the training forces (``n_third``; no full solve),
each of the part outside the vectors already in the basis, in the energy inner product
``xᵀ K₀ y`` or the Euclidean one (``pod_inner``). ``modal_derivatives=False`` keeps the
derivatives out of the basis. The basis is orthonormalised (Euclidean).

**Hyper-reduction** (:mod:`mechlib.hexflex.rom.ecsw`). Energy-conserving sampling and weighting
(ECSW; Farhat, Avery, Chapman & Cortial 2014; Farhat, Chapman & Avery 2015): a sparse set of
weighted elements whose summed projected forces reproduce the quadratic and cubic parts of the
non-linear reduced force, separately, at training states — the second-order responses at
``n_training`` seeded forces in ``±force_range`` and the snapshots' projections — to the
relative error ``ecsw_tol`` with at most ``max_elements`` elements.
``hyper_reduction=False`` sums every element instead (exact Galerkin; small meshes only).

**Reduced force** (:mod:`mechlib.hexflex.rom.tensors`). On the weighted elements the SVK reduced
internal force is an exact polynomial in the reduced coordinates ``q``: the exact reduced linear
stiffness ``Vᵀ K₀ V`` plus cubic and quartic energy tensors, so evaluating it costs the same
whatever the number of elements.

**Equilibrium.** Galerkin projection ``Vᵀ(f(Vq) − L F) = 0``, solved by Newton in ``q`` on all
force vectors at once, from a cubic polynomial in the forces fitted to the ROM's own equilibria
at ``N_PREDICT`` seeded forces; a force vector that does not converge is solved again over
``CONTINUATION`` load steps. Poses are ``P q``, ``P`` the model's (linear) pose fit applied to
the basis, so the ROM's poses are fitted as the FE model's.

Design decisions (``make bench`` measures speed and accuracy): modes and derivatives alone miss
the response by percents of the ranges — the basis, not the sampling — so full solutions join by
POD; third-order vectors instead of them, dropping the derivatives, or one POD of both did worse.
Looser ECSW tolerances (1e-3–1e-4) were rejected, probably because in the derivative coordinates
the non-linear force nearly cancels the linear one, amplifying its error. Evaluating the sampled
elements online (an estimated hundred times the polynomial's flops) was not built.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from mechlib.blas import one_thread
from mechlib.hexflex.rom import basis as rb
from mechlib.hexflex.rom import ecsw
from mechlib.hexflex.rom.tensors import PolynomialForce, polynomial_force
from mechlib.params import check_choice, check_float, check_int, check_matrix

if TYPE_CHECKING:
    from mechlib.fe.nonlinear import NonlinearSolver

#: Reduced Newton stops at ‖Vᵀ(f − L F)‖ ≤ TOL ‖Vᵀ L F‖ (the polynomial is exact: round-off).
TOL = 1e-10
#: Newton iterations allowed per solve (the identified model's ROM takes 4–5).
MAX_ITERATIONS = 30
#: ... or when a Newton correction is below this fraction of the coordinates (see ``_newton``).
STEP_TOL = 1e-6
#: Load steps tried, in turn, for the force vectors whose Newton iteration did not converge.
CONTINUATION = (4, 16)
POD_INNER: tuple[str, ...] = ("energy", "euclidean")
#: Default ECSW tolerance (relative error of the fitted non-linear reduced force per state).
ECSW_TOL = 1e-6
#: Default training forces for the ECSW fit (seeded, uniform in ±force_range).
N_TRAINING = 24
#: ROM solves the Newton predictor is fitted to (cubic in the forces: 83 coefficients; degree 4
#: took as many iterations, degree 2 4.6 a pose on the identified model).
N_PREDICT = 600


@dataclass
class ReducedOrderModel:
    """A Galerkin ROM of one non-linear HexFlex model (build with :meth:`build`).

    Attributes
    ----------
    basis : ndarray (n_dofs, n_basis)
        Orthonormal reduced basis.
    force : PolynomialForce
        The reduced internal force (exact polynomial of the weighted elements).
    loads : ndarray (n_basis, 6)
        ``Vᵀ L``: reduced unit actuator loads.
    pose_map : ndarray (6, n_basis)
        Stage pose [µm, µrad] per reduced coordinate.
    predictor : ndarray (83, n_basis)
        Newton's start: coefficients of the force monomials of degree 1 to 3
        (:func:`mechlib.hexflex.rom.basis.monomials`), a least-squares fit of the ROM's own
        equilibria at ``N_PREDICT`` seeded forces (started from the second-order response).
    cells, weights : ndarray
        The elements summed and their weights.
    force_range : float
        Largest |actuator force| accepted [N].
    info : dict
        Build timings [s], ECSW fit error, sizes.
    """

    basis: np.ndarray
    force: PolynomialForce
    loads: np.ndarray
    pose_map: np.ndarray
    predictor: np.ndarray
    cells: np.ndarray
    weights: np.ndarray
    force_range: float
    info: dict[str, float] = field(default_factory=dict)

    @property
    def n_basis(self) -> int:
        """Number of basis vectors."""
        return self.basis.shape[1]

    @property
    def n_elements(self) -> int:
        """Number of elements the reduced force sums."""
        return len(self.cells)

    @classmethod
    def build(
        cls,
        solver: NonlinearSolver,
        snapshots: np.ndarray | None = None,
        *,
        n_pod: int | None = None,
        hyper_reduction: bool = True,
        ecsw_tol: float = ECSW_TOL,
        max_elements: int = 1000,
        force_range: float = 1.0,
        n_training: int = N_TRAINING,
        n_third: int = 0,
        modal_derivatives: bool = True,
        pod_inner: str = "energy",
    ) -> ReducedOrderModel:
        """Build the ROM of ``solver``'s model.

        Parameters
        ----------
        solver : NonlinearSolver
            The full solver (batched tangent): its model's stiffness, loads and pose fit.
        snapshots : ndarray (n_s, n_dofs), optional
            Converged full non-linear displacement fields [mm] to add by POD.
        n_pod : int, optional
            POD vectors kept from the snapshots, in [0, n_s]; default all that are independent.
        hyper_reduction : bool
            ECSW sample of elements (default) or all elements (exact Galerkin; its tensors cost
            ≈ n⁴ per quadrature point: small meshes only).
        ecsw_tol : float
            Relative error of the fitted non-linear reduced force per training state, (0, 1).
        max_elements : int
            Most elements ECSW may select, ≥ 1.
        force_range : float
            Largest |actuator force| [N] the ROM accepts, in (0, model bound]; the ECSW training
            forces are drawn in it.
        n_training : int
            ECSW training force vectors (seeded), in [1, 1000]; their second-order states, and
            the snapshots' projections, are fitted.
        n_third : int
            Third-order vectors added, in [0, n_training]: the POD of the corrections
            ``K₀⁻¹ r`` of the second-order responses ``Φ f + ½ θ(f, f)`` at the training forces
            (``r`` their full residual: one internal force and one back-substitution a force, no
            non-linear solve); 0 (default) adds none.
        modal_derivatives : bool
            Keep the 21 modal derivatives in the basis (default); without them the basis is
            the static modes and the POD vectors (the derivatives still give Newton's start and
            the ECSW training states).
        pod_inner : {"energy", "euclidean"}
            Inner product of the POD (snapshots and third-order vectors): the energy one
            ``xᵀ K₀ y`` (default) or the Euclidean one.

        Returns
        -------
        ReducedOrderModel
            With ``info``: build timings [s] (``basis_s``, ``contributions_s``, ``fit_s``,
            ``tensors_s``, ``build_s``) and the ECSW fit's largest relative error
            (``ecsw_error``).

        Raises
        ------
        ValueError, TypeError
            On a bad argument (named, with what is allowed).
        """
        from mechlib.hexflex.fe.model import MAX_FORCE_N

        if solver.batched is None:
            raise ValueError("solver must use the batched tangent (tangent='batched')")
        for name, flag in (
            ("hyper_reduction", hyper_reduction),
            ("modal_derivatives", modal_derivatives),
        ):
            if not isinstance(flag, bool):
                raise TypeError(f"{name} must be True or False, got {flag!r}")
        force_range = check_float("force_range [N]", force_range, low=0.0, high=MAX_FORCE_N)
        if force_range == 0.0:
            raise ValueError("force_range [N] must be > 0, got 0")
        n_training = check_int("n_training", n_training, low=1, high=1000)
        max_elements = check_int("max_elements", max_elements, low=1)
        n_third = check_int("n_third", n_third, low=0, high=n_training)
        pod_inner = check_choice("pod_inner", pod_inner, POD_INNER)
        ecsw_tol = check_float("ecsw_tol", ecsw_tol, low=0.0, high=1.0, low_open=True)
        model, tangent = solver.model, solver.batched
        if snapshots is not None:
            snapshots = check_matrix("snapshots", snapshots, shape=(None, model.n_dofs))
            n_pod = len(snapshots) if n_pod is None else n_pod
            n_pod = check_int("n_pod", n_pod, low=0, high=len(snapshots))
        elif n_pod is not None:
            raise ValueError(f"n_pod = {n_pod} needs snapshots (none given)")
        info: dict[str, float] = {}
        with one_thread():
            t0 = time.perf_counter()
            modes, derivatives = rb.static_basis(solver)
            parts = [rb.unit(modes)] + ([rb.unit(derivatives)] if modal_derivatives else [])
            training = rb.training_forces(force_range, n_training)
            energy = model.assembled_stiffness() if pod_inner == "energy" else None
            if n_third:
                corrections = rb.third_order(solver, modes, derivatives, training)
                parts.append(rb.pod(rb.orthonormal(np.hstack(parts)), corrections, n_third, energy))
            if snapshots is not None and n_pod:
                parts.append(rb.pod(rb.orthonormal(np.hstack(parts)), snapshots.T, n_pod, energy))
            basis = rb.orthonormal(np.hstack(parts))
            t1 = time.perf_counter()
            info["basis_s"] = t1 - t0
            stiffness = basis.T @ (model.assembled_stiffness() @ basis)
            # Newton's first start: the second-order response Φ f + ½ θ(f, f)
            predictor = np.zeros((rb.N_MONOMIALS, basis.shape[1]))
            predictor[:6] = (basis.T @ modes).T
            predictor[6:27] = ((basis.T @ derivatives) * rb.PRODUCT_FACTOR).T
            loads = basis.T @ model.load_vectors()
            pose_map = model.pose_of(basis)
            if hyper_reduction:
                states = rb.training_states(basis, modes, derivatives, snapshots, training)
                contrib = ecsw.nonlinear_contributions(tangent, basis, states)
                t2 = time.perf_counter()
                cells, weights, error = ecsw.fit_weights(
                    contrib, ecsw_tol, min(max_elements, contrib.shape[-1])
                )
                info.update(contributions_s=t2 - t1, fit_s=time.perf_counter() - t2)
                info["ecsw_error"] = error
            else:
                cells = np.arange(tangent.element_nodes.shape[0])
                weights = np.ones(len(cells))
            t3 = time.perf_counter()
            poly = polynomial_force(tangent, basis, cells, weights)
            poly = PolynomialForce(0.5 * (stiffness + stiffness.T), poly.cubic, poly.quartic)
            info["tensors_s"] = time.perf_counter() - t3
            rom = cls(basis, poly, loads, pose_map, predictor, cells, weights, force_range, info)
            t4 = time.perf_counter()
            forces = rb.training_forces(force_range, N_PREDICT, seed=rb.SEED + 1)
            rom.predictor = np.linalg.lstsq(
                rb.monomials(forces), rom.coordinates(forces), rcond=None
            )[0]
            info["predictor_s"] = time.perf_counter() - t4
            info["build_s"] = time.perf_counter() - t0
        return rom

    # online ---------------------------------------------------------------------------------
    def check_design(self, design: object) -> np.ndarray:
        """Force vectors as (n, 6) [N] within ``±force_range``; raises ``ValueError`` else."""
        f = np.asarray(design, dtype=float)
        f = check_matrix("forces [N]", f[None, :] if f.ndim == 1 else f, shape=(None, 6))
        worst = float(np.abs(f).max(initial=0.0))
        if worst > self.force_range:
            raise ValueError(
                f"forces [N] must lie in [-{self.force_range:g}, {self.force_range:g}] (the ROM's "
                f"force_range), got |force| = {worst:g}"
            )
        return f

    def coordinates(self, design: object) -> np.ndarray:
        """Reduced coordinates (n, n_basis) [mm] of the equilibria under forces (n, 6) [N].

        Newton from the cubic predictor (``predictor``); a force vector whose Newton iteration
        does not converge within ``MAX_ITERATIONS`` is solved again over ``CONTINUATION`` equal
        load steps (each from the last step's equilibrium).

        Parameters
        ----------
        design : array_like (n, 6) or (6,)
            Actuator forces [N], within ``±force_range``.

        Raises
        ------
        ValueError
            If a force is out of range, or no continuation converges (names the force vector
            and the residual reached).
        """
        f = self.check_design(design)
        target = f @ self.loads.T
        q = rb.monomials(f) @ self.predictor
        with one_thread():
            residual = self._newton(q, target)
            for steps in CONTINUATION:
                redo = np.flatnonzero(~(residual <= TOL))  # NaN: not converged
                if len(redo) == 0:
                    break
                start = np.zeros((len(redo), self.n_basis))
                for k in range(1, steps + 1):
                    left = self._newton(start, target[redo] * (k / steps))
                residual[redo] = left
                q[redo] = start
        failed = np.flatnonzero(~(residual <= TOL))
        if len(failed):
            bad = int(failed[0])
            raise ValueError(
                f"reduced Newton did not converge in {MAX_ITERATIONS} iterations (nor over "
                f"{CONTINUATION} load steps) for forces [N] {f[bad].tolist()} (relative "
                f"residual {residual[bad]:.1e} > {TOL:g}); {len(failed)} of {len(f)} failed"
            )
        return q

    def _newton(self, q: np.ndarray, target: np.ndarray) -> np.ndarray:
        """Newton iterations on every row of ``q`` (updated in place) towards ``target``.

        A row has converged when its relative residual is ≤ ``TOL``, or when a correction is
        ≤ ``STEP_TOL`` of its ``q`` (then quadratic convergence leaves an error of order
        ``STEP_TOL²``, and the residual evaluation that would confirm it, the costly part of an
        iteration, is skipped). Returns the relative residuals reached: 0 where converged by the
        step, NaN where the iteration blew up.
        """
        scale = np.linalg.norm(target, axis=1)
        scale[scale == 0.0] = 1.0  # zero load: q = 0 is exact
        relative = np.full(len(q), np.nan)
        k = self.force.stiffness
        todo = np.arange(len(q))
        for _ in range(MAX_ITERATIONS):
            bq, zc = self.force.terms(q[todo])
            res = q[todo] @ k + ((3.0 * bq + 2.0 * zc) @ q[todo][:, :, None])[:, :, 0]
            res -= target[todo]
            relative[todo] = np.linalg.norm(res, axis=1) / scale[todo]
            going = ~(relative[todo] <= TOL) & np.isfinite(relative[todo])
            todo, res = todo[going], res[going]
            if len(todo) == 0:
                break
            jac = k + 6.0 * (bq[going] + zc[going])
            step = np.linalg.solve(jac, res[..., None])[..., 0]
            q[todo] -= step
            small = np.linalg.norm(step, axis=1) <= STEP_TOL * np.linalg.norm(q[todo], axis=1)
            relative[todo[small]] = 0.0
            todo = todo[~small]
            if len(todo) == 0:
                break
        return relative

    def poses(self, design: object) -> np.ndarray:
        """Stage poses (n, 6) [µm, µrad] under actuator forces ``design`` (n, 6) or (6,) [N]:
        the model's pose fit of ``V q``, precomputed on the basis; raises as
        :meth:`coordinates`."""
        return self.coordinates(design) @ self.pose_map.T

    def displacement(self, forces: object) -> np.ndarray:
        """Reduced displacement vector ``V q`` (n_dofs,) [mm] under one force vector (6,) [N];
        raises ``ValueError`` on another shape, and as :meth:`coordinates`."""
        f = np.asarray(forces, dtype=float)
        if f.shape != (6,):
            raise ValueError(f"forces must have shape (6,), got {f.shape}")
        return self.basis @ self.coordinates(f)[0]
