"""5R kinematics, its instance of the calibration core (legs, identification Jacobian, the
chapter's study) and posture selection on it."""

import numpy as np
import pytest

from mechlib import dyad
from mechlib import published as pub
from mechlib.calibration import identify as ci
from mechlib.calibration import mechanism as cm
from mechlib.calibration import selection as sel
from mechlib.fivebar import kinematics as kin
from mechlib.fivebar import mechanism as fivebar

PHI1 = kin.leg_vector(pub.TABLE7_NOMINAL, 1)
PHI2 = kin.leg_vector(pub.TABLE7_NOMINAL, 2)
REAL1 = kin.leg_vector(pub.TABLE7_REAL, 1)
REAL2 = kin.leg_vector(pub.TABLE7_REAL, 2)
MODES = kin.NOMINAL_MODES
MIW = kin.miw_closed_form(PHI1[0], PHI1[1], abs(PHI1[2]))
CANDIDATES = kin.in_circle_grid((0.0, MIW["cy"]), 0.8 * MIW["radius"], 8, 24)
MECH = fivebar.mechanism(0.8)


def test_ik_then_fk_is_identity_over_the_workspace() -> None:
    pts = kin.in_circle_grid((0.0, MIW["cy"]), 0.99 * MIW["radius"], 12, 36)
    psi1 = kin.joint_reading(pts, PHI1, MODES[0])
    psi2 = kin.joint_reading(pts, PHI2, MODES[1])
    np.testing.assert_allclose(kin.forward(psi1, psi2, PHI1, PHI2), pts, atol=1e-12)


def test_thesis_layout_is_mirror_symmetric() -> None:
    pts = np.array([[0.0, 1.0], [0.2, 1.3]])
    mirrored = pts * [-1, 1]
    np.testing.assert_allclose(
        kin.joint_reading(pts, PHI1, 1), kin.joint_reading(mirrored, PHI2, -1), atol=1e-4
    )  # γ2 is printed as 3.1416, not π


def test_miw_numeric_agrees_with_closed_form() -> None:
    num = kin.miw_numeric(PHI1, PHI2, n_centers=61, tol=1e-5)
    assert num["cy"] == pytest.approx(MIW["cy"], abs=5e-4)
    assert num["radius"] == pytest.approx(MIW["radius"], abs=5e-4)


def test_miw_touches_the_parallel_singularity() -> None:
    bottom = np.array([[0.0, MIW["cy"] - MIW["radius"] + 1e-9]])
    assert abs(kin.singularity_measures(bottom, PHI1, PHI2)["parallel"][0]) < 1e-3


def test_identification_jacobian_matches_finite_differences() -> None:
    c = MECH.legs[0].jacobian(PHI1, CANDIDATES)
    h = 1e-7
    fd = np.column_stack(
        [
            (
                kin.joint_reading(CANDIDATES, PHI1 + h * e, 1)
                - kin.joint_reading(CANDIDATES, PHI1 - h * e, 1)
            )
            / (2 * h)
            for e in np.eye(6)
        ]
    )
    np.testing.assert_allclose(c, fd, atol=1e-7)


def test_the_5r_instance_reads_its_legs_in_the_chapters_modes() -> None:
    for k, (leg, phi) in enumerate(zip(MECH.legs, (PHI1, PHI2), strict=True)):
        assert leg.names == kin.leg_keys(k + 1)
        np.testing.assert_array_equal(
            leg.ik(phi, CANDIDATES), kin.joint_reading(CANDIDATES, phi, MODES[k])
        )
    np.testing.assert_array_equal(np.concatenate(fivebar.real_parameters()), np.r_[REAL1, REAL2])


def test_noise_free_gauss_newton_recovers_the_real_parameters() -> None:
    r, q = cm.simulate(MECH, (REAL1, REAL2), CANDIDATES, 0.0, np.random.default_rng(0))
    fit = ci.identify_leg(MECH.legs[0], r, q[:, 0], solver="gn")
    assert fit.converged and fit.evaluations < ci.GN_MAX_ITER
    np.testing.assert_allclose(fit.phi, REAL1, atol=1e-10)
    both = ci.identify_traditional(MECH, r, q, solver="gn")
    assert both.converged and both.residual_rms < 1e-12
    np.testing.assert_allclose(both.phi, np.r_[REAL1, REAL2], atol=1e-10)
    errors = cm.pose_errors(MECH, ci.split(MECH, both.phi), (REAL1, REAL2), CANDIDATES)
    assert np.abs(errors).max() < 1e-9


