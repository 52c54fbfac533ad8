"""One figure style for the whole book, and the screening figures (Figs 6 and 7)."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import matplotlib.ticker as mticker
import numpy as np

from mechlib.screening import half_normal_points, pareto_order

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


def use_style() -> None:
    """Apply the book's matplotlib style."""
    plt.rcParams.update(STYLE)


def half_normal_panels(
    effects: np.ndarray,
    factor_names: Sequence[str],
    response_labels: Sequence[str],
    margins: Sequence[float] | None = None,
    title: str = "",
) -> plt.Figure:
    """Fig 6: one half-normal plot of |effects| per response (2 × 3 panels).

    Parameters
    ----------
    effects : numpy.ndarray, shape (factors, responses)
    factor_names, response_labels : sequence of str
    margins : sequence of float, optional
        Lenth's ME per response, drawn as a vertical line when positive.
    """
    fig, axes = plt.subplots(2, 3, figsize=(10, 5.6), constrained_layout=True)
    for j, ax in enumerate(axes.flat):
        order, mag, q = half_normal_points(effects[:, j])
        ax.plot(mag, q, "o", color=OURS_COLOR)
        for m, qq, i in zip(mag, q, order, strict=True):
            ax.annotate(
                factor_names[i], (m, qq), textcoords="offset points", xytext=(4, -3), fontsize=7
            )
        if margins is not None and margins[j] > 0:
            ax.axvline(margins[j], color=ACTIVE_COLOR, ls="--", lw=1, label="Lenth ME")
            ax.legend(loc="lower right", fontsize=7)
        ax.set_title(f"({'abcdef'[j]}) {response_labels[j]}")
        ax.set_xlabel("|effect|")
        ax.set_ylabel("half-normal quantile")
        ax.set_xlim(left=-0.05 * max(mag.max(), 1e-12), right=1.25 * max(mag.max(), 1e-12))
    fig.suptitle(title)
    return fig


def pareto_panels(
    effects: np.ndarray,
    factor_names: Sequence[str],
    response_labels: Sequence[str],
    margins: Sequence[float] | None = None,
    title: str = "",
) -> plt.Figure:
    """Fig 7: Pareto chart of |effects| per response, largest first (2 × 3 panels)."""
    fig, axes = plt.subplots(2, 3, figsize=(10, 5.6), constrained_layout=True)
    for j, ax in enumerate(axes.flat):
        order = pareto_order(effects[:, j])
        mag = np.abs(effects[order, j])
        ax.barh(np.arange(len(order))[::-1], mag, color=OURS_COLOR)
        ax.set_yticks(np.arange(len(order))[::-1], [factor_names[i] for i in order])
        if margins is not None and margins[j] > 0:
            ax.axvline(margins[j], color=ACTIVE_COLOR, ls="--", lw=1, label="Lenth ME")
            ax.legend(loc="lower right", fontsize=7)
        ax.set_title(f"({'abcdef'[j]}) {response_labels[j]}")
        ax.set_xlabel("|effect|")
    fig.suptitle(title)
    return fig


def discrepancy_histogram(random_cd: np.ndarray, design_cd: float, label: str) -> plt.Figure:
    """Histogram of the CD2 of random balanced designs with the given design marked."""
    fig, ax = plt.subplots(figsize=(6, 3.4), constrained_layout=True)
    ax.hist(random_cd, bins=40, color=PUBLISHED_COLOR, alpha=0.8, label="random balanced designs")
    ax.axvline(design_cd, color=ACTIVE_COLOR, lw=2, label=label)
    ax.set_xlabel("centred L2 discrepancy (CD2, squared)")
    ax.set_ylabel("count")
    ax.legend()
    return fig


