"""Cached FE results recomputed cold: evidence that what a build reads from the FE cache is what
a fresh process computes, bit for bit.

The determinism re-run (:mod:`mechlib.pipeline.rerun`) starts from the first run's FE cache and
logs every hit (``$MECHLIB_FE_LOG``, written by
:func:`mechlib.campaign.experiments.run_experiments`);
:func:`check_sample` then recomputes a seeded sample of the logged tasks in this process and
compares each with its cached file (agreement within ``AGREE_RTOL``). The records check every
seeded stream and every computation downstream of the FE solves; the sample checks the solves.
:func:`check_entries` recomputes a sample of a results store's tasks alike, the displacement
fields of its ``STATE`` tasks (:mod:`mechlib.hexflex.rom.snapshots`) among them.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mechlib.campaign.executors import worker_pool
from mechlib.campaign.experiments import POSE_COLUMNS, TASK_KINDS, release_models, task_poses
from mechlib.campaign.spec import Spec
from mechlib.campaign.spec import family_of as family
from mechlib.campaign.spec import spec_from_key as spec_from_key  # re-exported
from mechlib.params import check_int

#: seed of the sample of logged tasks that :func:`check_sample` recomputes
SAMPLE_SEED = 2010
#: a recomputed task agrees with its cached result when every pose component differs by at most
#: this share of the task's largest |pose component|: far below the non-linear solver's relative
#: residual tolerance, seven times the largest difference measured between processors, and below
#: the records' tightest relative tolerances on FE results (1e-6). Bit-identity is not required:
#: a solve's last digits differ between the process that first ran it and a fresh one (measured
#: on the identified model: about 1e-13 of the largest component), and more between processors
#: whose BLAS runs other kernels (measured with OpenBLAS's Sandybridge kernels against the
#: Haswell ones that stored them, 32 sampled tasks: non-linear runs up to 1e-8 µm absolute,
#: linear blocks of the thin members up to 1.4e-8 of their largest component). A ``STATE`` task's
#: displacement field is held to the same share of its largest |component|.
AGREE_RTOL = 1e-7
#: non-linear and linear tasks of the store that ``make test`` recomputes cold
COLD_NONLINEAR, COLD_LINEAR = 14, 2
#: snapshot (``STATE``) tasks of the store that ``make test`` recomputes cold: one full field
COLD_STATE = 1


@dataclass(frozen=True)
class CacheCheck:
    """One cached task recomputed: its cache file, kind, rows, whether the fresh result is
    bit-identical, whether it agrees within ``AGREE_RTOL``, and ``max_abs_diff`` [µm, µrad;
    mm for a ``STATE`` task's field], the largest difference (0 when identical)."""

    file: str
    kind: str
    rows: int
    identical: bool
    agrees: bool
    max_abs_diff: float
    #: the row of the cached and of the recomputed poses where they differ most (of a field: the
    #: component that differs most)
    stored: tuple[float, ...] = ()
    fresh: tuple[float, ...] = ()


def read_log(path: Path) -> list[dict]:
    """The distinct tasks of a hit log (one JSON object per line), in order of first hit.

    Returns
    -------
    list of dict
        Keys ``file`` (cache file name), ``spec`` (a specification's ``key()`` text),
        ``kind``, ``steps`` and ``forces`` (rows of loads).
    """
    seen: dict[str, dict] = {}
    for line in Path(path).read_text().splitlines():
        if line.strip():
            entry = json.loads(line)
            if entry.get("hit", True):  # a task computed by this run is no cached result
                seen.setdefault(entry["file"], entry)
    return list(seen.values())


def _one_per_family(specs: list[str], order: np.ndarray) -> list[int]:
    """``order`` (indices into ``specs``) with the first model of each mechanism family moved
    to the front, so that a sample smaller than the number of models still draws from every
    family logged (the HexFlex, a compliant layout …)."""
    first: dict[str, int] = {}
    for g in order.tolist():
        first.setdefault(family(specs[g]) if specs[g] else "", g)  # "": a log without specs
    lead = sorted(first.values(), key=order.tolist().index)
    return lead + [g for g in order.tolist() if g not in lead]


def sample(entries: list[dict], per_kind: dict[str, int], seed: int = SAMPLE_SEED) -> list[dict]:
    """A seeded sample of logged tasks: ``per_kind[kind]`` of each kind (all if fewer), in log
    order, spread over models: one task of every model (``spec``) first — of as many models,
    drawn at random, when there are more models than draws, one of each mechanism family
    (the HexFlex, a compliant layout) among them —, the rest drawn from all others.

    Returns
    -------
    list of dict
        The sampled entries of :func:`read_log`.
    """
    rng = np.random.default_rng(seed)
    chosen: list[int] = []
    for kind in TASK_KINDS:
        n = check_int(f"per_kind[{kind!r}]", per_kind.get(kind, 0), low=0, high=10_000)
        # by file name: the same tasks give the same sample whatever order the log has them in
        # (two chapters at a time append to it concurrently)
        idx = sorted((i for i, e in enumerate(entries) if e["kind"] == kind),
                     key=lambda i: entries[i]["file"])  # fmt: skip
        if not (n and idx):
            continue
        groups: dict[str, list[int]] = {}
        for i in idx:
            groups.setdefault(entries[i].get("spec", ""), []).append(i)
        order = _one_per_family(list(groups), rng.permutation(len(groups)))
        order = order[: min(n, len(groups))]
        members = list(groups.values())
        picked = [int(rng.choice(members[g])) for g in sorted(order)]
        taken = set(picked)
        rest = [i for i in idx if i not in taken]
        extra = min(n - len(picked), len(rest))
        chosen.extend(
            picked + (rng.choice(rest, size=extra, replace=False).tolist() if extra else [])
        )
    return [entries[i] for i in sorted(chosen)]


def sample_uniform(entries: list, per_kind: dict[str, int], seed: int) -> list:
    """A seeded sample of at least ``per_kind[kind]`` tasks of each kind (all if fewer), drawn
    uniformly without replacement within each mechanism family (:func:`~.store.family`: the
    HexFlex, the compliant layouts), whatever their model, ``ceil(n N_f / N)`` from a family
    holding ``N_f`` of the kind's ``N`` tasks — so every family is drawn from, and the total
    exceeds ``n`` by less than the number of families. Grouped by kind and family, by key
    within each.

    Were a share ``p`` of the tasks of a kind wrong, the sample would miss every wrong one with
    probability at most ``(1 − p)^n``: within a family the draws miss its share ``p_f`` with
    ``C(N_f − p_f N_f, n_f) / C(N_f, n_f) ≤ (1 − p_f)^(n_f)``, ``n_f ≥ n N_f / N``, and
    ``Σ (N_f / N) log(1 − p_f) ≤ log(1 − p)`` (the logarithm is concave). That bound is the
    results store's stated chance of a miss; :func:`sample` spreads its draws over the models
    instead, so a wrong share inside one large model may be drawn far less often.

    Parameters
    ----------
    entries : list
        Objects with ``key``, ``kind`` and ``spec`` attributes (:class:`~.store.Entry`).
    per_kind : dict
        Tasks to draw per kind (at least).
    seed : int
        Seed of the draw.
    """
    rng = np.random.default_rng(seed)
    chosen: list = []
    for kind in TASK_KINDS:
        n = check_int(f"per_kind[{kind!r}]", per_kind.get(kind, 0), low=0, high=10_000)
        pool = [e for e in entries if e.kind == kind]
        for fam in sorted({family(e.spec) for e in pool}) if n else ():
            tasks = sorted((e for e in pool if family(e.spec) == fam), key=lambda e: e.key)
            share = -(-n * len(tasks) // len(pool))  # ceil(n N_f / N), exactly in integers
            picked = rng.choice(len(tasks), size=min(share, len(tasks)), replace=False)
            chosen.extend(tasks[i] for i in sorted(picked.tolist()))
    return chosen


def check_sample(
    log: Path,
    cache_dir: Path,
    per_kind: dict[str, int],
    seed: int = SAMPLE_SEED,
    workers: int = 1,
    exclude: frozenset[str] = frozenset(),
) -> list[CacheCheck]:
    """Recompute a seeded sample of the tasks logged in ``log`` and compare each with its file
    in ``cache_dir``, the task files named in ``exclude`` left out of the draw (those another
    cold check covers: the results store's entries, which ``make test`` samples on its own).

    Returns
    -------
    list of CacheCheck
        One per sampled task, grouped by model (each model is released before the next).
    """
    picked = sample([e for e in read_log(log) if e["file"] not in exclude], per_kind, seed)
    tasks = [
        (e["file"], e["spec"], e["kind"], np.array(e["forces"]), e["steps"],
         np.load(Path(cache_dir) / e["file"]))
        for e in picked
    ]  # fmt: skip
    return _recompute(tasks, workers)


def check_entries(
    entries: list, per_kind: dict[str, int], seed: int, workers: int = 1
) -> list[CacheCheck]:
    """Recompute a seeded sample of results-store entries
    (:class:`mechlib.campaign.store.Entry`), drawn uniformly over each kind's tasks
    (:func:`sample_uniform`), and compare each with its stored poses.

    Parameters
    ----------
    entries : list of Entry
        The store's tasks.
    per_kind : dict
        Tasks to draw per kind (all of a kind if fewer).
    seed : int
        Seed of the draw (``make test`` takes it from the commit: each commit checks others).
    workers : int
        Processes recomputing the sample, each a share of its models (1: this process).

    Returns
    -------
    list of CacheCheck
        One per sampled task.
    """
    picked = sample_uniform(entries, per_kind, seed)
    return _recompute(
        [(e.file, e.spec, e.kind, e.forces, e.steps, e.results) for e in picked], workers
    )


def _recompute(tasks: list[tuple], workers: int = 1) -> list[CacheCheck]:
    """Each (file, spec text, kind, forces, steps, cached results) task solved now and its poses
    compared (the solve statistics after a non-linear run's poses are not), in the order given;
    with ``workers`` > 1 the models are shared out among that many worker processes
    (:func:`~mechlib.campaign.executors.worker_pool`: the cores shared out among them),
    every task of a model in the same one."""
    workers = check_int("workers", workers, low=1, high=64)
    keys = list(dict.fromkeys(t[1] for t in tasks))
    specs = {k: spec_from_key(k) for k in keys}  # here: a worker's registry may be empty
    if workers == 1 or len(keys) < 2:
        by_file = {c.file: c for c in _recompute_models(tasks, specs)}
        return [by_file[t[0]] for t in tasks]
    # the models dealt out largest first (by task count) to the least loaded process
    bins: list[list[str]] = [[] for _ in range(min(workers, len(keys)))]
    load = [0] * len(bins)
    for key in sorted(keys, key=lambda k: -sum(t[1] == k for t in tasks)):
        i = load.index(min(load))
        bins[i].append(key)
        load[i] += sum(t[1] == key for t in tasks)
    with worker_pool(len(bins)) as pool:
        parts = pool.map(
            _recompute_models,
            [[t for t in tasks if t[1] in b] for b in bins],
            [{k: specs[k] for k in b} for b in bins],
        )
        by_file = {c.file: c for part in parts for c in part}
    return [by_file[t[0]] for t in tasks]


def _recompute_models(tasks: list[tuple], specs: dict[str, Spec]) -> list[CacheCheck]:
    out: list[CacheCheck] = []
    for key in dict.fromkeys(t[1] for t in tasks):  # one model at a time (memory)
        spec = specs[key]
        for file, _, kind, forces, steps, cached in (t for t in tasks if t[1] == key):
            fresh = task_poses(spec, kind, forces, steps)
            if fresh.shape != cached.shape:
                out.append(CacheCheck(file, kind, len(forces), False, False, np.inf))
                continue
            # the poses are compared; the solve statistics after them may differ with round-off
            # (a correction more or less) while the converged poses agree. A field: all of it
            cols = slice(0, POSE_COLUMNS.get(kind))
            fresh, cached = fresh[:, cols], cached[:, cols]
            same = np.array_equal(fresh, cached)
            diff = np.abs(fresh - cached)
            worst = np.unravel_index(int(np.argmax(diff)), diff.shape)
            agrees = float(diff.max()) <= AGREE_RTOL * float(np.abs(cached).max())
            shown = slice(0, 6) if kind in POSE_COLUMNS else slice(worst[1], worst[1] + 1)
            rows = (tuple(cached[worst[0], shown].tolist()), tuple(fresh[worst[0], shown].tolist()))
            out.append(CacheCheck(file, kind, len(forces), same, agrees, float(diff.max()), *rows))
        release_models()
    return out
