"""The seeded Monte Carlo of D&C against traditional identification on a
:class:`mechlib.calibration.study.Study`, and the runs built on it: one budget set
(:func:`run`), sweeps over noise and pose counts (:func:`sweep`), and D&C under each
observability index (:func:`index_comparison`).

Each trial measures every pose set with fresh Gaussian noise (σ on every pose coordinate and
joint reading) drawn from the set's own stream, seeded by ``(seed, trial, label)``: D&C leg κ's
set is labelled ``dc<κ>`` (from 0), a traditional set by its key. A strategy's numbers therefore
do not depend on which other strategies run beside it: the same study, seed and settings give the
same numbers whether a page compares two budgets or three. The noise-free measurements (the
real mechanism's pose at the nominal inverse kinematics of each target, and the commanded
readings) are the same in every trial and computed once.
"""

from __future__ import annotations

import time
import zlib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from threadpoolctl import threadpool_limits

from mechlib.calibration import identify as ci
from mechlib.calibration import mechanism as cm
from mechlib.calibration import selection as sel
from mechlib.calibration import statistics as cs
from mechlib.calibration import study as st
from mechlib.params import check_float, check_int

#: What an identified model's evaluation may raise (a leg that cannot reach a grid pose, a
#: forward kinematics that does not converge): that model's errors are then NaN.
EVALUATION_ERRORS = (ValueError, RuntimeError, np.linalg.LinAlgError)
#: The arrays of a strategy's result, one entry per trial.
RESULT_KEYS = ("phi", "param", "pos_rms", "ang_rms", "pos_sq", "time", "converged")


def _stream(seed: int, trial: int, label: str) -> np.random.Generator:
    """The noise stream of one pose set in one trial."""
    return np.random.default_rng([seed, trial, zlib.crc32(label.encode())])


def _errors(study: st.Study, phis: Sequence[np.ndarray]) -> np.ndarray:
    """Pose errors (k, grid, d) over the grid of k stacked models (one forward kinematics)."""
    m, n, k = study.mech, len(study.grid), len(phis)
    q = np.vstack([cm.readings(m, ci.split(m, phi), study.grid) for phi in phis])
    guess = np.tile(study.grid, (k, 1))
    reached = cm.forward(m, study.real, q, guess, np.tile(study.jac_grid, (k, 1, 1)))
    return (reached - guess).reshape(k, n, m.dof)


def _evaluate(study: st.Study, phis: Sequence[np.ndarray]) -> np.ndarray:
    """:func:`_errors` of every model, NaN for a model that cannot be evaluated."""
    try:
        return _errors(study, phis)
    except EVALUATION_ERRORS:
        out = np.full((len(phis), len(study.grid), study.mech.dof), np.nan)
        for i, phi in enumerate(phis):
            try:
                out[i] = _errors(study, [phi])[0]
            except EVALUATION_ERRORS:
                pass
        return out


def _record(out: dict, study: st.Study, fits: Mapping[str, tuple[np.ndarray, float, bool]]) -> None:
    """Every identified model's errors over the grid, appended to ``out`` per strategy."""
    err = _evaluate(study, [phi for phi, _, _ in fits.values()])
    ang = study.mech.angular
    real = np.concatenate(study.real)
    for (key, (phi, seconds, ok)), e in zip(fits.items(), err, strict=True):
        pos = np.sum(e[:, ~ang] ** 2, axis=1)
        o = out.setdefault(key, {k: [] for k in RESULT_KEYS})
        o["phi"].append(phi)
        o["param"].append((phi - real) / study.scale)
        o["pos_rms"].append(np.sqrt(pos.mean()))
        o["ang_rms"].append(np.sqrt(np.sum(e[:, ang] ** 2, axis=1).mean()) if ang.any() else 0.0)
        o["pos_sq"].append(pos)
        o["time"].append(seconds)
        # a model that cannot be evaluated (NaN errors) is a failed fit: left out, never compared
        o["converged"].append(bool(ok and np.all(np.isfinite(pos))))


