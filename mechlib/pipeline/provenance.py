"""Where and with what a build was made: commit, date, profile, Python and package versions, CPU.

The landing page shows it (:mod:`mechlib.pipeline.landing`), so that a reader can tell which code
and which machine produced the numbers and timings of the book. Nothing here enters a record:
records must be identical between builds, provenance is not.
"""

from __future__ import annotations

import datetime as dt
import platform
import subprocess
from importlib import metadata
from pathlib import Path

from mechlib.paths import REPO_ROOT

#: The packages whose versions decide the book's numbers and pages.
PACKAGES: tuple[str, ...] = (
    "numpy",
    "scipy",
    "sfepy",
    "cvxopt",
    "scikit-learn",
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


def text(now: dt.datetime | None = None) -> str:
    """Markdown lines: commit, build date (UTC), Python and package versions, CPU model."""
    when = (now or dt.datetime.now(dt.UTC)).strftime("%Y-%m-%d %H:%M UTC")
    listed = ", ".join(f"{k} {v}" for k, v in versions().items())
    return "\n".join(
        [
            f"- commit `{commit()}`, built {when}",
            f"- Python {platform.python_version()}; {listed}",
            f"- processor: {cpu_model()} (timings quoted in the chapters are this machine's)",
        ]
    )
