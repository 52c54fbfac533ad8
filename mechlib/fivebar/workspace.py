"""The planar 5R's workspace sampled on a grid: where both legs reach, and on which side of the
parallel singularity each point lies (the data of Fig 10), plus the leg chains drawn in Figs 10–11.

The parallel-singularity measure is :func:`mechlib.fivebar.kinematics.singularity_measures`'
``parallel`` entry (sine of the angle between the two distal links): it is zero where the distal
links are aligned and changes sign across that curve, so the curve is its zero contour.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechlib import dyad
from mechlib.fivebar import kinematics as kin
from mechlib.params import check_int, check_matrix

#: Default number of grid points per side of the field (Fig 10: 400 × 400, 0.16 M points).
DEFAULT_FIELD_POINTS = 400
#: Fewest and most grid points per side a field may have.
FIELD_POINTS_RANGE = (3, 4000)


@dataclass(frozen=True)
class SingularityField:
    """The parallel-singularity measure on a regular grid over a rectangular window.

    Attributes
    ----------
    x, y : numpy.ndarray, shape (n,)
        Grid coordinates [m].
    reachable : numpy.ndarray of bool, shape (n, n)
        True where both legs reach the point (rows follow ``y``, columns ``x``).
    parallel : numpy.ndarray, shape (n, n)
        Sine of the angle between the distal links; NaN where a leg cannot reach.
    modes : (int, int)
        The legs' working modes the measure was computed for.
    """

    x: np.ndarray
    y: np.ndarray
    reachable: np.ndarray
    parallel: np.ndarray
    modes: tuple[int, int]


def check_window(window: object) -> tuple[float, float, float, float]:
    """A window ``(x_min, x_max, y_min, y_max)`` [m] of finite numbers with min < max.

    Raises
    ------
    ValueError
        If it does not have four entries or a lower limit is not below its upper one.
    """
    allowed = "four finite numbers (x_min, x_max, y_min, y_max) [m]"
    try:
        w = np.asarray(window, dtype=float).ravel()
    except (TypeError, ValueError):
        raise ValueError(f"window must be {allowed}, got {window!r}") from None
    if w.shape != (4,) or not np.all(np.isfinite(w)):
        raise ValueError(f"window must be {allowed}, got {window!r}")
    if not (w[0] < w[1] and w[2] < w[3]):
        raise ValueError(f"window must have x_min < x_max and y_min < y_max, got {w.tolist()}")
    return float(w[0]), float(w[1]), float(w[2]), float(w[3])


def singularity_field(
    phi1: object,
    phi2: object,
    window: object,
    modes: tuple[int, int] = kin.NOMINAL_MODES,
    n: int = DEFAULT_FIELD_POINTS,
) -> SingularityField:
    """Sample reach and the parallel-singularity measure on an ``n`` × ``n`` grid.

    Parameters
    ----------
    phi1, phi2 : array_like, shape (6,)
        Leg parameters (Eq 21).
    window : sequence of 4 float
        ``(x_min, x_max, y_min, y_max)`` [m], edges included in the grid.
    modes : (int, int)
        Working modes of the legs (±1 each).
    n : int
        Grid points per side, in ``FIELD_POINTS_RANGE``.

    Returns
    -------
    SingularityField
        A point counts as reachable when ``|cos| < 1`` for both legs (strictly: a leg stretched or
        folded is on its reach boundary, a serial singularity).
    """
    x0, x1, y0, y1 = check_window(window)
    n = check_int("n", n, low=FIELD_POINTS_RANGE[0], high=FIELD_POINTS_RANGE[1])
    xs, ys = np.linspace(x0, x1, n), np.linspace(y0, y1, n)
    xx, yy = np.meshgrid(xs, ys)
    pts = np.column_stack([xx.ravel(), yy.ravel()])
    ok = np.all(
        [np.abs(dyad.reach_cosine(pts, kin.check_leg(p))) < 1 for p in (phi1, phi2)], axis=0
    )
    par = np.full(len(pts), np.nan)
    if np.any(ok):
        par[ok] = kin.singularity_measures(pts[ok], phi1, phi2, modes)["parallel"]
    modes = (int(modes[0]), int(modes[1]))
    return SingularityField(xs, ys, ok.reshape(xx.shape), par.reshape(xx.shape), modes)


def working_side_share(field: SingularityField, point: object) -> dict[str, float]:
    """Shares of the field's window that both legs reach, and that lie on ``point``'s side of the
    parallel singularity (reachable, with the measure's sign at ``point``).

    Parameters
    ----------
    field : SingularityField
    point : array_like, shape (2,)
        A regular point of the working assembly (e.g. the MIW centre) inside the window.

    Returns
    -------
    dict
        ``reachable`` and ``working_side``: fractions of the grid points, in [0, 1].

    Raises
    ------
    ValueError
        If ``point`` is outside the window, unreachable, or on the singularity itself.
    """
    p = check_matrix("point", np.asarray(point, dtype=float)[None, :], shape=(1, 2))[0]
    if not (field.x[0] <= p[0] <= field.x[-1] and field.y[0] <= p[1] <= field.y[-1]):
        raise ValueError(
            f"point must lie in the field's window x in [{field.x[0]:g}, {field.x[-1]:g}], "
            f"y in [{field.y[0]:g}, {field.y[-1]:g}], got {p.tolist()}"
        )
    j = int(np.argmin(np.abs(field.x - p[0])))
    i = int(np.argmin(np.abs(field.y - p[1])))
    sign = np.sign(field.parallel[i, j])
    if not field.reachable[i, j] or sign == 0:
        raise ValueError(f"point {p.tolist()} must be reachable and off the parallel singularity")
    with np.errstate(invalid="ignore"):
        side = field.reachable & (np.sign(field.parallel) == sign)
    return {"reachable": float(field.reachable.mean()), "working_side": float(side.mean())}


def leg_chain(point: object, phi: object, mode: int) -> tuple[np.ndarray, float]:
    """Base A, elbow B and end-effector P of one leg posed at ``point``, and its active angle.

    Parameters
    ----------
    point : array_like, shape (2,)
        End-effector position [m], inside the leg's reach.
    phi : array_like, shape (6,)
        Leg parameters (Eq 21).
    mode : {1, -1}
        Working mode.

    Returns
    -------
    chain : numpy.ndarray, shape (3, 2)
        Rows A, B, P [m].
    theta : float
        Active angle θ [rad] (inverse kinematics, Eq 23), on the branch of
        :func:`mechlib.dyad.active_angle`.
    """
    phi = kin.check_leg(phi)
    p = np.asarray(point, dtype=float)
    theta = float(dyad.active_angle(kin.check_points(p), phi, kin.check_mode("mode", mode))[0])
    a = phi[2:4]
    b = a + phi[0] * np.array([np.cos(theta), np.sin(theta)])
    return np.vstack([a, b, p]), theta


def mechanism_chains(
    point: object, phi1: object, phi2: object, modes: tuple[int, int] = kin.NOMINAL_MODES
) -> np.ndarray:
    """Both legs' chains (2, 3, 2) — base, elbow, end-effector [m] — posed at ``point``."""
    return np.stack(
        [leg_chain(point, phi, mode)[0] for phi, mode in zip((phi1, phi2), modes, strict=True)]
    )
