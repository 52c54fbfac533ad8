"""Benchmarks of the non-linear HexFlex solve and of the DOE chapter's FE work (``make bench``).

See :mod:`mechlib.bench` for what each section measures.
"""

from __future__ import annotations

import json
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from mechlib import published as pub
from mechlib.paths import REPO_ROOT

#: Non-linear validation runs timed in-process, and on the two-process pool.
N_NONLINEAR_SERIAL = 2
N_NONLINEAR_POOL = 8
#: Runs on which the non-linear solvers are compared (the old one costs ≈ 45 s a run).
N_SOLVER_RUNS = 3
#: Right-preconditioned GMRES: iterations allowed, and the residual reduction asked for.
KRYLOV_MAXITER = 60
KRYLOV_RTOL = 1e-3
#: Newton corrections allowed to the Newton–Krylov solve.
KRYLOV_NEWTON = 30
#: Calls of each building block timed; the fastest is reported (the machine is noisy).
BLOCK_REPEATS = 3


def _fastest(call) -> float:
    """Fastest wall time [s] of ``BLOCK_REPEATS`` calls of ``call()``."""
    times = []
    for _ in range(BLOCK_REPEATS):
        t0 = time.perf_counter()
        call()
        times.append(time.perf_counter() - t0)
    return min(times)


def nonlinear_options() -> dict[str, float]:
    """Time the non-linear solvers on the same validation runs, and their building blocks."""

    from mechlib.fe.factor import PatternCholesky, factorise
    from mechlib.fe.nonlinear import NonlinearSolver

    spec, _ = _chapter_spec()
    model = spec.build()
    runs = np.random.default_rng(2010).uniform(-1.0, 1.0, (N_SOLVER_RUNS, 6))
    lu = NonlinearSolver(model, factorisation="superlu")
    chol = NonlinearSolver(model)  # the default: batched tangent, CHOLMOD
    variants = {
        "newton_sfepy": (
            NonlinearSolver(model, tangent="sfepy", factorisation="superlu"),
            "newton",
        ),
        "newton_batched": (lu, "newton"),
        "modified_superlu": (lu, "modified"),
        "modified": (chol, "modified"),
    }
    # the pattern's Cholesky analysis, once per model, is not a run's cost; this equilibrium is
    # where the building blocks are timed below
    u_eq, _ = chol.solve(runs[0])
    lu.batched.values(u_eq)  # the LU solver's first-call buffers, as warm as the Cholesky's
    out: dict[str, float] = {"n_dofs": model.n_dofs, "runs": N_SOLVER_RUNS}
    poses = {}
    for name, (solver, method) in variants.items():
        t0 = time.perf_counter()
        sols = [solver.solve(f, method=method) for f in runs]
        out[f"{name}_per_run_s"] = (time.perf_counter() - t0) / N_SOLVER_RUNS
        out[f"{name}_factorisations"] = float(np.mean([sum(s.factorisations) for _, s in sols]))
        out[f"{name}_corrections"] = float(np.mean([sum(s.iterations) for _, s in sols]))
        poses[name] = np.array([model.pose_of(u) for u, _ in sols])
    ref = poses["newton_sfepy"]
    for name in variants:
        out[f"{name}_pose_rel_diff"] = float(np.abs(poses[name] - ref).max() / np.abs(ref).max())
        out[f"{name}_speedup"] = out["newton_sfepy_per_run_s"] / out[f"{name}_per_run_s"]
    # building blocks at the first run's equilibrium, each the fastest of BLOCK_REPEATS calls
    solver = chol
    load = model.load_vectors() @ runs[0]
    u = u_eq
    res = solver.residual(u, load)
    cholesky = PatternCholesky(solver.batched.pattern())
    tangent = solver.batched.matrix(u)
    upper = solver.batched.upper_values(u)
    lu_factor = factorise(tangent)
    blocks = {
        "residual_s": lambda: solver.evaluator.eval_residual(u),
        "batched_residual_s": lambda: solver.batched.internal_force(u),
        "sfepy_tangent_s": lambda: solver.evaluator.eval_tangent_matrix(u),
        "batched_tangent_s": lambda: solver.batched.matrix(u),
        "upper_tangent_s": lambda: solver.batched.upper_values(u),  # as the solver does
        "factorisation_s": lambda: factorise(tangent),
        "back_substitution_s": lambda: lu_factor.solve(res),
        "cholesky_analysis_s": lambda: PatternCholesky(solver.batched.pattern()),
        "cholesky_s": lambda: cholesky.factorise_upper(upper),  # as the solver does
    }
    for name, call in blocks.items():
        out[name] = _fastest(call)
    solve = cholesky.factorise_upper(upper)
    out["cholesky_solve_s"] = _fastest(lambda: solve(res))
    out["tangent_rel_diff"] = float(
        abs(solver.evaluator.eval_tangent_matrix(u) - tangent).max() / abs(tangent).max()
    )
    out["cholesky_fallbacks"] = float(chol.cholesky.fallbacks + cholesky.fallbacks)
    # Newton–Krylov: every Newton correction by GMRES on the exact (batched) tangent, right-
    # preconditioned by the factorised linear stiffness (no factorisation after the model's)
    t0 = time.perf_counter()
    nk = newton_krylov(solver, runs[0])
    out["krylov_s"] = time.perf_counter() - t0
    out.update({f"krylov_{k}": v for k, v in nk.items()})
    ref_pose = poses["newton_sfepy"][0]
    out["krylov_pose_rel_diff"] = float(
        np.abs(model.pose_of(nk["u"]) - ref_pose).max() / np.abs(ref_pose).max()
    )
    del out["krylov_u"]
    return out


