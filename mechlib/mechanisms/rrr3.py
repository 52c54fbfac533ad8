"""A planar 3-RRR parallel mechanism (three legs, pose ``r = (x, y, φ)``).

Leg κ is the 5R's RR dyad (:mod:`mechlib.dyad`): the proximal link ``lκ`` turns
about the base joint ``Aκ`` by ``θκ = kκ ψκ + γκ``; the distal link ``Lκ`` joins its elbow to the
platform joint ``Cκ = (x, y) + R(φ) cκ``, where ``cκ`` is the platform attachment in the
platform frame. Leg parameters (the 5R's Eq 21): ``φκ = [lκ, Lκ, Aκx, Aκy, kκ, γκ]``; the platform
attachments are known (the stated minimal set of the study: see :func:`mechanism`). The
nominal design is symmetric: base joints on a circle of radius ``base_radius`` at 90°, 210°
and 330°, platform joints on one of radius ``platform_radius`` at the same angles, every elbow
on the same side (working mode +1), each zero reading pointing at the centre.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import partial

import numpy as np

from mechlib import dyad
from mechlib.calibration.mechanism import Leg, Mechanism
from mechlib.params import check_float

UNITS = ("m", "m", "m", "m", "-", "rad")
#: Angular positions of the legs on the base and platform circles [rad].
LEG_ANGLES = np.deg2rad([90.0, 210.0, 330.0])
#: Nominal design [m]: base and platform circle radii, proximal and distal link lengths.
BASE_RADIUS, PLATFORM_RADIUS, PROXIMAL, DISTAL = 0.6, 0.15, 0.35, 0.35
#: Working mode of every leg (elbow side).
MODE = 1
#: Calibration box: |x|, |y| <= HALF_SIDE [m], |φ| <= HALF_ANGLE [rad].
HALF_SIDE, HALF_ANGLE = 0.1, 0.3


def platform_points(poses: object, attachment: object) -> np.ndarray:
    """Platform joint ``C = (x, y) + R(φ) c`` for poses (N, 3), shape (N, 2)."""
    r = np.atleast_2d(np.asarray(poses, dtype=float))
    c = np.asarray(attachment, dtype=float)
    cos, sin = np.cos(r[:, 2]), np.sin(r[:, 2])
    return np.column_stack([r[:, 0] + cos * c[0] - sin * c[1], r[:, 1] + sin * c[0] + cos * c[1]])


def _ik(phi: np.ndarray, poses: np.ndarray, attachment: np.ndarray) -> np.ndarray:
    return dyad.reading(platform_points(poses, attachment), phi, MODE)


def _jac(phi: np.ndarray, poses: np.ndarray, attachment: np.ndarray) -> np.ndarray:
    return dyad.jacobian(platform_points(poses, attachment), phi, MODE)


def _box(poses: np.ndarray, half: np.ndarray) -> np.ndarray:
    return np.all(np.abs(np.atleast_2d(poses)) <= half * (1 + 1e-12), axis=1)


def nominal_legs(
    base_radius: float = BASE_RADIUS,
    platform_radius: float = PLATFORM_RADIUS,
    proximal: float = PROXIMAL,
    distal: float = DISTAL,
) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Nominal ``φκ`` and platform attachments ``cκ`` of the three legs."""
    for name, v in (("base_radius", base_radius), ("platform_radius", platform_radius)):
        check_float(f"{name} [m]", v, low=0.0, low_open=True)
    for name, v in (("proximal", proximal), ("distal", distal)):
        check_float(f"{name} [m]", v, low=0.0, low_open=True)
    if platform_radius >= base_radius:
        raise ValueError(
            f"platform_radius must be < base_radius = {base_radius} m, got {platform_radius} m"
        )
    gap = base_radius - platform_radius
    if not abs(proximal - distal) < gap < proximal + distal:
        raise ValueError(
            f"the legs cannot reach the centred pose: base_radius − platform_radius = {gap} m "
            f"must lie in (|l − L|, l + L) = ({abs(proximal - distal)}, {proximal + distal}) m"
        )
    phis, atts = [], []
    for a in LEG_ANGLES:
        u = np.array([np.cos(a), np.sin(a)])
        phis.append(np.array([proximal, distal, *(base_radius * u), 1.0, a + np.pi]))
        atts.append(platform_radius * u)
    return phis, atts


def mechanism(min_conditioning: float = 0.05, **design: float) -> Mechanism:
    """The 3-RRR with nominal design ``design`` (see :func:`nominal_legs`).

    Identified per leg: ``[l, L, Ax, Ay, k, γ]`` (six parameters, identifiable — tested); the
    platform attachments ``cκ`` are taken as known. Calibration region: the box
    ``|x|, |y| <= 0.1 m, |φ| <= 0.3 rad`` where the pose Jacobian's inverse condition number
    (angles scaled by the platform radius) is at least ``min_conditioning``.
    """
    phis, atts = nominal_legs(**design)
    legs = tuple(
        Leg(
            tuple(f"{n}{k + 1}" for n in ("l", "L", "Ax", "Ay", "k", "gamma")),
            UNITS,
            p,
            partial(_ik, attachment=c),
            partial(_jac, attachment=c),
        )
        for k, (p, c) in enumerate(zip(phis, atts, strict=True))
    )
    half = np.array([HALF_SIDE, HALF_SIDE, HALF_ANGLE])
    return Mechanism(
        "planar 3-RRR",
        legs,
        ("x", "y", "phi"),
        ("m", "m", "rad"),
        partial(_box, half=half),
        f"|x|, |y| <= {HALF_SIDE} m and |phi| <= {HALF_ANGLE} rad",
        min_conditioning=check_float("min_conditioning", min_conditioning, low=0.0, high=1.0),
        length_scale=design.get("platform_radius", PLATFORM_RADIUS),
    )


def box(mech: Mechanism | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Low and high corners of the calibration box."""
    half = np.array([HALF_SIDE, HALF_SIDE, HALF_ANGLE])
    return -half, half


def leg_chains(mech: Mechanism, phis: Sequence[np.ndarray], pose: object) -> list[np.ndarray]:
    """Base, elbow and platform joint of every leg at one pose, each (3, 2) [m] (for figures)."""
    r = np.atleast_2d(np.asarray(pose, dtype=float))
    q = np.array([leg.ik(p, r)[0] for leg, p in zip(mech.legs, phis, strict=True)])
    out = []
    for leg, p, qk in zip(mech.legs, phis, q, strict=True):
        c = platform_points(r, leg.ik.keywords["attachment"])[0]
        b = dyad.elbow(np.array([qk]), np.asarray(p, dtype=float))[0]
        out.append(np.vstack([p[2:4], b, c]))
    return out
