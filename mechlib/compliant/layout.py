"""The description of a planar compliant mechanism and the checks that refuse a bad one.

A mechanism is a planform in the x-y plane made of named polygonal parts, extruded along z by
``thickness`` (mid-plane at z = 0), with named regions given on the planform's boundary:

- the **clamp**: boundary segments whose extruded faces are fixed;
- the **stage**: the parts that form the moving body whose pose is reported, as translation and
  rotation of the rigid motion that best fits its nodes, about the origin (put the stage's
  reference point at the origin);
- the **loads**: each on one boundary segment of the stage, as a unit force along a direction
  (spread uniformly over the segment's extruded face) or a unit couple about z (a normal
  traction varying linearly along the segment, zero net force); a load vector's entries are the
  loads' magnitudes in their units (N, N·mm);
- optional **material regions**: a Young's modulus per part.

Lengths in mm, forces in N, moduli in MPa. :func:`check_layout` (called on construction) refuses
a part that is not a simple polygon, a planform in pieces, a clamp segment on no face, a stage
in pieces or clamped, and a load off the stage's outer boundary, naming the region and what is
wrong — before any mesh is made.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from mechlib.params import check_float, check_int

#: Load kinds: a force along ``direction``, or a couple about z.
LOAD_KINDS: tuple[str, ...] = ("force", "couple")
#: Geometric tolerance, as a fraction of the planform's size: points closer are the same point.
TOL = 1e-9


@dataclass(frozen=True)
class Load:
    """One load port: ``name``, the boundary ``segment`` ((2, 2) [mm]) of the stage it acts on,
    its ``kind`` (``"force"``: a unit force along ``direction`` (3,), normalised here;
    ``"couple"``: a unit couple about +z, counter-clockwise), its ``unit`` for tables and the
    largest magnitude a model accepts, ``bound`` (in ``unit``)."""

    name: str
    segment: tuple[tuple[float, float], tuple[float, float]]
    kind: str = "force"
    direction: tuple[float, float, float] = (1.0, 0.0, 0.0)
    unit: str = "N"
    bound: float = float("inf")


@dataclass(frozen=True)
class Layout:
    """A planar compliant mechanism (see the module's description).

    Parameters
    ----------
    parts : tuple of (name, vertices)
        Named simple polygons, vertices ((k, 2), k ≥ 3) [mm] in order (either sense).
    thickness : float
        Extrusion along z [mm], > 0; the mid-plane is z = 0.
    clamp : tuple of segments
        Boundary segments ((2, 2) [mm]) whose extruded faces are fixed.
    stage : tuple of str
        Names of the parts that form the stage.
    loads : tuple of Load
        The load ports, in the order of a load vector's entries.
    young, poisson : float
        Material [MPa], [-].
    part_young : tuple of (name, E [MPa])
        Material regions: another Young's modulus for the parts named.
    mesh_sizes : tuple of (name, size [mm])
        A part's own element size (default: the model's ``mesh_size``).
    """

    parts: tuple[tuple[str, tuple[tuple[float, float], ...]], ...]
    thickness: float
    clamp: tuple[tuple[tuple[float, float], tuple[float, float]], ...]
    stage: tuple[str, ...]
    loads: tuple[Load, ...]
    young: float
    poisson: float
    part_young: tuple[tuple[str, float], ...] = field(default=())
    mesh_sizes: tuple[tuple[str, float], ...] = field(default=())

    def __post_init__(self) -> None:
        check_layout(self)

    @property
    def names(self) -> tuple[str, ...]:
        """The parts' names, in order."""
        return tuple(name for name, _ in self.parts)

    def polygon(self, name: str) -> np.ndarray:
        """Vertices (k, 2) [mm] of part ``name``, counter-clockwise."""
        return _ccw(np.asarray(dict(self.parts)[name], dtype=float))

    def young_of(self, name: str) -> float:
        """Young's modulus [MPa] of part ``name``."""
        return float(dict(self.part_young).get(name, self.young))

    @property
    def one_material(self) -> bool:
        """True when every part has the same Young's modulus."""
        return all(float(e) == float(self.young) for _, e in self.part_young)

    @property
    def span(self) -> float:
        """The planform's largest extent [mm] (the scale of the geometric tolerance)."""
        pts = np.vstack([self.polygon(n) for n in self.names])
        return float(np.ptp(pts, axis=0).max())


def _ccw(v: np.ndarray) -> np.ndarray:
    return v if _area(v) > 0 else v[::-1]


