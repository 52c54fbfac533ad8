"""The FE results store: packed from a build's task log, verified, seeded into a cache, refused
by name when stale, edited or corrupt, and sampled cold."""

from __future__ import annotations

import json

import numpy as np
import pytest
from test_hexflex import SMALL  # tests/ is on sys.path (pytest prepend import mode)

from mechlib import fespecs as fespecs  # the FE families a store holds, registered
from mechlib.campaign import cachecheck as cc
from mechlib.campaign import experiments as ex
from mechlib.campaign import store as st
from mechlib.hexflex.spec import ModelSpec
from mechlib.paths import FE_LOG_ENV

SPEC = ModelSpec(SMALL, element="q2", mesh_size=1.0)
FORCES = np.array([[0.5, -0.3, 0.2, 0.4, -0.1, 0.3], [-0.2, 0.1, 0.4, -0.3, 0.2, 0.1]])


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """A build's FE cache and task log: two non-linear runs and a linear block, all computed."""
    tmp = tmp_path_factory.mktemp("build")
    cache, log = tmp / "cache", tmp / "tasks.jsonl"
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv(FE_LOG_ENV, str(log))
        ex.run_experiments(SPEC, FORCES, kind="nonlinear", cache_dir=cache, progress=False)
        ex.run_experiments(SPEC, FORCES, kind="linear", cache_dir=cache, progress=False)
    return cache, log


def test_every_task_a_build_runs_is_logged_and_packed(built, tmp_path) -> None:
    cache, log = built
    lines = [json.loads(x) for x in log.read_text().splitlines()]
    assert [x["hit"] for x in lines] == [False, False, False]  # computed, not read
    assert cc.read_log(log) == []  # the determinism sample reads hits only
    entries = st.entries_from_cache(log, cache)
    assert [e.kind for e in entries] == ["nonlinear", "nonlinear", "linear"]
    folder = st.write_store(entries, tmp_path / "store", {"commit": "abc"})
    manifest, back = st.read_store(folder)
    assert manifest["entries"] == {"linear": 1, "nonlinear": 2, "size": 0, "state": 0}
    assert manifest["runs"] == {"linear": 2, "nonlinear": 2, "size": 0, "state": 0}
    assert manifest["commit"] == "abc"
    for a, b in zip(entries, back, strict=True):
        assert (a.key, a.spec, a.kind, a.steps) == (b.key, b.spec, b.kind, b.steps)
        np.testing.assert_array_equal(a.forces, b.forces)
        np.testing.assert_array_equal(a.results, b.results)  # bit for bit through the file
    assert (folder / st.RESULTS).stat().st_size < 10_000


def test_a_seeded_cache_serves_the_build_without_a_solve(built, tmp_path, monkeypatch) -> None:
    cache, log = built
    folder = st.write_store(st.entries_from_cache(log, cache), tmp_path / "store")
    fresh = tmp_path / "fresh-cache"
    assert st.seed_cache(folder, fresh) == 3
    monkeypatch.setattr(ex, "_task", lambda *a: pytest.fail("solved instead of read"))
    got = ex.run_experiments(SPEC, FORCES, kind="nonlinear", cache_dir=fresh, progress=False)
    want = ex.run_experiments(SPEC, FORCES, kind="nonlinear", cache_dir=cache, progress=False)
    np.testing.assert_array_equal(got, want)


