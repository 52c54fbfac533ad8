"""The book's landing page, generated from the records: readable in thirty seconds.

:func:`write_landing` writes a MyST page that opens with the outcome
(:mod:`mechlib.pipeline.outcome`, from the claims registry and the report rows), then the main
findings in a sentence each with a link to their evidence, then what the thesis is (prose from
:data:`THESIS_TEXT`, which states no result), one table with a verdict per thesis artefact
(:func:`mechlib.reporting.verdicts.rollup`), the counts per verdict category, and the profile
the book was built with.

Every result the page states is read from the records: a finding (:class:`Finding`) quotes
recorded values, and is shown only when the report row it rests on has one of the categories
that make its sentence true (else its ``otherwise`` sentence, else nothing).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from mechlib.pipeline import bundle as bundle_mod
from mechlib.pipeline import outcome
from mechlib.pipeline.book import reportpage
from mechlib.pipeline.findings import FINDINGS, Finding, Quote
from mechlib.pipeline.provenance import DEFAULT_PROFILE
from mechlib.reporting import claimlist, verdicts

#: ``link(page, what, text)`` → a MyST link to the section of chapter ``page`` that shows ``what``.
Link = Callable[[str, str, str], str]
#: profile names: what ``notebooks/profiles/<name>`` may be called
_PROFILE = re.compile(r"^[A-Za-z0-9_-]+$")
#: the record keys that hold a chapter's parameters
PARAMETER_PREFIX = "parameters."

TITLE_TEXT = """\
# An executable reproduction of a 2010 thesis on mechanism modelling

This book re-derives, from code that runs whenever the book is built, the tables, figures and
equations of a 2010 master's thesis from EAFIT University (Medellín) on predicting small
quasi-static deformations of mechanisms: a compliant six-axis positioner (chapter 2) and the
kinematic identification of a planar five-bar (chapter 3). What follows first is the outcome,
then the main findings; the thesis, and a verdict per artefact of it, come after.
"""

THESIS_TEXT = """\
## The thesis, and how it is reproduced

**Chapter 2 — design of computer experiments on a compliant mechanism.** The HexFlex, a flat
aluminium six-degree-of-freedom nano-positioner, is modelled with finite elements and pushed at
three tabs, in and out of plane. A 12-run Plackett–Burman screening (Tables 2–3, Figs 6–7) shows
which forces move which pose component; a 30-run uniform design (Table 4) feeds a linear
force→pose meta-model $S_T$ (Eqs 6–9), validated on 1000 random runs (Table 5, Eqs 10–11). The
thesis claims that the HexFlex is linear over its ±1 N actuator range and that a 6 × 6 matrix is
an accurate, real-time-capable model of it.

**Chapter 3 — divide-and-conquer kinematic identification.** A planar five-bar (5R) parallel
mechanism is calibrated leg by leg, with postures chosen by an observability index (Figs 9–14,
Tables 6–8); the thesis claims that this beats identifying all parameters at once.

