"""The three mechanisms of the "Beyond the 5R" study, each assembled into a
:class:`mechlib.calibration.study.Study`: nominal design, real (disturbed) parameters, candidate
poses and the evaluation poses (a regular slice of the workspace, for the maps, then random poses
over the whole calibration region). The 5R is its chapter's study
(:func:`mechlib.fivebar.mechanism.study`), with the chapter's settings by default.

A composition root, like :mod:`mechlib.fespecs`: it names mechanisms of several packages
(:mod:`mechlib.fivebar`, :mod:`mechlib.mechanisms`), so it sits above them, in none of them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechlib.calibration import mechanism as cm
from mechlib.calibration import study as st
from mechlib.fivebar import mechanism as fivebar
from mechlib.mechanisms import gough_stewart, rrr3
from mechlib.params import check_choice, check_float, check_int

NAMES = ("5R", "3-RRR", "6-UPS")
#: Share of the 5R's MIW radius inside which its candidate poses lie (the thesis's workspace).
FIVEBAR_FRACTION = fivebar.FRACTION


@dataclass(frozen=True)
class Built:
    """A study and how many of its evaluation poses form the regular slice (first ``n_slice``)."""

    study: st.Study
    n_slice: int


def _slice(lo: np.ndarray, hi: np.ndarray, points: int) -> np.ndarray:
    """A ``points × points`` lattice over the first two pose coordinates at the box centre."""
    centre = (lo + hi) / 2
    xs = np.linspace(lo[0], hi[0], points)
    ys = np.linspace(lo[1], hi[1], points)
    xx, yy = np.meshgrid(xs, ys)
    out = np.tile(centre, (xx.size, 1))
    out[:, 0], out[:, 1] = xx.ravel(), yy.ravel()
    return out


def build(
    name: str,
    *,
    seed: int,
    disturbance: float,
    n_candidates: int,
    n_random_grid: int,
    slice_points: int,
    fivebar_fraction: float = FIVEBAR_FRACTION,
    fivebar_spacing: float = fivebar.CANDIDATE_SPACING,
    fivebar_grid_spacing: float = fivebar.GRID_SPACING,
    fivebar_solver: str = fivebar.SOLVER,
) -> Built:
    """Assemble the study of mechanism ``name``.

    Parameters
    ----------
    name : {"5R", "3-RRR", "6-UPS"}
    seed : int
        Seed of the real parameters and of the random poses.
    disturbance : float
        Standard deviation of every parameter's error (m, rad, and gain) for the 3-RRR and the
        6-UPS; the 5R uses Table 7's real parameters. Also the unit of the reported parameter
        errors (of all three).
    n_candidates : int
        Random candidate poses drawn in the box (3-RRR, 6-UPS; those not regular are dropped).
    n_random_grid : int
        Random evaluation poses after the slice (3-RRR, 6-UPS).
    slice_points : int
        Points per side of the regular evaluation slice (``x``–``y`` at the box centre; 3-RRR,
        6-UPS).
    fivebar_fraction, fivebar_spacing, fivebar_grid_spacing : float
        The 5R's calibration disc (share of the MIW radius), candidate and evaluation lattice
        spacings [m]; the 5R's evaluation poses are all its lattice (``n_slice`` = all).
    fivebar_solver : {"gn", "lm"}
        The 5R's identification solver: its chapter's Gauss–Newton (Eq 26) by default; the
        3-RRR and the 6-UPS are solved by Levenberg–Marquardt.
    """
    check_choice("mechanism", name, NAMES)
    seed = check_int("seed", seed, low=0)
    disturbance = check_float("disturbance", disturbance, low=0.0, low_open=True)
    n_candidates = check_int("n_candidates", n_candidates, low=10, high=100_000)
    n_random_grid = check_int("n_random_grid", n_random_grid, low=0, high=100_000)
    slice_points = check_int("slice_points", slice_points, low=3, high=200)
    rng = np.random.default_rng(seed)
    units = {"m": disturbance, "-": disturbance, "rad": disturbance}
    if name == "5R":
        study = fivebar.study(
            fivebar_fraction, fivebar_spacing, fivebar_grid_spacing, disturbance, fivebar_solver
        )
        return Built(study, len(study.grid))
    mod = rrr3 if name == "3-RRR" else gough_stewart
    mech = mod.mechanism()
    lo, hi = mod.box()
    real, scale = st.disturbed(mech, units, rng)
    candidates = cm.candidate_poses(mech, lo, hi, n_candidates, rng)
    sl = _slice(lo, hi, slice_points)
    sl = sl[cm.regular(mech, mech.nominal, sl)]
    grid = np.vstack([sl, cm.candidate_poses(mech, lo, hi, n_random_grid, rng)])
    study = st.make_study(mech, real, candidates, grid, scale)
    return Built(study, len(sl))
