"""A 6-UPS Gough–Stewart platform (six legs, pose ``r = (x, y, z, α, β, γ)``).

Leg κ joins the base joint ``aκ`` (universal) to the platform joint ``bκ`` (spherical, in the
platform frame) with a prismatic actuator whose length is ``ρκ = ρ0κ + kκ ψκ`` (offset and gain
of the reading ψκ). With ``R = Rz(γ) Ry(β) Rx(α)`` the inverse kinematics is
``ψκ = (|p + R bκ − aκ| − ρ0κ) / kκ``. Leg parameters:
``φκ = [aκx, aκy, aκz, bκx, bκy, bκz, ρ0κ, kκ]`` (eight per leg). Measurements: the platform pose
and the six readings.

Nominal design: base joints on a circle of radius ``BASE_RADIUS`` in pairs ±``BASE_HALF_GAP``
about 0°, 120°, 240°; platform joints on a circle of radius ``PLATFORM_RADIUS`` in pairs about
60°, 180°, 300°; the home pose at height ``HOME_Z``.
"""

from __future__ import annotations

from functools import partial

import numpy as np

from mechlib.calibration.mechanism import Leg, Mechanism
from mechlib.params import check_float

UNITS = ("m", "m", "m", "m", "m", "m", "m", "-")
PARAM_NAMES = ("ax", "ay", "az", "bx", "by", "bz", "rho0", "k")
#: Nominal design [m, rad].
BASE_RADIUS, PLATFORM_RADIUS, HOME_Z = 0.5, 0.3, 0.6
BASE_HALF_GAP, PLATFORM_HALF_GAP = np.deg2rad(12.0), np.deg2rad(12.0)
#: Nominal leg length at a zero reading [m] and reading gain.
RHO0, GAIN = 0.5, 1.0
#: Calibration box about the home pose: |x|, |y| [m], |z − HOME_Z| [m], |angles| [rad].
HALF_XY, HALF_Z, HALF_ANGLE = 0.1, 0.1, 0.2


def rotation(angles: object) -> np.ndarray:
    """``Rz(γ) Ry(β) Rx(α)`` for angles (N, 3), shape (N, 3, 3)."""
    a = np.atleast_2d(np.asarray(angles, dtype=float))
    (ca, cb, cg), (sa, sb, sg) = np.cos(a.T), np.sin(a.T)
    rot = np.empty((len(a), 3, 3))
    rot[:, 0, 0], rot[:, 0, 1], rot[:, 0, 2] = (
        cg * cb,
        cg * sb * sa - sg * ca,
        cg * sb * ca + sg * sa,
    )
    rot[:, 1, 0], rot[:, 1, 1], rot[:, 1, 2] = (
        sg * cb,
        sg * sb * sa + cg * ca,
        sg * sb * ca - cg * sa,
    )
    rot[:, 2, 0], rot[:, 2, 1], rot[:, 2, 2] = -sb, cb * sa, cb * ca
    return rot


_LAST_ROTATION: dict[bytes, np.ndarray] = {}


def _rotation_cached(angles: np.ndarray) -> np.ndarray:
    """:func:`rotation`, remembering the last poses' (the six legs of one call share them)."""
    key = angles.tobytes()
    if key not in _LAST_ROTATION:
        _LAST_ROTATION.clear()
        _LAST_ROTATION[key] = rotation(angles)
    return _LAST_ROTATION[key]


def _leg_vectors(phi: np.ndarray, poses: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r = np.atleast_2d(np.asarray(poses, dtype=float))
    rot = _rotation_cached(np.ascontiguousarray(r[:, 3:]))
    return r[:, :3] + rot @ phi[3:6] - phi[:3], rot


def leg_ik(phi: np.ndarray, poses: np.ndarray) -> np.ndarray:
    """Reading ``ψ = (|p + R b − a| − ρ0) / k`` at poses (N, 6), shape (N,)."""
    v, _ = _leg_vectors(phi, poses)
    return (np.linalg.norm(v, axis=1) - phi[6]) / phi[7]


def leg_jacobian(phi: np.ndarray, poses: np.ndarray) -> np.ndarray:
    """Analytic ``∂ψ/∂φ`` (N, 8): with ``d = |v|``, ``u = v/d``: ``∂d/∂a = −u``,
    ``∂d/∂b = Rᵀu``; ``∂ψ/∂(a, b) = ∂d/k``, ``∂ψ/∂ρ0 = −1/k``, ``∂ψ/∂k = −ψ/k``."""
    v, rot = _leg_vectors(phi, poses)
    d = np.linalg.norm(v, axis=1)
    u = v / d[:, None]
    k = phi[7]
    psi = (d - phi[6]) / k
    dbu = np.einsum("nij,ni->nj", rot, u)
    return np.column_stack([-u / k, dbu / k, np.full(len(d), -1.0 / k), -psi / k])


def _box(poses: np.ndarray, center: np.ndarray, half: np.ndarray) -> np.ndarray:
    return np.all(np.abs(np.atleast_2d(poses) - center) <= half * (1 + 1e-12), axis=1)


def nominal_parameters() -> list[np.ndarray]:
    """Nominal ``φκ`` of the six legs (base joint κ joins platform joint κ)."""
    phis = []
    for i in range(3):
        for side in (-1, 1):
            ab = np.deg2rad(120.0 * i) + side * BASE_HALF_GAP
            # each base pair reaches to the nearest platform joints of the two neighbouring pairs
            ap = np.deg2rad(120.0 * i + 60.0 * side) - side * PLATFORM_HALF_GAP
            a = BASE_RADIUS * np.array([np.cos(ab), np.sin(ab), 0.0])
            b = PLATFORM_RADIUS * np.array([np.cos(ap), np.sin(ap), 0.0])
            phis.append(np.r_[a, b, RHO0, GAIN])
    return phis


def mechanism(min_conditioning: float = 0.05) -> Mechanism:
    """The 6-UPS with its nominal design; every leg's eight parameters are identified
    (identifiable from pose and reading measurements — tested). Calibration region: the box
    about the home pose where the pose Jacobian's inverse condition number (angles scaled by
    the platform radius) is at least ``min_conditioning``."""
    legs = tuple(
        Leg(tuple(f"{n}{k + 1}" for n in PARAM_NAMES), UNITS, p, leg_ik, leg_jacobian)
        for k, p in enumerate(nominal_parameters())
    )
    lo, hi = box()
    center, half = (lo + hi) / 2, (hi - lo) / 2
    return Mechanism(
        "6-UPS Gough–Stewart",
        legs,
        ("x", "y", "z", "alpha", "beta", "gamma"),
        ("m", "m", "m", "rad", "rad", "rad"),
        partial(_box, center=center, half=half),
        f"|x|, |y| <= {HALF_XY} m, |z - {HOME_Z}| <= {HALF_Z} m, |angles| <= {HALF_ANGLE} rad",
        min_conditioning=check_float("min_conditioning", min_conditioning, low=0.0, high=1.0),
        length_scale=PLATFORM_RADIUS,
    )


def box(mech: Mechanism | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Low and high corners of the calibration box."""
    half = np.array([HALF_XY, HALF_XY, HALF_Z, HALF_ANGLE, HALF_ANGLE, HALF_ANGLE])
    center = np.array([0.0, 0.0, HOME_Z, 0.0, 0.0, 0.0])
    return center - half, center + half
