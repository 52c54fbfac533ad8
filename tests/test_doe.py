"""Designs: Plackett–Burman via pyDOE3, mapping, CD² (known answers), random balanced designs."""

import numpy as np
import pytest

from mechlib import doe
from mechlib import published as pub


def test_pydoe3_sizes_designs_by_the_next_multiple_of_four() -> None:
    import pyDOE3

    assert pyDOE3.pbdesign(6).shape == (8, 6)
    assert doe.plackett_burman(12).shape == (12, 11)


def test_plackett_burman_12_is_orthogonal_and_balanced() -> None:
    x = doe.plackett_burman(12)
    assert np.array_equal(x.T @ x, 12 * np.eye(11))
    assert np.all(x.sum(axis=0) == 0)


def test_table2_is_a_signed_column_subset_of_pb12() -> None:
    full = doe.plackett_burman(12)
    m = doe.match_columns(full, pub.TABLE2_DESIGN)
    mapped = full[m["rows"]][:, m["columns"]] * m["signs"]
    assert np.array_equal(mapped, pub.TABLE2_DESIGN)
    assert sorted(m["rows"].tolist()) == list(range(12))


def test_match_columns_rejects_a_non_pb_matrix() -> None:
    bad = pub.TABLE2_DESIGN.copy()
    bad[0, 0] *= -1  # one flipped sign breaks balance and the mapping
    with pytest.raises(ValueError, match="not a signed column subset"):
        doe.match_columns(doe.plackett_burman(12), bad)


CD2_ATOL = 1e-13
"""CD² is (13/12)^s − 2A + B with A, B of order one: round-off is absolute, ~1e-15 per term."""


def cramer_von_mises_integral(x: np.ndarray) -> float:
    """∫₀¹ (F_n(t) − t)² dt of the empirical distribution F_n of ``x`` (closed form).

    With the points sorted, x_(1) ≤ … ≤ x_(n), it equals 1/(12 n²) + (1/n) Σ (x_(i) − (2i−1)/(2n))²
    (the Cramér–von Mises statistic divided by n).
    """
    xs = np.sort(x)
    n = xs.size
    mid = (2 * np.arange(1, n + 1) - 1) / (2 * n)
    return 1 / (12 * n**2) + float(np.sum((xs - mid) ** 2)) / n


@pytest.mark.parametrize("d", [1, 2, 3, 6])
def test_cd2_of_a_point_at_the_centre_is_13_over_12_to_the_d_minus_1(d: int) -> None:
    # At x = ½ every |x − ½| vanishes, so Hickernell's three sums give (13/12)^d − 2 + 1.
    centre = np.zeros((2, d))  # one level per column: mapped to ½; two runs, one point
    assert doe.centered_l2_discrepancy_squared(centre) == pytest.approx(
        (13 / 12) ** d - 1, rel=0, abs=CD2_ATOL
    )


@pytest.mark.parametrize("q", [2, 3, 6, 11])
@pytest.mark.parametrize("replicates", [1, 5])
def test_cd2_of_one_factor_with_q_equally_spaced_levels_is_1_over_12_q2(
    q: int, replicates: int
) -> None:
    # In one dimension CD² = ∫₀¹ (F_n(t) − t)² dt (the box from t to its nearest corner); for
    # points at (k − ½)/q, each repeated r times, F_n − t is a saw-tooth of slope −1 and height
    # 1/q centred on 0 in every cell, whose mean square is (1/q)² / 12.
    design = np.repeat(np.linspace(-1, 1, q), replicates)[:, None]
    assert doe.centered_l2_discrepancy_squared(design) == pytest.approx(
        1 / (12 * q**2), rel=0, abs=CD2_ATOL
    )


def test_cd2_of_one_factor_with_unused_levels_is_the_cramer_von_mises_integral() -> None:
    # levels 1, 1, 2, 6 of q = 6: the closed form of the 1-D integral, not the equispaced 1/(12 q²)
    design = np.array([[-1.0], [-1.0], [-0.6], [1.0]])
    points = doe.uniform_design_points(design, n_levels=6)
    np.testing.assert_allclose(points.ravel(), np.array([1, 1, 3, 11]) / 12)
    assert doe.centered_l2_discrepancy_squared(design, n_levels=6) == pytest.approx(
        cramer_von_mises_integral(points.ravel()), rel=0, abs=CD2_ATOL
    )


def test_table4_levels_go_to_the_centres_of_six_cells() -> None:
    points = doe.uniform_design_points(pub.TABLE4_DESIGN)
    k = np.rint((pub.TABLE4_DESIGN + 1) / 0.4) + 1  # level number 1..6 of each entry
    np.testing.assert_allclose(points, (k - 0.5) / 6, rtol=0, atol=1e-15)
    assert points.min() == pytest.approx(1 / 12) and points.max() == pytest.approx(11 / 12)


def test_table4_cd2_equals_the_published_u30_6_6_value() -> None:
    ours = doe.centered_l2_discrepancy_squared(pub.TABLE4_DESIGN)
    # printed to 16 decimals; UniDOE's and SciPy's sums differ only by round-off (~2e-16)
    assert ours == pytest.approx(pub.UD_U30_6_6_CD2, rel=0, abs=CD2_ATOL)
    assert ours > pub.UNIDOE_U30_6_6_CD2  # a better design of the same size is known


def test_cd2_is_invariant_to_run_order_and_level_reversal() -> None:
    base = doe.centered_l2_discrepancy_squared(pub.TABLE4_DESIGN)
    shuffled = pub.TABLE4_DESIGN[::-1] * np.array([1, -1, 1, -1, -1, 1])
    assert doe.centered_l2_discrepancy_squared(shuffled) == pytest.approx(base, rel=0, abs=CD2_ATOL)


