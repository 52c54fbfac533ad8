"""Figures of the five-bar chapter: workspace and singularities (Fig 10), the leg loop (Fig 11),
postures (Fig 12), parameter errors (Fig 13), error maps (Fig 14), and the Monte Carlo
distributions and sensitivity.

The data arrive computed: the singularity field and the leg chains by
:mod:`mechlib.fivebar.workspace`, the errors by the calibration core
(:mod:`mechlib.calibration.montecarlo`, :mod:`mechlib.calibration.statistics`). A MIW is the dict
of :func:`mechlib.fivebar.kinematics.miw_closed_form` (``cx``, ``cy``, ``radius`` [m]).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from matplotlib import colors
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from mechlib.fivebar.workspace import SingularityField
from mechlib.plotting.style import (
    ACTIVE_COLOR,
    OURS_COLOR,
    PUBLISHED_COLOR,
    REGION_COLOR,
    circle,
    figure_and_axes,
    figure_and_panels,
    panel_label,
    unit_ticks,
)

#: Strategy colours of the Monte Carlo figures, in the order the strategies are given.
STRATEGY_COLORS = (OURS_COLOR, ACTIVE_COLOR)
#: Metres to micrometres, for error axes.
UM_PER_M = 1e6


def _miw_circle(ax: Axes, miw: Mapping[str, float], radius: float | None = None, **kw) -> None:
    r = miw["radius"] if radius is None else radius
    circle(ax, (miw["cx"], miw["cy"]), r, color=OURS_COLOR, **kw)


def fivebar_workspace(
    field: SingularityField,
    miw: Mapping[str, float],
    legs: Sequence[np.ndarray] | np.ndarray,
    ax: Axes | None = None,
) -> Figure:
    """Fig 10: reach of both legs, the parallel singularity, the MIW and the mechanism in a pose.

    Parameters
    ----------
    field : SingularityField
        Reach and parallel-singularity measure on a grid
        (:func:`mechlib.fivebar.workspace.singularity_field`); its window is the plot's.
    miw : mapping
        ``cx``, ``cy``, ``radius`` [m].
    legs : sequence of numpy.ndarray, shape (3, 2)
        Each leg's base, elbow and end-effector [m]
        (:func:`mechlib.fivebar.workspace.mechanism_chains`).
    ax : Axes, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax = figure_and_axes(ax, (6.4, 5.2))
    xx, yy = np.meshgrid(field.x, field.y)
    ax.contourf(xx, yy, field.reachable, levels=[0.5, 1.5], colors=[REGION_COLOR])
    if np.any(field.reachable):
        ax.contour(xx, yy, field.parallel, levels=[0.0], colors=[ACTIVE_COLOR], linewidths=1.2)
    _miw_circle(ax, miw, lw=2)
    for chain in legs:
        c = np.asarray(chain, dtype=float)
        ax.plot(c[:, 0], c[:, 1], "-o", color="k", lw=2, ms=4)
    modes = ", ".join(f"{m:+d}".replace("-", "−") for m in field.modes)
    ax.plot([], [], color=ACTIVE_COLOR, label=f"parallel singularity (working modes {modes})")
    ax.plot([], [], color=OURS_COLOR, label="maximal inscribed workspace")
    ax.fill([], [], color=REGION_COLOR, label="reachable by both legs")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.legend(loc="upper right", fontsize=7)
    ax.set_title("Fig 10: planar 5R, workspace, singularities and MIW")
    return fig


