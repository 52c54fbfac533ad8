"""The RR dyad of a planar leg (the 5R's leg, thesis Eqs 20–23), without per-call validation.

The same formulas as :func:`mechlib.fivebar.kinematics.joint_reading` and
:func:`mechlib.fivebar.identification.identification_jacobian` (tests compare them), written for
the many small calls of a Monte Carlo: parameters ``φ = [l, L, Ax, Ay, k, γ]`` are assumed
valid (a :class:`mechlib.calibration.mechanism.Leg` checks them); an unreachable point still
raises.
"""

from __future__ import annotations

import numpy as np

#: Round-off slack of the reach test |cos| <= 1 (as in :mod:`mechlib.fivebar.kinematics`).
REACH_TOL = 1e-12


def active_angle(points: np.ndarray, phi: np.ndarray, mode: int) -> np.ndarray:
    """θ of the dyad reaching ``points`` (N, 2) with elbow side ``mode`` (±1).

    Raises
    ------
    ValueError
        If a point is out of reach (its index and the reach interval are named).
    """
    prox, big_l, ax, ay = phi[:4]
    dx, dy = points[:, 0] - ax, points[:, 1] - ay
    rho = np.hypot(dx, dy)
    c = (rho**2 + prox**2 - big_l**2) / (2 * prox * rho)
    bad = ~(np.abs(c) <= 1 + REACH_TOL)
    if np.any(bad):
        i = int(np.argmax(bad))
        raise ValueError(
            f"point #{i} {points[i].tolist()} is out of the leg's reach: its distance from the "
            f"base must lie in [{abs(big_l - prox):g}, {prox + big_l:g}] m"
        )
    return np.arctan2(dy, dx) + mode * np.arccos(np.clip(c, -1.0, 1.0))


def reading(points: np.ndarray, phi: np.ndarray, mode: int) -> np.ndarray:
    """ψ = (θ − γ)/k, θ − γ wrapped to (−π, π]."""
    theta = active_angle(points, phi, mode)
    return np.angle(np.exp(1j * (theta - phi[5]))) / phi[4]


def jacobian(points: np.ndarray, phi: np.ndarray, mode: int) -> np.ndarray:
    """``∂ψ/∂φ`` (N, 6) by implicit differentiation of ``|P − B|² = L²`` (see
    :func:`mechlib.fivebar.identification.identification_jacobian`)."""
    prox, big_l, ax, ay, k, gamma = phi
    theta = active_angle(points, phi, mode)
    u = points[:, 0] - prox * np.cos(theta) - ax
    v = points[:, 1] - prox * np.sin(theta) - ay
    f_theta = 2 * prox * (u * np.sin(theta) - v * np.cos(theta))
    f_p = np.column_stack(
        [-2 * (u * np.cos(theta) + v * np.sin(theta)), np.full_like(u, -2 * big_l), -2 * u, -2 * v]
    )
    psi = np.angle(np.exp(1j * (theta - gamma))) / k
    return np.column_stack([-f_p / f_theta[:, None] / k, -psi / k, np.full_like(u, -1.0 / k)])
