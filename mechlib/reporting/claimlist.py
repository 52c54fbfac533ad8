"""Every claim the book judges — the registry of :mod:`mechlib.reporting.claims` — by id.

The claims of the thesis are in :mod:`mechlib.reporting.thesisclaims`, findings of ours in
:mod:`mechlib.reporting.ourclaims`; this module gathers them, gives one by id, and judges them
again from a build's records for the book's pages (:func:`judge`).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from mechlib.metamodels.metrics import FULL_SCALE, FULL_SCALE_DEFINITION
from mechlib.metamodels.realtime import DEADLINE_US
from mechlib.reporting import categories as cat
from mechlib.reporting import claims
from mechlib.reporting.claims import ClaimSpec
from mechlib.reporting.ourclaims import our_claims
from mechlib.reporting.thesisclaims import CONTROL_PERIOD_US, thesis_claims

__all__ = [
    "CLAIMS",
    "CONTROL_PERIOD_US",
    "claim",
    "claims_file",
    "for_page",
    "judge",
    "thesis_claims_judged",
    "verdict_table",
]

#: every claim the book judges, by id, in the order the report lists them
CLAIMS: dict[str, ClaimSpec] = {c.id: c for c in [*thesis_claims(), *our_claims()]}


def claim(claim_id: str) -> ClaimSpec:
    """The registered claim ``claim_id``.

    Raises
    ------
    KeyError
        For an id the registry does not hold, naming the known ones of its page prefix.
    """
    if claim_id not in CLAIMS:
        near = [c for c in CLAIMS if c.split(".")[0] == claim_id.split(".")[0]]
        raise KeyError(f"no registered claim {claim_id!r}; registered: {near or list(CLAIMS)}")
    return CLAIMS[claim_id]


def for_page(page: str) -> list[ClaimSpec]:
    """The claims whose evidence the notebook ``page`` records."""
    return [c for c in CLAIMS.values() if c.page == page]


def claim_group(spec: ClaimSpec) -> str:
    """The claim ``spec`` judges whatever its setting: the group it declares (chapter 3's (iii)
    at each measurement budget: ``ch3.iii.5r.table8`` → ``ch3.iii.5r``); any other claim, with a
    setting or not, is its own."""
    return spec.group or spec.id


def group_word(words: Iterable[str]) -> str:
    """The word of a claim judged in several settings, from its word in each: the word they
    share, else :data:`~mechlib.reporting.claims.MIXED` (the evidence splits across settings).

    Raises
    ------
    ValueError
        For no word, or a word no claim reads.
    """
    found = list(words)
    unknown = [w for w in found if w not in claims.WORDS]
    if not found or unknown:
        raise ValueError(f"words must be some of {claims.WORDS}, got {found}")
    return found[0] if len(set(found)) == 1 else claims.MIXED


def thesis_claims_judged(claim_ids: Iterable[str]) -> tuple[int, int, int]:
    """How many distinct claims of the thesis the rows judging ``claim_ids`` (the ``claim``
    fields of the report's thesis-claim rows) judge: ``(rows, claims, claims judged in several
    settings)``, claims grouped by :func:`claim_group`.

    Raises
    ------
    KeyError
        For an id the registry does not hold.
    ValueError
        For an id of a finding of ours (never counted among the thesis's claims).
    """
    specs = [claim(c) for c in claim_ids]
    ours = [s.id for s in specs if s.source != cat.SOURCE_THESIS]
    if ours:
        raise ValueError(f"claims of ours among the thesis's claim rows: {ours}")
    groups = [claim_group(s) for s in specs]
    several = {g for g in groups if groups.count(g) > 1}
    return len(groups), len(set(groups)), len(several)


def judge(records: Mapping[str, Mapping[str, Any]]) -> dict[str, claims.Verdict]:
    """Every registered claim that its page judged (recorded ``claims.<id>``), judged again from
    that record's values (and timings) and checked against the verdict word the page recorded.

    Parameters
    ----------
    records : mapping
        ``{notebook: record}`` as :class:`mechlib.reporting.records.Recorder` saves them.

    Raises
    ------
    ValueError
        When a page recorded another verdict word than its values give (naming the page, the
        claim and both words).
    """
    judged = {}
    for spec in CLAIMS.values():
        record = records.get(spec.page)
        if record is None:
            continue
        values = {**record.get("values", {}), **record.get("timings", {})}
        key = f"claims.{spec.id}"
        if key not in values:  # not judged in this run (e.g. its non-linear runs were skipped)
            continue
        verdict = claims.evaluate(spec, values)
        recorded = values[key]["value"]
        if recorded != verdict.word:
            raise ValueError(
                f"{spec.page} recorded {recorded!r} for claim {spec.id!r}, its values give "
                f"{verdict.word!r}"
            )
        judged[spec.id] = verdict
    return judged


def verdict_table(judged: Mapping[str, claims.Verdict]) -> dict[str, dict[str, str]]:
    """What the book's pages quote of each judged claim (``verdict`` role): its word, statement,
    setting, source, where and page — JSON-ready."""
    return {
        cid: {
            "word": v.word,
            "statement": v.spec.statement,
            "setting": v.setting,
            "source": v.spec.source,
            "where": v.spec.where,
            "page": v.spec.page,
        }
        for cid, v in judged.items()
    }


#: the claims file's format (raise it when a field changes meaning)
CLAIMS_FILE_FORMAT = 1
#: how the claims file says its words are given
WORD_RULE = (
    "A claim's word comes from its parts that could fail ('can_fail': true) only: a thesis "
    "claim is 'supported' when each holds, 'not supported' when none does, 'mixed' when they "
    "split; a finding of ours 'holds', 'does not hold' or is 'mixed' likewise. A part that "
    "cannot fail (true by construction on our model, or arithmetic on published values) is "
    "listed with its reason ('why') and never counted; a claim with no other part reads "
    "'consistent by construction'. A claim judged in several settings has one entry per "
    "setting, sharing its 'group'."
)


def _index(index: object) -> object:
    """A record reference's index, JSON-ready (a slice as ``"0:3"``)."""
    if isinstance(index, slice):
        start, stop = ("" if i is None else i for i in (index.start, index.stop))
        return f"{start}:{stop}"
    if isinstance(index, tuple):
        return [_index(i) for i in index]
    return index


def _plain(value: object) -> object:
    """A recorded value, JSON-ready (NumPy scalars and arrays as Python numbers and lists)."""
    if hasattr(value, "tolist"):
        return value.tolist()
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


def claims_file(judged: Mapping[str, claims.Verdict]) -> dict[str, Any]:
    """Every judged claim, machine-readable, for the data bundle's ``claims.json``: so that
    another reproduction, or a later build of this one, can be compared claim by claim.

    Returns
    -------
    dict
        ``format``, ``word_rule``, ``measure`` (the name and definition of the relative error
        measure), ``deadline_us`` and ``claims``: per claim its ``id``, ``group``, ``source``,
        ``where`` (the thesis location, or the section of the book), ``statement``, ``page``
        (notebook), ``setting``, ``word`` and ``parts``, each with its ``label``, ``rule``,
        ``record_keys`` (``notebook``, ``key``, ``index``), the ``values`` read, its ``limit``,
        ``can_fail``, ``why`` (when it cannot fail), ``holds`` and ``evidence`` in words.
    """
    out = []
    for cid, v in judged.items():
        spec = v.spec
        parts = []
        for k, test in enumerate(spec.parts):
            refs = [(r, None) if isinstance(r, str) else r for r in test.refs]
            parts.append(
                {
                    "label": test.label,
                    "rule": test.kind,
                    "record_keys": [
                        {"notebook": spec.page, "key": key, "index": _index(i)} for key, i in refs
                    ],
                    "values": _plain(list(v.read[k])) if v.read else None,
                    "limit": test.limit,
                    "can_fail": not test.by_construction,
                    "why": test.why,
                    "holds": v.holds[k],
                    "evidence": v.described[k] if v.described else "",
                }
            )
        out.append(
            {
                "id": cid,
                "group": claim_group(spec),
                "source": spec.source,
                "where": spec.where,
                "statement": spec.statement,
                "page": spec.page,
                "setting": v.setting,
                "word": v.word,
                "parts": parts,
            }
        )
    return {
        "format": CLAIMS_FILE_FORMAT,
        "word_rule": WORD_RULE,
        "measure": {"name": FULL_SCALE, "definition": FULL_SCALE_DEFINITION},
        "deadline_us": DEADLINE_US,
        "claims": out,
    }
