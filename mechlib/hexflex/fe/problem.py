"""The SfePy problem of one HexFlex geometry: mesh, regions, field, clamp, actuator loads, pose.

Two element kinds on the same planar quad mesh:

- ``"q2"`` (reference): one layer of 27-node (Q2) hexahedra through the thickness — linear
  hexahedra lock in bending (``../shared/TOOLCHAIN.md``);
- ``"shell"``: SfePy's ``shell10x`` Reissner–Mindlin shell (the thesis used shells in ANSYS).

Regions: ``Ground`` (the radial segments' outer ends, clamped: the grounded zone is rigid) and
``Edge0..2`` (each tab's external edge, where its two actuators push). An actuator force is a
uniform traction over the edge's end face (Q2) or a uniform line load along the edge (shell,
lumped to the nodes with the edge lengths as weights): both θ entries of the compliance scale
with the load's radius, so the load sits where the thesis puts the actuators (sec. 2.6.1).
Units: mm, N, MPa (N/mm²).
"""

from __future__ import annotations

from dataclasses import dataclass
from dataclasses import field as dataclass_field  # `field` is an FEProblem attribute
from typing import Any

import numpy as np

from mechlib.fe.pose import fit_operator
from mechlib.fe.sfepy_base import QUAD_ORDER, integral, quiet_sfepy
from mechlib.hexflex import geometry as geo
from mechlib.hexflex.fe import mesh as ms

ELEMENTS: tuple[str, ...] = ("q2", "shell")
#: Shell drilling stiffness factor (SfePy's shell10x examples).
SHELL_DRILL = 1e-7
#: Parts of the moving body (stiffened by ``body_factor``); the others are the beams.
BODY_PARTS: tuple[str, ...] = ("stage", "tab")
#: Relative tolerance of the region selections (coordinates on a cut line or an edge).
_REGION_TOL = 1e-6


@dataclass
class FEProblem:
    """The assembled pieces of one SfePy problem (see :func:`build`), given by name.

    ``loads`` is not given: it is computed on construction, the reduced load vectors of unit
    actuator forces at the tabs' edges of ``geometry`` (:func:`unit_loads`).
    """

    pb: Any
    field: Any
    u: Any
    v: Any
    material: Any
    omega: Any
    edges: list[Any]
    coors: np.ndarray
    eq: np.ndarray
    n_comp: int
    cell_parts: np.ndarray
    fit: np.ndarray
    stage_idx: np.ndarray
    geometry: geo.HexFlexGeometry
    loads: np.ndarray = dataclass_field(init=False, repr=False)

    def __post_init__(self) -> None:
        self.loads = unit_loads(self, self.geometry)

    @property
    def n_dofs(self) -> int:
        """Number of free degrees of freedom (after clamping the ground)."""
        return int(self.eq.max()) + 1


