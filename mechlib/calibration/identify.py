"""Inverse calibration of a parallel mechanism, leg by leg or all at once (thesis Eqs 16–19, 24–26).

For leg κ, measured poses ``R̂`` and readings ``Q̂κ``, the residual is ``Q̂κ − gκ(φκ, R̂)`` and its
Jacobian ``Cκ`` (Eq 17). *Divide and conquer* solves each leg on its own pose set; the
*traditional* method solves every parameter at once on one shared pose set, with the total
matrix ``C = diag(C1, …, Cn)`` (leg κ's reading depends only on φκ). Both solve by
Levenberg–Marquardt (``scipy.optimize.least_squares(method="lm")``, the default) or by the
thesis's Gauss–Newton iteration (Eq 26, ``solver="gn"``): ``Δφ = (CᵀC)⁻¹ Cᵀ ΔQ`` (a least-squares
solve) until the largest step is below :data:`GN_TOL`. Identifiability is the rank of the
column-scaled ``C`` and its minimal parameter set the pivots of a QR factorisation with column
pivoting.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.linalg import block_diag, qr
from scipy.optimize import least_squares

from mechlib.calibration.mechanism import Leg, Mechanism, check_phis
from mechlib.params import check_choice

#: Relative threshold on |R_ii| / |R_00| of the pivoted QR below which a column is dependent.
RANK_TOL = 1e-9
#: Levenberg–Marquardt tolerances (MINPACK needs them above machine epsilon).
LM_TOL = 1e-14
#: Gauss–Newton (Eq 26): stop when the largest parameter step is below GN_TOL [m, rad, gain];
#: a fit still moving after GN_MAX_ITER iterations has not converged.
GN_TOL = 1e-12
GN_MAX_ITER = 50
#: The solvers: Levenberg–Marquardt (SciPy's MINPACK) and the thesis's Gauss–Newton (Eq 26).
SOLVERS = ("lm", "gn")


@dataclass(frozen=True)
class Fit:
    """Identified parameters (one leg, or every leg stacked), function evaluations
    (Levenberg–Marquardt) or iterations (Gauss–Newton), residual RMS and whether the solver
    reported convergence."""

    phi: np.ndarray
    evaluations: int
    residual_rms: float
    converged: bool


def identifiability(c: object, names: Sequence[str]) -> dict[str, object]:
    """Rank and minimal parameter set of an identification matrix.

    Columns are scaled to unit norm (parameters of different units), then factorised by QR with
    column pivoting: the first ``rank`` pivots form a minimal identifiable set, the others are
    (numerically) combinations of them.

    Returns
    -------
    dict
        ``rank`` (int), ``identifiable`` and ``dependent`` (tuples of names), ``conditioning``
        (inverse condition number of the scaled matrix).
    """
    c = np.asarray(c, dtype=float)
    if c.ndim != 2 or c.shape[1] != len(names):
        raise ValueError(f"C must be (equations, {len(names)}) for {names}, got {c.shape}")
    scale = np.linalg.norm(c, axis=0)
    cs = c / np.where(scale > 0, scale, 1.0)
    _, r, piv = qr(cs, mode="economic", pivoting=True)
    diag = np.abs(np.diag(r))
    rank = int(np.sum(diag > RANK_TOL * diag[0])) if diag.size and diag[0] > 0 else 0
    s = np.linalg.svd(cs, compute_uv=False)
    return {
        "rank": rank,
        "identifiable": tuple(names[i] for i in sorted(piv[:rank])),
        "dependent": tuple(names[i] for i in sorted(piv[rank:])),
        "conditioning": float(s[-1] / s[0]) if s[0] > 0 else 0.0,
    }


def check_identifiable(c: object, names: Sequence[str]) -> None:
    """Raise ``ValueError`` if ``C`` has fewer equations than parameters or is rank-deficient,
    naming the parameters the pose set leaves unidentifiable."""
    c = np.asarray(c, dtype=float)
    if c.shape[0] < c.shape[1]:
        raise ValueError(
            f"pose budget too small: {c.shape[0]} equations cannot identify {c.shape[1]} "
            f"parameters {tuple(names)}; allowed: at least {c.shape[1]} equations"
        )
    info = identifiability(c, names)
    if info["rank"] < c.shape[1]:
        raise ValueError(
            f"the poses leave {info['dependent']} unidentifiable (rank {info['rank']} of "
            f"{c.shape[1]}): choose other poses or drop them from the parameter set"
        )


def check_solver(solver: str) -> str:
    """``solver`` if it is one of :data:`SOLVERS`, else ``ValueError``."""
    return check_choice("solver", solver, SOLVERS)


def _gauss_newton(fun, jac, x0: np.ndarray) -> tuple[np.ndarray, int, float, bool]:
    """Eq 26 iterated: ``x ← x + lstsq(C, −r)``; converged when the step is below GN_TOL."""
    x, step, it = x0.copy(), np.inf, 0
    for it in range(1, GN_MAX_ITER + 1):  # noqa: B007 - the count is reported
        dx = np.linalg.lstsq(jac(x), -fun(x), rcond=None)[0]
        x = x + dx
        step = float(np.max(np.abs(dx)))
        if not step >= GN_TOL:  # below the tolerance, or not finite
            break
    res = fun(x) if np.all(np.isfinite(x)) else np.full(1, np.nan)
    return x, it, float(np.sqrt(np.mean(res**2))), bool(step < GN_TOL)


def _fit(fun, jac, x0: np.ndarray, solver: str) -> tuple[np.ndarray, int, float, bool]:
    if check_solver(solver) == "gn":
        return _gauss_newton(fun, jac, x0)
    sol = least_squares(
        fun, x0, jac=jac, method="lm", x_scale="jac", xtol=LM_TOL, ftol=LM_TOL, gtol=LM_TOL
    )
    return sol.x, int(sol.nfev), float(np.sqrt(np.mean(sol.fun**2))), bool(sol.status > 0)


def identify_leg(
    leg: Leg,
    poses: object,
    q: object,
    phi0: object | None = None,
    *,
    check: bool = True,
    solver: str = "lm",
) -> Fit:
    """Identify one leg from its own measured poses and readings (divide and conquer).

    Parameters
    ----------
    leg : Leg
    poses : array_like, shape (N, d)
        Measured end-effector poses.
    q : array_like, shape (N,)
        Measured readings of this leg.
    phi0 : array_like, optional
        Starting parameters; default the nominal ones.
    check : bool
        Check identifiability first (a Monte Carlo checks its pose sets once).
    solver : {"lm", "gn"}
        Levenberg–Marquardt or Gauss–Newton (Eq 26); both stop at the least-squares solution.

    Raises
    ------
    ValueError
        If the poses cannot identify the leg's parameters (too few, or rank-deficient).
    """
    r = np.asarray(poses, dtype=float)
    qk = np.asarray(q, dtype=float)
    x0 = leg.check_phi(leg.nominal if phi0 is None else phi0)
    if qk.shape != (len(r),):
        raise ValueError(f"q must have one reading per pose ({len(r)}), got shape {qk.shape}")
    if check:
        check_identifiable(leg.jacobian(x0, r), leg.names)
    x, nfev, rms, ok = _fit(lambda p: leg.ik(p, r) - qk, lambda p: leg.jacobian(p, r), x0, solver)
    return Fit(x, nfev, rms, ok)


def total_jacobian(mech: Mechanism, phis: Sequence[object], poses: object) -> np.ndarray:
    """Traditional total identification matrix over shared poses: ``diag(C1, …, Cn)``, shape
    (n_limbs·N, Σnκ), rows grouped by leg."""
    phis = check_phis(mech, phis)
    r = np.asarray(poses, dtype=float)
    return block_diag(*[leg.jacobian(p, r) for leg, p in zip(mech.legs, phis, strict=True)])


def identify_traditional(
    mech: Mechanism,
    poses: object,
    q: object,
    phis0: Sequence[object] | None = None,
    *,
    check: bool = True,
    solver: str = "lm",
) -> Fit:
    """Identify every parameter at once from one shared pose set (Eq 19 on the total matrix).

    Parameters
    ----------
    mech : Mechanism
    poses : array_like, shape (N, d)
    q : array_like, shape (N, n_limbs)
        Readings of every leg at every pose.
    phis0 : sequence of array_like, optional
        Starting parameters per leg; default the nominal ones.
    check : bool
        Check identifiability first.
    solver : {"lm", "gn"}
        As for :func:`identify_leg`.

    Returns
    -------
    Fit
        ``phi`` is every leg's parameters stacked.
    """
    r = np.asarray(poses, dtype=float)
    qa = np.asarray(q, dtype=float)
    phis0 = check_phis(mech, mech.nominal if phis0 is None else phis0)
    if qa.shape != (len(r), mech.n_limbs):
        raise ValueError(
            f"q must be (N, {mech.n_limbs}) = ({len(r)}, {mech.n_limbs}), got {qa.shape}"
        )
    if check:
        check_identifiable(total_jacobian(mech, phis0, r), mech.names)
    cuts = np.cumsum([leg.size for leg in mech.legs])[:-1]
    target = qa.T.ravel()

    def fun(x: np.ndarray) -> np.ndarray:
        parts = np.split(x, cuts)
        return (
            np.concatenate([leg.ik(p, r) for leg, p in zip(mech.legs, parts, strict=True)]) - target
        )

    x, nfev, rms, ok = _fit(
        fun, lambda x: total_jacobian(mech, np.split(x, cuts), r), np.concatenate(phis0), solver
    )
    return Fit(x, nfev, rms, ok)


def split(mech: Mechanism, phi: object) -> tuple[np.ndarray, ...]:
    """Stacked parameters back into one vector per leg."""
    phi = np.asarray(phi, dtype=float)
    return tuple(np.split(phi, np.cumsum([leg.size for leg in mech.legs])[:-1]))
