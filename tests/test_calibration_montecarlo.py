"""The calibration core's options, on a coarse 5R study: the Gauss–Newton solver (Eq 26), trials
whose fits did not converge left out of both strategies (paired) and listed, each pose set's own
noise stream, the three budgets, the full sweep; and the statistics' known answers."""

import numpy as np
import pytest

from mechlib import published as pub
from mechlib.calibration import identify as ci
from mechlib.calibration import mechanism as cm
from mechlib.calibration import montecarlo as mcarlo
from mechlib.calibration import statistics as cs
from mechlib.calibration import study as st
from mechlib.fivebar import mechanism as fivebar

STUDY = fivebar.study(candidate_spacing=0.08, grid_spacing=0.2)
MECH = STUDY.mech
DC = st.select_dc(STUDY, 8)
TRAD = {"thesis": st.select_traditional(STUDY, 16), "matched": st.select_traditional(STUDY, 12)}


def _draw(sigma: float = 1e-4) -> tuple[np.ndarray, np.ndarray]:
    return cm.simulate(MECH, STUDY.real, STUDY.candidates[DC[0]], sigma, np.random.default_rng(3))


def test_gauss_newton_and_levenberg_marquardt_reach_the_same_least_squares_solution() -> None:
    r, q = _draw()
    gn = ci.identify_leg(MECH.legs[0], r, q[:, 0], solver="gn")
    lm = ci.identify_leg(MECH.legs[0], r, q[:, 0], solver="lm")
    assert gn.converged and lm.converged and gn.evaluations < ci.GN_MAX_ITER
    np.testing.assert_allclose(gn.phi, lm.phi, atol=1e-9)
    assert gn.residual_rms == pytest.approx(lm.residual_rms, rel=1e-9)
    assert np.abs(gn.phi - STUDY.real[0]).max() > 1e-5  # noisy: not the real parameters


def test_gauss_newton_reports_a_fit_stopped_before_its_tolerance(monkeypatch) -> None:
    r, q = _draw()
    monkeypatch.setattr(ci, "GN_MAX_ITER", 1)
    fit = ci.identify_leg(MECH.legs[0], r, q[:, 0], solver="gn")
    assert not fit.converged and fit.evaluations == 1
    shared = STUDY.candidates[TRAD["thesis"]]
    r, q = cm.simulate(MECH, STUDY.real, shared, 1e-4, np.random.default_rng(0))
    trad = ci.identify_traditional(MECH, r, q, solver="gn")
    assert not trad.converged and trad.evaluations == 1


def test_an_unknown_solver_is_refused() -> None:
    r, q = _draw()
    with pytest.raises(ValueError, match=r"solver must be one of \['lm', 'gn'\], got 'newton'"):
        ci.identify_leg(MECH.legs[0], r, q[:, 0], solver="newton")
    with pytest.raises(ValueError, match="solver must be one of"):
        st.make_study(MECH, STUDY.real, STUDY.candidates, STUDY.grid, STUDY.scale, "newton")


def _failing(monkeypatch, name: str, failing_calls: set[int]) -> None:
    """Make the ``failing_calls``-th calls (from 1) of ``ci.<name>`` report no convergence."""
    real, calls = getattr(ci, name), {"n": 0}

    def fit(*args, **kwargs):
        calls["n"] += 1
        out = real(*args, **kwargs)
        return ci.Fit(out.phi, out.evaluations, out.residual_rms, calls["n"] not in failing_calls)

    monkeypatch.setattr(ci, name, fit)


