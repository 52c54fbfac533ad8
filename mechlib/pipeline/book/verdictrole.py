"""The book's roles for verdicts: a claim's verdict word quoted by id, a category's name marked.

``{verdict}`ch3.iii.5r.table8``` renders the verdict word the claims registry gives that claim in
this build (``book/generated/claims.json``, written by the book build from the records:
:func:`mechlib.reporting.claimlist.judge`), as ``<span class="claim-verdict claim-id-ch3-iii-5r-
table8">mixed</span>``; an id that this build did not judge stops the build. ``{category}`…```
marks the name of a report category ("thesis claim supported"), which contains verdict words
without being a verdict of its own. The page check (:mod:`mechlib.pipeline.book.claimcheck`) reads
both classes: no verdict word may stand outside them, and no claim may read differently on two
pages. A Sphinx extension (``book/_config.yml``).
"""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

from docutils import nodes

#: the judged claims, relative to the book's source folder
CLAIMS_FILE = Path("generated") / "claims.json"
VERDICT_CLASS = "claim-verdict"
CATEGORY_CLASS = "verdict-category"
#: prefix of the class naming the claim's id on its verdict span
CLAIM_CLASS_PREFIX = "claim-id-"


def claim_class(claim_id: str) -> str:
    """The HTML class that names ``claim_id`` on its verdict span (dots as hyphens)."""
    return CLAIM_CLASS_PREFIX + re.sub(r"[^a-z0-9]+", "-", claim_id.lower()).strip("-")


def _judged(srcdir: str) -> dict[str, Any]:
    path = Path(srcdir) / CLAIMS_FILE
    return json.loads(path.read_text()) if path.exists() else {}


def verdict_role(name, rawtext, text, lineno, inliner, options=None, content=None):
    """``{verdict}`<claim id>```: the claim's verdict word in this build."""
    claim_id = text.strip()
    judged = _judged(inliner.document.settings.env.srcdir)
    if claim_id not in judged:
        msg = inliner.reporter.error(
            f"verdict: claim {claim_id!r} was not judged in this build ({CLAIMS_FILE} holds "
            f"{len(judged)} claims)",
            line=lineno,
        )
        return [inliner.problematic(rawtext, rawtext, msg)], [msg]
    word = judged[claim_id]["word"]
    return [nodes.inline(rawtext, word, classes=[VERDICT_CLASS, claim_class(claim_id)])], []


def category_role(name, rawtext, text, lineno, inliner, options=None, content=None):
    """``{category}`<name>```: a report category's name, marked apart from prose."""
    return [nodes.inline(rawtext, text, classes=[CATEGORY_CLASS])], []


def setup(app: Any) -> dict[str, Any]:
    """Register the roles (Sphinx extension entry point)."""
    app.add_role("verdict", verdict_role)
    app.add_role("category", category_role)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
