"""The book's data bundle: one zip with the thesis's transcribed tables, every record and our runs.

``make book`` writes it (:func:`write_bundle`, called by :mod:`mechlib.pipeline.bookbuild`) to
``book/generated/``; the landing page links it with a ``{download}`` role, so Sphinx copies it into
the HTML output. Contents:

* ``thesis/*.csv``: the tables and equations transcribed from the thesis
  (:mod:`mechlib.published`), values as printed (Table 2 in its printed nm and mrad), one file per
  artefact;
* ``records/<notebook>.json``: every record of this build (key numbers, tolerances, report rows);
* ``runs/*.csv``: the FE runs the records hold in full (our responses to the designs of Tables 2
  and 4), with their forces, and the members the caller adds (every run of the results store:
  :mod:`mechlib.pipeline.bundleruns`);
* ``data/<notebook>/``: the tables and models the notebooks kept for it
  (:meth:`~mechlib.reporting.records.Recorder.add_data`), with the plain-Python evaluator of the
  real-time model beside it;
* ``claims.json``: every claim the book judges, machine-readable
  (:func:`mechlib.reporting.claimlist.claims_file`), so that another reproduction can be compared
  with this one claim by claim;
* ``README.txt``: what each file is, how to read the claims file, and what is not included.
"""

from __future__ import annotations

import csv
import io
import json
import textwrap
import zipfile
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path

import numpy as np

from mechlib import published as pub
from mechlib.metamodels import evaluator
from mechlib.metamodels.metrics import FULL_SCALE_DEFINITION
from mechlib.reporting import claimlist
from mechlib.reporting.records import DATA_DIR, DATA_INDEX

#: The bundle's file name (the landing page links it).
NAME = "mechlib-data.zip"
#: a fixed time stamp for every member, so that equal contents give equal bytes
_STAMP = (2010, 1, 1, 0, 0, 0)
_HEADS = [f"{r} [{u}]" for r, u in zip(pub.RESPONSES, pub.RESPONSE_UNITS, strict=True)]
_FORCES = [f"{f} [N]" for f in pub.FACTORS]
#: records whose values hold whole runs: (notebook, record key, design, file, what)
RUNS: tuple[tuple[str, str, str, str], ...] = (
    ("virtual_experiments", "table2.responses", "TABLE2_DESIGN", "runs/table2_ours.csv"),
    ("virtual_experiments", "table4.responses", "TABLE4_DESIGN", "runs/table4_ours.csv"),
)

README = """\
Data of the executable reproduction of D. Restrepo, "Experiment Design in Compliant Mechanisms
and Kinematic Identification of Parallel Mechanisms", thesis, Universidad EAFIT, 2010.

thesis/   values transcribed from the thesis (mechlib/published.py), as printed:
          table1_levels.csv, table2_printed.csv (responses in nm and mrad, although the thesis's
          header says um and urad), table3_effects.csv, table3_summary.csv,
          table4_printed.csv, eq8_S_T.csv, table5.csv, table6_printed.csv, table7.csv,
          table8_printed.csv
records/  every record of this build: key numbers with their tolerances, glued values and the
          reproduction report's rows (JSON)
runs/     table2_ours.csv, table4_ours.csv: our FE model's responses to the designs of Tables 2
          and 4 (um, urad), with the forces
claims.json
          every claim the book judges, one entry per claim and setting. Each entry: id; group
          (the claim a setting belongs to: count groups, not entries); source ("thesis" or
          "ours"); where (the thesis's section and artefact, or the book's section); statement;
          page (the notebook that records its evidence); setting; word; parts. Each part:
          label; rule (at_most, paired, ...); record_keys (notebook, key in that notebook's
          records/<notebook>.json under "values", else under "timings", and an index into the
          value, "0:3" a slice); values (as read); limit (its threshold; null when the
          threshold is itself a recorded value or two values are compared); can_fail; why (for
          a part that cannot fail: the reason); holds; evidence (in words). "word_rule" says
          how a word follows from the parts: only parts with can_fail true count. "measure"
          defines "% of full scale"; "deadline_us" is the one real-time deadline. To compare
          two reproductions, match entries by id, then compare word, then each part's values
          against the other's limit.

Errors in "% of full scale": {measure}

Licence: what this reproduction computed is under the MIT licence of its repository (LICENSE,
(c) 2026 The mechlib reproduction contributors); the values under thesis/ are the thesis's,
transcribed and cited, and keep its rights.
"""
#: where the real-time model's plain-Python evaluator goes, beside the model
EVALUATOR = "data/nonlinear_metamodels/evaluator.py"


