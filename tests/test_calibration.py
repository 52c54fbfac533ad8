"""The leg-wise calibration core on the 5R instance: identification, identifiability, selection,
budgets, the Monte Carlo and the refusals of bad input (the core's options — solvers, failed
trials, noise streams, budgets, sweeps — in tests/test_calibration_montecarlo.py)."""

import numpy as np
import pytest

from mechlib import dyad
from mechlib.calibration import cost
from mechlib.calibration import identify as ci
from mechlib.calibration import mechanism as cm
from mechlib.calibration import montecarlo as mcarlo
from mechlib.calibration import selection as sel
from mechlib.calibration import study as st
from mechlib.fivebar import kinematics as kin
from mechlib.fivebar import mechanism as fivebar

MECH = fivebar.mechanism(0.8)
REAL = fivebar.real_parameters()
MIW = kin.miw_closed_form(0.75, 1.1, 0.5)
CANDIDATES = fivebar.disc_grid((0.0, MIW["cy"]), 0.8 * MIW["radius"], 0.08)


def test_the_5r_chapter_calls_the_dyad() -> None:
    # the chapter's kinematics checks its input, then runs the dyad's formulas: the same digits;
    # the core's 5R legs are the dyad's too
    for k, mode in ((0, 1), (1, -1)):
        phi = MECH.nominal[k]
        np.testing.assert_array_equal(
            dyad.reading(CANDIDATES, phi, mode), kin.joint_reading(CANDIDATES, phi, mode)
        )
        np.testing.assert_array_equal(
            dyad.jacobian(CANDIDATES, phi, mode), MECH.legs[k].jacobian(phi, CANDIDATES)
        )


def test_unreachable_point_is_refused_by_the_dyad() -> None:
    with pytest.raises(ValueError, match="out of the leg's reach"):
        dyad.reading(np.array([[0.0, 5.0]]), MECH.nominal[0], 1)


def test_generic_forward_kinematics_matches_the_closed_form() -> None:
    q = cm.readings(MECH, MECH.nominal, CANDIDATES)
    newton = cm.Mechanism(**{**MECH.__dict__, "forward": None})
    np.testing.assert_allclose(
        cm.forward(newton, REAL, q, CANDIDATES), cm.forward(MECH, REAL, q, CANDIDATES), atol=1e-12
    )


def test_noise_free_identification_recovers_the_real_parameters() -> None:
    r, q = cm.simulate(MECH, REAL, CANDIDATES[:20], 0.0, np.random.default_rng(0))
    for k, leg in enumerate(MECH.legs):
        fit = ci.identify_leg(leg, r, q[:, k])
        assert fit.converged
        np.testing.assert_allclose(fit.phi, REAL[k], atol=1e-9)
    trad = ci.identify_traditional(MECH, r, q)
    np.testing.assert_allclose(trad.phi, np.concatenate(REAL), atol=1e-9)


def test_the_5r_leg_is_identifiable_with_six_parameters_and_rank_loss_is_named() -> None:
    c = MECH.legs[0].jacobian(MECH.nominal[0], CANDIDATES)
    info = ci.identifiability(c, MECH.legs[0].names)
    assert info["rank"] == 6 and info["dependent"] == ()
    # a duplicated column (gain and a copy of it) is found dependent
    c2 = np.column_stack([c, 2 * c[:, 4]])
    info2 = ci.identifiability(c2, (*MECH.legs[0].names, "k1bis"))
    assert info2["rank"] == 6 and len(info2["dependent"]) == 1
    with pytest.raises(ValueError, match="unidentifiable"):
        ci.check_identifiable(c2, (*MECH.legs[0].names, "k1bis"))


def test_too_small_a_pose_budget_is_refused_before_computing() -> None:
    r, q = cm.simulate(MECH, REAL, CANDIDATES[:5], 0.0, np.random.default_rng(0))
    with pytest.raises(ValueError, match="5 equations cannot identify 6"):
        ci.identify_leg(MECH.legs[0], r, q[:, 0])
    study = st.make_study(MECH, REAL, CANDIDATES, CANDIDATES[:10], np.ones(12))
    with pytest.raises(ValueError, match="n_per_leg"):
        st.select_dc(study, 5)


def test_negative_noise_and_poses_outside_the_region_are_refused() -> None:
    with pytest.raises(ValueError, match="sigma"):
        cm.simulate(MECH, REAL, CANDIDATES[:8], -1e-4, np.random.default_rng(0))
    with pytest.raises(ValueError, match="outside the calibration region"):
        cm.simulate(MECH, REAL, [[0.0, 0.2]], 1e-4, np.random.default_rng(0))


