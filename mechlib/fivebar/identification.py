"""Kinematic identification of the 5R by inverse calibration (thesis Eqs 16–19, 24–26).

For leg κ and measured end-effector points ``P̂`` and joint readings ``ψ̂``, the residual is
``ΔQ = ψ̂ − gκ(P̂; φκ)`` and the identification Jacobian is ``Cκ = ∂gκ/∂φκ`` (Eq 17), computed
analytically by implicit differentiation of the loop equation (Eq 23) in the RR dyad's
:func:`mechlib.dyad.jacobian`.

*Divide and conquer* identifies each leg from its own posture set. The *traditional* method
identifies all twelve parameters from one posture set; because leg κ's reading depends only on
φκ, its total identification matrix is block diagonal, ``C = diag(C1, C2)`` over shared postures.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from mechlib import dyad
from mechlib.fivebar.kinematics import (
    PARAM_NAMES,
    SINGULAR_TOL,
    check_leg,
    check_mode,
    check_points,
    check_regular,
    forward,
    joint_reading,
)
from mechlib.params import check_float, check_int

RANK_TOL = 1e-9
"""Relative singular-value threshold below which a parameter combination is unidentifiable."""


def identification_jacobian(points: object, phi: object, mode: int) -> np.ndarray:
    """Analytic ``C = ∂ψ/∂φ`` of one leg at end-effector points (Eq 17), shape (n, 6):
    :func:`mechlib.dyad.jacobian` on checked input, refusing serial singularities.

    Parameters
    ----------
    points, phi, mode
        End-effector points (n, 2) or (2,), leg parameters (Eq 21) and working mode (±1), as
        for :func:`mechlib.fivebar.kinematics.joint_reading`.

    Returns
    -------
    numpy.ndarray, shape (n, 6)

    Raises
    ------
    ValueError
        Invalid input, a point out of reach, or one at a serial singularity (|sine| below
        :data:`mechlib.fivebar.kinematics.SINGULAR_TOL`: the Jacobian is unbounded there).
    """
    phi = check_leg(phi)
    mode = check_mode("mode", mode)
    return dyad.jacobian(check_points(points), phi, mode, min_sine=SINGULAR_TOL)


def check_rank(c: object, names: tuple[str, ...] = PARAM_NAMES) -> None:
    """Raise if ``C`` is rank-deficient, naming the unidentifiable parameter combination."""
    c = np.asarray(c, dtype=float)
    if c.shape[0] < c.shape[1]:
        raise ValueError(f"{c.shape[0]} equations cannot identify {c.shape[1]} parameters")
    scale = np.linalg.norm(c, axis=0)
    scale[scale == 0] = 1.0
    _, s, vt = np.linalg.svd(c / scale, full_matrices=False)
    if s[-1] <= RANK_TOL * s[0]:
        v = vt[-1] / scale
        v = v / np.abs(v).max()
        combo = " + ".join(f"{w:+.3g}·{n}" for w, n in zip(v, names, strict=True) if abs(w) > 1e-3)
        raise ValueError(
            f"the posture set leaves a parameter combination unidentifiable "
            f"(σ_min/σ_max = {s[-1] / s[0]:.2e}): {combo}"
        )


@dataclass(frozen=True)
class LegFit:
    """Result of an identification: one leg's parameters, or both legs' stacked
    (:func:`identify_traditional`)."""

    phi: np.ndarray
    iterations: int
    residual_rms: float
    converged: bool


def identify_leg(
    points: object, psi: object, phi0: object, mode: int, *, max_iter: int = 50, tol: float = 1e-12
) -> LegFit:
    """Iterative linearised least squares of Eqs 24–26 for one leg.

    Parameters
    ----------
    points : array_like, shape (N, 2)
        Measured end-effector points.
    psi : array_like, shape (N,)
        Measured joint readings of this leg.
    phi0 : array_like, shape (6,)
        Starting (nominal) parameters.
    mode : {1, -1}
        Working mode.
    max_iter : int
    tol : float
        Stop when the update's largest component is below ``tol``.

    Raises
    ------
    ValueError
        If the postures make the problem rank-deficient (the combination is named).
    """
    phi = check_leg(phi0).copy()
    p = np.asarray(points, dtype=float)
    q = np.asarray(psi, dtype=float)
    max_iter = check_int("max_iter", max_iter, low=1, high=10_000)
    tol = check_float("tol", tol, low=0.0, low_open=True)
    check_rank(identification_jacobian(p, phi, mode))
    iterations = 0
    for iterations in range(1, max_iter + 1):  # noqa: B007 - the count is reported
        c = identification_jacobian(p, phi, mode)
        dq = q - joint_reading(p, phi, mode)
        dphi = np.linalg.lstsq(c, dq, rcond=None)[0]
        phi = phi + dphi
        if np.max(np.abs(dphi)) < tol:
            break
    res = q - joint_reading(p, phi, mode)
    converged = bool(np.max(np.abs(dphi)) < tol)
    return LegFit(phi, iterations, float(np.sqrt(np.mean(res**2))), converged)


def identify_leg_scipy(points: object, psi: object, phi0: object, mode: int) -> np.ndarray:
    """Cross-check of :func:`identify_leg` with ``scipy.optimize.least_squares`` (TRF)."""
    p = np.asarray(points, dtype=float)
    q = np.asarray(psi, dtype=float)
    fit = least_squares(
        lambda f: joint_reading(p, f, mode) - q,
        check_leg(phi0),
        jac=lambda f: identification_jacobian(p, f, mode),
        xtol=1e-15,
        ftol=1e-15,
        gtol=1e-15,
    )
    return fit.x


def simulate_measurements(
    targets: object,
    phi1_real: object,
    phi2_real: object,
    phi1_nom: object,
    phi2_nom: object,
    modes: tuple[int, int],
    sigma: float,
    rng: np.random.Generator,
) -> dict[str, np.ndarray]:
    """Simulated calibration measurements (thesis sec. 3.7 items 8–9).

    The controller commands the nominal inverse kinematics of each target point; the real
    mechanism moves to the forward kinematics of the *real* parameters; both the end-effector
    point and the two joint readings are measured with Gaussian noise of standard deviation
    ``sigma`` (m and rad, as in the thesis).
    """
    sigma = check_float("sigma", sigma, low=0.0)
    t = check_regular(targets, phi1_nom, phi2_nom, modes)
    psi1 = joint_reading(t, phi1_nom, modes[0])
    psi2 = joint_reading(t, phi2_nom, modes[1])
    p_real = forward(psi1, psi2, phi1_real, phi2_real)
    return {
        "points": p_real + rng.normal(0.0, sigma, p_real.shape),
        "psi1": psi1 + rng.normal(0.0, sigma, psi1.shape),
        "psi2": psi2 + rng.normal(0.0, sigma, psi2.shape),
    }


def posture_blocks(c1: object, c2: object) -> np.ndarray:
    """The traditional identification matrix of each shared posture: ``diag(C1_j, C2_j)``.

    Leg κ's reading depends only on φκ, so at posture ``j`` the two readings give the rows
    ``[C1_j, 0]`` and ``[0, C2_j]`` over the stacked parameters ``[φ1, φ2]``.

    Parameters
    ----------
    c1, c2 : array_like, shape (N, n1) and (N, n2)
        Identification matrices of legs 1 and 2 (:func:`identification_jacobian`) at the same
        N postures; ``n1`` and ``n2`` are the lengths of the legs' parameter vectors.

    Returns
    -------
    numpy.ndarray, shape (N, 2, n1 + n2)
        Block ``j``: row 0 ``[C1_j, 0]``, row 1 ``[0, C2_j]``.

    Raises
    ------
    ValueError
        If ``c1`` and ``c2`` are not matrices over the same number of postures.
    """
    a, b = np.asarray(c1, dtype=float), np.asarray(c2, dtype=float)
    if a.ndim != 2 or b.ndim != 2 or len(a) != len(b):
        raise ValueError(
            f"c1 and c2 must be (N, n1) and (N, n2) matrices over the same N postures, got "
            f"shapes {a.shape} and {b.shape}"
        )
    n1 = a.shape[1]
    blocks = np.zeros((len(a), 2, n1 + b.shape[1]))
    blocks[:, 0, :n1], blocks[:, 1, n1:] = a, b
    return blocks


def total_jacobian(
    points: object, phi1: object, phi2: object, modes: tuple[int, int]
) -> np.ndarray:
    """Traditional total identification matrix over shared postures, block diagonal.

    Returns
    -------
    numpy.ndarray, shape (2N, n1 + n2)
        ``diag(C1, C2)``: the N rows of leg 1's readings, then the N rows of leg 2's (the rows
        of :func:`posture_blocks` grouped by leg).
    """
    blocks = posture_blocks(
        identification_jacobian(points, phi1, modes[0]),
        identification_jacobian(points, phi2, modes[1]),
    )
    return np.concatenate([blocks[:, 0], blocks[:, 1]])


def identify_traditional(
    points: object,
    psi1: object,
    psi2: object,
    phi1_0: object,
    phi2_0: object,
    modes: tuple[int, int],
    *,
    max_iter: int = 50,
    tol: float = 1e-12,
) -> LegFit:
    """All twelve parameters at once from one shared posture set (Eq 19 on the total matrix).

    The Gauss–Newton step solves the full (2N × 12) system of :func:`total_jacobian`; it equals
    two independent leg solves because the matrix is block diagonal. Returns a :class:`LegFit`
    of the stacked ``[φ1, φ2]`` (its residual over both legs' readings), ``converged`` False when
    the update was still above ``tol`` after ``max_iter`` iterations.
    """
    phi1_0 = check_leg(phi1_0, "phi1_0")
    phi = np.concatenate([phi1_0, check_leg(phi2_0, "phi2_0")])
    n1 = len(phi1_0)
    p = np.asarray(points, dtype=float)
    q = np.concatenate([np.asarray(psi1, dtype=float), np.asarray(psi2, dtype=float)])
    max_iter = check_int("max_iter", max_iter, low=1, high=10_000)
    tol = check_float("tol", tol, low=0.0, low_open=True)
    check_rank(
        total_jacobian(p, phi[:n1], phi[n1:], modes),
        tuple(f"{n}{k}" for k in (1, 2) for n in PARAM_NAMES),
    )

    def readings(phi: np.ndarray) -> np.ndarray:
        return np.concatenate(
            [joint_reading(p, phi[:n1], modes[0]), joint_reading(p, phi[n1:], modes[1])]
        )

    iterations = 0
    for iterations in range(1, max_iter + 1):  # noqa: B007 - the count is reported
        c = total_jacobian(p, phi[:n1], phi[n1:], modes)
        dphi = np.linalg.lstsq(c, q - readings(phi), rcond=None)[0]
        phi = phi + dphi
        if np.max(np.abs(dphi)) < tol:
            break
    res = q - readings(phi)
    converged = bool(np.max(np.abs(dphi)) < tol)
    return LegFit(phi, iterations, float(np.sqrt(np.mean(res**2))), converged)


def position_errors(
    points: object,
    phi1_model: object,
    phi2_model: object,
    phi1_real: object,
    phi2_real: object,
    modes: tuple[int, int],
) -> np.ndarray:
    """End-effector position error |P_reached − P_target| when commanding with a model.

    The controller computes joint readings by the model's inverse kinematics; the real mechanism
    reaches the forward kinematics of the real parameters.
    """
    t = np.atleast_2d(np.asarray(points, dtype=float))
    psi1 = joint_reading(t, phi1_model, modes[0])
    psi2 = joint_reading(t, phi2_model, modes[1])
    reached = forward(psi1, psi2, phi1_real, phi2_real)
    return np.hypot(*(reached - t).T)
