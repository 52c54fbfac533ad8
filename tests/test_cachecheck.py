"""Cached FE results recomputed cold (the determinism check's sample of the FE cache)."""

from __future__ import annotations

import numpy as np
import pytest
from test_hexflex import SMALL  # tests/ is on sys.path (pytest prepend import mode)

from mechlib import fespecs as fespecs  # the FE families a store holds, registered
from mechlib.campaign import cachecheck as cc
from mechlib.campaign import experiments as ex
from mechlib.hexflex.spec import ModelSpec
from mechlib.paths import FE_LOG_ENV

SPEC = ModelSpec(SMALL, element="q2", mesh_size=1.0)


def _log_two_builds(tmp_path, monkeypatch, forces: np.ndarray):
    cache, log = tmp_path / "cache", tmp_path / "hits.jsonl"
    ex.run_experiments(SPEC, forces, kind="nonlinear", cache_dir=cache, progress=False)
    assert not log.exists()  # no log unless asked for
    monkeypatch.setenv(FE_LOG_ENV, str(log))
    ex.run_experiments(SPEC, forces, kind="nonlinear", cache_dir=cache, progress=False)
    ex.run_experiments(SPEC, forces[:1], kind="linear", cache_dir=cache, progress=False)  # miss
    ex.run_experiments(SPEC, forces[:1], kind="linear", cache_dir=cache, progress=False)  # hit
    return cache, log


def test_hits_are_logged_and_a_sample_recomputes_bit_identically(tmp_path, monkeypatch) -> None:
    forces = np.array([[0.5, -0.3, 0.2, 0.4, -0.1, 0.3], [-0.2, 0.1, 0.4, -0.3, 0.2, 0.1]])
    cache, log = _log_two_builds(tmp_path, monkeypatch, forces)
    entries = cc.read_log(log)
    assert [e["kind"] for e in entries] == ["nonlinear", "nonlinear", "linear"]
    assert cc.spec_from_key(entries[0]["spec"]) == SPEC
    checks = cc.check_sample(log, cache, {"nonlinear": 1, "linear": 5})
    assert [c.kind for c in checks].count("nonlinear") == 1
    assert [c.kind for c in checks].count("linear") == 1  # all there are
    assert all(c.identical and c.agrees and c.max_abs_diff == 0.0 for c in checks)
    # tasks another cold check covers (the results store's) are left out of the draw
    linear = [e["file"] for e in entries if e["kind"] == "linear"]
    checks = cc.check_sample(log, cache, {"nonlinear": 1, "linear": 5}, exclude=frozenset(linear))
    assert [c.kind for c in checks] == ["nonlinear"]


def test_a_tampered_cache_file_is_found(tmp_path, monkeypatch) -> None:
    forces = np.array([[0.5, -0.3, 0.2, 0.4, -0.1, 0.3]])
    cache, log = _log_two_builds(tmp_path, monkeypatch, forces)
    (entry,) = [e for e in cc.read_log(log) if e["kind"] == "nonlinear"]
    stored = np.load(cache / entry["file"])
    np.save(cache / entry["file"], stored * (1 + 1e-12))  # round-off: agrees, not identical
    (check,) = cc.check_sample(log, cache, {"nonlinear": 1})
    assert not check.identical and check.agrees and 0 < check.max_abs_diff < 1e-6
    np.save(cache / entry["file"], stored * (1 + 10 * cc.AGREE_RTOL))  # beyond the tolerance
    (check,) = cc.check_sample(log, cache, {"nonlinear": 1})
    assert not check.identical and not check.agrees


def test_the_sample_is_seeded_and_refuses_bad_counts() -> None:
    entries = [{"file": f"{i}.npy", "kind": "nonlinear"} for i in range(20)]
    a = cc.sample(entries, {"nonlinear": 4})
    assert a == cc.sample(entries, {"nonlinear": 4}) and len(a) == 4
    assert a != cc.sample(entries, {"nonlinear": 4}, seed=1)
    with pytest.raises(ValueError, match="per_kind"):
        cc.sample(entries, {"nonlinear": -1})


def test_the_sample_takes_a_task_of_every_model_first() -> None:
    # a model with one task among thousands of another's is still checked (key texts: JSON)
    rare, common, other = (f'{{"model": "{m}"}}' for m in ("rare", "common", "other"))
    specs = [rare] + [common] * 300 + [other] * 50
    entries = [{"file": f"{i}.npy", "kind": "nonlinear", "spec": s} for i, s in enumerate(specs)]
    for seed in range(5):
        picked = cc.sample(entries, {"nonlinear": 4}, seed=seed)
        assert len(picked) == 4 and {e["spec"] for e in picked} == {rare, common, other}
        assert len({e["file"] for e in picked}) == 4
        two = cc.sample(entries, {"nonlinear": 2}, seed=seed)
        assert len({e["spec"] for e in two}) == 2  # fewer draws than models: distinct models


