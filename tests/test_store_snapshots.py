"""The reduced-order model's snapshots as a task kind of the FE store: keyed like the runs,
logged, packed into ``snapshots.npz``, seeded back, refused when corrupt, sampled cold."""

from __future__ import annotations

import json

import numpy as np
import pytest
from test_hexflex import SMALL  # tests/ is on sys.path (pytest prepend import mode)

from mechlib import fespecs as fespecs  # the FE families a store holds, registered
from mechlib.campaign import cachecheck as cc
from mechlib.campaign import experiments as ex
from mechlib.campaign import store as st
from mechlib.campaign.taskcache import STATE, model_code_fingerprint, task_key
from mechlib.hexflex.rom import snapshots
from mechlib.hexflex.spec import ModelSpec
from mechlib.paths import FE_LOG_ENV

SPEC = ModelSpec(SMALL, element="q2", mesh_size=1.0)
FORCES = np.array([[0.5, -0.3, 0.2, 0.4, -0.1, 0.3], [-0.2, 0.1, 0.4, -0.3, 0.2, 0.1]])


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """A build's FE cache and task log: two snapshot fields and a non-linear run, computed."""
    tmp = tmp_path_factory.mktemp("build")
    cache, log = tmp / "cache", tmp / "tasks.jsonl"
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv(FE_LOG_ENV, str(log))
        fields = snapshots.nonlinear_states(SPEC, FORCES, cache_dir=cache)
        ex.run_experiments(SPEC, FORCES[:1], kind="nonlinear", cache_dir=cache, progress=False)
    return cache, log, fields


def test_a_snapshot_is_keyed_as_a_task_of_its_own_kind() -> None:
    key = snapshots.state_key(SPEC, FORCES[0])
    fingerprint = model_code_fingerprint(SPEC.TASK_MODULES)
    assert key == task_key(SPEC.key(), STATE, FORCES[:1], 1, fingerprint)
    assert key != task_key(SPEC.key(), "nonlinear", FORCES[:1], 1, fingerprint)
    assert key != snapshots.state_key(SPEC, FORCES[1])
    assert st.Entry(key, SPEC.key(), STATE, 1, FORCES[:1], np.zeros((1, 3))).file == (
        f"{key}.state.npy"
    )


def test_each_snapshot_is_logged_and_read_back_from_the_cache(built, monkeypatch) -> None:
    cache, log, fields = built
    lines = [json.loads(x) for x in log.read_text().splitlines()]
    states = [x for x in lines if x["kind"] == STATE]
    assert [(x["hit"], x["steps"]) for x in states] == [(False, 1), (False, 1)]
    assert [x["file"] for x in states] == [
        f"{snapshots.state_key(SPEC, f)}.state.npy" for f in FORCES
    ]
    monkeypatch.setenv(FE_LOG_ENV, str(log.with_name("again.jsonl")))
    monkeypatch.setattr(snapshots, "same_code_task", lambda *a: pytest.fail("solved, not read"))
    np.testing.assert_array_equal(snapshots.nonlinear_states(SPEC, FORCES, cache_dir=cache), fields)
    again = [json.loads(x) for x in log.with_name("again.jsonl").read_text().splitlines()]
    assert [x["hit"] for x in again] == [True, True]


def test_snapshots_are_packed_apart_and_seeded_bit_for_bit(built, tmp_path, monkeypatch) -> None:
    cache, log, fields = built
    entries = st.entries_from_cache(log, cache)
    assert [e.kind for e in entries] == [STATE, STATE, "nonlinear"]
    folder = st.write_store(entries, tmp_path / "store")
    manifest, back = st.read_store(folder)
    assert manifest["entries"] == {"linear": 0, "nonlinear": 1, "size": 0, "state": 2}
    assert (folder / st.SNAPSHOTS).is_file() and st.SNAPSHOTS_SHA in manifest
    by_key = {e.key: e for e in back}
    for e, u in zip(entries[:2], fields, strict=True):
        np.testing.assert_array_equal(by_key[e.key].results, u[None])  # bit for bit
        np.testing.assert_array_equal(by_key[e.key].forces, e.forces)
    fresh = tmp_path / "fresh-cache"
    assert st.seed_cache(folder, fresh) == 3
    monkeypatch.setattr(snapshots, "same_code_task", lambda *a: pytest.fail("solved, not read"))
    np.testing.assert_array_equal(snapshots.nonlinear_states(SPEC, FORCES, cache_dir=fresh), fields)


def test_snapshots_are_added_to_a_store_its_runs_kept_byte_for_byte(built, tmp_path) -> None:
    cache, log, _ = built
    entries = st.entries_from_cache(log, cache)
    folder = st.write_store(entries[2:], tmp_path / "store", {"commit": "abc"})
    runs = (folder / st.RESULTS).read_bytes()
    assert not (folder / st.SNAPSHOTS).exists()
    manifest = st.add_states(folder, entries[:1], {"commit": "def", "seconds": 1.0})
    manifest = st.add_states(folder, entries[:2], {"commit": "ghi", "seconds": 2.0})  # replaces
    assert (folder / st.RESULTS).read_bytes() == runs
    assert manifest["entries"]["state"] == 2 and manifest["runs"]["state"] == 2
    assert (manifest["commit"], manifest["snapshots"]["commit"]) == ("abc", "ghi")
    assert st.read_store(folder)[0] == manifest
    with pytest.raises(ValueError, match="states must be 'state' tasks"):
        st.add_states(folder, entries[2:], {})


