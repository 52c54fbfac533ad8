"""Figures of the HexFlex model: planform and dimensions (Fig 2), stage motions (Fig 3), actuator
directions (Fig 4), mesh (Fig 5) and deformed shapes (Fig 8 style).

Meshes are passed as objects with ``nodes`` (n, 2) [mm] and ``quads`` (m, 4) arrays
(:class:`mechlib.hexflex.fe.mesh.PlanarMesh`); displacements arrive solved
(:meth:`mechlib.hexflex.fe.model.HexFlexModel.midplane_shapes`).
"""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Patch, Polygon

from mechlib.hexflex.fe.mesh import PlanarMesh
from mechlib.hexflex.geometry import TAB_ANGLES_DEG, HexFlexGeometry, ground_polygons
from mechlib.plotting.style import (
    ACTIVE_COLOR,
    OURS_COLOR,
    draw_quads,
    figure_and_axes,
    figure_and_panels,
    panel_grid,
)

#: Share of the planform's span that the largest in-plane displacement is magnified to.
DEFORMED_SHARE = 0.05
#: Displacement components below this share of the largest one are drawn as 0 (round-off).
ROUND_OFF_SHARE = 1e-6


def hexflex_geometry(
    g: HexFlexGeometry,
    planar: PlanarMesh,
    parts: np.ndarray,
    part_names: Sequence[str],
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """Fig 2: the planform coloured by part, the grounded zone, and the dimensions [mm].

    Parameters
    ----------
    g : HexFlexGeometry
        The dimensions drawn and listed.
    planar : PlanarMesh
        The planform's quads.
    parts : numpy.ndarray of int, shape (m,)
        Part index of each quad, into ``part_names``.
    part_names : sequence of str
    axes : sequence of 2 Axes, optional
        The drawing and the dimension table.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, (ax, ax_t) = figure_and_panels(
        axes, (1, 2), (10.0, 5.2), gridspec_kw={"width_ratios": [1.6, 1]}
    )
    colors = plt.cm.tab10(np.arange(len(part_names)))
    draw_quads(ax, planar.nodes, planar.quads, facecolors=colors[parts], edgecolors="none")
    outer = 1.12 * max(g.tab_outer, 2 * g.ground_radius)
    for poly in ground_polygons(g, outer):
        ax.add_patch(Polygon(poly, closed=True, fill=False, hatch="///", ec="0.5", lw=0.8))
    ax.annotate("grounded zone (clamped)", (0, -0.95 * outer), ha="center", fontsize=8)
    for k, angle in enumerate(TAB_ANGLES_DEG):
        a, r = np.deg2rad(angle), 1.06 * g.tab_outer
        ax.annotate(
            f"T{k + 1}", (r * np.cos(a), r * np.sin(a)), ha="center", fontsize=10, weight="bold"
        )
    handles = [Patch(color=c, label=n) for c, n in zip(colors, part_names, strict=True)]
    handles.append(Patch(fill=False, hatch="///", ec="0.5", label="ground"))
    ax.legend(handles=handles, fontsize=7, loc="upper right")
    ax.set_xlim(-outer, outer)
    ax.set_ylim(-outer, 1.1 * g.tab_outer)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    # the flexures are a few tenths of a millimetre wide: one end of T1's beam, enlarged
    end = g.tab_half_width + g.beam_length
    box = (end - 3.0, end + 1.5, g.beam_radius - 1.5, g.beam_radius + g.radial_length + 1.0)
    zoom = ax_t.inset_axes((0.08, 0.56, 0.84, 0.42))
    draw_quads(zoom, planar.nodes, planar.quads, facecolors=colors[parts], edgecolors="0.3",
               linewidths=0.2)  # fmt: skip
    zoom.set(xlim=box[:2], ylim=box[2:], aspect="equal")
    zoom.set_title("T1's beam and radial flexure, enlarged [mm]", fontsize=8)
    zoom.tick_params(labelsize=7)
    ax.indicate_inset_zoom(zoom, edgecolor="k")
    rows = [(k, f"{v:.4g}") for k, v in g.as_dict().items()]
    rows += [("ground radius", f"{g.ground_radius:.4g}"), ("stage gap", f"{g.stage_gap:.3g}")]
    ax_t.axis("off")
    ax_t.table(
        cellText=[[k, v] for k, v in rows],
        colLabels=["dimension", "mm"],
        bbox=(0.08, 0.0, 0.84, 0.48),
    )
    fig.suptitle("Fig 2 (reconstructed): our HexFlex planform and its dimensions")
    return fig


def hexflex_mesh(
    sector: PlanarMesh, full: PlanarMesh, axes: Sequence[Axes] | None = None
) -> Figure:
    """Fig 5: (a) the meshed sixth, (b) the whole mesh completed by symmetry.

    Parameters
    ----------
    sector, full : PlanarMesh
    axes : sequence of 2 Axes, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, panels = figure_and_panels(axes, (1, 2), (10.0, 4.8))
    for ax, m, title in ((panels[0], sector, "(a) one sixth"), (panels[1], full, "(b) full mesh")):
        draw_quads(ax, m.nodes, m.quads, facecolors="#dde8f4", edgecolors="k", linewidths=0.15)
        ax.set_title(f"{title}: {len(m.quads)} quads")
        ax.set_xlabel("x [mm]")
    fig.suptitle("Fig 5: finite-element mesh (quads; extruded to one layer of Q2 hexahedra)")
    return fig


def hexflex_actuators(
    planar: PlanarMesh,
    directions: np.ndarray,
    centers: np.ndarray,
    ax: Axes | None = None,
) -> Figure:
    """Fig 4: positive actuator directions D1 (arrows) and D2 (+z, dots) at each tab's edge.

    Parameters
    ----------
    planar : PlanarMesh
    directions : numpy.ndarray, shape (6, 3)
        Unit directions T1D1, T1D2, …, T3D2.
    centers : numpy.ndarray, shape (3, 2)
        Centres of the tabs' external edges [mm].
    ax : Axes, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax = figure_and_axes(ax, (5.6, 5.2))
    draw_quads(ax, planar.nodes, planar.quads, facecolors="#e6e6e6", edgecolors="none")
    arrow = 0.27 * np.abs(centers).max()  # arrow length [mm], a fraction of the drawing
    tips = centers + arrow * directions[0::2, :2]
    lim = 1.15 * max(np.abs(planar.nodes).max(), np.abs(tips).max())
    for k in range(len(centers)):
        c, d = centers[k], directions[2 * k, :2]
        ax.annotate(
            "", c + arrow * d, c, arrowprops={"arrowstyle": "->", "color": ACTIVE_COLOR, "lw": 2}
        )
        ax.plot(*c, "o", color=OURS_COLOR, ms=8, mfc="none", mew=2)
        ax.plot(*c, ".", color=OURS_COLOR, ms=4)
        ax.annotate(f"T{k + 1}D1", c + 1.08 * arrow * d, fontsize=8, color=ACTIVE_COLOR)
        ax.annotate(f"T{k + 1}D2 (+z)", c + np.array([2.0, -5.0]), fontsize=8, color=OURS_COLOR)
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title("Fig 4: actuator directions (D2 out of the page)")
    return fig


def hexflex_deformed(
    planar: PlanarMesh,
    disp: np.ndarray,
    title: str,
    ax: Axes | None = None,
    scale: float | None = None,
    colorbar: bool | None = None,
) -> Figure:
    """Deformed planform (in-plane displacements magnified) coloured by u_z [µm].

    Parameters
    ----------
    planar : PlanarMesh
    disp : numpy.ndarray, shape (n_nodes, 3)
        Mid-plane displacements [mm] of ``planar``'s nodes.
    title : str
        The panel's title.
    ax : Axes, optional
        Draw into this panel; default: a new figure.
    colorbar : bool, optional
        Add a u_z colour bar [µm] beside the panel (when u_z is not zero); default: only on a
        new figure.
    scale : float, optional
        In-plane magnification; default: the largest in-plane displacement becomes
        ``DEFORMED_SHARE`` of the planform's span (0 if the in-plane part is round-off).

    Returns
    -------
    matplotlib.figure.Figure
    """
    disp = np.asarray(disp, dtype=float)
    if disp.shape != (len(planar.nodes), 3):
        raise ValueError(f"disp must have shape ({len(planar.nodes)}, 3), got {disp.shape}")
    own = ax is None
    fig, ax = figure_and_axes(ax, (5.6, 5.0))
    span = np.ptp(planar.nodes, axis=0).max()
    in_plane, out = np.abs(disp[:, :2]).max(), np.abs(disp[:, 2]).max()
    largest = max(in_plane, out)
    if scale is None:
        significant = in_plane > ROUND_OFF_SHARE * largest
        scale = DEFORMED_SHARE * span / in_plane if significant else 0.0
    nodes = planar.nodes + scale * disp[:, :2]
    draw_quads(
        ax, planar.nodes, planar.quads, facecolors="none", edgecolors="#bbbbbb", linewidths=0.2
    )
    uz = 1e3 * disp[planar.quads, 2].mean(axis=1)
    uz = np.where(np.abs(uz) > ROUND_OFF_SHARE * 1e3 * largest, uz, 0.0)
    lim = max(np.abs(uz).max(), 1e-12)
    pc = draw_quads(ax, nodes, planar.quads, values=uz, cmap="coolwarm", edgecolors="none")
    pc.set_clim(-lim, lim)
    flat = not np.any(uz)
    colour = "u_z zero to round-off" if flat else "colour u_z"
    ax.set_title(f"{title}\n(in-plane ×{scale:.3g}; {colour})", fontsize=8)
    ax.set_xticks([])
    ax.set_yticks([])
    if (own if colorbar is None else colorbar) and not flat:
        fig.colorbar(pc, ax=ax, label="u_z [µm]", shrink=0.8)
    return fig


def hexflex_stage_motions(
    planar: PlanarMesh,
    displacements: np.ndarray,
    labels: Sequence[str],
    title: str = "Fig 3: the six stage motions, each from the inverse model",
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """Fig 3: deformed shapes of given stage motions, one panel each.

    Parameters
    ----------
    planar : PlanarMesh
    displacements : numpy.ndarray, shape (k, n_nodes, 3)
        Mid-plane displacements [mm] of each motion (e.g.
        ``model.midplane_shapes(model.forces_for_poses(poses))``).
    labels : sequence of str
        One panel title per motion.
    title : str
        The figure's title.
    axes : sequence of Axes, optional
        One panel per motion (new figure: rows of three).

    Returns
    -------
    matplotlib.figure.Figure
    """
    shapes = np.asarray(displacements, dtype=float)
    if shapes.ndim != 3 or len(shapes) != len(labels):
        raise ValueError(
            f"displacements must have shape ({len(labels)}, n_nodes, 3), one per label, "
            f"got {shapes.shape}"
        )
    rows, cols = panel_grid(len(labels))
    fig, panels = figure_and_panels(axes, (rows, cols), (11.0 * cols / 3, 3.5 * rows))
    for ax, d, label in zip(panels, shapes, labels, strict=True):
        hexflex_deformed(planar, d, label, ax=ax, colorbar=True)
    fig.suptitle(title)
    return fig
