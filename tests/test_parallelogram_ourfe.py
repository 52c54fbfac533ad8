"""Our FE's rows in the benchmark's units: conversions, the sweep rows chosen, the mesh measure."""

from __future__ import annotations

import numpy as np
import pytest

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
