"""Known answers for the calibration study's summaries: mean_ci and measurement_counts."""

import numpy as np
import pytest

from mechlib.fivebar import study


def test_mean_ci_of_two_values_at_level_half_is_their_range() -> None:
    # one degree of freedom: Student's t is the Cauchy law, t(p) = tan(π (p − ½)); at the 50 %
    # level t(0.75) = tan(π/4) = 1, and s/√n = (|b − a|/√2)/√2 = |b − a|/2: the CI is [a, b]
    assert study.mean_ci(np.array([0.0, 2.0]), level=0.5) == pytest.approx((1.0, 0.0, 2.0))


def test_mean_ci_of_three_values_uses_the_two_dof_t_quantile_in_closed_form() -> None:
    # two degrees of freedom: F(t) = ½ + t / (2 √(t² + 2)), so t(p) = α √(2 / (1 − α²)), α = 2p − 1
    level = 0.95
    alpha = 2 * (0.5 + level / 2) - 1
    t = alpha * np.sqrt(2 / (1 - alpha**2))
    half = t * 1.0 / np.sqrt(3)  # sample standard deviation of 1, 2, 3 is 1
    mean, lo, hi = study.mean_ci(np.array([3.0, 1.0, 2.0]), level=level)
    assert (mean, lo, hi) == pytest.approx((2.0, 2.0 - half, 2.0 + half), rel=1e-12)
    assert t == pytest.approx(4.303, abs=5e-4)  # t(0.975, 2) as printed in t tables


def test_mean_ci_of_one_or_constant_values_has_no_width() -> None:
    assert study.mean_ci(np.array([4.0])) == (4.0, 4.0, 4.0)
    assert study.mean_ci(np.full(5, -1.5)) == (-1.5, -1.5, -1.5)


@pytest.mark.parametrize(("n_per_leg", "n_shared"), [(6, 6), (9, 18), (18, 36), (25, 7)])
def test_measurement_counts_follow_the_per_posture_costs(n_per_leg: int, n_shared: int) -> None:
    counts = study.measurement_counts(n_per_leg, n_shared)
    # divide and conquer: 2 n postures, each one planar point (2 coordinates) and one reading
    assert counts["dc"] == {
        "postures": 2 * n_per_leg,
        "ee_points": 2 * n_per_leg,
        "ee_coordinates": 4 * n_per_leg,
        "joint_readings": 2 * n_per_leg,
        "total": 6 * n_per_leg,
    }
    # traditional: m shared postures, each one planar point and both joint readings
    assert counts["trad"] == {
        "postures": n_shared,
        "ee_points": n_shared,
        "ee_coordinates": 2 * n_shared,
        "joint_readings": 2 * n_shared,
        "total": 4 * n_shared,
    }


def test_the_thesis_posture_ratio_measures_as_many_points() -> None:
    # (Table 8's printed totals are tested in tests/test_fivebar.py.) The thesis's ratio
    # n_shared = 2 n_per_leg measures the same number of end-effector points
    c = study.measurement_counts(18, 36)
    assert c["dc"]["ee_coordinates"] == c["trad"]["ee_coordinates"]
