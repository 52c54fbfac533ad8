"""Speed benchmarks (``make bench``): ratios measured in one run, never asserted in tests.

Posture selection at 10⁴ candidates: the active-calibration search with determinant and
Woodbury updates against the same search scoring every candidate by an SVD.
"""

from __future__ import annotations

import time

import numpy as np

from mechlib import published as pub
from mechlib.fivebar import identification as idf
from mechlib.fivebar import kinematics as kin
from mechlib.fivebar import postures as ps
from mechlib.fivebar.study import disc_grid

N_CANDIDATES = 10_000
N_SELECT = 18


def posture_selection() -> dict[str, float]:
    """Time both selection implementations on ~10⁴ candidates of leg 1 (greedy phase only)."""
    phi1 = kin.leg_vector(pub.TABLE7_NOMINAL, 1)
    miw = kin.miw_closed_form(phi1[0], phi1[1], abs(phi1[2]))
    radius = 0.8 * miw["radius"]
    spacing = radius * np.sqrt(np.pi / N_CANDIDATES)
    cands = disc_grid((0.0, miw["cy"]), radius, spacing)
    c1 = idf.identification_jacobian(cands, phi1, 1)
    t0 = time.perf_counter()
    fast = ps.select_active(c1, N_SELECT, max_passes=0)
    t1 = time.perf_counter()
    slow = ps.select_reference_svd(c1, N_SELECT, max_passes=0)
    t2 = time.perf_counter()
    return {
        "candidates": len(cands),
        "active_s": t1 - t0,
        "svd_s": t2 - t1,
        "speedup": (t2 - t1) / (t1 - t0),
        "same_selection": float(np.array_equal(fast, slow)),
    }


def main() -> int:
    """Run the benchmarks and print their ratios."""
    res = posture_selection()
    print(f"posture selection, {res['candidates']} candidates, {N_SELECT} postures (greedy phase):")
    print(f"  active (det + Woodbury updates): {res['active_s']:.3f} s")
    print(f"  reference (SVD per candidate):   {res['svd_s']:.3f} s")
    print(f"  speed-up: {res['speedup']:.0f}x; same selection: {bool(res['same_selection'])}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
