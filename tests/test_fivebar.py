"""5R kinematics, identification Jacobian, identification and posture selection."""

import numpy as np
import pytest
from scipy.linalg import block_diag

from mechlib import published as pub
from mechlib.fivebar import identification as idf
from mechlib.fivebar import kinematics as kin
from mechlib.fivebar import postures as ps
from mechlib.fivebar import study

PHI1 = kin.leg_vector(pub.TABLE7_NOMINAL, 1)
PHI2 = kin.leg_vector(pub.TABLE7_NOMINAL, 2)
REAL1 = kin.leg_vector(pub.TABLE7_REAL, 1)
REAL2 = kin.leg_vector(pub.TABLE7_REAL, 2)
MODES = kin.NOMINAL_MODES
MIW = kin.miw_closed_form(PHI1[0], PHI1[1], abs(PHI1[2]))
CANDIDATES = kin.in_circle_grid((0.0, MIW["cy"]), 0.8 * MIW["radius"], 8, 24)


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
    c = idf.identification_jacobian(CANDIDATES, PHI1, 1)
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


def test_noise_free_identification_recovers_the_real_parameters() -> None:
    rng = np.random.default_rng(0)
    m = idf.simulate_measurements(CANDIDATES, REAL1, REAL2, PHI1, PHI2, MODES, 0.0, rng)
    fit = idf.identify_leg(m["points"], m["psi1"], PHI1, 1)
    np.testing.assert_allclose(fit.phi, REAL1, atol=1e-10)
    np.testing.assert_allclose(
        idf.identify_leg_scipy(m["points"], m["psi1"], PHI1, 1), REAL1, atol=1e-9
    )
    fit = idf.identify_traditional(m["points"], m["psi1"], m["psi2"], PHI1, PHI2, MODES)
    assert fit.converged and fit.residual_rms < 1e-12
    both = fit.phi
    np.testing.assert_allclose(both, np.r_[REAL1, REAL2], atol=1e-10)
    stopped = idf.identify_traditional(
        m["points"], m["psi1"], m["psi2"], PHI1, PHI2, MODES, max_iter=1
    )
    assert not stopped.converged and stopped.iterations == 1
    assert idf.position_errors(CANDIDATES, both[:6], both[6:], REAL1, REAL2, MODES).max() < 1e-9


def test_posture_blocks_are_diag_c1_c2_sized_by_the_legs() -> None:
    c1 = np.array([[1.0, 2.0], [3.0, 4.0]])  # two postures, a 2-parameter leg
    c2 = np.array([[5.0, 6.0, 7.0], [8.0, 9.0, 10.0]])  # and a 3-parameter leg
    expected = [
        [[1.0, 2.0, 0.0, 0.0, 0.0], [0.0, 0.0, 5.0, 6.0, 7.0]],
        [[3.0, 4.0, 0.0, 0.0, 0.0], [0.0, 0.0, 8.0, 9.0, 10.0]],
    ]
    assert idf.posture_blocks(c1, c2).tolist() == expected
    with pytest.raises(ValueError, match=r"same N postures, got shapes \(2, 2\) and \(1, 3\)"):
        idf.posture_blocks(c1, c2[:1])


def test_total_jacobian_is_the_block_diagonal_of_the_legs() -> None:
    c1 = idf.identification_jacobian(CANDIDATES, PHI1, MODES[0])
    c2 = idf.identification_jacobian(CANDIDATES, PHI2, MODES[1])
    total = idf.total_jacobian(CANDIDATES, PHI1, PHI2, MODES)
    np.testing.assert_array_equal(total, block_diag(c1, c2))


def test_active_selection_equals_svd_reference() -> None:
    c1 = idf.identification_jacobian(CANDIDATES, PHI1, 1)
    a = ps.select_active(c1, 18)
    assert sorted(a.tolist()) == sorted(ps.select_reference_svd(c1, 18).tolist())
    assert len(set(a.tolist())) == 18
    random_set = np.random.default_rng(1).choice(len(c1), 18, replace=False)
    assert ps.observability_o1(c1[a]) > ps.observability_o1(c1[random_set])


def test_o1_definitions_differ_only_by_a_constant_for_fixed_sizes() -> None:
    c = idf.identification_jacobian(CANDIDATES[:20], PHI1, 1)
    ratio = ps.observability_o1(c) / ps.observability_borm_menq(c)
    assert ratio == pytest.approx(np.sqrt(20) / 6)


def test_bad_input_gets_clear_errors() -> None:
    with pytest.raises(ValueError, match="outside the workspace"):
        kin.joint_reading([[5.0, 5.0]], PHI1, 1)
    with pytest.raises(ValueError, match=r"mode must be one of \[1, -1\]"):
        kin.joint_reading([[0.0, 1.0]], PHI1, 0)
    with pytest.raises(ValueError, match="sigma must be >= 0"):
        idf.simulate_measurements(
            CANDIDATES, REAL1, REAL2, PHI1, PHI2, MODES, -1.0, np.random.default_rng(0)
        )
    with pytest.raises(ValueError, match="n_select must be <= the number of candidates"):
        ps.select_active(np.ones((3, 6)), 4)
    same = np.tile(CANDIDATES[:1], (10, 1))  # one posture repeated: rank 1
    with pytest.raises(ValueError, match="unidentifiable"):
        idf.identify_leg(same, kin.joint_reading(same, PHI1, 1), PHI1, 1)
    with pytest.raises(ValueError, match=r"phi.L must be > 0.0"):
        kin.check_leg([0.75, -1.0, 0, 0, 1, 0])


