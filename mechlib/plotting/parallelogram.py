"""Figures of the "Beyond the HexFlex" page: the parallelogram flexure's published 3-D FE sweep
beside our elastica, and the deformed elastica at a few loads.

The data arrive arranged (:mod:`mechlib.parallelogram.drawing`); nothing is computed here.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Polygon

from mechlib.plotting.style import (
    ACTIVE_COLOR,
    OURS_COLOR,
    PUBLISHED_COLOR,
    figure_and_panels,
    panel_label,
    readable_value_axis,
)

#: y-axis label of each pose component, with its unit
COMPONENT_LABELS = ("$u_x/L$ [–]", "$u_y/L$ [–]", r"$\varphi$ [rad]")
LOAD_LABEL = "$A_y = F_y L^2/EI$ [–]"
#: colour of the lines and markers of each printed couple's sign: B < 0, B = 0, B > 0
SIGN_COLORS = {-1: ACTIVE_COLOR, 0: "0.15", 1: OURS_COLOR}
#: colour of the elastica under the couple the FE applied (the same for B and -B)
APPLIED_COLOR = "#9467bd"


def _minus(value: float) -> str:
    """A number as text, with a true minus sign."""
    return f"{value:g}".replace("-", "−")


def _markers(ax: Axes, a_y: np.ndarray, values: np.ndarray, b: float) -> None:
    sign = int(np.sign(b))
    label = f"3-D FE, B = {_minus(b)}"
    style = {"ls": "none", "color": SIGN_COLORS[sign], "label": label}
    if sign < 0:
        ax.plot(a_y, values, marker="s", ms=6, mfc="none", mew=1.0, **style)
    else:
        ax.plot(a_y, values, marker="o", ms=3.2, **style)


def _legend_order(item: tuple[str, object]) -> tuple[int, str]:
    """The FE's markers first, then the elastica under the applied and the printed couple."""
    label = item[0]
    return (0 if label.startswith("3-D FE") else 1 if "applied" in label else 2, label)


