"""Figures of the design-of-experiments chapter: half-normal and Pareto plots (Figs 6, 7), the
discrepancy of a design against random ones, matrix differences and running errors."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import matplotlib.ticker as mticker
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from mechlib.plotting.style import (
    ACTIVE_COLOR,
    OURS_COLOR,
    PUBLISHED_COLOR,
    figure_and_axes,
    figure_and_panels,
    margin_line,
    panel_grid,
    panel_label,
    readable_value_axis,
)
from mechlib.screening import half_normal_points, pareto_order

#: Size [in] of a figure of two rows of three response panels.
SIX_PANELS_SIZE = (10.0, 5.6)


def _effects(effects: object, factor_names: Sequence[str], response_labels: Sequence[str]):
    e = np.asarray(effects, dtype=float)
    if e.ndim != 2 or e.shape != (len(factor_names), len(response_labels)):
        raise ValueError(
            f"effects must have shape (factors, responses) = "
            f"({len(factor_names)}, {len(response_labels)}), got {e.shape}"
        )
    return e


def _response_panels(axes, n: int):
    rows, cols = panel_grid(n)
    size = (SIX_PANELS_SIZE[0] * cols / 3, SIX_PANELS_SIZE[1] * rows / 2)
    return figure_and_panels(axes, (rows, cols), size)


def half_normal_panels(
    effects: np.ndarray,
    factor_names: Sequence[str],
    response_labels: Sequence[str],
    margins: Sequence[float] | None = None,
    title: str = "",
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """Fig 6: one half-normal plot of |effects| per response.

    Parameters
    ----------
    effects : numpy.ndarray, shape (factors, responses)
    factor_names, response_labels : sequence of str
        One name per row and per column of ``effects``.
    margins : sequence of float, optional
        A margin (Lenth's ME) per response, drawn as a dashed line where positive.
    title : str
        The figure's title.
    axes : sequence of Axes, optional
        One panel per response (new figure: rows of three panels).

    Returns
    -------
    matplotlib.figure.Figure
    """
    e = _effects(effects, factor_names, response_labels)
    fig, panels = _response_panels(axes, e.shape[1])
    for j, ax in enumerate(panels):
        order, mag, q = half_normal_points(e[:, j])
        ax.plot(mag, q, "o", color=OURS_COLOR)
        for m, qq, i in zip(mag, q, order, strict=True):
            ax.annotate(
                factor_names[i], (m, qq), textcoords="offset points", xytext=(4, -3), fontsize=7
            )
        ax.set_title(f"{panel_label(j)} {response_labels[j]}")
        ax.set_xlabel("|effect|")
        ax.set_ylabel("half-normal quantile")
        top = max(mag.max(), 1e-12)
        ax.set_xlim(left=-0.05 * top, right=1.25 * top)
        margin_line(ax, None if margins is None else margins[j])  # widens the axis to show it
        readable_value_axis(ax.xaxis)
    fig.suptitle(title)
    return fig


def pareto_panels(
    effects: np.ndarray,
    factor_names: Sequence[str],
    response_labels: Sequence[str],
    margins: Sequence[float] | None = None,
    title: str = "",
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """Fig 7: Pareto chart of |effects| per response, largest first.

    Parameters
    ----------
    effects, factor_names, response_labels, margins, title
        As in :func:`half_normal_panels`.
    axes : sequence of Axes, optional
        One panel per response (new figure: rows of three panels).

    Returns
    -------
    matplotlib.figure.Figure
    """
    e = _effects(effects, factor_names, response_labels)
    fig, panels = _response_panels(axes, e.shape[1])
    for j, ax in enumerate(panels):
        order = pareto_order(e[:, j])
        ticks = np.arange(len(order))[::-1]
        ax.barh(ticks, np.abs(e[order, j]), color=OURS_COLOR)
        ax.set_yticks(ticks, [factor_names[i] for i in order])
        margin_line(ax, None if margins is None else margins[j])
        ax.set_title(f"{panel_label(j)} {response_labels[j]}")
        ax.set_xlabel("|effect|")
        readable_value_axis(ax.xaxis)
    fig.suptitle(title)
    return fig


def discrepancy_histogram(
    random_cd: np.ndarray, design_cd: float, label: str, ax: Axes | None = None
) -> Figure:
    """Histogram of the CD2 of random balanced designs with one design's CD2 marked.

    Parameters
    ----------
    random_cd : numpy.ndarray, shape (n,)
        Squared centred L2 discrepancies of the random designs.
    design_cd : float
        The marked design's value.
    label : str
        Legend entry of the marked design.
    ax : Axes, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax = figure_and_axes(ax, (6.0, 3.4))
    ax.hist(random_cd, bins=40, color=PUBLISHED_COLOR, alpha=0.8, label="random balanced designs")
    ax.axvline(design_cd, color=ACTIVE_COLOR, lw=2, label=label)
    ax.set_xlabel("centred L2 discrepancy (CD2, squared)")
    ax.set_ylabel("count")
    ax.legend()
    return fig


def relative_difference_pct(reference: np.ndarray, other: np.ndarray) -> np.ndarray:
    """``100 (other − reference) / |reference|`` entry by entry; NaN where the reference is 0."""
    reference, other = np.asarray(reference, dtype=float), np.asarray(other, dtype=float)
    if other.shape != reference.shape:
        raise ValueError(
            f"matrices must have the reference's shape {reference.shape}, got {other.shape}"
        )
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(reference != 0, 100 * (other - reference) / np.abs(reference), np.nan)


def matrix_difference(
    reference: np.ndarray,
    others: Mapping[str, np.ndarray],
    row_labels: Sequence[str],
    col_labels: Sequence[str],
    title: str = "",
    reference_label: str = "reference",
    limit: float | None = None,
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """Heat maps of the relative difference [%] of several matrices from a reference.

    Parameters
    ----------
    reference : numpy.ndarray, shape (m, n)
    others : mapping of str to numpy.ndarray, shape (m, n)
        One panel per matrix, titled by its key.
    row_labels, col_labels : sequence of str
    title : str
        The figure's title.
    reference_label : str
        Name of the reference in the colour bar's label ("difference from <name> [%]").
    limit : float, optional
        Half-range [%] of the symmetric colour scale; default: the largest |difference| drawn.
    axes : sequence of Axes, optional
        One panel per entry of ``others``.

    Returns
    -------
    matplotlib.figure.Figure
    """
    rel = {name: relative_difference_pct(reference, m) for name, m in others.items()}
    if limit is None:
        finite = np.concatenate([r[np.isfinite(r)] for r in rel.values()] + [np.zeros(1)])
        limit = max(float(np.abs(finite).max()), 1e-12)
    elif not limit > 0:
        raise ValueError(f"limit must be > 0 %, got {limit}")
    fig, panels = figure_and_panels(axes, (1, len(rel)), (4.2 * len(rel), 3.6))
    for ax, (name, r) in zip(panels, rel.items(), strict=True):
        im = ax.imshow(r, cmap="coolwarm", vmin=-limit, vmax=limit)
        for (i, j), v in np.ndenumerate(r):
            if np.isfinite(v):
                ax.text(j, i, f"{v:+.2f}", ha="center", va="center", fontsize=7)
        ax.set_xticks(range(len(col_labels)), col_labels, rotation=45, fontsize=7)
        ax.set_yticks(range(len(row_labels)), row_labels, fontsize=7)
        ax.grid(False)
        ax.set_title(name, fontsize=9)
    fig.colorbar(im, ax=list(panels), label=f"difference from {reference_label} [%]", shrink=0.8)
    fig.suptitle(title)
    return fig


def running_errors(
    running: Mapping[str, np.ndarray],
    labels: Sequence[str],
    title: str,
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """Pointwise maximum error, and maximum error in % of full scale, against the number of
    validation runs.

    Parameters
    ----------
    running : mapping
        The output of :func:`mechlib.metamodels.metrics.running_error_metrics`: ``runs`` (k,) and
        ``max_rel_pct``, ``max_range_pct`` (k, responses).
    labels : sequence of str
        One legend entry per response.
    title : str
        The figure's title.
    axes : sequence of 2 Axes, optional
        The pointwise and the full-scale panel.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, panels = figure_and_panels(axes, (1, 2), (10.0, 3.8), sharex=True)
    k = np.asarray(running["runs"])
    for ax, key, name in zip(
        panels,
        ("max_rel_pct", "max_range_pct"),
        ("pointwise: max 100 |ψ − ψ̂| / |ψ|", "% of full scale: 100 MAXABS / max |ψ|"),
        strict=True,
    ):
        for j, label in enumerate(labels):
            ax.plot(k, np.maximum(running[key][:, j], 1e-12), label=label, lw=1.2)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.xaxis.set_major_formatter(mticker.FormatStrFormatter("%g"))
        # plain run counts on the minor ticks too while they fit (fewer than ten runs)
        few = k[-1] < 10
        ax.xaxis.set_minor_formatter(
            mticker.FormatStrFormatter("%g") if few else mticker.NullFormatter()
        )
        ax.set_xlabel("runs included")
        ax.set_ylabel("max error [%]")
        ax.set_title(name, fontsize=9)
    panels[0].legend(fontsize=7, ncol=2)
    fig.suptitle(title)
    return fig
