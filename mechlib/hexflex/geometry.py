"""Parametric planform of our HexFlex, reconstructed from the thesis's text and Eq 8.

The thesis's Fig 2 (the drawing with dimensions) is not available. Its text (sec. 2.6.1) says the
part is *a triangular motion stage, three tabs that interface with the actuators, and six
connection beams between the motion stage and the grounded zone*, with two actuators at each
tab's *external edge*: D1 in-plane and parallel to the connection beams, D2 out of plane. The
signs of Eq 8 fix the layout: tab T1 on the +y axis, T2 at 330°, T3 at 210°, and the positive D1
vectors T1 (1, 0), T2 (0.5, 0.866), T3 (−0.5, 0.866). D1 is tangential at every tab but *not*
with the same handedness: T1 and T3 point clockwise about the stage centre and T2
counter-clockwise (Eq 8's θz row: −3101.84, +3101.79, −3101.81), so the actuator convention of
Fig 4 is not three-fold symmetric although the mechanism is.

Our reconstruction: the stage and its three tabs are **one body** — a triangle of circumradius
``stage_radius`` with vertices on the tab axes, and three radial tabs of half-width
``tab_half_width`` out to the external edge at ``tab_outer``. Each tab carries two L-shaped
connection beams, mirror images of each other. In a tab's local frame (``r`` along its axis,
``s`` along the counter-clockwise tangent) one beam is, on centre lines:

- a *D1 segment* (parallel to D1) of width ``beam_width`` at radius ``beam_radius`` (ρ), from
  the tab's side ``s = tab_half_width`` to ``s = tab_half_width + beam_length``;
- a *corner* block where the two segments meet;
- a *radial segment* of width ``radial_width`` on ``s = tab_half_width + beam_length``, from
  ``r = beam_radius`` out to the grounded zone at ``r = beam_radius + radial_length``, where it
  is clamped. The grounded zone is three sectors between the tabs.

The radial segment is the bending element in series that a straight beam between a rigid stage
and a rigid ground lacks: pushing a tab along D1 loads the D1 segments axially, and the radial
segments bend. All lengths are in mm.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, fields

import numpy as np

from mechlib.params import check_float

#: Axis angles of tabs T1, T2, T3 [deg] fixed by the signs of Eq 8 (T1 on +y).
TAB_ANGLES_DEG: tuple[float, float, float] = (90.0, 330.0, 210.0)
#: Sign of each tab's positive D1 relative to the counter-clockwise tangent (Eq 8, θz row).
TAB_D1_SIGNS: tuple[int, int, int] = (-1, 1, -1)
#: The part's material, Al 7075-T6 (thesis sec. 2.6.1): Young's modulus [MPa], Poisson's ratio.
AL7075_YOUNG_MPA = 71_700.0
AL7075_POISSON = 0.33
#: Largest Poisson's ratio the models accept (0.5 is incompressible: the stiffness is singular).
MAX_POISSON = 0.499
#: Part labels returned by :func:`classify`.
PARTS: tuple[str, ...] = ("stage", "tab", "beam", "corner", "radial")
#: Smallest slot between two separate parts of the plate [mm] (a wire-EDM or water-jet kerf).
MIN_GAP_MM = 0.5
#: Allowed range of every dimension [mm] (inclusive), checked before anything is meshed.
DIMENSION_BOUNDS: dict[str, tuple[float, float]] = {
    "stage_radius": (5.0, 40.0),
    "tab_half_width": (1.0, 10.0),
    "tab_outer": (15.0, 80.0),
    "beam_radius": (8.0, 50.0),
    "beam_width": (0.1, 3.0),
    "beam_length": (2.0, 30.0),
    "radial_width": (0.1, 3.0),
    "radial_length": (1.0, 30.0),
    "thickness": (0.2, 5.0),
}
_EPS = 1e-9


@dataclass(frozen=True)
class HexFlexGeometry:
    """Dimensions of the planform and the plate thickness, all in mm (see the module text).

    Raises
    ------
    ValueError
        If a dimension is outside :data:`DIMENSION_BOUNDS`, or parts overlap (the tab leaves the
        stage's sector, a beam touches the stage or the tab, a tab ends before its beams) or the
        beams do not fit between the tabs — each with the dimension, its value and its range.
    """

    stage_radius: float = 25.0
    tab_half_width: float = 3.0
    tab_outer: float = 45.0
    beam_radius: float = 22.0
    beam_width: float = 0.276
    beam_length: float = 11.72
    radial_width: float = 0.276
    radial_length: float = 3.95
    thickness: float = 0.505

    def __post_init__(self) -> None:
        for f in fields(self):
            low, high = DIMENSION_BOUNDS[f.name]
            check_float(f"{f.name} [mm]", getattr(self, f.name), low=low, high=high)
        g, gap = self, MIN_GAP_MM
        widest = np.sqrt(3) / 4 * g.stage_radius
        _need(
            g.tab_half_width < widest,
            "tab_half_width",
            g.tab_half_width,
            f"< √3/4 · stage_radius = {widest:.4g}",
            "the tab's root leaves the stage's sixth",
        )
        # the stage's edge crosses the tab's side at r = stage_edge; the D1 segment must clear it
        low = g.stage_edge + 0.5 * g.beam_width + gap
        _need(
            g.beam_radius >= low,
            "beam_radius",
            g.beam_radius,
            f">= stage_radius − √3·tab_half_width + beam_width/2 + {gap:g} = {low:.4g}",
            "the D1 segment would touch the stage",
        )
        low = 0.5 * g.radial_width + gap
        _need(
            g.beam_length >= low,
            "beam_length",
            g.beam_length,
            f">= radial_width/2 + {gap:g} = {low:.4g}",
            "the radial segment would touch the tab",
        )
        low = 0.5 * g.beam_width + gap
        _need(
            g.radial_length >= low,
            "radial_length",
            g.radial_length,
            f">= beam_width/2 + {gap:g} = {low:.4g}",
            "no free radial segment",
        )
        low = g.beam_radius + 0.5 * g.beam_width + gap
        _need(
            g.tab_outer >= low,
            "tab_outer",
            g.tab_outer,
            f">= beam_radius + beam_width/2 + {gap:g} = {low:.4g}",
            "the tab ends inside its beams",
        )
        # the two beams between neighbouring tabs are mirror images about the 60° line: the
        # corner's inner outer-corner must stay gap/2 away from it
        far = g.corner_s + 0.5 * g.radial_width
        high = np.sqrt(3) * (g.beam_radius - 0.5 * g.beam_width) - far - gap
        _need(
            high >= 0,
            "beam_length",
            g.beam_length,
            f"<= {g.beam_length + high:.4g} at beam_radius = {g.beam_radius:g}",
            "the beams of neighbouring tabs would overlap: they do not fit between the tabs",
        )

    # derived radii and offsets ------------------------------------------------------------
    @property
    def corner_s(self) -> float:
        """Tangential offset of the radial segments' centre lines [mm]."""
        return self.tab_half_width + self.beam_length

    @property
    def ground_radius(self) -> float:
        """Radius (in each tab's frame) where the radial segments are clamped [mm]."""
        return self.beam_radius + self.radial_length

    @property
    def stage_edge(self) -> float:
        """Radius where the stage's edge crosses the tab's side ``s = tab_half_width`` [mm]."""
        return self.stage_radius - np.sqrt(3) * self.tab_half_width

    @property
    def tab_start(self) -> float:
        """Radius where the tab rectangle starts, inside the stage and inside the 60° sector."""
        low = self.tab_half_width / np.sqrt(3)  # its corner on the sector's 30° cut line
        return 0.5 * (low + self.stage_edge)  # ... and its corner inside the stage edge

    @property
    def stage_gap(self) -> float:
        """Radial slot between the stage's edge and the D1 segment at the tab's side [mm]."""
        return self.beam_radius - 0.5 * self.beam_width - self.stage_edge

    @property
    def narrowest(self) -> float:
        """Narrowest flexure width [mm] (the mesh is sized on it)."""
        return min(self.beam_width, self.radial_width)

    def as_dict(self) -> dict[str, float]:
        """Dimensions by name [mm] (what records and notebooks pass around)."""
        return {k: float(v) for k, v in asdict(self).items()}

    @classmethod
    def from_dict(cls, dims: dict[str, float]) -> HexFlexGeometry:
        """The geometry of dimensions given by name [mm] (all of :data:`DIMENSION_BOUNDS`).

        Raises
        ------
        ValueError
            If a name is unknown or missing.
        """
        names = set(DIMENSION_BOUNDS)
        unknown, missing = sorted(set(dims) - names), sorted(names - set(dims))
        if unknown or missing:
            raise ValueError(
                f"geometry must name exactly the dimensions {sorted(names)}; "
                f"unknown: {unknown}, missing: {missing}"
            )
        return cls(**{k: float(v) for k, v in dims.items()})

    def replace(self, **changes: float) -> HexFlexGeometry:
        """A copy with some dimensions changed (validated again)."""
        return HexFlexGeometry(**{**asdict(self), **changes})

    def rectangles(self) -> dict[str, list[tuple[float, float, float, float]]]:
        """Half-leg rectangles ``(r0, r1, s0, s1)`` for ``s >= 0``, per part (not the stage)."""
        g = self
        b0, b1 = g.beam_radius - 0.5 * g.beam_width, g.beam_radius + 0.5 * g.beam_width
        c0, c1 = g.corner_s - 0.5 * g.radial_width, g.corner_s + 0.5 * g.radial_width
        return {
            "tab": [(g.tab_start, g.tab_outer, 0.0, g.tab_half_width)],
            "beam": [(b0, b1, g.tab_half_width, c0)],
            "corner": [(b0, b1, c0, c1)],
            "radial": [(b1, g.ground_radius, c0, c1)],
        }


def _need(ok: bool, name: str, value: float, allowed: str, why: str) -> None:
    if not ok:
        raise ValueError(f"{name} [mm] must be {allowed} mm ({why}), got {value:g} mm")


def tab_frames() -> tuple[np.ndarray, np.ndarray]:
    """Unit radial axes ``e_r`` and counter-clockwise tangents ``e_s`` of T1..T3, each (3, 2)."""
    a = np.deg2rad(TAB_ANGLES_DEG)
    return np.column_stack([np.cos(a), np.sin(a)]), np.column_stack([-np.sin(a), np.cos(a)])


def actuator_directions() -> np.ndarray:
    """Unit force directions (6, 3) in the order of Eq 4: T1D1, T1D2, T2D1, T2D2, T3D1, T3D2."""
    _, e_s = tab_frames()
    out = np.zeros((6, 3))
    out[0::2, :2] = e_s * np.asarray(TAB_D1_SIGNS)[:, None]
    out[1::2, 2] = 1.0
    return out


def actuator_points(g: HexFlexGeometry) -> np.ndarray:
    """Centres (3, 2) [mm] of the tabs' external edges, where the actuators act."""
    e_r, _ = tab_frames()
    return g.tab_outer * e_r


def ground_polygons(g: HexFlexGeometry, outer: float, n_arc: int = 24) -> list[np.ndarray]:
    """Outlines (m, 2) [mm] of the three grounded sectors between the tabs, for drawings.

    Each sector's inner edge is the line ``r = ground_radius`` of both neighbouring tabs' frames
    (where the radial segments are clamped), its sides keep ``MIN_GAP_MM`` from the tabs, and it
    is closed by an arc of radius ``outer``.
    """
    e_r, e_s = tab_frames()
    gap, rg = g.tab_half_width + MIN_GAP_MM, g.ground_radius

    def at(k: int, r: float, s: float) -> np.ndarray:
        return r * e_r[k] + s * e_s[k]

    out = []
    for k in range(3):
        # j: the next tab counter-clockwise; tab k's s > 0 side and tab j's s < 0 side face it
        ahead = [(a - TAB_ANGLES_DEG[k]) % 360 or 360 for a in TAB_ANGLES_DEG]
        j = int(np.argmin(ahead))
        p0, p1 = at(k, rg, gap), at(k, rg, np.sqrt(3) * rg)
        p2, p3 = at(j, rg, -gap), at(j, outer, -gap)
        a0, a1 = np.arctan2(*p3[::-1]), np.arctan2(*at(k, outer, gap)[::-1])
        a1 = a1 if a1 < a0 else a1 - 2 * np.pi
        arc = outer * np.c_[np.cos(np.linspace(a0, a1, n_arc)), np.sin(np.linspace(a0, a1, n_arc))]
        out.append(np.vstack([p0, p1, p2, arc]))
    return out


def local_coordinates(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Local ``(r, s)`` of in-plane points in each leg's frame, each (n, 3)."""
    p = np.asarray(points, dtype=float)[:, :2]
    e_r, e_s = tab_frames()
    return p @ e_r.T, p @ e_s.T


def in_stage(points: np.ndarray, g: HexFlexGeometry) -> np.ndarray:
    """True for points inside the stage triangle (vertices toward the tabs)."""
    r, _ = local_coordinates(points)
    # the triangle is the set where the projection on each *edge normal* (= -e_r of the
    # opposite vertex) is at most the inradius R/2
    return np.all(-r <= 0.5 * g.stage_radius + _EPS, axis=1)


def classify(points: np.ndarray, g: HexFlexGeometry) -> np.ndarray:
    """Part index (into :data:`PARTS`) of in-plane points, or -1 outside the planform."""
    r, s = local_coordinates(points)
    s = np.abs(s)
    label = np.full(len(r), -1)
    label[in_stage(points, g)] = PARTS.index("stage")
    for part, rects in g.rectangles().items():
        for r0, r1, s0, s1 in rects:
            inside = (r >= r0 - _EPS) & (r <= r1 + _EPS) & (s >= s0 - _EPS) & (s <= s1 + _EPS)
            hit = np.any(inside, axis=1) & (label < 0)
            label[hit] = PARTS.index(part)
    return label