def sweep_comparison(
    a_y: np.ndarray,
    fe: np.ndarray,
    applied: np.ndarray,
    printed: np.ndarray,
    a_x_levels: Sequence[float],
    b_levels: Sequence[float],
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """The pose components against A_y, one column of panels per A_x, one row per component.

    Markers: the published 3-D FE per printed couple B (open squares for B < 0, drawn over the
    B > 0 dots they coincide with when the couple's sign was lost). Lines: the elastica under the
    couple the FE applied (solid; black for B = 0, purple for ±B, whose applied couples are the
    same) and under the couple the file prints (dashed, in the colour of B's sign).

    Parameters
    ----------
    a_y : numpy.ndarray, shape (k,)
        The A_y levels.
    fe, applied, printed : numpy.ndarray, shape (len(a_x_levels), len(b_levels), k, 3)
        (u_x/L, u_y/L, φ [rad]) of the FE, of the elastica under the applied couple and under
        the printed one (:func:`mechlib.parallelogram.drawing.by_line`).
    a_x_levels, b_levels : sequence of float
        The columns' A_x and the lines' printed B.
    axes : sequence of Axes, optional
        3 × len(a_x_levels) panels, row by row.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        If an array does not match the levels, or ``axes`` holds another number of Axes.
    """
    n_ax, n_b = len(a_x_levels), len(b_levels)
    shape = (n_ax, n_b, len(a_y), 3)
    if any(np.shape(arr) != shape for arr in (fe, applied, printed)):
        raise ValueError(f"fe, applied and printed must have shape {shape}")
    fig, panels = figure_and_panels(axes, (3, n_ax), (3.3 * n_ax, 7.6), sharex=True)
    grid = np.asarray(panels, dtype=object).reshape(3, n_ax)
    for c in range(3):
        for j, a_x in enumerate(a_x_levels):
            ax = grid[c, j]
            for k, b in enumerate(b_levels):
                sign = int(np.sign(b))
                solid = APPLIED_COLOR if sign else SIGN_COLORS[0]
                label = "elastica, couple applied" + (" (±B)" if sign else " (B = 0)")
                ax.plot(a_y, applied[j, k, :, c], "-", color=solid, lw=1.2, label=label)
                if sign:
                    printed_label = f"elastica, couple printed (B = {_minus(b)})"
                    ax.plot(a_y, printed[j, k, :, c], "--", color=SIGN_COLORS[sign], lw=1.0,
                            label=printed_label)  # fmt: skip
                _markers(ax, a_y, fe[j, k, :, c], b)
            title = f"{panel_label(c * n_ax + j)} $A_x$ = {_minus(a_x)}"
            ax.set_title(title, fontsize=9)
            readable_value_axis(ax.yaxis)
            if j == 0:
                ax.set_ylabel(COMPONENT_LABELS[c])
            if c == 2:
                ax.set_xlabel(LOAD_LABEL)
    handles, labels = grid[0, 0].get_legend_handles_labels()
    unique = dict(sorted(zip(labels, handles, strict=True), key=_legend_order))
    fig.legend(unique.values(), unique.keys(), loc="lower center", ncol=3, fontsize=7,
               bbox_to_anchor=(0.5, -0.08))  # fmt: skip
    return fig


def deformed_shapes(
    lines: np.ndarray,
    outlines: np.ndarray,
    ours: np.ndarray,
    fe: np.ndarray,
    rest_lines: np.ndarray,
    rest_outline: np.ndarray,
    titles: Sequence[str],
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """The deformed parallelogram at a few loads, to scale, one panel per load.

    Parameters
    ----------
    lines : numpy.ndarray, shape (n, 2, m, 2)
        Both beams' centre lines per load, (x, y)/L.
    outlines : numpy.ndarray, shape (n, 5, 2)
        The stage block's outline per load, (x, y)/L.
    ours, fe : numpy.ndarray, shape (n, 2)
        The load point of the elastica and of the 3-D FE, (x, y)/L (NaN: no FE row).
    rest_lines, rest_outline : numpy.ndarray, shapes (2, m, 2) and (5, 2)
        The unloaded mechanism, drawn in grey.
    titles : sequence of str
        One per load (e.g. its loads).
    axes : sequence of Axes, optional
        ``n`` panels.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        If the arrays do not hold one entry per title, or ``axes`` another number of Axes.
    """
    n = len(titles)
    if not len(lines) == len(outlines) == len(ours) == len(fe) == n:
        raise ValueError(f"lines, outlines, ours and fe must hold {n} loads, one per title")
    fig, panels = figure_and_panels(axes, (1, n), (2.9 * n, 3.6))
    drawn = np.concatenate([np.reshape(lines, (-1, 2)), np.reshape(outlines, (-1, 2)),
                            np.reshape(rest_outline, (-1, 2))])  # fmt: skip
    low, high = drawn.min(axis=0) - 0.05, drawn.max(axis=0) + 0.05
    for j, ax in enumerate(panels):
        for beam in rest_lines:
            ax.plot(beam[:, 0], beam[:, 1], color="0.75", lw=1.0)
        ax.add_patch(Polygon(rest_outline, closed=True, fc="0.92", ec="0.75", lw=0.8))
        for beam in lines[j]:
            ax.plot(beam[:, 0], beam[:, 1], color=OURS_COLOR, lw=1.6)
        ax.add_patch(Polygon(outlines[j], closed=True, fc="#d6e6f5", ec=OURS_COLOR, lw=1.0))
        ax.plot(*ours[j], "o", color=OURS_COLOR, ms=4, label="load point, elastica")
        if np.all(np.isfinite(fe[j])):
            ax.plot(*fe[j], "x", color=PUBLISHED_COLOR, ms=7, mew=1.6, label="load point, 3-D FE")
        ax.set(xlim=(low[0], high[0]), ylim=(low[1], high[1]), aspect="equal")
        ax.set_title(f"{panel_label(j)} {titles[j]}", fontsize=9)
        ax.set_xlabel("$x/L$ [–]")
    panels[0].set_ylabel("$y/L$ [–]")
    unique = {}
    for ax in panels:
        for handle, label in zip(*ax.get_legend_handles_labels(), strict=True):
            unique.setdefault(label, handle)
    fig.legend(unique.values(), unique.keys(), loc="lower center", ncol=2, fontsize=7,
               bbox_to_anchor=(0.5, -0.08))  # fmt: skip
    return fig


def line_differences(
    loads: np.ndarray, shares: np.ndarray, axes: Sequence[Axes] | None = None
) -> Figure:
    """Our FE's difference from the published 3-D FE at every row solved, against A_y: one line
    per line of the sweep (its A_x and applied B), a lone row (a corner of the grid) as a grey
    marker of its own, the largest difference of each component ringed.

    Parameters
    ----------
    loads : ndarray (n, 3)
        A_x, A_y and the couple applied of every row.
    shares : ndarray (n, 3)
        |our FE − published FE| per row and component, % of full scale.
    axes : sequence of Axes, optional
        Three panels.
    """
    loads, shares = np.asarray(loads, dtype=float), np.asarray(shares, dtype=float)
    fig, panels = figure_and_panels(axes, (1, 3), (10.2, 3.4))
    groups: dict[tuple[float, float], list[int]] = {}
    for i, (a_x, _, b) in enumerate(loads):
        groups.setdefault((float(a_x), float(b)), []).append(i)
    colours = iter(("0.15", OURS_COLOR, ACTIVE_COLOR, PUBLISHED_COLOR, APPLIED_COLOR, "0.55"))
    corners = iter(("*", "P", "X", "D", "v", "^", "<", ">"))
    for (a_x, b), rows in sorted(groups.items()):
        rows = sorted(rows, key=lambda i: loads[i, 1])
        label = f"$A_x$ = {_minus(a_x)}, $B$ = {_minus(b)}"
        if len(rows) == 1:
            marker = next(corners, "o")
            for c, ax in enumerate(panels):
                ax.plot(loads[rows, 1], shares[rows, c], marker, color="0.3", ms=6,
                        label=f"{label} (corner)" if c == 0 else None)  # fmt: skip
            continue
        colour = next(colours, "0.55")
        for c, ax in enumerate(panels):
            ax.plot(loads[rows, 1], shares[rows, c], "-o", color=colour, lw=1.1, ms=3,
                    label=label if c == 0 else None)  # fmt: skip
    for c, ax in enumerate(panels):
        worst = int(np.argmax(shares[:, c]))
        ax.plot(loads[worst, 1], shares[worst, c], "o", ms=12, mfc="none", color="k")
        ax.set_title(f"{panel_label(c)} {COMPONENT_LABELS[c].split(' [')[0]}", fontsize=9)
        ax.set_xlabel(LOAD_LABEL)
        ax.set_ylabel("|our FE − published| [% of full scale]" if c == 0 else "")
        readable_value_axis(ax.yaxis)
    panels[0].legend(fontsize=6)
    return fig
