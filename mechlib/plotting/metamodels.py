"""Figures of the meta-model comparison on the non-linear HexFlex: error against training
runs, against the force range, and accuracy against latency."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from matplotlib.figure import Figure

from mechlib.plotting.style import figure_and_axes

#: one colour and marker per model on every figure of the page, by the first keyword (lower
#: case) its name holds; a name with none of them is drawn in black crosses
MODEL_STYLES: tuple[tuple[str, str, str], ...] = (
    ("error model", "tab:olive", "h"),
    ("correction", "tab:pink", "P"),
    ("distilled", "tab:gray", "*"),
    ("reduced-order", "tab:brown", "p"),
    ("gaussian", "tab:red", "^"),
    ("chaos", "tab:purple", "v"),
    ("cubic", "tab:green", "D"),
    ("quadratic", "tab:orange", "s"),
    ("linear", "tab:blue", "o"),
)


def model_style(name: str) -> dict[str, str]:
    """The colour and marker of model ``name`` (:data:`MODEL_STYLES`), as plot keywords."""
    low = name.lower()
    for key, color, marker in MODEL_STYLES:
        if key in low:
            return {"color": color, "marker": marker}
    return {"color": "k", "marker": "x"}


def _budget(ax, budget_pct: float, horizontal: bool = True, word: str = "budget") -> None:
    line = ax.axhline if horizontal else ax.axvline
    line(budget_pct, color="k", lw=0.8, ls="--", label=f"{budget_pct:g} % {word}")


def learning_curves(
    sizes: Sequence[int],
    worst_pct: np.ndarray,
    names: Sequence[str],
    points: Mapping[str, tuple[float, float]],
    budget_pct: float,
    ax=None,
    budget_word: str = "budget",
    extra_runs: Sequence[int] | None = None,
) -> Figure:
    """Largest validation error (% of full scale, worst component) against the number
    of full FE training runs: one line per family (``worst_pct`` (families, sizes); NaN where a
    family cannot be fitted), each shifted by its ``extra_runs`` (the full runs a model needs
    before the curve's ones, e.g. a reduced-order model's own), and single points (``points``:
    name → (runs, error)); the dashed line at ``budget_pct`` is labelled with ``budget_word``
    ("budget", "goal", ...). Each model keeps its colour and marker (:func:`model_style`)."""
    fig, ax = figure_and_axes(ax, (6.4, 4.0))
    w = np.asarray(worst_pct, dtype=float)
    extra = [0] * len(names) if extra_runs is None else list(extra_runs)
    if len(extra) != len(names):
        raise ValueError(f"extra_runs must give one count per model ({len(names)}), got {extra}")
    for k, name in enumerate(names):
        ok = np.isfinite(w[k])
        if ok.any():
            x = np.asarray(sizes)[ok] + extra[k]
            ax.plot(x, w[k][ok], label=name, **model_style(name))
    for name, (n, e) in points.items():
        ax.plot([n], [e], ls="none", ms=10, mfc="none", mew=1.5, label=name, **model_style(name))
    _budget(ax, budget_pct, word=budget_word)
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("full non-linear FE runs used for training")
    ax.set_ylabel("largest error [% of full scale]")
    ax.legend(fontsize=7, ncol=2)
    return fig


def error_vs_range(
    amplitudes: Sequence[float],
    worst_pct: np.ndarray,
    names: Sequence[str],
    budget_pct: float,
    ax=None,
) -> Figure:
    """Largest validation error (% of full scale) of each model (rows of ``worst_pct``) at each
    force range ±amplitude [N] (columns)."""
    fig, ax = figure_and_axes(ax, (6.4, 4.0))
    w = np.asarray(worst_pct, dtype=float)
    for k, name in enumerate(names):
        ax.plot(amplitudes, w[k], label=name, **model_style(name))
    _budget(ax, budget_pct)
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xticks(list(amplitudes), [f"±{a:g}" for a in amplitudes])
    ax.set_xlabel("force range [N]")
    ax.set_ylabel("largest error [% of full scale]")
    ax.legend(fontsize=7, ncol=2)
    return fig


def latency_accuracy(
    latency_us: Sequence[float],
    worst_pct: Sequence[float],
    names: Sequence[str],
    budget_pct: float,
    deadline_us: float,
    ax=None,
) -> Figure:
    """Largest validation error (% of full scale) against the time to predict one pose [µs], with
    the error budget and a control-loop deadline."""
    fig, ax = figure_and_axes(ax, (6.4, 4.0))
    for t, e, name in zip(latency_us, worst_pct, names, strict=True):
        ax.plot([t], [e], ls="none", ms=8, label=name, **model_style(name))
    _budget(ax, budget_pct)
    ax.axvline(deadline_us, color="grey", lw=0.8, ls=":", label=f"{deadline_us:g} µs a pose")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time to predict one pose [µs]")
    ax.set_ylabel("largest error [% of full scale]")
    ax.legend(fontsize=7, ncol=2)
    return fig
