"""Inverse meta-model for control (the analogue of Eq 9): forces for a desired pose by Newton.

Newton's method on ``f(τ) = ψ`` for every desired pose at once, with the Jacobian of the
meta-model by central differences (one batched prediction per iteration), started from the
linear inverse ``τ₀ = J(0)⁻¹ (ψ − f(0))`` — Eq 9 when the meta-model is linear.
"""

from __future__ import annotations

import numpy as np

from mechlib.blas import one_thread
from mechlib.metamodels.families import Surrogate, predict_array
from mechlib.params import check_float, check_int, check_matrix

NEWTON_TOL = 1e-8
"""Convergence: max |f(τ) − ψ| of every component, relative to the component's linear scale;
far above a GP's prediction round-off (measured ≈ 4e-11 on 40 runs on one processor; at 1e-10,
7 of 16 inverses of the meta-model page's GP did not converge under OpenBLAS's Sandybridge
kernels where all did under its Haswell ones), far below any modelling error (≥ 1e-5)."""
NEWTON_MAX_ITER = 50
"""Newton iterations before a pose is reported as not converged."""
STALL_RATIO = 0.5
"""A Newton step that does not at least halve a pose's residual ends its iterations: the
meta-model's own round-off is reached (a GP's predictions carry ~1e-11 relative noise)."""
FD_STEP = 1e-5
"""Central-difference step of the Jacobian, as a fraction of the validated force range."""


def jacobian(surrogate: Surrogate, forces: np.ndarray) -> np.ndarray:
    """Jacobians of the meta-model by central differences of step ``FD_STEP`` × validated range.

    Exact (to round-off) for polynomials up to degree 2; one batched prediction of 2k points
    per run.

    Parameters
    ----------
    surrogate : Surrogate
    forces : array_like, shape (runs, inputs)
        Where to differentiate [N]; may lie up to one step outside the validated range.

    Returns
    -------
    numpy.ndarray, shape (runs, outputs, inputs)
        ∂pose/∂force (pose units per N).

    Raises
    ------
    ValueError
        Wrong shape.
    """
    x = check_matrix("forces", forces, shape=(None, surrogate.n_inputs))
    k = surrogate.n_inputs
    h = FD_STEP * surrogate.amplitude
    steps = np.concatenate([h * np.eye(k), -h * np.eye(k)])  # (2k, inputs)
    pts = (x[:, None, :] + steps[None, :, :]).reshape(-1, k)
    with one_thread():
        y = predict_array(surrogate, pts).reshape(len(x), 2 * k, -1)
    return np.transpose((y[:, :k] - y[:, k:]) / (2 * h), (0, 2, 1))


def invert(
    surrogate: Surrogate,
    poses: object,
    *,
    tol: float = NEWTON_TOL,
    max_iter: int = NEWTON_MAX_ITER,
) -> dict[str, np.ndarray]:
    """Forces that make the meta-model reach each desired pose (Newton from the linear inverse).

    Parameters
    ----------
    surrogate : Surrogate
        Fitted meta-model with as many outputs as inputs (square, as S_T of Eq 9).
    poses : array_like, shape (runs, outputs)
        Desired poses.
    tol : float
        Convergence threshold on max |f(τ) − ψ| per component, relative to the component's
        scale (the row norm of J(0) times the validated range).
    max_iter : int
        Largest number of Newton iterations.

    Returns
    -------
    dict
        ``forces`` (runs, inputs) [N]; ``residual`` (runs,) the relative residual reached;
        ``iterations`` (runs,); ``converged`` (runs,) bool, residual ≤ ``tol`` (Newton stops
        earlier where a step no longer halves the residual, the meta-model's round-off);
        ``start`` (runs, inputs) the linear inverse's forces.

    Raises
    ------
    ValueError
        Non-square meta-model, wrong pose shape, or a solution outside the validated force
        range (naming the pose and the force).
    """
    if surrogate.n_inputs != surrogate.n_outputs:
        raise ValueError(
            f"surrogate must have as many outputs as inputs to invert, got "
            f"{surrogate.n_outputs} outputs and {surrogate.n_inputs} inputs"
        )
    psi = check_matrix("poses", poses, shape=(None, surrogate.n_outputs))
    tol = check_float("tol", tol, low=0.0, low_open=True)
    max_iter = check_int("max_iter", max_iter, low=1)
    zero = np.zeros((1, surrogate.n_inputs))
    j0 = jacobian(surrogate, zero)[0]
    with one_thread():
        f0 = predict_array(surrogate, zero)[0]
        scale = np.linalg.norm(j0, axis=1) * surrogate.amplitude
        tau = np.linalg.solve(j0, (psi - f0).T).T
        start = tau.copy()
        iters = np.zeros(len(psi), dtype=int)
        res = (np.abs(predict_array(surrogate, tau) - psi) / scale).max(axis=1)
        active = res > tol
        for _ in range(max_iter):
            if not active.any():
                break
            idx = np.flatnonzero(active)
            r = predict_array(surrogate, tau[idx]) - psi[idx]
            step = np.linalg.solve(jacobian(surrogate, tau[idx]), r[:, :, None])[:, :, 0]
            trial = tau[idx] - step
            new = (np.abs(predict_array(surrogate, trial) - psi[idx]) / scale).max(axis=1)
            old = res[idx]
            better = new < old  # a step that does not lower the residual is not taken
            tau[idx[better]] = trial[better]
            res[idx[better]] = new[better]
            iters[idx] += 1
            # go on while above the tolerance and Newton still gains (not at round-off)
            active[idx] = (res[idx] > tol) & (new <= STALL_RATIO * old)
    top = np.abs(tau).max(axis=1)
    bad = np.flatnonzero(top > surrogate.amplitude)
    if bad.size:
        i = int(bad[0])
        raise ValueError(
            f"poses[{i}] needs a force of {float(top[i])} N, outside the validated range "
            f"[-{surrogate.amplitude}, {surrogate.amplitude}] N of this {surrogate.family} "
            f"meta-model ({bad.size} pose(s) out of range)"
        )
    return {
        "forces": tau,
        "residual": res,
        "iterations": iters,
        "converged": res <= tol,
        "start": start,
    }
