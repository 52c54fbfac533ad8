"""Pose of the motion stage at finite rotation: exact rigid registration of its nodes.

:mod:`mechlib.fe.pose` fits ``u = t + θ × (X − c)``, which is exact only for infinitesimal
rotations. Here the stage's nodes are registered by the exact least-squares rigid motion
``X ↦ R (X − X̄) + Y̅`` (Kabsch, :meth:`scipy.spatial.transform.Rotation.align_vectors` on the
centred point sets, every node weighted equally), and the pose is reported in three conventions,
all as [x y z θx θy θz] in µm and µrad for coordinates and displacements in mm:

``"small"``
    the small-rotation fit of :func:`mechlib.fe.pose.fit_operator` (what the linear model's
    tables use);
``"rotvec"``
    the translation of the stage centre ``c`` and the rotation vector of ``R`` (axis × angle);
``"euler_xyz"``
    the same translation and the intrinsic Euler angles ``XYZ`` of ``R`` (see
    :data:`EULER_SEQUENCE`).

The translation is the displacement of the stage centre ``c`` under the rigid motion,
``Y̅ − X̄ + R (c − X̄) − (c − X̄)``: the same point whose translation the small-rotation fit
reports. ``c`` defaults to the origin, as in :func:`~mechlib.fe.pose.fit_operator` (the
meshes put the stage centre, the thesis's moving frame, at the origin; sec. 2.6.1).

The three conventions agree to first order in the rotation. At the tilts of the non-linear runs
(up to ~50 mrad) they differ at second order, e.g. by ``θx θy / 2`` in θz between the rotation
vector and the Euler angles: a fraction of a milliradian, comparable with θz itself.
"""

from __future__ import annotations

from collections.abc import Mapping
from itertools import combinations

import numpy as np
from numpy.typing import ArrayLike
from scipy.spatial.transform import Rotation

from mechlib.fe.pose import POSE_SCALE, fit_operator
from mechlib.params import check_matrix

#: Euler-angle sequence of the ``"euler_xyz"`` convention, in SciPy's notation: upper case is
#: *intrinsic* — rotate by θx about the stage's X axis, then by θy about the once-rotated Y axis,
#: then by θz about the twice-rotated Z axis, ``R = Rx(θx) Ry(θy) Rz(θz)``. The thesis reports
#: "differential Euler XYZ angles" of a moving frame attached to the stage centre (sec. 2.6.1);
#: in the usual robotics naming (e.g. Craig, *Introduction to Robotics*, sec. 2.8) "Euler
#: angles" turn about the moving frame's axes and "fixed angles" about the reference frame's,
#: so "Euler XYZ" is ``Rx Ry Rz``. Extrinsic ``"xyz"`` (``Rz Ry Rx``, "X-Y-Z fixed angles")
#: flips the sign of every second-order term relative to the rotation vector.
EULER_SEQUENCE = "XYZ"
#: Pose conventions returned by :func:`finite_poses`, in order.
CONVENTIONS: tuple[str, ...] = ("small", "rotvec", "euler_xyz")
#: Number of pose components [x y z θx θy θz].
N_POSE = 6
#: Fewest points that can determine a rigid motion (and must not all be collinear).
MIN_POINTS = 3
#: Rank of a centred point set that is not collinear.
_PLANE_RANK = 2


def _center(center: ArrayLike | None) -> np.ndarray:
    """The stage centre as a finite (3,) array [mm]; ``None`` is the origin."""
    if center is None:
        return np.zeros(3)
    c = np.asarray(center, dtype=float)
    if c.shape != (3,) or not np.all(np.isfinite(c)):
        raise ValueError(f"center must be 3 finite coordinates [mm], got {center!r}")
    return c


def _check_points(points: ArrayLike) -> np.ndarray:
    """Reference points (n, 3) [mm], at least three of them not collinear."""
    x = check_matrix("points", points, shape=(None, 3))
    rank = np.linalg.matrix_rank(x - x.mean(axis=0)) if len(x) else 0
    if len(x) < MIN_POINTS or rank < _PLANE_RANK:
        raise ValueError(
            f"points must contain at least {MIN_POINTS} non-collinear points for a rigid "
            f"registration, got {len(x)} point(s) spanning rank {rank}"
        )
    return x


def register(
    points: ArrayLike, displaced: ArrayLike, center: ArrayLike | None = None
) -> tuple[np.ndarray, Rotation]:
    """Exact least-squares rigid motion taking ``points`` to ``displaced``.

    Minimises ``Σ_i |R (X_i − X̄) + Y̅ − Y_i|²`` over rotations ``R`` (Kabsch, equal weights; the
    centred vectors are not normalised, so every node counts equally, not every direction).

    Parameters
    ----------
    points : array_like, shape (n, 3)
        Reference coordinates ``X`` [mm]; at least three points, not all collinear.
    displaced : array_like, shape (n, 3)
        Displaced coordinates ``Y = X + u`` [mm], row for row.
    center : array_like, shape (3,), optional
        The point whose displacement is reported as the translation [mm]; default the origin
        (the stage centre, as in :func:`mechlib.fe.pose.fit_operator`).

    Returns
    -------
    translation : ndarray, shape (3,)
        Displacement of ``center`` under the rigid motion [mm].
    rotation : scipy.spatial.transform.Rotation
        The rotation ``R`` (reference to displaced frame).

    Raises
    ------
    ValueError
        If ``points`` has fewer than three non-collinear points, ``displaced`` does not have the
        shape of ``points``, ``center`` is not three numbers, or any holds NaN or inf.
    """
    x = _check_points(points)
    y = check_matrix("displaced", displaced, shape=x.shape)
    c = _center(center)
    x_mean, y_mean = x.mean(axis=0), y.mean(axis=0)
    rotation, _ = Rotation.align_vectors(y - y_mean, x - x_mean)
    arm = c - x_mean
    return y_mean - x_mean + rotation.apply(arm) - arm, rotation