def fivebar_leg_loop(
    chain: np.ndarray, theta: float, gamma: float, ax: Axes | None = None
) -> Figure:
    """Fig 11: the vector loop P = A + l + L of one leg (Eq 22) with its parameters (Eq 21).

    Parameters
    ----------
    chain : numpy.ndarray, shape (3, 2)
        Base A, elbow B, end-effector P [m] (:func:`mechlib.fivebar.workspace.leg_chain`).
    theta : float
        Active angle [rad], drawn as an arc from 0.
    gamma : float
        Joint offset γ [rad] (Eq 20), drawn as a dotted reference line at A.
    ax : Axes, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    a, b, p = np.asarray(chain, dtype=float)
    fig, ax = figure_and_axes(ax, (5.6, 4.4))
    arrow = {"length_includes_head": True, "head_width": 0.04, "lw": 1.5}
    ax.arrow(0.0, 0.0, *a, color=PUBLISHED_COLOR, ls="--", **arrow)
    ax.arrow(*a, *(b - a), color=OURS_COLOR, **arrow)
    ax.arrow(*b, *(p - b), color=ACTIVE_COLOR, **arrow)
    ax.arrow(0.0, 0.0, *p, color="k", **arrow)
    ref = 0.25 * np.array([np.cos(gamma), np.sin(gamma)])
    ax.plot([a[0], a[0] + ref[0]], [a[1], a[1] + ref[1]], ":", color="k")
    arc = np.linspace(0.0, theta, 40)
    ax.plot(a[0] + 0.18 * np.cos(arc), a[1] + 0.18 * np.sin(arc), color=OURS_COLOR, lw=1)
    labels = (
        (0.5 * a + np.array([-0.12, 0.03]), r"$\mathbf{A} = (A_x, A_y)$"),
        (0.5 * (a + b) + [0.05, 0.0], r"$\mathbf{l}$, length $l$"),
        (0.5 * (b + p) + [0.05, 0.0], r"$\mathbf{L}$, length $L$"),
        (0.5 * p + [-0.32, 0.0], r"$\mathbf{P} = (x, y)$"),
        (a + np.array([0.2, 0.12]), r"$\theta = k\psi + \gamma$"),
    )
    for xy, text in labels:
        ax.annotate(text, xy, fontsize=9)
    ax.plot(*np.c_[[0.0, 0.0], a, b, p], "o", color="k", ms=4)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("Fig 11: leg loop P = A + l + L (Eqs 22–23)")
    return fig


def fivebar_postures(
    candidates: np.ndarray,
    chosen: Mapping[str, np.ndarray],
    miw: Mapping[str, float],
    fraction: float,
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """Fig 12: postures selected for the traditional method and for each leg (D&C).

    Parameters
    ----------
    candidates : numpy.ndarray, shape (n, 2)
        Candidate postures [m].
    chosen : mapping
        Indices into ``candidates``: ``trad``, ``leg1``, ``leg2``.
    miw : mapping
        ``cx``, ``cy``, ``radius`` [m].
    fraction : float
        Share of the MIW radius that bounds the candidates (dotted circle).
    axes : sequence of 3 Axes, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, panels = figure_and_panels(axes, (1, 3), (11.0, 4.4), sharey=True)
    titles = {"trad": "(a) traditional", "leg1": "(b) D&C, left leg", "leg2": "(c) D&C, right leg"}
    for ax, (key, title) in zip(panels, titles.items(), strict=True):
        ax.plot(candidates[:, 0], candidates[:, 1], ".", color="#cccccc", ms=1.5, label="candidate")
        sel = candidates[chosen[key]]
        ax.plot(sel[:, 0], sel[:, 1], "o", color=ACTIVE_COLOR, ms=5, label="selected posture")
        _miw_circle(ax, miw, ls="-", label="MIW")
        _miw_circle(
            ax, miw, fraction * miw["radius"], ls=":", label=f"{fraction:.0%} of the MIW radius"
        )
        ax.set_aspect("equal")
        ax.set_title(f"{title}: {len(sel)} postures")
        ax.set_xlabel("x [m]")
    panels[0].set_ylabel("y [m]")
    handles, names = panels[0].get_legend_handles_labels()
    fig.legend(handles, names, loc="outside lower center", ncol=len(names), fontsize=8)
    return fig


#: the value axis of per-parameter errors: each parameter keeps its own unit (tick label)
PARAMETER_ERROR_LABEL = "|error| (unit under each bar; gains unitless)"