def matrix_difference(
    reference: np.ndarray,
    others: dict[str, np.ndarray],
    row_labels: Sequence[str],
    col_labels: Sequence[str],
    title: str = "",
) -> plt.Figure:
    """Heat maps of the relative difference (%) of several matrices from a reference."""
    fig, axes = plt.subplots(
        1, len(others), figsize=(4.2 * len(others), 3.6), constrained_layout=True, squeeze=False
    )
    for ax, (name, m) in zip(axes.flat, others.items(), strict=True):
        with np.errstate(divide="ignore", invalid="ignore"):
            rel = np.where(reference != 0, 100 * (m - reference) / np.abs(reference), np.nan)
        im = ax.imshow(rel, cmap="coolwarm", vmin=-0.7, vmax=0.7)
        for (i, j), v in np.ndenumerate(rel):
            if np.isfinite(v):
                ax.text(j, i, f"{v:+.2f}", ha="center", va="center", fontsize=7)
        ax.set_xticks(range(len(col_labels)), col_labels, rotation=45, fontsize=7)
        ax.set_yticks(range(len(row_labels)), row_labels, fontsize=7)
        ax.grid(False)
        ax.set_title(name, fontsize=9)
    fig.colorbar(im, ax=axes, label="difference from Eq 8 [%]", shrink=0.8)
    fig.suptitle(title)
    return fig


def _singularity_field(mech, xlim, ylim, n=400):
    """Singularity measures on a grid (NaN where a leg cannot reach)."""
    from mechlib.fivebar import kinematics as kin

    xs, ys = np.linspace(*xlim, n), np.linspace(*ylim, n)
    xx, yy = np.meshgrid(xs, ys)
    pts = np.column_stack([xx.ravel(), yy.ravel()])
    ok = np.all(
        [np.abs(kin.reach_cosine(pts, p)) < 1 for p in (mech.nominal1, mech.nominal2)], axis=0
    )
    par = np.full(len(pts), np.nan)
    par[ok] = kin.singularity_measures(pts[ok], mech.nominal1, mech.nominal2, mech.modes)[
        "parallel"
    ]
    return xx, yy, ok.reshape(xx.shape), par.reshape(xx.shape)


def _draw_mechanism(ax, mech, point):
    from mechlib.fivebar import kinematics as kin

    for phi, mode, color in (
        (mech.nominal1, mech.modes[0], "k"),
        (mech.nominal2, mech.modes[1], "k"),
    ):
        psi = kin.joint_reading(np.atleast_2d(point), phi, mode)
        b = kin.elbow(psi, phi)[0]
        ax.plot([phi[2], b[0], point[0]], [phi[3], b[1], point[1]], "-o", color=color, lw=2, ms=4)


def fivebar_workspace(mech, miw: dict, pose: tuple[float, float]) -> plt.Figure:
    """Fig 10: the mechanism in one pose, its reachable set, parallel singularity and MIW."""
    fig, ax = plt.subplots(figsize=(6.4, 5.2), constrained_layout=True)
    xx, yy, ok, par = _singularity_field(mech, (-2.2, 2.2), (-0.5, 2.2))
    ax.contourf(xx, yy, ok, levels=[0.5, 1.5], colors=["#e8f0fa"])
    ax.contour(
        xx, yy, np.where(ok, par, np.nan), levels=[0.0], colors=[ACTIVE_COLOR], linewidths=1.2
    )
    circle = plt.Circle((miw["cx"], miw["cy"]), miw["radius"], fill=False, color=OURS_COLOR, lw=2)
    ax.add_patch(circle)
    _draw_mechanism(ax, mech, np.array(pose))
    ax.plot([], [], color=ACTIVE_COLOR, label="parallel singularity (working modes +1, −1)")
    ax.plot([], [], color=OURS_COLOR, label="maximal inscribed workspace")
    ax.fill([], [], color="#e8f0fa", label="reachable by both legs")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.legend(loc="upper right", fontsize=7)
    ax.set_title("Fig 10: planar 5R, workspace, singularities and MIW")
    return fig


def fivebar_postures(
    candidates: np.ndarray, chosen: dict, miw: dict, fraction: float
) -> plt.Figure:
    """Fig 12: postures selected for the traditional method and for each leg (D&C)."""
    fig, axes = plt.subplots(1, 3, figsize=(11, 3.9), constrained_layout=True, sharey=True)
    for ax, (key, title) in zip(
        axes,
        (
            ("trad", "(a) traditional"),
            ("leg1", "(b) D&C, left leg"),
            ("leg2", "(c) D&C, right leg"),
        ),
        strict=True,
    ):
        ax.plot(candidates[:, 0], candidates[:, 1], ".", color="#cccccc", ms=1.5)
        sel = candidates[chosen[key]]
        ax.plot(sel[:, 0], sel[:, 1], "o", color=ACTIVE_COLOR, ms=5)
        for r, ls in ((miw["radius"], "-"), (fraction * miw["radius"], ":")):
            ax.add_patch(plt.Circle((miw["cx"], miw["cy"]), r, fill=False, color=OURS_COLOR, ls=ls))
        ax.set_aspect("equal")
        ax.set_title(f"{title}: {len(sel)} postures")
        ax.set_xlabel("x [m]")
    axes[0].set_ylabel("y [m]")
    return fig


