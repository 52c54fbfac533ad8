"""``python -m mechlib.pipeline store …``: the FE results store of the repository (``store/``).

=============  ====================================================================================
seed           write the store's tasks into a build's FE cache (refuses a stale, edited or corrupt
               store)
clean          refuse a work tree with uncommitted changes (``make store`` starts with it)
pack           collect every FE task a build logged into the store, with its provenance
               (``make store``)
check          recompute a sample of the store's tasks cold, seeded by the commit (``make test``)
add-snapshots  add the meta-model page's reduced-order-model snapshots (full fields) to the store,
               read from the build's FE cache or solved, its runs kept byte for byte
=============  ====================================================================================

Each refusal is one line naming the thing and what to do, with exit code 2.
"""

from __future__ import annotations

import argparse
import datetime as dt
import platform
import subprocess
import sys
from pathlib import Path

from mechlib import fespecs as fespecs  # the FE families a store holds, registered
from mechlib.campaign import store
from mechlib.paths import DEFAULT_BUILD, REPO_ROOT, STORE_DIR
from mechlib.pipeline.provenance import UNKNOWN, commit, cpu_model

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


def _seed(args: argparse.Namespace) -> int:
    if not (args.store / store.MANIFEST).exists():
        print(f"store: no {args.store / store.MANIFEST}: every FE task is computed (`make store`)")
        return 0
    n = store.seed_cache(args.store, args.cache)
    print(f"store: {n} FE tasks of {args.store} verified (checksum, keys) and written to the cache")
    return 0


#: what :func:`mechlib.pipeline.provenance.commit` appends for a tree with uncommitted changes
DIRTY = "local changes"


def clean_commit(expected: str | None = None) -> str:
    """The checked-out commit, refusing a tree with uncommitted changes (a store must be
    reproducible from a commit) or, with ``expected``, a commit other than the one a build started
    from.

    Raises
    ------
    StoreError
        Naming the commit and what to do.
    """
    head = commit()
    if head == UNKNOWN:
        raise store.StoreError(
            "no git commit could be read: a store records the commit that computed it"
        )
    untracked = _untracked_sources()
    if untracked:
        raise store.StoreError(
            f"files not in git that a build reads: {', '.join(untracked[:5])}: add or remove them, "
            "then `make store`"
        )
    if DIRTY in head:
        raise store.StoreError(
            f"the work tree has uncommitted changes ({head}): commit them, then `make store`, so "
            "that the store records the commit that computed it"
        )
    if expected is not None and (
        not expected.strip() or not (expected.startswith(head) or head.startswith(expected))
    ):
        raise store.StoreError(
            f"the checked-out commit {head} is not {expected}, the one the build started from: "
            "run `make store` again on one commit"
        )
    return head


def _untracked_sources() -> list[str]:
    """Files under mechlib/ and notebooks/ that git does not track (and does not ignore)."""
    try:
        out = subprocess.run(
            ["git", "-C", str(REPO_ROOT), "ls-files", "--others", "--exclude-standard",
             "mechlib", "notebooks"],
            capture_output=True, text=True, check=True,
        ).stdout  # fmt: skip
    except (OSError, subprocess.CalledProcessError):
        return []
    return [line for line in out.splitlines() if line.strip()]


def _clean(args: argparse.Namespace) -> int:
    print(f"store: work tree clean at commit {clean_commit()}")
    return 0


def _pack(args: argparse.Namespace) -> int:
    head = clean_commit(args.commit)
    entries = store.entries_from_cache(args.log, args.cache)
    provenance = {
        "commit": head,
        "date": dt.datetime.now(dt.UTC).isoformat(timespec="seconds"),
        "processor": cpu_model(),
        "python": platform.python_version(),
        "seconds": args.seconds,
        "workers": args.workers,
        # whether those seconds solved every run (an empty FE cache) or resumed from a cache
        "from_empty": args.from_empty,
    }
    if args.compare is not None:
        from mechlib.campaign.carry import compare

        provenance["compared"] = c = compare(entries, args.compare)
        print(
            f"store: {c['both']} of {len(entries)} FE tasks also in {args.compare}, "
            f"{c['identical']} of them bit for bit; largest difference by kind "
            f"{c['largest_difference']}; {c['only_previous']} of its tasks not in this build"
        )
    if args.carry is not None:
        from mechlib.campaign.carry import carry

        carried, provenance["carried"] = carry(entries, args.carry)
        print(
            f"store: {len(carried)} FE tasks carried from {args.carry} (the "
            f"{provenance['carried']['agreed']} both hold agree bit for bit)"
        )
        entries = entries + carried
    folder = store.write_store(entries, args.store, provenance)
    m = store.read_manifest(folder)
    print(f"store: {len(entries)} FE tasks ({m['runs']}) written to {folder}")
    return 0