def finite_poses(
    points: ArrayLike, displacements: ArrayLike, center: ArrayLike | None = None
) -> dict[str, np.ndarray]:
    """Stage poses [µm, µrad] in the three conventions of :data:`CONVENTIONS`.

    Parameters
    ----------
    points : array_like, shape (n, 3)
        Reference coordinates of the stage's nodes [mm].
    displacements : array_like, shape (n, 3) or (n_sets, n, 3)
        Nodal displacements [mm] of one or several solutions, rows as in ``points``.
    center : array_like, shape (3,), optional
        The stage centre [mm]; default the origin (as :func:`mechlib.fe.pose.fit_operator`).

    Returns
    -------
    dict of str to ndarray
        ``"small"``, ``"rotvec"``, ``"euler_xyz"``: poses [x y z θx θy θz] [µm, µrad], shape
        (6,) for one displacement set, (n_sets, 6) for several. ``"small"`` is
        ``fit_operator(points, center) @ vec(u)``; ``"rotvec"`` and ``"euler_xyz"`` share the
        translation of :func:`register`. The registration runs once per set (SciPy's
        ``align_vectors`` takes one set at a time); the conversions are vectorised.

    Raises
    ------
    ValueError
        If ``points`` has fewer than three non-collinear points, ``displacements`` is not
        (n, 3) or (n_sets, n, 3) with ``n = len(points)``, or an input holds NaN or inf.
    """
    x = _check_points(points)
    c = _center(center)
    u = np.asarray(displacements, dtype=float)
    single = u.ndim == x.ndim
    sets = u[None] if single else u
    if sets.ndim != x.ndim + 1 or sets.shape[1:] != x.shape:
        raise ValueError(
            f"displacements must have shape ({len(x)}, 3) or (n_sets, {len(x)}, 3) to match "
            f"points, got {u.shape}"
        )
    if not np.all(np.isfinite(sets)):
        raise ValueError("displacements must hold only finite numbers (found NaN or inf)")
    small = (fit_operator(x, c) @ sets.reshape(len(sets), -1).T).T
    fits = [register(x, x + s, c) for s in sets]
    translation = np.array([t for t, _ in fits]).reshape(len(sets), 3)
    rotations = Rotation.concatenate([r for _, r in fits])
    poses = {
        "small": small,
        "rotvec": POSE_SCALE * np.hstack([translation, rotations.as_rotvec()]),
        "euler_xyz": POSE_SCALE * np.hstack([translation, rotations.as_euler(EULER_SEQUENCE)]),
    }
    return {k: v[0] if single else v for k, v in poses.items()}


def convention_differences(
    poses_by_convention: Mapping[str, ArrayLike],
) -> dict[str, dict[str, np.ndarray]]:
    """Largest per-component differences between every pair of pose conventions.

    Parameters
    ----------
    poses_by_convention : mapping of str to array_like, each (n_sets, 6) or (6,)
        Poses of the same solutions in two or more conventions [µm, µrad], e.g. the result of
        :func:`finite_poses`.

    Returns
    -------
    dict of str to dict
        For every pair ``(a, b)`` of keys, in the mapping's order, an entry ``"a vs b"`` with
        ``"max_abs"``: ``max over sets |a − b|`` per component (6,) [µm, µrad], and
        ``"relative"``: that divided by the component's range (max − min) over the sets, the
        larger of the two conventions' ranges; NaN where both ranges are zero.

    Raises
    ------
    ValueError
        If fewer than two conventions are given, an entry is not (n_sets, 6) or (6,) and finite,
        or the entries differ in shape.
    """
    if len(poses_by_convention) < 2:
        raise ValueError(
            "poses_by_convention must hold at least two conventions, "
            f"got {list(poses_by_convention)}"
        )
    arrays = {
        name: check_matrix(
            f"poses_by_convention[{name!r}]", np.atleast_2d(value), shape=(None, N_POSE)
        )
        for name, value in poses_by_convention.items()
    }
    shapes = {name: a.shape for name, a in arrays.items()}
    if len(set(shapes.values())) > 1:
        raise ValueError(f"poses_by_convention entries must share one shape, got {shapes}")
    out: dict[str, dict[str, np.ndarray]] = {}
    for a, b in combinations(arrays, 2):
        max_abs = np.abs(arrays[a] - arrays[b]).max(axis=0)
        span = np.maximum(np.ptp(arrays[a], axis=0), np.ptp(arrays[b], axis=0))
        relative = np.divide(max_abs, span, out=np.full(N_POSE, np.nan), where=span > 0)
        out[f"{a} vs {b}"] = {"max_abs": max_abs, "relative": relative}
    return out
