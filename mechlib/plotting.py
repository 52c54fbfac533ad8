"""One figure style for the whole book, and the screening figures (Figs 6 and 7)."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
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
