"""Our reference model of the parallelogram flexure: two Euler–Bernoulli elastica beams and a
rigid stage, solved by shooting.

Geometry and axes (lengths over the beam length L, loads as in :mod:`.published`): beam 1 is
clamped at (0, +w) and beam 2 at (0, -w) with w = W/(2L), both along +x in the undeformed state.
Their tips, (1, ±w), are rigidly attached to a stage whose reference point P starts at (1 + d, 0):
d = 0 (the default) is the midpoint between the beam tips, where the benchmark's 3-D FE applies
its loads and measures the displacement. The stage pose is (u_x, u_y, φ): P's displacement over
L and the rotation [rad], counter-clockwise positive. A_x = F_x L²/EI acts along the beams, A_y
across them (it gives the large u_y), B = M_z L/EI counter-clockwise, all dead loads at P.

Beam i under the (unknown) force (a_x, a_y) and couple b its tip receives from the stage obeys,
with arc length s ∈ [0, 1] and θ(0) = 0, θ'(0) = κ₀ (the clamp moment),

    x' = λ cos θ,  y' = λ sin θ,  θ' = κ,  κ' = λ (a_x sin θ − a_y cos θ),
    λ = 1 + c (a_x cos θ + a_y sin θ),

c = EI/(EA L²) = (T/L)²/12 the axial compliance: c = 0 (the default) is the inextensible
elastica; c > 0 lets the beams stretch under their axial force (the benchmark's beams have
c = 3.3e-5, which sets the stage rotation under a couple). The tip couple is b = κ(1).

Nine unknowns (a_x, a_y, κ₀ of both beams and the pose) satisfy nine equations: each tip at the
position and angle the rigid stage prescribes, and the stage's force and moment balance about P.
A damped Newton method uses the exact Jacobian, from the variational equations integrated
alongside the beams (:func:`scipy.integrate.solve_ivp`, DOP853). Loads are applied by
continuation along the straight path from the unloaded state (as a proportionally loaded FE
run does) or from a previous solution, with a tangent predictor; a step that fails, or that
moves the pose suspiciously far (a jump to another equilibrium branch), is halved.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from scipy.integrate import solve_ivp

from mechlib.params import check_float, check_int

#: The benchmark's geometry (Su & Survey, see :mod:`.published`): W/(2L) = 75/250.
BENCHMARK_HALF_WIDTH = 0.3
#: Most compressive A_x accepted: 3/4 of the parallelogram's sway-buckling load, two
#: fixed-guided beams of π² each (inextensible), -2π² ≈ -19.7.
MIN_A_X = -15.0
#: Largest |A_x| in tension, |A_y| and |B| accepted (the benchmark sweeps 10, 20 and 3).
MAX_A_X, MAX_A_Y, MAX_B = 40.0, 40.0, 10.0
#: Relative and absolute tolerances of the beam integration (the pose to ~1e-10).
_RTOL, _ATOL = 1e-10, 1e-12
#: Largest residual accepted as converged (positions over L, angles, normalised loads).
_RESIDUAL_TOL = 1e-9
#: Continuation: largest load increment per step (each of A_x, A_y, B), largest change of the
#: pose (u_x, u_y, φ) accepted in one step (a larger one is a jump to another equilibrium
#: branch: the step is halved), and the number of halvings before giving up. A step of 5 was
#: seen to jump branches on the way to (-10, 20, 3); 2 never did on the benchmark's loads.
_LOAD_STEP, _MAX_POSE_JUMP, _MAX_HALVINGS = 2.0, 0.2, 12
#: Newton iterations per load step, and step halvings within one iteration.
_MAX_NEWTON, _MAX_DAMPING = 12, 6


class ElasticaConvergenceError(RuntimeError):
    """Raised when the continuation cannot reach a load (named in the message)."""


class StageSolution(NamedTuple):
    """Equilibrium of the parallelogram under one load.

    ``u_x``, ``u_y``: displacement of the stage's reference point over L; ``phi``: stage rotation
    [rad], counter-clockwise; ``loads``: (A_x, A_y, B); ``unknowns``: the solver's nine unknowns
    (a_x, a_y, κ₀ of beam 1, of beam 2, then u_x, u_y, φ), to continue from; ``geometry``:
    (half_width, load_offset, axial_compliance) it was solved with.
    """

    u_x: float
    u_y: float
    phi: float
    loads: tuple[float, float, float]
    unknowns: np.ndarray
    geometry: tuple[float, float, float]


def check_loads(a_x: object, a_y: object, b: object) -> tuple[float, float, float]:
    """The loads as floats in the accepted ranges (``MIN_A_X`` … ``MAX_B``), else ValueError."""
    return (
        check_float("a_x (F_x L^2/EI)", a_x, low=MIN_A_X, high=MAX_A_X),
        check_float("a_y (F_y L^2/EI)", a_y, low=-MAX_A_Y, high=MAX_A_Y),
        check_float("b (M_z L/EI)", b, low=-MAX_B, high=MAX_B),
    )


def _check_geometry(half_width: object, load_offset: object, axial_compliance: object):
    return (
        check_float("half_width (W/2L)", half_width, low=0.0, high=2.0, low_open=True),
        check_float("load_offset (d/L)", load_offset, low=-2.0, high=2.0),
        check_float("axial_compliance (EI/(EA L^2))", axial_compliance, low=0.0, high=1e-2),
    )


def _rhs(_s: float, z: np.ndarray, p: np.ndarray, c: float) -> np.ndarray:
    """Beams and their sensitivities: z holds per beam (x, y, θ, κ) then d(x, y, θ, κ)/d(a_x,
    a_y, κ₀) row by row; p is (2, 3), the beams' (a_x, a_y, κ₀)."""
    z = z.reshape(2, 16)
    th, ka = z[:, 2], z[:, 3]
    sens = z[:, 4:].reshape(2, 4, 3)
    ax, ay = p[:, 0], p[:, 1]
    cs, sn = np.cos(th), np.sin(th)
    g = ax * sn - ay * cs
    n = ax * cs + ay * sn
    lam = 1.0 + c * n
    out = np.empty((2, 16))
    out[:, 0], out[:, 1], out[:, 2], out[:, 3] = lam * cs, lam * sn, ka, lam * g
    # d(rhs)/dθ and d(rhs)/d(a_x, a_y); only θ and κ enter the right-hand side
    d_th = np.stack([-c * g * cs - lam * sn, -c * g * sn + lam * cs, 0 * th, -c * g * g + lam * n])
    d_ax = np.stack([c * cs * cs, c * cs * sn, 0 * th, c * cs * g + lam * sn])
    d_ay = np.stack([c * sn * cs, c * sn * sn, 0 * th, c * sn * g - lam * cs])
    dsens = d_th.T[:, :, None] * sens[:, 2, None, :]  # (2, 4, 3)
    dsens[:, 2, :] += sens[:, 3, :]
    dsens[:, :, 0] += d_ax.T
    dsens[:, :, 1] += d_ay.T
    out[:, 4:] = dsens.reshape(2, 12)
    return out.ravel()


