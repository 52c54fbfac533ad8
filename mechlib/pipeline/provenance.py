"""Where and with what a build was made: commit, date, profile, Python and package versions, CPU.

The landing page shows it (:mod:`mechlib.pipeline.landing`) and every other generated page ends
with it (:func:`block`, added by :mod:`mechlib.pipeline.bookbuild`), so that a reader can tell
which code and which machine produced the numbers and timings of the page. Nothing here enters
a record: records must be identical between builds, provenance is not.
"""

from __future__ import annotations

import datetime as dt
import platform
import subprocess
from importlib import metadata
from pathlib import Path

from mechlib.paths import REPO_ROOT

#: the profile of the default build (each notebook's own defaults: no override file)
DEFAULT_PROFILE = "ci"

#: The packages whose versions decide the book's numbers and pages.
PACKAGES: tuple[str, ...] = (
    "numpy",
    "scipy",
    "sfepy",
    "cvxopt",
    "scikit-learn",
    "pyDOE3",
    "matplotlib",
    "papermill",
    "jupyter-book",
)
#: What a value that cannot be read is shown as.
UNKNOWN = "unknown"


def commit(repo: Path = REPO_ROOT) -> str:
    """The checked-out commit (12 hex digits, ``+ local changes`` when the tree is dirty)."""
    try:
        head = subprocess.run(
            ["git", "-C", str(repo), "rev-parse", "--short=12", "HEAD"],
            capture_output=True, text=True, check=True,
        ).stdout.strip()  # fmt: skip
        dirty = subprocess.run(
            ["git", "-C", str(repo), "status", "--porcelain", "--untracked-files=no"],
            capture_output=True, text=True, check=True,
        ).stdout.strip()  # fmt: skip
    except (OSError, subprocess.CalledProcessError):
        return UNKNOWN
    return f"{head} + local changes" if dirty else head


def cpu_model(cpuinfo: Path = Path("/proc/cpuinfo")) -> str:
    """The processor's model name (Linux ``/proc/cpuinfo``), else what ``platform`` says."""
    try:
        for line in cpuinfo.read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or UNKNOWN


def versions(packages: tuple[str, ...] = PACKAGES) -> dict[str, str]:
    """Installed version of each package (``UNKNOWN`` when it is not installed)."""
    out = {}
    for name in packages:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = UNKNOWN
    return out


def utc_text(when: dt.datetime) -> str:
    """A time as the book writes it, in UTC (a naive time is taken as UTC).

    >>> utc_text(dt.datetime(2026, 11, 29, 7, 16, tzinfo=dt.timezone(dt.timedelta(hours=1))))
    '2026-11-29 06:16 UTC'
    """
    when = when if when.tzinfo else when.replace(tzinfo=dt.UTC)
    return when.astimezone(dt.UTC).strftime("%Y-%m-%d %H:%M UTC")


def text(now: dt.datetime | None = None, profile: str = "") -> str:
    """Markdown lines: commit, build date (UTC), profile, Python and package versions, CPU."""
    when = utc_text(now or dt.datetime.now(dt.UTC))
    listed = ", ".join(f"{k} {v}" for k, v in versions().items())
    parameters = (
        ""
        if not profile
        else ", with each chapter's default parameters"
        if profile == DEFAULT_PROFILE
        else f", with the parameters of profile `{profile}`"
    )
    built = f"- commit `{commit()}`, built {when}{parameters}"
    return "\n".join(
        [
            built,
            f"- Python {platform.python_version()}; {listed}",
            f"- processor: {cpu_model()} (timings quoted in the chapters are this machine's)",
        ]
    )


#: The title of the provenance box at the end of a generated page.
BLOCK_TITLE = "How this page was built"


def block(made: str) -> str:
    """A folded MyST admonition holding the provenance lines ``made`` (see :func:`text`), for the
    end of a Markdown page."""
    return f"\n```{{admonition}} {BLOCK_TITLE}\n:class: dropdown\n\n{made}\n```\n"


def rerun_lines(
    name: str,
    seconds: float | None,
    tasks: dict[str, int] | None = None,
    main: tuple[str, ...] = (),
) -> str:
    """Markdown lines for a chapter's provenance box: how long its default run took here, how
    many of its FE tasks were read rather than solved (``tasks``: ``total`` and ``cached``, from
    the execution; unknown: not said), the parameters a reader changes first (``main``) and the
    command that runs it again with a reader's."""
    took = (
        f"- this page's default run took {seconds:.0f} s on this machine"
        if seconds is not None
        else "- this page's run time was not recorded"
    )
    if tasks and tasks.get("total"):
        share = 100 * tasks["cached"] / tasks["total"]
        took += (
            f"; of its {tasks['total']:,} finite-element tasks, {tasks['cached']:,} "
            f"({share:.0f} %) were read from the FE cache seeded from the results store, not "
            "solved (a run with new forces or a new geometry solves them anew)"
        )
    elif tasks is not None:
        took += "; it runs no finite-element task"
    names = ", ".join(f"`{p}`" for p in main)
    first = f"its first code cell: {names} first" if main else "its first code cell"
    return (
        f"{took}\n- run it again with your own parameters (names and ranges in {first}): "
        f"`make run NB={name} ARGS='-p <name> <value>'`, into `build/runs/`"
    )


def notebook_cell(made: str) -> dict[str, object]:
    """A markdown cell holding :func:`block`, for the end of a chapter notebook."""
    return {"cell_type": "markdown", "id": "provenance", "metadata": {}, "source": block(made)}