def newton_krylov(solver, forces: np.ndarray) -> dict:
    """Newton's method whose corrections are solved by GMRES (restarted never, at most
    ``KRYLOV_MAXITER`` iterations, to ``KRYLOV_RTOL`` of the true residual) on the exact tangent,
    right-preconditioned by the model's factorised linear stiffness; at most
    ``KRYLOV_NEWTON`` corrections. Returns ``u``, ``newton`` (corrections), ``gmres`` (total
    GMRES iterations) and ``residual`` (final relative residual)."""
    import scipy.sparse.linalg as sla

    from mechlib.fe.nonlinear import NEWTON_TOL

    model = solver.model
    load = model.load_vectors() @ forces
    scale = np.linalg.norm(load)
    n = model.n_dofs
    u = model.back_substitute(load)  # the first correction, from u = 0, is exact
    res = solver.residual(u, load)
    if res is None:
        raise RuntimeError("the linear solution inverts an element: no Newton-Krylov start")
    count, newton = [0], 1
    while np.linalg.norm(res) > NEWTON_TOL * scale and newton < KRYLOV_NEWTON:
        tangent = solver.batched.matrix(u)
        operator = sla.LinearOperator(
            (n, n), matvec=lambda v, k=tangent: k @ model.back_substitute(v)
        )
        y, _ = sla.gmres(
            operator,
            res,
            rtol=KRYLOV_RTOL,
            restart=KRYLOV_MAXITER,
            maxiter=1,
            callback=lambda _: count.__setitem__(0, count[0] + 1),
            callback_type="pr_norm",
        )
        trial = u - model.back_substitute(y)
        new = solver.residual(trial, load)
        newton += 1
        if new is None:
            break  # an element inverted
        u, res = trial, new
    return {
        "u": u,
        "newton": newton,
        "gmres": count[0],
        "residual": float(np.linalg.norm(res) / scale),
    }


def _warm_worker(spec) -> int:
    """Build a worker's model and non-linear solver (what its first run would pay)."""
    from mechlib.campaign.experiments import solver_for

    return solver_for(spec).model.n_dofs


def _chapter_spec():
    """The FE model of the DOE chapter: the geometry and mesh the hexflex notebook identified
    when the build holds its record (the chapter inputs the build wing passes), else the bench
    geometry at the default mesh (the second item says which)."""
    from mechlib.hexflex.fe.model import DEFAULT_MESH_FRACTION
    from mechlib.hexflex.geometry import HexFlexGeometry
    from mechlib.hexflex.spec import ModelSpec
    from mechlib.paths import records_dir
    from mechlib.pipeline.execute import chapter_inputs

    try:
        inputs = chapter_inputs("virtual_experiments", records_dir())
    except (FileNotFoundError, KeyError):
        # the bench geometry (mechlib.bench.basics.bench_geometry): the default dimensions
        g, fraction, source = HexFlexGeometry(), DEFAULT_MESH_FRACTION, "bench"
    else:
        g = HexFlexGeometry.from_dict(inputs["geometry"])
        fraction, source = float(inputs["mesh_fraction"]), "identified"
    return ModelSpec(g, mesh_size=fraction * g.narrowest), source