def build(
    g: geo.HexFlexGeometry,
    planar: ms.PlanarMesh,
    element: str,
    young: float,
    poisson: float,
    body_factor: float = 1.0,
) -> FEProblem:
    """The linear-elastic SfePy problem of ``g`` on ``planar`` with the ground clamped.

    ``body_factor`` multiplies the stiffness of the stage and tabs (not the beams): 1 is the real
    part; a large value makes the body nearly rigid, as the reduced beam model assumes.
    """
    quiet_sfepy()  # before the first SfePy import prints its notices
    from sfepy.discrete import Equation, Equations, FieldVariable, Function, Problem
    from sfepy.discrete.conditions import Conditions, EssentialBC
    from sfepy.discrete.fem import FEDomain, Field, Mesh
    from sfepy.mechanics.matcoefs import stiffness_from_youngpoisson
    from sfepy.terms import Term

    parts = _cell_parts(g, planar)
    if element == "q2":
        coors, cells = ms.extrude(planar, g.thickness)
        desc = "3_8"
    else:
        coors, cells = np.c_[planar.nodes, np.zeros(len(planar.nodes))], planar.quads
        desc = "2_4"
    mesh = Mesh.from_data(
        "hexflex",
        np.ascontiguousarray(coors),
        np.zeros(len(coors), dtype=np.int32),
        [cells.astype(np.int32)],
        [(1 + parts).astype(np.int32)],
        [desc],
    )
    domain = FEDomain("hexflex", mesh)
    omega = domain.create_region("Omega", "all")
    select = {"ground": lambda c, domain=None: np.flatnonzero(ground_vertices(c, g))}
    for k in range(3):
        select[f"edge{k}"] = lambda c, domain=None, k=k: np.flatnonzero(edge_vertices(c, g, k))
    funcs = {name: Function(name, f) for name, f in select.items()}
    gamma = domain.create_region("Ground", "vertices by ground", "facet", functions=funcs)
    kind = "facet" if element == "q2" else "vertex"
    edges = [
        domain.create_region(f"Edge{k}", f"vertices by edge{k}", kind, functions=funcs)
        for k in range(3)
    ]
    if element == "q2":
        fld = Field.from_args("fu", np.float64, "vector", omega, approx_order=2)
        elastic = stiffness_from_youngpoisson(3, young, poisson)
    else:
        import sfepy.mechanics.shell10x as sh

        fld = Field.from_args(
            "fu", np.float64, 6, omega, approx_order=1, poly_space_basis="shell10x"
        )
        elastic = sh.create_elastic_tensor(young=young, poisson=poisson)
    u = FieldVariable("u", "unknown", fld)
    v = FieldVariable("v", "test", fld, primary_var_name="u")
    mat = _material("m", elastic, element)
    if body_factor == 1.0:
        pieces = [(omega, mat)]
    else:  # the stage and tabs scaled, the beams as they are
        body = " +c ".join(f"cells of group {1 + geo.PARTS.index(p)}" for p in BODY_PARTS)
        flex = " +c ".join(
            f"cells of group {1 + i}" for i, p in enumerate(geo.PARTS) if p not in BODY_PARTS
        )
        pieces = [
            (domain.create_region("Body", body), _material("mb", body_factor * elastic, element)),
            (domain.create_region("Flex", flex), mat),
        ]
    term = None
    for region, m in pieces:
        if element == "q2":
            t = Term.new(f"dw_lin_elastic({m.name}.D, v, u)", integral(), region, v=v, u=u,
                         **{m.name: m})  # fmt: skip
        else:
            t = Term.new(f"dw_shell10x({m.name}.D, {m.name}.drill, v, u)", _shell_integral(g),
                         region, v=v, u=u, **{m.name: m})  # fmt: skip
        term = t if term is None else term + t
    pb = Problem("hexflex", equations=Equations([Equation("balance", term)]))
    pb.set_bcs(ebcs=Conditions([EssentialBC("clamp", gamma, {"u.all": 0.0})]))
    pb.time_update()
    vert = np.asarray(fld.get_coor()[: fld.n_vertex_dof], dtype=float)
    n_comp = 3 if element == "q2" else 6
    eq = pb.get_variables()["u"].eq_map.eq
    stage = geo.in_stage(vert, g)
    stage_idx = eq.reshape(-1, n_comp)[: len(vert)][stage, :3].ravel()
    if np.any(stage_idx < 0):
        raise RuntimeError("stage nodes are clamped: geometry error")
    return FEProblem(
        pb=pb,
        field=fld,
        u=u,
        v=v,
        material=mat,
        omega=omega,
        edges=edges,
        coors=vert,
        eq=eq,
        n_comp=n_comp,
        cell_parts=parts,
        fit=fit_operator(vert[stage]),
        stage_idx=stage_idx,
        geometry=g,
    )


def _material(name: str, elastic: np.ndarray, element: str):
    """SfePy material with the elasticity tensor (and the shell's drilling factor)."""
    from sfepy.discrete import Material

    if element == "q2":
        return Material(name, D=elastic)
    return Material(name, D=elastic, values={".drill": SHELL_DRILL})


