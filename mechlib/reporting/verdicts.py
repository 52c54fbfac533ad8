"""Report rows gathered from the records, counted per verdict category and rolled up per artefact.

The rows are the ones the notebooks recorded (:mod:`mechlib.reporting.report` builds them, with a
``category`` from :mod:`mechlib.reporting.categories`). This module reads them back from the
records, counts
them per category, rolls them up per thesis artefact (Tables 1–8, Figs 1–14, Eqs 6–11: the
thesis's inventory is :data:`THESIS_ARTEFACTS`) and names the artefacts that no row reports on.
The landing page (:mod:`mechlib.pipeline.landing`) and the report page show the same counts, made
here once.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from mechlib.reporting import artefacts, claimlist, claims
from mechlib.reporting import categories as cat

#: Every numbered artefact of the thesis that the book reproduces, with its chapter and a short
#: title after its caption (``shared/paper/thesis.md``: Tables 1–5, Figs 1–8 and Eqs 6–11 in
#: chapter 2; Figs 9–14 and Tables 6–8 in chapter 3). Eqs 1–5 and 12–26 define notation only.
THESIS_ARTEFACTS: tuple[tuple[str, int, int, str], ...] = (
    ("table", 1, 2, "Studied factors: forces at the HexFlex tabs"),
    ("table", 2, 2, "Plackett–Burman design, 12 runs and 6 factors, and its responses"),
    ("table", 3, 2, "Lenth's analysis of the screening"),
    ("table", 4, 2, "Uniform design, 30 runs, and its responses"),
    ("table", 5, 2, "Meta-model error over 1000 random experiments"),
    ("fig", 1, 2, "Force–displacement meta-modelling methodology"),
    ("fig", 2, 2, "The six-degree-of-freedom compliant mechanism (HexFlex)"),
    ("fig", 3, 2, "The HexFlex's six motions"),
    ("fig", 4, 2, "The HexFlex's actuator directions"),
    ("fig", 5, 2, "Finite-element model of the HexFlex"),
    ("fig", 6, 2, "Half-normal probability plots of the screening"),
    ("fig", 7, 2, "Pareto charts of the screening"),
    ("fig", 8, 2, "Deformed shape in one validation experiment"),
    ("eq", 6, 2, "Quadratic meta-model"),
    ("eq", 7, 2, "Linear meta-model, pose = S_T · forces"),
    ("eq", 8, 2, "The fitted matrix S_T"),
    ("eq", 9, 2, "Inverse model, forces = S_T⁻¹ · pose"),
    ("eq", 10, 2, "Maximum absolute error (MAXABS)"),
    ("eq", 11, 2, "Root mean square error (RMSE)"),
    ("fig", 9, 3, "Kinematic identification protocol of symmetrical parallel mechanisms"),
    ("fig", 10, 3, "Planar 5R symmetrical mechanism"),
    ("fig", 11, 3, "Planar 5R leg loop"),
    ("fig", 12, 3, "Postures selected for identification"),
    ("fig", 13, 3, "Residual parameter errors before and after calibration"),
    ("fig", 14, 3, "Local RMS error over the maximal inscribed workspace after calibration"),
    ("table", 6, 3, "Computational and measurement costs of kinematic identification"),
    ("table", 7, 3, "Identification results (nominal and real parameters)"),
    ("table", 8, 3, "5R computational and measurement costs"),
)
#: The verdict an artefact shows when its rows have several: what a reader must know first
#: (a published value not reached, then a divergence, …); its other verdicts are in its summary.
HEADLINE_ORDER = (
    cat.CAT_NOT_REPRODUCED,
    cat.CAT_DIVERGES,
    cat.CAT_INCONSISTENT,
    cat.CAT_NOT_SUPPORTED,
    cat.CAT_MIXED,
    cat.CAT_REPRODUCED,
    cat.CAT_SUPPORTED,
    cat.CAT_CONSTRUCTION,
    cat.CAT_CLAIM_CONSTRUCTION,
    cat.CAT_CONSISTENT_THESIS,
    cat.CAT_OURS,
    cat.CAT_COMPUTED,
    cat.CAT_REDRAWN,
)
#: What the landing table shows for an artefact that no report row covers.
NO_ROW = "no row"
#: How the counts are grouped: the thesis's published values, its claims, and ours.
COUNT_GROUPS: tuple[tuple[str, tuple[str, ...]], ...] = (
    (
        "published values and by-construction checks",
        (
            cat.CAT_REPRODUCED,
            cat.CAT_CONSTRUCTION,
            cat.CAT_DIVERGES,
            cat.CAT_INCONSISTENT,
            cat.CAT_CONSISTENT_THESIS,
            cat.CAT_NOT_REPRODUCED,
        ),
    ),
    ("claims of the thesis, tested", cat.TESTED_CLAIM_CATEGORIES),
    ("claims of the thesis that no test could fail", (cat.CAT_CLAIM_CONSTRUCTION,)),
    ("beyond the thesis", (cat.CAT_OURS, cat.CAT_COMPUTED)),
    ("not compared", (cat.CAT_REDRAWN,)),
)
#: Header of the counts table; :func:`mechlib.pipeline.pagecheck.count_table` finds it by this.
#: A claim is counted once, however many rows (settings) judge it; any other row once.
COUNTS_HEADER = "| Verdict | Counted among | Claims or rows |"
#: a thesis claim's category from its word
_CLAIM_CATEGORY = {
    claims.SUPPORTED: cat.CAT_SUPPORTED,
    claims.NOT_SUPPORTED: cat.CAT_NOT_SUPPORTED,
    claims.MIXED: cat.CAT_MIXED,
    claims.BY_CONSTRUCTION: cat.CAT_CLAIM_CONSTRUCTION,
}


@dataclass(frozen=True)
class ReportRow:
    """A report row with the page (notebook name) that recorded it."""

    page: str
    fields: dict[str, Any]

    @property
    def category(self) -> str:
        """The row's verdict category (see :func:`row_category`)."""
        return row_category(self.fields)

    @property
    def holds(self) -> bool:
        """Whether the row's values all agree or its claim holds (see :func:`row_holds`)."""
        return row_holds(self.fields)

    @property
    def artefacts(self) -> list[artefacts.Artefact]:
        """The thesis artefacts the row names, e.g. ``[("table", 6), ("table", 8)]``."""
        return artefacts.parse(self.fields["artefact"])


