"""Statistics of a :func:`mechlib.calibration.montecarlo.monte_carlo` result: paired comparisons
of D&C with a traditional budget, the local RMS error over the grid, summaries.

A result holds, per strategy, one entry per trial (``converged`` says whether the strategy's
fits converged in it). With ``drop_failed`` (the default) a comparison leaves out every trial in
which a fit of *either* strategy did not converge, from both strategies at once, so that they
stay paired trial by trial; those trials are listed (:func:`failed_trials`), never averaged in.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from scipy import stats

#: D&C "wins" a comparison when it is better in more than this share of the paired trials ...
CLAIM_MIN_SHARE = 0.5
#: ... and the Wilcoxon signed-rank test rejects "no difference" at this level (two-sided).
CLAIM_MAX_P = 0.05
#: Metres to micrometres and seconds to milliseconds, for the summary's rows.
UM_PER_M = 1e6
MS_PER_S = 1e3

Result = Mapping[str, Mapping[str, np.ndarray]]


def failed_trials(mc: Result, keys: Sequence[str]) -> np.ndarray:
    """Indices of the trials in which a fit of some strategy of ``keys`` did not converge."""
    ok = np.logical_and.reduce([np.asarray(mc[k]["converged"], dtype=bool) for k in keys])
    return np.flatnonzero(~ok)


def used_trials(mc: Result, keys: Sequence[str], drop_failed: bool = True) -> np.ndarray:
    """Mask of the trials a comparison of ``keys`` uses: every trial, or (``drop_failed``) those
    in which every fit of every strategy of ``keys`` converged.

    Raises
    ------
    RuntimeError
        If no trial is left.
    """
    n = len(mc[keys[0]]["converged"])
    used = np.ones(n, dtype=bool)
    if drop_failed:
        used[failed_trials(mc, keys)] = False
    if not used.any():
        raise RuntimeError(f"no Monte Carlo trial converged for {list(keys)} ({n} trials)")
    return used


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


def parameter_rms(errors: np.ndarray, per_parameter: bool = False) -> float | np.ndarray:
    """RMS of parameter errors (trials, P): over everything, or per parameter (P,). In units of
    the disturbance's scale, 1 is the size of the disturbance."""
    e = np.asarray(errors, dtype=float)
    if e.ndim != 2:
        raise ValueError(f"errors must be (trials, parameters), got shape {e.shape}")
    return np.sqrt(np.mean(e**2, axis=0)) if per_parameter else float(np.sqrt(np.mean(e**2)))


def compare(mc: Result, trad_key: str, drop_failed: bool = True) -> dict[str, float]:
    """D&C against one traditional budget over the paired trials (:func:`used_trials`).

    Returns
    -------
    dict
        Means and medians over the trials of the workspace RMS position [m] and orientation
        [rad] errors (``pos_rms_dc``, ``pos_rms_median_dc``, ``ang_rms_dc``, and ``_trad``);
        ``param_rms_dc``/``_trad`` in units of the disturbance; D&C's share of better trials and
        the Wilcoxon p-value on the workspace RMS (``share_dc_better``, ``p_value``) and on each
        trial's parameter RMS (``param_share_dc_better``, ``param_p_value``); ``holds``
        (:func:`claim_holds` on the workspace RMS, 1.0 or 0.0); ``trials_used`` and
        ``failed_trials`` (counts).
    """
    used = used_trials(mc, ("dc", trad_key), drop_failed)
    dc = {k: np.asarray(v)[used] for k, v in mc["dc"].items()}
    tr = {k: np.asarray(v)[used] for k, v in mc[trad_key].items()}
    verdict = paired_verdict(dc["pos_rms"], tr["pos_rms"])
    par = paired_verdict(
        np.sqrt(np.mean(dc["param"] ** 2, axis=1)), np.sqrt(np.mean(tr["param"] ** 2, axis=1))
    )
    return {
        "pos_rms_dc": float(dc["pos_rms"].mean()),
        "pos_rms_trad": float(tr["pos_rms"].mean()),
        "pos_rms_median_dc": float(np.median(dc["pos_rms"])),
        "pos_rms_median_trad": float(np.median(tr["pos_rms"])),
        "ang_rms_dc": float(dc["ang_rms"].mean()),
        "ang_rms_trad": float(tr["ang_rms"].mean()),
        "param_rms_dc": parameter_rms(dc["param"]),
        "param_rms_trad": parameter_rms(tr["param"]),
        "share_dc_better": verdict["share_a_better"],
        "p_value": verdict["p_value"],
        "param_share_dc_better": par["share_a_better"],
        "param_p_value": par["p_value"],
        "holds": float(claim_holds(verdict)),
        "trials_used": int(used.sum()),
        "failed_trials": int((~used).sum()),
    }


def local_rms(
    mc: Result, key: str, paired_with: Sequence[str] = (), drop_failed: bool = True
) -> np.ndarray:
    """Local RMS position error [m] at each grid pose over the trials of strategy ``key`` (the
    trials a comparison with ``paired_with`` uses: Fig 14)."""
    used = used_trials(mc, (key, *paired_with), drop_failed)
    return np.sqrt(np.mean(np.asarray(mc[key]["pos_sq"])[used], axis=0))


def summary(mc: Result, trad_key: str, drop_failed: bool = True) -> dict[str, dict[str, float]]:
    """Per strategy (``dc``, ``trad_key``), over the paired trials: the workspace RMS error's
    mean, 95 % confidence interval and median [µm], the parameter RMS [units of the
    disturbance] and the median solve time [ms]."""
    used = used_trials(mc, ("dc", trad_key), drop_failed)
    rows = {}
    for key in ("dc", trad_key):
        rms = np.asarray(mc[key]["pos_rms"])[used]
        mean, lo, hi = mean_ci(rms)
        rows[key] = {
            "workspace RMS mean [µm]": UM_PER_M * mean,
            "95 % CI low [µm]": UM_PER_M * lo,
            "95 % CI high [µm]": UM_PER_M * hi,
            "workspace RMS median [µm]": UM_PER_M * float(np.median(rms)),
            "param. RMS [σ_dist]": parameter_rms(np.asarray(mc[key]["param"])[used]),
            "solve time median [ms]": MS_PER_S
            * float(np.median(np.asarray(mc[key]["time"])[used])),
        }
    return rows
