"""Computational cost of identification against the number of legs (thesis Table 6).

Table 6 states the inversion cost of the normal matrix as ∝ N³·n_limbs³ for the traditional
method and ∝ N³·n_limbs for divide and conquer: a ratio of n_limbs². The normal matrix ``CᵀC``
is *parameters × parameters*: ``(n_limbs·nκ)²`` for the traditional method and ``nκ²`` per leg
for D&C, so the inversion flops are ``(n_limbs·nκ)³`` against ``n_limbs·nκ³`` — the same ratio
n_limbs². Here both are counted and the solve of the normal equations is timed.
"""

from __future__ import annotations

import time

import numpy as np
from scipy.linalg import block_diag
from threadpoolctl import threadpool_limits

from mechlib.calibration.mechanism import Mechanism
from mechlib.params import check_int


def normal_sizes(mech: Mechanism) -> dict[str, int]:
    """Sizes of the normal matrices and the cubic flop counts of their inversion."""
    n_leg = mech.legs[0].size
    total = n_leg * mech.n_limbs
    return {
        "n_limbs": mech.n_limbs,
        "n_leg": n_leg,
        "trad_size": total,
        "dc_size": n_leg,
        "trad_flops": total**3,
        "dc_flops": mech.n_limbs * n_leg**3,
        "flop_ratio": total**3 / (mech.n_limbs * n_leg**3),
    }


def _median_time(fun, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fun()
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


def time_normal_solves(mech: Mechanism, poses: object, repeats: int = 200) -> dict[str, float]:
    """Median time [s] of one Gauss–Newton step's normal-equation solve, both strategies.

    At ``poses`` (N, d): the traditional step forms ``CᵀC`` of the dense total matrix
    (n_limbs·N × n_limbs·nκ) and solves it; D&C forms and solves each leg's ``CκᵀCκ``. One
    thread, so that the ratio compares work rather than parallelism.
    """
    repeats = check_int("repeats", repeats, low=1, high=100_000)
    r = np.asarray(poses, dtype=float)
    legs = [leg.jacobian(leg.nominal, r) for leg in mech.legs]
    total = block_diag(*legs)
    rhs = np.ones(total.shape[0])
    rhs_leg = np.ones(len(r))

    def trad() -> None:
        np.linalg.solve(total.T @ total, total.T @ rhs)

    def dc() -> None:
        for c in legs:
            np.linalg.solve(c.T @ c, c.T @ rhs_leg)

    with threadpool_limits(1):
        t_trad, t_dc = _median_time(trad, repeats), _median_time(dc, repeats)
    return {"trad": t_trad, "dc": t_dc, "ratio": t_trad / t_dc}
