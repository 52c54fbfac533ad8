"""Main effects and Lenth's method on hand-checkable examples."""

import numpy as np
import pytest

from mechlib import screening


def t975_df2() -> float:
    """Closed form of Student's t quantile for 2 degrees of freedom: (2p-1)/sqrt(2p(1-p))."""
    p = 0.975
    return (2 * p - 1) / np.sqrt(2 * p * (1 - p))


def test_lenth_by_hand_six_effects() -> None:
    # |c| sorted: 0.5 1 1 2 3 8 -> median 1.5, s0 2.25, cut 5.625 drops 8,
    # trimmed median of 0.5 1 1 2 3 is 1 -> PSE 1.5; d = 2.
    res = screening.lenth([8.0, -1.0, 2.0, 0.5, 1.0, -3.0])
    assert res.median_abs == 1.5 and res.s0 == 2.25 and res.pse == 1.5 and res.d == 2.0
    assert res.me == pytest.approx(t975_df2() * 1.5, rel=1e-10)
    gamma = (1 + 0.95 ** (1 / 6)) / 2
    t_gamma = (2 * gamma - 1) / np.sqrt(2 * gamma * (1 - gamma))
    assert res.sme == pytest.approx(t_gamma * 1.5, rel=1e-10)
    assert res.active(np.array([8.0, -1.0])).tolist() == [True, False]


def test_margins_from_scale_known_answers() -> None:
    # m = 6: d = 2, where Student's t has a closed form
    gamma = (1 + 0.95 ** (1 / 6)) / 2
    t_gamma = (2 * gamma - 1) / np.sqrt(2 * gamma * (1 - gamma))
    me, sme = screening.margins_from_scale(1.5, 6)
    assert me == pytest.approx(t975_df2() * 1.5, rel=1e-10)
    assert sme == pytest.approx(t_gamma * 1.5, rel=1e-10)
    # Lenth (1989), m = 15 effects (d = 5): t(0.975; 5) = 2.571 and t(γ; 5) = 5.219
    me, sme = screening.margins_from_scale(1.0, 15)
    assert me == pytest.approx(2.5706, abs=1e-4) and sme == pytest.approx(5.2187, abs=1e-4)
    # one formula: lenth's margins are margins_from_scale at its own PSE
    res = screening.lenth([8.0, -1.0, 2.0, 0.5, 1.0, -3.0, 0.7], alpha=0.1)
    assert screening.margins_from_scale(res.pse, res.m, 0.1) == (res.me, res.sme)


def test_margins_from_scale_refuses_bad_input_by_name() -> None:
    with pytest.raises(ValueError, match=r"scale must be >= 0"):
        screening.margins_from_scale(-1.0, 6)
    with pytest.raises(ValueError, match=r"m must be >= 3"):
        screening.margins_from_scale(1.0, 2)


def test_main_effects_of_a_known_linear_response() -> None:
    x = np.array([[-1, -1], [1, -1], [-1, 1], [1, 1]], dtype=float)
    y = 5 + 3 * x[:, 0] - 2 * x[:, 1]
    assert screening.main_effects(x, y).tolist() == [6.0, -4.0]


def test_half_normal_and_pareto_ordering() -> None:
    order, mag, q = screening.half_normal_points([3.0, -1.0, 2.0])
    assert order.tolist() == [1, 2, 0] and mag.tolist() == [1.0, 2.0, 3.0]
    assert np.all(np.diff(q) > 0) and q[0] > 0
    assert screening.pareto_order([3.0, -1.0, 2.0]).tolist() == [0, 2, 1]


def test_dominant_effects() -> None:
    assert screening.dominant([100.0, 0.5, -2.0], 0.01).tolist() == [True, False, True]


def test_bad_input_gets_clear_errors() -> None:
    with pytest.raises(ValueError, match=r"number of effects must be >= 3"):
        screening.lenth([1.0, 2.0])
    with pytest.raises(ValueError, match=r"alpha must be in \(0.0, 0.5\]"):
        screening.lenth([1.0, 2.0, 3.0], alpha=0.7)
    with pytest.raises(ValueError, match="two-level"):
        screening.main_effects(np.array([[0.5, 1], [-1, -1]]), [1.0, 2.0])
    with pytest.raises(ValueError, match="not balanced"):
        screening.main_effects(np.array([[1.0], [1.0], [-1.0]]), [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match=r"responses must have shape \(3, any\)"):
        screening.main_effects(np.array([[1.0], [-1.0], [1.0]]), [1.0, 2.0])


def test_per_column_analyses_equal_the_single_column_ones() -> None:
    effects = np.array([[100.0, 0.0], [0.5, 0.5], [-2.0, -0.3], [0.1, 0.002]])
    lenths = screening.lenth_columns(effects, alpha=0.05)
    assert lenths == [screening.lenth(effects[:, j], alpha=0.05) for j in range(2)]
    summary = screening.lenth_summary(lenths, ("median_abs", "me"))
    assert summary.shape == (2, 2)
    np.testing.assert_allclose(summary[0], [1.25, 0.151])  # medians by hand
    assert screening.dominant_columns(effects, 0.01).tolist() == [
        [True, False],
        [False, True],
        [True, True],
        [False, False],
    ]  # column 1 judged against its own largest effect (0.5): all below 1 % of 100
    active = screening.active_columns(effects, lenths)
    assert active[:, 1].tolist() == lenths[1].active(effects[:, 1]).tolist()
    sets = screening.factor_sets(screening.dominant_columns(effects), ["A", "B", "C", "D"])
    assert sets == [frozenset({"A", "C"}), frozenset({"B", "C"})]
    with pytest.raises(ValueError, match="not Lenth results"):
        screening.lenth_summary(lenths, ("median",))
    with pytest.raises(ValueError, match=r"mask must be \(3, outputs\)"):
        screening.factor_sets(np.ones((4, 2)), ["A", "B", "C"])
