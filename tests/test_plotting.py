"""Every public figure function: returns a Figure, draws into the Axes it is given, refuses a wrong
number of panels; and the colour scale of the matrix-difference heat maps."""

from __future__ import annotations

from collections.abc import Callable

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import pytest
from matplotlib.figure import Figure

from mechlib import plotting
from mechlib import published as pub
from mechlib.fivebar import kinematics as kin
from mechlib.fivebar import workspace as ws
from mechlib.hexflex import geometry as geo
from mechlib.hexflex.fe.mesh import PlanarMesh

RNG = np.random.default_rng(0)
F, R = list(pub.FACTORS), ["x", "y", "z", "θx", "θy", "θz"]
EFFECTS = RNG.normal(size=(6, 6))
MARGINS = np.full(6, 0.5)

# a 2 × 2-quad planform and displacements of its nine nodes [mm]
_XY = np.array([[x, y] for y in (-10.0, 0.0, 10.0) for x in (-10.0, 0.0, 10.0)])
MESH = PlanarMesh(_XY, np.array([[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]]))
DISP = 1e-3 * RNG.normal(size=(9, 3))

PHI1 = kin.leg_vector(pub.TABLE7_NOMINAL, 1)
PHI2 = kin.leg_vector(pub.TABLE7_NOMINAL, 2)
MIW = kin.miw_closed_form(PHI1[0], PHI1[1], abs(PHI1[2]))
POSE = (0.0, 1.25)
CANDIDATES = kin.in_circle_grid((0.0, MIW["cy"]), 0.5, 5, 12)
CHOSEN = {"trad": np.arange(12), "leg1": np.arange(6), "leg2": np.arange(6, 12)}
NAMES = [*kin.leg_keys(1), *kin.leg_keys(2)]
SENS = pd.DataFrame(
    [
        {
            "n_per_leg": n,
            "n_shared": 2 * n,
            "sigma": s,
            "pos_rms_dc": 2.0 * s,
            "pos_rms_trad": s,
            "share_dc_better": 0.3,
        }
        for n in (9, 18)
        for s in (1e-5, 1e-4)
    ]
)
RUNNING = {
    "runs": np.arange(1, 21),
    "max_rel_pct": RNG.uniform(0.1, 1, (20, 6)),
    "max_range_pct": RNG.uniform(0.1, 1, (20, 6)),
}


def _field() -> ws.SingularityField:
    return ws.singularity_field(PHI1, PHI2, (-2.2, 2.2, -0.5, 2.2), n=41)


def _chain() -> tuple[np.ndarray, float]:
    return ws.leg_chain(POSE, PHI1, 1)


# name -> (call with keyword arguments added, number of panels; 0: one ``ax=``)
CASES: dict[str, tuple[Callable[..., Figure], int]] = {
    "half_normal_panels": (
        lambda **kw: plotting.half_normal_panels(EFFECTS, F, R, MARGINS, "t", **kw),
        6,
    ),
    "pareto_panels": (lambda **kw: plotting.pareto_panels(EFFECTS, F, R, MARGINS, "t", **kw), 6),
    "discrepancy_histogram": (
        lambda **kw: plotting.discrepancy_histogram(RNG.uniform(size=50), 0.1, "T4", **kw),
        0,
    ),
    "matrix_difference": (
        lambda **kw: plotting.matrix_difference(
            pub.EQ8_ST, {"a": 1.01 * pub.EQ8_ST, "b": 0.99 * pub.EQ8_ST}, R, F, "t", **kw
        ),
        2,
    ),
    "running_errors": (lambda **kw: plotting.running_errors(RUNNING, R, "t", **kw), 2),
    "hexflex_geometry": (
        lambda **kw: plotting.hexflex_geometry(
            geo.HexFlexGeometry(), MESH, np.array([0, 1, 2, 3]), geo.PARTS, **kw
        ),
        2,
    ),
    "hexflex_mesh": (lambda **kw: plotting.hexflex_mesh(MESH, MESH, **kw), 2),
    "hexflex_actuators": (
        lambda **kw: plotting.hexflex_actuators(
            MESH, geo.actuator_directions(), 8.0 * geo.tab_frames()[0], **kw
        ),
        0,
    ),
    "hexflex_deformed": (lambda **kw: plotting.hexflex_deformed(MESH, DISP, "t", **kw), 0),
    "hexflex_stage_motions": (
        lambda **kw: plotting.hexflex_stage_motions(
            MESH, np.stack([DISP] * 6), [f"m{i}" for i in range(6)], **kw
        ),
        6,
    ),
    "fivebar_workspace": (
        lambda **kw: plotting.fivebar_workspace(
            _field(), MIW, ws.mechanism_chains(POSE, PHI1, PHI2), **kw
        ),
        0,
    ),
    "fivebar_leg_loop": (lambda **kw: plotting.fivebar_leg_loop(*_chain(), PHI1[5], **kw), 0),
    "fivebar_postures": (
        lambda **kw: plotting.fivebar_postures(CANDIDATES, CHOSEN, MIW, 0.8, **kw),
        3,
    ),
    "fivebar_parameter_errors": (
        lambda **kw: plotting.fivebar_parameter_errors(
            NAMES, *RNG.uniform(1e-6, 1e-3, (3, 12)), **kw
        ),
        0,
    ),
    "fivebar_error_maps": (
        lambda **kw: plotting.fivebar_error_maps(
            CANDIDATES, {"a": np.ones(len(CANDIDATES)), "b": np.ones(len(CANDIDATES))}, MIW, **kw
        ),
        2,
    ),
    "fivebar_distributions": (
        lambda **kw: plotting.fivebar_distributions(
            {"D&C": RNG.uniform(size=20), "trad": RNG.uniform(size=20)},
            {"D&C": RNG.normal(size=(20, 12)), "trad": RNG.normal(size=(20, 12))},
            NAMES,
            **kw,
        ),
        2,
    ),
    "fivebar_sensitivity": (
        lambda **kw: plotting.fivebar_sensitivity(SENS, [1e-5, 1e-4], [9, 18], **kw),
        2,
    ),
}


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def test_every_public_figure_function_is_covered() -> None:
    public = {n for n in plotting.__all__ if callable(getattr(plotting, n)) and n != "use_style"}
    assert public == set(CASES)


