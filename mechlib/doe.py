"""Designs of experiments: Plackett–Burman, uniform-design quality (CD²), random balanced designs,
the random validation design.

Designs are ``(runs, factors)`` arrays in coded units, every level in ``[-1, 1]``
(Table 1 of the thesis: ±1 N maps to ±1).
"""

from __future__ import annotations

import itertools

import numpy as np
import pyDOE3
from scipy.stats import qmc

from mechlib.params import check_int, check_matrix

LEVEL_LIMIT = 1.0
"""Coded levels must lie in [-LEVEL_LIMIT, LEVEL_LIMIT] (Table 1: ±1 N)."""

LEVEL_DECIMALS = 12
"""Decimals to which two coded levels must agree to count as one level."""

LEVEL_TOL = 1e-9
"""Largest distance of a coded entry from its level on the equally spaced grid."""

MAX_LEVELS = 1000
"""Most levels a factor may have in :func:`uniform_design_points`."""

MAX_RANDOM_RUNS = 100_000
"""Most runs of a :func:`random_design` (the DOE chapter's bound on its validation runs)."""


def check_design(
    design: object, *, n_factors: int | None = None, two_level: bool = False
) -> np.ndarray:
    """Validate a coded design matrix and return it as a float array.

    Parameters
    ----------
    design : array_like, shape (runs, factors)
        Coded factor levels.
    n_factors : int, optional
        Required number of columns.
    two_level : bool
        If true every entry must be exactly -1 or +1.

    Raises
    ------
    ValueError
        Wrong shape, non-finite entries, levels outside [-1, 1] or not two-level.
    """
    arr = check_matrix("design", design, shape=(None, n_factors))
    if arr.shape[0] < 2:
        raise ValueError(f"design must have at least 2 runs, got {arr.shape[0]}")
    if np.any(np.abs(arr) > LEVEL_LIMIT):
        worst = float(arr.flat[np.argmax(np.abs(arr))])
        raise ValueError(
            f"design levels must lie in [-{LEVEL_LIMIT}, {LEVEL_LIMIT}] (coded units), got {worst}"
        )
    if two_level and not np.all(np.isin(arr, (-1.0, 1.0))):
        raise ValueError("design must be two-level: every entry -1 or +1")
    return arr


def plackett_burman(n_runs: int) -> np.ndarray:
    """Full Plackett–Burman matrix with ``n_runs - 1`` columns, from pyDOE3.

    ``pyDOE3.pbdesign(k)`` sizes the design for ``k`` factors as the next multiple of four
    *above* ``k`` (so ``pbdesign(6)`` has 8 runs); asking for ``n_runs - 1`` factors gives the
    saturated design with exactly ``n_runs`` runs.

    Parameters
    ----------
    n_runs : int
        Number of runs, a multiple of 4 from 4 to 48.

    Returns
    -------
    numpy.ndarray, shape (n_runs, n_runs - 1)

    Examples
    --------
    A 12-run design has 11 balanced columns, orthogonal to each other (``XᵀX / 12 = I``):

    >>> x = plackett_burman(12)
    >>> x.shape, bool(np.allclose(orthogonality(x), np.eye(11))), is_balanced(x)
    ((12, 11), True, True)
    >>> plackett_burman(10)
    Traceback (most recent call last):
    ...
    ValueError: n_runs must be a multiple of 4, got 10
    """
    n_runs = check_int("n_runs", n_runs, low=4, high=48)
    if n_runs % 4:
        raise ValueError(f"n_runs must be a multiple of 4, got {n_runs}")
    design = np.asarray(pyDOE3.pbdesign(n_runs - 1), dtype=float)
    if design.shape != (n_runs, n_runs - 1):  # pragma: no cover - guards a pyDOE3 change
        raise RuntimeError(f"pyDOE3.pbdesign gave shape {design.shape} for {n_runs} runs")
    return design


def orthogonality(design: object) -> np.ndarray:
    """Return ``XᵀX / runs`` for a two-level design (identity when columns are orthogonal)."""
    arr = check_design(design)
    return arr.T @ arr / arr.shape[0]


def interaction_aliasing(design: object) -> float:
    """The largest |correlation| between a two-factor interaction column ``x_i x_j`` and a
    main-effect column ``x_k`` (k ≠ i, j) over the design's runs.

    0 means the design estimates every main effect clear of every two-factor interaction (a
    resolution IV design or better); a 12-run Plackett–Burman design gives 1/3: each of its
    main effects carries a third of every interaction of two other factors, so it cannot show
    that interactions are negligible.

    Parameters
    ----------
    design : array_like, shape (runs, factors)
        A two-level design, levels ±1 (at least three factors).

    Raises
    ------
    ValueError
        For fewer than three factors, or a constant column.

    Examples
    --------
    >>> round(interaction_aliasing(plackett_burman(12)), 6)  # a third of each interaction
    0.333333
    >>> round(interaction_aliasing(plackett_burman(8)), 6)  # 2^(7-4): main effects = interactions
    1.0
    """
    arr = check_design(design, two_level=True)
    k = arr.shape[1]
    if k < 3:
        raise ValueError(f"interaction aliasing needs at least 3 factors, got {k}")
    centred = arr - arr.mean(axis=0)
    norms = np.linalg.norm(centred, axis=0)
    if np.any(norms == 0):
        raise ValueError("every column of the design must vary")
    worst = 0.0
    for i in range(k):
        for j in range(i + 1, k):
            product = arr[:, i] * arr[:, j]
            product = product - product.mean()
            size = np.linalg.norm(product)
            if size == 0:  # a product that is constant is aliased with the mean only
                continue
            others = [m for m in range(k) if m not in (i, j)]
            corr = np.abs(product @ centred[:, others]) / (size * norms[others])
            worst = max(worst, float(corr.max()))
    return worst


