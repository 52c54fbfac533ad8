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
    head = clean_commit()
    if args.reads_store and (args.store / store.MANIFEST).exists():
        carried = store.read_manifest(args.store).get("carried")
        if carried:
            raise store.StoreError(
                f"{args.store} carries {carried['entries']} tasks it did not solve; a build that "
                "reads it would pack them again as solved: finish the regeneration with "
                "make store NO_STORE_SEED=1 where its FE cache is, or make store FROM_EMPTY=1"
            )
    print(f"store: work tree clean at commit {head}")
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
    if args.compare is not None and args.carry is not None:
        raise store.StoreError(
            "store pack: --compare and --carry together would count the carried tasks as "
            "missing; --carry's record already compares the tasks both stores hold"
        )
    if args.compare is not None:
        from mechlib.campaign.compare import compare

        provenance["compared"] = c = compare(entries, args.compare)
        print(
            f"store: {c['both']} of {len(entries)} FE tasks also in {args.compare}, "
            f"{c['identical']} of them bit for bit; largest difference by kind "
            f"{c['largest_difference']}; {c['only_previous']} of its tasks not in this store"
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
    clean.add_argument("--store", type=Path, default=STORE_DIR)
    clean.add_argument(
        "--reads-store",
        action="store_true",
        help="the build will seed its FE cache from the store (refused for a carried store)",
    )
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
    from mechlib.campaign.cachecheck import COLD_LINEAR, COLD_NONLINEAR, COLD_STATE

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
