"""The factorised linear FE model of the HexFlex: assemble and factorise once, solve many cases.

:func:`mechlib.hexflex.fe.problem.build` sets up the SfePy problem (mesh, clamp, edge loads, pose
fit); this module assembles its stiffness once, factorises it, and answers load cases by
back-substitution: a load case costs one solve, and the 6 × 6 compliance (pose per unit actuator
force, µm/N and µrad/N, columns in the order of Eq 4) six of them. The geometrically non-linear
solve is built on a model, ``NonlinearSolver(model)`` (:mod:`mechlib.fe.nonlinear`; the
model knows nothing of it), the mesh study lives in :mod:`mechlib.hexflex.studies.convergence`.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import partial

import numpy as np

from mechlib.fe.linear import FactorisedModel
from mechlib.fe.sfepy_base import assemble_stiffness, integral
from mechlib.hexflex import geometry as geo
from mechlib.hexflex.fe import mesh as ms
from mechlib.hexflex.fe import problem as fe
from mechlib.hexflex.geometry import AL7075_POISSON, AL7075_YOUNG_MPA, MAX_POISSON
from mechlib.params import check_choice, check_float, check_matrix

ELEMENTS = fe.ELEMENTS
#: Largest |actuator force| the model accepts [N] (Table 1 uses ±1 N; sweeps go further).
MAX_FORCE_N = 50.0
#: Default element size at the flexures as a fraction of the narrowest flexure width (two
#: structured Q2 elements across it; convergence study in the hexflex notebook).
DEFAULT_MESH_FRACTION = 0.5
#: Default largest element in the stage and tabs, in narrowest flexure widths.
COARSE_WIDTHS = 3.0
#: Element sizes at the flexures that a model recipe takes, as fractions of the narrowest flexure
#: width (what the hexflex notebook's mesh-convergence study covers).
MESH_FRACTION_RANGE = (0.1, 1.0)


def check_settings(
    young: object, poisson: object, element: object, mesh_fraction: object | None = None
) -> tuple[float, float, str, float | None]:
    """The material and discretisation settings of a model, validated (what every model and
    model recipe checks): Young's modulus [MPa] > 0, Poisson's ratio in (−1, ``MAX_POISSON``],
    an element of ``ELEMENTS`` and, if given, a mesh fraction in ``MESH_FRACTION_RANGE``.

    Raises
    ------
    ValueError, TypeError
        Naming the setting, what was given and what is allowed.
    """
    young = check_float("young [MPa]", young, low=0.0, low_open=True)
    poisson = check_float("poisson", poisson, low=-1.0, high=MAX_POISSON, low_open=True)
    element = check_choice("element", element, ELEMENTS)
    if mesh_fraction is not None:
        low, high = MESH_FRACTION_RANGE
        mesh_fraction = check_float("mesh_fraction", mesh_fraction, low=low, high=high)
    return young, poisson, element, mesh_fraction


@dataclass
class HexFlexModel(FactorisedModel):
    """A linear FE model of one geometry, with its factorised stiffness.

    Parameters
    ----------
    geometry : HexFlexGeometry
    young : float
        Young's modulus [MPa], > 0.
    poisson : float
        Poisson's ratio, in (−1, ``MAX_POISSON``].
    mesh_size : float, optional
        Target in-plane element size at the flexures [mm]; default: ``DEFAULT_MESH_FRACTION``
        times the narrowest flexure width, which it must not exceed. Flexures get a structured
        grid with an even number (≥ 2) of elements across (see ``mesh.sector_mesh``).
    coarsening : float, optional
        Largest element in the stage and tabs as a multiple of ``mesh_size``, in [1, 64];
        default: the multiple that makes it ``COARSE_WIDTHS`` narrowest flexure widths, whatever
        ``mesh_size`` (so refining ``mesh_size`` refines the flexures, where the compliance is).
    element : {"q2", "shell"}
    body_factor : float
        Stiffness multiplier of the stage and tabs, in [1, 1e6] (1: the real part; large: a
        nearly rigid body, the reduced beam model's assumption).
    body_grading : float, optional
        Grade the stage and tabs' elements from ``mesh_size`` at the flexures' corners by this
        size gradient [mm/mm], > 0, up to ``coarsening * mesh_size`` (``mesh.sector_mesh``);
        default None: the default meshing.
    mid_widths : float
        Length of the flexures' elements mid-way along them, in flexure widths, in
        [``mesh.BEAM_ASPECT``, 8] (default ``mesh.MID_WIDTHS``).
    """

    geometry: geo.HexFlexGeometry = field(default_factory=geo.HexFlexGeometry)
    young: float = AL7075_YOUNG_MPA
    poisson: float = AL7075_POISSON
    mesh_size: float | None = None
    coarsening: float | None = None
    element: str = "q2"
    body_factor: float = 1.0
    body_grading: float | None = None
    mid_widths: float = ms.MID_WIDTHS
    timings: dict[str, float] = field(default_factory=dict, init=False)

    def __post_init__(self) -> None:
        g = self.geometry
        self.young, self.poisson, self.element, _ = check_settings(
            self.young, self.poisson, self.element
        )
        self.body_factor = check_float("body_factor", self.body_factor, low=1.0, high=1e6)
        size = DEFAULT_MESH_FRACTION * g.narrowest if self.mesh_size is None else self.mesh_size
        self.mesh_size = check_float(
            "mesh_size [mm]", size, low=0.0, high=g.narrowest, low_open=True
        )
        if self.coarsening is None:
            self.coarsening = coarsening_for(COARSE_WIDTHS, self.mesh_size / g.narrowest)
        self.coarsening = check_float("coarsening", self.coarsening, low=1.0, high=64.0)
        t0 = time.perf_counter()
        sector = ms.sector_mesh(
            g,
            self.mesh_size,
            self.coarsening,
            self.body_grading,
            self.mid_widths,
        )
        self.planar = ms.full_mesh(sector, self.mesh_size)
        t1 = time.perf_counter()
        self.fe = fe.build(g, self.planar, self.element, self.young, self.poisson, self.body_factor)
        t2 = time.perf_counter()
        matrix = self._assemble()
        t3 = time.perf_counter()
        self.set_stiffness(matrix)
        t4 = time.perf_counter()
        self.timings.update(mesh=t1 - t0, setup=t2 - t1, assembly=t3 - t2, factorisation=t4 - t3)
        self.cell_parts = self.fe.cell_parts

    def _assemble(self):
        """Tangent (= stiffness) matrix of the Problem's own equations, reduced to free DOFs."""
        return assemble_stiffness(self.fe.pb, self.n_dofs)

    # public API (and FactorisedModel's: solve_reduced, pose_of, compliance, poses …) ---------
    def check_forces(self, forces: object) -> np.ndarray:
        """Actuator forces as an (n, 6) array [N], each within ``±MAX_FORCE_N``."""
        f = np.asarray(forces, dtype=float)
        return check_forces("forces [N]", f[None, :] if f.ndim == 1 else f)

    def stage_motion(self, reduced: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The stage's nodes (m, 3) [mm] and their displacements (m, 3) [mm] in the reduced
        displacement vector ``reduced``: what :meth:`pose_of` fits, for an exact rigid
        registration (:func:`mechlib.fe.finite_pose.finite_poses`)."""
        points = self.fe.coors[geo.in_stage(self.fe.coors, self.geometry)]
        return points, np.asarray(reduced)[self.fe.stage_idx].reshape(-1, 3)

    def poses_plain_sfepy(self, forces: object) -> np.ndarray:
        """Stage poses (n, 6) by SfePy's own ``Problem.solve()``, one full solve per load case.

        The textbook SfePy path — each case builds its edge tractions as SfePy terms, assembles,
        factorises and solves (``nls.newton`` + ``ls.scipy_direct``). It exists as the
        cross-check of :meth:`poses` (which builds the same loads by hand) and as the baseline
        of the speed benchmark (``make bench``).
        """
        from sfepy.discrete import Equation, Equations, Material, Problem
        from sfepy.solvers.ls import ScipyDirect
        from sfepy.solvers.nls import Newton
        from sfepy.terms import Term

        if self.element != "q2":
            raise ValueError(f"element must be 'q2' for the plain SfePy path, got {self.element!r}")
        f = self.check_forces(forces)
        p, g = self.fe, self.geometry
        dirs = geo.actuator_directions()
        area = 2 * g.tab_half_width * g.thickness  # the external edge's end face [mm²]
        stiff = Term.new(
            "dw_lin_elastic(m.D, v, u)", integral(), p.omega, m=p.material, v=p.v, u=p.u
        )
        stage = geo.in_stage(p.coors, g)
        out = np.empty((len(f), 6))
        for n, row in enumerate(f):
            rhs = None
            for k in range(3):
                force = row[2 * k] * dirs[2 * k] + row[2 * k + 1] * dirs[2 * k + 1]
                mat = Material(f"f{k}", val=(force / area)[:, None])
                term = Term.new(
                    f"dw_surface_ltr(f{k}.val, v)", integral(), p.edges[k], v=p.v,
                    **{f"f{k}": mat},
                )  # fmt: skip
                rhs = term if rhs is None else rhs + term
            pb = Problem("plain", equations=Equations([Equation("balance", stiff - rhs)]))
            pb.set_bcs(ebcs=p.pb.ebcs)
            pb.set_solver(
                Newton({"i_max": 1, "eps_a": 1e-12, "eps_r": 1e-10}, lin_solver=ScipyDirect({}))
            )
            state = pb.solve(save_results=False)
            full = state.get_state_parts()["u"].reshape(-1, 3)
            out[n] = p.fit @ full[: len(p.coors)][stage].ravel()
        return out

    def port_compliance(self) -> np.ndarray:
        """Work-conjugate port compliance (6, 6) [µm/N]: ``Bᵀ K⁻¹ B`` for the unit load vectors.

        Entry (i, j) is the load-weighted displacement of port i along its force direction under
        a unit force at port j; Maxwell–Betti reciprocity makes it symmetric.
        """
        return 1e3 * self.fe.loads.T @ self.solve_reduced(np.eye(6))

    def forces_for_poses(self, poses: object) -> np.ndarray:
        """Actuator forces (n, 6) [N] that produce the stage poses (n, 6) (inverse model, Eq 9)."""
        p = np.asarray(poses, dtype=float)
        p = check_matrix("poses", p[None, :] if p.ndim == 1 else p, shape=(None, 6))
        return np.linalg.solve(self.compliance(), p.T).T

    def midplane_displacements(self, forces: object) -> np.ndarray:
        """Displacements (n_nodes, 3) [mm] of the planar mesh nodes for one force vector (6,)."""
        return self.midplane_of(self.solve_reduced(forces)[:, 0])

    def midplane_shapes(self, forces: object) -> np.ndarray:
        """Mid-plane displacements (n, n_nodes, 3) [mm] for force vectors (n, 6) [N].

        One back-substitution for all of them; e.g. the shapes of given stage poses are
        ``midplane_shapes(forces_for_poses(poses))`` (Fig 3).
        """
        reduced = self.solve_reduced(forces)
        return np.stack([self.midplane_of(reduced[:, i]) for i in range(reduced.shape[1])])

    def midplane_of(self, reduced: np.ndarray) -> np.ndarray:
        """Mid-plane displacements (n_nodes, 3) [mm] of one reduced displacement vector."""
        full = self.fe.pb.get_variables().make_full_vec(reduced).reshape(-1, self.fe.n_comp)
        n = len(self.planar.nodes)
        vert = full[: len(self.fe.coors), :3]
        return 0.5 * (vert[:n] + vert[n : 2 * n]) if self.element == "q2" else vert[:n]


def model_maker(
    *, young: float, poisson: float, element: str, mesh_fraction: float
) -> Callable[..., HexFlexModel]:
    """``make(g, **kwargs) -> HexFlexModel`` with these settings and flexure elements
    ``mesh_fraction`` of ``g``'s narrowest width (one model recipe for a whole study); the
    settings are checked here (:func:`check_settings`), before any model is built."""
    young, poisson, element, mesh_fraction = check_settings(young, poisson, element, mesh_fraction)
    return partial(
        _make_model, young=young, poisson=poisson, element=element, mesh_fraction=mesh_fraction
    )


def compliance_maker(
    make: Callable[..., HexFlexModel],
) -> Callable[[geo.HexFlexGeometry], np.ndarray]:
    """Geometry → 6 × 6 compliance of the model that ``make`` builds (e.g. :func:`model_maker`'s
    recipe): the FE side of :func:`mechlib.hexflex.identify.identify` and ``log_sensitivity``."""
    return partial(_compliance_of, make)


def _compliance_of(make: Callable[..., HexFlexModel], g: geo.HexFlexGeometry) -> np.ndarray:
    return make(g).compliance()


def _make_model(g: geo.HexFlexGeometry, *, mesh_fraction: float, **kwargs) -> HexFlexModel:
    return HexFlexModel(g, mesh_size=mesh_fraction * g.narrowest, **kwargs)


def check_forces(name: str, forces: object) -> np.ndarray:
    """Actuator forces ``name`` as an (n, 6) array of finite values within ``±MAX_FORCE_N`` [N]
    (the one force bound of the FE models and the experiment runner)."""
    f = check_matrix(name, forces, shape=(None, 6))
    worst = float(np.abs(f).max(initial=0.0))
    if worst > MAX_FORCE_N:
        raise ValueError(
            f"{name} must lie in [-{MAX_FORCE_N:g}, {MAX_FORCE_N:g}], got |force| = {worst:g}"
        )
    return f


def coarsening_for(coarse_widths: float, fraction: float) -> float:
    """The ``coarsening`` that makes the largest element ``coarse_widths`` narrowest flexure
    widths when the flexure elements are ``fraction`` of that width (at least 1)."""
    return max(1.0, coarse_widths / fraction)
