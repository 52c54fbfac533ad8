"""Figures of the "Beyond the 5R" chapter: selected poses, parameter errors, workspace error maps,
error against noise and pose budget, and costs against the number of legs.

The data arrive computed (:mod:`mechlib.calibration.study`, :mod:`mechlib.calibration.cost`);
nothing is computed here.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from matplotlib.figure import Figure

from mechlib.plotting.style import ACTIVE_COLOR, OURS_COLOR, PUBLISHED_COLOR, figure_and_panels

UM_PER_M = 1e6
#: Line styles of the strategies: D&C, traditional under the thesis and the matched budget.
STYLES = {
    "dc": {"color": OURS_COLOR, "marker": "o", "label": "D&C"},
    "thesis": {"color": ACTIVE_COLOR, "marker": "s", "label": "traditional, thesis budget"},
    "matched": {"color": PUBLISHED_COLOR, "marker": "^", "label": "traditional, matched budget"},
    "equal": {"color": "0.3", "marker": "v", "ls": ":", "label": "traditional, n shared poses"},
}


def selected_poses(
    candidates: Mapping[str, np.ndarray],
    dc_sets: Mapping[str, Sequence[np.ndarray]],
    trad_sets: Mapping[str, np.ndarray],
    axes=None,
) -> Figure:
    """Candidate poses (grey) and the selected ones, projected on the first two coordinates [m]:
    each leg's D&C set (one marker per leg) and the traditional shared set (crosses)."""
    names = list(candidates)
    fig, panels = figure_and_panels(axes, (1, len(names)), (4.0 * len(names), 3.8))
    for ax, name in zip(panels, names, strict=True):
        c = candidates[name]
        ax.plot(c[:, 0], c[:, 1], ".", color="0.8", ms=3, label="candidates")
        for k, idx in enumerate(dc_sets[name]):
            ax.plot(c[idx, 0], c[idx, 1], "o", ms=5, mfc="none", label=f"D&C leg {k + 1}")
        t = c[trad_sets[name]]
        ax.plot(t[:, 0], t[:, 1], "kx", ms=5, label="traditional (shared)")
        ax.set(title=name, xlabel="x [m]", ylabel="y [m]", aspect="equal")
    panels[-1].legend(fontsize=7, loc="center left", bbox_to_anchor=(1.02, 0.5))
    fig.suptitle("Poses selected by active calibration (x–y projection)")
    return fig


def parameter_errors(
    names: Mapping[str, Sequence[str]],
    errors: Mapping[str, Mapping[str, np.ndarray]],
    axes=None,
) -> Figure:
    """|parameter error| before calibration and after it (one seeded draw), in units of the
    disturbance's standard deviation, one panel per mechanism."""
    mechs = list(names)
    fig, panels = figure_and_panels(axes, (len(mechs), 1), (11.0, 2.6 * len(mechs)))
    for ax, m in zip(panels, mechs, strict=True):
        x = np.arange(len(names[m]))
        width = 0.8 / len(errors[m])
        for j, (label, e) in enumerate(errors[m].items()):
            ax.bar(x + (j - (len(errors[m]) - 1) / 2) * width, np.abs(e), width, label=label)
        ax.set_yscale("log")
        ax.set_xticks(x, names[m], rotation=90, fontsize=6)
        ax.set(title=m, ylabel="|error| / disturbance σ")
    panels[0].legend(fontsize=7, ncols=3)
    fig.suptitle("Parameter errors before and after calibration (one seeded draw)")
    return fig


#: the error maps' colour scales end at this percentile of their points (and start at 100 minus
#: it): a few points near a singular corner, orders of magnitude above the rest, would otherwise
#: leave one colour
MAP_PERCENTILE = 95.0


