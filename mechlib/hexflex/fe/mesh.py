"""Quad mesh of one sixth of the planform (gmsh) completed by symmetry, and its hex extrusion.

As in the thesis (sec. 2.6.1), one sixth of the mechanism is meshed — the wedge between T1's
axis (90°) and the stage edge's midline (30°) — and the whole is obtained by one reflection
(about the T1 axis) and two rotations by 120°; coincident nodes on the cut lines are merged.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from mechlib.hexflex.geometry import HexFlexGeometry
from mechlib.params import check_float

#: Element growth from the flexures to the stage and tabs.
COARSENING = 4.0
#: Length-to-width ratio of the structured elements at the ends of the beams and links.
BEAM_ASPECT = 2.0
#: Length of the structured elements mid-way along a flexure, in flexure widths: the joints at
#: the ends carry the stress concentrations, the prismatic middle is smooth.
MID_WIDTHS = 2.0
#: Elements per (length / middle size) of a graded flexure: gmsh's "Bump" spacing with end/middle
#: ratio c puts ≈ 1.6–2.2 × length / n mid-way for c in [0.05, 0.2] (measured).
BUMP_FACTOR = 2.2
#: Nodes closer than this fraction of the element size are merged.
MERGE_TOL = 1e-6


@dataclass(frozen=True)
class PlanarMesh:
    """All-quad planar mesh: ``nodes`` (n, 2) in mm, ``quads`` (m, 4) counter-clockwise."""

    nodes: np.ndarray
    quads: np.ndarray


def structured_pieces(
    g: HexFlexGeometry, size: float, mid_widths: float = MID_WIDTHS
) -> list[tuple[tuple, tuple, tuple]]:
    """The flexure rectangles of the half-leg and their structured gmsh grids.

    Returns
    -------
    list of (rect, s_spec, r_spec)
        ``rect`` = ``(r0, r1, s0, s1)`` [mm]; ``s_spec`` and ``r_spec`` = ``(nodes, bump)`` of the
        curves running along ``s`` and along ``r``: gmsh node count (before the all-quad
        subdivision doubles the elements) and the "Bump" end/middle ratio, or None for uniform.
        Shared curves get the same count: the corner takes the D1 segment's count across it
        along ``r`` and the radial segment's along ``s``. ``mid_widths``: the elements' length
        mid-way along a flexure, in its widths (``sector_mesh``).
    """
    rects = g.rectangles()
    (beam,), (corner,), (radial,) = rects["beam"], rects["corner"], rects["radial"]
    across_b = _across(g.beam_width, size)
    across_r = _across(g.radial_width, size)
    along_b = _along(g.beam_width, across_b, beam[3] - beam[2], mid_widths)
    along_r = _along(g.radial_width, across_r, radial[1] - radial[0], mid_widths)
    return [
        (beam, along_b, (across_b + 1, None)),
        (corner, (across_r + 1, None), (across_b + 1, None)),
        (radial, (across_r + 1, None), along_r),
    ]


def _across(width: float, size: float) -> int:
    """gmsh elements across a flexure (doubled by the subdivision: an even count >= 2)."""
    return int(np.ceil(width / (2 * size) - 1e-9))


def _along(width: float, across: int, length: float, mid_widths: float) -> tuple[int, float | None]:
    """gmsh nodes along a flexure and its bump ratio (None: uniform)."""
    end, middle = _along_sizes(width, across, mid_widths)
    if end / middle < 1.0 and length > 4 * middle:  # graded: `end` at both ends, ~`middle` mid-way
        return int(np.ceil(BUMP_FACTOR * length / middle)) + 1, end / middle
    return int(np.ceil(length / end - 1e-9)) + 1, None


def sector_mesh(
    g: HexFlexGeometry,
    size: float,
    coarsening: float = COARSENING,
    body_grading: float | None = None,
    mid_widths: float = MID_WIDTHS,
) -> PlanarMesh:
    """All-quad mesh of the 30°–90° sector: structured in the flexures, free elsewhere.

    Every flexure segment (D1 segment, corner, radial segment) is a structured grid with an even
    number of elements across its width (at most ``size`` [mm] wide, at least two); along it
    the elements are ``BEAM_ASPECT`` times longer than wide at both ends and grow toward
    ``mid_widths`` flexure widths mid-way (default ``MID_WIDTHS``, in [``BEAM_ASPECT``, 8]).
    The stage and tab are meshed freely with elements growing from ``size`` at the flexures'
    corners to ``coarsening * size``: by default the sizes set at the corners are interpolated
    along the boundary curves; with ``body_grading`` [mm/mm] the size grows
    linearly with the distance ``d`` from the nearest flexure corner, ``size + body_grading *
    d``, capped at ``coarsening * size`` (the nearly rigid stage and tabs can then take much
    larger elements without coarsening the joints).

    Raises
    ------
    ValueError
        If ``size`` is larger than the narrowest flexure or not positive, or ``mid_widths`` or
        ``body_grading`` is out of range.
    """
    size = check_float("mesh_size [mm]", size, low=0.0, high=g.narrowest, low_open=True)
    import gmsh

    mid_widths = check_float("mid_widths", mid_widths, low=BEAM_ASPECT, high=8.0)
    if body_grading is not None:
        body_grading = check_float("body_grading", body_grading, low=0.0, low_open=True)
    pieces = structured_pieces(g, size, mid_widths)
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("hexflex_sector")
        occ = gmsh.model.occ
        tags, fine = [], []
        for part_rects in g.rectangles().values():
            for r0, r1, s0, s1 in part_rects:  # leg T1: global (x, y) = (s, r)
                tags.append((2, occ.addRectangle(s0, r0, 0.0, s1 - s0, r1 - r0)))
        for (r0, r1, s0, s1), _, _ in pieces:
            fine += [(s0, r0), (s1, r0), (s0, r1), (s1, r1)]
        mid = 0.5 * g.stage_radius * np.array([np.cos(np.pi / 6), np.sin(np.pi / 6)])
        pts = [occ.addPoint(0, 0, 0), occ.addPoint(*mid, 0), occ.addPoint(0, g.stage_radius, 0)]
        lines = [occ.addLine(pts[i], pts[(i + 1) % 3]) for i in range(3)]
        tags.append((2, occ.addPlaneSurface([occ.addCurveLoop(lines)])))
        occ.fragment(tags[:1], tags[1:])
        occ.synchronize()
        occ.removeAllDuplicates()
        occ.synchronize()
        surfaces = gmsh.model.getEntities(2)
        gmsh.model.addPhysicalGroup(2, [t for _, t in surfaces])
        # sizes handed to gmsh are doubled: the all-quad subdivision below halves every element
        for dim, tag in surfaces:
            s_c, r_c, _ = occ.getCenterOfMass(dim, tag)
            for (r0, r1, s0, s1), s_spec, r_spec in pieces:
                if not (r0 < r_c < r1 and s0 < s_c < s1):
                    continue
                for _, curve in gmsh.model.getBoundary([(dim, tag)], oriented=False):
                    x0, y0, _, x1, y1, _ = gmsh.model.getBoundingBox(1, curve)
                    nodes, bump = s_spec if (x1 - x0) > (y1 - y0) else r_spec
                    if bump is None:
                        gmsh.model.mesh.setTransfiniteCurve(curve, nodes)
                    else:
                        gmsh.model.mesh.setTransfiniteCurve(curve, nodes, "Bump", bump)
                gmsh.model.mesh.setTransfiniteSurface(tag)
        coarse = max(size, coarsening * size)
        fine_xy = np.asarray(fine)
        near_tags = []
        for dim_tag in gmsh.model.getEntities(0):
            xyz = gmsh.model.getValue(0, dim_tag[1], [])
            near = np.min(np.hypot(*(fine_xy - xyz[:2]).T)) < 1e-6 * g.tab_outer
            if near:
                near_tags.append(dim_tag[1])
            gmsh.model.mesh.setSize([dim_tag], 2 * (size if near else coarse))
        gmsh.option.setNumber("Mesh.MeshSizeMax", 2 * coarse)
        if body_grading is None:
            gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 1)
        else:
            _graded_field(gmsh, near_tags, 2 * size, 2 * coarse, body_grading)
        gmsh.option.setNumber("Mesh.Algorithm", 8)
        gmsh.option.setNumber("Mesh.RecombineAll", 1)
        gmsh.option.setNumber("Mesh.SubdivisionAlgorithm", 1)  # all quads
        gmsh.option.setNumber("Mesh.RandomSeed", 1)
        gmsh.model.mesh.generate(2)
        node_tags, coords, _ = gmsh.model.mesh.getNodes()
        etypes, _, enodes = gmsh.model.mesh.getElements(2)
    finally:
        gmsh.finalize()
    quad_type = 3
    if set(int(e) for e in etypes) != {quad_type}:
        raise RuntimeError(f"gmsh returned non-quad elements: types {list(etypes)}")
    xy = np.asarray(coords).reshape(-1, 3)[:, :2]
    index = {int(t): i for i, t in enumerate(node_tags)}
    quads = np.vectorize(index.__getitem__)(np.asarray(enodes[0]).reshape(-1, 4).astype(int))
    used = np.unique(quads)
    remap = np.full(len(xy), -1)
    remap[used] = np.arange(len(used))
    return _orient(PlanarMesh(xy[used], remap[quads]))


def _graded_field(gmsh, point_tags: list[int], small: float, large: float, grading: float) -> None:
    """Background size field on every surface: ``small`` at the points, growing to ``large``
    (gmsh sizes, before the subdivision halves them) so that the final elements grow by
    ``grading`` per unit distance from the nearest point."""
    field = gmsh.model.mesh.field
    dist = field.add("Distance")
    field.setNumbers(dist, "PointsList", point_tags)
    ramp = field.add("Threshold")
    field.setNumber(ramp, "InField", dist)
    field.setNumber(ramp, "SizeMin", small)
    field.setNumber(ramp, "SizeMax", large)
    field.setNumber(ramp, "DistMin", 0.0)
    field.setNumber(ramp, "DistMax", max((large - small) / (2 * grading), 1e-9))
    field.setAsBackgroundMesh(ramp)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)


def _along_sizes(width: float, across: int, mid_widths: float) -> tuple[float, float]:
    """gmsh element lengths (before the subdivision halves them) at the ends and mid-way."""
    return 2 * BEAM_ASPECT * width / (2 * across), 2 * mid_widths * width


def signed_areas(m: PlanarMesh) -> np.ndarray:
    """Signed area of every quad [mm²] (shoelace; positive when counter-clockwise)."""
    p = m.nodes[m.quads]
    x, y = p[:, :, 0], p[:, :, 1]
    return 0.5 * np.sum(x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y, axis=1)


def _orient(m: PlanarMesh) -> PlanarMesh:
    """Make every quad counter-clockwise."""
    flip = signed_areas(m) < 0
    quads = m.quads.copy()
    quads[flip] = quads[flip][:, ::-1]
    return PlanarMesh(m.nodes, quads)


def _merge(parts: list[PlanarMesh], tol: float) -> PlanarMesh:
    nodes = np.vstack([p.nodes for p in parts])
    offsets = np.cumsum([0] + [len(p.nodes) for p in parts[:-1]])
    quads = np.vstack([p.quads + o for p, o in zip(parts, offsets, strict=True)])
    rep = np.arange(len(nodes))
    for i, j in sorted(cKDTree(nodes).query_pairs(tol)):
        ri, rj = rep[i], rep[j]
        while rep[ri] != ri:
            ri = rep[ri]
        while rep[rj] != rj:
            rj = rep[rj]
        rep[max(ri, rj)] = min(ri, rj)
    for k in range(len(rep)):
        r = k
        while rep[r] != r:
            r = rep[r]
        rep[k] = r
    keep, inverse = np.unique(rep, return_inverse=True)
    return _orient(PlanarMesh(nodes[keep], inverse[quads]))


def full_mesh(sector: PlanarMesh, size: float) -> PlanarMesh:
    """Complete a sector mesh by the reflection x → −x and rotations by 120° and 240°."""
    mirror = PlanarMesh(sector.nodes * np.array([-1.0, 1.0]), sector.quads)
    leg = _merge([sector, mirror], MERGE_TOL * size)
    parts = []
    for k in range(3):
        a = 2 * np.pi * k / 3
        rot = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
        parts.append(PlanarMesh(leg.nodes @ rot.T, leg.quads))
    return _merge(parts, MERGE_TOL * size)


def extrude(m: PlanarMesh, thickness: float) -> tuple[np.ndarray, np.ndarray]:
    """One layer of 8-node hexahedra through the thickness, mid-plane at z = 0.

    Returns
    -------
    coors : ndarray, shape (2 n, 3)
        Bottom nodes first, then top nodes.
    hexes : ndarray, shape (m, 8)
        SfePy ``3_8`` order (bottom face counter-clockwise seen from +z, then top face).
    """
    n = len(m.nodes)
    h = 0.5 * thickness
    coors = np.vstack([np.c_[m.nodes, np.full(n, -h)], np.c_[m.nodes, np.full(n, h)]])
    return coors, np.hstack([m.quads, m.quads + n])
