"""Pose of the motion stage from nodal displacements: small-rotation rigid-body least squares.

The stage's nodes are fitted by ``u = t + θ × (X − c)`` with ``c`` the stage centre (the thesis's
moving frame, sec. 2.6.1). Poses are reported as [x y z θx θy θz] in µm and µrad for
displacements in mm.
"""

from __future__ import annotations

import numpy as np

from mechlib.params import check_matrix

#: Scale from (mm, rad) to the thesis's pose units (µm, µrad).
POSE_SCALE = np.array([1e3, 1e3, 1e3, 1e6, 1e6, 1e6])


def rigid_basis(points: np.ndarray, center: np.ndarray | None = None) -> np.ndarray:
    """Matrix ``A`` (3 n, 6) with ``vec(u) = A @ [t, θ]`` for small rigid motions of ``points``."""
    d = check_matrix("points", np.asarray(points, dtype=float), shape=(None, 3))
    d = d - (np.zeros(3) if center is None else np.asarray(center, dtype=float))
    a = np.zeros((len(d), 3, 6))
    a[:, :, :3] = np.eye(3)
    a[:, 0, 4], a[:, 0, 5] = d[:, 2], -d[:, 1]
    a[:, 1, 3], a[:, 1, 5] = -d[:, 2], d[:, 0]
    a[:, 2, 3], a[:, 2, 4] = d[:, 1], -d[:, 0]
    return a.reshape(-1, 6)


def fit_operator(points: np.ndarray, center: np.ndarray | None = None) -> np.ndarray:
    """Least-squares operator ``P`` (6, 3 n): pose [µm, µrad] = ``P @ vec(u [mm])``.

    Raises
    ------
    ValueError
        If the points cannot determine a rigid motion (fewer than three non-collinear points).
    """
    a = rigid_basis(points, center)
    if np.linalg.matrix_rank(a) < 6:
        raise ValueError("points must contain at least three non-collinear points for a pose fit")
    return POSE_SCALE[:, None] * np.linalg.pinv(a)