def test_cd2_prefers_a_spread_latin_square_to_its_diagonal() -> None:
    spread = np.array([[1, 3], [2, 1], [3, 4], [4, 2]], dtype=float)
    diagonal = np.array([[1, 1], [2, 2], [3, 3], [4, 4]], dtype=float)
    to_coded = lambda levels: -1 + 2 * (levels - 1) / 3  # noqa: E731
    assert doe.centered_l2_discrepancy_squared(
        to_coded(spread)
    ) < doe.centered_l2_discrepancy_squared(to_coded(diagonal))


@pytest.mark.parametrize(
    ("design", "n_levels", "message"),
    [
        (np.array([[-1.0], [0.9], [1.0]]), None, "column 0 has level 0.9"),
        (np.array([[-1.0], [0.5], [1.0]]), 6, "not one of 6 equally spaced"),
        (np.array([[-1.0], [1.0]]), 0, r"n_levels must be in \[1, 1000\]"),
    ],
)
def test_off_grid_levels_are_refused(
    design: np.ndarray, n_levels: int | None, message: str
) -> None:
    with pytest.raises(ValueError, match=message):
        doe.uniform_design_points(design, n_levels)


def test_random_balanced_designs_keep_level_counts_and_are_seeded() -> None:
    a = doe.random_balanced_designs(pub.TABLE4_DESIGN, 3, seed=7)
    b = doe.random_balanced_designs(pub.TABLE4_DESIGN, 3, seed=7)
    assert np.array_equal(a, b)
    for d in a:
        for col, ref in zip(d.T, pub.TABLE4_DESIGN.T, strict=True):
            assert np.array_equal(np.sort(col), np.sort(ref))


@pytest.mark.parametrize(
    ("design", "message"),
    [
        (np.ones(6), "2-D array"),
        (np.full((4, 6), 1.5), r"levels must lie in \[-1.0, 1.0\]"),
        (np.full((1, 6), 0.5), "at least 2 runs"),
        (np.array([[0.0, np.nan], [1.0, 1.0]]), "finite"),
    ],
)
def test_bad_designs_get_clear_errors(design: np.ndarray, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        doe.check_design(design)


def test_wrong_factor_count_and_bad_run_counts() -> None:
    with pytest.raises(ValueError, match=r"shape \(any, 6\)"):
        doe.check_design(np.zeros((4, 5)), n_factors=6)
    with pytest.raises(ValueError, match="multiple of 4"):
        doe.plackett_burman(10)
    with pytest.raises(ValueError, match=r"n_designs must be in \[1, 100000\]"):
        doe.random_balanced_designs(pub.TABLE4_DESIGN, 0, seed=1)


def test_balance_means_every_level_equally_often_in_every_column() -> None:
    assert doe.is_balanced(pub.TABLE4_DESIGN) and doe.is_balanced(pub.TABLE2_DESIGN)
    assert doe.is_balanced(np.array([[-1.0, 1.0], [1.0, -1.0], [0.0, 0.0]]))
    repeated = pub.TABLE4_DESIGN.copy()
    repeated[0, 2] = repeated[1, 2]  # one level six times, another four times, in one column
    assert not doe.is_balanced(repeated)
    missing = np.array([[-1.0, -1.0], [0.0, 1.0], [1.0, -1.0], [-1.0, 1.0]])
    assert not doe.is_balanced(missing)  # column 1 never takes the level 0


def test_random_design_is_the_chapters_draw_and_its_prefix_is_the_smaller_design() -> None:
    # the DOE chapter's validation draw and the family page's runs are this one stream: NumPy's
    # PCG64 uniform in [-1, 1] N, run by run (a change here changes every cached validation run)
    d = doe.random_design(1000, 6, 2010)
    np.testing.assert_array_equal(d, np.random.default_rng(2010).uniform(-1.0, 1.0, (1000, 6)))
    assert d.shape == (1000, 6) and np.abs(d).max() <= doe.LEVEL_LIMIT
    np.testing.assert_array_equal(doe.random_design(4, 6, 2010), d[:4])
    assert not np.array_equal(doe.random_design(4, 6, 2011), d[:4])
    with pytest.raises(ValueError, match=r"n_runs must be in \[1, 100000\], got 0"):
        doe.random_design(0, 6, 2010)
    with pytest.raises(ValueError, match="seed must be >= 0, got -1"):
        doe.random_design(10, 6, -1)


def test_a_plackett_burman_design_aliases_interactions_into_main_effects() -> None:
    """PB-12 carries a third of every two-factor interaction in each other main effect; a full
    factorial and a resolution IV fraction carry none."""
    assert doe.interaction_aliasing(doe.plackett_burman(12)) == pytest.approx(1 / 3)
    assert doe.interaction_aliasing(pub.TABLE2_DESIGN) == pytest.approx(1 / 3)
    full = np.array([[a, b, c] for a in (-1, 1) for b in (-1, 1) for c in (-1, 1)], dtype=float)
    assert doe.interaction_aliasing(full) == pytest.approx(0.0, abs=1e-15)
    resolution_iv = np.c_[full, full.prod(axis=1)]  # D = ABC
    assert doe.interaction_aliasing(resolution_iv) == pytest.approx(0.0, abs=1e-15)
    resolution_iii = np.c_[full[:, :2], full[:, 0] * full[:, 1]]  # C = AB
    assert doe.interaction_aliasing(resolution_iii) == pytest.approx(1.0)
    with pytest.raises(ValueError, match="at least 3 factors"):
        doe.interaction_aliasing(full[:, :2])