def test_inconsistent_legs_are_refused() -> None:
    leg3 = cm.Leg(("a", "b"), ("m", "m"), np.zeros(2), MECH.legs[0].ik, MECH.legs[0].jacobian)
    with pytest.raises(ValueError, match="leg 2 has 2 parameters"):
        cm.Mechanism("bad", (MECH.legs[0], leg3), ("x", "y"), ("m", "m"), MECH.region, "")
    with pytest.raises(ValueError, match="as many names, units and nominal"):
        cm.Leg(("a", "b"), ("m",), np.zeros(2), MECH.legs[0].ik, MECH.legs[0].jacobian)


def test_shared_selection_equals_active_selection_on_the_stacked_blocks() -> None:
    c1, c2 = (leg.jacobian(leg.nominal, CANDIDATES) for leg in MECH.legs)
    blocks = np.zeros((len(CANDIDATES), 2, 12))  # posture j: rows [C1_j, 0] and [0, C2_j]
    blocks[:, 0, :6], blocks[:, 1, 6:] = c1, c2
    np.testing.assert_array_equal(sel.select_shared([c1, c2], 14), sel.select_active(blocks, 14))


def test_indices_known_answers() -> None:
    c = np.diag([3.0, 2.0, 1.0])
    assert sel.observability_o1(c) == pytest.approx(6 ** (1 / 3) / 3)
    assert sel.observability_o3(c) == pytest.approx(1.0)  # unit columns after scaling
    assert sel.d_optimality(c) == pytest.approx(36 ** (1 / 3))


def test_budgets_follow_table_8s_accounting_for_the_5r() -> None:
    assert st.measurement_counts(MECH, 18, 36) == {"dc": 108, "trad": 144}
    assert st.budgets(MECH, 18) == {"thesis": 36, "matched": 27}
    assert st.budgets(MECH, 18, st.ALL_BUDGETS) == {"thesis": 36, "equations": 18, "matched": 27}
    assert cost.normal_sizes(MECH)["flop_ratio"] == 4.0


def test_monte_carlo_is_seeded_and_noise_free_trials_are_exact() -> None:
    study = st.make_study(MECH, REAL, CANDIDATES, CANDIDATES[::5], np.ones(12))
    dc = st.select_dc(study, 8)
    trad = {"thesis": st.select_traditional(study, 16)}
    a = mcarlo.monte_carlo(study, dc, trad, 1e-4, 3, 7)
    b = mcarlo.monte_carlo(study, dc, trad, 1e-4, 3, 7)
    np.testing.assert_array_equal(a["dc"]["pos_rms"], b["dc"]["pos_rms"])
    exact = mcarlo.monte_carlo(study, dc, trad, 0.0, 1, 7)
    assert exact["dc"]["pos_rms"][0] < 1e-10 and exact["thesis"]["pos_rms"][0] < 1e-10
    assert np.abs(exact["thesis"]["param"]).max() < 1e-8


def test_greedy_selection_by_o1_variants_and_d_optimality_agree_with_active_calibration() -> None:
    c = MECH.legs[0].jacobian(MECH.nominal[0], CANDIDATES)
    picks = {name: sel.select_greedy(c, 12, name) for name in sel.INDICES}
    d_opt = picks["D-optimality"]
    for name in ("O1 (thesis, Eq 18)", "O1 (Borm & Menq)"):
        np.testing.assert_array_equal(picks[name], d_opt)
    np.testing.assert_array_equal(d_opt, sel.select_active(c, 12, max_passes=0))
    # O3 maximises its own index: at least as good as the D-optimal set on O3
    assert sel.observability_o3(c[picks["O3 (inverse condition number)"]]) >= sel.observability_o3(
        c[d_opt]
    )
    with pytest.raises(ValueError, match="index must be one of"):
        sel.select_greedy(c, 12, "O9")


def test_catalog_builds_each_mechanism_and_refuses_an_unknown_one() -> None:
    from mechlib import mechanism_catalog as catalog

    sizes = {}
    for name in catalog.NAMES:
        built = catalog.build(
            name, seed=1, disturbance=4e-3, n_candidates=60, n_random_grid=5, slice_points=3
        )
        sizes[name] = (built.study.mech.n_limbs, built.study.mech.dof)
        assert 0 < built.n_slice <= len(built.study.grid)
    assert sizes == {"5R": (2, 2), "3-RRR": (3, 3), "6-UPS": (6, 6)}
    with pytest.raises(ValueError, match="mechanism must be one of"):
        catalog.build(
            "4-RRR", seed=1, disturbance=4e-3, n_candidates=60, n_random_grid=5, slice_points=3
        )


def test_measurement_matched_budget_equalises_the_counts() -> None:
    from mechlib.mechanisms import gough_stewart

    gs = gough_stewart.mechanism()
    b = st.budgets(gs, 24)
    counts = st.measurement_counts(gs, 24, b["matched"])
    assert b["thesis"] == 144 and counts["dc"] == counts["trad"] == 24 * 6 * 7