def monte_carlo(
    study: st.Study,
    dc_sets: Sequence[np.ndarray],
    trad_sets: Mapping[str, np.ndarray],
    sigma: float,
    n_trials: int,
    seed: int,
) -> dict[str, dict[str, np.ndarray]]:
    """Seeded trials of D&C and of the traditional method on each of ``trad_sets``.

    Each trial measures every pose set with noise from its own stream (module docstring),
    identifies with each strategy from the nominal parameters by ``study.solver`` and evaluates
    the pose error over the grid. Every trial is kept, whether its fits converged or not:
    :mod:`mechlib.calibration.statistics` leaves the failed ones out of its comparisons.

    Returns
    -------
    dict
        Per strategy (``"dc"`` and the keys of ``trad_sets``), one entry per trial: ``phi``
        (trials, P) identified parameters; ``param`` (trials, P) their errors in units of
        ``study.scale``; ``pos_rms`` [m] and ``ang_rms`` [rad] workspace RMS errors; ``pos_sq``
        (trials, grid) squared position error at each grid pose [m²]; ``time`` solve time [s];
        ``converged`` whether every fit of the strategy converged and its model could be evaluated
        (a failed fit far from the real parameters has NaN errors and counts as not converged).

    Raises
    ------
    ValueError
        σ < 0, a bad trial count, a traditional key named like a D&C set (``dc…``), or a pose
        set that cannot identify its parameters.
    """
    sigma = check_float("sigma [m, rad]", sigma, low=0.0)
    n_trials = check_int("n_trials", n_trials, low=1, high=100_000)
    seed = check_int("seed", seed, low=0)
    m = study.mech
    if any(str(key).startswith("dc") for key in trad_sets):
        raise ValueError(f"traditional keys must not start with 'dc', got {list(trad_sets)}")
    labels = [f"dc{k}" for k in range(m.n_limbs)] + list(trad_sets)
    sets = [*dc_sets, *trad_sets.values()]
    if len(dc_sets) != m.n_limbs:
        raise ValueError(
            f"dc_sets must hold one pose set per leg ({m.n_limbs}), got {len(dc_sets)}"
        )
    out: dict = {}
    with threadpool_limits(1):
        for leg, idx in zip(m.legs, dc_sets, strict=True):
            ci.check_identifiable(leg.jacobian(leg.nominal, study.candidates[idx]), leg.names)
        for idx in trad_sets.values():
            ci.check_identifiable(ci.total_jacobian(m, m.nominal, study.candidates[idx]), m.names)
        # the noise-free measurements of every set, in one forward kinematics
        every = np.concatenate(sets)
        targets = study.candidates[every]
        q0 = cm.readings(m, m.nominal, targets)
        r0 = cm.forward(m, study.real, q0, targets, study.jac_candidates[every])
        cuts = np.cumsum([len(idx) for idx in sets])[:-1]
        exact = dict(
            zip(labels, zip(np.split(r0, cuts), np.split(q0, cuts), strict=True), strict=True)
        )
        for trial in range(n_trials):
            meas = {}
            for label, (r, q) in exact.items():
                g = _stream(seed, trial, label)
                meas[label] = (r + g.normal(0.0, sigma, r.shape), q + g.normal(0.0, sigma, q.shape))
            phis, ok, t_dc = [], True, 0.0
            for k, leg in enumerate(m.legs):
                r, q = meas[f"dc{k}"]
                t0 = time.perf_counter()
                fit = ci.identify_leg(leg, r, q[:, k], check=False, solver=study.solver)
                t_dc += time.perf_counter() - t0
                ok &= fit.converged
                phis.append(fit.phi)
            fits = {"dc": (np.concatenate(phis), t_dc, ok)}
            for key in trad_sets:
                t0 = time.perf_counter()
                fit = ci.identify_traditional(m, *meas[key], check=False, solver=study.solver)
                fits[key] = (fit.phi, time.perf_counter() - t0, fit.converged)
            _record(out, study, fits)
    return {key: {k: np.asarray(v) for k, v in o.items()} for key, o in out.items()}


@dataclass(frozen=True)
class Run:
    """Selected pose sets and the Monte Carlo of one mechanism at one pose budget."""

    n_per_leg: int
    shared: dict[str, int]
    dc_sets: list[np.ndarray]
    trad_sets: dict[str, np.ndarray]
    mc: dict[str, dict[str, np.ndarray]]


def run(
    study: st.Study,
    n_per_leg: int,
    sigma: float,
    n_trials: int,
    seed: int,
    budgets: Sequence[str] = st.BUDGETS,
) -> Run:
    """Select D&C's poses and the traditional poses of each of ``budgets``
    (:func:`mechlib.calibration.study.budgets`), then run :func:`monte_carlo`."""
    shared = st.budgets(study.mech, n_per_leg, budgets)
    dc = st.select_dc(study, n_per_leg)
    trad = {b: st.select_traditional(study, n) for b, n in shared.items()}
    return Run(n_per_leg, shared, dc, trad, monte_carlo(study, dc, trad, sigma, n_trials, seed))