def _cell_parts(g: geo.HexFlexGeometry, planar: ms.PlanarMesh) -> np.ndarray:
    """Part index (into ``geometry.PARTS``) of every quad, by its centroid."""
    centroids = planar.nodes[planar.quads].mean(axis=1)
    part = geo.classify(centroids, g)
    lost = part < 0  # a coarse cell spanning a re-entrant corner: its centroid is outside
    if np.all(lost):
        raise RuntimeError("mesh cells outside the planform: geometry and mesh disagree")
    if np.any(lost):
        from scipy.spatial import cKDTree

        _, near = cKDTree(centroids[~lost]).query(centroids[lost])
        part[lost] = part[~lost][near]
    return part


def ground_vertices(coors: np.ndarray, g: geo.HexFlexGeometry) -> np.ndarray:
    """True for points on the clamped ends of the radial segments (any leg)."""
    r, s = geo.local_coordinates(coors)
    tol = _REGION_TOL * g.tab_outer
    inner = g.corner_s - 0.5 * g.radial_width - tol
    return np.any((r >= g.ground_radius - tol) & (np.abs(s) >= inner), axis=1)


def edge_vertices(coors: np.ndarray, g: geo.HexFlexGeometry, k: int) -> np.ndarray:
    """True for points on tab ``k``'s external edge (where its actuators act)."""
    r, s = geo.local_coordinates(coors)
    tol = _REGION_TOL * g.tab_outer
    return (r[:, k] >= g.tab_outer - tol) & (np.abs(s[:, k]) <= g.tab_half_width + tol)


def _shell_integral(g: geo.HexFlexGeometry):
    from sfepy.discrete import Integral

    aux = Integral("i", order=3)
    qp_coors, qp_weights = aux.get_qp("3_8")
    qp_coors[:, 2] = g.thickness * (qp_coors[:, 2] - 0.5)
    return Integral("i", coors=qp_coors, weights=qp_weights * g.thickness, order="custom")


def unit_loads(prob: FEProblem, g: geo.HexFlexGeometry) -> np.ndarray:
    """Reduced load vectors (n_dofs, 6) of unit actuator forces at the tabs' external edges."""
    dirs = geo.actuator_directions()
    out = np.zeros((prob.n_dofs, 6))
    for j in range(6):
        k = j // 2
        out[:, j] = edge_load(prob, k, dirs[j], g)
    return out


def edge_load(prob: FEProblem, k: int, force: np.ndarray, g: geo.HexFlexGeometry) -> np.ndarray:
    """Reduced load vector of the force (3,) [N] spread uniformly over tab ``k``'s edge."""
    red = np.zeros(prob.n_dofs)
    if prob.n_comp == 3:  # Q2: uniform traction over the end face, normalised to the total
        from sfepy.discrete import Material

        vec = prob.pb.evaluate(
            f"dw_surface_ltr.{QUAD_ORDER}.Edge{k}(f.val, v)",
            mode="weak",
            dw_mode="vector",
            f=Material("f", val=np.ones((3, 1))),
            v=prob.v,
            copy_materials=False,
        )
        dofs = prob.eq.reshape(-1, 3)  # every DOF node (vertices, edges, faces, bubbles)
        free = dofs[:, 0] >= 0
        weights = np.zeros(len(dofs))
        weights[free] = vec[dofs[free, 0]]
        weights /= weights.sum()
        for c in range(3):
            red[dofs[free, c]] = weights[free] * force[c]
        return red
    idx = np.flatnonzero(edge_vertices(prob.coors, g, k))
    _, s = geo.local_coordinates(prob.coors[idx])
    order = np.argsort(s[:, k])
    seg = np.diff(s[order, k])
    w = np.zeros(len(idx))
    w[order[:-1]] += 0.5 * seg
    w[order[1:]] += 0.5 * seg
    full = np.zeros((len(prob.coors), prob.n_comp))
    full[idx, :3] = (w / w.sum())[:, None] * np.asarray(force)[None, :]
    dofs = prob.eq.reshape(-1, prob.n_comp)[: len(prob.coors)]
    ok = dofs >= 0
    red[dofs[ok]] = full[ok]
    return red