def _wrapped(text: str, width: int = 92) -> str:
    """``text`` in lines of at most ``width`` characters (the README's plain text)."""
    return textwrap.fill(text, width)


def _number(value: float) -> str:
    return np.format_float_positional(float(value), trim="-")


def csv_text(header: Sequence[str], rows: Iterable[Sequence[object]]) -> str:
    """CSV text (``\\n`` line ends) of a header and rows; floats as their shortest decimal."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(header)
    for row in rows:
        writer.writerow([_number(v) if isinstance(v, float | np.floating) else v for v in row])
    return out.getvalue()


def _matrix(header: Sequence[str], index: Sequence[str], values: np.ndarray) -> str:
    rows = zip(index, values, strict=True)
    return csv_text(header, ([name, *map(float, row)] for name, row in rows))


def _printed(rows: Sequence[str], columns: Mapping[str, Sequence[str]]) -> str:
    cells = ([r, *(c[i] for c in columns.values())] for i, r in enumerate(rows))
    return csv_text(["row", *columns], cells)


def thesis_tables() -> dict[str, str]:
    """The transcribed thesis tables as CSV texts, by file name inside the bundle."""
    runs12 = [str(i) for i in range(1, 13)]
    runs30 = [str(i) for i in range(1, 31)]
    printed_t2 = [
        f"{r} [{u}]" for r, u in zip(pub.RESPONSES, pub.TABLE2_PRINTED_UNITS, strict=True)
    ]
    t7 = (
        [n, pub.TABLE7_UNITS[n], *map(float, row)]
        for n, row in zip(pub.TABLE7_NAMES, pub.TABLE7, strict=True)
    )
    per_n = [f"{r} [{u}/N]" for r, u in zip(pub.RESPONSES, pub.RESPONSE_UNITS, strict=True)]
    return {
        "thesis/table1_levels.csv": csv_text(
            ["factor", "low [N]", "high [N]"],
            ([f, pub.TABLE1_LOW_N, pub.TABLE1_HIGH_N] for f in pub.FACTORS),
        ),
        "thesis/table2_printed.csv": _matrix(
            ["run", *_FORCES, *printed_t2], runs12, np.c_[pub.TABLE2_DESIGN, pub.TABLE2_RESPONSES]
        ),
        "thesis/table3_effects.csv": _matrix(
            ["factor", *printed_t2], pub.TABLE3_EFFECT_ROWS, pub.TABLE3_EFFECTS
        ),
        "thesis/table3_summary.csv": _matrix(
            ["statistic", *printed_t2], pub.TABLE3_SUMMARY_ROWS, pub.TABLE3_SUMMARY
        ),
        "thesis/table4_printed.csv": _matrix(
            ["run", *_FORCES, *_HEADS], runs30, np.c_[pub.TABLE4_DESIGN, pub.TABLE4_RESPONSES]
        ),
        "thesis/eq8_S_T.csv": _matrix(
            ["response [per N]", *pub.FACTORS],
            per_n,
            pub.EQ8_ST,
        ),
        "thesis/table5.csv": _matrix(["response", *pub.TABLE5_COLUMNS], _HEADS, pub.TABLE5),
        "thesis/table6_printed.csv": _printed(pub.TABLE6_ROWS, pub.TABLE6_PRINTED),
        "thesis/table7.csv": csv_text(["parameter", "unit", "nominal", "real"], t7),
        "thesis/table8_printed.csv": _printed(pub.TABLE8_ROWS, pub.TABLE8_PRINTED),
    }


def link_text(bundle: str, size_bytes: int, members: Sequence[str] = ()) -> str:
    """The landing page's paragraph linking the bundle (``bundle``: its path in the book;
    ``size_bytes``: the zip's size; ``members``: its file names, which say what it holds)."""
    size = f"{size_bytes / 1e6:.2g} MB" if size_bytes >= 1e6 else f"{size_bytes / 1e3:.3g} kB"
    held = ["every record of key numbers with its tolerance and report rows (JSON)"]
    if "claims.json" in members:
        held.append(
            "every verdict of the book, machine-readable (claims.json: each claim's thesis "
            "location, statement, setting, word, and its parts with their record keys, values, "
            "thresholds and whether each can fail)"
        )
    if "runs/nonlinear_runs.csv" in members:
        held.append(
            "every FE run the book reads (the linear and non-linear runs with their forces, "
            "poses and solve statistics, and the FE models with their geometry)"
        )
    else:
        held.append("our FE runs of the designs of Tables 2 and 4 (CSV)")
    if "data/nonlinear_metamodels/learning_curves.csv" in members:
        held.append("the learning curves of the meta-models")
    if EVALUATOR in members:
        held.append("the real-time model as coefficients (JSON) with a plain-Python evaluator")
    return (
        f"{{download}}`Download the data of this build <{bundle}>` (one zip, {size}): the "
        f"thesis's tables as transcribed (CSV), {', '.join(held[:-1])} and {held[-1]}; its "
        "README says what each file is, with units, and how to read the claims file."
    )