def fivebar_parameter_errors(names, before, dc, trad) -> plt.Figure:
    """Fig 13: parameter errors (value − real) before and after calibration."""
    fig, ax = plt.subplots(figsize=(9, 3.6), constrained_layout=True)
    x = np.arange(len(names))
    for off, vals, label, color in (
        (-0.27, before, "nominal (before)", PUBLISHED_COLOR),
        (0.0, dc, "divide and conquer", OURS_COLOR),
        (0.27, trad, "traditional", ACTIVE_COLOR),
    ):
        ax.bar(x + off, np.abs(vals), 0.27, label=label, color=color)
    ax.set_yscale("log")
    ax.set_xticks(x, names, rotation=45)
    ax.set_ylabel("|parameter − real| [m or rad]")
    ax.legend(fontsize=7)
    ax.set_title("Fig 13: residual parameter errors, one seeded draw")
    return fig


def fivebar_error_maps(grid: np.ndarray, maps: dict, miw: dict) -> plt.Figure:
    """Fig 14: local RMS position error over the workspace, one panel per model."""
    fig, axes = plt.subplots(1, len(maps), figsize=(4 * len(maps), 3.8), constrained_layout=True)
    for ax, (title, err) in zip(axes, maps.items(), strict=True):
        sc = ax.scatter(grid[:, 0], grid[:, 1], c=1e6 * err, s=14, cmap="viridis")
        ax.add_patch(
            plt.Circle((miw["cx"], miw["cy"]), miw["radius"], fill=False, color=OURS_COLOR)
        )
        ax.set_aspect("equal")
        ax.set_title(title)
        fig.colorbar(sc, ax=ax, label="local RMS error [µm]", shrink=0.8)
    fig.suptitle("Fig 14: position error over the workspace")
    return fig


def fivebar_leg_loop(phi: np.ndarray, mode: int, point: tuple[float, float]) -> plt.Figure:
    """Fig 11: the vector loop P = A + l + L of one leg (Eq 22) with its parameters (Eq 21)."""
    from mechlib.fivebar import kinematics as kin

    p = np.asarray(point, dtype=float)
    theta = float(kin.active_angle(p, phi, mode)[0])
    a = phi[2:4]
    b = a + phi[0] * np.array([np.cos(theta), np.sin(theta)])
    fig, ax = plt.subplots(figsize=(5.6, 4.4), constrained_layout=True)
    arrow = {"length_includes_head": True, "head_width": 0.04, "lw": 1.5}
    ax.arrow(0.0, 0.0, *a, color=PUBLISHED_COLOR, ls="--", **arrow)
    ax.arrow(*a, *(b - a), color=OURS_COLOR, **arrow)
    ax.arrow(*b, *(p - b), color=ACTIVE_COLOR, **arrow)
    ax.arrow(0.0, 0.0, *p, color="k", **arrow)
    ref = 0.25 * np.array([np.cos(phi[5]), np.sin(phi[5])])
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