@pytest.mark.parametrize("name", sorted(CASES))
def test_returns_a_new_figure(name: str) -> None:
    call, _ = CASES[name]
    before = set(plt.get_fignums())
    fig = call()
    assert isinstance(fig, Figure) and fig.number not in before
    assert any(ax.has_data() for ax in fig.axes)


@pytest.mark.parametrize("name", sorted(CASES))
def test_draws_into_the_given_axes(name: str) -> None:
    call, n = CASES[name]
    fig, grid = plt.subplots(1, max(n, 1), squeeze=False)
    given = list(grid.ravel())
    out = call(ax=given[0]) if n == 0 else call(axes=given)
    assert out is fig
    assert len(plt.get_fignums()) == 1  # no other figure was made
    for ax in given:
        assert ax.has_data() or ax.tables, f"{name} left a given panel empty"


@pytest.mark.parametrize("name", sorted(n for n, (_, k) in CASES.items() if k > 0))
def test_a_wrong_number_of_panels_is_refused(name: str) -> None:
    call, n = CASES[name]
    _, grid = plt.subplots(1, n + 1, squeeze=False)
    with pytest.raises(ValueError, match=f"axes must hold {n} matplotlib Axes, got {n + 1}"):
        call(axes=list(grid.ravel()))


def test_matrix_difference_scale_and_label_come_from_the_caller_or_the_data() -> None:
    ref = np.array([[1.0, -2.0], [0.0, 4.0]])
    others = {"a": np.array([[1.01, -2.0], [5.0, 4.0]]), "b": np.array([[1.0, -2.02], [0, 3.9]])}
    fig = plotting.matrix_difference(ref, others, ["r1", "r2"], ["c1", "c2"], reference_label="Q")
    images = [ax.images[0] for ax in fig.axes if ax.images]
    # largest finite |difference|: 100 · 0.1 / 4 = 2.5 % (the entry over a 0 is not drawn)
    assert len(images) == 2
    for im in images:
        np.testing.assert_allclose(im.get_clim(), (-2.5, 2.5), rtol=1e-12)
    assert fig.axes[-1].get_ylabel() == "difference from Q [%]"
    fig = plotting.matrix_difference(ref, others, ["r1", "r2"], ["c1", "c2"], limit=0.7)
    assert fig.axes[0].images[0].get_clim() == (-0.7, 0.7)
    with pytest.raises(ValueError, match="limit must be > 0"):
        plotting.matrix_difference(ref, others, ["r1", "r2"], ["c1", "c2"], limit=0.0)


def test_shapes_that_do_not_match_are_refused_by_name() -> None:
    with pytest.raises(ValueError, match=r"effects must have shape \(factors, responses\)"):
        plotting.half_normal_panels(EFFECTS[:, :5], F, R)
    with pytest.raises(ValueError, match="disp must have shape"):
        plotting.hexflex_deformed(MESH, DISP[:5], "t")
    with pytest.raises(ValueError, match="displacements must have shape"):
        plotting.hexflex_stage_motions(MESH, np.stack([DISP] * 5), list("abcdef"))
    with pytest.raises(TypeError, match="ax must be a matplotlib Axes"):
        plotting.discrepancy_histogram(np.ones(3), 1.0, "x", ax="not an axes")


def test_each_model_keeps_one_colour_and_marker_on_every_figure() -> None:
    from mechlib.plotting import metamodels as mmplot

    gp = mmplot.model_style("Gaussian process")
    assert mmplot.model_style("Gaussian process, Sobol' 256") == gp
    assert mmplot.model_style("reduced-order model + correction") != mmplot.model_style(
        "reduced-order model"
    )
    assert mmplot.model_style("linear S_T (Eq 7), Table 4") == mmplot.model_style("linear (Eq 7)")
    fig = mmplot.learning_curves(
        [16, 32], [[2.0, 1.0]], ["reduced-order model + correction"], {}, 1.0, extra_runs=[42]
    )
    line = fig.axes[0].get_lines()[0]
    assert list(line.get_xdata()) == [58, 74] and line.get_color() == "tab:pink"
    with pytest.raises(ValueError, match="one count per model"):
        mmplot.learning_curves([16], [[1.0]], ["linear"], {}, 1.0, extra_runs=[1, 2])