The thesis used ANSYS; we use SfePy, Python and open libraries. Every number in this book is
computed by the code that builds it: the finite-element runs are read from a results store that
the same FE code computed at a named commit (which runs, and how a sample of them is
recomputed, is under "This build" below), and every
table, figure and number after them is computed when the book
is built. The thesis's printed values enter in two ways only: as published
values to compare against, and as inputs the report names — our FE model's dimensions are fitted
to Eq 8, and Tables 2 and 4's force designs are run as printed — so agreement that follows from
them is counted as *consistent by construction*, not as reproduction. The
[reproduction report](report.md) lists every compared quantity with its published value, ours
and a verdict.
"""

LEGEND = (
    "*Reproduced*: our independent computation agrees within the tolerance the report states. "
    "*Consistent by construction*: we fitted to the published value or computed ours from it, "
    "so agreement is expected, not evidence. *Inconsistency inside the thesis*: published "
    "values contradict each other; *consistent inside the thesis*: published values set against "
    "each other agree (no computation of ours is tested). A claim of the thesis reads the word of "
    "its tests that could fail; a part that cannot fail (true by construction on our model, "
    "or is arithmetic on published values) is shown, never counted, and a claim with no other "
    "part is *consistent by construction*, counted apart. *Computed*: a figure or number of the "
    "thesis that we compute with nothing published to compare it with. *Redrawn*: a diagram of "
    "the thesis's method, drawn from its text."
)

RERUN_TEXT = """\
```{admonition} Re-run a chapter with your own parameters
Each chapter is a notebook whose first cell sets its parameters.
`make run NB=published_doe ARGS="-p n_random_designs 5000"` executes one into `build/runs/`
without touching this build; `make book PROFILE=full` builds the whole book with a finer
mesh-convergence study of the linear model.
```
"""


def doc_link(page: str, what: str, text: str) -> str:
    """A MyST link to chapter ``page`` (or ``folder/page`` under ``book/``); ``what`` unused."""
    return f"{{doc}}`{text} </{page if '/' in page else f'chapters/{page}'}>`"


def quote(records: verdicts.Records, where: Quote) -> float:
    """The recorded number ``where`` names (an element, or the max/min of an array).

    Raises
    ------
    KeyError
        When the notebook or the key was not recorded (naming both).
    ValueError
        When the quoted element is not one number.
    """
    notebook, key, index = where
    record = records.get(notebook, {})
    values, timings = record.get("values", {}), record.get("timings", {})
    if key not in values and key not in timings:
        raise KeyError(f"landing: {notebook} recorded no value {key!r}")
    arr = np.asarray(values[key]["value"] if key in values else timings[key], dtype=float)
    item = (
        arr.max()
        if index == "max"
        else arr.min()
        if index == "min"
        else arr[() if index is None else index]
    )
    if np.ndim(item):
        raise ValueError(f"landing: {notebook} {key}[{index}] is not one number: {item!r}")
    return float(item)


def find_row(rows: Sequence[verdicts.ReportRow], spec: tuple[str, str, str]) -> verdicts.ReportRow:
    """The report row ``(notebook, artefact, start of quantity)`` (the first that matches).

    Raises
    ------
    KeyError
        When no row matches, naming the three parts.
    """
    page, artefact, quantity = spec
    for row in rows:
        f = row.fields
        if row.page == page and f["artefact"] == artefact and f["quantity"].startswith(quantity):
            return row
    raise KeyError(f"landing: no report row {artefact!r} {quantity!r}… in {page}")


#: a claim's verdict in a finding's text: ``[[ch3.iii.5r.table8]]``
_CLAIM = re.compile(r"\[\[([\w.]+)\]\]")


def finding_lines(
    finding: Finding, records: verdicts.Records, rows: Sequence[verdicts.ReportRow], link: Link
) -> list[str]:
    """The finding as a Markdown list item, or no line when its row or values are missing or its
    row's category makes neither sentence true. A finding that rests on registered claims
    quotes their verdicts (``[[claim id]]`` in its text) and is always stated.

    Raises
    ------
    ValueError
        For a finding that quotes a claim the registry does not hold.
    """
    unknown = [c for c in _CLAIM.findall(finding.text) if c not in claimlist.CLAIMS]
    if unknown:
        raise ValueError(f"finding {finding.title!r} quotes unregistered claims {unknown}")
    try:
        row = find_row(rows, finding.row) if finding.row else None
        numbers = {name: quote(records, where) for name, where in finding.values.items()}
    except KeyError:
        return []
    shown = row is None or (row.category in finding.shown_if and finding.holds in (None, row.holds))
    title, template = (finding.title, finding.text) if shown else finding.otherwise
    if not template:
        return []
    page, what = finding.evidence
    sentence = template.format(**numbers)
    sentence = _CLAIM.sub(lambda m: reportpage.verdict_markup(m.group(1)), sentence)
    label = f" ({reportpage.category_markup(row.category)})" if row is not None else ""
    return [f"- **{title.rstrip('.')}**{label}. {sentence} "
            f"Evidence: {link(page, what, what)}."]  # fmt: skip


def _escape(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def artefact_table(rows: Sequence[verdicts.ReportRow], link: Link) -> str:
    """One line per thesis artefact: its title, its verdict, the roll-up of its rows and the
    claims filed under it (each quoted with its own word, by id)."""
    lines = [
        "| Artefact | In the thesis | Verdict | Rows | Claims judged here |",
        "|---|---|---|---|---|",
    ]
    for entry in verdicts.rollup(rows):
        name = entry["artefact"]
        cell = link(entry["pages"][0], name, name) if entry["pages"] else name
        under = ", ".join(entry["counted_under"])
        if entry["verdict"] == verdicts.NO_ROW and under:
            verdict, detail = f"counted under {under}", "—"
        else:
            verdict = reportpage.category_markup(entry["verdict"])
            detail = entry["summary"].split(": ", 1)[1] if entry["counts"] else "—"
            detail += f" (also counted under {under})" if under else ""
        claimed = "; ".join(claim_cell(ids) for ids in entry["claims"].values())
        lines.append(
            f"| {cell} | {_escape(entry['title'])} | {verdict} | {_mark_categories(detail)} | "
            f"{claimed or '—'} |"
        )
    return "\n".join(lines)


def claim_cell(ids: Sequence[str]) -> str:
    """A claim judged in the settings ``ids``: its statement, then its word in each, quoted by
    id (one claim: one word, wherever it is shown)."""
    statement = claimlist.claim(ids[0]).statement
    words = " / ".join(reportpage.verdict_markup(i) for i in ids)
    return f"{_escape(statement)}: {words}"


def _mark_categories(text: str) -> str:
    """A roll-up summary with every category name in it marked (they hold verdict words)."""
    out = _escape(text)
    for category in sorted(verdicts.cat.CATEGORIES, key=len, reverse=True):
        out = re.sub(
            rf"(?<![`\w]){re.escape(category)}(?![`\w])", reportpage.category_markup(category), out
        )
    return out


def counts_sentence(claim_ids: Sequence[str] = ()) -> str:
    """One sentence of the counts: what they count (claims once, other rows each) and, of the
    judged claims ``claim_ids`` (the report's thesis-claim rows), how many distinct claims of
    the thesis their rows judge (one claim may have a row per setting)."""
    rows, distinct, several = claimlist.thesis_claims_judged(claim_ids)
    per_claim = (
        f" The report's {rows} rows on the thesis's claims judge {distinct} distinct claims"
        + (
            f", {several} of them once per setting (the report names each row's setting); the "
            f"table counts such a claim once, under the word its settings share, or under the "
            f"word for settings that disagree"
            if rows > distinct
            else ""
        )
        + "."
        if rows
        else ""
    )
    return (
        "The table counts each claim once and every other report row once."
        f"{per_claim} Findings of ours are never counted among the thesis's claims; agreement "
        "that follows by construction is not counted as reproduction, and a part of a claim "
        "that cannot fail is shown with its evidence, never counted as support."
    )


def _plain(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, list):
        return ", ".join(_plain(v) for v in value)
    return str(value)


def profile_text(records: verdicts.Records, profile: str) -> str:
    """The profile named and every chapter's recorded parameters (``parameters.*`` records)."""
    parts, silent = [], []
    for name, rec in sorted(records.items()):
        params = {
            k.removeprefix(PARAMETER_PREFIX): v["value"]
            for k, v in sorted(rec.get("values", {}).items())
            if k.startswith(PARAMETER_PREFIX)
        }
        if params:
            listed = "; ".join(f"`{k}` = {_plain(v)}" for k, v in params.items())
            parts.append(f"- {name}: {listed}")
        else:
            silent.append(name)
    if parts and silent:
        parts.append(
            f"- {', '.join(silent)}: no parameter recorded (each page's parameters cell shows the "
            "values it ran with)"
        )
    head = (
        "This book was built with each chapter's default parameters. The parameters each chapter "
        "recorded:"
        if profile == DEFAULT_PROFILE
        else f"This book was built with the **{profile}** profile. Its recorded parameters:"
    )
    if parts:
        return "\n".join([head, "", *parts])
    return head.split(". ")[0] + ". No parameters were recorded."


def landing_markdown(
    records: verdicts.Records,
    profile: str,
    link: Link = doc_link,
    provenance: str = "",
    bundle: str = "",
    bundle_bytes: int = 0,
    bundle_members: Sequence[str] = (),
) -> str:
    """The landing page's MyST text (see :func:`write_landing`)."""
    if not isinstance(profile, str) or not _PROFILE.match(profile):
        raise ValueError(f"profile must be a name of letters, digits, - or _, got {profile!r}")
    rows = verdicts.all_rows(records)
    counts = verdicts.category_counts(rows)
    findings = [line for f in FINDINGS for line in finding_lines(f, records, rows, link)]
    data_text = bundle_mod.link_text(bundle, bundle_bytes, bundle_members) if bundle else ""
    return "\n".join(
        [
            TITLE_TEXT,
            outcome.outcome_markdown(claimlist.judge(records), rows),
            "",
            "## Main findings",
            "",
            *(findings or ["No finding could be stated from this build's records."]),
            "",
            THESIS_TEXT,
            "## Verdict per thesis artefact",
            "",
            LEGEND,
            "",
            artefact_table(rows, link),
            "",
            "## Counts per verdict",
            "",
            counts_sentence(verdicts.thesis_claim_ids(rows)),
            "",
            verdicts.counts_table(counts, reportpage.category_markup),
            "",
            "## This build",
            "",
            profile_text(records, profile),
            "",
            *([f"Made from:\n\n{provenance}", ""] if provenance else []),
            *(["## Data", "", data_text, ""] if bundle else []),
            RERUN_TEXT,
        ]
    )


def write_landing(
    records: verdicts.Records | Path,
    out: Path,
    profile: str,
    *,
    link: Link = doc_link,
    provenance: str = "",
    bundle: str = "",
    bundle_bytes: int = 0,
    bundle_members: Sequence[str] = (),
) -> None:
    """Write the landing page ``out`` from the records (only when its text changed).

    Parameters
    ----------
    records : mapping or Path
        ``{notebook: record}`` or the folder of record files (``build/records``).
    out : Path
        The page, e.g. ``book/intro.md``.
    profile : str
        The profile the book was built with (``ci``, ``full``, …).
    link : callable, optional
        ``link(page, what, text)`` → a MyST link to the section of a chapter page (the book
        build's ``Linker``); default: a link to the page.
    provenance : str, optional
        Markdown lines saying what made the build (:func:`mechlib.pipeline.provenance.text`).
    bundle : str, optional
        The data bundle's path in the book (``/generated/mechlib-data.zip``), linked when given.
    bundle_bytes : int, optional
        Its size, stated beside the link.
    bundle_members : sequence of str, optional
        Its file names: the link's sentence says what it holds from them.

    Raises
    ------
    ValueError
        For a profile that is not a plain name.
    FileNotFoundError
        For a records folder without records.
    """
    text = landing_markdown(
        verdicts.load_records(records),
        profile,
        link,
        provenance,
        bundle,
        bundle_bytes,
        bundle_members,
    )
    out = Path(out)
    if not out.exists() or out.read_text() != text:
        out.write_text(text)