def fivebar_distributions(
    rms: dict[str, np.ndarray], param_err: dict[str, np.ndarray], names: Sequence[str]
) -> plt.Figure:
    """Monte Carlo distributions: workspace RMS error and per-parameter errors, per strategy."""
    fig, (ax0, ax1) = plt.subplots(
        1, 2, figsize=(11, 3.8), constrained_layout=True, gridspec_kw={"width_ratios": [1, 2]}
    )
    colors = (OURS_COLOR, ACTIVE_COLOR)
    bins = np.histogram_bin_edges(1e6 * np.concatenate(list(rms.values())), 30)
    for (label, vals), color in zip(rms.items(), colors, strict=True):
        ax0.hist(1e6 * vals, bins, alpha=0.55, color=color, label=label)
    ax0.set_xlabel("workspace RMS position error [µm]")
    ax0.set_ylabel("trials")
    ax0.legend(fontsize=7)
    x = np.arange(len(names))
    for off, ((label, err), color) in zip(
        (-0.2, 0.2), zip(param_err.items(), colors, strict=True), strict=True
    ):
        parts = ax1.boxplot(
            np.abs(err), positions=x + off, widths=0.35, showfliers=False, patch_artist=True
        )
        for box in parts["boxes"]:
            box.set_facecolor(color)
            box.set_alpha(0.55)
        ax1.plot([], [], "s", color=color, alpha=0.55, label=label)
    ax1.set_yscale("log")
    ax1.set_xticks(x, names, rotation=45)
    ax1.set_ylabel("|identified − real| [m or rad]")
    ax1.legend(fontsize=7)
    fig.suptitle("Monte Carlo distributions over the seeded trials")
    return fig


def fivebar_sensitivity(table, sigmas: Sequence[float], counts: Sequence[int]) -> plt.Figure:
    """Sensitivity of the D&C vs traditional verdict to σ and to the number of postures.

    ``table`` is the frame of :func:`mechlib.fivebar.study.sensitivity`.
    """
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(10, 3.6), constrained_layout=True)
    for n, marker in zip(counts, "osd^v", strict=False):
        sub = table[table["n_per_leg"] == n]
        ratio = sub["rms_dc_um"] / sub["rms_trad_um"]
        ax0.plot(sub["sigma"], ratio, marker=marker, label=f"{n} per leg / {2 * n} shared")
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


def _quads(ax, nodes, quads, values=None, cmap="viridis", **kw):
    from matplotlib.collections import PolyCollection

    pc = PolyCollection(nodes[quads], **kw)
    if values is not None:
        pc.set_array(values)
        pc.set_cmap(cmap)
    ax.add_collection(pc)
    ax.autoscale_view()
    ax.set_aspect("equal")
    return pc


def hexflex_geometry(g, planar, parts: np.ndarray, part_names: Sequence[str]) -> plt.Figure:
    """Fig 2: the identified planform, its parts, the grounded zone and the dimensions [mm]."""
    from matplotlib.patches import Patch, Polygon

    from mechlib.hexflex.geometry import TAB_ANGLES_DEG, ground_polygons

    fig, (ax, ax_t) = plt.subplots(
        1, 2, figsize=(10, 5.2), constrained_layout=True, gridspec_kw={"width_ratios": [1.6, 1]}
    )
    colors = plt.cm.tab10(np.arange(len(part_names)))
    _quads(ax, planar.nodes, planar.quads, facecolors=colors[parts], edgecolors="none")
    outer = 1.12 * max(g.tab_outer, 2 * g.ground_radius)
    for poly in ground_polygons(g, outer):
        ax.add_patch(Polygon(poly, closed=True, fill=False, hatch="///", ec="0.5", lw=0.8))
    ax.annotate("grounded zone (clamped)", (0, -0.95 * outer), ha="center", fontsize=8)
    for k, name in enumerate(("T1", "T2", "T3")):
        a = np.deg2rad(TAB_ANGLES_DEG[k])
        r = 1.06 * g.tab_outer
        ax.annotate(name, (r * np.cos(a), r * np.sin(a)), ha="center", fontsize=10, weight="bold")
    handles = [Patch(color=c, label=n) for c, n in zip(colors, part_names, strict=True)]
    handles.append(Patch(fill=False, hatch="///", ec="0.5", label="ground"))
    ax.legend(handles=handles, fontsize=7, loc="upper right")
    ax.set_xlim(-outer, outer)
    ax.set_ylim(-outer, 1.1 * g.tab_outer)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    rows = [(k, f"{v:.4g}") for k, v in g.as_dict().items()]
    rows += [("ground radius", f"{g.ground_radius:.4g}"), ("stage gap", f"{g.stage_gap:.3g}")]
    ax_t.axis("off")
    table = ax_t.table(
        cellText=[[k, v] for k, v in rows], colLabels=["dimension", "mm"], loc="center"
    )
    table.scale(1, 1.2)
    fig.suptitle("Fig 2 (reconstructed): our HexFlex planform and its dimensions")
    return fig


