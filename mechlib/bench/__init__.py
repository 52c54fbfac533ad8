"""Speed benchmarks (``make bench``): ratios measured in one run, never asserted in tests.

- Posture selection at 10⁴ candidates: the active-calibration search with determinant and
  Woodbury updates against the same search scoring every candidate by an SVD.
- HexFlex load cases: the factorise-once model (assembly and factorisation once, one
  back-substitution per case) against SfePy's plain ``Problem.solve()`` per case, for the 1042
  cases of Tables 2, 4 and 5 (12 + 30 + 1000). The plain path is timed on a few cases and its
  per-case time multiplied by 1042 (it is the same work every case); the fast path is timed on
  all 1042.
- SuperLU ordering on the same stiffness: the minimum-degree ordering of A + Aᵀ with symmetric
  pivoting that the model uses, against SciPy's default column ordering (COLAMD).
- The non-linear solve (issue 18's options, :mod:`mechlib.bench.nonlinear`), on the first
  validation runs of the DOE chapter's model: Newton with SfePy's tangent and SuperLU (the solver
  before issue 18), Newton with the batched-BLAS tangent (:mod:`mechlib.fe.svk_tangent`),
  modified Newton with SuperLU and modified Newton with CHOLMOD's Cholesky (the default,
  :mod:`mechlib.fe.factor`), each timed on the same runs, with the largest relative pose
  difference to the first; the cost of one tangent (SfePy's, batched), one factorisation (LU,
  Cholesky), one residual and one back-substitution; and the Newton–Krylov alternative: GMRES
  iterations, preconditioned by the factorised linear stiffness (a whole solve on the first run:
  Newton corrections, GMRES iterations, time).
- Reusing one factorised tangent across runs (:mod:`mechlib.bench.reuse`): chord iterations
  with the tangent of a neighbouring equilibrium, at growing distances in force space, and the
  nearest-neighbour distances of random designs.
- The hyper-reduced ROM of the non-linear HexFlex (:mod:`mechlib.bench.rom`): its online cost
  per pose against one full non-linear run, as a ratio measured in one run, and its pose error.
- The lean FE model against the default one (:mod:`mechlib.bench.lean`): both identified to
  Eq 8, the same seeded non-linear runs in one process; the speed-up at equal accuracy and the
  accuracy check (poses as % of full scale, the departure from linearity as % of itself).
- The DOE chapter (``virtual_experiments``) on the identified model, cold (no FE cache): the linear
  part (model, Tables 2 and 4, the 1000 validation runs) timed whole; the non-linear part timed
  per run in-process and on two-process pools (one BLAS thread per worker, and a plain one), and
  projected to the chapter's run count on two workers. The executed
  notebooks' own papermill durations are printed when a build holds them.
- A campaign on a Dask cluster against the local worker pool (:mod:`mechlib.bench.dask`): the
  same non-linear runs on the same number of single-threaded workers, on a cluster the
  benchmark starts itself; the ratio of the two times and whether the poses are bit-identical.
- The main job as a reader runs it (:mod:`mechlib.bench.book`, ``--only book``, not in the
  default run: it builds the whole book): ``make book`` on a fresh clone of HEAD, its wall time
  and each chapter's papermill duration.
"""

from __future__ import annotations

import time
from pathlib import Path

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
REPO_ROOT = Path(__file__).resolve().parents[2]


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


SECTIONS: tuple[str, ...] = (
    "postures",
    "load-cases",
    "orderings",
    "nonlinear",
    "chapter",
    "reuse",
    "calibration",
    "rom",
    "lean",
    "dask",
)
#: Sections run only when named (``--only``): the book section clones and builds the book.
ON_REQUEST: tuple[str, ...] = ("book",)


def main(argv: list[str] | None = None) -> int:
    """Run the benchmarks (all, or ``--only`` some sections) and print their ratios."""
    import argparse

    from mechlib.bench import nonlinear as nlb
    from mechlib.fe.nonlinear import NEWTON_TOL

    parser = argparse.ArgumentParser(prog="python -m mechlib.bench", description=__doc__)
    parser.add_argument(
        "--only",
        default=",".join(SECTIONS),
        help=f"comma-separated sections of {SECTIONS + ON_REQUEST} (default all but {ON_REQUEST})",
    )
    only = [x for x in parser.parse_args(argv).only.split(",") if x]
    unknown = sorted(set(only) - set(SECTIONS + ON_REQUEST))
    if unknown:
        allowed = ", ".join(SECTIONS + ON_REQUEST)
        parser.error(f"--only: unknown sections {unknown}; allowed: {allowed}")
    if "postures" in only:
        _print_postures()
    if "load-cases" in only:
        _print_load_cases()
    if "orderings" in only:
        _print_orderings()
    if "nonlinear" in only:
        nlb.print_nonlinear(NEWTON_TOL)
    if "chapter" in only:
        nlb.print_chapter()
    if "reuse" in only:
        from mechlib.bench.reuse import print_reuse

        print_reuse()
    if "calibration" in only:
        _print_calibration()
    if "rom" in only:
        from mechlib.bench import rom

        rom.print_rom()
    if "lean" in only:
        from mechlib.bench.lean import print_lean

        print_lean()
    if "dask" in only:
        from mechlib.bench import dask

        print("\n".join(dask.report(dask.dask_vs_local())))
    if "book" in only:
        from mechlib.bench.book import print_book

        print_book()
    return 0


def _print_calibration() -> None:
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


def _print_postures() -> None:
    res = posture_selection()
    print(f"posture selection, {res['candidates']} candidates, {N_SELECT} postures (greedy phase):")
    print(f"  active (det + Woodbury updates): {res['active_s']:.3f} s")
    print(f"  reference (SVD per candidate):   {res['svd_s']:.3f} s")
    print(f"  speed-up: {res['speedup']:.0f}x; same selection: {bool(res['same_selection'])}")


def _print_load_cases() -> None:
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


def _print_orderings() -> None:
    lu = factorisation_orderings()
    print(f"SuperLU on the same stiffness ({lu['n_dofs']} DOFs):")
    print(f"  minimum degree on A + A^T, symmetric mode: {lu['ours_s']:.2f} s")
    print(f"  SciPy default (COLAMD):                    {lu['default_s']:.2f} s")
    print(f"  speed-up: {lu['speedup']:.1f}x; fill ratio default/ours: {lu['fill_ratio']:.1f}")
