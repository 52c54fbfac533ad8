"""Screening analysis of two-level designs: main effects and Lenth's method.

Definitions follow Lenth (1989), "Quick and easy analysis of unreplicated factorials",
Technometrics 31(4), 469–473, as also implemented by the R package BsMD (``LenthPlot``):

- ``s0 = 1.5 · median |c_j|`` over the ``m`` effects,
- ``PSE = 1.5 · median { |c_j| : |c_j| < 2.5 s0 }`` (pseudo standard error),
- ``ME = t(0.975; d) · PSE`` and ``SME = t(γ; d) · PSE`` with ``d = m / 3`` degrees of freedom
  and ``γ = (1 + 0.95^(1/m)) / 2`` (simultaneous margin of error).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import stats

from mechlib.doe import check_design
from mechlib.params import check_float, check_int, check_matrix

S0_FACTOR = 1.5
"""Lenth (1989): consistency factor of the median of |effects| for normal effects."""
TRIM_FACTOR = 2.5
"""Lenth (1989): effects larger than 2.5 s0 are treated as active and left out of the PSE."""
MIN_EFFECTS = 3
"""Lenth's method needs at least three effects (d = m/3 >= 1 degree of freedom)."""


def main_effects(design: object, responses: object) -> np.ndarray:
    """Main effects of a two-level design: mean response at +1 minus mean at -1.

    Parameters
    ----------
    design : array_like, shape (runs, factors)
        Two-level design with entries ±1 and balanced columns.
    responses : array_like, shape (runs,) or (runs, outputs)

    Returns
    -------
    numpy.ndarray, shape (factors,) or (factors, outputs)

    Raises
    ------
    ValueError
        If the design is not two-level, a column is not balanced, or the run counts differ.

    Examples
    --------
    A main effect is twice the slope of a linear response in coded units:

    >>> from mechlib.doe import plackett_burman
    >>> x = plackett_burman(12)
    >>> y = 10.0 + 3.0 * x[:, 0] - 0.5 * x[:, 4]
    >>> bool(np.allclose(main_effects(x, y), [6.0, 0, 0, 0, -1.0, 0, 0, 0, 0, 0, 0]))
    True
    """
    x = check_design(design, two_level=True)
    y = np.asarray(responses, dtype=float)
    one_d = y.ndim == 1
    y = check_matrix("responses", y[:, None] if one_d else y, shape=(x.shape[0], None))
    plus = (x > 0).sum(axis=0)
    if np.any(plus * 2 != x.shape[0]):
        bad = int(np.argmax(plus * 2 != x.shape[0]))
        raise ValueError(
            f"design column {bad} is not balanced: {int(plus[bad])} of {x.shape[0]} runs at +1"
        )
    effects = x.T @ y / (x.shape[0] / 2)
    return effects[:, 0] if one_d else effects


@dataclass(frozen=True)
class Lenth:
    """Result of Lenth's analysis of one response."""

    m: int
    """number of effects"""
    median_abs: float
    """median of |effects| (the thesis's ν)"""
    s0: float
    """initial scale estimate 1.5 ν"""
    pse: float
    """pseudo standard error"""
    d: float
    """degrees of freedom m/3"""
    gamma: float
    """quantile used for the simultaneous margin"""
    me: float
    """margin of error"""
    sme: float
    """simultaneous margin of error"""

    def active(self, effects: np.ndarray, simultaneous: bool = False) -> np.ndarray:
        """Mask of effects whose magnitude exceeds ME (or SME)."""
        return np.abs(np.asarray(effects)) > (self.sme if simultaneous else self.me)


