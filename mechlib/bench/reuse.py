"""Can one factorised tangent serve several non-linear runs? (``make bench ONLY=reuse``)

A chord iteration with a tangent factorised at another run's equilibrium costs no factorisation,
but converges only if that equilibrium is close. This section measures how close: on the DOE
chapter's model it solves the first validation run, factorises the tangent at its equilibrium,
and then solves loads at growing distances from it (a seeded direction in force space) by
Anderson-accelerated chord iterations with that one factorisation, from the first-order
predictor ``u₀ + K(u₀)⁻¹ ΔF``. Beside it, the nearest-neighbour distances of seeded uniform
designs in the chapter's force box say how far a random run usually is from every other one.
"""

from __future__ import annotations

import time

import numpy as np

from mechlib.params import check_int

#: Distances [N] from the reference run at which the reused tangent is tried.
REUSE_DISTANCES_N = (0.02, 0.05, 0.1, 0.2)
#: Chord corrections allowed per load; a load not converged by then counts as a failure.
REUSE_MAX_CORRECTIONS = 40
#: Anderson depth of the reused-tangent chord (deeper than the solver's 5: no refactorisation).
REUSE_ANDERSON_DEPTH = 10
#: Design sizes whose nearest-neighbour distances are reported.
DESIGN_SIZES = (200, 1000, 10_000)


def nearest_neighbour_distances(n_runs: int, seed: int = 2010) -> np.ndarray:
    """Distance [N] from each run of a seeded uniform design in [−1, 1]⁶ N to its nearest
    other run (Euclidean, in force space).

    Parameters
    ----------
    n_runs : int
        Runs of the design, ≥ 2.
    seed : int
        Seed of the design's draw (``numpy.random.default_rng``).

    Returns
    -------
    numpy.ndarray (n_runs,)
        Per run, the distance [N] to its nearest other run.

    Raises
    ------
    ValueError, TypeError
        If ``n_runs`` is not an integer ≥ 2 or ``seed`` not a non-negative integer.
    """
    from scipy.spatial import cKDTree

    n_runs = check_int("n_runs", n_runs, low=2)
    seed = check_int("seed", seed, low=0)
    design = np.random.default_rng(seed).uniform(-1.0, 1.0, (n_runs, 6))
    dist, _ = cKDTree(design).query(design, k=2)
    return dist[:, 1]


def chord_with(solver, solve, u: np.ndarray, target: np.ndarray, tol: float) -> tuple[int, bool]:
    """Anderson-accelerated chord iterations with the fixed factorisation ``solve`` from ``u``
    towards equilibrium under ``target``.

    Parameters
    ----------
    solver : NonlinearSolver
        The solver whose residual is driven to zero.
    solve : callable
        A factorised tangent: residual (n_dofs,) → correction (n_dofs,).
    u : numpy.ndarray (n_dofs,)
        The start [mm].
    target : numpy.ndarray (n_dofs,)
        The load vector to equilibrate.
    tol : float
        Converged when ‖residual‖ ≤ ``tol`` ‖target‖.

    Returns
    -------
    tuple of (int, bool)
        The corrections used (at most ``REUSE_MAX_CORRECTIONS``), and whether the iteration
        converged to ``tol`` (False also when an element inverted).
    """
    from mechlib.fe.anderson import Anderson

    scale = np.linalg.norm(target)
    res = solver.residual(u, target)
    mixer = Anderson(REUSE_ANDERSON_DEPTH)
    for k in range(REUSE_MAX_CORRECTIONS + 1):
        if res is None or not np.all(np.isfinite(res)):
            return k, False  # an element inverted
        if np.linalg.norm(res) <= tol * scale:
            return k, True
        if k == REUSE_MAX_CORRECTIONS:
            break
        u = u + mixer.step(u, -solve(res))
        res = solver.residual(u, target)
    return REUSE_MAX_CORRECTIONS, False


