"""The first benchmarks of ``make bench``: posture selection, HexFlex load cases, SuperLU
orderings and the identification cost against the number of legs (what :mod:`mechlib.bench`
describes), each a function that times and one that prints.
"""

from __future__ import annotations

import time

import numpy as np

from mechlib import dyad
from mechlib import published as pub
from mechlib.calibration import selection as sel
from mechlib.fivebar import kinematics as kin
from mechlib.fivebar.mechanism import disc_grid

N_CANDIDATES = 10_000
N_SELECT = 18
#: Load cases of Tables 2, 4 and 5 together (12 + 30 + 1000).
N_LOAD_CASES = 1042
#: Plain SfePy solves actually timed (each costs a full assembly and factorisation).
N_PLAIN_TIMED = 3


def bench_geometry():
    """A representative geometry of the size the hexflex notebook identifies (the defaults)."""
    from mechlib.hexflex.geometry import HexFlexGeometry

    return HexFlexGeometry()


def posture_selection() -> dict[str, float]:
    """Time both selection implementations on ~10⁴ candidates of leg 1 (greedy phase only)."""
    phi1 = kin.leg_vector(pub.TABLE7_NOMINAL, 1)
    miw = kin.miw_closed_form(phi1[0], phi1[1], abs(phi1[2]))
    radius = 0.8 * miw["radius"]
    spacing = radius * np.sqrt(np.pi / N_CANDIDATES)
    cands = disc_grid((0.0, miw["cy"]), radius, spacing)
    c1 = dyad.jacobian(cands, phi1, 1)
    t0 = time.perf_counter()
    fast = sel.select_active(c1, N_SELECT, max_passes=0)
    t1 = time.perf_counter()
    slow = sel.select_reference_svd(c1, N_SELECT, max_passes=0)
    t2 = time.perf_counter()
    return {
        "candidates": len(cands),
        "active_s": t1 - t0,
        "svd_s": t2 - t1,
        "speedup": (t2 - t1) / (t1 - t0),
        "same_selection": float(np.array_equal(fast, slow)),
    }


def hexflex_load_cases() -> dict[str, float]:
    """Time 1042 load cases on a representative HexFlex geometry (Q2, default mesh)."""
    from mechlib.hexflex.fe.model import HexFlexModel

    g = bench_geometry()
    forces = np.random.default_rng(2010).uniform(-1.0, 1.0, (N_LOAD_CASES, 6))
    t0 = time.perf_counter()
    model = HexFlexModel(g)
    t1 = time.perf_counter()
    fast = model.poses(forces)
    t2 = time.perf_counter()
    plain = model.poses_plain_sfepy(forces[:N_PLAIN_TIMED])
    t3 = time.perf_counter()
    per_plain = (t3 - t2) / N_PLAIN_TIMED
    fast_total = (t1 - t0) + (t2 - t1)
    return {
        "n_dofs": model.n_dofs,
        **{f"{k}_s": v for k, v in model.timings.items()},
        "per_case_s": (t2 - t1) / N_LOAD_CASES,
        "fast_total_s": fast_total,
        "plain_per_case_s": per_plain,
        "plain_total_s": per_plain * N_LOAD_CASES,
        "speedup": per_plain * N_LOAD_CASES / fast_total,
        "max_rel_diff": float(
            np.abs(plain - fast[:N_PLAIN_TIMED]).max() / np.abs(fast[:N_PLAIN_TIMED]).max()
        ),
    }


def factorisation_orderings() -> dict[str, float]:
    """Time SuperLU with the model's ordering and with SciPy's default on one stiffness."""
    import scipy.sparse.linalg as sla

    from mechlib.fe.factor import factorise
    from mechlib.hexflex.fe.model import HexFlexModel

    matrix = HexFlexModel(bench_geometry()).assembled_stiffness().tocsc()
    t0 = time.perf_counter()
    ours = factorise(matrix)
    t1 = time.perf_counter()
    default = sla.splu(matrix)
    t2 = time.perf_counter()
    return {
        "n_dofs": matrix.shape[0],
        "ours_s": t1 - t0,
        "default_s": t2 - t1,
        "speedup": (t2 - t1) / (t1 - t0),
        "fill_ratio": (default.L.nnz + default.U.nnz) / (ours.L.nnz + ours.U.nnz),
    }


