"""The claims registry: every claim the book judges, each with one verdict computed once.

A claim is a statement the book gives a verdict on — a claim of the thesis (with its section,
equation, table or figure) or a finding of ours. Each :class:`ClaimSpec` names the page (notebook)
that records its evidence, the record keys the verdict is computed from and the rule
(:class:`Test`: one per part of the claim). The verdict follows from the parts:

- a thesis claim is **supported** when every part holds, **not supported** when none does, and
  **mixed** when the evidence splits;
- a finding of ours **holds**, **does not hold**, or is **mixed** likewise.

A part that holds by construction on our model is the claim tested in the thesis's own setting —
a linear FE analysis, which our linear model reproduces — and it counts in the verdict: a claim
that holds there and fails on a geometrically non-linear model is **mixed**, its report row marks
the part "(by construction)", and the pages say which part is which.

A notebook records the evidence, then calls :meth:`mechlib.reporting.records.Recorder.claim`,
which evaluates the rule here, records the verdict word under ``claims.<id>`` and adds the claim's
report row. The book's pages never compose a verdict word: they quote it by id (the ``verdict``
role of the book build), and the build checks that no page gives a claim another word and that no
verdict word stands outside a quoted claim.

The claims themselves are listed in :mod:`mechlib.reporting.claimlist`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from mechlib.calibration.statistics import CLAIM_MAX_P, CLAIM_MIN_SHARE
from mechlib.reporting import categories as cat

SUPPORTED, NOT_SUPPORTED, MIXED = "supported", "not supported", "mixed"
HOLDS, DOES_NOT_HOLD = "holds", "does not hold"
#: every verdict word, longest first (a page check finds them in this order)
VERDICT_WORDS = (NOT_SUPPORTED, DOES_NOT_HOLD, SUPPORTED, HOLDS, MIXED)
#: what a claim's report row shows as its published value
CLAIM_PUBLISHED = "(claim)"
#: D&C "wins" a paired comparison when it is better in more than this share of the trials and
#: the Wilcoxon signed-rank test rejects "no difference" at this level (two-sided): the
#: calibration core's rule (:func:`mechlib.calibration.statistics.claim_holds`), one definition
PAIRED_MIN_SHARE, PAIRED_MAX_P = CLAIM_MIN_SHARE, CLAIM_MAX_P

#: A record reference: a key, or a key and an index into its value (or "min"/"max" of it).
Ref = str | tuple[str, object]


def read(values: Mapping[str, Any], ref: Ref) -> Any:
    """The recorded value ``ref`` names, from a record's ``values`` (entries ``{"value": …}``)
    or its ``timings`` merged in (plain numbers).

    Raises
    ------
    KeyError
        Naming the key when it was not recorded.
    """
    key, index = (ref, None) if isinstance(ref, str) else ref
    if key not in values:
        raise KeyError(f"claims: the record has no value {key!r}")
    entry = values[key]
    value = entry["value"] if isinstance(entry, Mapping) else entry
    if index in ("min", "max"):
        return float(getattr(np.asarray(value, dtype=float), index)())
    return value if index is None else np.asarray(value)[index].tolist()


@dataclass(frozen=True)
class Test:
    """One part of a claim: a rule over recorded values, with what it reads in words.

    Attributes
    ----------
    label : str
        The part, e.g. ``"workspace RMS error"`` or ``"on the linear FE model"``.
    refs : tuple of Ref
        The recorded values the rule reads, in the order ``rule`` takes them.
    rule : callable
        ``rule(*values) -> bool``: whether the part holds.
    describe : callable
        ``describe(*values) -> str``: the evidence in words (numbers included).
    by_construction : bool
        The part holds by construction on our model (e.g. a linear model is linear): it is shown,
        and counted in the verdict, but it is no independent evidence.
    """

    label: str
    refs: tuple[Ref, ...]
    rule: Callable[..., bool]
    describe: Callable[..., str]
    by_construction: bool = False

    def values(self, values: Mapping[str, Any]) -> list[Any]:
        """The values this part reads (see :func:`read`)."""
        return [read(values, r) for r in self.refs]


@dataclass(frozen=True)
class ClaimSpec:
    """A claim the book judges.

    Attributes
    ----------
    id : str
        Stable identifier, dotted: ``"ch3.iii.5r.table8"``, ``"ours.b5r.6ups.iii.matched"``.
    source : {"thesis", "ours"}
        A claim of the thesis, or a finding of ours (never counted with the thesis's claims).
    where : str
        For a thesis claim its section and artefact (``"sec. 3.8 (iii); Figs 13–14"``); for ours
        the artefact or section of the book it belongs to.
    statement : str
        The claim in one sentence.
    page : str
        The notebook that records its evidence and its verdict.
    parts : tuple of Test
        The rule, one test per part.
    setting : str
        The setting the verdict holds for, a ``str.format`` template over ``setting_refs`` (the
        budget of a calibration comparison); empty when there is one setting only.
    setting_refs : mapping of str to Ref
        The recorded values the setting names.
    """

    id: str
    source: str
    where: str
    statement: str
    page: str
    parts: tuple[Test, ...]
    setting: str = ""
    setting_refs: Mapping[str, Ref] | None = None

    def __post_init__(self) -> None:
        cat.check_kinds(cat.BASIS_INDEPENDENT, self.source)
        if not self.parts:
            raise ValueError(f"claim {self.id!r} has no part to test")


@dataclass(frozen=True)
class Verdict:
    """A claim's verdict as computed from the records."""

    spec: ClaimSpec
    word: str
    holds: tuple[bool, ...]
    evidence: str
    setting: str

    @property
    def category(self) -> str:
        """The report category of the claim's row (:mod:`mechlib.reporting.categories`)."""
        if self.spec.source == cat.SOURCE_OURS:
            return cat.CAT_OURS
        return {
            SUPPORTED: cat.CAT_SUPPORTED,
            NOT_SUPPORTED: cat.CAT_NOT_SUPPORTED,
            MIXED: cat.CAT_MIXED,
        }[self.word]

    def row(self) -> dict[str, Any]:
        """The claim's report row (fields as :func:`mechlib.reporting.report.claim_row`'s)."""
        quantity = self.spec.statement + (f" — {self.setting}" if self.setting else "")
        return {
            "artefact": self.spec.where,
            "quantity": quantity,
            "published": CLAIM_PUBLISHED,
            "ours": self.evidence,
            "max_abs_diff": None,
            "max_rel_diff": None,
            "difference": None,
            "verdict": self.word,
            "category": self.category,
            "source": self.spec.source,
            "basis": cat.BASIS_INDEPENDENT,
            "n_values": len(self.holds),
            "n_agree": int(sum(self.holds)),
            "difference_text": "—",
            "claim": self.spec.id,
        }


def verdict_word(source: str, holds: Sequence[bool]) -> str:
    """The verdict word of a claim whose parts hold or not (see the module's rules)."""
    n, n_hold = len(holds), int(sum(holds))
    if not n:
        raise ValueError("a verdict needs at least one part")
    thesis = source == cat.SOURCE_THESIS
    if n_hold == n:
        return SUPPORTED if thesis else HOLDS
    if n_hold == 0:
        return NOT_SUPPORTED if thesis else DOES_NOT_HOLD
    return MIXED


def evaluate(spec: ClaimSpec, values: Mapping[str, Any]) -> Verdict:
    """The verdict of ``spec`` from a record's values (and timings, merged in).

    Raises
    ------
    KeyError
        When a value the rule reads was not recorded (naming it and the claim).
    """
    try:
        read_parts = [(t, t.values(values)) for t in spec.parts]
        setting = spec.setting.format(
            **{k: read(values, r) for k, r in (spec.setting_refs or {}).items()}
        )
    except KeyError as err:
        raise KeyError(f"claim {spec.id!r} (page {spec.page}): {err.args[0]}") from None
    holds = tuple(bool(t.rule(*v)) for t, v in read_parts)
    evidence = "; ".join(
        f"{t.label}{' (by construction)' if t.by_construction else ''}: {t.describe(*v)} "
        f"({'met' if h else 'not met'})"
        for (t, v), h in zip(read_parts, holds, strict=True)
    )
    return Verdict(spec, verdict_word(spec.source, holds), holds, evidence, setting)


# --- rules ----------------------------------------------------------------------------------


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
        )
    return Test(
        label,
        (ref,),
        lambda v: float(_num(v).max()) <= limit,
        lambda v: f"{what} {_q(float(_num(v).max()), unit)} (at most {_q(limit, unit, '.4g')})",
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
    )