def is_balanced(design: object) -> bool:
    """Whether every column takes each level of the design equally often (a U-type design).

    The levels are those found anywhere in the design (see :func:`level_counts`): a column that
    misses one of them, or repeats one more often than another, makes the design unbalanced.
    """
    counts = np.array(list(level_counts(design).values()))  # (levels, factors)
    return bool(np.all(counts == counts[0, 0]))


def match_columns(full: object, target: object) -> dict[str, np.ndarray]:
    """Find how ``target`` is obtained from ``full`` by row order, column choice and signs.

    Solves ``target = full[rows][:, columns] * signs`` by backtracking over the columns of
    ``target``, keeping only column choices under which the multiset of partial rows of both
    matrices still agrees.

    Parameters
    ----------
    full : array_like, shape (runs, k)
        Two-level design to choose from (e.g. :func:`plackett_burman`).
    target : array_like, shape (runs, m), m <= k
        Two-level design to explain (e.g. Table 2's design matrix).

    Returns
    -------
    dict
        ``columns`` (m,), ``signs`` (m,), ``rows`` (runs,) with
        ``target[i] == full[rows[i], columns] * signs``.

    Raises
    ------
    ValueError
        If the shapes do not fit or no such mapping exists.
    """
    a = check_design(full, two_level=True)
    b = check_design(target, two_level=True)
    if a.shape[0] != b.shape[0] or b.shape[1] > a.shape[1]:
        raise ValueError(f"cannot map a {b.shape} design into a {a.shape} design")

    def rows_agree(cols: list[int], signs: list[float]) -> bool:
        left = sorted(map(tuple, a[:, cols] * signs))
        right = sorted(map(tuple, b[:, : len(cols)]))
        return left == right

    def search(cols: list[int], signs: list[float]) -> tuple[list[int], list[float]] | None:
        if len(cols) == b.shape[1]:
            return cols, signs
        for c, s in itertools.product(range(a.shape[1]), (1.0, -1.0)):
            if c not in cols and rows_agree([*cols, c], [*signs, s]):
                found = search([*cols, c], [*signs, s])
                if found:
                    return found
        return None

    found = search([], [])
    if found is None:
        raise ValueError("target is not a signed column subset of full up to row order")
    cols, signs = np.array(found[0]), np.array(found[1])
    mapped = a[:, cols] * signs
    unused = list(range(a.shape[0]))
    rows = []
    for row in b:
        i = next(j for j in unused if np.array_equal(mapped[j], row))
        unused.remove(i)
        rows.append(i)
    return {"columns": cols, "signs": signs, "rows": np.array(rows)}


def uniform_design_points(design: object, n_levels: int | None = None) -> np.ndarray:
    """Map coded levels to the unit cube as the uniform-design literature does.

    A column with ``q`` equally spaced coded levels from -1 to 1 has level ``k`` (``k = 1..q``,
    from the lowest) at ``(k - 1/2) / q``: the centre of the k-th of ``q`` equal cells of
    [0, 1], as in the uniform-design tables (Fang, Li and Sudjianto, *Design and Modeling for
    Computer Experiments*, 2006) and the UniDOE package. The ends -1 and +1 therefore go to
    ``1/(2q)`` and ``1 - 1/(2q)``, not onto the faces of the cube. A one-level column (every
    entry 0) goes to the centre, 1/2.

    Parameters
    ----------
    design : array_like, shape (runs, factors)
        Coded design, every entry on the grid of ``q`` equally spaced levels of its column.
    n_levels : int, optional
        ``q`` for every column, 1 to ``MAX_LEVELS``. By default each column's ``q`` is its number
        of distinct levels, which must then be exactly the equally spaced grid; give
        ``n_levels`` when a column does not use every level.

    Returns
    -------
    numpy.ndarray, shape (runs, factors)
        Points in (0, 1).

    Raises
    ------
    ValueError
        An entry is not one of the ``q`` equally spaced levels of its column.
    """
    arr = check_design(design)
    if n_levels is not None:
        n_levels = check_int("n_levels", n_levels, low=1, high=MAX_LEVELS)
    points = np.empty_like(arr)
    for j, col in enumerate(arr.T):
        q = n_levels or np.unique(np.round(col, LEVEL_DECIMALS)).size
        grid = np.linspace(-LEVEL_LIMIT, LEVEL_LIMIT, q) if q > 1 else np.zeros(1)
        k = np.abs(col[:, None] - grid[None, :]).argmin(axis=1)
        off = np.abs(col - grid[k])
        if off.max() > LEVEL_TOL:
            raise ValueError(
                f"design column {j} has level {col[off.argmax()]}, which is not one of {q} "
                "equally spaced levels from -1 to 1 (give n_levels if the column does not use "
                "every level)"
            )
        points[:, j] = (k + 0.5) / q
    return points


