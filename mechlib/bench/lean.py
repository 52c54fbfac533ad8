"""The lean FE model against the default one for non-linear runs (``make bench``, ``lean``).

The default model is the hexflex chapter's (read from its record); the lean one is fitted to the
magnitudes it achieves (:func:`mechlib.hexflex.studies.leanmesh.fit_lean`). Both solve the same
seeded non-linear runs in one process, one after the other, with one BLAS thread: the first
``N_RUNS`` of the DOE chapter's validation draw (seed 2010, uniform in ±1 N) and its
linear-range sweep along the first run. Accuracy as the non-linear family chapter states it
(:func:`mechlib.hexflex.studies.leanmesh.compare`: poses as % of full scale over the
1000-run draw, departures from linearity as % of themselves); speed is the mean wall time of the
``N_RUNS`` runs.
"""

from __future__ import annotations

import time

import numpy as np

#: Seeded runs timed and compared, from the DOE chapter's validation draw.
N_RUNS = 20
SEED, N_DRAW = 2010, 1000
#: The DOE chapter's linear-range sweep amplitudes [N] (``sweep_amplitudes``), along run 0.
SWEEP = (0.05, 0.1, 0.25, 0.5, 0.75, 1.0)


def _runs(model, cases: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Non-linear poses (n, 6), linear poses (n, 6), wall times (n,) [s] and factorisations
    (n,) of ``cases`` (n, 6) [N] on ``model``, one BLAS thread."""
    from mechlib.blas import one_thread
    from mechlib.fe.nonlinear import NonlinearSolver

    solver = NonlinearSolver(model)
    poses, seconds, facts = [], [], []
    with one_thread():
        for f in cases:
            t0 = time.perf_counter()
            u, stats = solver.solve(f)
            seconds.append(time.perf_counter() - t0)
            poses.append(model.pose_of(u))
            facts.append(sum(stats.factorisations))
    return np.array(poses), model.poses(cases), np.array(seconds), np.array(facts)


def lean_comparison(n_runs: int = N_RUNS) -> dict[str, object]:
    """Fit the lean model, run both models on the same loads, compare (see the module).

    Returns a dict: ``source`` of the default model, ``runs``, ``fit`` (the lean
    identification) and ``fit_s`` [s], DOFs, worst pose and departure differences [%] on the
    runs and on the sweep, Eq 8 misfits [%], mean seconds and factorisations per run of each
    model, and ``passed`` (both criteria met on runs and sweep). A run that does not converge
    raises :class:`mechlib.fe.nonlinear.ConvergenceError`, naming it."""
    import gc

    from mechlib import published as pub
    from mechlib.bench.nonlinear import _chapter_spec
    from mechlib.hexflex import identify as ident
    from mechlib.hexflex.fe.lean import lean_model
    from mechlib.hexflex.studies import leanmesh

    spec, source = _chapter_spec()
    draw = np.random.default_rng(SEED).uniform(-1.0, 1.0, (N_DRAW, 6))
    cases = np.vstack([draw[:n_runs], leanmesh.sweep_design(draw[0], SWEEP)])
    default_model = spec.build()
    achieved = np.abs(ident.target_values(default_model.compliance()))
    ranges = np.abs(default_model.poses(draw)).max(axis=0)
    t0 = time.perf_counter()
    fit = leanmesh.fit_lean(spec.geometry, achieved)
    out: dict[str, object] = {"source": source, "runs": n_runs, "fit": fit}
    out["fit_s"] = time.perf_counter() - t0
    out["default_dofs"] = default_model.n_dofs
    p0, l0, s0, f0 = _runs(default_model, cases)
    del default_model  # a Q2 solver of the default model holds gigabytes
    gc.collect()
    lean = lean_model(fit.geometry)
    out["lean_dofs"] = lean.n_dofs
    p1, l1, s1, f1 = _runs(lean, cases)
    for label, rows in (("runs", slice(0, n_runs)), ("sweep", slice(n_runs, None))):
        c = leanmesh.compare(p0[rows], l0[rows], p1[rows], l1[rows], ranges)
        out[f"pose_pct_{label}"] = float(c["pose_pct"].max())
        out[f"departure_pct_{label}"] = float(c["departure_pct"].max())
    eq8 = ident.target_values(pub.EQ8_ST)
    out["eq8_pct"] = float(100 * np.abs(fit.achieved / eq8 - 1).max())
    out["default_eq8_pct"] = float(100 * np.abs(achieved / eq8 - 1).max())
    out["default_s"], out["lean_s"] = float(s0[:n_runs].mean()), float(s1[:n_runs].mean())
    out["default_facts"], out["lean_facts"] = float(f0[:n_runs].mean()), float(f1[:n_runs].mean())
    out["passed"] = all(
        out[f"{q}_pct_{label}"] <= limit
        for q, limit in (("pose", leanmesh.POSE_PCT), ("departure", leanmesh.DEPARTURE_PCT))
        for label in ("runs", "sweep")
    )
    return out


def print_lean() -> None:
    """Print the speed-up line (marked when the accuracy check fails) and the accuracy line."""
    from mechlib.hexflex.studies.leanmesh import DEPARTURE_PCT, POSE_PCT

    r = lean_comparison()
    print(
        f"non-linear run speed-up at equal accuracy: {r['default_s'] / r['lean_s']:.1f}x "
        f"(baseline {r['default_s']:.2f} s, new {r['lean_s']:.2f} s, {r['runs']} runs)"
        + ("" if r["passed"] else " -- accuracy check FAILED, see below")
    )
    print(
        f"  accuracy check {'passed' if r['passed'] else 'FAILED'}: lean model "
        f"({r['lean_dofs']:,} DOFs; fitted to the default model's Eq 8 magnitudes in "
        f"{r['fit'].n_evaluations} FE models, {r['fit_s']:.0f} s; Eq 8 within {r['eq8_pct']:.3f} "
        f"%) vs the {r['source']} default model ({r['default_dofs']:,} DOFs; Eq 8 within "
        f"{r['default_eq8_pct']:.3f} %): worst pose difference {r['pose_pct_runs']:.3f} % "
        f"of full scale on the runs, {r['pose_pct_sweep']:.3f} % on the {len(SWEEP)}-amplitude "
        f"sweep (limit {POSE_PCT:g} %); departure from linearity within "
        f"{r['departure_pct_runs']:.2f} % / {r['departure_pct_sweep']:.2f} % of itself (limit "
        f"{DEPARTURE_PCT:g} %); factorisations per run {r['default_facts']:.2f} / "
        f"{r['lean_facts']:.2f}"
    )
