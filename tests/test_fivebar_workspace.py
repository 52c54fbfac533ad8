"""The five-bar's workspace field (Fig 10's data) and leg chains: known answers."""

import numpy as np
import pytest

from mechlib import dyad
from mechlib import published as pub
from mechlib.fivebar import kinematics as kin
from mechlib.fivebar import workspace as ws

PHI1 = kin.leg_vector(pub.TABLE7_NOMINAL, 1)
PHI2 = kin.leg_vector(pub.TABLE7_NOMINAL, 2)
L_PROX, L_DIST, HALF_BASE = PHI1[0], PHI1[1], abs(PHI1[2])
MIW = kin.miw_closed_form(L_PROX, L_DIST, HALF_BASE)


def _reach_area() -> float:
    """Area [m²] both legs reach: the lens of the outer discs (radius l + L, centres 2a apart)
    minus the two inner discs (radius L − l), which lie inside the lens and apart."""
    big, small, d = L_PROX + L_DIST, L_DIST - L_PROX, 2 * HALF_BASE
    assert d + small < big and d > 2 * small  # the geometry this formula needs
    lens = 2 * big**2 * np.arccos(d / (2 * big)) - 0.5 * d * np.sqrt(4 * big**2 - d**2)
    return lens - 2 * np.pi * small**2


def test_reachable_area_matches_the_closed_form_lens_minus_holes() -> None:
    n, half = 401, 2.0
    field = ws.singularity_field(PHI1, PHI2, (-half, half, -half, half), n=n)
    cell = (2 * half / (n - 1)) ** 2
    # measured: 0.05 % at n = 401 (0.3 % at n = 101); one leg alone would give 64 % more
    assert field.reachable.sum() * cell == pytest.approx(_reach_area(), rel=2e-3)
    assert np.all(np.isnan(field.parallel[~field.reachable]))
    assert np.all(np.isfinite(field.parallel[field.reachable]))


def test_parallel_measure_vanishes_on_the_axis_singularity_and_changes_sign_across_it() -> None:
    y_p = MIW["y_parallel"]  # distal links aligned on the symmetry axis (closed form)
    # a grid with a node exactly at (0, y_p): odd n centred on x = 0, y rows through y_p
    n, h = 101, 0.01
    window = (-0.5, 0.5, y_p - 50 * h, y_p + 50 * h)
    field = ws.singularity_field(PHI1, PHI2, window, n=n)
    i0, j0 = 50, 50
    assert field.x[j0] == pytest.approx(0.0, abs=1e-15)
    assert field.y[i0] == pytest.approx(y_p, abs=1e-12)
    assert abs(field.parallel[i0, j0]) < 1e-9
    column = field.parallel[:, j0]
    assert np.all(np.sign(column[:i0]) == -np.sign(column[i0 + 1 :][0]))
    assert np.all(np.sign(column[i0 + 1 :]) == np.sign(column[i0 + 1]))
    # the MIW centre is on the side above the singularity
    centre = kin.singularity_measures([[0.0, MIW["cy"]]], PHI1, PHI2)["parallel"][0]
    assert np.sign(centre) == np.sign(column[-1])


def test_working_side_share_counts_the_reachable_points_on_the_centres_side() -> None:
    field = ws.singularity_field(PHI1, PHI2, (-2.2, 2.2, -0.5, 2.2), n=81)
    share = ws.working_side_share(field, (0.0, MIW["cy"]))
    assert share["reachable"] == pytest.approx(field.reachable.mean(), abs=0)
    above = field.reachable & (field.parallel > 0)
    assert np.sign(kin.singularity_measures([[0.0, MIW["cy"]]], PHI1, PHI2)["parallel"][0]) > 0
    assert share["working_side"] == pytest.approx(above.mean(), abs=0)
    assert 0 < share["working_side"] < share["reachable"] < 1
    # from a point on the other side (below the axis singularity) the shares are complementary
    below = ws.working_side_share(field, (0.0, 0.5 * MIW["y_parallel"]))
    below_count = (field.reachable & (field.parallel < 0)).mean()
    assert below["working_side"] == pytest.approx(below_count, abs=0)
    # no reachable grid node lies exactly on the singularity, so the two sides fill the reach
    assert share["working_side"] + below["working_side"] == pytest.approx(share["reachable"])


def test_leg_chain_closes_the_vector_loop_of_eq22() -> None:
    point = np.array([0.1, 1.2])
    for phi, mode in ((PHI1, 1), (PHI2, -1)):
        (a, b, p), theta = ws.leg_chain(point, phi, mode)
        np.testing.assert_allclose(a, phi[2:4])
        np.testing.assert_allclose(p, point)
        assert np.hypot(*(b - a)) == pytest.approx(phi[0], rel=1e-12)
        assert np.hypot(*(p - b)) == pytest.approx(phi[1], rel=1e-12)
        assert theta == pytest.approx(dyad.active_angle(point[None, :], phi, mode)[0], abs=0)
        # the elbow is the one the joint reading puts there (Eqs 13, 20)
        np.testing.assert_allclose(b, kin.elbow(kin.joint_reading(point, phi, mode), phi)[0])
    chains = ws.mechanism_chains(point, PHI1, PHI2)
    assert chains.shape == (2, 3, 2)
    np.testing.assert_allclose(chains[1], ws.leg_chain(point, PHI2, -1)[0])


def test_bad_input_gets_clear_errors() -> None:
    with pytest.raises(ValueError, match="x_min < x_max"):
        ws.singularity_field(PHI1, PHI2, (1.0, -1.0, 0.0, 1.0))
    with pytest.raises(ValueError, match="window must be four finite numbers"):
        ws.singularity_field(PHI1, PHI2, (0.0, 1.0, 0.0))
    with pytest.raises(ValueError, match="n must be"):
        ws.singularity_field(PHI1, PHI2, (-1, 1, 0, 1), n=2)
    field = ws.singularity_field(PHI1, PHI2, (-1.0, 1.0, 0.5, 2.0), n=21)
    with pytest.raises(ValueError, match="point must lie in the field's window"):
        ws.working_side_share(field, (0.0, 3.0))
    with pytest.raises(ValueError, match="outside the workspace"):
        ws.leg_chain((5.0, 5.0), PHI1, 1)
