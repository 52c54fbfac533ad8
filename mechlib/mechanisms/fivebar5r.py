"""The planar 5R of the thesis (sec. 3.7) as an instance of the leg-wise calibration core.

Leg κ's reading and identification Jacobian are the RR dyad's (:mod:`mechlib.dyad`,
which the 5R chapter's :mod:`mechlib.fivebar.kinematics` and :mod:`mechlib.fivebar.identification`
call too; Eq 21's parameters ``[l, L, Ax, Ay, k, γ]``); forward kinematics is the closed-form
circle intersection. The calibration region is a disc around the MIW centre (``fraction`` of its
radius).
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import partial

import numpy as np

from mechlib import dyad
from mechlib import published as pub
from mechlib.calibration.mechanism import Leg, Mechanism
from mechlib.fivebar import kinematics as kin
from mechlib.params import check_float

UNITS = ("m", "m", "m", "m", "-", "rad")
"""Units of Eq 21's parameters."""


def _ik(phi: np.ndarray, poses: np.ndarray, mode: int) -> np.ndarray:
    return dyad.reading(np.atleast_2d(poses), phi, mode)


def _jac(phi: np.ndarray, poses: np.ndarray, mode: int) -> np.ndarray:
    return dyad.jacobian(np.atleast_2d(poses), phi, mode)


def _forward(phis: Sequence[np.ndarray], q: np.ndarray, guess: np.ndarray) -> np.ndarray:
    return kin.forward(q[:, 0], q[:, 1], phis[0], phis[1])


def _disc(poses: np.ndarray, center: tuple[float, float], radius: float) -> np.ndarray:
    r = np.atleast_2d(poses)
    return np.hypot(r[:, 0] - center[0], r[:, 1] - center[1]) <= radius * (1 + 1e-12)


def legs(nominal: dict[str, float], modes: tuple[int, int] = kin.NOMINAL_MODES) -> tuple[Leg, ...]:
    """The two legs with Table 7-style nominal values."""
    return tuple(
        Leg(
            kin.leg_keys(k),
            UNITS,
            kin.leg_vector(nominal, k),
            partial(_ik, mode=modes[k - 1]),
            partial(_jac, mode=modes[k - 1]),
        )
        for k in (1, 2)
    )


def mechanism(fraction: float = 0.8) -> Mechanism:
    """The thesis's 5R (Table 7 nominal), calibrated inside ``fraction`` of its MIW radius."""
    fraction = check_float("fraction", fraction, low=0.0, high=1.0, low_open=True)
    lg = legs(pub.TABLE7_NOMINAL)
    nom = lg[0].nominal
    miw = kin.miw_closed_form(nom[0], nom[1], abs(nom[2]))
    center, radius = (miw["cx"], miw["cy"]), fraction * miw["radius"]
    return Mechanism(
        "planar 5R",
        lg,
        ("x", "y"),
        ("m", "m"),
        partial(_disc, center=center, radius=radius),
        f"the disc of radius {radius:.4g} m about ({center[0]:g}, {center[1]:.4g}) m",
        forward=_forward,
    )


def real_parameters() -> tuple[np.ndarray, np.ndarray]:
    """Table 7's disturbed (real) parameters."""
    return kin.leg_vector(pub.TABLE7_REAL, 1), kin.leg_vector(pub.TABLE7_REAL, 2)
