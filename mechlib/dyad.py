"""The RR dyad of a planar leg (the 5R's leg, thesis Eqs 20–23): its reach, inverse kinematics,
joint reading and identification Jacobian, without per-call validation.

The one home of these formulas: the 5R chapter (:mod:`mechlib.fivebar.kinematics`, which checks
its input first) and the calibration core's instances (:mod:`mechlib.fivebar.mechanism`,
:mod:`mechlib.mechanisms.rrr3`, whose :class:`mechlib.calibration.mechanism.Leg` checks the
parameters once) call them. ``points`` is a float array (N, 2), the parameters
``φ = [l, L, Ax, Ay, k, γ]`` (Eq 21) are valid and ``mode`` (the working mode, the elbow side) is
±1; an unreachable point still raises.
"""

from __future__ import annotations

import numpy as np

REACH_TOL = 1e-12
"""Round-off slack of the reach tests: |cos| <= 1 + slack in the inverse kinematics (a leg reaches
a point) and h² >= −slack in the 5R's forward kinematics (the distal links close the loop)."""


def elbow(psi: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """Elbow points B = A + l (cos θ, sin θ), θ = k ψ + γ, for joint readings ψ (N,): (N, 2)."""
    theta = phi[4] * np.asarray(psi, dtype=float) + phi[5]
    return np.column_stack([phi[2] + phi[0] * np.cos(theta), phi[3] + phi[0] * np.sin(theta)])


def reach_cosine(points: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """``cos`` of the angle at A between A→P and A→B; the leg reaches P iff ``|value| <= 1``.

    Parameters
    ----------
    points : numpy.ndarray, shape (N, 2)
        End-effector points P [m].
    phi : numpy.ndarray, shape (6,)
        Leg parameters (Eq 21).

    Returns
    -------
    numpy.ndarray, shape (N,)
        NaN or ±inf at the base point itself.
    """
    prox, big_l, ax, ay = phi[:4]
    rho = np.hypot(points[:, 0] - ax, points[:, 1] - ay)
    with np.errstate(divide="ignore", invalid="ignore"):
        return (rho**2 + prox**2 - big_l**2) / (2 * prox * rho)


def active_angle(points: np.ndarray, phi: np.ndarray, mode: int) -> np.ndarray:
    """Active joint angle θ of the dyad reaching ``points`` (inverse kinematics, Eq 23).

    ``θ = atan2(P − A) + mode · acos(c)`` with ``c`` of :func:`reach_cosine`: ``mode`` +1 puts
    the elbow counter-clockwise of the line A→P.

    Parameters
    ----------
    points : numpy.ndarray, shape (N, 2)
    phi : numpy.ndarray, shape (6,)
    mode : {1, -1}

    Returns
    -------
    numpy.ndarray, shape (N,)

    Raises
    ------
    ValueError
        If a point is out of reach (its index, the leg's base and the reach interval are named).
    """
    prox, big_l, ax, ay = phi[:4]
    c = reach_cosine(points, phi)
    bad = ~(np.abs(c) <= 1 + REACH_TOL)
    if np.any(bad):
        i = int(np.argmax(bad))
        raise ValueError(
            f"point #{i} {points[i].tolist()} is out of the leg's reach, outside the workspace "
            f"of the leg based at ({ax:g}, {ay:g}): its distance from the base must lie in "
            f"[|L - l|, l + L] = [{abs(big_l - prox):g}, {prox + big_l:g}] m"
        )
    base = np.arctan2(points[:, 1] - ay, points[:, 0] - ax)
    return base + mode * np.arccos(np.clip(c, -1.0, 1.0))


def reading(points: np.ndarray, phi: np.ndarray, mode: int) -> np.ndarray:
    """Joint reading ψ = (θ − γ)/k of the dyad for end-effector points (the function gκ, Eq 13).

    θ − γ is wrapped to (−π, π], the branch nearest the offset γ, so that ψ is continuous over
    the workspace.

    Returns
    -------
    numpy.ndarray, shape (N,)
    """
    theta = active_angle(points, phi, mode)
    return np.angle(np.exp(1j * (theta - phi[5]))) / phi[4]


def jacobian(points: np.ndarray, phi: np.ndarray, mode: int, min_sine: float = 0.0) -> np.ndarray:
    """Analytic ``C = ∂ψ/∂φ`` of the dyad at end-effector points (Eq 17), shape (N, 6).

    With ``u = x − l cos θ − Ax``, ``v = y − l sin θ − Ay`` and ``F = u² + v² − L² = 0``:
    ``dθ/dp = −F_p / F_θ``, ``F_θ = 2 l (u sin θ − v cos θ)``, ``F_l = −2 (u cos θ + v sin θ)``,
    ``F_L = −2 L``, ``F_Ax = −2 u``, ``F_Ay = −2 v``; then ``ψ = (θ − γ)/k`` gives
    ``∂ψ/∂p = (dθ/dp)/k``, ``∂ψ/∂k = −(θ − γ)/k²`` and ``∂ψ/∂γ = −1/k``.

    Parameters
    ----------
    points : numpy.ndarray, shape (N, 2)
    phi : numpy.ndarray, shape (6,)
    mode : {1, -1}
    min_sine : float
        Smallest accepted |sine| of the angle between the proximal and distal links,
        ``F_θ / (2 l L)``; 0 (the default) checks nothing.

    Raises
    ------
    ValueError
        If a point is out of reach, or at a serial singularity (|sine| < ``min_sine``: the leg
        stretched or folded, where the Jacobian is unbounded).
    """
    prox, big_l, ax, ay, k, gamma = phi
    theta = active_angle(points, phi, mode)
    u = points[:, 0] - prox * np.cos(theta) - ax
    v = points[:, 1] - prox * np.sin(theta) - ay
    f_theta = 2 * prox * (u * np.sin(theta) - v * np.cos(theta))
    if min_sine > 0:
        sine = f_theta / (2 * prox * big_l)
        if np.any(np.abs(sine) < min_sine):
            i = int(np.argmax(np.abs(sine) < min_sine))
            raise ValueError(
                f"point #{i} {points[i].tolist()} is at a serial singularity of the leg "
                f"(stretched or folded, |sine| = {abs(sine[i]):.2g}): the identification "
                f"Jacobian is unbounded; allowed |sine| >= {min_sine:g}"
            )
    f_p = np.column_stack(
        [-2 * (u * np.cos(theta) + v * np.sin(theta)), np.full_like(u, -2 * big_l), -2 * u, -2 * v]
    )
    psi = np.angle(np.exp(1j * (theta - gamma))) / k
    return np.column_stack([-f_p / f_theta[:, None] / k, -psi / k, np.full_like(u, -1.0 / k)])