def members(path: Path) -> list[str]:
    """The file names inside the bundle ``path``."""
    with zipfile.ZipFile(path) as archive:
        return archive.namelist()


def notebook_data(records: Path) -> tuple[dict[str, str], list[str]]:
    """The files the notebooks kept for the bundle (``<records>/data/<notebook>/``) by name in
    the bundle, and their README lines; the real-time model's evaluator beside its model."""
    files: dict[str, str] = {}
    lines: list[str] = []
    for index in sorted(Path(records).glob(f"{DATA_DIR}/*/{DATA_INDEX}")):
        folder = index.parent
        for name, about in json.loads(index.read_text()).items():
            member = f"{DATA_DIR}/{folder.name}/{name}"
            files[member] = (folder / name).read_text()
            lines.append(f"{member}: {about}")
    if "data/nonlinear_metamodels/realtime_model.json" in files:
        files[EVALUATOR] = Path(evaluator.__file__).read_text()
        lines.append(
            f"{EVALUATOR}: the real-time model's evaluator in plain Python (no NumPy); "
            "`python evaluator.py realtime_model.json` prints its largest difference from the "
            "model's check values"
        )
    return files, lines


def run_tables(records: Mapping[str, Mapping]) -> dict[str, str]:
    """Our runs that the records hold in full (:data:`RUNS`), as CSV texts by file name; a
    record this build does not have is left out."""
    out = {}
    for notebook, key, design_name, name in RUNS:
        values = records.get(notebook, {}).get("values", {})
        if key not in values:
            continue
        design = getattr(pub, design_name)
        runs = [str(i) for i in range(1, len(design) + 1)]
        out[name] = _matrix(
            ["run", *_FORCES, *_HEADS], runs, np.c_[design, np.asarray(values[key]["value"])]
        )
    return out


def write_bundle(
    records: Path, out: Path, extra: Mapping[str, str] | None = None, extra_readme: str = ""
) -> Path:
    """Write the bundle ``out`` (a zip) from the record folder ``records``; return its path.

    ``extra`` adds members (name → text), ``extra_readme`` their README paragraph.

    Raises
    ------
    FileNotFoundError
        When ``records`` holds no record.
    """
    paths = sorted(Path(records).glob("*.json"))
    if not paths:
        raise FileNotFoundError(f"bundle: no <notebook>.json in {records}")
    loaded = {p.stem: json.loads(p.read_text()) for p in paths}
    data, data_lines = notebook_data(records)
    readme = README.format(measure=_wrapped(FULL_SCALE_DEFINITION)) + extra_readme
    if data_lines:
        readme += "data/     what the notebooks kept for this bundle:\n"
        readme += "".join(f"          {line}\n" for line in data_lines)
    claims = claimlist.claims_file(claimlist.judge(loaded))
    members = {
        "README.txt": readme,
        "claims.json": json.dumps(claims, indent=1, ensure_ascii=False) + "\n",
        **thesis_tables(),
        **{f"records/{p.name}": p.read_text() for p in paths},
        **run_tables(loaded),
        **(extra or {}),
        **data,
    }
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, text in members.items():
            info = zipfile.ZipInfo(name, _STAMP)
            info.compress_type = zipfile.ZIP_DEFLATED
            archive.writestr(info, text)
    return out
