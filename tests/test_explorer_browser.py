"""The built explorer page ("Try the model") in headless Chromium, from ``file://``, network off:
its own JavaScript evaluates and inverts the recorded model as Python does (run after
``make book``).

Skipped when no Chromium is installed, and when no book with the page is built, except under
``make check-book`` (``MECHLIB_REQUIRE_BOOK=1``), where a missing page or record fails. The
measured numbers (largest differences, round trip, µs a pose in the browser, the page's bytes)
are written to ``book/_build/explorer-check.json``.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from mechlib.paths import REPO_ROOT, records_dir
from mechlib.pipeline.book import browser, explorer, explorercheck

HTML = REPO_ROOT / "book" / "_build" / "html"
OUT = REPO_ROOT / "book" / "_build" / "explorer-check.json"


@pytest.fixture(scope="module")
def chromium() -> str:
    found = browser.find_browser()
    if found is None:
        pytest.skip(f"no Chromium (looked for {', '.join(browser.BROWSERS)})")
    return found


@pytest.fixture(scope="module")
def html_root() -> Path:
    needed = (HTML / explorercheck.PAGE, explorer.model_path(records_dir()))
    missing = [str(p) for p in needed if not p.is_file()]
    if missing:
        if os.environ.get("MECHLIB_REQUIRE_BOOK") == "1":
            pytest.fail(f"the explorer page cannot be checked, missing: {', '.join(missing)}")
        pytest.skip(f"no built explorer page or recorded model: {', '.join(missing)}")
    return HTML


def test_the_pages_javascript_evaluates_and_inverts_the_recorded_model_as_python_does(
    html_root: Path, chromium: str
) -> None:
    measured, problems = explorercheck.check(html_root, records_dir(), chromium)
    OUT.write_text(json.dumps({**measured, "problems": problems}, indent=1) + "\n")
    assert problems == [], "\n".join(problems)
    assert measured["vectors"] >= 1000 and measured["targets"] >= 16
    assert measured["max_rel_diff_vs_numpy"] <= explorercheck.POSE_TOL
    assert measured["page_bytes_total"] <= explorercheck.PAGE_BUDGET