def test_a_sample_smaller_than_the_models_draws_from_both_mechanisms() -> None:
    # 40 HexFlex models and one compliant layout: two draws take one of each, whatever the seed
    specs = [f'{{"geometry": {i}}}' for i in range(40)] + ['{"mechanism": {"mesh_size": 10}}']
    entries = [{"file": f"{i}.npy", "kind": "nonlinear", "spec": s} for i, s in enumerate(specs)]
    for seed in range(8):
        picked = cc.sample(entries, {"nonlinear": 2}, seed=seed)
        assert sorted(e["spec"].startswith('{"mechanism"') for e in picked) == [False, True]


def test_the_stores_sample_is_uniform_over_its_tasks_whatever_their_model() -> None:
    from types import SimpleNamespace

    # one model holds 90 % of the tasks: it gets about 90 % of the draws (spread over models,
    # it would get a third), so a wrong share anywhere is missed with at most (1 - p)^n
    big, small, tiny = (f'{{"model": "{m}"}}' for m in ("big", "small", "tiny"))
    specs = [big] * 900 + [small] * 50 + [tiny] * 50
    entries = [
        SimpleNamespace(key=f"{i:04d}", kind="nonlinear", spec=s) for i, s in enumerate(specs)
    ]
    draws = [cc.sample_uniform(entries, {"nonlinear": 10}, seed) for seed in range(200)]
    assert all(len({e.key for e in d}) == 10 for d in draws)
    share = np.mean([e.spec == big for d in draws for e in d])
    assert 0.87 < share < 0.93  # 2000 draws: standard error 0.0067
    # seeded, whatever order the entries come in; all of a kind when fewer than asked
    assert draws[3] == cc.sample_uniform(entries[::-1], {"nonlinear": 10}, 3)
    assert len(cc.sample_uniform(entries, {"nonlinear": 5000, "linear": 2}, 0)) == 1000
    with pytest.raises(ValueError, match="per_kind"):
        cc.sample_uniform(entries, {"nonlinear": -1}, 0)
    # two mechanisms: each drawn from in proportion, rounded up (95 of 1000 tasks: 1 of 10)
    layout = '{"mechanism": {"mesh_size": 10}}'
    both = entries[:905] + [SimpleNamespace(key=f"m{i:03d}", kind="nonlinear", spec=layout)
                            for i in range(95)]  # fmt: skip
    for seed in range(20):
        got = cc.sample_uniform(both, {"nonlinear": 10}, seed)
        assert sum(e.spec == layout for e in got) == 1 and len(got) == 11  # ceil 9.05 + ceil 0.95


def test_two_processes_recompute_the_same_checks_in_the_same_order(tmp_path) -> None:
    from mechlib.campaign.store import Entry

    specs = [ModelSpec(SMALL, mesh_size=f * SMALL.narrowest) for f in (0.9, 1.0)]
    forces = np.array([[0.3, -0.2, 0.1, 0.0, 0.2, -0.1]])
    entries = [
        Entry(
            f"k{i}",
            s.key(),
            "linear",
            1,
            forces * (i + 1),
            ex.task_poses(s, "linear", forces * (i + 1), 1),
        )
        for i, s in enumerate(specs + specs)
    ]
    entries[3] = Entry("k3", specs[1].key(), "linear", 1, forces * 4, entries[3].results * 1.01)
    one = cc.check_entries(entries, {"linear": 4}, seed=0)
    two = cc.check_entries(entries, {"linear": 4}, seed=0, workers=2)
    assert (
        [c.file for c in one] == [c.file for c in two] == ["k0.npy", "k1.npy", "k2.npy", "k3.npy"]
    )
    assert [c.agrees for c in two] == [True, True, True, False]


def test_the_determinism_sample_leaves_the_stores_entries_to_the_store_check(
    tmp_path, monkeypatch, capsys
) -> None:
    from mechlib.campaign import store
    from mechlib.pipeline.coldsample import cold_sample
    from mechlib.pipeline.rerun import HIT_LOG

    forces = np.array([[0.5, -0.3, 0.2, 0.4, -0.1, 0.3]])
    cache, log = _log_two_builds(tmp_path, monkeypatch, forces)
    rerun = tmp_path / "rerun"
    rerun.mkdir()
    (rerun / HIT_LOG).write_text(log.read_text())
    (rerun / "fe-cache").symlink_to(cache)
    folder = store.write_store(store.entries_from_cache(log, cache), tmp_path / "store")
    assert cold_sample(rerun, 1, folder) is False  # nothing of its own to recompute
    assert "results store's entries" in capsys.readouterr().out
    assert cold_sample(rerun, 1) is False  # without the store: recomputed, bit-identical
    assert "bit-identical" in capsys.readouterr().out
    # a cache file that is not the store's entry under its key is found, not left out
    (entry,) = [e for e in cc.read_log(log) if e["kind"] == "nonlinear"]
    np.save(cache / entry["file"], np.load(cache / entry["file"]) * (1 + 1e-12))
    assert cold_sample(rerun, 1, folder) is True
    assert "DIFFERS from the results store's entry" in capsys.readouterr().out
    # a re-run that read no non-linear task has nothing to show: it fails
    (rerun / HIT_LOG).write_text("")
    assert cold_sample(rerun, 1, folder) is True
    assert "read no non-linear FE task" in capsys.readouterr().out