def _area(v: np.ndarray) -> float:
    x, y = v[:, 0], v[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def _edges(v: np.ndarray) -> np.ndarray:
    """Edges (k, 2, 2) of polygon ``v``."""
    return np.stack([v, np.roll(v, -1, axis=0)], axis=1)


def _point_segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    ab = b - a
    t = np.clip(np.dot(p - a, ab) / max(np.dot(ab, ab), 1e-300), 0.0, 1.0)
    return float(np.linalg.norm(p - (a + t * ab)))


def _overlap(seg: np.ndarray, edge: np.ndarray, tol: float) -> float:
    """Length [mm] over which segment ``seg`` lies on ``edge`` (both (2, 2)); 0 unless collinear."""
    a, b = edge
    d = b - a
    length = float(np.linalg.norm(d))
    if length <= tol:
        return 0.0
    u = d / length
    normal = np.array([-u[1], u[0]])
    if any(abs(float(np.dot(p - a, normal))) > tol for p in seg):
        return 0.0
    s = sorted(float(np.dot(p - a, u)) for p in seg)
    return max(0.0, min(s[1], length) - max(s[0], 0.0))


def boundary_overlap(layout: Layout, seg: object, name: str) -> float:
    """Length [mm] of the boundary segment ``seg`` that lies on part ``name``'s edges."""
    s = np.asarray(seg, dtype=float)
    tol = TOL * layout.span
    return sum(_overlap(s, e, tol) for e in _edges(layout.polygon(name)))


def _touching(layout: Layout, seg: np.ndarray) -> dict[str, float]:
    """Parts whose edges ``seg`` lies on, with the overlap length [mm]."""
    out = {n: boundary_overlap(layout, seg, n) for n in layout.names}
    return {n: v for n, v in out.items() if v > TOL * layout.span}


def _nearest_edge(layout: Layout, seg: np.ndarray) -> tuple[str, float]:
    """The part whose boundary is nearest ``seg``'s midpoint, and the distance [mm]."""
    mid = seg.mean(axis=0)
    best = min(
        (_point_segment_distance(mid, e[0], e[1]), n)
        for n in layout.names
        for e in _edges(layout.polygon(n))
    )
    return best[1], best[0]


def adjacency(layout: Layout) -> dict[str, set[str]]:
    """Parts that share a piece of boundary of positive length, per part."""
    tol = TOL * layout.span
    adj: dict[str, set[str]] = {n: set() for n in layout.names}
    names = layout.names
    for i, a in enumerate(names):
        for b in names[i + 1 :]:
            if any(
                _overlap(e, f, tol) > tol
                for e in _edges(layout.polygon(a))
                for f in _edges(layout.polygon(b))
            ):
                adj[a].add(b)
                adj[b].add(a)
    return adj


def _components(nodes: tuple[str, ...], adj: dict[str, set[str]]) -> list[set[str]]:
    left, out = set(nodes), []
    while left:
        todo, comp = [left.pop()], set()
        while todo:
            n = todo.pop()
            comp.add(n)
            for m in adj[n] & left:
                left.discard(m)
                todo.append(m)
        out.append(comp)
    return out


def _check_segment(name: str, seg: object) -> np.ndarray:
    s = np.asarray(seg, dtype=float)
    if s.shape != (2, 2) or not np.all(np.isfinite(s)):
        raise ValueError(f"{name} must be a segment ((x0, y0), (x1, y1)) in mm, got {seg!r}")
    if np.allclose(s[0], s[1]):
        raise ValueError(f"{name} must have two distinct end points, got {seg!r}")
    return s


def _check_parts(layout: Layout) -> None:
    if not layout.parts:
        raise ValueError("parts must name at least one polygon, got none")
    seen = set()
    for name, verts in layout.parts:
        if name in seen:
            raise ValueError(f"part names must be unique, got {name!r} twice")
        seen.add(name)
        v = np.asarray(verts, dtype=float)
        if v.ndim != 2 or v.shape[1] != 2 or len(v) < 3 or not np.all(np.isfinite(v)):
            raise ValueError(
                f"part {name!r} must have ≥ 3 finite (x, y) vertices [mm], got {verts!r}"
            )
        edges = _edges(v)
        for i in range(len(v)):  # a simple polygon: non-adjacent edges do not meet
            for j in range(i + 2, len(v) - (i == 0)):
                if _segments_cross(edges[i], edges[j]):
                    raise ValueError(
                        f"part {name!r} is not a simple polygon: edges {i} and {j} cross"
                    )
        if abs(_area(v)) <= TOL * float(np.ptp(v, axis=0).max()) ** 2:
            raise ValueError(f"part {name!r} has zero area: its vertices are collinear")


def _segments_cross(e: np.ndarray, f: np.ndarray) -> bool:
    def orient(a, b, c):
        return np.sign((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))

    o1, o2 = orient(e[0], e[1], f[0]), orient(e[0], e[1], f[1])
    o3, o4 = orient(f[0], f[1], e[0]), orient(f[0], f[1], e[1])
    return bool(o1 * o2 < 0 and o3 * o4 < 0)


def check_layout(layout: Layout) -> None:
    """Refuse a bad mechanism before meshing (see the module's description).

    Raises
    ------
    ValueError
        Naming the part or region and what is wrong with it.
    """
    _check_parts(layout)
    check_float("thickness [mm]", layout.thickness, low=0.0, low_open=True)
    check_float("young [MPa]", layout.young, low=0.0, low_open=True)
    check_float("poisson", layout.poisson, low=-1.0, high=0.49, low_open=True)
    names = layout.names
    for label, pairs in (("part_young", layout.part_young), ("mesh_sizes", layout.mesh_sizes)):
        for name, value in pairs:
            if name not in names:
                raise ValueError(f"{label} names part {name!r}, which is not one of {names}")
            check_float(f"{label}[{name!r}]", value, low=0.0, low_open=True)
    adj = adjacency(layout)
    pieces = _components(names, adj)
    if len(pieces) > 1:
        raise ValueError(
            f"the planform must be one piece: parts {sorted(map(sorted, pieces))} share no edge"
        )
    if not layout.stage or any(s not in names for s in layout.stage):
        raise ValueError(f"stage must name parts of {names}, got {layout.stage!r}")
    stage_pieces = _components(tuple(layout.stage), adj)
    if len(stage_pieces) > 1:
        raise ValueError(
            f"the stage region is not connected: its parts form {len(stage_pieces)} pieces "
            f"{sorted(map(sorted, stage_pieces))} that share no edge"
        )
    if not layout.clamp:
        raise ValueError("clamp must give at least one boundary segment, got none")
    for k, seg in enumerate(layout.clamp):
        s = _check_segment(f"clamp segment {k}", seg)
        off = f"{s.tolist()} lies on no face of the part: it has no faces to clamp"
        part, _ = _outside_part(layout, s, f"clamp segment {k}", off)
        if part in layout.stage:
            raise ValueError(f"clamp segment {k} is on the stage (part {part!r})")
    _check_loads(layout)
    check_int("loads", len(layout.loads), low=1, high=12)


def _outside_part(layout: Layout, s: np.ndarray, what: str, off: str) -> tuple[str, float]:
    """The one part whose outside boundary holds segment ``s`` and the length of ``s`` on it
    [mm]; a segment on no face (``what``, ``off`` and the nearest edge named) or between two
    parts is refused."""
    on = _touching(layout, s)
    if not on:
        part, dist = _nearest_edge(layout, s)
        raise ValueError(
            f"{what} {off} (the nearest edge, of part {part!r}, is {dist:.4g} mm from its midpoint)"
        )
    if len(on) > 1:
        raise ValueError(f"{what} lies between parts {sorted(on)}: not on the outside")
    ((part, covered),) = on.items()
    return part, covered


def _check_loads(layout: Layout) -> None:
    names = [ld.name for ld in layout.loads]
    if len(set(names)) != len(names):
        raise ValueError(f"load names must be unique, got {names}")
    for ld in layout.loads:
        s = _check_segment(f"load {ld.name!r} segment", ld.segment)
        if ld.kind not in LOAD_KINDS:
            raise ValueError(f"load {ld.name!r} kind must be one of {LOAD_KINDS}, got {ld.kind!r}")
        d = np.asarray(ld.direction, dtype=float)
        if d.shape != (3,) or not np.all(np.isfinite(d)) or np.linalg.norm(d) == 0.0:
            raise ValueError(
                f"load {ld.name!r} direction must be a non-zero 3-vector, got {ld.direction!r}"
            )
        if not isinstance(ld.bound, (int, float)) or not ld.bound > 0:  # inf: no bound
            raise ValueError(f"load {ld.name!r} bound must be > 0 {ld.unit}, got {ld.bound!r}")
        length = float(np.linalg.norm(s[1] - s[0]))
        off = f"is off the part: its segment {s.tolist()} lies on no face"
        part, covered = _outside_part(layout, s, f"load {ld.name!r}", off)
        if part not in layout.stage:
            raise ValueError(
                f"load {ld.name!r} is on part {part!r}, not on the stage {layout.stage}"
            )
        if covered < length * (1 - 1e-9):
            raise ValueError(
                f"load {ld.name!r} runs off the part: {covered:.4g} of its {length:.4g} mm lie on "
                f"an edge of {part!r}"
            )


def check_load_design(layout: Layout, loads: object) -> np.ndarray:
    """Loads as an (n, k) array of finite values, column j within load port j's bound (its
    unit); a single vector (k,) is one row.

    Raises
    ------
    ValueError
        Naming the port, the largest magnitude given and the allowed range.
    """
    f = np.asarray(loads, dtype=float)
    f = f[None, :] if f.ndim == 1 else f
    k = len(layout.loads)
    if f.ndim != 2 or f.shape[1] != k:
        names = ", ".join(ld.name for ld in layout.loads)
        raise ValueError(f"loads must have {k} columns ({names}), got shape {f.shape}")
    if not np.all(np.isfinite(f)):
        raise ValueError("loads must be finite (found NaN or inf)")
    for j, ld in enumerate(layout.loads):
        worst = float(np.abs(f[:, j]).max(initial=0.0))
        if worst > ld.bound:
            raise ValueError(
                f"load {ld.name!r} must lie in [-{ld.bound:g}, {ld.bound:g}] {ld.unit}, got "
                f"|{ld.name}| = {worst:g}"
            )
    return f