def nonlinear_run_counts() -> dict[str, int]:
    """``nonlinear_runs`` of the ci profile (the notebook's default; no other profile changes
    it)."""
    nb = REPO_ROOT / "notebooks" / "virtual_experiments.ipynb"
    cell = next(
        c
        for c in json.loads(nb.read_text())["cells"]
        if "parameters" in c.get("metadata", {}).get("tags", [])
    )
    ci = next(
        line for line in "".join(cell["source"]).splitlines() if line.startswith("nonlinear_runs")
    )
    return {"ci": int(ci.split("=")[1].split("#")[0])}


def chapter_timings() -> dict[str, float | str]:
    """Cold wall times of the DOE chapter's FE work (no cache), measured and projected."""
    from mechlib.campaign import executors
    from mechlib.campaign import experiments as ex

    counts = nonlinear_run_counts()

    spec, source = _chapter_spec()
    validation = np.random.default_rng(2010).uniform(-1.0, 1.0, (1000, 6))
    t0 = time.perf_counter()
    model = ex.model_for(spec)  # the model run_experiments uses in this process
    t1 = time.perf_counter()
    for design in (pub.TABLE2_DESIGN, pub.TABLE4_DESIGN, validation):
        ex.run_experiments(spec, design, executor=None, cache_dir=None, progress=False)
    t2 = time.perf_counter()
    solver = ex.solver_for(spec)  # the solver run_experiments uses in this process
    t2b = time.perf_counter()
    factorisations = [
        sum(solver.pose(f)[1].factorisations) for f in validation[:N_NONLINEAR_SERIAL]
    ]
    t3 = time.perf_counter()
    with ProcessPoolExecutor(max_workers=2) as pool:
        ex.run_experiments(
            spec, validation[:N_NONLINEAR_POOL], kind="nonlinear", executor=pool, progress=False
        )
    t4 = time.perf_counter()
    with executors.worker_pool(2) as pool:
        # start-up first (each worker builds the model and its tangent once), then the runs
        list(pool.map(_warm_worker, [spec, spec]))
        t5 = time.perf_counter()
        ex.run_experiments(
            spec, validation[:N_NONLINEAR_POOL], kind="nonlinear", executor=pool, progress=False
        )
    t6 = time.perf_counter()
    plain_pool_per_run = (t4 - t3) / N_NONLINEAR_POOL
    startup = t5 - t4
    pool_per_run = (t6 - t5) / N_NONLINEAR_POOL
    return {
        "geometry": source,
        "n_dofs": model.n_dofs,
        "build_s": t1 - t0,
        "linear_s": t2 - t1,
        "solver_build_s": t2b - t2,
        "nonlinear_per_run_s": (t3 - t2b) / N_NONLINEAR_SERIAL,
        "factorisations": float(np.mean(factorisations)),
        "pool_startup_s": startup,
        "pool_per_run_s": pool_per_run,
        "plain_pool_per_run_s": plain_pool_per_run,
        **{f"{name}_nonlinear_s": startup + n * pool_per_run for name, n in counts.items()},
        **{f"{name}_runs": n for name, n in counts.items()},
    }


def executed_durations() -> dict[str, dict[str, float]]:
    """Papermill durations [s] of the executed notebooks, per build profile that has them."""
    out: dict[str, dict[str, float]] = {}
    for folder in sorted(REPO_ROOT.glob("build/**/executed")):
        profile = folder.parent.name if folder.parent.name != "build" else "ci"
        for nb in sorted(folder.glob("*.ipynb")):
            meta = json.loads(nb.read_text()).get("metadata", {}).get("papermill", {})
            if meta.get("duration") is not None:
                out.setdefault(profile, {})[nb.stem] = float(meta["duration"])
    return out