def timed_below(label: str, ref: Ref, limit: float, unit: str) -> Test:
    """A measured time (a record's timing) is below ``limit``. Its value is not written into the
    evidence (a timing differs between runs; the page quotes it as measured), and the limit must
    leave a margin of orders of magnitude, so that no machine of ours flips the verdict."""
    return Test(
        label,
        (ref,),
        lambda v: float(v) < limit,
        lambda v: f"measured on the machine that built the book, below {_q(limit, unit, 'g')}",
    )


def all_above(label: str, ref: Ref, limit: float, unit: str = "") -> Test:
    """Every recorded value is above ``limit`` (e.g. a share of trials in every cell)."""
    return Test(
        label,
        (ref,),
        lambda v: bool(np.all(_num(v) > limit)),
        lambda v: (
            f"smallest {_q(float(_num(v).min()), unit)} of {np.size(v)} (each above "
            f"{_q(limit, unit, 'g')})"
        ),
    )


def exceeds(label: str, ref: Ref, limit: float, what: str = "") -> Test:
    """The recorded number is greater than ``limit``."""
    return Test(
        label,
        (ref,),
        lambda v: float(v) > limit,
        lambda v: f"{what + ' ' if what else ''}{float(v):.4g} (more than {limit:g})",
    )


def greater(label: str, a: Ref, b: Ref, names: tuple[str, str], fmt: str = ".3g") -> Test:
    """The value ``a`` is greater than ``b`` (named ``names``)."""
    return Test(
        label,
        (a, b),
        lambda x, y: float(x) > float(y),
        lambda x, y: f"{names[0]} {float(x):{fmt}} against {names[1]} {float(y):{fmt}}",
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
    )


def with_construction(test: Test) -> Test:
    """The same test, marked as holding by construction on our model."""
    return Test(test.label, test.refs, test.rule, test.describe, by_construction=True)
