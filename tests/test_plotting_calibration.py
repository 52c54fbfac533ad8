"""The "Beyond the 5R" figures: each returns a Figure with the panels it promises and draws into
given Axes; a wrong number of Axes is refused."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.figure import Figure

from mechlib.plotting import calibration as cplot

RNG = np.random.default_rng(0)
POINTS = RNG.random((20, 2))


def test_selected_poses_one_panel_per_mechanism() -> None:
    fig = cplot.selected_poses(
        {"A": POINTS, "B": POINTS}, {"A": [[0, 1], [2, 3]], "B": [[4]]}, {"A": [5, 6], "B": [7]}
    )
    assert isinstance(fig, Figure) and len([a for a in fig.axes if a.get_title()]) == 2
    plt.close(fig)


def test_parameter_errors_and_maps_and_curves_and_costs() -> None:
    fig = cplot.parameter_errors(
        {"A": ["p", "q"]}, {"A": {"before": [1.0, 2.0], "D&C": [0.1, 0.2]}}
    )
    assert len(fig.axes) == 1
    maps = {"A": {"before": RNG.random(20), "D&C": RNG.random(20)}}
    fig2 = cplot.error_maps({"A": POINTS}, maps)
    assert len([a for a in fig2.axes if a.get_title()]) == 2
    # one point far above the rest (a singular corner) does not set the colour scales
    values = RNG.random(100)
    values[0] = 1e3  # the rest below 1
    spiked = {"A": {"before": values, "D&C": values / 10}}
    fig4 = cplot.error_maps({"A": RNG.random((100, 2))}, spiked)
    tops = [c.get_clim()[1] for a in fig4.axes if a.get_title() for c in a.collections]
    assert len(tops) == 2 and max(tops) <= 1e6  # µm: below the spike's 1e9
    rows = [
        {
            "mechanism": "A",
            "budget": b,
            "sigma": s,
            "n_per_leg": n,
            "pos_rms_dc": 1e-4,
            "pos_rms_trad": 2e-4,
        }
        for b in ("thesis", "matched")
        for s, n in ((1e-4, 18), (1e-5, 18), (1e-4, 30))
    ]
    fig3 = cplot.error_curves(rows, ["A"])
    assert len(fig3.axes) == 2 and len(fig3.axes[0].lines) == 3  # D&C and both budgets
    fig4 = cplot.costs(
        ["A", "B"], [2, 3], [4.0, 9.0], [0.5, 0.6], {"dc": [6, 12], "thesis": [8, 18]}
    )
    assert len(fig4.axes) == 2
    for f in (fig, fig2, fig3, fig4):
        plt.close(f)


def test_given_axes_are_used_and_a_wrong_count_refused() -> None:
    fig, axes = plt.subplots(1, 2)
    out = cplot.costs(["A"], [2], [4.0], [0.5], {"dc": [6]}, axes=axes)
    assert out is fig
    with pytest.raises(ValueError, match="must hold 2"):
        cplot.costs(["A"], [2], [4.0], [0.5], {"dc": [6]}, axes=axes[:1])
    plt.close(fig)
