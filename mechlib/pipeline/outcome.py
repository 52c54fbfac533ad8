"""The landing page's outcome: a short abstract generated from the claims registry and the rows.

It states, before anything else on the page, what a reader weighing the thesis needs first: what
was reproduced independently, which claims of the thesis hold only by construction, which hold
and which fail when tested (why, in one line each, from the parts that failed), and the
inconsistencies found inside the thesis. Every word and number comes from the records: the
claims' words are quoted by id (the book's ``verdict`` role), their evidence is the registry's
text of the parts (:class:`mechlib.reporting.claims.Verdict`), the inconsistencies are the causes
the report rows name.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from mechlib.pipeline.book import reportpage
from mechlib.reporting import categories as cat
from mechlib.reporting import claimlist, claims, thesisclaims, verdicts

#: the outcome's heading
HEADING = "## Outcome"


def _failed_parts(verdict: claims.Verdict) -> str:
    """The parts that could fail and did, in words: ``"label: evidence"``, joined."""
    parts = zip(verdict.spec.parts, verdict.holds, verdict.described, strict=True)
    return "; ".join(
        f"{t.label}: {text}" for t, h, text in parts if not h and not t.by_construction
    )


def _failed_labels(verdict: claims.Verdict) -> str:
    """The labels of the parts that could fail and did, joined (``"a and b"``)."""
    parts = zip(verdict.spec.parts, verdict.holds, strict=True)
    return " and ".join(t.label for t, h in parts if not (h or t.by_construction))


def _setting_head(verdict: claims.Verdict) -> str:
    """A setting's name, without its numbers (``"Table 8's printed budget"``)."""
    return verdict.setting.split(":", 1)[0]


def claim_line(members: Sequence[claims.Verdict]) -> str:
    """One line on a claim of the thesis judged in one setting or several (``members``): its
    statement, its word in each setting quoted by id, and the parts that failed."""
    spec = members[0].spec
    if len(members) == 1:
        v = members[0]
        failed = _failed_parts(v)
        line = f"*{spec.statement}* ({spec.where}): {reportpage.verdict_markup(spec.id)}"
        line += f", {v.setting}" if v.setting else ""
        line += f" — {failed}" if failed else ""
    else:
        words = ", ".join(
            f"{reportpage.verdict_markup(v.spec.id)} at {_setting_head(v)}" for v in members
        )
        failed = "; ".join(
            f"at {_setting_head(v)}: {_failed_labels(v)}" for v in members if _failed_labels(v)
        )
        failed = f"not met {failed} (the evidence of each setting is in the report)"
        line = f"*{spec.statement}* ({spec.where}): {words} — {failed}"
    shown = sorted({t.label for t in spec.parts if t.by_construction})
    if shown and any(spec.counted) and not spec.setting:
        line += f" (true by construction, shown and not counted: {'; '.join(shown)})"
    return line + "."


def _groups(judged: Mapping[str, claims.Verdict]) -> dict[str, list[claims.Verdict]]:
    groups: dict[str, list[claims.Verdict]] = {}
    for v in judged.values():
        if v.spec.source == cat.SOURCE_THESIS:
            groups.setdefault(claimlist.claim_group(v.spec), []).append(v)
    return groups


def inconsistency_lines(rows: Sequence[verdicts.ReportRow]) -> list[str]:
    """One line per thesis artefact with an inconsistency inside the thesis: its causes."""
    causes: dict[str, list[str]] = {}
    for row in rows:
        if row.category == cat.CAT_INCONSISTENT and row.artefacts:
            name = verdicts.artefact_name(*row.artefacts[0])
            cause = str(row.fields.get("cause") or row.fields["quantity"])
            if cause not in causes.setdefault(name, []):
                causes[name].append(cause)
    order = [verdicts.artefact_name(k, n) for k, n, _, _ in verdicts.THESIS_ARTEFACTS]
    ranked = sorted(causes, key=lambda a: order.index(a) if a in order else len(order))
    return [f"  - {name}: {'; '.join(causes[name])}." for name in ranked]


def outcome_markdown(
    judged: Mapping[str, claims.Verdict], rows: Sequence[verdicts.ReportRow]
) -> str:
    """The outcome abstract (see the module).

    Parameters
    ----------
    judged : mapping
        ``{claim id: Verdict}`` as :func:`mechlib.reporting.claimlist.judge` gives them.
    rows : sequence of ReportRow
        Every report row (:func:`mechlib.reporting.verdicts.all_rows`).
    """
    thesis_rows = [
        r for r in rows if r.fields.get("source", cat.SOURCE_THESIS) == cat.SOURCE_THESIS
    ]
    counts = {c: sum(r.category == c for r in thesis_rows) for c in cat.CATEGORIES}
    reproduced = [r for r in thesis_rows if r.category == cat.CAT_REPRODUCED]
    by_arte = sorted({verdicts.artefact_name(*r.artefacts[0]) for r in reproduced if r.artefacts})
    lines = [HEADING, ""]
    if reproduced:
        lines.append(
            f"- **Reproduced independently:** {len(reproduced)} comparisons of published values "
            f"({', '.join(by_arte)})."
        )
    else:
        lines.append(
            "- **No published value was reproduced independently.** The thesis's drawing and "
            "finite-element files are not available: our FE model's dimensions are fitted to "
            "Eq 8 and the force designs of Tables 2 and 4 are run as printed, so "
            f"{counts[cat.CAT_CONSTRUCTION]} comparisons agree by construction and "
            f"{counts[cat.CAT_CONSISTENT_THESIS]} set published values against each other."
        )
    groups = _groups(judged)
    words = {g: claimlist.group_word(v.word for v in m) for g, m in groups.items()}
    heads = (
        ("Claims of the thesis true only by construction", (claims.BY_CONSTRUCTION,)),
        ("Claims of the thesis borne out when tested", (claims.SUPPORTED,)),
        (
            "Claims of the thesis that fail when tested, in part or in whole",
            (claims.NOT_SUPPORTED, claims.MIXED),
        ),
    )
    for head, wanted in heads:
        members = [m for g, m in groups.items() if words[g] in wanted]
        if not members:
            continue
        lines.append(f"- **{head}** ({len(members)}):")
        for m in members:
            line = claim_line(m)
            spec = m[0].spec
            if words[claimlist.claim_group(spec)] == claims.BY_CONSTRUCTION:
                line = line.rstrip(".") + f" — {'; '.join(t.why for t in spec.parts)}."
            lines.append(f"  - {line}")
    for where, statement, why in thesisclaims.UNTESTABLE:
        lines.append(f"- **Not testable here:** *{statement}* ({where}): {why}.")
    found = inconsistency_lines(rows)
    if found:
        n = counts[cat.CAT_INCONSISTENT]
        lines += [f"- **Inconsistencies inside the thesis** ({n} report rows):", *found]
    return "\n".join(lines)
