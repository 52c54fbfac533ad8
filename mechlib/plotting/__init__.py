"""The book's figures, one module per chapter, one style.

- :mod:`mechlib.plotting.style`: ``use_style``, colours and the helpers the figures share;
- :mod:`mechlib.plotting.doe`: half-normal and Pareto plots, discrepancy histogram, matrix
  differences, running errors;
- :mod:`mechlib.plotting.hexflex`: the HexFlex model's figures (Figs 2–5, 8 style);
- :mod:`mechlib.plotting.fivebar`: the five-bar's figures (Figs 10–14, Monte Carlo).

Every figure function takes computed arrays, an optional ``ax=`` (one panel) or ``axes=`` (a
sequence of panels, as documented), and returns a matplotlib Figure. The names are re-exported
here, so ``from mechlib import plotting; plotting.half_normal_panels(...)`` works.
"""

from mechlib.plotting.doe import (
    discrepancy_histogram,
    half_normal_panels,
    matrix_difference,
    pareto_panels,
    running_errors,
)
from mechlib.plotting.fivebar import (
    fivebar_distributions,
    fivebar_error_maps,
    fivebar_leg_loop,
    fivebar_parameter_errors,
    fivebar_postures,
    fivebar_sensitivity,
    fivebar_workspace,
)
from mechlib.plotting.hexflex import (
    hexflex_actuators,
    hexflex_deformed,
    hexflex_geometry,
    hexflex_mesh,
    hexflex_stage_motions,
)
from mechlib.plotting.style import (
    ACTIVE_COLOR,
    OURS_COLOR,
    PUBLISHED_COLOR,
    STYLE,
    use_style,
)

__all__ = [
    "ACTIVE_COLOR",
    "OURS_COLOR",
    "PUBLISHED_COLOR",
    "STYLE",
    "discrepancy_histogram",
    "fivebar_distributions",
    "fivebar_error_maps",
    "fivebar_leg_loop",
    "fivebar_parameter_errors",
    "fivebar_postures",
    "fivebar_sensitivity",
    "fivebar_workspace",
    "half_normal_panels",
    "hexflex_actuators",
    "hexflex_deformed",
    "hexflex_geometry",
    "hexflex_mesh",
    "hexflex_stage_motions",
    "matrix_difference",
    "pareto_panels",
    "running_errors",
    "use_style",
]
