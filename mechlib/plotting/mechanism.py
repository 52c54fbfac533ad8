"""Figures of a compliant mechanism's FE (:mod:`mechlib.compliant`): its planform mesh with the
named regions, and FE poses along a load line beside other models. Nothing is computed here.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from mechlib.plotting.style import (
    ACTIVE_COLOR,
    OURS_COLOR,
    PUBLISHED_COLOR,
    draw_quads,
    figure_and_axes,
    figure_and_panels,
    panel_label,
    readable_value_axis,
)

#: line style of each model drawn by :func:`pose_lines`, by its order in ``curves``
_STYLES = (("s", PUBLISHED_COLOR), ("-", OURS_COLOR), ("--", ACTIVE_COLOR), (":", "0.2"))


def planform_regions(
    nodes: np.ndarray,
    quads: np.ndarray,
    on_stage: np.ndarray,
    clamp: Sequence[np.ndarray],
    loads: Sequence[np.ndarray],
    ax: Axes | None = None,
) -> Figure:
    """The planform's quads (the stage shaded), the clamp segments (thick dark lines) and the
    load segments (thick red lines), in mm.

    Parameters
    ----------
    nodes : ndarray (n, 2)
    quads : ndarray (m, 4)
    on_stage : ndarray (m,) of bool
        Quads of the stage.
    clamp, loads : sequence of ndarray (2, 2)
        The regions' segments [mm].
    ax : Axes, optional
    """
    fig, ax = figure_and_axes(ax, (8.0, 5.0))
    faces = np.where(np.asarray(on_stage)[:, None], np.array([[0.55, 0.7, 0.9, 1.0]]),
                     np.array([[0.91, 0.94, 0.98, 1.0]]))  # fmt: skip
    draw_quads(ax, nodes, quads, facecolors=faces, edgecolors="0.35", linewidths=0.3)
    for k, seg in enumerate(clamp):
        ax.plot(*np.asarray(seg).T, "-", color="0.1", lw=4, label="clamp" if k == 0 else None)
    for k, seg in enumerate(loads):
        ax.plot(*np.asarray(seg).T, "-", color=ACTIVE_COLOR, lw=3,
                label="load face" if k == 0 else None)  # fmt: skip
    ax.plot([0.0], [0.0], "o", color="0.1", ms=4, label="pose reference point")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.legend(loc="center left", fontsize=8)
    return fig


def pose_lines(
    a_y: np.ndarray,
    curves: Mapping[str, np.ndarray],
    labels: Sequence[str],
    x_label: str,
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """The pose components against one load, one panel per component: the first model as
    markers, the others as lines.

    Parameters
    ----------
    a_y : ndarray (k,)
        The load's levels.
    curves : mapping of str to ndarray (k, c)
        Each model's poses, in drawing order (at most four).
    labels : sequence of str
        The c components' axis labels, with units.
    x_label : str
    axes : sequence of Axes, optional
        c panels.
    """
    if len(curves) > len(_STYLES):
        raise ValueError(f"curves must hold at most {len(_STYLES)} models, got {len(curves)}")
    fig, panels = figure_and_panels(axes, (1, len(labels)), (3.4 * len(labels), 3.4))
    for c, ax in enumerate(panels):
        for (name, values), (style, colour) in zip(curves.items(), _STYLES, strict=False):
            values = np.asarray(values)
            if style == "s":
                ax.plot(a_y, values[:, c], style, color=colour, mfc="none", ms=5, label=name)
            else:
                ax.plot(a_y, values[:, c], style, color=colour, lw=1.3, label=name)
        ax.set_title(f"{panel_label(c)} {labels[c]}", fontsize=9)
        ax.set_xlabel(x_label)
        readable_value_axis(ax.yaxis)
    panels[0].legend(fontsize=7)
    return fig
