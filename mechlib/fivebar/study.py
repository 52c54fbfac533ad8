"""The simulated calibration study of thesis sec. 3.7: one draw and a seeded Monte Carlo.

Strategies compared on the same simulated mechanism:

- ``dc``: divide and conquer, ``n_per_leg`` postures selected for each leg on its own matrix,
  each leg identified from its own postures (its own end-effector measurements and joint reading);
- ``trad``: traditional, ``n_shared`` postures selected on the total (block-diagonal) matrix,
  all twelve parameters identified at once from the shared postures.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from mechlib.calibration import study as core
from mechlib.fivebar import identification as idf
from mechlib.fivebar import kinematics as kin
from mechlib.fivebar import postures as ps
from mechlib.params import check_float, check_int

#: Fewest postures that can identify one leg's six parameters.
N_MIN_POSTURES = kin.N_LEG_PARAMS
#: Shared postures of the traditional method per D&C posture of one leg in the sensitivity sweep
#: (the thesis's budgets, sec. 3.7 items 8 and 10: equal end-effector measurements).
SHARED_PER_LEG_POSTURE = 2
#: The thesis's claim "D&C gives the better calibration" holds when D&C's workspace RMS error is
#: the smaller one in more than CLAIM_MIN_SHARE of the paired trials and the Wilcoxon signed-rank
#: test rejects "no difference" at CLAIM_MAX_P: the rules (and :func:`mean_ci`,
#: :func:`paired_verdict`, :func:`claim_holds`) live once in :mod:`mechlib.calibration.study`.
CLAIM_MIN_SHARE, CLAIM_MAX_P = core.CLAIM_MIN_SHARE, core.CLAIM_MAX_P
mean_ci, paired_verdict, claim_holds = core.mean_ci, core.paired_verdict, core.claim_holds
#: Strategy keys of :func:`monte_carlo` and their names in tables.
STRATEGIES = {"dc": "D&C", "trad": "traditional"}
M_TO_UM = 1e6


@dataclass(frozen=True)
class Mechanism:
    """Nominal and real parameters with the modes of the study."""

    nominal1: np.ndarray
    nominal2: np.ndarray
    real1: np.ndarray
    real2: np.ndarray
    modes: tuple[int, int] = kin.NOMINAL_MODES

    @property
    def nominal(self) -> np.ndarray:
        """Stacked nominal parameters (12,)."""
        return np.r_[self.nominal1, self.nominal2]

    @property
    def real(self) -> np.ndarray:
        """Stacked real parameters (12,)."""
        return np.r_[self.real1, self.real2]


def disc_grid(center: tuple[float, float], radius: float, spacing: float) -> np.ndarray:
    """Square-lattice points with the given spacing inside a disc."""
    spacing = check_float("spacing", spacing, low=0.0, low_open=True)
    n = int(np.ceil(radius / spacing))
    ax = np.arange(-n, n + 1) * spacing
    xx, yy = np.meshgrid(ax, ax)
    keep = xx**2 + yy**2 <= radius**2
    return np.column_stack([center[0] + xx[keep], center[1] + yy[keep]])


def select(
    mech: Mechanism, candidates: np.ndarray, n_per_leg: int, n_shared: int
) -> dict[str, np.ndarray]:
    """Posture indices: ``leg1``, ``leg2`` (divide and conquer) and ``trad`` (shared)."""
    c1 = idf.identification_jacobian(candidates, mech.nominal1, mech.modes[0])
    c2 = idf.identification_jacobian(candidates, mech.nominal2, mech.modes[1])
    return {
        "leg1": ps.select_active(c1, n_per_leg),
        "leg2": ps.select_active(c2, n_per_leg),
        "trad": ps.select_active(idf.posture_blocks(c1, c2), n_shared),
    }


def one_trial(
    mech: Mechanism,
    candidates: np.ndarray,
    chosen: dict[str, np.ndarray],
    sigma: float,
    rng: np.random.Generator,
) -> dict[str, np.ndarray]:
    """Simulate measurements and identify with both strategies; return identified parameters
    and whether all three fits (two legs, the traditional one) converged."""
    m = mech
    sim1 = idf.simulate_measurements(
        candidates[chosen["leg1"]], m.real1, m.real2, m.nominal1, m.nominal2, m.modes, sigma, rng
    )
    sim2 = idf.simulate_measurements(
        candidates[chosen["leg2"]], m.real1, m.real2, m.nominal1, m.nominal2, m.modes, sigma, rng
    )
    simt = idf.simulate_measurements(
        candidates[chosen["trad"]], m.real1, m.real2, m.nominal1, m.nominal2, m.modes, sigma, rng
    )
    t0 = time.perf_counter()
    dc1 = idf.identify_leg(sim1["points"], sim1["psi1"], m.nominal1, m.modes[0])
    dc2 = idf.identify_leg(sim2["points"], sim2["psi2"], m.nominal2, m.modes[1])
    t1 = time.perf_counter()
    trad = idf.identify_traditional(
        simt["points"], simt["psi1"], simt["psi2"], m.nominal1, m.nominal2, m.modes
    )
    t2 = time.perf_counter()
    return {
        "dc": np.r_[dc1.phi, dc2.phi],
        "trad": trad.phi,
        "time_dc": t1 - t0,
        "time_trad": t2 - t1,
        "converged": dc1.converged and dc2.converged and trad.converged,
    }


def position_error_map(mech: Mechanism, phi: np.ndarray, grid: np.ndarray) -> np.ndarray:
    """|position error| at each grid point when the controller uses parameters ``phi`` (12,)."""
    n1 = len(mech.real1)
    return idf.position_errors(grid, phi[:n1], phi[n1:], mech.real1, mech.real2, mech.modes)


def monte_carlo(
    mech: Mechanism,
    candidates: np.ndarray,
    chosen: dict[str, np.ndarray],
    grid: np.ndarray,
    sigma: float,
    n_trials: int,
    seed: int,
) -> dict[str, np.ndarray]:
    """Repeat :func:`one_trial` with independent seeded noise.

    Returns
    -------
    dict
        ``param_err_<s>`` (trials, 12) identified − real; ``rms_<s>`` (trials,) workspace RMS
        position error over ``grid``; ``local_sq_<s>`` (grid,) mean squared error per grid point;
        ``time_<s>`` (trials,) identification solve times; for ``s`` in ``dc``, ``trad``;
        ``failed`` the indices of the trials in which a fit did not converge, left out of every
        array (of both strategies, which stay paired trial by trial).

    Raises
    ------
    RuntimeError
        If no trial converged.
    """
    sigma = check_float("sigma", sigma, low=0.0)
    n_trials = check_int("n_trials", n_trials, low=1, high=100_000)
    rng = np.random.default_rng(check_int("seed", seed, low=0))
    out: dict[str, list] = {
        f"{k}_{s}": [] for k in ("param_err", "rms", "time") for s in ("dc", "trad")
    }
    local = {"dc": np.zeros(len(grid)), "trad": np.zeros(len(grid))}
    failed: list[int] = []
    for trial in range(n_trials):
        res = one_trial(mech, candidates, chosen, sigma, rng)
        if not res["converged"]:
            failed.append(trial)
            continue
        for s in ("dc", "trad"):
            err = position_error_map(mech, res[s], grid)
            out[f"param_err_{s}"].append(res[s] - mech.real)
            out[f"rms_{s}"].append(np.sqrt(np.mean(err**2)))
            out[f"time_{s}"].append(res[f"time_{s}"])
            local[s] += err**2 / n_trials
    used = n_trials - len(failed)
    if used == 0:
        raise RuntimeError(
            f"no Monte Carlo trial converged (sigma = {sigma:g}, n_trials = {n_trials})"
        )
    arrays = {k: np.asarray(v) for k, v in out.items()}
    # mean over the trials used (the same numbers as before when none failed)
    arrays["local_sq_dc"] = local["dc"] * (n_trials / used)
    arrays["local_sq_trad"] = local["trad"] * (n_trials / used)
    arrays["failed"] = np.asarray(failed, dtype=int)
    return arrays


def parameter_rms(errors: np.ndarray, per_parameter: bool = False) -> np.ndarray | float:
    """Root mean square of identified − real parameters (trials, 12): over everything, or per
    parameter (12,)."""
    e = np.asarray(errors, dtype=float)
    if e.ndim != 2:
        raise ValueError(f"errors must be (trials, parameters), got shape {e.shape}")
    return np.sqrt(np.mean(e**2, axis=0)) if per_parameter else float(np.sqrt(np.mean(e**2)))


def summary(mc: dict[str, np.ndarray]) -> dict[str, dict[str, float]]:
    """Per strategy (table name → row): workspace RMS mean and its 95 % CI [µm], parameter RMS
    error over all twelve, median solve time [ms], from a :func:`monte_carlo` result."""
    rows = {}
    for s, label in STRATEGIES.items():
        mean, lo, hi = mean_ci(mc[f"rms_{s}"])
        rows[label] = {
            "workspace RMS mean [µm]": M_TO_UM * mean,
            "95 % CI low": M_TO_UM * lo,
            "95 % CI high": M_TO_UM * hi,
            "param. RMS error (all 12)": parameter_rms(mc[f"param_err_{s}"]),
            "solve time median [ms]": 1e3 * float(np.median(mc[f"time_{s}"])),
        }
    return rows


def measurement_counts(n_per_leg: int, n_shared: int) -> dict[str, dict[str, int]]:
    """End-effector measurements (points, 2 coordinates each) and joint readings per strategy.

    Divide and conquer measures one end-effector point and uses one joint reading per posture
    of each leg; the traditional method measures one point and reads both joints per shared
    posture. ``total`` counts coordinates and readings (the cost of Table 8).
    """
    counts = {
        "dc": {
            "postures": 2 * n_per_leg,
            "ee_points": 2 * n_per_leg,
            "ee_coordinates": 4 * n_per_leg,
            "joint_readings": 2 * n_per_leg,
        },
        "trad": {
            "postures": n_shared,
            "ee_points": n_shared,
            "ee_coordinates": 2 * n_shared,
            "joint_readings": 2 * n_shared,
        },
    }
    for c in counts.values():
        c["total"] = c["ee_coordinates"] + c["joint_readings"]
    return counts


def sensitivity(
    mech: Mechanism,
    candidates: np.ndarray,
    grid: np.ndarray,
    sigmas: list[float],
    counts: list[int],
    n_trials: int,
    seed: int,
) -> list[dict[str, float]]:
    """D&C vs traditional over a grid of noise levels and posture counts.

    For each ``n`` in ``counts`` D&C gets ``n`` postures per leg and the traditional method
    ``SHARED_PER_LEG_POSTURE · n`` shared postures (the thesis's ratio, equal end-effector
    measurements); each cell runs :func:`monte_carlo` with the same ``seed``.

    Returns
    -------
    list of dict
        One row per (sigma, n): ``sigma``, ``n_per_leg``, ``rms_dc_um``, ``rms_trad_um`` (mean
        workspace RMS), ``share_dc_better`` and ``p_value`` (:func:`paired_verdict`), and
        ``failed_trials``, the trials left out because a fit did not converge.
    """
    rows = []
    for n in counts:
        n = check_int("counts", n, low=N_MIN_POSTURES, high=len(candidates) // 2)
        chosen = select(mech, candidates, n, SHARED_PER_LEG_POSTURE * n)
        for s in sigmas:
            mc = monte_carlo(mech, candidates, chosen, grid, s, n_trials, seed)
            verdict = paired_verdict(mc["rms_dc"], mc["rms_trad"])
            rows.append(
                {
                    "sigma": float(s),
                    "n_per_leg": n,
                    "rms_dc_um": M_TO_UM * float(mc["rms_dc"].mean()),
                    "rms_trad_um": M_TO_UM * float(mc["rms_trad"].mean()),
                    "share_dc_better": verdict["share_a_better"],
                    "p_value": verdict["p_value"],
                    "failed_trials": len(mc["failed"]),
                }
            )
    return rows
