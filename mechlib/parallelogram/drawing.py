"""What the parallelogram's figures draw, from the comparison's arrays (:mod:`.comparison`):
the sweep's lines arranged for plotting, the FE's poses at chosen loads, the deformed elastica
(beams and stage outline) and the load points. Lengths over L, rotations in radians.
"""

from __future__ import annotations

import numpy as np

from mechlib.parallelogram import elastica as el
from mechlib.parallelogram import published as pub
from mechlib.parallelogram.comparison import applied_loads, as_rows, fe_poses


def by_line(
    sweep: object, values: object, a_x_levels: object, b_levels: object
) -> tuple[np.ndarray, np.ndarray]:
    """Per-row values of a sweep arranged by line: printed (A_x, B) and increasing A_y.

    Parameters
    ----------
    sweep : array_like, shape (n, 6)
        Columns :data:`.published.SWEEP_COLUMNS` (B as printed).
    values : array_like, shape (n, k)
        One row per sweep row (e.g. poses).
    a_x_levels, b_levels : array_like
        The lines' A_x and printed B.

    Returns
    -------
    (a_y, grid)
        The A_y levels (shared by every line) and values of shape (len(a_x_levels),
        len(b_levels), len(a_y), k).

    Raises
    ------
    ValueError
        If a line has no row, or the lines do not share their A_y levels.
    """
    s, v = as_rows("sweep", sweep, 6), np.asarray(values, dtype=float)
    if len(v) != len(s):
        raise ValueError(f"values must have one row per sweep row ({len(s)}), got {len(v)}")
    grid, a_y = [], None
    for a_x in np.asarray(a_x_levels, dtype=float):
        row = []
        for b in np.asarray(b_levels, dtype=float):
            idx = np.flatnonzero((s[:, 0] == a_x) & (s[:, 2] == b))
            idx = idx[np.argsort(s[idx, 1], kind="stable")]
            if a_y is None:
                a_y = s[idx, 1]
            if not idx.size or not np.array_equal(s[idx, 1], a_y):
                raise ValueError(
                    f"line (A_x, B) = ({a_x:g}, {b:g}) has no rows or other A_y levels"
                )
            row.append(v[idx])
        grid.append(row)
    return np.asarray(a_y), np.array(grid)


def load_points(poses: object) -> np.ndarray:
    """(x, y)/L of the load point (the middle of the tip face, (L, 0) unloaded) at each pose
    (rows (u_x/L, u_y/L, φ); a NaN pose gives a NaN point).

    Raises
    ------
    ValueError
        If ``poses`` is not an (n, 3) array.
    """
    p = np.asarray(poses, dtype=float)
    if p.ndim != 2 or p.shape[1] != 3:
        raise ValueError(f"poses must be an (n, 3) array, got shape {p.shape}")
    return np.column_stack([1.0 + p[:, 0], p[:, 1]])


def stage_outline(pose: object, half_width: float = pub.HALF_WIDTH) -> np.ndarray:
    """The stage block's outline at a pose, (5, 2) closed polygon of (x, y)/L: from the beam tips
    (x = L) over :data:`.published.STAGE_LENGTH_MM`, across both beams' outer faces.

    Raises
    ------
    ValueError
        If ``pose`` is not three finite numbers.
    """
    p = as_rows("pose", np.reshape(np.asarray(pose, dtype=float), (1, -1)))[0]
    length = pub.STAGE_LENGTH_MM / pub.LENGTH_MM
    edge = half_width + pub.THICKNESS_MM / (2.0 * pub.LENGTH_MM)
    local = np.array([[0, -edge], [length, -edge], [length, edge], [0, edge], [0, -edge]])
    c, s = np.cos(p[2]), np.sin(p[2])
    return local @ np.array([[c, s], [-s, c]]) + [1.0 + p[0], p[1]]


def deformed(
    loads: object, *, axial_compliance: float = pub.AXIAL_COMPLIANCE, n_points: int = 41
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Centre lines, stage outlines and poses of the elastica at each load, each solved from the
    unloaded state along the straight load path.

    Parameters
    ----------
    loads : array_like, shape (n, 3)
        Rows (A_x, A_y, B) in the elastica's ranges.
    axial_compliance : float
        c = EI/(EA L²), as in :func:`.elastica.solve_pose` (default the benchmark beams').
    n_points : int
        Points along each beam, at least 2.

    Returns
    -------
    (lines, outlines, poses)
        Shapes (n, 2, n_points, 2) in (x, y)/L (:func:`.elastica.centre_lines`), (n, 5, 2)
        (:func:`stage_outline`) and (n, 3).

    Raises
    ------
    ValueError
        If ``loads`` is not a finite (n, 3) array or a load is out of range.
    """
    sols = [el.solve_pose(*r, axial_compliance=axial_compliance) for r in as_rows("loads", loads)]
    poses = np.array([[s.u_x, s.u_y, s.phi] for s in sols])
    lines = np.array([el.centre_lines(s, n_points) for s in sols])
    return lines, np.array([stage_outline(p) for p in poses]), poses


def fe_at(sweep: object, loads: object) -> np.ndarray:
    """The FE poses (:func:`fe_poses`) of the sweep rows whose applied loads
    (:func:`applied_loads`) are ``loads``; NaN for a load no row has.

    Raises
    ------
    ValueError
        If the arrays are not finite (n, 6) and (m, 3).
    """
    applied, poses = applied_loads(sweep), fe_poses(sweep)
    out = np.full((len(as_rows("loads", loads)), 3), np.nan)
    for i, r in enumerate(np.asarray(loads, dtype=float)):
        hit = np.flatnonzero(np.all(applied == r, axis=1))
        if hit.size:
            out[i] = poses[hit[0]]
    return out
