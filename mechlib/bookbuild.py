"""Assemble the book's generated pages from the executed notebooks and their records.

``python -m mechlib.bookbuild --executed build/executed --book book`` copies every executed
notebook into ``book/chapters/`` (a build product) and writes ``book/report.md``, the
reproduction report, from the ``report`` rows of every record in ``build/records``.
"""

from __future__ import annotations

import argparse
import shutil
from pathlib import Path

from mechlib.records import REPO_ROOT, load, records_dir

REPORT_HEADER = """# Reproduction report

One row per thesis artefact and compared quantity, generated from the records that the chapters'
notebooks wrote in this build (nothing on this page is typed by hand). *Reproduced* means the
difference is within half a unit of the last digit the thesis printed; *within tolerance* names
the relative tolerance allowed beyond that; *diverges* gives the cause found in the chapter.
Differences are absolute (in the units of the published value) and relative.

"""
COLUMNS = ("artefact", "quantity", "published", "ours", "max_abs_diff", "max_rel_diff", "verdict")


def _cell(value: object) -> str:
    if value is None:
        return "—"
    if isinstance(value, float):
        return f"{value:.3g}"
    return str(value).replace("|", "\\|").replace("\n", " ")


def report_markdown(records: Path) -> str:
    """Markdown of the reproduction report built from every record file in ``records``."""
    lines = [REPORT_HEADER]
    for path in sorted(Path(records).glob("*.json")):
        rec = load(path)
        if not rec.get("report"):
            continue
        lines.append(f"## From `{rec['notebook']}`\n")
        lines.append("| " + " | ".join(COLUMNS) + " |")
        lines.append("|" + "---|" * len(COLUMNS))
        for row in rec["report"]:
            lines.append("| " + " | ".join(_cell(row.get(c)) for c in COLUMNS) + " |")
        lines.append("")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """Copy executed notebooks into the book and write the report page."""
    parser = argparse.ArgumentParser(prog="python -m mechlib.bookbuild")
    parser.add_argument("--executed", type=Path, default=REPO_ROOT / "build" / "executed")
    parser.add_argument("--records", type=Path, default=records_dir())
    parser.add_argument("--book", type=Path, default=REPO_ROOT / "book")
    args = parser.parse_args(argv)
    chapters = args.book / "chapters"
    chapters.mkdir(parents=True, exist_ok=True)
    for nb in sorted(args.executed.glob("*.ipynb")):
        target = chapters / nb.name
        if not target.exists() or target.read_bytes() != nb.read_bytes():
            shutil.copyfile(nb, target)
    report = report_markdown(args.records)
    target = args.book / "report.md"
    if not target.exists() or target.read_text() != report:
        target.write_text(report)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