#: Table 4 counts as a uniform design when it is balanced and fewer than this share of random
#: balanced designs with its levels are at least as uniform (CD², :func:`random_balanced_designs`).
UNIFORM_SHARE_MAX = 0.01


def centered_l2_discrepancy_squared(design: object, n_levels: int | None = None) -> float:
    """Squared centred L2 discrepancy CD² (Hickernell 1998) of a coded design.

    The levels are first placed at ``(k - 1/2)/q`` (:func:`uniform_design_points`), the
    convention of the uniform-design tables, so the value can be compared with theirs; the
    discrepancy itself is ``scipy.stats.qmc.discrepancy(..., method="CD")``, which returns the
    square CD², not CD.

    Parameters
    ----------
    design : array_like, shape (runs, factors)
        Coded design (see :func:`uniform_design_points`).
    n_levels : int, optional
        Number of levels of every column; inferred per column by default.

    Returns
    -------
    float
        CD² (the square; take the root for CD). Smaller is more uniform.

    Raises
    ------
    ValueError
        As :func:`uniform_design_points`.

    Examples
    --------
    >>> square = [[-1.0, -1.0], [0.0, 1.0], [1.0, 0.0]]
    >>> diagonal = [[-1.0, -1.0], [0.0, 0.0], [1.0, 1.0]]  # less uniform than the Latin square
    >>> centered_l2_discrepancy_squared(square) < centered_l2_discrepancy_squared(diagonal)
    True
    """
    return float(qmc.discrepancy(uniform_design_points(design, n_levels), method="CD"))


def random_balanced_designs(design: object, n_designs: int, seed: int) -> np.ndarray:
    """Random designs with the same level counts per column as ``design``.

    Each column of each new design is an independent random permutation of the corresponding
    column of ``design``: the U-type (balanced) designs among which a uniform design is the
    most uniform one.

    Parameters
    ----------
    design : array_like, shape (runs, factors)
    n_designs : int
        How many designs, 1 to 100 000.
    seed : int
        Seed of ``numpy.random.default_rng``.

    Returns
    -------
    numpy.ndarray, shape (n_designs, runs, factors)

    Examples
    --------
    >>> designs = random_balanced_designs(plackett_burman(12), n_designs=5, seed=1)
    >>> designs.shape, all(is_balanced(d) for d in designs)
    ((5, 12, 11), True)
    """
    base = check_design(design)
    n_designs = check_int("n_designs", n_designs, low=1, high=100_000)
    rng = np.random.default_rng(check_int("seed", seed, low=0))
    idx = rng.random((n_designs, *base.shape)).argsort(axis=1)
    return np.take_along_axis(np.broadcast_to(base, idx.shape), idx, axis=1)


def level_counts(design: object) -> dict[float, np.ndarray]:
    """Number of runs at each level, per column: ``{level: counts (factors,)}``."""
    arr = check_design(design)
    levels = np.unique(np.round(arr, LEVEL_DECIMALS))
    return {float(v): np.sum(np.isclose(arr, v), axis=0) for v in levels}


def random_design(n_runs: int, n_factors: int, seed: int) -> np.ndarray:
    """The random validation design: every level drawn uniformly in
    ``[-LEVEL_LIMIT, LEVEL_LIMIT]`` (Table 5's random runs, at ±1 N).

    The draw fills the design run by run, so the first k runs of a design are the design of k
    runs with the same seed: a chapter that solves "the first k runs of the draw" needs only the
    seed.

    Parameters
    ----------
    n_runs : int
        Runs, 1 to :data:`MAX_RANDOM_RUNS`.
    n_factors : int
        Factors (columns), ≥ 1.
    seed : int
        Seed of ``numpy.random.default_rng``, ≥ 0.

    Returns
    -------
    numpy.ndarray, shape (n_runs, n_factors)
        Coded levels (= forces in N for the HexFlex's actuators).

    Raises
    ------
    ValueError, TypeError
        If an argument is not an integer in its range (named, with the range).

    Examples
    --------
    >>> x = random_design(1000, 6, seed=0)
    >>> bool(np.abs(x).max() <= LEVEL_LIMIT), bool(np.array_equal(random_design(10, 6, 0), x[:10]))
    (True, True)
    >>> random_design(0, 6, seed=0)
    Traceback (most recent call last):
    ...
    ValueError: n_runs must be in [1, 100000], got 0
    """
    n_runs = check_int("n_runs", n_runs, low=1, high=MAX_RANDOM_RUNS)
    n_factors = check_int("n_factors", n_factors, low=1)
    rng = np.random.default_rng(check_int("seed", seed, low=0))
    return rng.uniform(-LEVEL_LIMIT, LEVEL_LIMIT, (n_runs, n_factors))