def row_category(fields: Mapping[str, Any]) -> str:
    """A row's ``category`` field.

    Raises
    ------
    ValueError
        For a row without a category, or a category :mod:`mechlib.reporting.categories` does not
        define.
    """
    category = fields.get("category")
    if category not in cat.CATEGORIES:
        raise ValueError(f"unknown category {category!r}; known: {cat.CATEGORIES}")
    return category


Records = Mapping[str, Mapping[str, Any]]


def row_holds(fields: Mapping[str, Any]) -> bool:
    """Whether all of a row's values agree (a comparison) or its claim holds (``n_agree`` of
    ``n_values``; a row without counts, such as a computed one, holds)."""
    return fields.get("n_agree") == fields.get("n_values")


def load_records(records: Records | Path) -> dict[str, Mapping[str, Any]]:
    """``{notebook: record}`` from a folder of record files (``<notebook>.json``), or as given.

    Raises
    ------
    FileNotFoundError
        When ``records`` is a folder without any record.
    """
    if isinstance(records, (str, Path)):
        paths = sorted(Path(records).glob("*.json"))
        if not paths:
            raise FileNotFoundError(f"records: no <notebook>.json in {records}")
        return {p.stem: json.loads(p.read_text()) for p in paths}
    return dict(records)


def load_rows(records: Records | Path) -> list[ReportRow]:
    """Every report row of a folder of records or of loaded records (see :func:`load_records`).

    Parameters
    ----------
    records : mapping or Path
        ``{notebook: record}`` (a record as :class:`mechlib.reporting.records.Recorder` saves it)
        or a
        folder holding the record files.
    """
    return [
        ReportRow(rec.get("notebook", name), dict(row))
        for name, rec in sorted(load_records(records).items())
        for row in rec.get("report", [])
    ]


