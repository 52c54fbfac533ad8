"""The book's figure style and the helpers every chapter's figures share.

Every public figure function of :mod:`mechlib.plotting` takes arrays (or plain containers of
arrays), draws into the Axes it is given — ``ax=`` for one panel, ``axes=`` (a sequence of the
documented length) for several — or into a new figure, and returns the matplotlib Figure.
Nothing here solves or samples a model: the data arrive computed.
"""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib import ticker
from matplotlib.axes import Axes
from matplotlib.axis import Axis
from matplotlib.collections import PolyCollection
from matplotlib.figure import Figure

STYLE = {
    "figure.dpi": 110,
    "savefig.dpi": 110,
    "font.size": 9,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "svg.hashsalt": "mechlib",  # deterministic SVG ids
}
PUBLISHED_COLOR = "#7f7f7f"
OURS_COLOR = "#1f77b4"
ACTIVE_COLOR = "#d62728"
#: Fill of a reachable region (Fig 10).
REGION_COLOR = "#e8f0fa"


def use_style() -> None:
    """Apply the book's matplotlib style (``STYLE``) to every later figure."""
    plt.rcParams.update(STYLE)


def figure_and_axes(ax: Axes | None, figsize: tuple[float, float]) -> tuple[Figure, Axes]:
    """The Axes to draw into and its Figure: ``ax`` itself, or a new figure of ``figsize``.

    Parameters
    ----------
    ax : matplotlib.axes.Axes or None
    figsize : (float, float)
        Size [in] of the figure created when ``ax`` is None.

    Returns
    -------
    (Figure, Axes)
    """
    if ax is None:
        fig, ax = plt.subplots(figsize=figsize, constrained_layout=True)
        return fig, ax
    if not isinstance(ax, Axes):
        raise TypeError(f"ax must be a matplotlib Axes or None, got {type(ax).__name__}")
    return ax.figure, ax


def figure_and_panels(
    axes: Sequence[Axes] | np.ndarray | None,
    shape: tuple[int, int],
    figsize: tuple[float, float],
    **subplots_kw,
) -> tuple[Figure, np.ndarray]:
    """The panels to draw into, flattened, and their Figure.

    Parameters
    ----------
    axes : sequence of Axes, or None
        Exactly ``shape[0] * shape[1]`` Axes (any layout, of one figure); None makes a new figure
        with a ``shape`` grid of panels.
    shape : (int, int)
        Rows and columns of the new figure's panels.
    figsize : (float, float)
        Size [in] of the new figure.
    **subplots_kw
        Passed to :func:`matplotlib.pyplot.subplots` for a new figure only (``sharex``,
        ``gridspec_kw``, …).

    Returns
    -------
    (Figure, numpy.ndarray of Axes)

    Raises
    ------
    ValueError
        If ``axes`` holds another number of Axes, or Axes of several figures.
    """
    n = shape[0] * shape[1]
    if axes is None:
        fig, grid = plt.subplots(
            *shape, figsize=figsize, constrained_layout=True, squeeze=False, **subplots_kw
        )
        return fig, grid.ravel()
    flat = np.asarray(axes, dtype=object).ravel()
    if len(flat) != n or not all(isinstance(a, Axes) for a in flat):
        raise ValueError(f"axes must hold {n} matplotlib Axes, got {len(flat)} objects")
    if len({id(a.figure) for a in flat}) != 1:
        raise ValueError("axes must all belong to one figure")
    return flat[0].figure, flat


def panel_grid(n: int, columns: int = 3) -> tuple[int, int]:
    """Rows and columns of a grid of ``n`` panels at most ``columns`` wide."""
    return (n + columns - 1) // columns, min(n, columns)


#: at most this many ticks on a value axis of a small panel, so that long labels do not collide
VALUE_TICKS = 4


def readable_value_axis(axis: Axis) -> None:
    """At most :data:`VALUE_TICKS` ticks, and large or small magnitudes as a power of ten shown
    once at the axis's end (``×10⁵``) instead of long labels that collide.

    Parameters
    ----------
    axis : matplotlib.axis.Axis
        E.g. ``ax.xaxis``.
    """
    axis.set_major_locator(ticker.MaxNLocator(VALUE_TICKS))
    formatter = ticker.ScalarFormatter(useMathText=True)
    formatter.set_powerlimits((-3, 4))
    axis.set_major_formatter(formatter)


def panel_label(j: int) -> str:
    """``(a)``, ``(b)``, … for panel ``j`` (0-based)."""
    return f"({chr(ord('a') + j)})"


def margin_line(ax: Axes, margin: float | None, label: str = "Lenth ME") -> None:
    """A dashed vertical line at ``margin`` with a legend entry, when it is positive; the
    x-axis is widened to show it when it lies beyond the drawn values."""
    if margin is not None and margin > 0:
        left, right = ax.get_xlim()
        if margin >= right:
            ax.set_xlim(left, margin * 1.08)
        ax.axvline(margin, color=ACTIVE_COLOR, ls="--", lw=1, label=label)
        ax.legend(loc="lower right", fontsize=7)


def draw_quads(
    ax: Axes,
    nodes: np.ndarray,
    quads: np.ndarray,
    values: np.ndarray | None = None,
    cmap: str = "viridis",
    **kw,
) -> PolyCollection:
    """Draw quadrilaterals ``nodes[quads]`` (optionally coloured by ``values``) with equal axes.

    Parameters
    ----------
    ax : Axes
    nodes : numpy.ndarray, shape (n, 2)
    quads : numpy.ndarray of int, shape (m, 4)
    values : numpy.ndarray, shape (m,), optional
        One value per quad, mapped through ``cmap``.
    **kw
        Passed to :class:`matplotlib.collections.PolyCollection` (``facecolors``, …).

    Returns
    -------
    PolyCollection
    """
    pc = PolyCollection(np.asarray(nodes)[np.asarray(quads)], **kw)
    if values is not None:
        pc.set_array(values)
        pc.set_cmap(cmap)
    ax.add_collection(pc)
    ax.autoscale_view()
    ax.set_aspect("equal")
    return pc


def circle(ax: Axes, center: Sequence[float], radius: float, **kw) -> None:
    """An unfilled circle (e.g. the MIW) in data coordinates."""
    ax.add_patch(plt.Circle(tuple(center), radius, fill=False, **kw))


def unit_ticks(names: Sequence[str], units: Sequence[str] | None) -> list[str]:
    """Tick labels with each parameter's unit.

    Parameters
    ----------
    names : sequence of str
    units : sequence of str or None
        One unit per name ("" for a unitless gain); None keeps the names.

    Returns
    -------
    list of str
        ``["l1 [m]", "k1", …]``.

    Raises
    ------
    ValueError
        When ``units`` has another length than ``names``.
    """
    if units is None:
        return list(names)
    if len(units) != len(names):
        raise ValueError(f"{len(names)} parameter names need as many units, got {len(units)}")
    return [f"{n} [{u}]" if u else n for n, u in zip(names, units, strict=True)]