def _shoot(p: np.ndarray, w: float, c: float, dense: bool = False):
    z0 = np.zeros((2, 16))
    z0[:, 1] = (w, -w)
    z0[:, 3] = p[:, 2]
    z0[:, 4 + 3 * 3 + 2] = 1.0  # dκ(0)/dκ₀
    sol = solve_ivp(
        _rhs, (0.0, 1.0), z0.ravel(), method="DOP853", rtol=_RTOL, atol=_ATOL,
        args=(p, c), dense_output=dense,
    )  # fmt: skip
    if not sol.success:
        raise FloatingPointError(sol.message)
    return sol


def _residual(q: np.ndarray, loads, w: float, d: float, c: float):
    """The nine equations and their Jacobian at the unknowns ``q``."""
    p = q[:6].reshape(2, 3)
    ux, uy, phi = q[6:]
    end = _shoot(p, w, c).y[:, -1].reshape(2, 16)
    tip, sens = end[:, :4], end[:, 4:].reshape(2, 4, 3)
    cf, sf = math.cos(phi), math.sin(phi)
    side = np.array([w, -w])
    rel = np.stack([-d * cf - side * sf, -d * sf + side * cf], axis=1)  # tip − P, per beam
    drel = np.stack([d * sf - side * cf, -d * cf - side * sf], axis=1)  # d(rel)/dφ
    res, jac = np.zeros(9), np.zeros((9, 9))
    for i in range(2):
        r = slice(3 * i, 3 * i + 3)
        res[r] = tip[i, :3] - np.array([1.0 + d + ux + rel[i, 0], uy + rel[i, 1], phi])
        jac[r, r] = sens[i, :3, :]
        jac[r, 6:] = -np.array([[1.0, 0.0, drel[i, 0]], [0.0, 1.0, drel[i, 1]], [0.0, 0.0, 1.0]])
    ax, ay = p[:, 0], p[:, 1]
    res[6], res[7] = ax.sum() - loads[0], ay.sum() - loads[1]
    res[8] = tip[:, 3].sum() + np.sum(rel[:, 0] * ay - rel[:, 1] * ax) - loads[2]
    jac[6, [0, 3]] = 1.0
    jac[7, [1, 4]] = 1.0
    for i in range(2):
        jac[8, 3 * i : 3 * i + 3] = sens[i, 3, :] + np.array([-rel[i, 1], rel[i, 0], 0.0])
    jac[8, 8] = np.sum(drel[:, 0] * ay - drel[:, 1] * ax)
    return res, jac