def test_a_trial_whose_traditional_fit_failed_is_left_out_of_that_comparison_only(
    monkeypatch,
) -> None:
    full = mcarlo.monte_carlo(STUDY, DC, TRAD, 1e-4, 3, 5)
    # per trial the traditional fits run "thesis", then "matched": call 3 is trial 1's "thesis"
    _failing(monkeypatch, "identify_traditional", {3})
    part = mcarlo.monte_carlo(STUDY, DC, TRAD, 1e-4, 3, 5)
    assert cs.failed_trials(part, ("dc", "thesis")).tolist() == [1]
    assert cs.failed_trials(part, ("dc", "matched")).tolist() == []
    got, kept = cs.compare(part, "thesis"), [0, 2]
    assert got["failed_trials"] == 1 and got["trials_used"] == 2
    for strategy, suffix in (("dc", "dc"), ("thesis", "trad")):
        rms = full[strategy]["pos_rms"][kept]  # paired: the same noise draws, trial 1 left out
        assert got[f"pos_rms_{suffix}"] == pytest.approx(rms.mean(), rel=1e-12)
        assert got[f"pos_rms_median_{suffix}"] == pytest.approx(np.median(rms), rel=1e-12)
    assert got["share_dc_better"] == np.mean(
        full["dc"]["pos_rms"][kept] < full["thesis"]["pos_rms"][kept]
    )
    assert cs.compare(part, "matched") == cs.compare(full, "matched")
    np.testing.assert_allclose(
        cs.local_rms(part, "dc", ("thesis",)),
        np.sqrt(full["dc"]["pos_sq"][kept].mean(axis=0)),
        rtol=1e-12,
    )
    # kept in when asked: every trial, its (here unchanged) numbers averaged in
    assert cs.compare(part, "thesis", drop_failed=False) == cs.compare(full, "thesis")


def test_a_trial_whose_dc_fit_failed_is_left_out_of_every_comparison(monkeypatch) -> None:
    _failing(monkeypatch, "identify_leg", {2})  # trial 0's second leg
    part = mcarlo.monte_carlo(STUDY, DC, TRAD, 1e-4, 2, 5)
    assert not part["dc"]["converged"][0] and part["thesis"]["converged"].all()
    for key in TRAD:
        assert cs.compare(part, key)["trials_used"] == 1
    summary = cs.summary(part, "thesis")
    assert summary["dc"]["workspace RMS mean [µm]"] == pytest.approx(
        1e6 * part["dc"]["pos_rms"][1], rel=1e-12
    )


def test_a_failed_fit_that_cannot_be_evaluated_is_nan_and_left_out(monkeypatch) -> None:
    full = mcarlo.monte_carlo(STUDY, DC, {"thesis": TRAD["thesis"]}, 1e-4, 2, 5)
    real, calls = ci.identify_traditional, {"n": 0}

    def diverged(*args, **kwargs):
        calls["n"] += 1
        out = real(*args, **kwargs)
        if calls["n"] != 2:
            return out
        phi = out.phi.copy()
        phi[[1, 7]] = 0.1  # distal links of 0.1 m: no grid pose is reachable
        return ci.Fit(phi, out.evaluations, out.residual_rms, False)

    monkeypatch.setattr(ci, "identify_traditional", diverged)
    part = mcarlo.monte_carlo(STUDY, DC, {"thesis": TRAD["thesis"]}, 1e-4, 2, 5)
    assert np.isnan(part["thesis"]["pos_rms"][1]) and np.isnan(part["thesis"]["pos_sq"][1]).all()
    np.testing.assert_array_equal(part["dc"]["pos_rms"], full["dc"]["pos_rms"])
    got = cs.compare(part, "thesis")
    assert got["trials_used"] == 1 and np.isfinite(got["pos_rms_trad"])
    assert got["pos_rms_trad"] == full["thesis"]["pos_rms"][0]


def test_no_converged_trial_is_an_error_not_a_statistic(monkeypatch) -> None:
    _failing(monkeypatch, "identify_traditional", set(range(1, 10)))
    part = mcarlo.monte_carlo(STUDY, DC, {"thesis": TRAD["thesis"]}, 1e-4, 2, 5)
    with pytest.raises(RuntimeError, match="no Monte Carlo trial converged"):
        cs.compare(part, "thesis")


def test_each_pose_set_draws_its_own_noise_whatever_runs_beside_it() -> None:
    both = mcarlo.monte_carlo(STUDY, DC, TRAD, 1e-4, 3, 11)
    alone = mcarlo.monte_carlo(STUDY, DC, {"thesis": TRAD["thesis"]}, 1e-4, 3, 11)
    for key in ("dc", "thesis"):
        np.testing.assert_array_equal(both[key]["phi"], alone[key]["phi"])
        np.testing.assert_array_equal(both[key]["pos_rms"], alone[key]["pos_rms"])
    # another seed, other draws
    other = mcarlo.monte_carlo(STUDY, DC, {"thesis": TRAD["thesis"]}, 1e-4, 3, 12)
    assert not np.array_equal(other["dc"]["phi"], alone["dc"]["phi"])
    with pytest.raises(ValueError, match="must not start with 'dc'"):
        mcarlo.monte_carlo(STUDY, DC, {"dc_like": TRAD["thesis"]}, 1e-4, 1, 1)


