"""Where a build puts things, and the environment variables that move them.

The one place that names the repository's build folders and the ``MECHLIB_*`` variables: the
notebooks' :class:`~mechlib.reporting.records.Recorder` writes to :func:`records_dir`, the DOE
chapter
caches FE results in :func:`fe_cache_dir`, and the build wing sets the variables when it
executes a notebook (a re-run into its own folders, ``make run`` into ``build/runs``).
"""

from __future__ import annotations

import os
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[1]
#: the default build: ``make notebooks`` of the ci profile (other profiles: ``build/<profile>``)
DEFAULT_BUILD = REPO_ROOT / "build"
#: the FE results store the repository ships (``make store`` writes it, ``make store-seed`` reads
#: it into the FE cache)
STORE_DIR = REPO_ROOT / "store"
#: folder that a notebook's record is written to (default ``build/records``)
RECORDS_ENV = "MECHLIB_RECORDS"
#: folder of cached FE results (default ``build/cache/experiments``)
FE_CACHE_ENV = "MECHLIB_FE_CACHE"
#: file that the FE cache's hits are logged to, one JSON line each (unset: no log); the
#: determinism re-run sets it, to recompute a sample of what it read from the cache
FE_LOG_ENV = "MECHLIB_FE_LOG"
#: set to "1": a chapter's inputs are read from ``$MECHLIB_RECORDS`` only, never from the default
#: build's records (the determinism re-run, which must not read the first run's)
RECORDS_STRICT_ENV = "MECHLIB_RECORDS_STRICT"
#: file that FE campaigns report their progress to, one JSON line an event (unset: none); the
#: build sets it for each notebook it executes and shows the progress on its own terminal
PROGRESS_ENV = "MECHLIB_PROGRESS"


def records_dir() -> Path:
    """Folder that records are written to: ``$MECHLIB_RECORDS`` or ``<repo>/build/records``."""
    return Path(os.environ.get(RECORDS_ENV, DEFAULT_BUILD / "records"))


def fe_cache_dir() -> Path:
    """Folder of cached FE results: ``$MECHLIB_FE_CACHE`` or ``<repo>/build/cache/experiments``."""
    return Path(os.environ.get(FE_CACHE_ENV, DEFAULT_BUILD / "cache" / "experiments"))


def progress_path() -> Path | None:
    """File that FE campaigns report their progress to (``$MECHLIB_PROGRESS``), or ``None``."""
    value = os.environ.get(PROGRESS_ENV)
    return Path(value) if value else None


def fe_log_path() -> Path | None:
    """File that FE cache hits are logged to (``$MECHLIB_FE_LOG``), or ``None``."""
    value = os.environ.get(FE_LOG_ENV)
    return Path(value) if value else None