def sweep(
    study: st.Study,
    sigmas: Sequence[float],
    counts: Sequence[int],
    n_trials: int,
    seed: int,
    *,
    budgets: Sequence[str] = st.BUDGETS,
    full: bool = False,
) -> list[dict[str, float]]:
    """D&C against each of ``budgets`` over noise levels and pose counts: one
    :func:`mechlib.calibration.statistics.compare` row per cell and budget.

    The cells are every ``(n, σ)`` pair (``full``: pose count by pose count, σ inside) or the
    cross through the first of each: the noise levels at ``counts[0]`` poses per leg, then the
    other pose counts at ``sigmas[0]``. Each cell runs :func:`monte_carlo` with ``seed``; the
    poses of a count are selected once.

    Returns
    -------
    list of dict
        ``sigma``, ``n_per_leg``, ``budget``, ``n_shared`` and the comparison's fields.
    """
    if full:
        cells = [(float(s), int(n)) for n in counts for s in sigmas]
    else:
        cells = [(float(s), int(counts[0])) for s in sigmas]
        cells += [(float(sigmas[0]), int(n)) for n in counts[1:]]
    chosen: dict[int, tuple] = {}
    rows = []
    for s, n in cells:
        if n not in chosen:
            shared = st.budgets(study.mech, n, budgets)
            trad = {b: st.select_traditional(study, k) for b, k in shared.items()}
            chosen[n] = (shared, st.select_dc(study, n), trad)
        shared, dc, trad = chosen[n]
        mc = monte_carlo(study, dc, trad, s, n_trials, seed)
        for b in budgets:
            rows.append(
                {"sigma": s, "n_per_leg": n, "budget": b, "n_shared": shared[b]} | cs.compare(mc, b)
            )
    return rows


def index_comparison(
    study: st.Study, n_per_leg: int, sigma: float, n_trials: int, seed: int
) -> dict[str, dict[str, float]]:
    """D&C with each leg's poses chosen by each observability index of
    :data:`mechlib.calibration.selection.INDICES` (greedy, same budget), and by chance: the
    workspace RMS position error [m] and the parameter RMS of a seeded Monte Carlo per index
    (over the trials whose fits converged), and both per trial (``pos_rms_each``,
    ``param_rms_each``; NaN where a fit did not converge) for :func:`index_pair`."""
    n = st.check_count(study, "n_per_leg", n_per_leg)
    rng = np.random.default_rng(check_int("seed", seed, low=0))
    out = {}
    with threadpool_limits(1):
        jacs = [leg.jacobian(leg.nominal, study.candidates) for leg in study.mech.legs]
        choices = {name: [sel.select_greedy(c, n, name) for c in jacs] for name in sel.INDICES}
    choices["random"] = [rng.choice(len(study.candidates), n, replace=False) for _ in jacs]
    for name, sets in choices.items():
        mc = monte_carlo(study, sets, {}, sigma, n_trials, seed)
        used = cs.used_trials(mc, ("dc",))
        param = np.asarray(mc["dc"]["param"], dtype=float)
        out[name] = {
            "pos_rms": float(mc["dc"]["pos_rms"][used].mean()),
            "param_rms": cs.parameter_rms(mc["dc"]["param"][used]),
            # per trial (NaN where a fit did not converge), paired across indices by the seed
            "pos_rms_each": np.where(used, mc["dc"]["pos_rms"], np.nan),
            "param_rms_each": np.where(used, np.sqrt(np.mean(param**2, axis=1)), np.nan),
        }
    return out


def index_pair(a: dict[str, object], b: dict[str, object]) -> list[float]:
    """Index ``a``'s poses against index ``b``'s over the trials both converged in (the same
    seeded disturbances: :func:`index_comparison`): ``[share of trials a's parameter RMS error is
    the smaller, Wilcoxon p, the same for the workspace RMS position error]``, as
    :func:`mechlib.calibration.statistics.paired_verdict` gives them.

    Raises
    ------
    ValueError
        When the two hold different numbers of trials, or no trial in common.
    """
    pairs = []
    for key in ("param_rms_each", "pos_rms_each"):
        x, y = np.asarray(a[key], dtype=float), np.asarray(b[key], dtype=float)
        if x.shape != y.shape:
            raise ValueError(f"{key}: the indices hold {x.shape} and {y.shape} trials")
        both = np.isfinite(x) & np.isfinite(y)
        if not both.any():
            raise ValueError(f"{key}: no trial converged for both indices")
        verdict = cs.paired_verdict(x[both], y[both])
        pairs += [verdict["share_a_better"], verdict["p_value"]]
    return pairs