def test_a_stale_edited_or_corrupt_store_is_refused_in_one_line(built, tmp_path, monkeypatch):
    cache, log = built
    entries = st.entries_from_cache(log, cache)
    folder = st.write_store(entries, tmp_path / "store")
    # other FE code: the fingerprint differs
    monkeypatch.setattr(st, "model_code_fingerprint", lambda modules: "0123456789abcdef")
    with pytest.raises(st.StoreError, match=r"3 entries .* other FE code .*`make store`"):
        st.seed_cache(folder, tmp_path / "c1")
    monkeypatch.undo()
    # an edited force: the entry's key is no longer its inputs' digest
    bad = [st.Entry(e.key, e.spec, e.kind, e.steps, e.forces * 1.01, e.results) for e in entries]
    with pytest.raises(st.StoreError, match=rf"entry {entries[0].key} does not match its own"):
        st.read_store(st.write_store(bad, tmp_path / "edited"))
    # a changed byte of results.npz: the checksum
    raw = bytearray((folder / st.RESULTS).read_bytes())
    raw[-30] ^= 0xFF
    (folder / st.RESULTS).write_bytes(bytes(raw))
    with pytest.raises(st.StoreError, match="does not match the checksum"):
        st.read_store(folder)
    # a malformed manifest, an unknown version, no store
    m = json.loads((folder / st.MANIFEST).read_text())
    (folder / st.MANIFEST).write_text(json.dumps({**m, "version": 99}))
    with pytest.raises(
        st.StoreError, match=f"format version 99; this code reads versions {st.STORE_VERSION}"
    ):
        st.read_store(folder)
    (folder / st.MANIFEST).write_text("{not json")
    with pytest.raises(st.StoreError, match="not valid JSON"):
        st.read_manifest(folder)
    (folder / st.MANIFEST).write_text(json.dumps({"version": 1}))
    with pytest.raises(st.StoreError, match="lacks fields"):
        st.read_manifest(folder)
    with pytest.raises(st.StoreError, match="no store manifest"):
        st.read_manifest(tmp_path / "nowhere")