#: The thesis's method figures, which the book build redraws from the thesis's text
#: (:mod:`mechlib.pipeline.book.methods`; no notebook records them): page under ``book/``,
#: artefact, and what the page shows.
REDRAWN: tuple[tuple[str, str, str], ...] = (
    (
        "generated/method_doe",
        "Fig 1",
        "the meta-modelling method (sec. 2.5) as a flow diagram, each step linked to the "
        "section of this book that carries it out",
    ),
    (
        "generated/protocol_5r",
        "Fig 9",
        "the identification protocol (sec. 3.6) as a flow diagram, each step linked to the "
        "section of this book that carries it out",
    ),
)


def redrawn_rows() -> list[ReportRow]:
    """One row per method figure of :data:`REDRAWN`: category :data:`~mechlib.reporting.categories.
    CAT_REDRAWN` (a diagram of the thesis's text: nothing computed, nothing to compare)."""
    return [
        ReportRow(
            page,
            {
                "artefact": artefact,
                "quantity": quantity,
                "published": "(diagram)",
                "ours": "redrawn by code from the thesis's text",
                "max_abs_diff": None,
                "max_rel_diff": None,
                "difference": None,
                "verdict": cat.CAT_REDRAWN,
                "category": cat.CAT_REDRAWN,
                "source": cat.SOURCE_THESIS,
                "difference_text": "—",
            },
        )
        for page, artefact, quantity in REDRAWN
    ]


def all_rows(records: Records | Path) -> list[ReportRow]:
    """The records' rows (:func:`load_rows`) and the build's rows of redrawn method figures
    (:func:`redrawn_rows`): every row the report and the landing page count."""
    return load_rows(records) + redrawn_rows()


def thesis_claim_ids(rows: Iterable[ReportRow]) -> list[str]:
    """The claim ids of the rows counted as claims of the thesis (:data:`CLAIM_CATEGORIES`),
    one per row.

    Raises
    ------
    ValueError
        For such a row without its claim's id.
    """
    claimed = [r for r in rows if r.category in cat.CLAIM_CATEGORIES]
    missing = [r.fields.get("quantity", "?") for r in claimed if "claim" not in r.fields]
    if missing:
        raise ValueError(f"thesis-claim rows without a claim id: {missing}")
    return [r.fields["claim"] for r in claimed]


def claim_groups(rows: Iterable[ReportRow]) -> dict[str, list[ReportRow]]:
    """The rows that judge a registered claim, by the claim they judge whatever the setting
    (:func:`mechlib.reporting.claimlist.claim_group`), in order of first row.

    Raises
    ------
    KeyError
        For a row naming a claim the registry does not hold.
    """
    groups: dict[str, list[ReportRow]] = {}
    for row in rows:
        if row.fields.get("claim"):
            spec = claimlist.claim(row.fields["claim"])
            groups.setdefault(claimlist.claim_group(spec), []).append(row)
    return groups


def group_category(rows: Sequence[ReportRow]) -> str:
    """The category of a claim judged by ``rows`` (one per setting): a finding of ours is
    :data:`~mechlib.reporting.categories.CAT_OURS`; a thesis claim's category is that of its
    word across settings (:func:`mechlib.reporting.claimlist.group_word`)."""
    if rows[0].category not in cat.CLAIM_CATEGORIES:
        return rows[0].category
    return _CLAIM_CATEGORY[claimlist.group_word(r.fields["verdict"] for r in rows)]


def category_counts(rows: Iterable[ReportRow]) -> dict[str, int]:
    """Per category, the claims (counted once whatever the number of settings judging them,
    :func:`claim_groups`) and the other rows; every category present (zero if none), in report
    order."""
    rows = list(rows)
    counts = dict.fromkeys(cat.CATEGORIES, 0)
    for row in rows:
        if not row.fields.get("claim"):
            counts[row.category] += 1
    for members in claim_groups(rows).values():
        counts[group_category(members)] += 1
    return counts


def counts_table(counts: Mapping[str, int], mark: Callable[[str], str] = str) -> str:
    """The counts per category as a Markdown table (the landing and the report page show it).

    Raises
    ------
    ValueError
        If ``counts`` misses a category or names an unknown one.
    """
    if set(counts) != set(cat.CATEGORIES):
        raise ValueError(f"counts must name every category {cat.CATEGORIES}, got {sorted(counts)}")
    lines = [COUNTS_HEADER, "|---|---|---:|"]
    for group, members in COUNT_GROUPS:
        lines += [f"| {mark(category)} | {group} | {counts[category]} |" for category in members]
    return "\n".join(lines)