def hexflex_mesh(sector, full) -> plt.Figure:
    """Fig 5: (a) the meshed sixth, (b) the whole mesh completed by symmetry."""
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.8), constrained_layout=True)
    for ax, m, title in ((axes[0], sector, "(a) one sixth"), (axes[1], full, "(b) full mesh")):
        _quads(ax, m.nodes, m.quads, facecolors="#dde8f4", edgecolors="k", linewidths=0.15)
        ax.set_title(f"{title}: {len(m.quads)} quads")
        ax.set_xlabel("x [mm]")
    fig.suptitle("Fig 5: finite-element mesh (quads; extruded to one layer of Q2 hexahedra)")
    return fig


def hexflex_actuators(g, planar, directions: np.ndarray, centers: np.ndarray) -> plt.Figure:
    """Fig 4: positive actuator directions D1 (arrows) and D2 (+z, dots) at each tab's
    external edge (``centers``, (3, 2) [mm])."""
    fig, ax = plt.subplots(figsize=(5.6, 5.2), constrained_layout=True)
    _quads(ax, planar.nodes, planar.quads, facecolors="#e6e6e6", edgecolors="none")
    arrow = 0.27 * np.abs(centers).max()  # arrow length [mm], a fraction of the drawing
    tips = centers + arrow * directions[0::2, :2]
    lim = 1.15 * max(np.abs(planar.nodes).max(), np.abs(tips).max())
    for k in range(3):
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


def running_errors(running: dict, labels: Sequence[str], title: str) -> plt.Figure:
    """Pointwise and range-relative maximum error against the number of validation runs
    (the output of :func:`mechlib.metamodel.running_error_metrics`)."""
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), sharex=True, constrained_layout=True)
    k = running["runs"]
    for ax, key, name in zip(
        axes,
        ("max_rel_pct", "max_range_pct"),
        ("pointwise: max 100 |ψ − ψ̂| / |ψ|", "range-relative: 100 MAXABS / max |ψ|"),
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
    axes[0].legend(fontsize=7, ncol=2)
    fig.suptitle(title)
    return fig


def hexflex_deformed(planar, disp: np.ndarray, title: str, ax=None, scale: float | None = None):
    """Deformed planform (in-plane displacements magnified) coloured by u_z [µm]."""
    own = ax is None
    if own:
        fig, ax = plt.subplots(figsize=(5.6, 5.0), constrained_layout=True)
    span = np.ptp(planar.nodes, axis=0).max()
    in_plane, out = np.abs(disp[:, :2]).max(), np.abs(disp[:, 2]).max()
    significant = in_plane > 1e-6 * max(in_plane, out)  # else rounding noise only
    if scale is None:
        scale = 0.05 * span / in_plane if significant else 0.0
    nodes = planar.nodes + scale * disp[:, :2]
    _quads(ax, planar.nodes, planar.quads, facecolors="none", edgecolors="#bbbbbb", linewidths=0.2)
    uz = 1e3 * disp[planar.quads, 2].mean(axis=1)
    uz = np.where(np.abs(uz) > 1e-6 * 1e3 * max(in_plane, out), uz, 0.0)
    lim = max(np.abs(uz).max(), 1e-12)
    pc = _quads(ax, nodes, planar.quads, values=uz, cmap="coolwarm", edgecolors="none")
    pc.set_clim(-lim, lim)
    ax.set_title(f"{title}\n(in-plane ×{scale:.3g}; colour u_z)", fontsize=8)
    ax.set_xticks([])
    ax.set_yticks([])
    if own:
        fig.colorbar(pc, ax=ax, label="u_z [µm]", shrink=0.8)
        return fig
    return pc


def hexflex_stage_motions(model, poses: np.ndarray, labels: Sequence[str]) -> plt.Figure:
    """Fig 3: deformed shapes for given stage poses, each driven by the inverse model's forces."""
    forces = model.forces_for_poses(poses)
    fig, axes = plt.subplots(2, 3, figsize=(11, 7), constrained_layout=True)
    for ax, f, label in zip(axes.ravel(), forces, labels, strict=True):
        hexflex_deformed(model.planar, model.midplane_displacements(f), label, ax=ax)
    fig.suptitle("Fig 3: the six stage motions, each from the inverse model")
    return fig
