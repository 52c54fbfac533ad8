"""The drawing of the explorer page ("Try the model"): the HexFlex's moving body, displaced.

The stage and its three tabs move as one rigid plate; a pose (x, y, z [µm], θx, θy, θz [µrad])
moves a point ``p`` of its mid-plane by ``t + θ × p`` (small rotations), magnified for the eye.
Three orthographic views: the top view (x–y plane: x, y, θz) and two side views (x–z and y–z
planes: z, θx, θy), each with its own magnification (:func:`magnifications`), a scale bar and
axis arrows. The views are SVG written here (:func:`view_svg`): the page's interactive part
carries them with element ids that ``book/_static/explorer.js`` redraws for the reader's forces
(the same outline, displacement and arrows), and :func:`figure_svg` lays them out as the static
figure of a preset pose that the printed page shows.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

from mechlib.hexflex.geometry import HexFlexGeometry, actuator_directions, tab_frames

UM_TO_MM = 1e-3
URAD_TO_RAD = 1e-6
VIEW_SHARE = 0.25
"""The largest magnified displacement over the validated forces, as a share of the tabs' reach."""
ARROW_MM_PER_N = 12.0
"""Length of a force arrow [mm of the drawing per N]."""
MARGIN_MM = 4.0
"""Space around each view [mm]."""
SCALE_BAR_MM = 20.0
"""Length of each view's scale bar [mm] (the views have no axes: positions are not readable
where displacements are magnified)."""
#: views: (name, horizontal axis, vertical axis, which magnification)
VIEWS: tuple[tuple[str, int, int, str], ...] = (
    ("top view", 0, 1, "in_plane"),
    ("side view, x–z plane", 0, 2, "out_of_plane"),
    ("side view, y–z plane", 1, 2, "out_of_plane"),
)
AXES = "xyz"
TITLE_MM = 9.0
"""Height of a view's title in the static figure [mm of the drawing]."""
FIGURE_PX_PER_MM = 3.0
"""Size of the static figure on the page [px per mm of the drawing]."""


def outline(g: HexFlexGeometry | None = None) -> np.ndarray:
    """Outline (12, 2) [mm] of the stage triangle with its three tabs, counter-clockwise.

    Around each tab, in the tab's frame (r radial, s tangential): where the stage's edge meets
    the tab's sides (``stage_edge``, ∓ half width), then the tab's outer corners.
    """
    g = g or HexFlexGeometry()
    e_r, e_s = tab_frames()
    h = g.tab_half_width
    points = []
    for k in np.argsort(np.arctan2(e_r[:, 1], e_r[:, 0])):  # tabs in counter-clockwise order
        for r, s in ((g.stage_edge, -h), (g.tab_outer, -h), (g.tab_outer, h), (g.stage_edge, h)):
            points.append(r * e_r[k] + s * e_s[k])
    return np.array(points)