def artefact_name(kind: str, number: int) -> str:
    """``("fig", 6)`` → ``"Fig 6"``."""
    return artefacts.name((kind, number))


def _category_summary(category: str, rows: Sequence[ReportRow]) -> str:
    n = len(rows)
    text = f"{n} {'row' if n == 1 else 'rows'} {category}"
    compared = [r.fields for r in rows if r.fields.get("n_values") and r.fields["published"] != "—"]
    if compared and all(f.get("max_abs_diff") is not None for f in compared):
        agree = sum(f["n_agree"] for f in compared)
        text += f" ({agree}/{sum(f['n_values'] for f in compared)} values agree)"
    return text


def rollup(rows: Sequence[ReportRow]) -> list[dict[str, Any]]:
    """One entry per thesis artefact (then any other artefact a row names), in the thesis's order.

    A row counts under the first artefact it names only ("Tables 6, 8": Table 6); the others
    name that artefact in ``counted_under``. A claim's rows are listed as the claim they judge
    (``claims``), never as the artefact's verdict, which comes from its other rows (its claims'
    categories only when it has no other row).

    Returns
    -------
    list of dict
        ``artefact`` ("Table 3"), ``chapter``, ``title``, ``pages`` (notebooks whose rows it
        has), ``rows`` (their number), ``counts`` ({category: rows}, only those present),
        ``verdict`` (the first category present in :data:`HEADLINE_ORDER`, or :data:`NO_ROW`),
        ``claims`` ({claim group: [claim ids]}), ``counted_under`` (artefacts counting rows
        that name this one too) and ``summary`` (one line: rows and values agreeing per
        category).
    """
    known = [(k, n) for k, n, _, _ in THESIS_ARTEFACTS]
    named = {a for row in rows for a in row.artefacts}
    extra = sorted(named - set(known))
    meta = {(k, n): (ch, title) for k, n, ch, title in THESIS_ARTEFACTS}
    out = []
    for key in [*known, *extra]:
        mine = [r for r in rows if r.artefacts and r.artefacts[0] == key]
        values = [r for r in mine if not r.fields.get("claim")]
        groups = claim_groups(mine)
        present = {c: [r for r in values if r.category == c] for c in cat.CATEGORIES}
        present = {c: rs for c, rs in present.items() if rs}
        headline = present or {group_category(g): g for g in groups.values()}
        name = artefact_name(*key)
        chapter, title = meta.get(key, (None, ""))
        summary = "; ".join(_category_summary(c, rs) for c, rs in present.items())
        under = sorted(
            {artefact_name(*r.artefacts[0]) for r in rows if key in r.artefacts[1:]} - {name}
        )
        out.append(
            {
                "artefact": name,
                "chapter": chapter,
                "title": title,
                "pages": sorted({r.page for r in mine}),
                "rows": len(mine),
                "counts": {c: len(rs) for c, rs in present.items()},
                "verdict": next((c for c in HEADLINE_ORDER if c in headline), NO_ROW),
                "claims": {g: [r.fields["claim"] for r in rs] for g, rs in groups.items()},
                "counted_under": under,
                "summary": f"{name}: {summary or NO_ROW}",
            }
        )
    return out


def missing_artefacts(rows: Sequence[ReportRow]) -> list[str]:
    """The thesis artefacts that no report row names (empty when every one has a row)."""
    named = {a for row in rows for a in row.artefacts}
    return [artefact_name(k, n) for k, n, _, _ in THESIS_ARTEFACTS if (k, n) not in named]


def report_cells(fields: Mapping[str, Any]) -> dict[str, str]:
    """The Published, Ours, Difference and Verdict cells of a report row, as plain text.

    The Verdict cell is the row's category, then its cause (a divergence) or the tolerance its
    agreement met; the Difference cell is
    :func:`mechlib.reporting.categories.difference_text`'s.
    """
    category = row_category(fields)
    detail = fields.get("cause") or ""
    if not detail and fields.get("tolerance") and row_holds(fields):
        detail = f"within {fields['tolerance']}"
    return {
        "published": str(fields["published"]),
        "ours": str(fields["ours"]),
        "difference": fields["difference_text"],
        "verdict": f"{category}: {detail}" if detail else category,
    }