def error_maps(
    points: Mapping[str, np.ndarray], maps: Mapping[str, Mapping[str, np.ndarray]], axes=None
) -> Figure:
    """Position error [µm] over a workspace slice: one row per mechanism, one column per model
    (before calibration, D&C, traditional). Each panel has its own colour scale, from the
    (100 − :data:`MAP_PERCENTILE`)th to the :data:`MAP_PERCENTILE` th percentile of its points
    (the colour bar's arrows): a shared scale left a panel whose errors all lie above another's
    in one colour, and a scale from zero one whose errors vary little about a large mean; the
    levels are compared on the colour bars."""
    mechs = list(points)
    cols = max(len(v) for v in maps.values())
    fig, panels = figure_and_panels(axes, (len(mechs), cols), (3.6 * cols, 3.2 * len(mechs)))
    panels = panels.reshape(len(mechs), cols)
    for row, m in zip(panels, mechs, strict=True):
        p = points[m]
        for ax, (label, v) in zip(row, maps[m].items(), strict=False):
            low, top = (
                UM_PER_M * float(np.nanpercentile(v, q))
                for q in (100.0 - MAP_PERCENTILE, MAP_PERCENTILE)
            )
            sc = ax.scatter(
                p[:, 0], p[:, 1], c=UM_PER_M * v, s=14, cmap="viridis", vmin=low, vmax=top
            )
            fig.colorbar(sc, ax=ax, label="µm", extend="both")
            ax.set(title=f"{m}: {label}", xlabel="x [m]", ylabel="y [m]", aspect="equal")
    fig.suptitle(
        "Position error over a workspace slice (RMS over the trials after calibration; each "
        f"panel's colours span its {100 - MAP_PERCENTILE:g}th to {MAP_PERCENTILE:g}th percentile)"
    )
    return fig


def error_curves(rows: Sequence[Mapping[str, float]], mechs: Sequence[str], axes=None) -> Figure:
    """Workspace RMS position error [µm] against σ (left) and poses per leg (right)."""
    fig, panels = figure_and_panels(axes, (len(mechs), 2), (9.0, 2.8 * len(mechs)))
    panels = panels.reshape(len(mechs), 2)
    for (ax_s, ax_n), m in zip(panels, mechs, strict=True):
        mine = [r for r in rows if r["mechanism"] == m]
        n0, s0 = mine[0]["n_per_leg"], mine[0]["sigma"]
        for ax, key, fixed, other in (
            (ax_s, "sigma", "n_per_leg", n0),
            (ax_n, "n_per_leg", "sigma", s0),
        ):
            for b in ("thesis", "matched"):
                cells = sorted(
                    (r for r in mine if r["budget"] == b and r[fixed] == other),
                    key=lambda r: r[key],
                )
                x = [r[key] for r in cells]
                if b == "thesis":
                    ax.plot(x, [UM_PER_M * r["pos_rms_dc"] for r in cells], **STYLES["dc"])
                ax.plot(x, [UM_PER_M * r["pos_rms_trad"] for r in cells], **STYLES[b])
            ax.set(yscale="log", ylabel="workspace RMS [µm]", title=m)
        ax_s.set(xscale="log", xlabel=f"σ [m, rad] ({n0} poses per leg)")
        ax_n.set(xlabel=f"D&C poses per leg (σ = {s0:g})")
    panels[0, 1].legend(fontsize=7)
    fig.suptitle("Error against measurement noise and pose budget")
    return fig


def costs(
    names: Sequence[str],
    n_limbs: Sequence[int],
    flop_ratio: Sequence[float],
    time_ratio: Sequence[float],
    measurements: Mapping[str, Sequence[float]],
    axes=None,
) -> Figure:
    """Against the number of legs: the normal-matrix inversion ratio traditional / D&C (Table 6's
    n_limbs² law, the counted flops and the measured solve time), and the measurements per pose
    budget n (``measurements``: keys of :data:`STYLES`)."""
    fig, (a, b) = figure_and_panels(axes, (1, 2), (9.0, 3.4))
    n = np.asarray(n_limbs)
    a.plot(n, n**2, "k--", label="Table 6: n_limbs²")
    a.plot(n, flop_ratio, "o", color=OURS_COLOR, label="flops (counted)")
    a.plot(n, time_ratio, "s", color=ACTIVE_COLOR, label="solve time (measured)")
    a.axhline(1.0, color="0.6", lw=0.8)
    a.set(xlabel="legs n_limbs", ylabel="traditional / D&C", yscale="log", title="normal equations")
    a.legend(fontsize=7)
    for key, values in measurements.items():
        b.plot(n, values, **STYLES[key])
    b.set(xlabel="legs n_limbs", ylabel="measurements per pose budget n", title="measurement cost")
    b.legend(fontsize=7)
    for m, x, y in zip(names, n, flop_ratio, strict=True):
        a.annotate(m, (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
    fig.suptitle("Costs against the number of legs")
    return fig
