"""The main job timed as a reader runs it (``make bench ONLY=book``): ``git clone`` of HEAD, then
``make book`` in the clone, wall time measured, and each chapter's papermill duration read from
the clone's executed notebooks.

The clone is fresh (its own ``.venv``, FE cache seeded from its ``store/``, no build folder); the
package installer's cache is whatever this machine has (warm after a first install). Committed
work only: uncommitted changes of this working tree are not in the clone.
"""

from __future__ import annotations

import json
import subprocess
import tempfile
import time
from pathlib import Path

#: The repository whose HEAD is cloned.
REPO_ROOT = Path(__file__).resolve().parents[2]


def chapter_durations(executed: Path) -> dict[str, float]:
    """Papermill's duration [s] of every executed notebook in ``executed``, by notebook name
    (a notebook without one is left out)."""
    out = {}
    for nb in sorted(Path(executed).glob("*.ipynb")):
        seconds = json.loads(nb.read_text()).get("metadata", {}).get("papermill", {})
        if seconds.get("duration") is not None:
            out[nb.stem] = float(seconds["duration"])
    return out


def clone_and_build(repo: Path = REPO_ROOT, workdir: Path | None = None) -> dict[str, object]:
    """Clone ``repo``'s HEAD into a new folder and run ``make book`` there.

    Parameters
    ----------
    repo : Path
        A git working tree.
    workdir : Path, optional
        Where the clone goes (default: a new temporary folder, removed afterwards).

    Returns
    -------
    dict
        ``commit`` (short hash), ``clone_s`` and ``book_s`` [s] wall times, ``chapters``
        (:func:`chapter_durations` of the clone's build).

    Raises
    ------
    subprocess.CalledProcessError
        If the clone or ``make book`` fails (its output was shown as it ran).
    """
    commit = subprocess.run(
        ["git", "-C", str(repo), "rev-parse", "--short=12", "HEAD"],
        check=True, capture_output=True, text=True,
    ).stdout.strip()  # fmt: skip
    with tempfile.TemporaryDirectory(dir=workdir) as tmp:
        clone = Path(tmp) / "clone"
        t0 = time.perf_counter()
        subprocess.run(["git", "clone", "--quiet", str(repo), str(clone)], check=True)
        t1 = time.perf_counter()
        subprocess.run(["make", "--no-print-directory", "book"], cwd=clone, check=True)
        t2 = time.perf_counter()
        chapters = chapter_durations(clone / "build" / "executed")
    return {"commit": commit, "clone_s": t1 - t0, "book_s": t2 - t1, "chapters": chapters}


def report(result: dict[str, object]) -> list[str]:
    """The lines ``make bench ONLY=book`` prints: the total, then every chapter, longest first."""
    chapters: dict[str, float] = result["chapters"]  # type: ignore[assignment]
    lines = [
        f"make book on a fresh clone of {result['commit']}: {result['book_s']:.0f} s "
        f"({result['book_s'] / 60:.1f} min; git clone {result['clone_s']:.1f} s before it)",
        f"  chapters (papermill, in parallel as make book runs them; sum "
        f"{sum(chapters.values()):.0f} s):",
    ]
    lines += [
        f"    {name:<24} {s:6.1f} s" for name, s in sorted(chapters.items(), key=lambda kv: -kv[1])
    ]
    return lines


def print_book() -> None:
    """Run :func:`clone_and_build` and print :func:`report`."""
    print("\n".join(report(clone_and_build())))
