"""The landing page's sentence on the FE results store: where a build's FE runs came from, what
the store's cold sample implies, and how the store compares with the one it replaced (from its
manifest, :mod:`mechlib.campaign.store`).
"""

from __future__ import annotations

import datetime as dt
from pathlib import Path

from mechlib import fespecs as fespecs  # the FE families a store holds, registered
from mechlib.campaign import store
from mechlib.pipeline.provenance import utc_text

#: the pages whose finite-element results the store holds (what the landing page says it feeds)
STORE_USERS = (
    "the HexFlex model page's compliances and mesh study, the DOE chapter's Tables 2–5 with its "
    "non-linear validation, linear-range sweep and non-linear designs, the Eq 8 family page, "
    "the meta-model page and the parallelogram's own FE page"
)
#: share of wrong stored runs whose chance of escaping the cold sample the landing page states
WRONG_SHARE = 0.1


def landing_line(folder: Path, wrong_share: float = WRONG_SHARE) -> str:
    """One Markdown list line for the landing page: where this build's FE runs came from and,
    when from the store ``folder``, what its cold sample implies — the chance that
    at least ``COLD_NONLINEAR`` runs drawn uniformly, without replacement, within each
    mechanism family in proportion to its runs, from a store whose share ``wrong_share`` of runs
    is wrong miss every wrong one, at most ``(1 − wrong_share)^COLD_NONLINEAR``
    (:func:`~mechlib.campaign.cachecheck.sample_uniform`).

    Parameters
    ----------
    folder : Path
        The results store (absent: the build computed every FE run).
    wrong_share : float
        The share of wrong stored runs the sentence's probability assumes, in (0, 1).

    Returns
    -------
    str
        The Markdown list line, with the store's carried and compared records when it has them.

    Raises
    ------
    ValueError
        For a share outside (0, 1).
    StoreError
        For a store whose manifest cannot be read.
    """
    if not 0.0 < wrong_share < 1.0:
        raise ValueError(f"wrong_share must be in (0, 1), got {wrong_share}")
    if not (Path(folder) / store.MANIFEST).exists():
        return "- FE runs: every one computed by this build (no results store)."
    m = store.read_manifest(Path(folder))
    if m["fingerprint"] != store.fingerprint():
        return (
            "- FE runs: every one computed by this build (the results store was computed by "
            "other FE code)."
        )
    from mechlib.campaign.cachecheck import AGREE_RTOL, COLD_LINEAR, COLD_NONLINEAR

    runs = m["runs"]
    miss = (1.0 - wrong_share) ** COLD_NONLINEAR
    made = (
        f"computed {_when(m.get('date'))} on "
        f"{m.get('processor', 'an unrecorded processor')} at commit "
        f"`{m.get('commit', 'unrecorded')}`"
    )
    return (
        f"- FE runs: read from the results store, not solved again in this build: "
        f"{_n(runs.get('nonlinear', 0), 'geometrically non-linear run')} and "
        f"{_n(runs.get('linear', 0), 'linear load case')} of this FE code, {made}. "
        f"They are the finite-element results behind "
        f"{STORE_USERS}; every table, figure and number is computed from them when the book is "
        f"built. A sample of at least {COLD_NONLINEAR} stored non-linear runs and {COLD_LINEAR} "
        f"blocks of linear runs, drawn at random anew for each commit from each mechanism's "
        f"runs in proportion to their number, is recomputed "
        f"cold whenever the book is checked and must agree within {AGREE_RTOL:g} of each run's "
        f"largest pose component: were {wrong_share:.0%} of the stored runs wrong, such a "
        f"sample would miss every one of them with probability at most {miss:.1%}."
        + _carried_text(m)
        + _compared_text(m)
    )


def _when(date: str | None) -> str:
    """A manifest's ISO date as the book writes dates (``2026-11-29 06:16 UTC``; a date alone as
    it is)."""
    if not date:
        return "on an unrecorded date"
    try:
        when = dt.datetime.fromisoformat(date)
    except ValueError:
        return date
    return date if len(date) == 10 else utc_text(when)


def _n(count: int, word: str) -> str:
    """``count`` and ``word``, plural unless one."""
    return f"{count} {word}" if count == 1 else f"{count} {word}s"


def _previous(origin: dict, manifest: dict) -> str:
    """The FE code a record names: its commit, and whether it was this store's code."""
    commit = origin.get("commit")
    ours, theirs = manifest.get("fingerprints"), origin.get("fingerprints")
    code = "this FE code" if ours and ours == theirs else "the FE code"
    return f"{code} of commit `{commit}`" if commit else f"{code} of an unrecorded commit"


#: what a stored task is, for a reader who met runs and load cases first
TASKS = (
    "FE tasks (a task is one model's block of linear load cases, one non-linear run, one model "
    "size or one snapshot field)"
)


def _carried_text(manifest: dict) -> str:
    """What a store completed from an earlier one says of the tasks it carried (none: "")."""
    carried = manifest.get("carried")
    if not carried:
        return ""
    agreed = carried["agreed"]
    return (
        f" Of the store's {TASKS}, {carried['entries']} were not solved again but taken from the "
        f"results of {_previous(carried['from'], manifest)}, which are bit for bit these on "
        f"{'the' if agreed == 1 else 'all'} {_n(agreed, 'task')} both hold."
    )


#: a task kind as the landing page names it
KIND_WORDS = {
    "linear": "linear blocks",
    "nonlinear": "non-linear runs",
    "size": "model sizes",
    "state": "snapshot fields",
}


def _compared_text(manifest: dict) -> str:
    """What the store's comparison with the results computed before it says (none: "")."""
    c = manifest.get("compared")
    if not c:
        return ""
    old = f"the results of {_previous(c['from'], manifest)}"
    fresh = " solved from an empty FE cache" if manifest.get("from_empty") else ""
    if c["identical"] == c["both"] == c["tasks"] and not c["only_previous"]:
        fresh = f",{fresh}," if fresh else ""
        return f" The store's {c['tasks']} {TASKS}{fresh} are all bit for bit {old}."
    units = c.get("units", {})
    diffs = [
        " ".join(f"{v:.3g} {units.get(k, '')}".split()) + f" in its {KIND_WORDS.get(k, k)}"
        for k, v in c["largest_difference"].items()
        if v
    ]
    gone = c["only_previous"]
    tail = [f"the largest difference of any result is {', '.join(diffs)}"] if diffs else []
    if gone:
        tail.append(f"{_n(gone, 'task')} of those results {'is' if gone == 1 else 'are'} not here")
    return (
        f" Of the store's {c['tasks']} {TASKS}{fresh}, {c['both']} are also in {old}: "
        f"{c['identical']} bit for bit" + "".join(f"; {t}" for t in tail) + "."
    )