def print_nonlinear(newton_tol: float) -> None:
    nl = nonlinear_options()
    print(f"Non-linear solve, {nl['n_dofs']} DOFs, mean of the first {nl['runs']} validation runs:")
    for name, label in (
        ("newton_sfepy", "Newton, SfePy's tangent (before)"),
        ("newton_batched", "Newton, batched-BLAS tangent"),
        ("modified_superlu", "modified Newton + Anderson, SuperLU"),
        ("modified", "modified Newton + Anderson, CHOLMOD (now)"),
    ):
        print(
            f"  {label:34s} {nl[f'{name}_per_run_s']:5.1f} s/run, "
            f"{nl[f'{name}_factorisations']:.1f} factorisations, "
            f"{nl[f'{name}_corrections']:.1f} corrections; speed-up "
            f"{nl[f'{name}_speedup']:.1f}x; pose vs before {nl[f'{name}_pose_rel_diff']:.1e}"
        )
    print(
        f"  one tangent's factorisation: SuperLU LU {nl['factorisation_s']:.2f} s, CHOLMOD "
        f"Cholesky {nl['cholesky_s']:.2f} s ({nl['factorisation_s'] / nl['cholesky_s']:.1f}x; "
        f"its analysis, once per model, {nl['cholesky_analysis_s']:.2f} s); back-substitution "
        f"{nl['back_substitution_s']:.3f} s / {nl['cholesky_solve_s']:.3f} s; tangents not "
        f"positive definite (LU fallback): {nl['cholesky_fallbacks']:.0f}"
    )
    print(
        f"  one residual: SfePy {nl['residual_s']:.3f} s, batched {nl['batched_residual_s']:.3f} s "
        f"({nl['residual_s'] / nl['batched_residual_s']:.1f}x); "
        f"tangent: SfePy "
        f"{nl['sfepy_tangent_s']:.2f} s, batched {nl['batched_tangent_s']:.2f} s "
        f"({nl['sfepy_tangent_s'] / nl['batched_tangent_s']:.1f}x, max rel diff "
        f"{nl['tangent_rel_diff']:.0e}); its upper triangle alone (what the Cholesky reads) "
        f"{nl['upper_tangent_s']:.2f} s"
    )
    print(
        f"  Newton-Krylov (GMRES on the exact tangent, preconditioned by K_lin, to "
        f"{KRYLOV_RTOL:g}), first run: {nl['krylov_newton']} Newton corrections, "
        f"{nl['krylov_gmres']} GMRES iterations, {nl['krylov_s']:.1f} s, final residual "
        f"{nl['krylov_residual']:.1e} (tol {newton_tol:g}), pose vs before "
        f"{nl['krylov_pose_rel_diff']:.1e}"
    )


def print_chapter() -> None:
    ch = chapter_timings()
    print(f"DOE chapter FE work, cold, {ch['geometry']} geometry, {ch['n_dofs']} DOFs:")
    print(f"  model build (mesh, assembly, factorisation): {ch['build_s']:.1f} s")
    print(f"  linear part (Tables 2, 4 and 1000 validation runs): {ch['linear_s']:.1f} s")
    print(
        f"  non-linear solver build (SfePy set-up, batched tangent, Cholesky analysis): "
        f"{ch['solver_build_s']:.1f} s, once per process"
    )
    print(
        f"  non-linear run in-process: {ch['nonlinear_per_run_s']:.1f} s "
        f"({ch['factorisations']:.1f} tangent factorisations, mean of {N_NONLINEAR_SERIAL})"
    )
    print(
        f"  {N_NONLINEAR_POOL} runs on 2 processes, one BLAS thread per worker "
        f"(executors.worker_pool): start-up (each worker builds its non-linear solver; the "
        f"model comes with the fork when this process holds it, else it is built too) "
        f"{ch['pool_startup_s']:.1f} s, then {ch['pool_per_run_s']:.1f} s per run (wall); a plain "
        f"pool, a BLAS thread per core in each worker: {ch['plain_pool_per_run_s']:.1f} s per run "
        f"incl. start-up"
    )
    n = ch["ci_runs"]
    print(
        f"  projected non-linear validation on this (fine) mesh, {n} runs: "
        f"{ch['ci_nonlinear_s'] / 60:.1f} min (the chapter solves them on the lean stand-in: "
        f"make bench ONLY=lean measures that speed-up; the results store holds them)"
    )
    for profile, durations in executed_durations().items():
        listed = ", ".join(f"{nb} {d:.0f} s" for nb, d in durations.items())
        print(
            f"  executed notebooks, profile {profile} (papermill, as built; a warm FE cache "
            f"shortens virtual_experiments): {listed}"
        )
