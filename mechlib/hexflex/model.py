"""SfePy finite-element model of the HexFlex: factorise once, solve many load cases.

Two element kinds on the same planar quad mesh:

- ``"q2"`` (reference): one layer of 27-node (Q2) hexahedra through the thickness — linear
  hexahedra lock in bending (``../shared/TOOLCHAIN.md``);
- ``"shell"``: SfePy's ``shell10x`` Reissner–Mindlin shell (the thesis used shells in ANSYS).

Units: mm, N, MPa (N/mm²). The stiffness matrix is assembled and factorised once per geometry;
a load case is one back-substitution, and the 6 × 6 compliance (pose per unit actuator force,
µm/N and µrad/N, columns in the order of Eq 4) comes from six of them.

Geometric non-linearity (Q2 only): total-Lagrangian Saint Venant–Kirchhoff solid — the linear
model's own elasticity tensor between Green–Lagrange strain and second Piola–Kirchhoff stress,
i.e. large displacements and rotations with a linear-elastic material, which is what a
"geometrically non-linear" analysis of a metal flexure means — solved by Newton's method with load
steps. The first iteration from the undeformed state reuses the linear factorisation (the
tangent at u = 0 *is* the linear stiffness).

SfePy 2026.3's ``dw_tl_he_svk`` term doubles the shear *rows* of its tangent modulus, so its
tangent is not the derivative of its residual (Newton then converges only linearly, at rate ½).
``_register_svk_term`` adds ``dw_tl_he_svk_consistent``, the same residual with the consistent
tangent; ``tests/test_hexflex.py`` checks it against finite differences of the residual.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse.linalg as sla

from mechlib.hexflex import geometry as geo
from mechlib.hexflex import mesh as ms
from mechlib.hexflex.pose import fit_operator
from mechlib.params import check_choice, check_float, check_int, check_matrix

ELEMENTS: tuple[str, ...] = ("q2", "shell")
#: Al 7075-T6: Young's modulus [MPa] and Poisson's ratio (issue specification).
AL7075_YOUNG_MPA = 71_700.0
AL7075_POISSON = 0.33
#: Largest |actuator force| the model accepts [N] (Table 1 uses ±1 N; sweeps go further).
MAX_FORCE_N = 50.0
#: Default element size at the beams as a fraction of the narrowest beam width (two structured
#: Q2 elements across it): one element across is exact for a beam alone (see ``beamcheck``), but
#: the re-entrant corners where the flexures meet the stage and tabs need more (convergence study
#: in the hexflex notebook: < 1 % change to the next refinement).
DEFAULT_MESH_FRACTION = 0.5
#: Default largest element in the stage, arms and tabs, in narrowest beam widths.
COARSE_WIDTHS = 4.0
#: Shell drilling stiffness factor (SfePy's shell10x examples).
SHELL_DRILL = 1e-7
#: Quadrature order of the Q2 solid terms.
QUAD_ORDER = 4
#: Newton stopping rule: ‖residual‖ ≤ NEWTON_TOL · ‖external load‖. The round-off floor of the
#: TL residual on these meshes is ≈ 3e-8 (measured), so tighter values cannot be met.
NEWTON_TOL = 1e-6
#: ... or when a Newton correction is below this fraction of the displacement (small loads, where
#: the residual's round-off floor, relative to the load, rises above NEWTON_TOL).
INCREMENT_TOL = 1e-10
_TAB_GROUP = 10


def _quiet_sfepy() -> None:
    from sfepy.base.base import output

    output.set_output(quiet=True)


@dataclass
class HexFlexModel:
    """A linear FE model of one geometry, with its factorised stiffness.

    Parameters
    ----------
    geometry : HexFlexGeometry
    young : float
        Young's modulus [MPa], > 0.
    poisson : float
        Poisson's ratio, in (−1, 0.5).
    mesh_size : float, optional
        Target in-plane element size at the beams [mm]; default: ``DEFAULT_MESH_FRACTION`` times
        the narrowest beam width. Must not exceed that width. Beams and links get a structured
        grid with an even number (≥ 2) of elements across (see ``mesh.sector_mesh``).
    coarsening : float, optional
        Largest element in the stage, arms and tabs as a multiple of ``mesh_size``, in [1, 64];
        default: the multiple that makes it ``COARSE_WIDTHS`` narrowest beam widths, whatever
        ``mesh_size`` (so refining ``mesh_size`` refines the flexures, where the compliance is).
    element : {"q2", "shell"}
    """

    geometry: geo.HexFlexGeometry = field(default_factory=geo.HexFlexGeometry)
    young: float = AL7075_YOUNG_MPA
    poisson: float = AL7075_POISSON
    mesh_size: float | None = None
    coarsening: float | None = None
    element: str = "q2"
    timings: dict[str, float] = field(default_factory=dict, init=False)

    def __post_init__(self) -> None:
        _quiet_sfepy()
        g = self.geometry
        self.young = check_float("young [MPa]", self.young, low=0.0, low_open=True)
        self.poisson = check_float("poisson", self.poisson, low=-1.0, high=0.499, low_open=True)
        self.element = check_choice("element", self.element, ELEMENTS)
        narrowest = min(g.beam_width, g.link_width)
        size = DEFAULT_MESH_FRACTION * narrowest if self.mesh_size is None else self.mesh_size
        self.mesh_size = check_float("mesh_size [mm]", size, low=0.0, high=narrowest, low_open=True)
        if self.coarsening is None:
            self.coarsening = max(1.0, COARSE_WIDTHS * narrowest / self.mesh_size)
        self.coarsening = check_float("coarsening", self.coarsening, low=1.0, high=64.0)
        t0 = time.perf_counter()
        sector = ms.sector_mesh(g, self.mesh_size, self.coarsening)
        self.planar = ms.full_mesh(sector, self.mesh_size)
        t1 = time.perf_counter()
        self._build()
        t2 = time.perf_counter()
        self._matrix = self._assemble()
        t3 = time.perf_counter()
        self._lu = factorise(self._matrix)
        t4 = time.perf_counter()
        self.timings.update(mesh=t1 - t0, setup=t2 - t1, assembly=t3 - t2, factorisation=t4 - t3)
        self._loads = self._unit_loads()
        self._fit = self._pose_operator()
        self._compliance: np.ndarray | None = None
        self._nl_evaluator = None

    # construction ---------------------------------------------------------------------------
    def _cell_groups(self) -> np.ndarray:
        """Cell groups for SfePy; also sets ``cell_parts`` (index into ``geometry.PARTS``)."""
        g, m = self.geometry, self.planar
        centroids = m.nodes[m.quads].mean(axis=1)
        part = geo.classify(centroids, g)
        lost = part < 0  # a coarse cell spanning a re-entrant corner: its centroid is outside
        if np.all(lost):
            raise RuntimeError("mesh cells outside the planform: geometry and mesh disagree")
        if np.any(lost):
            from scipy.spatial import cKDTree

            _, near = cKDTree(centroids[~lost]).query(centroids[lost])
            part[lost] = part[~lost][near]
        leg = geo.tab_of(centroids)
        r, _ = geo.local_coordinates(centroids)
        bar = (part == geo.PARTS.index("tab")) & (r[np.arange(len(r)), leg] >= g.tab_inner - 1e-9)
        self.cell_parts = part
        return np.where(bar, _TAB_GROUP + leg, 1 + part).astype(np.int32)

    def _build(self) -> None:
        from sfepy.discrete import (
            Equation,
            Equations,
            FieldVariable,
            Function,
            Material,
            Problem,
        )
        from sfepy.discrete.conditions import Conditions, EssentialBC
        from sfepy.discrete.fem import FEDomain, Field, Mesh
        from sfepy.mechanics.matcoefs import stiffness_from_youngpoisson
        from sfepy.terms import Term

        g, m = self.geometry, self.planar
        groups = self._cell_groups()
        if self.element == "q2":
            coors, cells = ms.extrude(m, g.thickness)
            desc = "3_8"
        else:
            coors, cells = np.c_[m.nodes, np.zeros(len(m.nodes))], m.quads
            desc = "2_4"
        mesh = Mesh.from_data(
            "hexflex",
            np.ascontiguousarray(coors),
            np.zeros(len(coors), dtype=np.int32),
            [cells.astype(np.int32)],
            [groups],
            [desc],
        )
        domain = FEDomain("hexflex", mesh)
        omega = domain.create_region("Omega", "all")
        radius = g.ground_radius

        def ground(coors, domain=None):
            r, _ = geo.local_coordinates(coors)
            return np.flatnonzero(r.max(axis=1) >= radius - 1e-6 * radius)

        gamma = domain.create_region(
            "Ground",
            "vertices by ground",
            "facet",
            functions={"ground": Function("ground", ground)},
        )
        self._tabs = [
            domain.create_region(f"Tab{k}", f"cells of group {_TAB_GROUP + k}") for k in range(3)
        ]
        if self.element == "q2":
            fld = Field.from_args("fu", np.float64, "vector", omega, approx_order=2)
            mat = Material("m", D=stiffness_from_youngpoisson(3, self.young, self.poisson))
        else:
            import sfepy.mechanics.shell10x as sh

            fld = Field.from_args(
                "fu", np.float64, 6, omega, approx_order=1, poly_space_basis="shell10x"
            )
            mat = Material(
                "m",
                D=sh.create_elastic_tensor(young=self.young, poisson=self.poisson),
                values={".drill": SHELL_DRILL},
            )
        u = FieldVariable("u", "unknown", fld)
        v = FieldVariable("v", "test", fld, primary_var_name="u")
        integral = self._shell_integral() if self.element == "shell" else None
        term = (
            Term.new("dw_lin_elastic(m.D, v, u)", _integral(QUAD_ORDER), omega, m=mat, v=v, u=u)
            if self.element == "q2"
            else Term.new("dw_shell10x(m.D, m.drill, v, u)", integral, omega, m=mat, v=v, u=u)
        )
        pb = Problem("hexflex", equations=Equations([Equation("balance", term)]))
        pb.set_bcs(ebcs=Conditions([EssentialBC("clamp", gamma, {"u.all": 0.0})]))
        pb.time_update()
        self._pb, self._field, self._u, self._v, self._mat = pb, fld, u, v, mat
        self._domain, self._omega = domain, omega
        self._coors = np.asarray(fld.get_coor()[: fld.n_vertex_dof], dtype=float)
        self._eq = pb.get_variables()["u"].eq_map.eq
        self._n_comp = 3 if self.element == "q2" else 6

    def _shell_integral(self):
        from sfepy.discrete import Integral

        aux = Integral("i", order=3)
        qp_coors, qp_weights = aux.get_qp("3_8")
        qp_coors[:, 2] = self.geometry.thickness * (qp_coors[:, 2] - 0.5)
        return Integral(
            "i", coors=qp_coors, weights=qp_weights * self.geometry.thickness, order="custom"
        )

    def _assemble(self):
        """Tangent (= stiffness) matrix of the Problem's own equations, reduced to free DOFs."""
        self._pb.time_update(create_matrix=True)
        self._pb.get_variables().init_state()
        self._pb.update_materials()
        return self._pb.get_evaluator().eval_tangent_matrix(np.zeros(self.n_dofs)).copy()

    def _unit_loads(self) -> np.ndarray:
        """Reduced load vectors (n_dofs, 6) of unit actuator forces spread over each tab bar."""
        from sfepy.discrete import Material

        dirs = geo.actuator_directions()
        out = np.zeros((self.n_dofs, 6))
        for j in range(6):
            k = j // 2
            if self.element == "q2":
                vol = self._pb.evaluate(f"ev_volume.{QUAD_ORDER}.Tab{k}(u)", u=self._u)
                mat = Material("f", val=(dirs[j] / vol)[:, None])
                out[:, j] = self._pb.evaluate(
                    f"dw_volume_lvf.{QUAD_ORDER}.Tab{k}(f.val, v)",
                    mode="weak",
                    dw_mode="vector",
                    f=mat,
                    v=self._v,
                    copy_materials=False,
                )
            else:
                out[:, j] = self._lumped_load(k, dirs[j])
        return out

    def _lumped_load(self, k: int, direction: np.ndarray) -> np.ndarray:
        m = self.planar
        cells = self._tabs[k].get_cells()
        area = np.abs(ms.signed_areas(m))[cells]
        weights = np.zeros(len(m.nodes))
        np.add.at(weights, m.quads[cells], np.repeat(area[:, None] / 4, 4, axis=1))
        full = np.zeros((len(m.nodes), self._n_comp))
        full[:, :3] = weights[:, None] / weights.sum() * direction
        red = np.zeros(self.n_dofs)
        eq = self._eq.reshape(-1, self._n_comp)[: len(m.nodes)]
        ok = eq >= 0
        red[eq[ok]] = full[ok]
        return red

    def _pose_operator(self) -> np.ndarray:
        """Operator (6, n_dofs): pose [µm, µrad] from a reduced solution."""
        stage = geo.in_stage(self._coors, self.geometry)
        op = fit_operator(self._coors[stage])
        idx = self._eq.reshape(-1, self._n_comp)[: len(self._coors)][stage, :3].ravel()
        if np.any(idx < 0):
            raise RuntimeError("stage nodes are clamped: geometry error")
        self._stage_idx = idx
        return op

    # public API -----------------------------------------------------------------------------
    @property
    def n_dofs(self) -> int:
        """Number of free degrees of freedom (after clamping the ground)."""
        return int(self._eq.max()) + 1

    def _check_forces(self, forces: object) -> np.ndarray:
        f = np.asarray(forces, dtype=float)
        f = check_matrix("forces [N]", f[None, :] if f.ndim == 1 else f, shape=(None, 6))
        worst = np.abs(f).max(initial=0.0)
        if worst > MAX_FORCE_N:
            raise ValueError(
                f"forces [N] must lie in [-{MAX_FORCE_N:g}, {MAX_FORCE_N:g}] N, "
                f"got |force| = {worst:g}"
            )
        return f

    def assembled_stiffness(self):
        """The reduced stiffness matrix (free DOFs, SciPy sparse) [N/mm]."""
        return self._matrix

    def solve_reduced(self, forces: object) -> np.ndarray:
        """Reduced displacement vectors (n_dofs, n) for actuator forces (n, 6) [N]."""
        f = self._check_forces(forces)
        return self._lu.solve(np.ascontiguousarray(self._loads @ f.T))

    def poses(self, forces: object) -> np.ndarray:
        """Stage poses (n, 6) [µm, µrad] for actuator forces (n, 6) [N]: back-substitutions."""
        u = self.solve_reduced(forces)
        return (self._fit @ u[self._stage_idx]).T

    def _nonlinear_evaluator(self):
        """SfePy evaluator of the TL Saint Venant–Kirchhoff internal forces (same field, BCs)."""
        if self._nl_evaluator is None:
            self._nl_evaluator = self.tl_evaluator(_register_svk_term())
        return self._nl_evaluator

    def tl_evaluator(self, term: str):
        """SfePy evaluator (residual, tangent) of one total-Lagrangian term taking the linear
        model's elasticity tensor, ``term(s.D, v, u)``, on this model's field and clamp.

        Parameters
        ----------
        term : str
            SfePy term name, e.g. ``"dw_tl_he_svk"`` (the stock term) or the consistent one.
        """
        from sfepy.discrete import Equation, Equations, Material, Problem
        from sfepy.mechanics.matcoefs import stiffness_from_youngpoisson
        from sfepy.terms import Term

        if self.element != "q2":
            raise ValueError(f"element must be 'q2' for a TL term, got {self.element!r}")
        mat = Material("s", D=stiffness_from_youngpoisson(3, self.young, self.poisson))
        kw = dict(s=mat, v=self._v, u=self._u)
        t = Term.new(f"{term}(s.D, v, u)", _integral(QUAD_ORDER), self._omega, **kw)
        pb = Problem("hexflex_tl", equations=Equations([Equation("balance", t)]))
        pb.set_bcs(ebcs=self._pb.ebcs)
        pb.time_update(create_matrix=True)
        pb.get_variables().init_state()
        pb.update_materials()
        return pb.get_evaluator()

    def solve_nonlinear(
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
            Dead loads on the six ports [N], within ``±MAX_FORCE_N``.
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
        """
        if self.element != "q2":
            raise ValueError(
                f"element must be 'q2' for the non-linear solve (SfePy's shell10x is linear), "
                f"got {self.element!r}"
            )
        f = self._check_forces(forces)
        if f.shape[0] != 1:
            raise ValueError(f"forces must be one vector of 6 forces, got shape {f.shape}")
        steps = check_int("steps", steps, low=1, high=100)
        tol = check_float("tol", tol, low=1e-7, high=1e-2)
        max_iterations = check_int("max_iterations", max_iterations, low=1, high=100)
        ev = self._nonlinear_evaluator()
        load = self._loads @ f[0]
        scale = np.linalg.norm(load)
        u = np.zeros(self.n_dofs)
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
                    du = self._lu.solve(res)
                else:
                    tangent = ev.eval_tangent_matrix(u).copy()
                    du = factorise(tangent).solve(res)
                u = u - du
                if np.linalg.norm(du) <= INCREMENT_TOL * np.linalg.norm(u):
                    used.append(it + 1)  # at the round-off floor of the residual
                    break
        return u, used

    def poses_nonlinear(self, forces: object, steps: int = 1) -> tuple[np.ndarray, list[int]]:
        """Stage pose (6,) [µm, µrad] of the geometrically non-linear solution and the Newton
        iterations per load step (see :meth:`solve_nonlinear`). The pose is the same
        small-rotation rigid-body fit as the linear model's, so the two compare like with like."""
        u, iterations = self.solve_nonlinear(forces, steps=steps)
        return self._fit @ u[self._stage_idx], iterations

    def poses_plain_sfepy(self, forces: object) -> np.ndarray:
        """Stage poses (n, 6) by SfePy's own ``Problem.solve()``, one full solve per load case.

        The textbook SfePy path — each case builds the load terms, assembles, factorises and
        solves (``nls.newton`` + ``ls.scipy_direct``). It exists as the cross-check of
        :meth:`poses` and as the baseline of the speed benchmark (``make bench``).
        """
        from sfepy.discrete import Equation, Equations, Material, Problem
        from sfepy.solvers.ls import ScipyDirect
        from sfepy.solvers.nls import Newton
        from sfepy.terms import Term

        if self.element != "q2":
            raise ValueError(f"element must be 'q2' for the plain SfePy path, got {self.element!r}")
        f = self._check_forces(forces)
        dirs = geo.actuator_directions()
        integral = _integral(QUAD_ORDER)
        stiff = Term.new(
            "dw_lin_elastic(m.D, v, u)", integral, self._omega, m=self._mat, v=self._v, u=self._u
        )
        out = np.empty((len(f), 6))
        for n, row in enumerate(f):
            rhs = None
            for k in range(3):
                vol = self._pb.evaluate(f"ev_volume.{QUAD_ORDER}.Tab{k}(u)", u=self._u)
                force = row[2 * k] * dirs[2 * k] + row[2 * k + 1] * dirs[2 * k + 1]
                val = np.zeros((self._n_comp, 1))
                val[:3, 0] = force / vol
                mat = Material(f"f{k}", val=val)
                term = Term.new(
                    f"dw_volume_lvf(f{k}.val, v)",
                    integral,
                    self._tabs[k],
                    v=self._v,
                    **{f"f{k}": mat},
                )
                rhs = term if rhs is None else rhs + term
            pb = Problem("plain", equations=Equations([Equation("balance", stiff - rhs)]))
            pb.set_bcs(ebcs=self._pb.ebcs)
            ls = ScipyDirect({})
            pb.set_solver(Newton({"i_max": 1, "eps_a": 1e-12, "eps_r": 1e-10}, lin_solver=ls))
            state = pb.solve(save_results=False)
            full = state.get_state_parts()["u"].reshape(-1, self._n_comp)
            stage = geo.in_stage(self._coors, self.geometry)
            out[n] = self._fit @ full[: len(self._coors)][stage, :3].ravel()
        return out

    def compliance(self) -> np.ndarray:
        """Pose per unit actuator force (6, 6): rows x y z θx θy θz, columns T1D1 … T3D2."""
        if self._compliance is None:
            self._compliance = self.poses(np.eye(6)).T
        return self._compliance.copy()

    def port_compliance(self) -> np.ndarray:
        """Work-conjugate port compliance (6, 6) [µm/N]: ``Bᵀ K⁻¹ B`` for the unit load vectors.

        Entry (i, j) is the load-weighted displacement of port i along its force direction under
        a unit force at port j; Maxwell–Betti reciprocity makes it symmetric.
        """
        return 1e3 * self._loads.T @ self.solve_reduced(np.eye(6))

    def forces_for_poses(self, poses: object) -> np.ndarray:
        """Actuator forces (n, 6) [N] that produce the stage poses (n, 6) (inverse model, Eq 9)."""
        p = np.asarray(poses, dtype=float)
        p = check_matrix("poses", p[None, :] if p.ndim == 1 else p, shape=(None, 6))
        return np.linalg.solve(self.compliance(), p.T).T

    def midplane_displacements(self, forces: object) -> np.ndarray:
        """Displacements (n_nodes, 3) [mm] of the planar mesh nodes for one force vector (6,)."""
        red = self.solve_reduced(forces)[:, 0]
        full = self._pb.get_variables().make_full_vec(red).reshape(-1, self._n_comp)
        n = len(self.planar.nodes)
        vert = full[: len(self._coors), :3]
        return 0.5 * (vert[:n] + vert[n : 2 * n]) if self.element == "q2" else vert[:n]


def convergence(
    geometry: geo.HexFlexGeometry,
    fractions: list[float],
    young: float = AL7075_YOUNG_MPA,
    poisson: float = AL7075_POISSON,
    elements: tuple[str, ...] = ELEMENTS,
    coarse_widths: float = COARSE_WIDTHS,
) -> list[dict[str, object]]:
    """Compliance of one geometry over mesh sizes (fractions of the narrowest beam) and elements.

    The largest element (stage, arms, tabs) stays ``coarse_widths`` narrowest beam widths, so
    the fractions refine the flexures; call again with a smaller ``coarse_widths`` to refine the
    rest.

    Returns
    -------
    list of dict
        ``element``, ``fraction``, ``coarse_widths``, ``mesh_size`` [mm], ``n_dofs`` and
        ``compliance`` (6, 6) per model.
    """
    narrowest = min(geometry.beam_width, geometry.link_width)
    coarse_widths = check_float("coarse_widths", coarse_widths, low=1.0, high=64.0)
    rows = []
    for fraction in fractions:
        fraction = check_float("fractions", fraction, low=0.0, high=1.0, low_open=True)
        size = narrowest * fraction
        for kind in elements:
            m = HexFlexModel(
                geometry,
                young=young,
                poisson=poisson,
                element=kind,
                mesh_size=size,
                coarsening=max(1.0, coarse_widths / fraction),
            )
            rows.append(
                {
                    "element": kind,
                    "fraction": fraction,
                    "coarse_widths": coarse_widths,
                    "mesh_size": size,
                    "n_dofs": m.n_dofs,
                    "compliance": m.compliance(),
                }
            )
    return rows


def factorise(matrix):
    """Sparse LU of a symmetric stiffness or tangent matrix.

    A minimum-degree ordering of A + Aᵀ with symmetric pivoting suits FE matrices: on a 172k-DOF
    model it cuts SuperLU's fill 3× and its time 4–5× against the default column ordering
    (measured in ``make bench``).
    """
    return sla.splu(matrix.tocsc(), permc_spec="MMD_AT_PLUS_A", options={"SymmetricMode": True})


def _integral(order: int):
    from sfepy.discrete import Integral

    return Integral("i", order=check_int("order", order, low=1))


def _register_svk_term() -> str:
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