def fivebar_parameter_errors(
    names: Sequence[str],
    before: np.ndarray,
    dc: np.ndarray,
    trad: np.ndarray,
    ax: Axes | None = None,
    units: Sequence[str] | None = None,
) -> Figure:
    """Fig 13: parameter errors (value − real) before and after calibration, log scale.

    Parameters
    ----------
    names : sequence of str
        Parameter names.
    before, dc, trad : numpy.ndarray, shape (len(names),)
        Errors of the nominal, D&C and traditional parameters, each in its parameter's unit
        (m for lengths, rad for angles; gains are unitless).
    ax : Axes, optional
    units : sequence of str, optional
        Each parameter's unit, shown in its tick label ("" for a unitless gain).

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax = figure_and_axes(ax, (9.0, 3.6))
    x = np.arange(len(names))
    for off, vals, label, color in (
        (-0.27, before, "nominal (before)", PUBLISHED_COLOR),
        (0.0, dc, "divide and conquer", OURS_COLOR),
        (0.27, trad, "traditional", ACTIVE_COLOR),
    ):
        ax.bar(x + off, np.abs(vals), 0.27, label=label, color=color)
    ax.set_yscale("log")
    ax.set_xticks(x, unit_ticks(names, units), rotation=45)
    ax.set_ylabel(PARAMETER_ERROR_LABEL)
    ax.legend(fontsize=7)
    ax.set_title("Fig 13: residual parameter errors, one seeded draw")
    return fig


def fivebar_error_maps(
    grid: np.ndarray,
    maps: Mapping[str, np.ndarray],
    miw: Mapping[str, float],
    axes: Sequence[Axes] | None = None,
    shared: Sequence[str] = (),
    ratio: tuple[str, np.ndarray] | None = None,
) -> Figure:
    """Fig 14: local RMS position error over the workspace, one panel per model.

    Parameters
    ----------
    grid : numpy.ndarray, shape (n, 2)
        Evaluation points [m].
    maps : mapping of str to numpy.ndarray, shape (n,)
        Panel title → local RMS error [m] at each point.
    miw : mapping
        ``cx``, ``cy``, ``radius`` [m].
    axes : sequence of Axes, optional
        One panel per map (and one more for ``ratio``).
    shared : sequence of str
        Titles of the maps drawn on one colour scale (one colour bar), so that their colours
        compare; the other maps get a scale each.
    ratio : (title, numpy.ndarray of shape (n,)), optional
        A last panel of a ratio of two maps, on a diverging scale centred on 1.

    Returns
    -------
    matplotlib.figure.Figure
    """
    unknown = set(shared) - set(maps)
    if unknown:
        raise ValueError(f"shared names maps that are not given: {sorted(unknown)}")
    # maps on their own scales, then the ratio, then the maps sharing one scale, so that the
    # shared ones sit side by side under one colour bar
    order = [k for k in maps if k not in shared] + (["ratio"] if ratio else []) + list(shared)
    grid_shape = (2, 2) if len(order) == 4 else (1, len(order))  # four panels: a square
    fig, panels = figure_and_panels(axes, grid_shape, (4.3 * grid_shape[1], 3.8 * grid_shape[0]))
    panels = list(np.ravel(panels))
    top = max((UM_PER_M * maps[k].max() for k in shared), default=None)
    for j, (ax, key) in enumerate(zip(panels, order, strict=False)):
        if key == "ratio":
            title, values = ratio
            spread = max(float(np.abs(np.log(values)).max()), 1e-3)
            norm = colors.TwoSlopeNorm(1.0, np.exp(-spread), np.exp(spread))
            sc = ax.scatter(grid[:, 0], grid[:, 1], c=values, s=14, cmap="RdBu_r", norm=norm)
            fig.colorbar(sc, ax=ax, label="ratio (1: equal)", shrink=0.8)
        else:
            title = key
            scale = {"vmin": 0.0, "vmax": top} if key in shared else {}
            sc = ax.scatter(
                grid[:, 0], grid[:, 1], c=UM_PER_M * maps[key], s=14, cmap="viridis", **scale
            )
            if key not in shared:
                fig.colorbar(sc, ax=ax, label="local RMS error [µm]", shrink=0.8)
            elif key == shared[-1]:
                joint = [panels[order.index(k)] for k in shared]
                fig.colorbar(sc, ax=joint, label="local RMS error [µm], same scale", shrink=0.8)
        _miw_circle(ax, miw)
        ax.set_aspect("equal")
        ax.set_title(f"{panel_label(j)} {title}")
        ax.set_xlabel("x [m]")
    for ax in panels[:: grid_shape[1]]:
        ax.set_ylabel("y [m]")
    fig.suptitle("Fig 14: position error over the workspace")
    return fig


def fivebar_distributions(
    rms: Mapping[str, np.ndarray],
    param_err: Mapping[str, np.ndarray],
    names: Sequence[str],
    axes: Sequence[Axes] | None = None,
    units: Sequence[str] | None = None,
) -> Figure:
    """Monte Carlo distributions: workspace RMS error and per-parameter errors, per strategy.

    Parameters
    ----------
    rms : mapping of str to numpy.ndarray, shape (trials,)
        Workspace RMS error [m] of each trial, per strategy (two strategies).
    param_err : mapping of str to numpy.ndarray, shape (trials, len(names))
        Parameter errors per trial, same strategies.
    names : sequence of str
    axes : sequence of 2 Axes, optional
        The histogram and the box plots.
    units : sequence of str, optional
        Each parameter's unit, shown in its tick label ("" for a unitless gain).

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, (ax0, ax1) = figure_and_panels(
        axes, (1, 2), (11.0, 3.8), gridspec_kw={"width_ratios": [1, 2]}
    )
    bins = np.histogram_bin_edges(UM_PER_M * np.concatenate(list(rms.values())), 30)
    for (label, vals), color in zip(rms.items(), STRATEGY_COLORS, strict=True):
        ax0.hist(UM_PER_M * vals, bins, alpha=0.55, color=color, label=label)
    ax0.set_xlabel("workspace RMS position error [µm]")
    ax0.set_ylabel("trials")
    ax0.legend(fontsize=7)
    x = np.arange(len(names))
    for off, ((label, err), color) in zip(
        (-0.2, 0.2), zip(param_err.items(), STRATEGY_COLORS, strict=True), strict=True
    ):
        parts = ax1.boxplot(
            np.abs(err), positions=x + off, widths=0.35, showfliers=False, patch_artist=True
        )
        for box in parts["boxes"]:
            box.set_facecolor(color)
            box.set_alpha(0.55)
        ax1.plot([], [], "s", color=color, alpha=0.55, label=label)
    ax1.set_yscale("log")
    ax1.set_xticks(x, unit_ticks(names, units), rotation=45)
    ax1.set_ylabel(PARAMETER_ERROR_LABEL)
    ax1.legend(fontsize=7)
    fig.suptitle("Monte Carlo distributions over the seeded trials")
    return fig