def test_poses_at_a_singularity_are_refused_by_name() -> None:
    parallel = np.array([[0.0, MIW["y_parallel"]]])  # distal links aligned on the symmetry axis
    assert abs(kin.singularity_measures(parallel, PHI1, PHI2)["parallel"][0]) < 1e-9
    with pytest.raises(ValueError, match=r"parallel \(distal links aligned\) singularity"):
        idf.simulate_measurements(
            parallel, REAL1, REAL2, PHI1, PHI2, MODES, 1e-4, np.random.default_rng(0)
        )
    reach = PHI1[0] + PHI1[1]
    stretched = PHI1[2:4] + reach * np.array([np.cos(1.2), np.sin(1.2)])  # leg 1 stretched
    with pytest.raises(ValueError, match="serial singularity"):
        idf.identification_jacobian(stretched[None, :], PHI1, MODES[0])
    with pytest.raises(ValueError, match=r"serial \(leg 1 stretched or folded\)"):
        kin.check_regular(stretched[None, :], PHI1, PHI2, MODES)
    kin.check_regular(CANDIDATES, PHI1, PHI2, MODES)  # the study's candidates are regular


def test_monte_carlo_leaves_unconverged_trials_out_of_both_strategies(monkeypatch) -> None:
    real = study.one_trial
    calls = {"n": 0}

    def flaky(*args, **kwargs):
        calls["n"] += 1
        res = real(*args, **kwargs)
        return {**res, "converged": calls["n"] != 2}  # the second trial "fails"

    mech = study.Mechanism(PHI1, PHI2, REAL1, REAL2, MODES)
    cands = CANDIDATES
    chosen = study.select(mech, cands, 9, 18)
    grid = cands[:20]
    full = study.monte_carlo(mech, cands, chosen, grid, 1e-4, 3, seed=1)
    monkeypatch.setattr(study, "one_trial", flaky)
    part = study.monte_carlo(mech, cands, chosen, grid, 1e-4, 3, seed=1)
    assert full["failed"].tolist() == [] and part["failed"].tolist() == [1]
    for key in ("rms_dc", "rms_trad", "param_err_dc", "param_err_trad"):
        np.testing.assert_array_equal(part[key], full[key][[0, 2]])  # paired, same noise draws
    monkeypatch.setattr(study, "one_trial", lambda *a, **k: {**real(*a, **k), "converged": False})
    with pytest.raises(RuntimeError, match="no Monte Carlo trial converged"):
        study.monte_carlo(mech, cands, chosen, grid, 1e-4, 2, seed=1)


def test_the_claim_rule_needs_a_majority_and_significance() -> None:
    assert study.claim_holds({"share_a_better": 0.51, "p_value": 0.049})
    assert not study.claim_holds({"share_a_better": study.CLAIM_MIN_SHARE, "p_value": 1e-9})
    assert not study.claim_holds({"share_a_better": 0.9, "p_value": study.CLAIM_MAX_P})


def test_parameter_rms_over_all_and_per_parameter_by_hand() -> None:
    errors = np.array([[3.0, 0.0], [0.0, 4.0]])
    assert study.parameter_rms(errors) == 2.5  # sqrt((9 + 16) / 4)
    np.testing.assert_allclose(study.parameter_rms(errors, per_parameter=True), [4.5**0.5, 8**0.5])
    with pytest.raises(ValueError, match=r"errors must be \(trials, parameters\)"):
        study.parameter_rms(np.ones(3))


def test_summary_rows_in_micrometres_with_a_t_interval() -> None:
    from scipy import stats

    mc = {
        "rms_dc": np.array([1e-6, 3e-6]),
        "rms_trad": np.array([2e-6, 2e-6]),
        "param_err_dc": np.array([[3.0, 0.0], [0.0, 4.0]]),
        "param_err_trad": np.zeros((2, 2)),
        "time_dc": np.array([1e-3, 3e-3, 2e-3]),
        "time_trad": np.array([1e-3]),
    }
    rows = study.summary(mc)
    half = stats.t.ppf(0.975, 1) * np.sqrt(2) / np.sqrt(2)  # t · s / √n, s = √2 µm
    assert list(rows) == ["D&C", "traditional"]
    dc = rows["D&C"]
    assert dc["workspace RMS mean [µm]"] == pytest.approx(2.0)
    assert dc["95 % CI low"] == pytest.approx(2.0 - half) and dc["95 % CI high"] == pytest.approx(
        2.0 + half
    )
    assert dc["param. RMS error (all 12)"] == 2.5 and dc["solve time median [ms]"] == pytest.approx(
        2.0
    )
    assert rows["traditional"]["95 % CI low"] == pytest.approx(2.0)  # no spread, no interval


def test_measurement_totals_reproduce_table8_for_its_counts() -> None:
    """Table 8 prints 18·2(2+1) = 108 for D&C and 2·18·2 = 72 for 18 shared postures."""
    counts = study.measurement_counts(pub.SEC37_POSTURES_PER_LEG, pub.SEC37_POSTURES_PER_LEG)
    assert counts["dc"]["total"] == pub.TABLE8_MEASUREMENTS_DC
    assert counts["trad"]["total"] == pub.TABLE8_MEASUREMENTS_TRADITIONAL
    defaults = study.measurement_counts(18, 36)
    assert defaults["trad"]["total"] == 144 == 2 * 36 + 2 * 36