def _newton(q0: np.ndarray, loads, w: float, d: float, c: float):
    """Newton's method with the exact Jacobian, the step halved while the residual grows: the
    root and its Jacobian, or ``None`` if it does not converge within ``_MAX_NEWTON`` steps."""
    q = q0.copy()
    try:
        res, jac = _residual(q, loads, w, d, c)
        for _ in range(_MAX_NEWTON):
            norm = np.max(np.abs(res))
            if norm <= _RESIDUAL_TOL:
                return q, jac
            delta = np.linalg.solve(jac, res)
            for _ in range(_MAX_DAMPING):
                trial = q - delta
                res_t, jac_t = _residual(trial, loads, w, d, c)
                if np.max(np.abs(res_t)) < norm:
                    break
                delta *= 0.5
            else:
                return None
            q, res, jac = trial, res_t, jac_t
    except (FloatingPointError, np.linalg.LinAlgError):
        return None
    return None


def solve_pose(
    a_x: float,
    a_y: float,
    b: float,
    *,
    half_width: float = BENCHMARK_HALF_WIDTH,
    load_offset: float = 0.0,
    axial_compliance: float = 0.0,
    start: StageSolution | None = None,
) -> StageSolution:
    """Stage pose of the elastica parallelogram under normalised dead loads at the stage point.

    Parameters
    ----------
    a_x, a_y, b : float
        A_x = F_x L²/EI in [``MIN_A_X``, ``MAX_A_X``], A_y = F_y L²/EI in ±``MAX_A_Y``,
        B = M_z L/EI in ±``MAX_B`` (counter-clockwise positive).
    half_width : float
        w = W/(2L), half the distance between the beams' centre lines over L, in (0, 2].
    load_offset : float
        d/L, the stage point's distance beyond the beam tips along x, in [-2, 2]; 0 is the
        midpoint of the tips (the benchmark FE's load and probe point).
    axial_compliance : float
        c = EI/(EA L²) = (T/L)²/12 for a rectangular beam, in [0, 0.01]; 0: inextensible.
    start : StageSolution, optional
        A solution of the same mechanism to continue from (e.g. the previous point of a sweep);
        by default the unloaded state.

    Returns
    -------
    StageSolution

    Raises
    ------
    ValueError
        If a load or a geometric parameter is out of range.
    ElasticaConvergenceError
        If the continuation cannot reach the load (named in the message).
    """
    loads = np.array(check_loads(a_x, a_y, b))
    w, d, c = _check_geometry(half_width, load_offset, axial_compliance)
    if start is not None and tuple(start.geometry) != (w, d, c):
        raise ValueError(
            f"start must be a solution of the same mechanism (half_width, load_offset, "
            f"axial_compliance) = {(w, d, c)}, got {tuple(start.geometry)}"
        )
    q = np.zeros(9) if start is None else np.array(start.unknowns, dtype=float)
    origin = np.zeros(3) if start is None else np.array(start.loads, dtype=float)
    # steps of at most ``_LOAD_STEP`` in each normalised load; tangent predictor: along the
    # path the equilibrium rows change by -Δt (loads - origin), so dq/dt = J⁻¹ (0, loads - origin)
    max_step = min(1.0, _LOAD_STEP / max(float(np.max(np.abs(loads - origin))), 1e-300))
    step, t, halvings = max_step, 0.0, 0
    rate = np.zeros(9)
    rate[6:] = loads - origin
    jac = _residual(q, origin, w, d, c)[1]
    while t < 1.0:
        t_new = min(1.0, t + step)
        target = origin + t_new * (loads - origin)
        try:
            found = _newton(q + (t_new - t) * np.linalg.solve(jac, rate), target, w, d, c)
        except np.linalg.LinAlgError:
            found = None
        if found is None:
            found = _newton(q, target, w, d, c)
        if found is not None and np.max(np.abs(found[0][6:] - q[6:])) > _MAX_POSE_JUMP:
            found = None
        if found is None:
            halvings += 1
            if halvings > _MAX_HALVINGS:
                raise ElasticaConvergenceError(
                    f"elastica parallelogram did not converge for (A_x, A_y, B) = "
                    f"({loads[0]:g}, {loads[1]:g}, {loads[2]:g}): stuck at load fraction {t:.4f} "
                    f"from {tuple(float(v) for v in origin)} (w={w:g}, d={d:g}, c={c:g})"
                )
            step *= 0.5
            continue
        (q, jac), t = found, t_new
        step = min(2.0 * step, max_step)
    return StageSolution(float(q[6]), float(q[7]), float(q[8]), tuple(loads.tolist()), q, (w, d, c))