def tangent_reuse() -> dict[str, float]:
    """Corrections and time of the reused-tangent chord at each of ``REUSE_DISTANCES_N``,
    against the default solver on the same loads.

    Returns
    -------
    dict of str to float
        ``n_dofs``; per distance ``d`` (formatted ``{d:g}``): ``default_{d}_s`` and
        ``default_{d}_factorisations`` (the default solver's wall time [s] and
        factorisations), ``reuse_{d}_s``, ``reuse_{d}_corrections`` and
        ``reuse_{d}_converged`` (1.0 or 0.0) for the reused tangent; per design size ``n`` of
        ``DESIGN_SIZES``: ``nn_{n}_median_N`` and ``nn_{n}_p05_N``, the median and 5th
        percentile of :func:`nearest_neighbour_distances` [N].
    """
    from mechlib.bench.nonlinear import _chapter_spec
    from mechlib.fe.nonlinear import NEWTON_TOL, NonlinearSolver

    spec, _ = _chapter_spec()
    solver = NonlinearSolver(spec.build())
    model = solver.model
    loads = model.load_vectors()
    base = np.random.default_rng(2010).uniform(-1.0, 1.0, 6)
    direction = np.random.default_rng(1).normal(size=6)
    direction /= np.linalg.norm(direction)
    u0, _ = solver.solve(base)
    out: dict[str, float] = {"n_dofs": model.n_dofs}
    for delta in REUSE_DISTANCES_N:
        forces = base + delta * direction
        target = loads @ forces
        t0 = time.perf_counter()
        _, stats = solver.solve(forces)
        out[f"default_{delta:g}_s"] = time.perf_counter() - t0
        out[f"default_{delta:g}_factorisations"] = sum(stats.factorisations)
        # the reference tangent, factorised again (each solve overwrites the shared factor)
        solve = solver.factorised_tangent(u0)
        t0 = time.perf_counter()
        start = u0 + solve(loads @ (delta * direction))
        used, ok = chord_with(solver, solve, start, target, NEWTON_TOL)
        out[f"reuse_{delta:g}_s"] = time.perf_counter() - t0
        out[f"reuse_{delta:g}_corrections"] = used
        out[f"reuse_{delta:g}_converged"] = float(ok)
    for n in DESIGN_SIZES:
        nn = nearest_neighbour_distances(n)
        out[f"nn_{n}_median_N"] = float(np.median(nn))
        out[f"nn_{n}_p05_N"] = float(np.percentile(nn, 5))
    return out


def print_reuse() -> None:
    """Print :func:`tangent_reuse`'s table.

    Returns
    -------
    None
        The table goes to standard output.
    """
    r = tangent_reuse()
    print(f"Reusing one factorised tangent ({int(r['n_dofs'])} DOFs), chord + Anderson "
          f"({REUSE_ANDERSON_DEPTH}), at most {REUSE_MAX_CORRECTIONS} corrections (time without "
          "the one factorisation at the reference equilibrium):")  # fmt: skip
    print(
        "  distance [N]  reused: corrections  converged  time [s]"
        "   default: factorisations  time [s]"
    )
    for d in REUSE_DISTANCES_N:
        print(
            f"  {d:12g}  {r[f'reuse_{d:g}_corrections']:19.0f}  "
            f"{'yes' if r[f'reuse_{d:g}_converged'] else 'no':>9}  {r[f'reuse_{d:g}_s']:8.2f}"
            f"   {r[f'default_{d:g}_factorisations']:22.0f}  {r[f'default_{d:g}_s']:8.2f}"
        )
    print("Nearest other run in a seeded uniform design in [-1, 1]^6 N:")
    for n in DESIGN_SIZES:
        print(
            f"  {n:6d} runs: median {r[f'nn_{n}_median_N']:.3f} N, "
            f"5th percentile {r[f'nn_{n}_p05_N']:.3f} N"
        )
