"""Divide and conquer against traditional calibration on any :class:`Mechanism`: budgets, pose
selection, a seeded Monte Carlo and its paired verdict.

Strategies (thesis sec. 3.7 items 8 and 10, generalised to n_limbs legs):

- ``dc``: ``n`` poses selected for each leg on its own matrix ``Cκ``; leg κ identified from its
  own poses (the pose and that leg's reading at each);
- traditional: ``n_shared`` poses selected on the total matrix; every parameter identified at
  once from the shared poses (the pose and every reading at each).

Budgets (Table 8's accounting: a measurement is one pose coordinate or one joint reading; d pose
coordinates): D&C measures ``n_limbs · n · (d + 1)``; a shared pose costs ``d + n_limbs``. The
*thesis* budget gives the traditional method ``n_limbs · n`` shared poses (as many poses as D&C,
sec. 3.7: 36 against 2 × 18); the *matched* budget as many measurements as D&C.
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from scipy import stats
from threadpoolctl import threadpool_limits

from mechlib.calibration import identify as ci
from mechlib.calibration import mechanism as cm
from mechlib.calibration import selection as sel
from mechlib.params import check_float, check_int

#: D&C "wins" a comparison when it is better in more than this share of the paired trials ...
CLAIM_MIN_SHARE = 0.5
#: ... and the Wilcoxon signed-rank test rejects "no difference" at this level (two-sided).
CLAIM_MAX_P = 0.05
BUDGETS = ("thesis", "matched")


@dataclass(frozen=True)
class Study:
    """A mechanism with its real parameters, candidate poses and evaluation grid.

    ``scale`` is the standard deviation of each parameter's disturbance (parameter errors are
    reported in these units); ``jac_candidates`` and ``jac_grid`` are the pose Jacobians at the
    nominal parameters, reused as the chord of the forward kinematics.
    """

    mech: cm.Mechanism
    real: tuple[np.ndarray, ...]
    candidates: np.ndarray
    grid: np.ndarray
    scale: np.ndarray
    jac_candidates: np.ndarray
    jac_grid: np.ndarray


def make_study(
    mech: cm.Mechanism, real: Sequence[object], candidates: object, grid: object, scale: object
) -> Study:
    """Validate and assemble a :class:`Study` (poses must lie in the calibration region)."""
    real = cm.check_phis(mech, real)
    cand = cm.check_poses(mech, candidates, "candidates")
    grid = cm.check_poses(mech, grid, "grid")
    sc = np.asarray(scale, dtype=float)
    if sc.shape != (len(mech.names),) or np.any(sc <= 0):
        raise ValueError(f"scale must be {len(mech.names)} positive numbers, got {sc}")
    with threadpool_limits(1):
        jc = cm.pose_jacobian(mech, mech.nominal, cand)
        jg = cm.pose_jacobian(mech, mech.nominal, grid)
    return Study(mech, real, cand, grid, sc, jc, jg)


def disturbed(
    mech: cm.Mechanism, scale_by_unit: Mapping[str, float], rng: np.random.Generator
) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
    """Real parameters: nominal plus Gaussian errors whose standard deviation depends on the
    unit (thesis sec. 3.7 item 4). Returns the real parameters and the per-parameter scale."""
    units = [u for leg in mech.legs for u in leg.units]
    missing = sorted(set(units) - set(scale_by_unit))
    if missing:
        raise ValueError(f"scale_by_unit needs a standard deviation for units {missing}")
    scale = np.array(
        [check_float(f"scale[{u}]", scale_by_unit[u], low=0.0, low_open=True) for u in units]
    )
    real = np.concatenate(mech.nominal) + rng.normal(0.0, scale)
    return ci.split(mech, real), scale


def budgets(mech: cm.Mechanism, n_per_leg: int) -> dict[str, int]:
    """Shared poses of the traditional method under the thesis and the matched budget."""
    n = check_int("n_per_leg", n_per_leg, low=1)
    dc = measurement_counts(mech, n, 0)["dc"]
    return {"thesis": mech.n_limbs * n, "matched": round(dc / (mech.dof + mech.n_limbs))}


def measurement_counts(mech: cm.Mechanism, n_per_leg: int, n_shared: int) -> dict[str, int]:
    """Measurements (pose coordinates + joint readings) of D&C and of the traditional method."""
    return {
        "dc": mech.n_limbs * n_per_leg * (mech.dof + 1),
        "trad": n_shared * (mech.dof + mech.n_limbs),
    }


def _check_count(study: Study, name: str, n: int) -> int:
    low = max(leg.size for leg in study.mech.legs)
    return check_int(
        f"{name} (poses; parameters per leg = {low})", n, low=low, high=len(study.candidates)
    )


def select_dc(study: Study, n_per_leg: int) -> list[np.ndarray]:
    """Active-calibration selection of ``n_per_leg`` poses for each leg on its own matrix."""
    n = _check_count(study, "n_per_leg", n_per_leg)
    with threadpool_limits(1):
        return [
            sel.select_active(leg.jacobian(leg.nominal, study.candidates), n)
            for leg in study.mech.legs
        ]


def select_traditional(study: Study, n_shared: int) -> np.ndarray:
    """Active-calibration selection of ``n_shared`` shared poses on the total matrix."""
    n = _check_count(study, "n_shared", n_shared)
    with threadpool_limits(1):
        return sel.select_shared(
            [leg.jacobian(leg.nominal, study.candidates) for leg in study.mech.legs], n
        )


def _record(out: dict, study: Study, fits: Mapping[str, tuple[np.ndarray, float]]) -> None:
    """Pose errors over the grid of every identified model (one batched forward kinematics)."""
    m, n = study.mech, len(study.grid)
    q = np.vstack([cm.readings(m, ci.split(m, phi), study.grid) for phi, _ in fits.values()])
    k = len(fits)
    reached = cm.forward(
        m, study.real, q, np.tile(study.grid, (k, 1)), np.tile(study.jac_grid, (k, 1, 1))
    )
    err = (reached - np.tile(study.grid, (k, 1))).reshape(k, n, m.dof)
    ang = m.angular
    for (key, (phi, seconds)), e in zip(fits.items(), err, strict=True):
        pos = np.sum(e[:, ~ang] ** 2, axis=1)
        o = out.setdefault(key, {"param": [], "pos_rms": [], "ang_rms": [], "time": [], "local": 0})
        o["param"].append((phi - np.concatenate(study.real)) / study.scale)
        o["pos_rms"].append(np.sqrt(pos.mean()))
        o["ang_rms"].append(np.sqrt(np.sum(e[:, ang] ** 2, axis=1).mean()) if ang.any() else 0.0)
        o["time"].append(seconds)
        o["local"] = o["local"] + pos


def monte_carlo(
    study: Study,
    dc_sets: Sequence[np.ndarray],
    trad_sets: Mapping[str, np.ndarray],
    sigma: float,
    n_trials: int,
    seed: int,
) -> dict[str, dict[str, np.ndarray]]:
    """Seeded trials of D&C and of the traditional method on each of ``trad_sets``.

    Each trial draws fresh measurement noise (σ on every pose coordinate and reading) for every
    pose set, identifies with each strategy from the nominal parameters and evaluates the pose
    error over the grid. All strategies of a trial share nothing but the real mechanism.

    Returns
    -------
    dict
        Per strategy (``"dc"`` and the keys of ``trad_sets``): ``param`` (trials, P) errors in
        units of ``scale``; ``pos_rms`` [m] and ``ang_rms`` [rad] (trials,) workspace RMS;
        ``local`` (grid,) RMS position error per grid point over the trials [m]; ``time``
        (trials,) solve time [s]; and ``converged`` (trials,) whether every fit converged.

    Raises
    ------
    ValueError
        σ < 0, a bad trial count, or a pose set that cannot identify its parameters.
    """
    sigma = check_float("sigma [m, rad]", sigma, low=0.0)
    n_trials = check_int("n_trials", n_trials, low=1, high=100_000)
    rng = np.random.default_rng(check_int("seed", seed, low=0))
    m = study.mech
    out: dict = {}
    converged = []
    with threadpool_limits(1):
        for leg, idx in zip(m.legs, dc_sets, strict=True):
            ci.check_identifiable(leg.jacobian(leg.nominal, study.candidates[idx]), leg.names)
        for idx in trad_sets.values():
            ci.check_identifiable(ci.total_jacobian(m, m.nominal, study.candidates[idx]), m.names)
        sets = [*dc_sets, *trad_sets.values()]
        cuts = np.cumsum([len(idx) for idx in sets])[:-1]
        every = np.concatenate(sets)
        for _ in range(n_trials):
            # every pose set of the trial measured in one batch (one forward kinematics)
            r_all, q_all = cm.simulate(
                m, study.real, study.candidates[every], sigma, rng, study.jac_candidates[every]
            )
            meas = list(zip(np.split(r_all, cuts), np.split(q_all, cuts), strict=True))
            ok, phis, t_dc = True, [], 0.0
            for k, (leg, (r, q)) in enumerate(zip(m.legs, meas, strict=False)):
                t0 = time.perf_counter()
                fit = ci.identify_leg(leg, r, q[:, k], check=False)
                t_dc += time.perf_counter() - t0
                ok &= fit.converged
                phis.append(fit.phi)
            fits = {"dc": (np.concatenate(phis), t_dc)}
            for key, (r, q) in zip(trad_sets, meas[m.n_limbs :], strict=True):
                t0 = time.perf_counter()
                fit = ci.identify_traditional(m, r, q, check=False)
                fits[key] = (fit.phi, time.perf_counter() - t0)
                ok &= fit.converged
            _record(out, study, fits)
            converged.append(ok)
    res = {}
    for key, o in out.items():
        res[key] = {k: np.asarray(v) for k, v in o.items() if k != "local"}
        res[key]["local"] = np.sqrt(o["local"] / n_trials)
        res[key]["converged"] = np.asarray(converged)
    return res


def paired_verdict(a: np.ndarray, b: np.ndarray) -> dict[str, float]:
    """Share of trials where ``a < b`` and the Wilcoxon signed-rank p-value of a vs b."""
    a, b = np.asarray(a), np.asarray(b)
    p = float(stats.wilcoxon(a, b).pvalue) if len(a) > 1 and np.any(a != b) else 1.0
    return {"share_a_better": float(np.mean(a < b)), "p_value": p}


def claim_holds(verdict: Mapping[str, float]) -> bool:
    """D&C (``a``) better in more than ``CLAIM_MIN_SHARE`` of the trials at p < ``CLAIM_MAX_P``."""
    return bool(verdict["share_a_better"] > CLAIM_MIN_SHARE and verdict["p_value"] < CLAIM_MAX_P)


def mean_ci(x: np.ndarray, level: float = 0.95) -> tuple[float, float, float]:
    """Mean and its t-based confidence interval."""
    x = np.asarray(x, dtype=float)
    if len(x) < 2:
        return float(x.mean()), float(x.mean()), float(x.mean())
    half = stats.t.ppf(0.5 + level / 2, len(x) - 1) * x.std(ddof=1) / np.sqrt(len(x))
    return float(x.mean()), float(x.mean() - half), float(x.mean() + half)


def parameter_rms(errors: np.ndarray) -> float:
    """RMS of the scaled parameter errors (trials, P): 1 is the size of the disturbance."""
    return float(np.sqrt(np.mean(np.asarray(errors, dtype=float) ** 2)))


def compare(mc: Mapping[str, Mapping[str, np.ndarray]], trad_key: str) -> dict[str, float]:
    """D&C against one traditional budget: RMS values, share won and p-value (position error)."""
    dc, tr = mc["dc"], mc[trad_key]
    verdict = paired_verdict(dc["pos_rms"], tr["pos_rms"])
    par = paired_verdict(
        np.sqrt(np.mean(dc["param"] ** 2, axis=1)), np.sqrt(np.mean(tr["param"] ** 2, axis=1))
    )
    return {
        "pos_rms_dc": float(dc["pos_rms"].mean()),
        "pos_rms_trad": float(tr["pos_rms"].mean()),
        "ang_rms_dc": float(dc["ang_rms"].mean()),
        "ang_rms_trad": float(tr["ang_rms"].mean()),
        "param_rms_dc": parameter_rms(dc["param"]),
        "param_rms_trad": parameter_rms(tr["param"]),
        "share_dc_better": verdict["share_a_better"],
        "p_value": verdict["p_value"],
        "param_share_dc_better": par["share_a_better"],
        "param_p_value": par["p_value"],
        "holds": float(claim_holds(verdict)),
    }


def sweep(
    study: Study,
    sigmas: Sequence[float],
    counts: Sequence[int],
    n_trials: int,
    seed: int,
) -> list[dict[str, float]]:
    """D&C against both budgets over noise levels (at ``counts[0]`` poses per leg) and over
    pose counts (at ``sigmas[0]``): one :func:`compare` row per cell and budget."""
    rows = []
    cells = [(float(s), int(counts[0])) for s in sigmas] + [
        (float(sigmas[0]), int(n)) for n in counts[1:]
    ]
    for s, n in cells:
        dc = select_dc(study, n)
        trad = {b: select_traditional(study, k) for b, k in budgets(study.mech, n).items()}
        mc = monte_carlo(study, dc, trad, s, n_trials, seed)
        for b in BUDGETS:
            rows.append({"sigma": s, "n_per_leg": n, "budget": b, **compare(mc, b)})
    return rows


@dataclass(frozen=True)
class Run:
    """Selected pose sets and the Monte Carlo of one mechanism at one pose budget."""

    n_per_leg: int
    shared: dict[str, int]
    dc_sets: list[np.ndarray]
    trad_sets: dict[str, np.ndarray]
    mc: dict[str, dict[str, np.ndarray]]


def run(study: Study, n_per_leg: int, sigma: float, n_trials: int, seed: int) -> Run:
    """Select D&C's and both traditional budgets' poses, then run :func:`monte_carlo`."""
    shared = budgets(study.mech, n_per_leg)
    dc = select_dc(study, n_per_leg)
    trad = {b: select_traditional(study, n) for b, n in shared.items()}
    return Run(n_per_leg, shared, dc, trad, monte_carlo(study, dc, trad, sigma, n_trials, seed))


def conditioning(study: Study, result: Run) -> dict[str, float]:
    """Inverse condition number (columns scaled) of the identification matrices at the nominal
    parameters: the worst D&C leg and the traditional total matrix under each budget."""
    m, cand = study.mech, study.candidates
    legs = [
        ci.identifiability(leg.jacobian(leg.nominal, cand[idx]), leg.names)["conditioning"]
        for leg, idx in zip(m.legs, result.dc_sets, strict=True)
    ]
    out = {"dc": float(min(legs))}
    for b, idx in result.trad_sets.items():
        out[b] = ci.identifiability(ci.total_jacobian(m, m.nominal, cand[idx]), m.names)[
            "conditioning"
        ]
    return out


def index_comparison(
    study: Study, n_per_leg: int, sigma: float, n_trials: int, seed: int
) -> dict[str, dict[str, float]]:
    """D&C with each leg's poses chosen by each observability index of
    :data:`mechlib.calibration.selection.INDICES` (greedy, same budget), and by chance: the
    workspace RMS position error [m] and the parameter RMS of a seeded Monte Carlo per index
    (one Monte Carlo per distinct selection)."""
    n = _check_count(study, "n_per_leg", n_per_leg)
    rng = np.random.default_rng(check_int("seed", seed, low=0))
    out = {}
    with threadpool_limits(1):
        jacs = [leg.jacobian(leg.nominal, study.candidates) for leg in study.mech.legs]
        choices = {name: [sel.select_greedy(c, n, name) for c in jacs] for name in sel.INDICES}
    choices["random"] = [rng.choice(len(study.candidates), n, replace=False) for _ in jacs]
    for name, sets in choices.items():
        mc = monte_carlo(study, sets, {}, sigma, n_trials, seed)["dc"]
        out[name] = {
            "pos_rms": float(mc["pos_rms"].mean()),
            "param_rms": parameter_rms(mc["param"]),
        }
    return out