def _check(args: argparse.Namespace) -> int:
    from mechlib.campaign.cachecheck import AGREE_RTOL, check_entries

    _, entries = store.read_store(args.store)
    seed = int(commit().split("+")[0].strip()[:12] or "0", 16) if args.seed is None else args.seed
    per_kind = {"nonlinear": args.nonlinear, "linear": args.linear, "state": args.state}
    checks = check_entries(entries, per_kind, seed, workers=args.workers)
    for c in checks:
        verdict = "agrees" if c.agrees else "DIFFERS"
        print(
            f"  store {c.kind} task {c.file} ({c.rows} run(s)) recomputed cold: {verdict} "
            f"(largest difference {c.max_abs_diff:.3g}; stored {c.stored}, recomputed {c.fresh})"
            if not c.agrees
            else f"  store {c.kind} task {c.file} ({c.rows} run(s)) recomputed cold: {verdict}"
            f" (largest difference {c.max_abs_diff:.3g})"
        )
    bad = [c for c in checks if not c.agrees]
    print(
        f"store: {len(checks) - len(bad)} of {len(checks)} sampled tasks (seed {seed}, of "
        f"{len(entries)} stored) recomputed cold agree within {AGREE_RTOL:g} of each task's "
        f"largest pose (or snapshot field) component"
    )
    return 1 if bad else 0


def _add_snapshots(args: argparse.Namespace) -> int:
    from mechlib.pipeline.storesnapshots import add_snapshots

    head = clean_commit()
    m, solved = add_snapshots(args.store, args.records, args.cache, head, args.workers)
    size = (args.store / store.SNAPSHOTS).stat().st_size / 1e6
    print(
        f"store: {m['entries']['state']} snapshot fields in {args.store / store.SNAPSHOTS} "
        f"({size:.1f} MB; {solved} solved, the others read from {args.cache}, in "
        f"{m['snapshots']['seconds']:g} s at commit {head}); runs unchanged, sha256 "
        f"{m[store.SNAPSHOTS_SHA]}"
    )
    return 0


def parser() -> argparse.ArgumentParser:
    """The ``store`` command's arguments."""
    top = argparse.ArgumentParser(prog="python -m mechlib.pipeline store")
    sub = top.add_subparsers(dest="cmd", required=True)
    seed = sub.add_parser("seed", help="the store's tasks into an FE cache")
    seed.add_argument("--store", type=Path, required=True)
    seed.add_argument("--cache", type=Path, required=True)
    seed.set_defaults(func=_seed)
    clean = sub.add_parser("clean", help="refuse a work tree with uncommitted changes")
    clean.set_defaults(func=_clean)
    pack = sub.add_parser("pack", help="a build's logged FE tasks into the store")
    pack.add_argument("--commit", default=None, help="the commit the build started from")
    pack.add_argument("--log", type=Path, required=True)
    pack.add_argument("--cache", type=Path, required=True)
    pack.add_argument("--store", type=Path, required=True)
    pack.add_argument("--seconds", type=float, default=None, help="wall time of the build")
    pack.add_argument("--workers", type=str, default=None, help="where it ran")
    pack.add_argument(
        "--carry",
        type=Path,
        default=None,
        help="a previous store whose tasks the build did not solve are carried (a stopped "
        "regeneration; refused if a task both hold differs)",
    )
    pack.add_argument(
        "--compare",
        type=Path,
        default=None,
        help="a previous store the build's tasks are compared with (recorded in the manifest)",
    )
    pack.add_argument(
        "--from-empty", action="store_true", help="the build started from an empty FE cache"
    )
    pack.set_defaults(func=_pack)
    check = sub.add_parser("check", help="a seeded sample of the store recomputed cold")
    check.add_argument("--store", type=Path, required=True)
    check.add_argument("--nonlinear", type=int, default=COLD_NONLINEAR)
    check.add_argument("--linear", type=int, default=COLD_LINEAR)
    check.add_argument("--state", type=int, default=COLD_STATE, help="snapshot fields")
    check.add_argument("--seed", type=int, default=None, help="default: from the commit")
    check.add_argument("--workers", type=int, default=2, help="processes recomputing it")
    check.set_defaults(func=_check)
    snaps = sub.add_parser("add-snapshots", help="the ROM's snapshot fields into the store")
    snaps.add_argument("--store", type=Path, default=STORE_DIR)
    snaps.add_argument("--records", type=Path, default=DEFAULT_BUILD / "records")
    snaps.add_argument("--cache", type=Path, default=DEFAULT_BUILD / "cache" / "experiments")
    snaps.add_argument("--workers", type=int, default=1, help="processes solving the fields")
    snaps.set_defaults(func=_add_snapshots)
    return top


def main(argv: list[str]) -> int:
    """Run one ``store`` command; its exit code (2: the store was refused, with one line)."""
    args = parser().parse_args(argv)
    try:
        return args.func(args)
    except store.StoreError as err:
        print(f"store: {err}", file=sys.stderr)
        return 2
