"""The claims registry: every claim the book judges, each with one verdict computed once.

A claim is a statement the book gives a verdict on — a claim of the thesis (with its section,
equation, table or figure) or a finding of ours. Each :class:`ClaimSpec` names the page (notebook)
that records its evidence, the record keys the verdict is computed from and the rule
(:class:`Test`: one per part of the claim). The verdict follows from the parts that could fail:

- a thesis claim is **supported** when every such part holds, **not supported** when none does,
  and **mixed** when the evidence splits;
- a finding of ours **holds**, **does not hold**, or is **mixed** likewise;
- a claim with no part that could fail reads **consistent by construction**.

A part that cannot fail — it holds by construction on our model (a linear FE model is linear), or
it is arithmetic on published values (a flop count from the parameter counts) — is shown with the
claim's evidence, marked and with the reason it cannot fail, and never counted: a claim that holds
on a linear FE model and fails on a geometrically non-linear one is **not supported**, in the
setting it was tested in. :class:`Verdict` refuses a word that counts such a part, and a part
that "cannot fail" but fails is an error of the registry, raised as one.

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

from mechlib.reporting import categories as cat

SUPPORTED, NOT_SUPPORTED, MIXED = "supported", "not supported", "mixed"
HOLDS, DOES_NOT_HOLD = "holds", "does not hold"
#: the word of a claim none of whose parts could fail (also the name of a comparison category,
#: so the page check does not look for it in prose)
BY_CONSTRUCTION = cat.CAT_CONSTRUCTION
#: every verdict word a test that could fail gives, longest first (a page check finds them in
#: this order)
VERDICT_WORDS = (NOT_SUPPORTED, DOES_NOT_HOLD, SUPPORTED, HOLDS, MIXED)
#: every word a claim may read
WORDS = (*VERDICT_WORDS, BY_CONSTRUCTION)
#: what a claim's report row shows as its published value
CLAIM_PUBLISHED = "(claim)"

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
        The part cannot fail: it holds by construction on our model (a linear model is linear) or
        is arithmetic on published values. It is shown, never counted in the verdict.
    why : str
        Why it cannot fail, in a few words (required when ``by_construction``).
    kind : str
        The rule's name (:mod:`mechlib.reporting.claimrules`: ``"at_most"``, ``"paired"``, …).
    limit : object
        Its threshold when it has a fixed one (a number, or a mapping of numbers); None when it
        reads its threshold from the records (one of ``refs``) or compares two values.

    Raises
    ------
    ValueError
        For a part marked by construction without its reason.
    """

    label: str
    refs: tuple[Ref, ...]
    rule: Callable[..., bool]
    describe: Callable[..., str]
    by_construction: bool = False
    why: str = ""
    kind: str = ""
    limit: Any = None

    def __post_init__(self) -> None:
        if self.by_construction and not self.why.strip():
            raise ValueError(f"part {self.label!r} holds by construction: say why it cannot fail")

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
        budget of a calibration comparison, the model a claim was tested on); empty when there
        is one setting only.
    setting_refs : mapping of str to Ref
        The recorded values the setting names.
    group : str
        The claim this one judges in one of several settings (chapter 3's (iii) at each budget:
        ``"ch3.iii.5r"``), so that counts count it once; empty for a claim judged once.
    """

    id: str
    source: str
    where: str
    statement: str
    page: str
    parts: tuple[Test, ...]
    setting: str = ""
    setting_refs: Mapping[str, Ref] | None = None
    group: str = ""

    def __post_init__(self) -> None:
        cat.check_kinds(cat.BASIS_INDEPENDENT, self.source)
        if not self.parts:
            raise ValueError(f"claim {self.id!r} has no part to test")

    @property
    def counted(self) -> tuple[bool, ...]:
        """Per part, whether it could fail and so counts in the verdict."""
        return tuple(not t.by_construction for t in self.parts)


@dataclass(frozen=True)
class Verdict:
    """A claim's verdict as computed from the records.

    Attributes
    ----------
    spec : ClaimSpec
        The claim.
    word : str
        Its word (refused unless its parts that could fail give it: :func:`check_word`).
    holds : tuple of bool
        Per part, whether it holds.
    evidence : str
        Every part in words, marked when it cannot fail.
    setting : str
        The setting, filled in from the records.
    described : tuple of str
        Per part, its evidence in words (without label), e.g. for a one-line summary.
    read : tuple of list
        Per part, the recorded values its rule read, in the order of its ``refs``.
    """

    spec: ClaimSpec
    word: str
    holds: tuple[bool, ...]
    evidence: str
    setting: str
    described: tuple[str, ...] = ()
    read: tuple[list[Any], ...] = ()

    def __post_init__(self) -> None:
        check_word(self.spec, self.holds, self.word)

    @property
    def category(self) -> str:
        """The report category of the claim's row (:mod:`mechlib.reporting.categories`)."""
        if self.spec.source == cat.SOURCE_OURS:
            return cat.CAT_OURS
        return {
            SUPPORTED: cat.CAT_SUPPORTED,
            NOT_SUPPORTED: cat.CAT_NOT_SUPPORTED,
            MIXED: cat.CAT_MIXED,
            BY_CONSTRUCTION: cat.CAT_CLAIM_CONSTRUCTION,
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
            "n_values": sum(self.spec.counted),
            "n_agree": sum(h for h, c in zip(self.holds, self.spec.counted, strict=True) if c),
            "difference_text": "—",
            "claim": self.spec.id,
        }


