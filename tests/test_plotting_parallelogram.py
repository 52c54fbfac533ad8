"""The "Beyond the HexFlex" figures: the panels they promise, labelled with units and panel
letters, drawn into given Axes; arrays of the wrong shape and a wrong number of Axes refused."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest

from mechlib.plotting import parallelogram as pplot

RNG = np.random.default_rng(0)
A_Y = np.linspace(-2.0, 2.0, 5)
AX, B = [-5.0, 0.0, 5.0], [-3.0, 0.0, 3.0]


def _grid() -> np.ndarray:
    return RNG.random((len(AX), len(B), len(A_Y), 3))


def test_sweep_comparison_has_nine_labelled_panels_with_units() -> None:
    fig = pplot.sweep_comparison(A_Y, _grid(), _grid(), _grid(), AX, B)
    assert len(fig.axes) == 9
    titles = [a.get_title() for a in fig.axes]
    assert titles[0].startswith("(a)") and titles[-1].startswith("(i)")
    assert all("[" in a.get_ylabel() for a in fig.axes[::3])
    assert all("[–]" in a.get_xlabel() for a in fig.axes[6:])
    # per panel: 3 solid lines (one per printed B), 2 dashed (B ≠ 0), 3 marker sets
    assert len(fig.axes[0].lines) == 8
    assert {t.get_text() for t in fig.legends[0].get_texts()} >= {
        "3-D FE, B = −3",
        "elastica, couple applied (±B)",
        "elastica, couple printed (B = −3)",
    }
    plt.close(fig)


def test_sweep_comparison_refuses_arrays_of_another_shape() -> None:
    with pytest.raises(ValueError, match="must have shape"):
        pplot.sweep_comparison(A_Y, _grid()[:, :2], _grid(), _grid(), AX, B)


def test_deformed_shapes_one_panel_per_load_in_given_axes() -> None:
    n = 2
    lines = RNG.random((n, 2, 7, 2))
    outlines = RNG.random((n, 5, 2))
    points = RNG.random((n, 2))
    fe = np.array([[1.0, 0.2], [np.nan, np.nan]])
    fig, axes = plt.subplots(1, n)
    out = pplot.deformed_shapes(
        lines, outlines, points, fe, lines[0], outlines[0], ["one", "two"], axes=axes
    )
    assert out is fig and [a.get_title() for a in axes] == ["(a) one", "(b) two"]
    assert len(axes[0].lines) == 2 + 2 + 2 and len(axes[1].lines) == 2 + 2 + 1  # no FE point
    assert axes[0].get_ylabel() == "$y/L$ [–]" and axes[1].get_xlabel() == "$x/L$ [–]"
    with pytest.raises(ValueError, match="must hold 2 matplotlib Axes"):
        pplot.deformed_shapes(lines, outlines, points, fe, lines[0], outlines[0], ["a", "b"],
                              axes=axes[:1])  # fmt: skip
    with pytest.raises(ValueError, match="one per title"):
        pplot.deformed_shapes(lines, outlines, points, fe, lines[0], outlines[0], ["a"])
    plt.close(fig)
