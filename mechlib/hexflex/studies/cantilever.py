"""A benchmark with a known answer for the non-linear solver: the slender cantilever's elastica.

A prismatic cantilever of Q2 (27-node) hexahedra, clamped at x = 0, carries a dead load P along
+z spread as a uniform traction over its end face. :class:`Cantilever` provides what
:class:`~mechlib.fe.nonlinear.NonlinearSolver` and :class:`~mechlib.fe.svk_tangent.
SVKTangent` read from a model (:class:`mechlib.fe.protocol.SolidModel`: ``element``,
``body_factor``, ``young``, ``poisson``, ``fe``, ``n_dofs``, ``load_vectors``, ``check_forces``,
``back_substitute``), so the solid FE core's total-Lagrangian Saint Venant–Kirchhoff code path
that solves the HexFlex solves it; its one "actuator force" is P [N].

The reference is the inextensible Euler–Bernoulli elastica (:mod:`.elastica`). The solid
differs from it by shear (O((h/L)²)), by the clamp's restraint of the Poisson contraction
(O(ν² h/L)), by the strain measure at the outer fibres (strain ≈ α h / 2L) and by the
discretisation: :func:`mesh_study`.
It lives beside the solver it verifies and reuses ``problem``'s SfePy helpers (``mechlib/bench``
is the speed wing). Units: mm, N, MPa.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from mechlib.fe import sfepy_base as fe
from mechlib.fe.boxmesh import box_hexahedra
from mechlib.fe.linear import FactorisedStiffness
from mechlib.fe.nonlinear import NonlinearSolver, SolveStats
from mechlib.hexflex.geometry import AL7075_POISSON, AL7075_YOUNG_MPA, MAX_POISSON
from mechlib.hexflex.studies.elastica import MAX_ALPHA, TipResponse, check_alpha, elastica_tip
from mechlib.params import check_float, check_int, check_matrix

#: Default beam: length [mm] and square section side [mm] (L/h = 50).
LENGTH_MM = 100.0
SECTION_MM = 2.0
#: Smallest slenderness L/h accepted (below it a solid is no longer a slender beam).
MIN_SLENDERNESS = 20.0
#: Default elements along the length and across each side of the section (the tests' mesh;
#: :func:`mesh_study` refines both).
N_LENGTH = 32
N_SECTION = 1
#: Length of the element at the clamp, in section depths. The clamp holds the section's Poisson
#: contraction over a boundary layer about a depth long, which a longer element stiffens: at
#: L/h = 50, ν = 0.33, 16 elements, the linear tip deflection was −0.92 % off Euler–Bernoulli
#: with equal elements, −0.22 % with the first halved to ≤ h/4, −0.22 % to ≤ h/8.
CLAMP_DEPTHS = 0.25
#: Load-parameter increment per load step of :meth:`Cantilever.solve`. Measured on the default
#: beam: α = 2 in one step converged (the modified method gave up, Newton took 11 corrections);
#: in more steps, each step after the first went to Newton (5–7 corrections), so more steps
#: cost more (0.9 s for 1, 1.2 s for 2, 2.1 s for 4 at 16 elements) for the same answer.
ALPHA_STEP = 1.0
#: FE (default mesh 32 × 1 × 1 Q2, L/h = 50) against the elastica, relative, per quantity (δ/L,
#: shortening/L, θ₀), from :func:`mesh_study` at α = 0.25, 1, 2: the finer meshes' largest
#: difference (64 × 1 × 1, 32 × 2 × 2; chiefly the clamp's Poisson restraint, −0.18 %, −0.29 %,
#: −0.14 %, halving at L/h = 100) plus the default mesh's distance to them, rounded up.
ELASTICA_TOL: tuple[float, float, float] = (0.002, 0.0035, 0.0015)
#: Relative tolerance of coordinate selections (end faces).
_REGION_TOL = 1e-9


@dataclass
class CantileverFE:
    """The SfePy pieces of a :class:`Cantilever` that ``SVKTangent`` and the load use."""

    pb: Any
    field: Any
    v: Any
    omega: Any
    eq: np.ndarray
    coors: np.ndarray  # every field DOF node's reference coordinates (n_nodes, 3) [mm]


class Cantilever(FactorisedStiffness):
    """A clamped Q2 cantilever with a dead transverse end load, solvable by ``NonlinearSolver``.

    Parameters
    ----------
    length, width, depth : float
        Beam length along x and section sides along y and z (the load's direction) [mm];
        ``length / depth`` at least ``MIN_SLENDERNESS``, ``width`` at least ``depth`` (bending
        about the weak axis).
    n_length, n_section : int
        Q2 elements along the length (2–400; the first is further halved towards the clamp
        down to ``CLAMP_DEPTHS`` depths) and across each side of the section (1–8).
    young : float
        Young's modulus [MPa], > 0.
    poisson : float
        Poisson's ratio, in (−1, ``MAX_POISSON``].
    clamped : bool
        Clamp the face x = 0 (default). Without it the model floats (a singular stiffness:
        :meth:`back_substitute` refuses), for rigid-motion checks of the internal force.

    Raises
    ------
    ValueError
        If a parameter is out of range (the message names it).
    """

    element = "q2"
    body_factor = 1.0

    def __init__(
        self,
        length: float = LENGTH_MM,
        width: float = SECTION_MM,
        depth: float = SECTION_MM,
        n_length: int = N_LENGTH,
        n_section: int = N_SECTION,
        young: float = AL7075_YOUNG_MPA,
        poisson: float = AL7075_POISSON,
        clamped: bool = True,
    ) -> None:
        self.length = check_float("length [mm]", length, low=0.0, low_open=True)
        self.depth = check_float(
            "depth [mm]", depth, low=0.0, high=self.length / MIN_SLENDERNESS, low_open=True
        )
        self.width = check_float("width [mm]", width, low=self.depth, high=self.length)
        self.n_length = check_int("n_length", n_length, low=2, high=400)
        self.n_section = check_int("n_section", n_section, low=1, high=8)
        self.young = check_float("young [MPa]", young, low=0.0, low_open=True)
        self.poisson = check_float("poisson", poisson, low=-1.0, high=MAX_POISSON, low_open=True)
        self.clamped = bool(clamped)
        #: bending stiffness EI about y [N mm²]
        self.bending_stiffness = self.young * self.width * self.depth**3 / 12.0
        self.fe = self._build()
        self.set_stiffness(self._assemble(), factorise_now=False)
        self._load = self._end_load()
        nodes = self.fe.coors
        self._end = np.flatnonzero(np.abs(nodes[:, 0] - self.length) <= _REGION_TOL * self.length)
        self._tip = self._end[np.argmin(np.linalg.norm(nodes[self._end, 1:], axis=1))]
        if np.linalg.norm(nodes[self._tip, 1:]) > _REGION_TOL * self.length:
            raise RuntimeError("no node at the end face's centroid: mesh error")

    # what NonlinearSolver and SVKTangent read ---------------------------------------------------
    @property
    def n_dofs(self) -> int:
        """Number of free degrees of freedom."""
        return int(self.fe.eq.max()) + 1

    def load_vectors(self) -> np.ndarray:
        """Reduced load vector (n_dofs, 1) of a unit end load P = 1 N along +z."""
        return self._load[:, None].copy()

    def check_forces(self, forces: object) -> np.ndarray:
        """End loads P as an (n, 1) array [N], each with |α| = |P| L²/EI ≤ ``MAX_ALPHA``."""
        f = np.asarray(forces, dtype=float)
        f = check_matrix("forces [N] (end load P)", f.reshape(-1, 1) if f.ndim < 2 else f,
                         shape=(None, 1))  # fmt: skip
        bound = MAX_ALPHA * self.bending_stiffness / self.length**2
        worst = float(np.abs(f).max(initial=0.0))
        if worst > bound * (1.0 + 1e-12):
            raise ValueError(
                f"forces [N] (end load P) must lie in [-{bound:g}, {bound:g}] "
                f"(|PL^2/EI| <= {MAX_ALPHA:g}), got |P| = {worst:g}"
            )
        return f

    def back_substitute(self, rhs: np.ndarray) -> np.ndarray:
        """Solve ``K x = rhs`` with the factorised linear stiffness (rhs (n_dofs,) or
        (n_dofs, n)); one BLAS thread, as ``HexFlexModel.back_substitute``.

        Raises
        ------
        ValueError
            If the model is not clamped (its stiffness is singular).
        """
        if not self.clamped:
            raise ValueError("clamped must be True to solve: a floating cantilever is singular")
        return super().back_substitute(rhs)

    # the benchmark -----------------------------------------------------------------------------
    def load_for(self, alpha: float) -> float:
        """End load P [N] of the load parameter α = PL²/EI (checked as :func:`check_alpha`)."""
        return check_alpha(alpha) * self.bending_stiffness / self.length**2

    def tip_response(self, u: np.ndarray) -> TipResponse:
        """δ/L, shortening/L and rotation [rad] of the tip for reduced displacements ``u``.

        δ and the shortening are those of the end face's centroid node; the rotation is the
        least-squares rotation, in the x–z plane, of the end face's nodes (their lines across
        the depth), which equals the elastica's slope θ₀ for a plane section.
        """
        full = self.fe.pb.get_variables().make_full_vec(np.asarray(u, dtype=float))
        disp = full.reshape(-1, 3)
        tip = disp[self._tip]
        ref = self.fe.coors[self._end]
        now = ref + disp[self._end]
        z = ref[:, 2] - ref[:, 2].mean()
        xc, zc = now[:, 0] - now[:, 0].mean(), now[:, 2] - now[:, 2].mean()
        rotation = math.atan2(-float(z @ xc), float(z @ zc))
        return TipResponse(tip[2] / self.length, -tip[0] / self.length, rotation)

    def solve(
        self, alpha: float, steps: int | None = None, solver: NonlinearSolver | None = None
    ) -> tuple[TipResponse, SolveStats]:
        """FE tip response and ``SolveStats`` at α = PL²/EI (in [0, ``MAX_ALPHA``]) by
        ``NonlinearSolver.solve`` in ``steps`` load steps (default ``ceil(alpha / ALPHA_STEP)``),
        with ``solver`` if given (one built on this model: it keeps the Cholesky analysis)."""
        alpha = check_alpha(alpha)
        if steps is None:
            steps = max(1, math.ceil(alpha / ALPHA_STEP - 1e-9))
        solver = NonlinearSolver(self) if solver is None else solver
        if solver.model is not self:
            raise ValueError("solver must be built on this cantilever (solver.model is another)")
        u, stats = solver.solve([self.load_for(alpha)], steps=steps)
        return self.tip_response(u), stats

    # building ----------------------------------------------------------------------------------
    def _build(self) -> CantileverFE:
        fe.quiet_sfepy()
        from sfepy.discrete import Equation, Equations, FieldVariable, Material, Problem
        from sfepy.discrete.conditions import Conditions, EssentialBC
        from sfepy.discrete.fem import FEDomain, Field, Mesh
        from sfepy.mechanics.matcoefs import stiffness_from_youngpoisson
        from sfepy.terms import Term

        coors, cells = box_hexahedra(
            (self.length, self.width, self.depth),
            (self.n_length, self.n_section, self.n_section),
            clamp_size=min(self.length / self.n_length, CLAMP_DEPTHS * self.depth),
        )
        mesh = Mesh.from_data("cantilever", coors, np.zeros(len(coors), dtype=np.int32),
                              [cells], [np.ones(len(cells), dtype=np.int32)], ["3_8"])  # fmt: skip
        domain = FEDomain("cantilever", mesh)
        omega = domain.create_region("Omega", "all")
        tol = _REGION_TOL * self.length
        clamp = domain.create_region("Clamp", f"vertices in (x < {tol!r})", "facet")
        domain.create_region("End", f"vertices in (x > {self.length - tol!r})", "facet")
        field = Field.from_args("fu", np.float64, "vector", omega, approx_order=2)
        u = FieldVariable("u", "unknown", field)
        v = FieldVariable("v", "test", field, primary_var_name="u")
        mat = Material("m", D=stiffness_from_youngpoisson(3, self.young, self.poisson))
        term = Term.new("dw_lin_elastic(m.D, v, u)", fe.integral(), omega, m=mat, v=v, u=u)
        pb = Problem("cantilever", equations=Equations([Equation("balance", term)]))
        ebcs = [EssentialBC("clamp", clamp, {"u.all": 0.0})] if self.clamped else []
        pb.set_bcs(ebcs=Conditions(ebcs))
        pb.time_update()
        eq = np.asarray(pb.get_variables()["u"].eq_map.eq)
        nodes = np.asarray(field.get_coor(), dtype=float)
        return CantileverFE(pb, field, v, omega, eq, nodes)

    def _assemble(self):
        """Reduced linear stiffness (as ``HexFlexModel._assemble``)."""
        return fe.assemble_stiffness(self.fe.pb, self.n_dofs)

    def _end_load(self) -> np.ndarray:
        """Reduced consistent load vector of a uniform traction (0, 0, 1/A) on the end face:
        integrated exactly (Q2 on a flat face, quadrature order ``sfepy_base.QUAD_ORDER``)."""
        from sfepy.discrete import Material

        traction = np.array([[0.0], [0.0], [1.0 / (self.width * self.depth)]])
        vec = self.fe.pb.evaluate(
            f"dw_surface_ltr.{fe.QUAD_ORDER}.End(f.val, v)", mode="weak", dw_mode="vector",
            f=Material("f", val=traction), v=self.fe.v, copy_materials=False,
        )  # fmt: skip
        return np.asarray(vec, dtype=float).copy()


def mesh_study(
    meshes: object = ((8, 1), (16, 1), (32, 1), (64, 1), (32, 2)),
    alphas: object = (0.25, 1.0, 2.0),
    **beam: float,
) -> dict[str, np.ndarray]:
    """FE tip response against the elastica on a sequence of meshes.

    Parameters
    ----------
    meshes : sequence of (n_length, n_section)
        The meshes (elements along the length, across each side of the section).
    alphas : sequence of float
        Load parameters PL²/EI, each in [0, ``MAX_ALPHA``].
    **beam
        ``length``, ``width``, ``depth``, ``young``, ``poisson`` of :class:`Cantilever`.

    Returns
    -------
    dict of ndarray
        ``meshes`` (n_mesh, 2), ``alphas``, ``dofs`` (n_mesh,), ``fe`` (n_mesh, n_alpha, 3) and
        ``elastica`` (n_alpha, 3) as :class:`TipResponse`, ``relative`` = fe / elastica − 1,
        ``seconds`` (n_mesh,): model and solves.
    """
    grid = np.asarray(meshes, dtype=int).reshape(-1, 2)
    loads = [check_alpha(a) for a in np.atleast_1d(np.asarray(alphas, dtype=float))]
    ref = np.array([elastica_tip(a) for a in loads])
    out = np.empty((len(grid), len(loads), 3))
    dofs, seconds = np.empty(len(grid), dtype=int), np.empty(len(grid))
    for m, (n_length, n_section) in enumerate(grid):
        t0 = time.perf_counter()
        beam_m = Cantilever(n_length=int(n_length), n_section=int(n_section), **beam)
        solver = NonlinearSolver(beam_m)
        for a, alpha in enumerate(loads):
            out[m, a] = beam_m.solve(alpha, solver=solver)[0]
        dofs[m], seconds[m] = beam_m.n_dofs, time.perf_counter() - t0
    with np.errstate(divide="ignore", invalid="ignore"):
        relative = out / ref - 1.0
    return {"meshes": grid, "alphas": np.array(loads), "dofs": dofs, "fe": out,
            "elastica": ref, "relative": relative, "seconds": seconds}  # fmt: skip
