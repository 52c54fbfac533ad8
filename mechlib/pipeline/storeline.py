"""The landing page's sentence on the FE results store: where a build's FE runs came from, what
the store's cold sample implies, and how the store compares with the one it replaced (from its
manifest, :mod:`mechlib.campaign.store`).
"""

from __future__ import annotations

import datetime as dt
from pathlib import Path

from mechlib import fespecs as fespecs  # the FE families a store holds, registered
from mechlib.campaign import store

#: non-linear and linear tasks of the store that ``make test`` recomputes cold
COLD_NONLINEAR, COLD_LINEAR = 14, 2
#: snapshot (``STATE``) tasks of the store that ``make test`` recomputes cold: one full field
COLD_STATE = 1


#: the pages whose finite-element results the store holds (what the landing page says it feeds)
STORE_USERS = (
    "the HexFlex model page's compliances and mesh study, the DOE chapter's Tables 2–5 with its "
    "non-linear validation, linear-range sweep and non-linear designs, the Eq 8 family page and "
    "the meta-model page"
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
    from mechlib.campaign.cachecheck import AGREE_RTOL

    runs = m["runs"]
    miss = (1.0 - wrong_share) ** COLD_NONLINEAR
    made = (
        f"computed {_when(m.get('date'))} on "
        f"{m.get('processor', 'an unrecorded processor')} at commit "
        f"`{m.get('commit', 'unrecorded')}`"
    )
    return (
        f"- FE runs: read from the results store, not solved again in this build: "
        f"{runs.get('nonlinear', 0)} geometrically non-linear runs and {runs.get('linear', 0)} "
        f"linear load cases of this FE code, {made}. They are the finite-element results behind "
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
    """A manifest's ISO date as the book writes dates (``2026-11-29 06:16 UTC``)."""
    if not date:
        return "on an unrecorded date"
    try:
        when = dt.datetime.fromisoformat(date)
    except ValueError:
        return date
    if "T" not in date:  # a date without a time
        return when.strftime("%Y-%m-%d")
    when = when if when.tzinfo else when.replace(tzinfo=dt.UTC)
    return when.astimezone(dt.UTC).strftime("%Y-%m-%d %H:%M UTC")


def _carried_text(manifest: dict) -> str:
    """What a store completed from an earlier one says of the tasks it carried (none: "")."""
    carried = manifest.get("carried")
    if not carried:
        return ""
    return (
        f" Of the store's tasks, {carried['entries']} were not solved again by this FE code but "
        f"carried from the store of commit `{carried['from'].get('commit')}` (earlier FE code), "
        f"whose results agreed bit for bit on all {carried['agreed']} tasks this code solved."
    )


def _compared_text(manifest: dict) -> str:
    """What the store's comparison with the one it replaced says (none recorded: "")."""
    c = manifest.get("compared")
    if not c:
        return ""
    old = f"the store it replaced (commit `{c['from'].get('commit')}`, earlier FE code)"
    if c["identical"] == c["both"] == c["tasks"] and not c["only_previous"]:
        return f" All {c['tasks']} of its tasks are bit for bit those of {old}."
    diff = ", ".join(f"{k} {v:.3g}" for k, v in c["largest_difference"].items())
    return (
        f" Of its {c['tasks']} tasks, {c['both']} are also in {old}: {c['identical']} bit for "
        f"bit, the largest difference of any result by kind of task {diff or 'none'}"
        + (
            f"; {c['only_previous']} tasks of the store it replaced are no longer asked for."
            if c["only_previous"]
            else "."
        )
    )