def lenth(effects: object, alpha: float = 0.05) -> Lenth:
    """Lenth's pseudo standard error and margins of error for one set of effects.

    Parameters
    ----------
    effects : array_like, shape (m,)
        Effect estimates (contrasts), m >= 3.
    alpha : float
        Two-sided level, in (0, 0.5]; 0.05 gives the 0.975 quantile of Lenth (1989).

    Returns
    -------
    Lenth

    Raises
    ------
    ValueError
        Fewer than three effects, non-finite effects, or ``alpha`` out of range.

    Examples
    --------
    Six effects, one of them active: ν = median |c| = 1.5, s0 = 2.25; the five effects below
    2.5 s0 have median 1, so PSE = 1.5 and ME = t(0.975; d = 2) · PSE.

    >>> effects = [1.0, -1.0, 2.0, -2.0, 1.0, 30.0]
    >>> res = lenth(effects)
    >>> res.median_abs, res.s0, res.pse, res.d
    (1.5, 2.25, 1.5, 2.0)
    >>> round(res.me, 3), round(res.sme, 3)
    (6.454, 16.154)
    >>> res.active(effects).tolist()
    [False, False, False, False, False, True]
    >>> lenth(effects, alpha=0.7)
    Traceback (most recent call last):
    ...
    ValueError: alpha must be in (0.0, 0.5], got 0.7
    """
    c = np.abs(np.asarray(effects, dtype=float).ravel())
    check_int("number of effects", c.size, low=MIN_EFFECTS)
    if not np.all(np.isfinite(c)):
        raise ValueError("effects must be finite")
    alpha = check_float("alpha", alpha, low=0.0, high=0.5, low_open=True)
    m = c.size
    nu = float(np.median(c))
    s0 = S0_FACTOR * nu
    trimmed = c[c < TRIM_FACTOR * s0]
    pse = S0_FACTOR * float(np.median(trimmed)) if trimmed.size else 0.0
    d, gamma, me, sme = _margins(pse, m, alpha)
    return Lenth(m=m, median_abs=nu, s0=s0, pse=pse, d=d, gamma=gamma, me=me, sme=sme)


def _margins(scale: float, m: int, alpha: float) -> tuple[float, float, float, float]:
    """Lenth's margins for a checked scale, effect count and level: ``(d, γ, ME, SME)``.

    ``d = m / 3``, ``γ = (1 + (1 − α)^(1/m)) / 2``, ``ME = t(1 − α/2; d) · scale`` and
    ``SME = t(γ; d) · scale`` (the module docstring's formulas, for any α).
    """
    d = m / 3.0
    gamma = (1.0 + (1.0 - alpha) ** (1.0 / m)) / 2.0
    me = float(stats.t.ppf(1.0 - alpha / 2.0, d)) * scale
    sme = float(stats.t.ppf(gamma, d)) * scale
    return d, gamma, me, sme


def margins_from_scale(scale: float, m: int, alpha: float = 0.05) -> tuple[float, float]:
    """ME and SME for a given scale estimate and number of effects (no trimming step).

    Used to test hypotheses about how a published margin was computed.

    Parameters
    ----------
    scale : float
        Scale estimate (a PSE, or another estimate to test), >= 0.
    m : int
        Number of effects, >= 3.
    alpha : float
        Two-sided level, in (0, 0.5].

    Returns
    -------
    tuple of float
        ``(ME, SME)``, the same formulas as :func:`lenth` with ``scale`` in place of the PSE.

    Examples
    --------
    >>> res = lenth([1.0, -1.0, 2.0, -2.0, 1.0, 30.0])
    >>> margins_from_scale(res.pse, res.m) == (res.me, res.sme)
    True
    """
    scale = check_float("scale", scale, low=0.0)
    m = check_int("m", m, low=MIN_EFFECTS)
    alpha = check_float("alpha", alpha, low=0.0, high=0.5, low_open=True)
    return _margins(scale, m, alpha)[2:]