def actuators(g: HexFlexGeometry | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Points (6, 2) [mm] where the six forces act (the tabs' outer edges, Eq 4's order) and
    their unit directions (6, 3)."""
    g = g or HexFlexGeometry()
    e_r, _ = tab_frames()
    return np.repeat(g.tab_outer * e_r, 2, axis=0), actuator_directions()


def nice_floor(value: float) -> float:
    """The largest number of the 1–2–5 series (…, 0.5, 1, 2, 5, 10, …) at most ``value`` > 0."""
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"value must be a finite number > 0, got {value}")
    decade = 10.0 ** math.floor(math.log10(value))
    return max(m * decade for m in (1, 2, 5) if m * decade <= value * (1 + 1e-12))


def magnifications(pose_range: Sequence[float], reach_mm: float) -> dict[str, float]:
    """Magnifications of the top view and of the side views.

    Parameters
    ----------
    pose_range : sequence of 6 float
        Largest |x|, |y|, |z| [µm] and |θx|, |θy|, |θz| [µrad] over the validated forces.
    reach_mm : float
        Largest distance of the outline from the centre [mm].

    Returns
    -------
    dict
        ``in_plane`` and ``out_of_plane``: the 1–2–5 numbers that make the largest displacement
        of the outline at most :data:`VIEW_SHARE` × ``reach_mm`` in their views.
    """
    x, y, z, tx, ty, tz = (abs(float(v)) for v in pose_range)
    in_plane = max(x, y) * UM_TO_MM + tz * URAD_TO_RAD * reach_mm
    out_of_plane = z * UM_TO_MM + math.hypot(tx, ty) * URAD_TO_RAD * reach_mm
    return {
        "in_plane": nice_floor(VIEW_SHARE * reach_mm / in_plane),
        "out_of_plane": nice_floor(VIEW_SHARE * reach_mm / out_of_plane),
    }


def displaced(points_mm: np.ndarray, pose: Sequence[float], magnification: float) -> np.ndarray:
    """Points (n, 3) [mm] of the mid-plane points (n, 2) moved by ``magnification`` × (t + θ × p).

    ``pose``: x, y, z [µm], θx, θy, θz [µrad].
    """
    p = np.column_stack([np.asarray(points_mm, dtype=float), np.zeros(len(points_mm))])
    t = np.asarray(pose[:3], dtype=float) * UM_TO_MM
    theta = np.asarray(pose[3:6], dtype=float) * URAD_TO_RAD
    return p + magnification * (t + np.cross(theta, p))


def shown_forces(directions: np.ndarray, vertical: int) -> list[int]:
    """The forces a view draws: the in-plane ones (D1) in the top view, the out-of-plane ones
    (D2) in a side view (``vertical`` 2)."""
    out_of_plane = np.abs(np.asarray(directions)[:, 2]) > 0.5
    return [int(i) for i in np.flatnonzero(out_of_plane if vertical == 2 else ~out_of_plane)]


def extents(reach_mm: float) -> list[list[float]]:
    """Drawing limits [mm] of each view of :data:`VIEWS` (``[h_min, h_max, v_min, v_max]``): the
    outline, its largest magnified displacement and the force arrows, with a margin; the side
    views as tall as their scale bar and axis arrows need."""
    wide = reach_mm * (1 + VIEW_SHARE) + MARGIN_MM
    tall = max(VIEW_SHARE * reach_mm + ARROW_MM_PER_N, SCALE_BAR_MM) + MARGIN_MM
    return [
        [-wide, wide, -wide, wide] if v != 2 else [-wide, wide, -tall, tall] for *_, v, _ in VIEWS
    ]


def arrow_path(x0: float, y0: float, x1: float, y1: float) -> str:
    """SVG path data of an arrow from (x0, y0) to (x1, y1) (empty when shorter than 1 µm); the
    page's script draws the same."""
    dx, dy = x1 - x0, y1 - y0
    length = math.hypot(dx, dy)
    if length < 1e-6:
        return ""
    ux, uy, hl = dx / length, dy / length, min(3.0, 0.5 * length)
    hw = 0.45 * hl
    pts = [
        (x0, y0),
        (x1, y1),
        (x1 - hl * ux + hw * uy, y1 - hl * uy - hw * ux),
        (x1, y1),
        (x1 - hl * ux - hw * uy, y1 - hl * uy + hw * ux),
    ]
    return "".join(f"{c}{x:.2f} {y:.2f}" for c, (x, y) in zip("MLMLL", pts, strict=True))


def _points(xy: np.ndarray) -> str:
    return " ".join(f"{x:.3f},{y:.3f}" for x, y in xy)


def view_svg(
    view: Mapping[str, object],
    drawing: Mapping[str, object],
    pose: Sequence[float],
    forces: Sequence[float],
    index: int | None = None,
    place: str = "",
) -> str:
    """One view as an ``<svg>`` element: the outline at rest (dashed), moved by ``pose``
    (filled), the view's force arrows, axis arrows and a scale bar; y up.

    Parameters
    ----------
    view : mapping
        One of the literal's ``drawing["views"]`` (``h``, ``v``, ``magnification``, ``limits``,
        ``forces``).
    drawing : mapping
        The literal's ``drawing`` (outline, actuators, directions, magnifications, arrow scale).
    pose, forces : sequence of 6 float
        Pose [µm, µrad] and forces [N] drawn.
    index : int, optional
        When given, the moved outline and the arrows get the ids ``mx-body-<index>`` and
        ``mx-force-<index>`` (the page's script redraws them) and the view is labelled by the
        element ``mx-view-<index>``.
    place : str
        Extra attributes (position and size inside a larger SVG).
    """
    h, v = int(view["h"]), int(view["v"])
    h0, h1, v0, v1 = view["limits"]
    mag = float(drawing["magnification"][view["magnification"]])
    shape = np.asarray(drawing["outline_mm"], dtype=float)
    rest = displaced(shape, np.zeros(6), 0.0)[:, [h, v]]
    body = displaced(shape, pose, mag)[:, [h, v]]
    at = displaced(np.asarray(drawing["actuators_mm"], dtype=float), pose, mag)
    dirs, scale = np.asarray(drawing["directions"]), float(drawing["arrow_mm_per_n"])
    arrows = "".join(
        arrow_path(
            at[i, h],
            at[i, v],
            at[i, h] + scale * forces[i] * dirs[i, h],
            at[i, v] + scale * forces[i] * dirs[i, v],
        )
        for i in view["forces"]
    )
    ids = ("", "") if index is None else (f' id="mx-body-{index}"', f' id="mx-force-{index}"')
    label = "" if index is None else f' role="img" aria-labelledby="mx-view-{index}"'
    x, y, arm = h0 + 2, v0 + 2, 0.5 * SCALE_BAR_MM
    bar = x + arm + 7
    compass = arrow_path(x, y, x + arm, y) + arrow_path(x, y, x, y + arm)
    return "".join(
        [
            f'<svg viewBox="{h0:g} {-v1:g} {h1 - h0:g} {v1 - v0:g}"{place}{label}>',
            '<g transform="scale(1,-1)">',
            f'<polygon class="mx-rest" points="{_points(rest)}"/>',
            f'<polygon class="mx-body"{ids[0]} points="{_points(body)}"/>',
            f'<path class="mx-force"{ids[1]} d="{arrows}"/>',
            f'<path class="mx-ink" d="{compass}M{bar:g} {y:g}L{bar + SCALE_BAR_MM:g} {y:g}"/>',
            "</g>",
            f'<text class="mx-axis" x="{x + arm + 1:g}" y="{-y + 1.5:g}">{AXES[h]}</text>',
            f'<text class="mx-axis" x="{x - 1.5:g}" y="{-(y + arm + 1):g}">{AXES[v]}</text>',
            f'<text class="mx-axis" x="{bar + SCALE_BAR_MM / 2:g}" y="{-y - 1.5:g}" '
            f'text-anchor="middle">{SCALE_BAR_MM:g} mm</text>',
            "</svg>",
        ]
    )


#: the static figure's colours and strokes (the page's CSS styles the interactive views alike)
FIGURE_STYLE = (
    ".mx-rest{fill:none;stroke:#9a9a9a;stroke-width:.4;stroke-dasharray:1.5 1}"
    ".mx-body{fill:#cfe0f3;stroke:#1f4e79;stroke-width:.5}"
    ".mx-force{fill:none;stroke:#b23c17;stroke-width:.7}"
    ".mx-ink{fill:none;stroke:#000;stroke-width:.4}"
    "text{font-family:sans-serif;font-size:5px}.mx-title{font-size:6px}"
)


def figure_svg(
    drawing: Mapping[str, object], pose: Sequence[float], forces: Sequence[float]
) -> str:
    """The static figure: the top view on the left, the two side views stacked on its right,
    each under its title (with its magnification)."""
    views = list(drawing["views"])
    sizes = [(lim[1] - lim[0], lim[3] - lim[2]) for lim in (v["limits"] for v in views)]
    left_w, left_h = sizes[0]
    right_w = max(w for w, _ in sizes[1:])
    width, height = (
        left_w + right_w,
        max(left_h, sum(h for _, h in sizes[1:]) + TITLE_MM) + TITLE_MM,
    )
    spots = [(0.0, TITLE_MM), (left_w, TITLE_MM), (left_w, 2 * TITLE_MM + sizes[1][1])]
    parts = []
    for view, (w, h), (x, y) in zip(views, sizes, spots, strict=True):
        mag = drawing["magnification"][view["magnification"]]
        parts.append(
            f'<text class="mx-title" x="{x + w / 2:g}" y="{y - 2:g}" text-anchor="middle">'
            f"{view['name']}: displacements ×{mag:g}</text>"
        )
        place = f' x="{x:g}" y="{y:g}" width="{w:g}" height="{h:g}"'
        parts.append(view_svg(view, drawing, pose, forces, place=place))
    return (
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width * FIGURE_PX_PER_MM:.0f}" '
        f'height="{height * FIGURE_PX_PER_MM:.0f}" viewBox="0 0 {width:g} {height:g}">'
        f"<style>{FIGURE_STYLE}</style>" + "".join(parts) + "</svg>\n"
    )