def solve_path(
    loads: object,
    *,
    half_width: float = BENCHMARK_HALF_WIDTH,
    load_offset: float = 0.0,
    axial_compliance: float = 0.0,
) -> np.ndarray:
    """Poses along a sequence of loads, each solved by continuation from the previous one.

    Parameters
    ----------
    loads : array_like, shape (n, 3)
        Rows (A_x, A_y, B), each as in :func:`solve_pose`.
    half_width, load_offset, axial_compliance : float
        As in :func:`solve_pose`.

    Returns
    -------
    numpy.ndarray, shape (n, 3)
        Rows (u_x/L, u_y/L, φ [rad]).

    Raises
    ------
    ValueError
        If ``loads`` is not an (n, 3) array or an entry is out of range.
    ElasticaConvergenceError
        If a load cannot be reached.
    """
    arr = np.asarray(loads, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != 3 or arr.shape[0] < 1:
        raise ValueError(f"loads must be an (n, 3) array of (A_x, A_y, B), got shape {arr.shape}")
    out, prev = np.empty_like(arr), None
    for k, row in enumerate(arr):
        prev = solve_pose(
            *row, half_width=half_width, load_offset=load_offset,
            axial_compliance=axial_compliance, start=prev,
        )  # fmt: skip
        out[k] = prev.u_x, prev.u_y, prev.phi
    return out


def centre_lines(solution: StageSolution, n_points: int = 51) -> np.ndarray:
    """The deformed centre lines of both beams of a solution, shape (2, n_points, 2): (x, y)/L
    at evenly spaced arc lengths, beam 1 (clamped at (0, +w)) first.

    Raises
    ------
    ValueError
        If ``n_points`` < 2.
    """
    n_points = check_int("n_points", n_points, low=2)
    w, _, c = solution.geometry
    sol = _shoot(np.asarray(solution.unknowns[:6], dtype=float).reshape(2, 3), w, c, dense=True)
    z = sol.sol(np.linspace(0.0, 1.0, n_points)).reshape(2, 16, n_points)
    return np.stack([z[:, 0, :], z[:, 1, :]], axis=-1)
