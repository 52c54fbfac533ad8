"""The rules a claim's parts are made of (:class:`mechlib.reporting.claims.Test` factories).

Each returns a :class:`~mechlib.reporting.claims.Test`: a rule over recorded values and the
words that describe its evidence; :func:`with_construction` marks one that cannot fail (shown,
never counted). The claims are registered in :mod:`mechlib.reporting.thesisclaims`,
:mod:`mechlib.reporting.ourclaims` and :mod:`mechlib.reporting.mechanismclaims`.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from mechlib.calibration.statistics import CLAIM_MAX_P, CLAIM_MIN_SHARE
from mechlib.reporting.claims import Ref, Test

#: D&C "wins" a paired comparison when it is better in more than this share of the trials and
#: the Wilcoxon signed-rank test rejects "no difference" at this level (two-sided): the
#: calibration core's rule (:func:`mechlib.calibration.statistics.claim_holds`), one definition
PAIRED_MIN_SHARE, PAIRED_MAX_P = CLAIM_MIN_SHARE, CLAIM_MAX_P


def _num(x: Any) -> np.ndarray:
    return np.asarray(x, dtype=float)


def _q(value: float, unit: str, fmt: str = ".3g") -> str:
    """A number with its unit (none when ``unit`` is empty)."""
    return f"{value:{fmt}} {unit}".rstrip()


def paired(label: str, share: Ref, p_value: Ref, what: str = "D&C") -> Test:
    """``what`` is better in more than :data:`PAIRED_MIN_SHARE` of the paired trials and the
    Wilcoxon signed-rank test rejects "no difference" at :data:`PAIRED_MAX_P`."""
    return Test(
        label,
        (share, p_value),
        lambda s, p: s > PAIRED_MIN_SHARE and p < PAIRED_MAX_P,
        lambda s, p: f"{what} better in {100 * s:.0f} % of the paired trials, Wilcoxon p = {p:.2g}",
        kind="paired",
        limit={"share above": PAIRED_MIN_SHARE, "Wilcoxon p below": PAIRED_MAX_P},
    )


def at_most(
    label: str, ref: Ref, limit: float, unit: str, what: str = "largest", strict: bool = False
) -> Test:
    """The largest of the recorded values is at most ``limit`` (in ``unit``; below it when
    ``strict``)."""
    if strict:
        return Test(
            label,
            (ref,),
            lambda v: float(_num(v).max()) < limit,
            lambda v: f"{what} {_q(float(_num(v).max()), unit)} (below {_q(limit, unit, 'g')})",
            kind="at_most",
            limit=limit,
        )
    return Test(
        label,
        (ref,),
        lambda v: float(_num(v).max()) <= limit,
        lambda v: f"{what} {_q(float(_num(v).max()), unit)} (at most {_q(limit, unit, '.4g')})",
        kind="at_most",
        limit=limit,
    )


def within(label: str, ref: Ref, limit: Ref, unit: str, what: str = "largest") -> Test:
    """The largest of the recorded values is at most the recorded ``limit`` (a parameter of the
    page, e.g. its accuracy budget)."""
    return Test(
        label,
        (ref, limit),
        lambda v, lim: float(_num(v).max()) <= float(lim),
        lambda v, lim: (
            f"{what} {_q(float(_num(v).max()), unit)} (at most {_q(float(lim), unit, '.4g')})"
        ),
        kind="within",
        limit=None,
    )


def each_within(label: str, ref: Ref, limits: Ref, unit: str) -> Test:
    """Each recorded value is at most the recorded limit of the same index (e.g. a difference
    per quantity against a tolerance per quantity)."""
    return Test(
        label,
        (ref, limits),
        lambda v, lim: bool(np.all(_num(v) <= _num(lim))),
        lambda v, lim: "; ".join(
            f"{_q(a, unit)} (at most {_q(b, unit, '.4g')})"
            for a, b in zip(_num(v).ravel(), _num(lim).ravel(), strict=True)
        ),
        kind="each_within",
        limit=None,
    )


def at_least(
    label: str, ref: Ref, limit: float, unit: str, what: str = "smallest", reduce: str = "min"
) -> Test:
    """The smallest (``reduce="min"``) or largest (``"max"``) of the recorded values is at
    least ``limit`` (in ``unit``)."""
    if reduce not in ("min", "max"):
        raise ValueError(f"reduce must be 'min' or 'max', got {reduce!r}")
    return Test(
        label,
        (ref,),
        lambda v: float(getattr(_num(v), reduce)()) >= limit,
        lambda v: (
            f"{what} {float(getattr(_num(v), reduce)()):.3g} {unit} (at least {limit:.4g} {unit})"
        ),
        kind="at_least",
        limit=limit,
    )


def timed_below(label: str, ref: Ref, limit: float | Ref, unit: str) -> Test:
    """A measured time (a record's timing) is below ``limit`` (a number, or the record that holds
    it, e.g. a page's deadline parameter). Its value is not written into the evidence (a timing
    differs between runs; the page quotes it as measured), and the limit must leave a margin of
    an order of magnitude at least, so that no machine of ours flips the verdict."""
    if isinstance(limit, int | float):
        return Test(
            label,
            (ref,),
            lambda v: float(v) < limit,
            lambda v: f"measured on the machine that built the book, below {_q(limit, unit, 'g')}",
            kind="timed_below",
            limit=limit,
        )
    return Test(
        label,
        (ref, limit),
        lambda v, lim: float(v) < float(lim),
        lambda v, lim: (
            f"measured on the machine that built the book, below {_q(float(lim), unit, 'g')}"
        ),
        kind="timed_below",
    )


def all_above(label: str, ref: Ref, limit: float, unit: str = "") -> Test:
    """Every recorded value is above ``limit`` (e.g. a share of trials in every cell)."""
    return Test(
        label,
        (ref,),
        lambda v: bool(np.all(_num(v) > limit)),
        lambda v: (
            f"smallest {_q(float(_num(v).min()), unit)}, largest {_q(float(_num(v).max()), unit)} "
            f"over {np.size(v)} values (each must exceed {_q(limit, unit, 'g')})"
        ),
        kind="all_above",
        limit=limit,
    )


def exceeds(label: str, ref: Ref, limit: float, what: str = "") -> Test:
    """The recorded number is greater than ``limit``."""
    return Test(
        label,
        (ref,),
        lambda v: float(v) > limit,
        lambda v: f"{what + ' ' if what else ''}{float(v):.4g} (more than {limit:g})",
        kind="exceeds",
        limit=limit,
    )


def greater(label: str, a: Ref, b: Ref, names: tuple[str, str], fmt: str = ".3g") -> Test:
    """The value ``a`` is greater than ``b`` (named ``names``)."""
    return Test(
        label,
        (a, b),
        lambda x, y: float(x) > float(y),
        lambda x, y: f"{names[0]} {float(x):{fmt}} against {names[1]} {float(y):{fmt}}",
        kind="greater",
        limit=None,
    )


def is_true(label: str, ref: Ref, describe: str) -> Test:
    """Every element of a recorded boolean (a computed test named by ``describe``) is true."""
    return Test(
        label,
        (ref,),
        lambda v: bool(np.all(np.asarray(v, dtype=bool))),
        lambda v: (
            f"{describe}: {'yes' if np.all(v) else 'no'}"
            if np.size(v) == 1
            else f"{describe}: {int(np.sum(v))} of {np.size(v)} true"
        ),
        kind="is_true",
        limit=True,
    )


def with_construction(test: Test, why: str) -> Test:
    """The same test, marked as one that cannot fail (shown, never counted), for reason ``why``
    (e.g. ``"a linear model is linear"``)."""
    return replace(test, by_construction=True, why=why)