def test_disc_lattice_keeps_the_points_inside_the_disc() -> None:
    pts = fivebar.disc_grid((1.0, 2.0), 0.25, 0.1)
    # the 5 × 5 lattice of spacing 0.1 about the centre, less the 4 corners at 0.28 m
    assert len(pts) == 21
    assert np.hypot(pts[:, 0] - 1.0, pts[:, 1] - 2.0).max() <= 0.25
    with pytest.raises(ValueError, match="spacing"):
        fivebar.disc_grid((0.0, 0.0), 1.0, 0.0)


def test_the_chapters_study_lies_in_its_disc_with_table_7s_real_parameters() -> None:
    s = fivebar.study(candidate_spacing=0.1, grid_spacing=0.2)
    disc = fivebar.miw(s.mech)
    radius = fivebar.FRACTION * disc["radius"]
    for pts in (s.candidates, s.grid):
        assert np.hypot(pts[:, 0] - disc["cx"], pts[:, 1] - disc["cy"]).max() <= radius
    assert s.solver == "gn" and np.all(s.scale == fivebar.DISTURBANCE)
    np.testing.assert_array_equal(np.concatenate(s.real), np.r_[REAL1, REAL2])


def test_active_selection_equals_svd_reference() -> None:
    c1 = MECH.legs[0].jacobian(PHI1, CANDIDATES)
    a = sel.select_active(c1, 18)
    assert sorted(a.tolist()) == sorted(sel.select_reference_svd(c1, 18).tolist())
    assert len(set(a.tolist())) == 18
    random_set = np.random.default_rng(1).choice(len(c1), 18, replace=False)
    assert sel.observability_o1(c1[a]) > sel.observability_o1(c1[random_set])


def test_o1_definitions_differ_only_by_a_constant_for_fixed_sizes() -> None:
    c = MECH.legs[0].jacobian(PHI1, CANDIDATES[:20])
    ratio = sel.observability_o1(c) / sel.observability_borm_menq(c)
    assert ratio == pytest.approx(np.sqrt(20) / 6)


def test_bad_input_gets_clear_errors() -> None:
    with pytest.raises(ValueError, match="outside the workspace"):
        kin.joint_reading([[5.0, 5.0]], PHI1, 1)
    with pytest.raises(ValueError, match=r"mode must be one of \[1, -1\]"):
        kin.joint_reading([[0.0, 1.0]], PHI1, 0)
    with pytest.raises(ValueError, match="sigma"):
        cm.simulate(MECH, (REAL1, REAL2), CANDIDATES, -1.0, np.random.default_rng(0))
    with pytest.raises(ValueError, match="n_select must be <= the number of candidates"):
        sel.select_active(np.ones((3, 6)), 4)
    same = np.tile(CANDIDATES[:1], (10, 1))  # one posture repeated: rank 1
    with pytest.raises(ValueError, match="unidentifiable"):
        ci.identify_leg(MECH.legs[0], same, kin.joint_reading(same, PHI1, 1), solver="gn")
    with pytest.raises(ValueError, match=r"phi.L must be > 0.0"):
        kin.check_leg([0.75, -1.0, 0, 0, 1, 0])


def test_poses_at_a_singularity_are_refused_by_name() -> None:
    parallel = np.array([[0.0, MIW["y_parallel"]]])  # distal links aligned on the symmetry axis
    assert abs(kin.singularity_measures(parallel, PHI1, PHI2)["parallel"][0]) < 1e-9
    # the calibration disc stays inside the MIW, away from the parallel singularity
    with pytest.raises(ValueError, match="outside the calibration region of planar 5R"):
        cm.simulate(MECH, (REAL1, REAL2), parallel, 1e-4, np.random.default_rng(0))
    reach = PHI1[0] + PHI1[1]
    stretched = PHI1[2:4] + reach * np.array([np.cos(1.2), np.sin(1.2)])  # leg 1 stretched
    with pytest.raises(ValueError, match="serial singularity"):
        dyad.jacobian(stretched[None, :], PHI1, MODES[0], min_sine=kin.SINGULAR_TOL)
    with pytest.raises(ValueError, match=r"serial \(leg 1 stretched or folded\)"):
        kin.check_regular(stretched[None, :], PHI1, PHI2, MODES)
    kin.check_regular(CANDIDATES, PHI1, PHI2, MODES)  # the study's candidates are regular
