"""Designs: Plackett–Burman via pyDOE3, mapping, discrepancy, random balanced designs."""

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


def test_discrepancy_orders_designs_sensibly() -> None:
    spread = np.array([[-1.0, -1.0], [1.0, 1.0], [-1.0, 1.0], [1.0, -1.0]]) * 0.5
    clumped = np.array([[0.9, 0.9], [1.0, 1.0], [0.95, 0.9], [1.0, 0.95]])
    assert doe.centered_l2_discrepancy(spread) < doe.centered_l2_discrepancy(clumped)


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
