"""Our FE's rows in the benchmark's units: conversions, the sweep rows chosen, the mesh measure."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from mechlib.parallelogram import comparison as cmp
from mechlib.parallelogram import ourfe
from mechlib.parallelogram import published as pub


def test_loads_round_trip_through_newtons() -> None:
    loads = np.array([[-10.0, 20.0, 3.0], [0.5, -1.0, 0.0]])
    newton = ourfe.to_newton(loads)
    assert newton[0, 1] == pytest.approx(20 * pub.FORCE_UNIT_N)
    assert newton[0, 2] == pytest.approx(3 * pub.MOMENT_UNIT_NMM)
    np.testing.assert_allclose(ourfe.from_newton(newton), loads, rtol=1e-15)
    np.testing.assert_allclose(ourfe.from_newton(newton[0]), loads[0], rtol=1e-15)


def test_poses_are_normalised_by_the_beam_length() -> None:
    pose = np.array([[-250.0, 2500.0, 0.0, 0.0, 0.0, 1e5]])  # µm, µrad
    np.testing.assert_allclose(ourfe.normalised(pose), [[-1e-3, 1e-2, 0.1]])
    np.testing.assert_allclose(ourfe.in_mm(pose), [[-0.25, 2.5, 0.1]])


def test_computed_rows_apply_each_couple_once_and_only_computed_levels() -> None:
    sweep, loads, fe = ourfe.computed_rows([[0, 3], [0, -3]], corners=False)
    assert np.all(sweep[:, 1] >= 0)  # the mirrored rows are left out
    assert np.all(loads[:, 2] == 3.0)  # B and -B were both computed under +|B|: one run each
    assert len(np.unique(loads, axis=0)) == len(loads) == len(pub.A_Y_COMPUTED_LEVELS)
    assert fe.shape == (len(loads), 3)
    with pytest.raises(ValueError, match="select no computed row"):
        ourfe.computed_rows(np.zeros((0, 2)), corners=False)


def test_convergence_is_measured_against_the_last_row() -> None:
    values = np.array([[1.1, -2.0], [1.0, -2.5]])
    np.testing.assert_allclose(ourfe.convergence_pct(values), [[10.0, 20.0], [0.0, 0.0]])


def test_the_sweep_table_is_the_one_the_page_built_by_hand() -> None:
    loads, fe, mine, beam = np.random.default_rng(3).normal(size=(4, 5, 3))
    by_hand = pd.DataFrame(
        np.hstack([loads, fe, mine, beam]),
        columns=["A_x [-]", "A_y [-]", "B applied [-]", "published u_x/L [-]",
                 "published u_y/L [-]", "published phi rigid [rad]", "our FE u_x/L [-]",
                 "our FE u_y/L [-]", "our FE phi [rad]", "elastica u_x/L [-]",
                 "elastica u_y/L [-]", "elastica phi [rad]"],
    )  # fmt: skip
    table = ourfe.sweep_table(loads, fe, mine, beam)
    assert table.to_csv(index=False) == by_hand.to_csv(index=False)
    with pytest.raises(ValueError, match=r"\(n, 3\) arrays, got .*'ours': \(4, 3\)"):
        ourfe.sweep_table(loads, fe, mine[:4], beam)
    with pytest.raises(ValueError, match=r"'elastica': \(5,\)"):
        ourfe.sweep_table(loads, fe, mine, beam[:, 0])


def test_the_largest_difference_by_level_is_what_the_page_computed_by_hand() -> None:
    rng = np.random.default_rng(5)
    loads = np.column_stack([rng.choice([-5.0, 0.0, 5.0], 12), rng.choice([-4.0, 1.0, 2.0, 8.0],
                             12), np.full(12, 3.0)])  # fmt: skip
    loads[:2, 1] = [8.0, 1.0]  # a level beyond SMALL_A_Y and one within it, at least
    shares = rng.random((12, 3))
    shares[3, 2] = np.nan  # not compared
    ax_levels, by_ax = cmp.worst_by(loads[:, 0], shares)
    ay_levels, by_ay = cmp.worst_by(np.abs(loads[:, 1]), shares)
    small_top = [by_ay[ay_levels <= cmp.SMALL_A_Y].max(), by_ay[-1].max(), ay_levels[-1]]
    got = ourfe.largest_by_level(loads, shares)
    assert list(got) == ["a_x_levels", "by_a_x_pct", "a_y_levels", "by_a_y_pct",
                         "small_and_top_pct"]  # fmt: skip
    for mine, by_hand in zip(got.values(), [ax_levels, by_ax, ay_levels, by_ay, small_top],
                             strict=True):  # fmt: skip
        np.testing.assert_array_equal(mine, by_hand)
    with pytest.raises(ValueError, match=r"a row with \|A_y\| <= 2"):
        ourfe.largest_by_level(loads[loads[:, 1] > 2], shares[loads[:, 1] > 2])