def test_a_failed_write_leaves_the_old_store_whole(built, tmp_path, monkeypatch) -> None:
    cache, log = built
    entries = st.entries_from_cache(log, cache)
    folder = st.write_store(entries, tmp_path / "store")
    before = (folder / st.MANIFEST).read_text()

    def full(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(st.np, "savez_compressed", full)
    with pytest.raises(OSError, match="disk full"):
        st.write_store(entries[:1], folder)
    assert (folder / st.MANIFEST).read_text() == before
    assert st.read_store(folder)[0]["entries"]["nonlinear"] == 2


def test_a_sample_of_the_store_is_recomputed_cold_and_an_edit_is_named(built, tmp_path) -> None:
    cache, log = built
    entries = st.entries_from_cache(log, cache)
    checks = cc.check_entries(entries, {"nonlinear": 1, "linear": 1}, seed=7)
    assert sorted(c.kind for c in checks) == ["linear", "nonlinear"]
    assert all(c.agrees for c in checks)
    off = [
        st.Entry(e.key, e.spec, e.kind, e.steps, e.forces, e.results * (1 + 10 * cc.AGREE_RTOL))
        for e in entries
    ]
    (check,) = cc.check_entries(off, {"nonlinear": 1}, seed=7)
    assert not check.agrees and len(check.stored) == 6 and check.stored != check.fresh


@pytest.fixture(scope="module")
def cluster():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as c:
        yield c


def test_a_campaign_on_a_dask_cluster_matches_the_in_process_one(cluster, tmp_path, monkeypatch):
    from mechlib.campaign import executors

    forces = np.vstack([FORCES, -FORCES])
    with executors.dask_executor(cluster.scheduler_address) as pool:
        got = ex.run_experiments(SPEC, forces, kind="nonlinear", executor=pool,
                                 cache_dir=tmp_path / "cache", progress=False)  # fmt: skip
    want = ex.run_experiments(SPEC, forces, kind="nonlinear", progress=False)
    np.testing.assert_allclose(got, want, rtol=0, atol=cc.AGREE_RTOL * np.abs(want).max())
    assert len(list((tmp_path / "cache").glob("*.npy"))) == 4
    # $MECHLIB_DASK_SCHEDULER sends a notebook's campaign there, whatever its workers
    monkeypatch.setenv(executors.DASK_ENV, cluster.scheduler_address)
    with executors.executor(1) as pool:
        assert type(pool).__name__ == "_DaskExecutor"


def test_a_scheduler_that_does_not_answer_is_named() -> None:
    from mechlib.campaign import executors

    with pytest.raises(RuntimeError, match=r"no Dask scheduler answers at tcp://127\.0\.0\.1:9"):
        executors.dask_executor("tcp://127.0.0.1:9", timeout=2.0)


def test_the_store_command_packs_seeds_checks_and_refuses_in_one_line(
    built, tmp_path, capsys, monkeypatch
):
    from mechlib.pipeline import storecmd

    cache, log = built
    folder = tmp_path / "store"
    assert storecmd.main(["seed", "--store", str(folder), "--cache", str(tmp_path / "c")]) == 0
    assert "no " in capsys.readouterr().out  # no store yet: every task is computed
    args = ["--log", str(log), "--cache", str(cache), "--store", str(folder), "--seconds", "12"]
    # a store records the commit that computed it: a tree with uncommitted changes is refused
    monkeypatch.setattr(storecmd, "commit", lambda: "0123456789ab + local changes")
    assert storecmd.main(["pack", *args]) == 2 and not folder.exists()
    assert "uncommitted changes" in capsys.readouterr().err
    monkeypatch.setattr(storecmd, "commit", lambda: "0123456789ab")
    assert storecmd.main(["pack", *args, "--commit", "fedcba987654"]) == 2
    assert "not fedcba987654" in capsys.readouterr().err
    assert storecmd.main(["pack", *args, "--commit", "0123456789ab"]) == 0
    manifest = st.read_manifest(folder)
    assert manifest["seconds"] == 12 and manifest["processor"]
    assert manifest["commit"] == "0123456789ab"
    assert manifest["from_empty"] is False  # no --from-empty: the seconds resumed a cache
    assert storecmd.main(["seed", "--store", str(folder), "--cache", str(tmp_path / "c")]) == 0
    assert "3 FE tasks" in capsys.readouterr().out
    check = ["check", "--store", str(folder), "--nonlinear", "1", "--linear", "1", "--seed", "3"]
    assert storecmd.main(check) == 0
    assert "2 of 2 sampled tasks" in capsys.readouterr().out
    (folder / st.MANIFEST).write_text("[]")
    assert storecmd.main(["seed", "--store", str(folder), "--cache", str(tmp_path / "c")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "lacks fields" in err


def test_the_landing_page_says_where_the_fe_runs_came_from(tmp_path) -> None:
    from mechlib.pipeline import storeline

    assert "no results store" in storeline.landing_line(tmp_path / "absent")
    entries = [
        st.Entry("k" * 32, "spec", "nonlinear", 1, np.zeros((1, 6)), np.zeros((1, 22))),
        st.Entry("j" * 32, "spec", "linear", 1, np.zeros((3, 6)), np.zeros((3, 6))),
    ]
    folder = st.write_store(entries, tmp_path / "store", {"date": "2026-11-25", "commit": "abc"})
    line = storeline.landing_line(folder)
    assert "1 geometrically non-linear run and 3 linear load cases" in line
    assert "at commit `abc`" in line and "not solved again in this build" in line
    assert "computed 2026-11-25 on" in line
    from mechlib.campaign.cachecheck import COLD_NONLINEAR

    miss = (1 - storeline.WRONG_SHARE) ** COLD_NONLINEAR
    assert (
        f"probability at most {miss:.1%}" in line and f"{miss:.1%}" == "22.9%"
    )  # 14 runs, 10 % wrong: 0.9^14
    with pytest.raises(ValueError, match="wrong_share must be in"):
        storeline.landing_line(folder, wrong_share=1.0)
    manifest = json.loads((folder / st.MANIFEST).read_text())
    (folder / st.MANIFEST).write_text(json.dumps({**manifest, "fingerprint": "0" * 16}))
    assert "computed by other FE code" in storeline.landing_line(folder)


def test_a_store_holds_both_mechanisms_and_seeds_each_by_its_own_code(built, tmp_path) -> None:
    from mechlib.compliant.spec import MechanismSpec
    from mechlib.parallelogram import ourfe
    from mechlib.parallelogram.mechanism import layout

    cache, log = built
    pspec = MechanismSpec(layout(stage_young=5e6), 10.0, 1)
    loads = ourfe.to_newton([[0.0, 1.0, 0.0], [1.0, 0.5, 0.2]])
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv(FE_LOG_ENV, str(log))
        want = ex.run_experiments(pspec, loads, kind="nonlinear", steps=1, cache_dir=cache,
                                  progress=False)  # fmt: skip
    entries = st.entries_from_cache(log, cache)
    assert sorted({st.family(e.spec) for e in entries}) == ["hexflex", "mechanism"]
    folder = st.write_store(entries, tmp_path / "store")
    manifest, back = st.read_store(folder)
    assert manifest["version"] == st.STORE_VERSION and manifest["fingerprints"] == st.fingerprints()
    assert sorted(e.forces.shape[1] for e in back) == [3, 3, 6, 6, 6]
    fresh = tmp_path / "fresh"
    assert st.seed_cache(folder, fresh) == 5
    got = ex.run_experiments(pspec, loads, kind="nonlinear", steps=1, cache_dir=fresh,
                             progress=False)  # fmt: skip
    np.testing.assert_array_equal(got, want)
    # the layout's code changed since: its entries are left out, the HexFlex's still seeded
    now = {**st.fingerprints(), "mechanism": "0" * 16}
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(st, "fingerprints", lambda: now)
        assert st.seed_cache(folder, tmp_path / "fresh2") == 3


def test_a_stopped_regeneration_carries_the_previous_store_s_other_tasks(built, tmp_path) -> None:
    from dataclasses import replace

    from mechlib.campaign.carry import carry

    cache, log = built
    entries = st.entries_from_cache(log, cache)
    old_key = "f" * 32  # keys of another format: the tasks are matched by their inputs
    previous = [replace(e, key=old_key[:-1] + str(i)) for i, e in enumerate(entries)]
    folder = st.write_store(previous, tmp_path / "old", {"commit": "84391a6"})
    # the regeneration solved the first task of each family only
    firsts = {st.family(e.spec): e for e in reversed(entries)}
    first = {id(e) for e in firsts.values()}
    solved = [e for e in entries if id(e) in first]
    rest = [e for e in entries if id(e) not in first]
    carried, record = carry(solved, folder)
    assert record["entries"] == len(rest) >= 1 and record["agreed"] == len(solved)
    assert record["from"]["commit"] == "84391a6"
    assert [c.key for c in carried] == [e.key for e in rest]  # the current keys
    for a, b in zip(carried, rest, strict=True):
        np.testing.assert_array_equal(a.results, b.results)
    moved = replace(entries[0], results=entries[0].results + 1e-12)
    with pytest.raises(st.StoreError, match=f"task {moved.key} .* differs from the previous"):
        carry([moved], folder)
    assert record["agreed_by_family"] == {f: 1 for f in sorted(firsts)}


def test_a_family_none_of_whose_tasks_was_compared_is_not_carried(built, tmp_path, monkeypatch):
    """Agreement is required of each family carried: one family's agreement says nothing of
    another's code."""
    from dataclasses import replace

    from mechlib.campaign.carry import carry

    cache, log = built
    entries = st.entries_from_cache(log, cache)
    other = replace(entries[-1], spec=entries[-1].spec + " ")  # stands for another family's
    folder = st.write_store([*entries[:-1], other], tmp_path / "old", {"commit": "84391a6"})
    family = st.family
    monkeypatch.setattr(st, "family", lambda s: "mechanism" if s.endswith(" ") else family(s))
    with pytest.raises(st.StoreError, match="no task of family mechanism was solved"):
        carry(entries[:1], folder)


def test_a_new_store_is_compared_with_the_previous_one_by_its_tasks_inputs(built, tmp_path):
    from dataclasses import replace

    from mechlib.campaign.compare import compare

    cache, log = built
    entries = st.entries_from_cache(log, cache)
    previous = [replace(e, key="e" * 31 + str(i)) for i, e in enumerate(entries)]
    folder = st.write_store(previous, tmp_path / "old", {"commit": "84391a6"})
    same = compare(entries, folder)
    assert same["tasks"] == same["both"] == same["identical"] == len(entries) >= 2
    assert same["only_previous"] == 0 and same["from"]["commit"] == "84391a6"
    assert set(same["largest_difference"].values()) == {0.0}
    moved = [replace(entries[0], results=entries[0].results + 2.5e-9)]
    record = compare(moved, folder)
    assert (record["tasks"], record["both"], record["identical"]) == (1, 1, 0)
    assert record["only_previous"] == len(entries) - 1
    assert record["largest_difference"][entries[0].kind] == pytest.approx(2.5e-9, rel=1e-3)
    assert record["units"][entries[0].kind] == "µm, µrad"  # poses (mechlib.fe.pose)
    json.dumps(record, allow_nan=False)  # a manifest record: plain JSON
    reshaped = [replace(entries[0], results=entries[0].results[..., :1])]
    with pytest.raises(st.StoreError, match="of shape"):
        compare(reshaped, folder)
    broken = entries[0].results.copy()
    broken.flat[0] = np.nan
    with pytest.raises(st.StoreError, match="not finite"):
        compare([replace(entries[0], results=broken)], folder)
    # the same NaN in both stores is bit for bit, not a difference
    nan_old = st.write_store([replace(entries[0], results=broken)], tmp_path / "nan", {})
    assert compare([replace(entries[0], results=broken)], nan_old)["identical"] == 1


def test_pack_refuses_to_compare_and_carry_at_once(built, tmp_path, monkeypatch, capsys) -> None:
    from mechlib.pipeline import storecmd

    cache, log = built
    monkeypatch.setattr(storecmd, "commit", lambda: "0123456789ab")
    monkeypatch.setattr(storecmd, "_untracked_sources", lambda: [])
    args = ["pack", "--log", str(log), "--cache", str(cache), "--store", str(tmp_path / "s")]
    both = ["--compare", str(tmp_path / "a"), "--carry", str(tmp_path / "b")]
    assert storecmd.main([*args, *both]) == 2 and not (tmp_path / "s").exists()
    assert "--compare and --carry together" in capsys.readouterr().err


def test_the_landing_line_says_how_the_store_compares_with_the_previous_one() -> None:
    from mechlib.pipeline import storeline

    prints = {"hexflex": "ebad646bcc518499"}
    origin = {"commit": "ae68adb33567", "fingerprints": {"hexflex": "9848c5fc81fc5730"}}
    same = {"tasks": 9, "both": 9, "identical": 9, "only_previous": 0, "from": origin,
            "largest_difference": {"linear": 0.0}}  # fmt: skip
    text = storeline._compared_text({"compared": same, "fingerprints": prints, "from_empty": True})
    assert "The store's 9 FE tasks (a task is one model's block" in text
    assert text.endswith(", solved from an empty FE cache, are all bit for bit the results of "
                         "the FE code of commit `ae68adb33567`.")  # fmt: skip
    moved = {**same, "identical": 7, "largest_difference": {"linear": 0.0, "nonlinear": 3e-9},
             "units": {"linear": "µm, µrad", "nonlinear": "µm, µrad"}}  # fmt: skip
    text = storeline._compared_text({"compared": moved, "fingerprints": origin["fingerprints"]})
    assert "snapshot field), 9 are also in the results of this FE code of commit " in text
    assert ": 7 bit for bit; the largest difference" in text
    assert text.endswith("is 3e-09 µm, µrad in its non-linear runs.")  # zeros not listed
    dropped = storeline._compared_text({"compared": {**same, "only_previous": 1}})
    assert dropped.endswith(": 9 bit for bit; 1 task of those results is not here.")
    assert "an unrecorded commit" in storeline._compared_text({"compared": {**same, "from": {}}})
    assert storeline._compared_text({}) == ""


def test_the_landing_line_says_how_many_tasks_were_carried() -> None:
    from mechlib.pipeline import storeline

    carried = {"entries": 3, "agreed": 40, "from": {"commit": "ae68adb33567"}, "why": "stopped"}
    text = storeline._carried_text({"carried": carried})
    assert "3 were not solved again but taken from the results of the FE code of commit " in text
    assert text.endswith("bit for bit these on all 40 tasks both hold.")
    one = storeline._carried_text({"carried": {**carried, "agreed": 1}})
    assert one.endswith("on the 1 task both hold.")
    assert storeline._carried_text({}) == ""


def test_a_build_that_reads_a_carried_store_is_refused(tmp_path, monkeypatch, capsys) -> None:
    from mechlib.pipeline import storecmd

    monkeypatch.setattr(storecmd, "commit", lambda: "0123456789ab")
    monkeypatch.setattr(storecmd, "_untracked_sources", lambda: [])
    folder = st.write_store([], tmp_path / "s", {"carried": {"entries": 3, "agreed": 9}})
    assert storecmd.main(["clean", "--store", str(folder), "--reads-store"]) == 2
    assert "carries 3 tasks it did not solve" in capsys.readouterr().err
    assert storecmd.main(["clean", "--store", str(folder)]) == 0  # NO_STORE_SEED or FROM_EMPTY
    plain = st.write_store([], tmp_path / "p", {})
    assert storecmd.main(["clean", "--store", str(plain), "--reads-store"]) == 0


def test_a_manifest_date_is_written_as_the_book_writes_dates() -> None:
    from mechlib.pipeline import storeline

    assert storeline._when("2026-11-29T07:16:18+01:00") == "2026-11-29 06:16 UTC"
    assert storeline._when("2026-11-25 10:00:00") == "2026-11-25 10:00 UTC"  # naive: UTC
    assert storeline._when("2026-11-25") == "2026-11-25"
    assert storeline._when(None) == "on an unrecorded date"