def half_normal_points(effects: object) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Coordinates of a half-normal probability plot.

    Returns
    -------
    order : numpy.ndarray
        Indices of the effects sorted by increasing magnitude.
    abs_effects : numpy.ndarray
        Sorted |effects|.
    quantiles : numpy.ndarray
        Half-normal quantiles ``Φ⁻¹(0.5 + 0.5 (i - 0.5) / m)``, i = 1..m.
    """
    c = np.abs(np.asarray(effects, dtype=float).ravel())
    check_int("number of effects", c.size, low=1)
    order = np.argsort(c, kind="stable")
    m = c.size
    q = stats.norm.ppf(0.5 + 0.5 * (np.arange(1, m + 1) - 0.5) / m)
    return order, c[order], q


def pareto_order(effects: object) -> np.ndarray:
    """Indices of effects sorted by decreasing magnitude (ties keep factor order).

    Examples
    --------
    >>> pareto_order([0.1, -3.0, 2.0]).tolist()
    [1, 2, 0]
    """
    c = np.abs(np.asarray(effects, dtype=float).ravel())
    return np.argsort(-c, kind="stable")


#: an effect "mainly affects" a response when its magnitude is at least this share of the largest
DOMINANT_FRACTION = 0.01


def dominant(effects: object, fraction: float = DOMINANT_FRACTION) -> np.ndarray:
    """Mask of effects whose magnitude is at least ``fraction`` of the largest one.

    A magnitude criterion for "mainly affected by", suited to noise-free computer experiments
    where Lenth's PSE collapses to (numerically) zero and every non-zero contrast is
    "significant".

    Parameters
    ----------
    effects : array_like, shape (m,)
    fraction : float
        In (0, 1].

    Examples
    --------
    >>> dominant([100.0, 0.5, 2.0, -50.0]).tolist()  # |effect| >= 1 % of the largest
    [True, False, True, True]
    """
    c = np.abs(np.asarray(effects, dtype=float).ravel())
    fraction = check_float("fraction", fraction, low=0.0, high=1.0, low_open=True)
    return c >= fraction * c.max() if c.max() > 0 else np.zeros(c.size, dtype=bool)


def lenth_columns(effects: object, alpha: float = 0.05) -> list[Lenth]:
    """:func:`lenth` of each response: one analysis per column of ``effects`` (factors, outputs)."""
    c = check_matrix("effects", effects)
    return [lenth(c[:, j], alpha=alpha) for j in range(c.shape[1])]


def lenth_summary(lenths: list[Lenth], fields: tuple[str, ...]) -> np.ndarray:
    """(fields, outputs) array of :class:`Lenth` attributes, e.g. ``("median_abs", "me")``."""
    unknown = sorted(set(fields) - set(Lenth.__dataclass_fields__))
    if unknown:
        raise ValueError(
            f"fields {unknown} are not Lenth results; have {list(Lenth.__dataclass_fields__)}"
        )
    return np.array([[getattr(lz, f) for lz in lenths] for f in fields], dtype=float)


def dominant_columns(effects: object, fraction: float = DOMINANT_FRACTION) -> np.ndarray:
    """:func:`dominant` per response: a (factors, outputs) mask, each column against its own
    largest effect."""
    c = check_matrix("effects", effects)
    return np.column_stack([dominant(c[:, j], fraction) for j in range(c.shape[1])])


def active_columns(effects: object, lenths: list[Lenth], simultaneous: bool = False) -> np.ndarray:
    """Lenth-active effects per response: a (factors, outputs) mask, column j judged by
    ``lenths[j]`` (:meth:`Lenth.active`)."""
    c = check_matrix("effects", effects, shape=(None, len(lenths)))
    return np.column_stack([lz.active(c[:, j], simultaneous) for j, lz in enumerate(lenths)])


def factor_sets(mask: object, factors: tuple[str, ...] | list[str]) -> list[frozenset[str]]:
    """The names of the factors marked in each column of a (factors, outputs) mask."""
    m = np.asarray(mask, dtype=bool)
    if m.ndim != 2 or m.shape[0] != len(factors):
        raise ValueError(f"mask must be ({len(factors)}, outputs), got shape {m.shape}")
    names = np.asarray(factors)
    return [frozenset(names[col].tolist()) for col in m.T]
