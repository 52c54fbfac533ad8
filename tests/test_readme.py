"""The README: a new user's first screen, short, and every page it sends them to exists."""

from __future__ import annotations

import re

from mechlib.paths import REPO_ROOT

README = REPO_ROOT / "README.md"
#: the README's length limit in words (as ``wc -w`` counts them)
MAX_WORDS = 800
#: lines of a first screen (a terminal's, or a repository page's above the fold)
FIRST_SCREEN_LINES = 25


def test_the_readme_is_short_and_starts_with_the_two_commands() -> None:
    text = README.read_text()
    assert len(text.split()) <= MAX_WORDS
    first = "\n".join(text.splitlines()[:FIRST_SCREEN_LINES])
    assert re.search(r"^make book\b", first, re.M) and re.search(r"^make test\b", first, re.M)


def test_every_page_the_readme_links_exists() -> None:
    links = re.findall(r"\]\(([^)#]+)\)", README.read_text())
    assert any(link.startswith("docs/") for link in links)
    missing = [link for link in links if not (REPO_ROOT / link).is_file()]
    assert missing == []


def test_the_readme_types_no_page_count() -> None:
    """The book's page count is what `pdfinfo` says of a build, never a number typed in the
    README (it went stale: "≈ 140-page" against a 164-page print)."""
    assert re.findall(r"\d+[ -]pages?\b", README.read_text()) == []
