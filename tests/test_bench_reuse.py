"""The reuse benchmark's design statistic: nearest-neighbour distances of seeded uniform designs."""

import numpy as np
import pytest

from mechlib.bench.reuse import nearest_neighbour_distances


def test_nearest_neighbour_distances_match_brute_force():
    d = nearest_neighbour_distances(50, seed=3)
    design = np.random.default_rng(3).uniform(-1.0, 1.0, (50, 6))
    pair = np.linalg.norm(design[:, None] - design[None], axis=-1)
    np.fill_diagonal(pair, np.inf)
    np.testing.assert_allclose(d, pair.min(axis=1), rtol=1e-12)


def test_nearest_neighbour_distances_shrink_with_design_size():
    # a denser design has closer neighbours; in six dimensions they shrink only as n^(-1/6)
    small, large = (np.median(nearest_neighbour_distances(n)) for n in (200, 10_000))
    assert large < small
    assert large > small * (200 / 10_000) ** (1 / 6) * 0.8


def test_a_design_of_one_run_is_refused_by_name():
    # one run has no other run to be near: inf, not a distance
    with pytest.raises(ValueError, match="n_runs must be >= 2, got 1"):
        nearest_neighbour_distances(1)
