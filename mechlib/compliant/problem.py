"""The SfePy problem of a mechanism: Q2 hexahedra, named regions, unit load vectors, stage fit.

Regions: ``Omega``; ``Clamp`` (the facets on the clamp segments' extruded faces, fixed);
``Load0…`` (the facets on each load's segment). A force port's load vector is a uniform traction
of unit resultant along its direction; a couple port's a traction normal to its face, varying
linearly along the segment from zero at its middle, scaled so that the nodal forces' moment
about the z axis through the origin is 1 N·mm counter-clockwise (zero net force: the shape
functions sum to one). The stage's vertices are fitted by a rigid motion about the origin.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mechlib.compliant.layout import TOL, Layout
from mechlib.compliant.planform import Planform, extrude
from mechlib.fe.pose import fit_operator
from mechlib.fe.sfepy_base import QUAD_ORDER, integral, quiet_sfepy


@dataclass
class MechanismProblem:
    """The assembled pieces of one SfePy problem of a :class:`Layout` (see :func:`build`)."""

    pb: Any
    field: Any
    u: Any
    v: Any
    omega: Any
    coors: np.ndarray
    eq: np.ndarray
    cell_parts: np.ndarray
    stage_vertices: np.ndarray
    stage_idx: np.ndarray
    fit: np.ndarray
    loads: np.ndarray
    n_comp: int = 3

    @property
    def n_dofs(self) -> int:
        """Number of free degrees of freedom (after clamping)."""
        return int(self.eq.max()) + 1


def _on_segment(coors: np.ndarray, seg: object, tol: float) -> np.ndarray:
    """True for points whose (x, y) lie on segment ``seg`` (any z)."""
    a, b = np.asarray(seg, dtype=float)
    d = b - a
    length = float(np.linalg.norm(d))
    u = d / length
    rel = coors[:, :2] - a
    along = rel @ u
    across = rel @ np.array([-u[1], u[0]])
    return (np.abs(across) <= tol) & (along >= -tol) & (along <= length + tol)


def _check_coverage(name: str, segment: object, points: np.ndarray, tol: float) -> None:
    """Refuse a region whose facets do not cover its segment end to end (an end that is no
    vertex of the mesh: the facets across it are not selected, and the load would act on less
    than its face)."""
    a, b = np.asarray(segment, dtype=float)
    length = float(np.linalg.norm(b - a))
    on = points[_on_segment(points, segment, tol)]
    along = (on[:, :2] - a) @ ((b - a) / length) if len(on) else np.zeros(0)
    covered = float(np.ptp(along)) if len(along) > 1 else 0.0
    if covered < length - tol:
        raise ValueError(
            f"the {name} {np.asarray(segment).tolist()} is covered by facets over {covered:.4g} "
            f"of its {length:.4g} mm on this mesh: its ends must be corners of the parts (or "
            f"where parts meet)"
        )


def _selector(segments: list, tol: float):
    """SfePy region function: the vertices on any of ``segments``."""

    def select(coors: np.ndarray, domain=None) -> np.ndarray:
        return np.flatnonzero(np.any([_on_segment(coors, s, tol) for s in segments], axis=0))

    return select


def build(layout: Layout, planform: Planform, layers: int = 1) -> MechanismProblem:
    """The linear-elastic SfePy problem of ``layout`` on ``planform`` extruded in ``layers``.

    Raises
    ------
    ValueError
        If a clamp or load segment is not covered end to end by facets of this mesh (named),
        or the stage touches the clamp.
    """
    quiet_sfepy()
    from sfepy.discrete import Equation, Equations, FieldVariable, Function, Material, Problem
    from sfepy.discrete.conditions import Conditions, EssentialBC
    from sfepy.discrete.fem import FEDomain, Field, Mesh
    from sfepy.mechanics.matcoefs import stiffness_from_youngpoisson
    from sfepy.terms import Term

    coors, hexes = extrude(planform, layout.thickness, layers)
    parts = np.tile(planform.parts, layers)
    mesh = Mesh.from_data(
        "mechanism", np.ascontiguousarray(coors), np.zeros(len(coors), dtype=np.int32),
        [hexes.astype(np.int32)], [(1 + parts).astype(np.int32)], ["3_8"],
    )  # fmt: skip
    domain = FEDomain("mechanism", mesh)
    omega = domain.create_region("Omega", "all")
    tol = TOL * layout.span * 1e3
    segments = {"clamp": list(layout.clamp)}
    segments |= {f"load{k}": [ld.segment] for k, ld in enumerate(layout.loads)}
    funcs = {name: Function(name, _selector(segs, tol)) for name, segs in segments.items()}
    clamp = domain.create_region("Clamp", "vertices by clamp", "facet", functions=funcs)
    faces = [
        domain.create_region(f"Load{k}", f"vertices by load{k}", "facet", functions=funcs)
        for k in range(len(layout.loads))
    ]
    named = [("clamp segment", s, clamp) for s in layout.clamp]
    named += [
        (f"load {ld.name!r}", ld.segment, f) for ld, f in zip(layout.loads, faces, strict=True)
    ]
    for name, seg, region in named:
        _check_coverage(name, seg, mesh.coors[region.vertices], tol)
    fld = Field.from_args("fu", np.float64, "vector", omega, approx_order=2)
    u = FieldVariable("u", "unknown", fld)
    v = FieldVariable("v", "test", fld, primary_var_name="u")
    term = None
    for k, name in enumerate(layout.names):
        if not np.any(planform.parts == k):
            continue
        region = omega if layout.one_material else domain.create_region(
            f"Part{k}", f"cells of group {k + 1}")  # fmt: skip
        mat = Material(
            f"m{k}", D=stiffness_from_youngpoisson(3, layout.young_of(name), layout.poisson)
        )
        t = Term.new(
            f"dw_lin_elastic(m{k}.D, v, u)", integral(), region, v=v, u=u, **{f"m{k}": mat}
        )
        term = t if term is None else term + t
        if layout.one_material:
            break
    pb = Problem("mechanism", equations=Equations([Equation("balance", term)]))
    pb.set_bcs(ebcs=Conditions([EssentialBC("clamp", clamp, {"u.all": 0.0})]))
    pb.time_update()
    vert = np.asarray(fld.get_coor()[: fld.n_vertex_dof], dtype=float)
    eq = pb.get_variables()["u"].eq_map.eq
    stage_parts = [layout.names.index(s) for s in layout.stage]
    on_stage = np.zeros(len(vert), dtype=bool)
    on_stage[np.unique(hexes[np.isin(parts, stage_parts)])] = True
    stage_idx = eq.reshape(-1, 3)[: len(vert)][on_stage].ravel()
    if np.any(stage_idx < 0):
        raise ValueError("the stage touches the clamp: its nodes are fixed")
    prob = MechanismProblem(
        pb=pb, field=fld, u=u, v=v, omega=omega, coors=vert, eq=eq, cell_parts=parts,
        stage_vertices=np.flatnonzero(on_stage), stage_idx=stage_idx,
        fit=fit_operator(vert[on_stage]), loads=np.zeros((0, 0)),
    )  # fmt: skip
    prob.loads = np.column_stack([_port_load(prob, layout, k) for k in range(len(layout.loads))])
    return prob


def _port_load(prob: MechanismProblem, layout: Layout, k: int) -> np.ndarray:
    """Reduced load vector of load port ``k`` at unit magnitude."""
    from sfepy.discrete import Function, Material

    ld = layout.loads[k]
    a, b = np.asarray(ld.segment, dtype=float)
    tangent = (b - a) / np.linalg.norm(b - a)
    normal = np.array([tangent[1], -tangent[0], 0.0])
    mid = 0.5 * (a + b)

    def traction(ts, coors, mode=None, **kwargs):
        if mode != "qp":
            return None
        s = (coors[:, :2] - mid) @ tangent
        if ld.kind == "force":
            s = np.ones_like(s)
        return {"val": (s[:, None] * normal[None, :])[..., None]}

    mat = Material("f", function=Function("traction", traction))
    vec = prob.pb.evaluate(
        f"dw_surface_ltr.{QUAD_ORDER}.Load{k}(f.val, v)", mode="weak", dw_mode="vector",
        f=mat, v=prob.v, copy_materials=False,
    )  # fmt: skip
    dofs = prob.eq.reshape(-1, 3)
    free = dofs[:, 0] >= 0
    nodal = np.zeros((len(dofs), 3))
    nodal[free] = vec[dofs[free]]
    red = np.zeros(prob.n_dofs)
    if ld.kind == "force":  # the traction's pattern, along the direction, unit resultant
        weights = nodal @ normal
        direction = np.asarray(ld.direction, dtype=float)
        direction = direction / np.linalg.norm(direction)
        for c in range(3):
            red[dofs[free, c]] = weights[free] / weights.sum() * direction[c]
        return red
    xy = np.asarray(prob.field.get_coor(), dtype=float)[:, :2]
    moment = float(np.sum(xy[:, 0] * nodal[:, 1] - xy[:, 1] * nodal[:, 0]))
    red[dofs[free].ravel()] = (nodal[free] / moment).ravel()
    return red
