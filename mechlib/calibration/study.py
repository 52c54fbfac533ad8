"""Divide and conquer against traditional calibration on any :class:`Mechanism`: the study
(mechanism, real parameters, candidate and evaluation poses, solver), the budgets, the pose
selection and the conditioning of the selected sets. The seeded Monte Carlo is
:mod:`.montecarlo`'s, its statistics :mod:`.statistics`'.

Strategies (thesis sec. 3.7 items 8 and 10, generalised to n_limbs legs):

- ``dc``: ``n`` poses selected for each leg on its own matrix ``Cκ``; leg κ identified from its
  own poses (the pose and that leg's reading at each);
- traditional: ``n_shared`` poses selected on the total matrix; every parameter identified at
  once from the shared poses (the pose and every reading at each).

Budgets of the traditional method (Table 8's accounting: a measurement is one pose coordinate or
one joint reading; d pose coordinates): D&C measures ``n_limbs · n · (d + 1)``; a shared pose
costs ``d + n_limbs``.

- ``thesis``: ``n_limbs · n`` shared poses, as many poses as D&C (sec. 3.7 item 10: 36 against
  2 × 18 on the 5R);
- ``equations``: ``n`` shared poses, so that each leg gets as many equations as in D&C (the count
  behind Table 8's printed traditional cost, 2 · 18 · 2 = 72 on the 5R);
- ``matched``: as many measurements as D&C (rounded to whole poses).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from threadpoolctl import threadpool_limits

from mechlib.calibration import identify as ci
from mechlib.calibration import mechanism as cm
from mechlib.calibration import selection as sel
from mechlib.params import check_float, check_int

#: Every budget of the traditional method, and the two that "Beyond the 5R" compares.
ALL_BUDGETS = ("thesis", "equations", "matched")
BUDGETS = ("thesis", "matched")


@dataclass(frozen=True)
class Study:
    """A mechanism with its real parameters, candidate poses, evaluation grid and solver.

    ``scale`` is the standard deviation of each parameter's disturbance (parameter errors are
    reported in these units); ``jac_candidates`` and ``jac_grid`` are the pose Jacobians at the
    nominal parameters, reused as the chord of the forward kinematics; ``solver`` is the
    identification's (:data:`mechlib.calibration.identify.SOLVERS`).
    """

    mech: cm.Mechanism
    real: tuple[np.ndarray, ...]
    candidates: np.ndarray
    grid: np.ndarray
    scale: np.ndarray
    jac_candidates: np.ndarray
    jac_grid: np.ndarray
    solver: str = "lm"


def make_study(
    mech: cm.Mechanism,
    real: Sequence[object],
    candidates: object,
    grid: object,
    scale: object,
    solver: str = "lm",
) -> Study:
    """Validate and assemble a :class:`Study` (poses must lie in the calibration region).

    Raises
    ------
    ValueError
        Real parameters of the wrong shape, a pose outside the calibration region, a scale that
        is not positive, or an unknown solver.
    """
    real = cm.check_phis(mech, real)
    cand = cm.check_poses(mech, candidates, "candidates")
    grid = cm.check_poses(mech, grid, "grid")
    sc = np.asarray(scale, dtype=float)
    if sc.shape != (len(mech.names),) or np.any(sc <= 0):
        raise ValueError(f"scale must be {len(mech.names)} positive numbers, got {sc}")
    solver = ci.check_solver(solver)
    with threadpool_limits(1):
        jc = cm.pose_jacobian(mech, mech.nominal, cand)
        jg = cm.pose_jacobian(mech, mech.nominal, grid)
    return Study(mech, real, cand, grid, sc, jc, jg, solver)


def disturbed(
    mech: cm.Mechanism, scale_by_unit: Mapping[str, float], rng: np.random.Generator
) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
    """Real parameters: nominal plus Gaussian errors whose standard deviation depends on the
    unit (thesis sec. 3.7 item 4). Returns the real parameters and the per-parameter scale."""
    units = [u for leg in mech.legs for u in leg.units]
    missing = sorted(set(units) - set(scale_by_unit))
    if missing:
        raise ValueError(f"scale_by_unit needs a standard deviation for units {missing}")
    scale = np.array(
        [check_float(f"scale[{u}]", scale_by_unit[u], low=0.0, low_open=True) for u in units]
    )
    real = np.concatenate(mech.nominal) + rng.normal(0.0, scale)
    return ci.split(mech, real), scale


def budgets(mech: cm.Mechanism, n_per_leg: int, names: Sequence[str] = BUDGETS) -> dict[str, int]:
    """Shared poses of the traditional method under each budget of ``names`` (see the module's
    docstring) against ``n_per_leg`` D&C poses per leg.

    Raises
    ------
    ValueError
        A pose count below 1 or a budget not in :data:`ALL_BUDGETS`.
    """
    n = check_int("n_per_leg", n_per_leg, low=1)
    unknown = sorted(set(names) - set(ALL_BUDGETS))
    if unknown:
        raise ValueError(f"budgets must be among {list(ALL_BUDGETS)}, got {unknown}")
    dc = measurement_counts(mech, n, 0)["dc"]
    shared = {
        "thesis": mech.n_limbs * n,
        "equations": n,
        "matched": round(dc / (mech.dof + mech.n_limbs)),
    }
    return {b: shared[b] for b in names}


def measurement_breakdown(
    mech: cm.Mechanism, n_per_leg: int, n_shared: int
) -> dict[str, dict[str, int]]:
    """Per strategy (``dc``, ``trad``): measured ``poses``, their pose ``coordinates``, the joint
    ``readings`` used and the ``total`` of coordinates and readings (Table 8's cost).

    D&C measures each leg's ``n_per_leg`` poses and reads that leg's joint at each; the
    traditional method measures ``n_shared`` poses and reads every joint at each.
    """
    dc_poses = mech.n_limbs * n_per_leg
    out = {
        "dc": {"poses": dc_poses, "coordinates": mech.dof * dc_poses, "readings": dc_poses},
        "trad": {
            "poses": n_shared,
            "coordinates": mech.dof * n_shared,
            "readings": mech.n_limbs * n_shared,
        },
    }
    for c in out.values():
        c["total"] = c["coordinates"] + c["readings"]
    return out


def measurement_counts(mech: cm.Mechanism, n_per_leg: int, n_shared: int) -> dict[str, int]:
    """Measurements (pose coordinates + joint readings) of D&C and of the traditional method."""
    return {k: c["total"] for k, c in measurement_breakdown(mech, n_per_leg, n_shared).items()}


def check_count(study: Study, name: str, n: int) -> int:
    """``n`` poses if at least a leg's parameter count and at most the candidates."""
    low = max(leg.size for leg in study.mech.legs)
    return check_int(
        f"{name} (poses; parameters per leg = {low})", n, low=low, high=len(study.candidates)
    )


def select_dc(study: Study, n_per_leg: int) -> list[np.ndarray]:
    """Active-calibration selection of ``n_per_leg`` poses for each leg on its own matrix."""
    n = check_count(study, "n_per_leg", n_per_leg)
    with threadpool_limits(1):
        return [
            sel.select_active(leg.jacobian(leg.nominal, study.candidates), n)
            for leg in study.mech.legs
        ]


def select_traditional(study: Study, n_shared: int) -> np.ndarray:
    """Active-calibration selection of ``n_shared`` shared poses on the total matrix."""
    n = check_count(study, "n_shared", n_shared)
    with threadpool_limits(1):
        return sel.select_shared(
            [leg.jacobian(leg.nominal, study.candidates) for leg in study.mech.legs], n
        )


def conditioning(
    study: Study, dc_sets: Sequence[np.ndarray], trad_sets: Mapping[str, np.ndarray]
) -> dict[str, float]:
    """Inverse condition number (columns scaled) of the identification matrices at the nominal
    parameters: the worst D&C leg (``dc``) and the traditional total matrix of each of
    ``trad_sets`` (by its key)."""
    m, cand = study.mech, study.candidates
    legs = [
        ci.identifiability(leg.jacobian(leg.nominal, cand[idx]), leg.names)["conditioning"]
        for leg, idx in zip(m.legs, dc_sets, strict=True)
    ]
    out = {"dc": float(min(legs))}
    for b, idx in trad_sets.items():
        out[b] = ci.identifiability(ci.total_jacobian(m, m.nominal, cand[idx]), m.names)[
            "conditioning"
        ]
    return out


def position_errors(study: Study, phis: Sequence[object]) -> np.ndarray:
    """|position error| [m] at each grid pose when commanding with the model ``phis`` (one
    vector per leg): the real mechanism reaches the forward kinematics of the real parameters."""
    e = cm.pose_errors(study.mech, phis, study.real, study.grid)
    return np.linalg.norm(e[:, ~study.mech.angular], axis=1)