def fivebar_sensitivity(
    table,
    sigmas: Sequence[float],
    counts: Sequence[int],
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """Sensitivity of the D&C vs traditional verdict to σ and to the number of postures.

    Parameters
    ----------
    table : pandas.DataFrame
        The rows of :func:`mechlib.calibration.montecarlo.sweep` for one budget: ``n_per_leg``,
        ``n_shared``, ``sigma``, ``pos_rms_dc``, ``pos_rms_trad``, ``share_dc_better``.
    sigmas : sequence of float
        Noise levels [m and rad], the x ticks.
    counts : sequence of int
        Postures per leg, one line each.
    axes : sequence of 2 Axes, optional
        The RMS ratio and the share of trials won by D&C.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, (ax0, ax1) = figure_and_panels(axes, (1, 2), (10.0, 3.6))
    for n, marker in zip(counts, "osd^v", strict=False):
        sub = table[table["n_per_leg"] == n]
        ratio = sub["pos_rms_dc"] / sub["pos_rms_trad"]
        shared = int(sub["n_shared"].iloc[0])
        ax0.plot(sub["sigma"], ratio, marker=marker, label=f"{n} per leg / {shared} shared")
        ax1.plot(sub["sigma"], 100 * sub["share_dc_better"], marker=marker)
    ax0.axhline(1.0, color="k", lw=0.8)
    ax1.axhline(50.0, color="k", lw=0.8)
    for ax in (ax0, ax1):
        ax.set_xscale("log")
        ax.set_xlabel("σ [m and rad]")
        ax.set_xticks(list(sigmas))
    ax0.set_ylabel("workspace RMS, D&C / traditional")
    ax1.set_ylabel("trials where D&C is better [%]")
    ax0.legend(fontsize=7)
    fig.suptitle("Sensitivity of the verdict to noise and posture count (thesis's budgets)")
    return fig