def print_calibration() -> None:
    """Identification cost against the number of legs (5R, 3-RRR, 6-UPS): the normal-matrix
    inversion ratio counted (Table 6's n_limbs² law) and one normal-equation solve timed."""
    from mechlib.calibration import mechanism as cm
    from mechlib.fivebar import mechanism as fivebar
    from mechlib.mechanisms import gough_stewart, rrr3

    rng = np.random.default_rng(0)
    print("identification cost, traditional / D&C (one thread; 3 poses per parameter):")
    miw = kin.miw_closed_form(0.75, 1.1, 0.5)
    _print_cost(fivebar.mechanism(), disc_grid((0.0, miw["cy"]), 0.5 * miw["radius"], 0.1)[:18])
    for mech, box in (
        (rrr3.mechanism(), rrr3.box()),
        (gough_stewart.mechanism(), gough_stewart.box()),
    ):
        poses = cm.candidate_poses(mech, *box, 200, rng)
        _print_cost(mech, poses[: 3 * mech.legs[0].size])


def _print_cost(mech, poses: np.ndarray) -> None:
    from mechlib.calibration import cost

    size, t = cost.normal_sizes(mech), cost.time_normal_solves(mech, poses, 2000)
    print(
        f"  {mech.name}: n_limbs = {size['n_limbs']}, flops ratio {size['flop_ratio']:g} "
        f"(n_limbs² = {size['n_limbs'] ** 2}), measured solve-time ratio {t['ratio']:.2f} "
        f"({1e6 * t['trad']:.1f} µs vs {1e6 * t['dc']:.1f} µs)"
    )


def print_postures() -> None:
    """Time :func:`posture_selection` and print its times and speed-up."""
    res = posture_selection()
    print(f"posture selection, {res['candidates']} candidates, {N_SELECT} postures (greedy phase):")
    print(f"  active (det + Woodbury updates): {res['active_s']:.3f} s")
    print(f"  reference (SVD per candidate):   {res['svd_s']:.3f} s")
    print(f"  speed-up: {res['speedup']:.0f}x; same selection: {bool(res['same_selection'])}")


def print_load_cases() -> None:
    """Time :func:`hexflex_load_cases` and print its stages, totals and speed-up."""
    hx = hexflex_load_cases()
    print(f"HexFlex, Q2, {hx['n_dofs']} DOFs, {N_LOAD_CASES} load cases:")
    print(
        f"  mesh {hx['mesh_s']:.2f} s, SfePy setup {hx['setup_s']:.2f} s, assembly "
        f"{hx['assembly_s']:.2f} s, factorisation {hx['factorisation_s']:.2f} s"
    )
    print(
        f"  per load case (batched back-substitution + pose fit): {1e3 * hx['per_case_s']:.2f} ms"
    )
    print(f"  factorise once, all cases: {hx['fast_total_s']:.1f} s")
    print(
        f"  plain Problem.solve() per case: {hx['plain_per_case_s']:.2f} s "
        f"(timed on {N_PLAIN_TIMED}) -> {hx['plain_total_s'] / 60:.1f} min for {N_LOAD_CASES}"
    )
    print(
        f"  speed-up: {hx['speedup']:.0f}x; largest relative pose difference "
        f"{hx['max_rel_diff']:.1e}"
    )


def print_orderings() -> None:
    """Time :func:`factorisation_orderings` and print both times and the fill ratio."""
    lu = factorisation_orderings()
    print(f"SuperLU on the same stiffness ({lu['n_dofs']} DOFs):")
    print(f"  minimum degree on A + A^T, symmetric mode: {lu['ours_s']:.2f} s")
    print(f"  SciPy default (COLAMD):                    {lu['default_s']:.2f} s")
    print(f"  speed-up: {lu['speedup']:.1f}x; fill ratio default/ours: {lu['fill_ratio']:.1f}")