def verdict_word(source: str, holds: Sequence[bool], counted: Sequence[bool] | None = None) -> str:
    """The verdict word of a claim whose parts hold or not (see the module's rules).

    Parameters
    ----------
    source : {"thesis", "ours"}
        Whose claim it is.
    holds : sequence of bool
        Per part, whether it holds.
    counted : sequence of bool, optional
        Per part, whether it could fail (default: every part could); only those decide the word.

    Raises
    ------
    ValueError
        For no part, for ``counted`` not one per part, or when a part that cannot fail fails
        (the registry's reason for it is wrong).
    """
    counted = [True] * len(holds) if counted is None else list(counted)
    if not holds:
        raise ValueError("a verdict needs at least one part")
    if len(counted) != len(holds):
        raise ValueError(f"counted must name each of the {len(holds)} parts, got {len(counted)}")
    broken = [i for i, (h, c) in enumerate(zip(holds, counted, strict=True)) if not (h or c)]
    if broken:
        raise ValueError(f"parts {broken} hold by construction, yet they fail: check their reason")
    informative = [h for h, c in zip(holds, counted, strict=True) if c]
    if not informative:
        return BY_CONSTRUCTION
    n, n_hold = len(informative), int(sum(informative))
    thesis = source == cat.SOURCE_THESIS
    if n_hold == n:
        return SUPPORTED if thesis else HOLDS
    if n_hold == 0:
        return NOT_SUPPORTED if thesis else DOES_NOT_HOLD
    return MIXED


def check_word(spec: ClaimSpec, holds: Sequence[bool], word: str) -> None:
    """Refuse a word that the claim's parts that could fail do not give — in particular one
    that counts a part holding by construction.

    Raises
    ------
    ValueError
        Naming the claim, the word given and the word its informative parts give.
    """
    if len(holds) != len(spec.parts):
        raise ValueError(f"claim {spec.id!r} has {len(spec.parts)} parts, got {len(holds)} results")
    expected = verdict_word(spec.source, holds, spec.counted)
    if word != expected:
        raise ValueError(
            f"claim {spec.id!r}: the word {word!r} is refused; the parts that could fail give "
            f"{expected!r} (a part that holds by construction is shown, never counted)"
        )


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
        f"{t.label}{f' (by construction, not counted: {t.why})' if t.by_construction else ''}: "
        f"{t.describe(*v)} ({'met' if h else 'not met'})"
        for (t, v), h in zip(read_parts, holds, strict=True)
    )
    word = verdict_word(spec.source, holds, spec.counted)
    described = tuple(t.describe(*v) for t, v in read_parts)
    values_read = tuple(v for _, v in read_parts)
    return Verdict(spec, word, holds, evidence, setting, described, values_read)