def test_the_three_budgets_follow_table_8s_accounting_on_the_5r() -> None:
    n = pub.SEC37_POSTURES_PER_LEG
    shared = st.budgets(MECH, n, st.ALL_BUDGETS)
    assert shared == {"thesis": 2 * n, "equations": n, "matched": 27}
    counts = {b: st.measurement_breakdown(MECH, n, k) for b, k in shared.items()}
    # Table 8 prints 18·2(2+1) = 108 for D&C and 2·18·2 = 72 for 18 shared postures
    assert counts["equations"]["dc"]["total"] == pub.TABLE8_MEASUREMENTS_DC
    assert counts["equations"]["trad"]["total"] == pub.TABLE8_MEASUREMENTS_TRADITIONAL
    assert counts["thesis"]["trad"] == {
        "poses": 36,
        "coordinates": 72,
        "readings": 72,
        "total": 144,
    }
    assert counts["matched"]["trad"]["total"] == counts["matched"]["dc"]["total"] == 108
    # item 10's ratio measures as many end-effector coordinates as D&C
    assert counts["thesis"]["trad"]["coordinates"] == counts["thesis"]["dc"]["coordinates"]
    with pytest.raises(ValueError, match="budgets must be among"):
        st.budgets(MECH, n, ["table8"])


@pytest.mark.parametrize(("n_per_leg", "n_shared"), [(6, 6), (9, 18), (25, 7)])
def test_measurement_counts_follow_the_per_pose_costs(n_per_leg: int, n_shared: int) -> None:
    # D&C: 2 n poses, each one planar point and one reading; traditional: both readings
    assert st.measurement_breakdown(MECH, n_per_leg, n_shared) == {
        "dc": {
            "poses": 2 * n_per_leg,
            "coordinates": 4 * n_per_leg,
            "readings": 2 * n_per_leg,
            "total": 6 * n_per_leg,
        },
        "trad": {
            "poses": n_shared,
            "coordinates": 2 * n_shared,
            "readings": 2 * n_shared,
            "total": 4 * n_shared,
        },
    }
    assert st.measurement_counts(MECH, n_per_leg, n_shared) == {
        "dc": 6 * n_per_leg,
        "trad": 4 * n_shared,
    }


def test_the_full_sweep_runs_every_cell_and_the_cross_its_two_lines() -> None:
    full = mcarlo.sweep(STUDY, [1e-5, 1e-4], [8, 9], 2, 3, budgets=["thesis"], full=True)
    assert [(r["n_per_leg"], r["sigma"], r["n_shared"]) for r in full] == [
        (8, 1e-5, 16),
        (8, 1e-4, 16),
        (9, 1e-5, 18),
        (9, 1e-4, 18),
    ]
    direct = mcarlo.monte_carlo(STUDY, DC, {"thesis": TRAD["thesis"]}, 1e-4, 2, 3)
    assert full[1] == {"sigma": 1e-4, "n_per_leg": 8, "budget": "thesis", "n_shared": 16} | (
        cs.compare(direct, "thesis")
    )
    cross = mcarlo.sweep(STUDY, [1e-5, 1e-4], [8, 9], 2, 3)
    cells = [(r["n_per_leg"], r["sigma"], r["budget"]) for r in cross]
    assert cells == [
        (8, 1e-5, "thesis"),
        (8, 1e-5, "matched"),
        (8, 1e-4, "thesis"),
        (8, 1e-4, "matched"),
        (9, 1e-5, "thesis"),
        (9, 1e-5, "matched"),
    ]


def test_mean_ci_of_two_values_at_level_half_is_their_range() -> None:
    # one degree of freedom: Student's t is the Cauchy law, t(p) = tan(π (p − ½)); at the 50 %
    # level t(0.75) = tan(π/4) = 1, and s/√n = (|b − a|/√2)/√2 = |b − a|/2: the CI is [a, b]
    assert cs.mean_ci(np.array([0.0, 2.0]), level=0.5) == pytest.approx((1.0, 0.0, 2.0))


