"""Parametric planform of our HexFlex: three identical legs around a triangular stage.

The thesis's Fig 2 (the HexFlex drawing with dimensions) is not available, so the topology is
ours, built from the thesis's description (sec. 2.6.1: a triangular motion stage, three tabs that
interface the actuators, connection beams between the stage and the grounded zone, D1 in-plane and
parallel to the connection beams, D2 out of plane) and from the signs of Eq 8, which fix the
layout: tab T1 on the +y axis, T2 at 330°, T3 at 210°, and the positive D1 vectors T1 (1, 0),
T2 (0.5, 0.866), T3 (−0.5, 0.866). D1 is tangential at every tab, but *not* with the same
handedness: T1 and T3 point clockwise about the stage centre and T2 counter-clockwise (Eq 8's θz
row: −3101.84, +3101.79, −3101.81), so the actuator convention of Fig 4 is not three-fold
symmetric although the mechanism is.

Each leg, in its local frame (``r`` along the tab axis, ``s`` along the tangent), is a union of
rectangles, mirror-symmetric in ``s``:

- *arm*: a radial extension of the stage, ``|s| <= arm_half_width``, up to ``arm_end``;
- *links* (the connection beams, parallel to D1): ``r`` in ``[arm_end - link_width, arm_end]``,
  ``|s|`` from ``arm_half_width`` to ``arm_half_width + link_length``;
- *tab*: a U-shaped paddle opening toward the stage — two walls of width ``wall_width`` outside
  the links and an outer bar (the actuator interface) of radial depth ``tab_depth`` beyond a slot
  of width ``slot`` past the arm's end;
- *ground beams*: two radial beams of width ``beam_width`` and length ``beam_length`` on the
  walls' centre lines, from the tab's outer edge to the grounded zone (clamped).

Pushing a tab along D1 bends its ground beams (a parallelogram guide) and pulls the stage
through the links (axially); a radial stage motion bends the links; out of plane everything
bends and twists. All lengths are in mm.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, fields

import numpy as np

from mechlib.params import check_float

#: Axis angles of tabs T1, T2, T3 [deg] fixed by the signs of Eq 8 (T1 on +y).
TAB_ANGLES_DEG: tuple[float, float, float] = (90.0, 330.0, 210.0)
#: Sign of each tab's positive D1 relative to the counter-clockwise tangent (Eq 8, θz row).
TAB_D1_SIGNS: tuple[int, int, int] = (-1, 1, -1)
#: Part labels returned by :func:`classify`.
PARTS: tuple[str, ...] = ("stage", "arm", "link", "tab", "beam")
_EPS = 1e-9


@dataclass(frozen=True)
class HexFlexGeometry:
    """Dimensions of the planform and the plate thickness, all in mm (see the module text)."""

    stage_radius: float = 20.0
    arm_half_width: float = 4.0
    arm_end: float = 32.0
    link_width: float = 1.5
    link_length: float = 10.0
    wall_width: float = 4.0
    slot: float = 2.0
    tab_depth: float = 10.0
    beam_width: float = 1.5
    beam_length: float = 20.0
    thickness: float = 1.0

    def __post_init__(self) -> None:
        for f in fields(self):
            check_float(f"{f.name} [mm]", getattr(self, f.name), low=0.0, low_open=True)
        g = self
        if g.arm_end - g.link_width <= g.stage_radius:
            raise ValueError(
                f"link_width must be < arm_end - stage_radius = {g.arm_end - g.stage_radius:g} mm "
                f"(the links would overlap the stage), got {g.link_width:g} mm"
            )
        if g.beam_width > g.wall_width:
            raise ValueError(
                f"beam_width must be <= wall_width = {g.wall_width:g} mm (a ground beam is wider "
                f"than the tab wall it starts from), got {g.beam_width:g} mm"
            )
        widest = g.stage_radius * np.sqrt(3) / 4  # the arm's root stays on the stage's sixth
        if g.arm_half_width >= widest:
            raise ValueError(
                f"arm_half_width must be < √3/4 · stage_radius = {widest:g} mm, "
                f"got {g.arm_half_width:g} mm"
            )
        # the leg must stay inside its 120° sector: half-angle of its widest corner < 60°
        corner = np.arctan2(self.half_span, self.arm_end - self.link_width)
        if corner >= np.pi / 3:
            raise ValueError(
                f"legs overlap: arm_half_width + link_length + wall_width = {self.half_span:g} mm "
                f"must be < tan(60°)·(arm_end − link_width) = "
                f"{np.tan(np.pi / 3) * (self.arm_end - self.link_width):g} mm"
            )

    # derived radii and offsets ------------------------------------------------------------
    @property
    def half_span(self) -> float:
        """Tangential half-width of the tab (outer face of a wall) [mm]."""
        return self.arm_half_width + self.link_length + self.wall_width

    @property
    def beam_offset(self) -> float:
        """Tangential offset of the ground beams' centre lines (the walls' centre lines) [mm]."""
        return self.arm_half_width + self.link_length + 0.5 * self.wall_width

    @property
    def arm_start(self) -> float:
        """Radius where the arm rectangle starts, inside the stage and inside the 60° sector."""
        low = self.arm_half_width / np.sqrt(3)  # its corner on the sector's 30° cut line
        high = self.stage_radius - np.sqrt(3) * self.arm_half_width  # its corner on the stage edge
        return 0.5 * (low + high)

    @property
    def tab_inner(self) -> float:
        """Inner radius of the tab's outer bar (after the slot) [mm]."""
        return self.arm_end + self.slot

    @property
    def tab_outer(self) -> float:
        """Outer radius of the tab [mm]."""
        return self.tab_inner + self.tab_depth

    @property
    def ground_radius(self) -> float:
        """Radius (along each tab axis) where the ground beams are clamped [mm]."""
        return self.tab_outer + self.beam_length

    @property
    def tab_center(self) -> float:
        """Radius of the centre of the actuator interface (the tab's outer bar) [mm]."""
        return self.tab_inner + 0.5 * self.tab_depth

    def replace(self, **changes: float) -> HexFlexGeometry:
        """A copy with some dimensions changed (validated again)."""
        return HexFlexGeometry(**{**asdict(self), **changes})

    def rectangles(self) -> dict[str, list[tuple[float, float, float, float]]]:
        """Half-leg rectangles ``(r0, r1, s0, s1)`` for ``s >= 0``, per part."""
        g = self
        wall0 = g.arm_half_width + g.link_length
        b0, b1 = g.beam_offset - 0.5 * g.beam_width, g.beam_offset + 0.5 * g.beam_width
        return {
            "arm": [(g.arm_start, g.arm_end, 0.0, g.arm_half_width)],
            "link": [(g.arm_end - g.link_width, g.arm_end, g.arm_half_width, wall0)],
            "tab": [
                (g.arm_end - g.link_width, g.tab_outer, wall0, g.half_span),
                (g.tab_inner, g.tab_outer, 0.0, wall0),
            ],
            "beam": [(g.tab_outer, g.ground_radius, b0, b1)],
        }


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


def tab_of(points: np.ndarray) -> np.ndarray:
    """Index (0, 1, 2) of the leg whose axis is nearest in angle to each point."""
    r, _ = local_coordinates(points)
    return np.argmax(r, axis=1)