def test_a_corrupt_edited_or_unlisted_snapshot_file_is_refused(built, tmp_path) -> None:
    cache, log, _ = built
    entries = st.entries_from_cache(log, cache)
    folder = st.write_store(entries, tmp_path / "store")
    raw = bytearray((folder / st.SNAPSHOTS).read_bytes())
    raw[len(raw) // 2] ^= 0xFF
    (folder / st.SNAPSHOTS).write_bytes(bytes(raw))
    with pytest.raises(st.StoreError, match=r"snapshots\.npz does not match the checksum"):
        st.seed_cache(folder, tmp_path / "c1")
    # an edited force: the snapshot's key is no longer its inputs' digest
    bad = [st.Entry(e.key, e.spec, e.kind, e.steps, e.forces * 1.01, e.results) for e in entries]
    bad[2] = entries[2]  # the run as it was
    with pytest.raises(st.StoreError, match=rf"entry {entries[0].key} does not match its own"):
        st.read_store(st.write_store(bad, tmp_path / "edited"))
    # a snapshot file its manifest does not list, a manifest that counts others
    runs_only = st.write_store(entries[2:], tmp_path / "runs")
    (runs_only / st.SNAPSHOTS).write_bytes((tmp_path / "edited" / st.SNAPSHOTS).read_bytes())
    with pytest.raises(st.StoreError, match=r"snapshots\.npz is not listed in its manifest"):
        st.read_store(runs_only)
    (runs_only / st.SNAPSHOTS).unlink()
    m = json.loads((runs_only / st.MANIFEST).read_text())
    m["entries"]["state"] = 2
    (runs_only / st.MANIFEST).write_text(json.dumps(m))
    with pytest.raises(st.StoreError, match="its manifest counts"):
        st.read_store(runs_only)
    # other FE code: refused before anything is added
    foreign = st.write_store(entries[2:], tmp_path / "foreign")
    m = json.loads((foreign / st.MANIFEST).read_text())
    m["fingerprints"]["mechanism"] = "0123456789abcdef"
    (foreign / st.MANIFEST).write_text(json.dumps(m))
    with pytest.raises(st.StoreError, match="other FE code"):
        st.add_states(foreign, entries[:1], {})


def test_the_cold_check_recomputes_a_snapshot_field_and_names_an_edit(built) -> None:
    cache, log, _ = built
    entries = st.entries_from_cache(log, cache)
    picked = cc.sample_uniform(entries, {"state": 1}, seed=3)
    assert [e.kind for e in picked] == [STATE]
    (check,) = cc.check_entries(entries, {"state": 1}, seed=3)
    assert check.kind == STATE and check.agrees and check.file.endswith(".state.npy")
    off = [
        st.Entry(e.key, e.spec, e.kind, e.steps, e.forces, e.results * (1 + 10 * cc.AGREE_RTOL))
        for e in entries
    ]
    (check,) = cc.check_entries(off, {"state": 1}, seed=3)
    assert not check.agrees and len(check.stored) == 1 and check.stored != check.fresh
    assert check.max_abs_diff > cc.AGREE_RTOL * np.abs(entries[0].results).max()


def test_add_snapshots_solves_the_meta_model_page_s_snapshot_runs_on_its_model() -> None:
    from mechlib.paths import REPO_ROOT
    from mechlib.pipeline import storesnapshots

    source = (REPO_ROOT / "notebooks" / f"{storesnapshots.CHAPTER}.ipynb").read_text()
    for line in (  # the page's design, its default model, its snapshot call
        "design_runs = np.vstack([pub.TABLE2_DESIGN, pub.TABLE4_DESIGN])",
        'nonlinear_mesh = \\"lean\\"',
        "spec = ModelSpec(g, mesh_size=mesh_fraction * g.narrowest)",
        "spec = leanmesh.lean_spec(spec, cache_dir=cache)[0]",
        "snapshots.nonlinear_states(spec, design_runs,",
    ):
        assert line in source, line
    runs = storesnapshots.snapshot_runs()
    assert runs.shape == (42, 6) and len(np.unique(runs, axis=0)) == 42


def test_a_worker_with_other_fe_code_refuses_a_snapshot(tmp_path, monkeypatch) -> None:
    """Snapshot fields are submitted like the runs: a worker whose FE code is not the code of
    the key refuses the task, and nothing is cached under that key."""
    monkeypatch.setattr(snapshots, "model_code_fingerprint", lambda modules: "0" * 16)
    monkeypatch.setattr(ex, "_task", lambda *a: pytest.fail("solved by other code"))
    with pytest.raises(ex.CodeMismatchError, match=r"\(0{16}\)"):
        snapshots.nonlinear_states(SPEC, FORCES[:1], cache_dir=tmp_path / "c")
    assert not list((tmp_path / "c").glob("*.npy"))
