"""The planar 5R of the thesis (sec. 3.7) as an instance of the leg-wise calibration core, and
the study its chapter runs.

Leg κ's reading and identification Jacobian are the RR dyad's (:mod:`mechlib.dyad`; Eq 21's
parameters ``[l, L, Ax, Ay, k, γ]``); forward kinematics is the closed-form circle intersection
of :mod:`mechlib.fivebar.kinematics`. The calibration region is a disc about the MIW centre
(``fraction`` of its radius). The study's candidate postures and evaluation grid are square
lattices in that disc, its real parameters Table 7's, its solver the thesis's Gauss–Newton
iteration (Eq 26). "Beyond the 5R" builds its 5R column with the same :func:`study`.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import partial

import numpy as np

from mechlib import dyad
from mechlib import published as pub
from mechlib.calibration.mechanism import Leg, Mechanism
from mechlib.calibration.study import Study, make_study
from mechlib.fivebar import kinematics as kin
from mechlib.params import check_float

UNITS = ("m", "m", "m", "m", "-", "rad")
"""Units of Eq 21's parameters."""
#: Share of the MIW radius inside which candidate postures and the grid lie (sec. 3.7: near the
#: MIW's boundary the real mechanism cannot assemble).
FRACTION = 0.8
#: Lattice spacing of the candidate postures and of the evaluation grid (Fig 14) [m].
CANDIDATE_SPACING = 0.02
GRID_SPACING = 0.05
#: σ_dist, the unit of the reported parameter errors [m, rad and gain]: about the RMS of Table
#: 7's real − nominal differences (3.7e-3), and "Beyond the 5R"'s default disturbance.
DISTURBANCE = 4e-3
#: The thesis's solver (Eq 26).
SOLVER = "gn"
#: The 5R chapter's names of the core's budgets (:mod:`mechlib.calibration.study`): sec. 3.7
#: item 10's 2 · n shared postures, Table 8's printed n, and equal measurement counts.
BUDGETS = {"item10": "thesis", "table8": "equations", "equal": "matched"}


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


def miw(mech: Mechanism) -> dict[str, float]:
    """Closed-form MIW of the mechanism's nominal legs (:func:`kinematics.miw_closed_form`)."""
    nom = mech.nominal[0]
    return kin.miw_closed_form(nom[0], nom[1], abs(nom[2]))


def mechanism(fraction: float = FRACTION) -> Mechanism:
    """The thesis's 5R (Table 7 nominal), calibrated inside ``fraction`` of its MIW radius."""
    fraction = check_float("fraction", fraction, low=0.0, high=1.0, low_open=True)
    lg = legs(pub.TABLE7_NOMINAL)
    nom = lg[0].nominal
    disc = kin.miw_closed_form(nom[0], nom[1], abs(nom[2]))
    center, radius = (disc["cx"], disc["cy"]), fraction * disc["radius"]
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


def disc_grid(center: tuple[float, float], radius: float, spacing: float) -> np.ndarray:
    """Square-lattice points with the given spacing [m] inside a disc."""
    spacing = check_float("spacing", spacing, low=0.0, low_open=True)
    n = int(np.ceil(radius / spacing))
    ax = np.arange(-n, n + 1) * spacing
    xx, yy = np.meshgrid(ax, ax)
    keep = xx**2 + yy**2 <= radius**2
    return np.column_stack([center[0] + xx[keep], center[1] + yy[keep]])


def study(
    fraction: float = FRACTION,
    candidate_spacing: float = CANDIDATE_SPACING,
    grid_spacing: float = GRID_SPACING,
    disturbance: float = DISTURBANCE,
    solver: str = SOLVER,
) -> Study:
    """The 5R chapter's calibration study: Table 7's real parameters, candidate postures and
    evaluation grid on lattices of the given spacings [m] inside ``fraction`` of the MIW radius,
    parameter errors in units of ``disturbance`` (σ_dist) and the identification ``solver``.

    Raises
    ------
    ValueError
        A fraction outside (0, 1], a spacing or disturbance that is not positive, or an unknown
        solver.
    """
    mech = mechanism(fraction)
    disc = miw(mech)
    center, radius = (disc["cx"], disc["cy"]), fraction * disc["radius"]
    disturbance = check_float("disturbance", disturbance, low=0.0, low_open=True)
    return make_study(
        mech,
        real_parameters(),
        disc_grid(center, radius, candidate_spacing),
        disc_grid(center, radius, grid_spacing),
        np.full(len(mech.names), disturbance),
        solver,
    )
