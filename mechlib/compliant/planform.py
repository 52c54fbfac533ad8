"""The quad mesh of a mechanism's planform (gmsh) and its extrusion to hexahedra.

Each part is a plane surface; gmsh's boolean fragment makes the parts share their common edges,
so the mesh is conforming across them. Quads come from gmsh's Frontal-Delaunay algorithm for
quads with Blossom recombination, or where that leaves triangles (a part as wide as an element),
with Blossom "full-quad" recombination (every element split in four: smaller elements, e.g.
3.75 mm in the parallelogram's beams and 4.85 mm in its stage at 5 mm); a part
given with its own element size keeps it. The mesh is refused if a triangle is left or a quad is
inverted.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechlib.compliant.layout import Layout
from mechlib.params import check_float, check_int

#: gmsh's 2-D algorithm "Frontal-Delaunay for quads", and its recombinations tried in turn:
#: "Blossom", then "Blossom full-quad" (measured on the parallelogram: the first leaves triangles
#: at 5 and 4 mm, the second cannot divide the 10 and 7.5 mm meshes)
GMSH_ALGORITHM, GMSH_RECOMBINATIONS = 8, (1, 3)
#: gmsh element type of 4-node quads.
QUAD_TYPE = 3


@dataclass(frozen=True)
class Planform:
    """All-quad planar mesh: ``nodes`` (n, 2) [mm], ``quads`` (m, 4) counter-clockwise, and the
    index (into ``Layout.names``) of the part each quad belongs to, ``parts`` (m,)."""

    nodes: np.ndarray
    quads: np.ndarray
    parts: np.ndarray


def mesh_planform(layout: Layout, size: float) -> Planform:
    """The planform of ``layout`` meshed with quads of about ``size`` mm (each part its own
    size if ``layout.mesh_sizes`` gives one).

    Raises
    ------
    ValueError
        If ``size`` is not > 0, or the mesh cannot be made all of valid quads.
    """

    size = check_float("mesh_size [mm]", size, low=0.0, low_open=True)
    for recombination in GMSH_RECOMBINATIONS:
        try:
            return _mesh(layout, size, recombination)
        except ValueError as err:
            failure = err
    raise failure


def _mesh(layout: Layout, size: float, recombination: int) -> Planform:
    import gmsh

    own = dict(layout.mesh_sizes)
    gmsh.initialize(readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("planform")
        occ = gmsh.model.occ
        tags = []
        for name in layout.names:
            pts = [occ.addPoint(x, y, 0.0) for x, y in layout.polygon(name)]
            lines = [occ.addLine(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts))]
            tags.append(occ.addPlaneSurface([occ.addCurveLoop(lines)]))
        _, pieces = occ.fragment([(2, t) for t in tags], [])
        occ.synchronize()
        surface_part = {}
        for k, name in enumerate(layout.names):
            for dim, tag in pieces[k]:
                surface_part[tag] = k
                part_size = float(own.get(name, size))
                points = gmsh.model.getBoundary([(dim, tag)], recursive=True)
                gmsh.model.mesh.setSize(points, part_size)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 1)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 1)
        gmsh.option.setNumber("Mesh.Algorithm", GMSH_ALGORITHM)
        gmsh.option.setNumber("Mesh.RecombineAll", 1)
        gmsh.option.setNumber("Mesh.RecombinationAlgorithm", recombination)
        try:
            gmsh.model.mesh.generate(2)
        except Exception as err:  # gmsh raises a bare Exception with its message
            raise ValueError(f"gmsh could not mesh the planform at {size:g} mm: {err}") from err
        node_tags, coords, _ = gmsh.model.mesh.getNodes()
        index = np.full(int(node_tags.max()) + 1, -1, dtype=np.int64)
        index[node_tags.astype(np.int64)] = np.arange(len(node_tags))
        nodes = coords.reshape(-1, 3)[:, :2]
        quads, parts = [], []
        for _, tag in gmsh.model.getEntities(2):
            types, _, conn = gmsh.model.mesh.getElements(2, tag)
            if set(types.tolist()) != {QUAD_TYPE}:
                raise ValueError(
                    f"the mesh of part {layout.names[surface_part[tag]]!r} is not all quads at "
                    f"mesh_size {size:g} mm: use another size"
                )
            q = index[conn[0].astype(np.int64)].reshape(-1, 4)
            quads.append(q)
            parts.append(np.full(len(q), surface_part[tag]))
    finally:
        gmsh.finalize()
    quads, parts = np.vstack(quads), np.concatenate(parts)
    used = np.unique(quads)
    renumber = np.full(len(nodes), -1, dtype=np.int64)
    renumber[used] = np.arange(len(used))
    quads, nodes = renumber[quads], nodes[used]
    quads = _counter_clockwise(nodes, quads)
    return Planform(np.ascontiguousarray(nodes), quads, parts.astype(np.int64))


def _counter_clockwise(nodes: np.ndarray, quads: np.ndarray) -> np.ndarray:
    """``quads`` reordered counter-clockwise; refused if one is not convex (inverted)."""
    p = nodes[quads]
    e1 = np.roll(p, -1, axis=1) - p
    e0 = p - np.roll(p, 1, axis=1)
    cross = e0[..., 0] * e1[..., 1] - e0[..., 1] * e1[..., 0]
    flip = cross.sum(axis=1) < 0
    quads = np.where(flip[:, None], quads[:, ::-1], quads)
    cross = np.where(flip[:, None], -cross, cross)
    if np.any(cross <= 0):
        raise ValueError(f"{int(np.sum(np.any(cross <= 0, axis=1)))} quads are not convex")
    return quads


def extrude(planform: Planform, thickness: float, layers: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """Hexahedra through ``thickness`` [mm] in ``layers`` equal layers, mid-plane at z = 0.

    Returns
    -------
    coors : ndarray (n (layers + 1), 3)
        Node coordinates [mm], layer by layer from the bottom.
    hexes : ndarray (m layers, 8)
        SfePy ``3_8`` order (bottom face counter-clockwise seen from +z, then top), layer by
        layer; hex ``i`` of a layer lies on quad ``i % m``.
    """
    layers = check_int("layers", layers, low=1, high=64)
    n = len(planform.nodes)
    z = np.linspace(-0.5 * thickness, 0.5 * thickness, layers + 1)
    coors = np.vstack([np.c_[planform.nodes, np.full(n, zk)] for zk in z])
    q = planform.quads
    hexes = np.vstack([np.hstack([q + k * n, q + (k + 1) * n]) for k in range(layers)])
    return coors, hexes