def test_mean_ci_of_three_values_uses_the_two_dof_t_quantile_in_closed_form() -> None:
    # two degrees of freedom: F(t) = ½ + t / (2 √(t² + 2)), so t(p) = α √(2 / (1 − α²)), α = 2p − 1
    level = 0.95
    alpha = 2 * (0.5 + level / 2) - 1
    t = alpha * np.sqrt(2 / (1 - alpha**2))
    half = t * 1.0 / np.sqrt(3)  # sample standard deviation of 1, 2, 3 is 1
    mean, lo, hi = cs.mean_ci(np.array([3.0, 1.0, 2.0]), level=level)
    assert (mean, lo, hi) == pytest.approx((2.0, 2.0 - half, 2.0 + half), rel=1e-12)
    assert t == pytest.approx(4.303, abs=5e-4)  # t(0.975, 2) as printed in t tables


def test_mean_ci_of_one_or_constant_values_has_no_width() -> None:
    assert cs.mean_ci(np.array([4.0])) == (4.0, 4.0, 4.0)
    assert cs.mean_ci(np.full(5, -1.5)) == (-1.5, -1.5, -1.5)


def test_the_claim_rule_needs_a_majority_and_significance() -> None:
    assert cs.claim_holds({"share_a_better": 0.51, "p_value": 0.049})
    assert not cs.claim_holds({"share_a_better": cs.CLAIM_MIN_SHARE, "p_value": 1e-9})
    assert not cs.claim_holds({"share_a_better": 0.9, "p_value": cs.CLAIM_MAX_P})


def test_parameter_rms_over_all_and_per_parameter_by_hand() -> None:
    errors = np.array([[3.0, 0.0], [0.0, 4.0]])
    assert cs.parameter_rms(errors) == 2.5  # sqrt((9 + 16) / 4)
    np.testing.assert_allclose(cs.parameter_rms(errors, per_parameter=True), [4.5**0.5, 8**0.5])
    with pytest.raises(ValueError, match=r"errors must be \(trials, parameters\)"):
        cs.parameter_rms(np.ones(3))


def test_summary_rows_in_micrometres_over_the_paired_trials() -> None:
    from scipy import stats

    def strategy(rms, param, times, ok):
        return {"pos_rms": np.array(rms), "param": np.array(param), "time": np.array(times),
                "converged": np.array(ok)}  # fmt: skip

    mc = {
        "dc": strategy([1e-6, 3e-6, 9.0], [[3.0, 0.0], [0.0, 4.0], [9.0, 9.0]],
                       [1e-3, 3e-3, 5.0], [True, True, True]),
        "t": strategy([2e-6, 2e-6, 9.0], np.zeros((3, 2)), [1e-3, 1e-3, 5.0],
                      [True, True, False]),
    }  # fmt: skip
    rows = cs.summary(mc, "t")  # the third trial failed: left out of both strategies
    half = stats.t.ppf(0.975, 1) * np.sqrt(2) / np.sqrt(2)  # t · s / √n, s = √2 µm
    dc = rows["dc"]
    assert dc["workspace RMS mean [µm]"] == pytest.approx(2.0)
    assert dc["95 % CI low [µm]"] == pytest.approx(2.0 - half)
    assert dc["95 % CI high [µm]"] == pytest.approx(2.0 + half)
    assert dc["workspace RMS median [µm]"] == pytest.approx(2.0)
    assert dc["param. RMS [σ_dist]"] == 2.5 and dc["solve time median [ms]"] == pytest.approx(2.0)
    assert rows["t"]["95 % CI low [µm]"] == pytest.approx(2.0)  # no spread, no interval


def test_two_indices_are_compared_on_both_metrics_over_their_common_trials() -> None:
    rng = np.random.default_rng(5)
    base = rng.uniform(1.0, 2.0, 40)
    a = {"param_rms_each": base * 1.1, "pos_rms_each": base * 0.9}  # worse params, better poses
    b = {"param_rms_each": base.copy(), "pos_rms_each": base.copy()}
    a["pos_rms_each"][3] = np.nan  # a fit that did not converge: left out of that pairing
    share_p, p_p, share_x, p_x = mcarlo.index_pair(a, b)
    assert share_p == 0.0 and share_x == 1.0 and p_p < 1e-6 and p_x < 1e-6
    with pytest.raises(ValueError, match="trials"):
        mcarlo.index_pair(a, {"param_rms_each": base[:5], "pos_rms_each": base[:5]})
