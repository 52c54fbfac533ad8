"""Benchmark of the hyper-reduced ROM of the non-linear HexFlex (``make bench``, section ``rom``).

On the DOE chapter's model (:func:`mechlib.bench.nonlinear._chapter_spec`): the full non-linear
runs of the thesis's designs, Table 2 (12 runs) and Table 4 (30), are the ROM's snapshots
(:mod:`mechlib.hexflex.rom.model`; ``N_POD`` energy-POD vectors of them join the static modes and
modal derivatives); the ROM is built; then the first ``N_CHECK`` validation runs of the chapter
(seed 2010, uniform in ±1 N) are solved by the full non-linear solver and by the ROM, in the
same process: the ratio of the full run's wall time to the ROM's, per pose (one pose per call,
and a batch of ``N_BATCH``), and the ROM's pose error (largest |difference| over the runs as %
of full scale over them, and as % of each run's largest component).
"""

from __future__ import annotations

import time

import numpy as np

from mechlib import published as pub

#: POD vectors of the 42 snapshots: 12 left x and y errors of 1.3–1.4 % of their full scale on the
#: identified model, 24 brought every component below 0.5 % (16 validation runs, ±1 N).
N_POD = 24
#: Validation runs solved by both (each full run costs seconds).
N_CHECK = 6
#: Force vectors of the batched timing.
N_BATCH = 1000
#: Repeats of the one-pose timing (the fastest pass is kept: the machine is noisy).
REPEATS = 5


def rom_timings() -> dict[str, float | str]:
    """Build the ROM on the chapter's model, time it against full non-linear runs."""
    from mechlib.bench.nonlinear import _chapter_spec
    from mechlib.campaign import experiments as ex
    from mechlib.hexflex.rom.model import ReducedOrderModel

    spec, source = _chapter_spec()
    solver = ex.solver_for(spec)
    model = solver.model
    t0 = time.perf_counter()
    designs = np.vstack([pub.TABLE2_DESIGN, pub.TABLE4_DESIGN])
    snapshots = np.array([solver.solve(f)[0] for f in designs])
    t1 = time.perf_counter()
    rom = ReducedOrderModel.build(solver, snapshots, n_pod=N_POD)
    t2 = time.perf_counter()
    design = np.random.default_rng(2010).uniform(-1.0, 1.0, (N_BATCH, 6))
    check = design[:N_CHECK]
    t3 = time.perf_counter()
    full = np.array([model.pose_of(solver.solve(f)[0]) for f in check])
    t4 = time.perf_counter()
    single = []
    for _ in range(REPEATS):
        ts = time.perf_counter()
        reduced = np.vstack([rom.poses(f) for f in check])
        single.append((time.perf_counter() - ts) / N_CHECK)
    ts = time.perf_counter()
    rom.poses(design)
    batch = (time.perf_counter() - ts) / N_BATCH
    full_run = (t4 - t3) / N_CHECK
    diff = np.abs(reduced - full)
    span = full.max(axis=0) - full.min(axis=0)
    relative = diff.max(axis=1) / np.abs(full).max(axis=1)
    linear = np.abs(model.poses(check) - full).max(axis=0) / span
    return {
        "geometry": source,
        "n_dofs": model.n_dofs,
        "snapshots_s": t1 - t0,
        "build_s": t2 - t1,
        "n_basis": rom.n_basis,
        "n_elements": rom.n_elements,
        "full_run_s": full_run,
        "rom_pose_s": min(single),
        "rom_batch_pose_s": batch,
        "ratio": full_run / min(single),
        "batch_ratio": full_run / batch,
        "error_range_pct": 100 * float((diff.max(axis=0) / span).max()),
        "linear_error_range_pct": 100 * float(linear.max()),
        "error_relative_pct": 100 * float(relative.max()),
    }


def print_rom() -> None:
    r = rom_timings()
    print(
        f"ROM of the non-linear HexFlex, {r['geometry']} geometry, {r['n_dofs']} DOFs "
        f"(static modes, modal derivatives, {N_POD} POD vectors of the non-linear runs of "
        f"Tables 2 and 4, 42 runs: {r['snapshots_s']:.0f} s):"
    )
    print(
        f"  build {r['build_s']:.1f} s: {r['n_basis']} basis vectors, {r['n_elements']} "
        f"ECSW elements"
    )
    print(
        f"  full non-linear run {r['full_run_s']:.2f} s (mean of {N_CHECK}); ROM "
        f"{1e6 * r['rom_pose_s']:.0f} µs per pose one at a time ({r['ratio']:.0f}x), "
        f"{1e6 * r['rom_batch_pose_s']:.0f} µs per pose in a batch of {N_BATCH} "
        f"({r['batch_ratio']:.0f}x)"
    )
    print(
        f"  pose error vs full FE on those {N_CHECK} runs: {r['error_range_pct']:.2f} % of a "
        f"component's range (linear model: {r['linear_error_range_pct']:.2f} %), "
        f"{r['error_relative_pct']:.2f} % of a run's largest component"
    )
