"""Experiment runner: executors (in-process, dask), disk cache, failures, bad designs; sweeps."""

import concurrent.futures as cf
from pathlib import Path

import numpy as np
import pytest
from test_hexflex import SMALL  # tests/ is on sys.path (pytest prepend import mode)

from mechlib.campaign import executors
from mechlib.campaign import experiments as ex
from mechlib.campaign.sources import model_modules
from mechlib.campaign.taskcache import SOLVE_MODULE
from mechlib.fe.nonlinear import ConvergenceError
from mechlib.hexflex.spec import ModelSpec

SPEC = ModelSpec(SMALL, element="shell", mesh_size=1.0)


class FailingExecutor(cf.Executor):
    """Runs calls in-process but fails the second one, as a lost worker would."""

    def __init__(self) -> None:
        self.calls = 0

    def submit(self, fn, /, *args, **kwargs):
        self.calls += 1
        fut: cf.Future = cf.Future()
        if self.calls == 2:
            fut.set_exception(OSError("worker lost"))
        else:
            fut.set_result(fn(*args, **kwargs))
        return fut


def _design(n: int) -> np.ndarray:
    return np.random.default_rng(5).uniform(-1, 1, (n, 6))


def test_serial_runner_matches_the_model_and_the_cache_is_reused(tmp_path) -> None:
    d = _design(30)
    got = ex.run_experiments(SPEC, d, cache_dir=tmp_path, progress=False)
    np.testing.assert_array_equal(got, ex.model_for(SPEC).poses(d))
    files = sorted(tmp_path.glob("*.npy"))
    assert len(files) == 1
    # a cached result is read back, not recomputed: tamper with it and see it come back
    np.save(files[0], np.zeros((30, 6)))
    assert not ex.run_experiments(SPEC, d, cache_dir=tmp_path, progress=False).any()
    other = ModelSpec(SMALL, element="shell", mesh_size=1.0, young=70_000.0)
    assert ex.run_experiments(other, d, cache_dir=tmp_path, progress=False).any()


def _modules_a_task_loads(statements: str) -> set[str]:
    """The mechlib modules loaded by a fresh Python process that imports the runner as ``ex``
    and runs ``statements`` (a task: imports inside functions count too)."""
    import subprocess
    import sys

    code = (
        "import sys, numpy as np; from mechlib.campaign import experiments as ex; "
        + statements
        + "print(' '.join(m for m in sys.modules if m.startswith('mechlib.') "
        "and getattr(sys.modules[m], '__file__', None)))"
    )
    root = Path(__file__).resolve().parents[1]
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=root
    )
    return set(out.stdout.split())


def test_every_module_that_defines_a_result_is_in_the_cache_key() -> None:
    import dataclasses

    # every mechlib module that a task's code loads (run one: imports inside functions too)
    loaded_all = _modules_a_task_loads(
        "from mechlib.hexflex.geometry import HexFlexGeometry; "
        "from mechlib.hexflex.spec import ModelSpec; "
        f"spec = ModelSpec(HexFlexGeometry(**{dataclasses.asdict(SMALL)!r}), element='q2', "
        "mesh_size=1.0); "
        "ex._task(spec, 'nonlinear', np.full((1, 6), 0.1), 1); "
    )
    # the runner, where it runs tasks, its progress reports, its cache key and its cache's
    # folders define no result
    runner = {
        "mechlib.campaign",
        "mechlib.campaign.experiments",
        "mechlib.campaign.executors",
        "mechlib.campaign.spec",  # what the runner needs of a specification
        "mechlib.progress",
        "mechlib.campaign.sources",
        "mechlib.campaign.codedigest",
        "mechlib.campaign.taskcache",
        "mechlib.paths",
    }
    # the runner also takes a compliant layout's specification: that code is in the layout's
    # tasks' key (the test below), not the HexFlex's
    runner |= {m for m in loaded_all if m.startswith("mechlib.compliant")}
    loaded = loaded_all - runner
    keyed = set(model_modules((*ModelSpec.TASK_MODULES, SOLVE_MODULE)))
    assert {"mechlib.fe.factor", "mechlib.fe.svk_tangent"} <= keyed
    # the runner's own code defines no result; the specification and the task's solve do
    assert "mechlib.campaign.experiments" not in keyed
    assert {"mechlib.hexflex.spec", SOLVE_MODULE} <= keyed
    assert loaded <= keyed, sorted(loaded - keyed)


def test_every_module_of_a_layouts_task_is_in_its_cache_key() -> None:

    loaded_all = _modules_a_task_loads(
        "from mechlib.compliant.spec import MechanismSpec; "
        "from mechlib.parallelogram.mechanism import layout; "
        "spec = MechanismSpec(layout(stage_young=5e6), 10.0, 1); "
        "ex._task(spec, 'nonlinear', np.array([[0.0, 1000.0, 0.0]]), 1); "
    )
    from mechlib.compliant.spec import MechanismSpec

    keyed = set(model_modules((*MechanismSpec.TASK_MODULES, SOLVE_MODULE)))
    runner = {
        "mechlib.campaign",
        "mechlib.campaign.experiments",
        "mechlib.campaign.executors",
        "mechlib.hexflex.spec",  # imported by the runner's registry, not run by a layout's task
        "mechlib.campaign.spec",
        "mechlib.progress",
        "mechlib.campaign.sources",
        "mechlib.campaign.codedigest",
        "mechlib.campaign.taskcache",
        "mechlib.paths",
        "mechlib.parallelogram",  # the test's layout, given to the task as data
        "mechlib.parallelogram.mechanism",
        "mechlib.parallelogram.published",
        "mechlib.parallelogram.published_sweep",
        # the runner's HexFlex specification imports the HexFlex's model (not the layout's)
        "mechlib.hexflex",
        "mechlib.hexflex.geometry",
        "mechlib.hexflex.fe",
        "mechlib.hexflex.fe.lean",
        "mechlib.hexflex.fe.mesh",
        "mechlib.hexflex.fe.model",
        "mechlib.hexflex.fe.problem",
        "mechlib.compliant",  # the package: its docstring only
    }
    loaded = loaded_all - runner
    assert {"mechlib.compliant.solver", "mechlib.compliant.problem"} <= keyed
    assert loaded <= keyed, sorted(loaded - keyed)


def test_an_unreadable_cache_file_is_a_miss(tmp_path, monkeypatch) -> None:
    monkeypatch.setattr(ex, "_task", FakeTask(fail_at=-1, error=RuntimeError("never raised")))
    d = _design(5)
    ex.run_experiments(SPEC, d, cache_dir=tmp_path, progress=False)
    (cached,) = tmp_path.glob("*.npy")
    cached.write_bytes(b"not an npy file")  # e.g. a write cut short
    np.testing.assert_array_equal(
        ex.run_experiments(SPEC, d, cache_dir=tmp_path, progress=False), 2.0 * d
    )
    np.testing.assert_array_equal(np.load(cached), 2.0 * d)  # and it was written again


def test_the_cache_is_keyed_by_the_model_code(tmp_path, monkeypatch) -> None:
    d = _design(5)
    ex.run_experiments(SPEC, d, cache_dir=tmp_path, progress=False)
    (cached,) = tmp_path.glob("*.npy")
    np.save(cached, np.zeros((5, 6)))
    # the same spec and forces after a change to the mesher or solver: the stale file is ignored
    monkeypatch.setattr(ex, "model_code_fingerprint", lambda *modules: "changed-code")
    assert ex.run_experiments(SPEC, d, cache_dir=tmp_path, progress=False).all()
    assert len(list(tmp_path.glob("*.npy"))) == 2


def test_dask_local_cluster_gives_identical_results() -> None:
    distributed = pytest.importorskip("distributed")
    d = _design(600)
    serial = ex.run_experiments(SPEC, d, progress=False)
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        parallel = ex.run_experiments(SPEC, d, executor=client.get_executor(), progress=False)
    np.testing.assert_array_equal(parallel, serial)


def test_a_failed_task_is_named_and_completed_results_are_kept(tmp_path) -> None:
    d = _design(600)  # three tasks of LINEAR_BLOCK = 250 rows
    msg = r"250 of 600 experiments failed \(first: run 250"
    with pytest.raises(ex.ExperimentError, match=msg) as info:
        ex.run_experiments(SPEC, d, executor=FailingExecutor(), cache_dir=tmp_path, progress=False)
    assert info.value.failed == list(range(250, 500))
    assert sorted(info.value.completed) == [*range(250), *range(500, 600)]
    # the completed tasks were cached: the rerun only computes the failed block
    assert len(list(tmp_path.glob("*.npy"))) == 2
    full = ex.run_experiments(SPEC, d, cache_dir=tmp_path, progress=False)
    np.testing.assert_allclose(full[250:500], ex.model_for(SPEC).poses(d[250:500]))


def _poses(kind: str, forces: np.ndarray) -> np.ndarray:
    """A fake task's result: 2 × forces as the pose, in every convention the kind has, and
    made-up solve statistics after a non-linear run's poses."""
    poses = np.tile(2.0 * forces, (1, ex.POSE_COLUMNS[kind] // 6))
    stats = np.tile([3.0, 1.0, 0.0, 1e-8], (len(forces), 1))[
        :, : ex.RESULT_COLUMNS[kind] - poses.shape[1]
    ]
    return np.hstack([poses, stats])


class FakeTask:
    """Stands in for the FE task: a known pose per row, and an exception at one call."""

    def __init__(self, fail_at: int, error: BaseException) -> None:
        self.fail_at, self.error, self.calls = fail_at, error, 0

    def __call__(self, spec, kind, forces, steps) -> np.ndarray:
        self.calls += 1
        if self.calls == self.fail_at:
            raise self.error
        return _poses(kind, forces)


def test_ctrl_c_in_a_task_stops_the_run_at_once(monkeypatch, tmp_path) -> None:
    task = FakeTask(fail_at=2, error=KeyboardInterrupt())
    monkeypatch.setattr(ex, "_task", task)
    with pytest.raises(KeyboardInterrupt):
        ex.run_experiments(SPEC, _design(600), cache_dir=tmp_path, progress=False)
    assert task.calls == 2  # the third task never ran
    # ... and the first one's result was cached before the interrupt: a rerun resumes there
    (cached,) = tmp_path.glob("*.npy")
    np.testing.assert_array_equal(np.load(cached), 2.0 * _design(600)[:250])


@pytest.mark.parametrize("error", [KeyboardInterrupt(), SystemExit(3)])
def test_the_in_process_executor_lets_interrupts_through(error) -> None:
    def interrupted():
        raise error

    with pytest.raises(type(error)):
        executors.InProcessExecutor().submit(interrupted)


def test_an_ordinary_exception_in_process_is_a_failed_task(monkeypatch, tmp_path) -> None:
    task = FakeTask(fail_at=2, error=ArithmeticError("diverged"))
    monkeypatch.setattr(ex, "_task", task)
    d = _design(600)  # three tasks of LINEAR_BLOCK = 250 rows
    msg = r"250 of 600 experiments failed \(first: run 250, .*: diverged\); 350 completed"
    with pytest.raises(ex.ExperimentError, match=msg) as info:
        ex.run_experiments(SPEC, d, cache_dir=tmp_path, progress=False)
    assert task.calls == 3  # the remaining task still ran
    assert info.value.failed == list(range(250, 500))
    assert sorted(info.value.completed) == [*range(250), *range(500, 600)]
    np.testing.assert_array_equal(info.value.completed[599], 2.0 * d[599])
    assert len(list(tmp_path.glob("*.npy"))) == 2  # both completed tasks cached


def test_bad_designs_are_refused_by_name() -> None:
    with pytest.raises(ValueError, match="design must have 6 factor columns"):
        ex.run_experiments(SPEC, np.zeros((3, 5)), progress=False)
    with pytest.raises(ValueError, match=r"design \[N\] must lie in \[-50, 50\]"):
        ex.run_experiments(SPEC, np.full((2, 6), 80.0), progress=False)
    with pytest.raises(ValueError, match="kind must be one of"):
        ex.run_experiments(SPEC, np.zeros((2, 6)), kind="plastic", progress=False)


def test_failed_non_linear_runs_are_listed_with_forces_and_residual(monkeypatch) -> None:
    def task(spec, kind, forces, steps):
        if forces[0, 0] > 0.5:
            raise ConvergenceError("did not converge", forces[0].tolist(), 2e-3)
        return _poses(kind, forces)

    monkeypatch.setattr(ex, "_task", task)
    d = _design(20)
    index, poses, failures = ex.run_keeping_failures(SPEC, d, kind="nonlinear", progress=False)
    bad = np.flatnonzero(d[:, 0] > 0.5)
    assert bad.size and [f.index for f in failures] == bad.tolist()
    assert index.tolist() == np.flatnonzero(d[:, 0] <= 0.5).tolist()
    np.testing.assert_array_equal(poses, 2.0 * d[index])
    first = failures[0]
    assert first.forces == tuple(d[bad[0]]) and first.residual == 2e-3
    assert "did not converge" in first.reason
    # an error without a residual (a lost worker) is listed with nan
    monkeypatch.setattr(ex, "_task", FakeTask(fail_at=2, error=OSError("worker lost")))
    _, _, lost = ex.run_keeping_failures(SPEC, d[:3], kind="nonlinear", progress=False)
    assert [f.index for f in lost] == [1] and np.isnan(lost[0].residual)
    # nothing failed: every row, no failures
    monkeypatch.setattr(ex, "_task", lambda spec, kind, forces, steps: _poses(kind, forces))
    index, poses, failures = ex.run_keeping_failures(SPEC, d, kind="nonlinear", progress=False)
    assert index.tolist() == list(range(20)) and failures == []


def _blas_threads() -> int:
    from threadpoolctl import threadpool_info

    return max(i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas")


def test_the_worker_pool_shares_the_cores_and_agrees_with_the_in_process_run() -> None:
    import os

    with executors.worker_pool(2) as pool:
        assert pool.submit(_blas_threads).result() == max(1, (os.cpu_count() or 1) // 2)
        spec = ModelSpec(SMALL, mesh_size=1.0)  # Q2: the non-linear solve
        d = 3.0 * _design(2)
        pooled = ex.run_experiments(spec, d, kind="nonlinear", executor=pool, progress=False)
    here = ex.run_experiments(spec, d, kind="nonlinear", progress=False)
    # BLAS thread counts differ (one per worker here): equal to the solver's tolerance, not bits
    np.testing.assert_allclose(pooled, here, rtol=1e-8)
    with pytest.raises(ValueError, match="workers must be"):
        executors.worker_pool(0)


def test_nonlinear_runs_give_the_pose_in_three_conventions(tmp_path) -> None:
    from mechlib.fe.finite_pose import finite_poses

    spec = ModelSpec(SMALL, element="q2", mesh_size=1.0)
    d = np.array([[0.3, -0.5, 0.2, 1.0, -0.7, 0.1]]) * 3.0
    small = ex.run_experiments(spec, d, kind="nonlinear", cache_dir=tmp_path, progress=False)
    solver = ex.solver_for(spec)
    u, _ = solver.solve(d[0])
    np.testing.assert_array_equal(small[0], solver.model.pose_of(u))  # as before, bit for bit
    # the stage nodes registered exactly are the nodes the small-rotation fit reads: its own
    # fit of them is the model's pose
    exact = finite_poses(*solver.model.stage_motion(u))
    np.testing.assert_allclose(exact["small"], small[0], rtol=1e-9, atol=1e-9 * abs(small).max())
    for name in ("rotvec", "euler_xyz"):
        again = ex.run_experiments(
            spec, d, kind="nonlinear", cache_dir=tmp_path, progress=False, pose=name
        )
        np.testing.assert_array_equal(again[0], exact[name])
    # a tilt of several mrad: the conventions differ (at second order), the translations agree
    rot, eul = exact["rotvec"], exact["euler_xyz"]
    assert np.abs(rot[3:] - small[0, 3:]).max() > 0
    np.testing.assert_allclose(rot[:3], eul[:3], rtol=1e-12)
    both = ex.run_experiments(
        spec, d, kind="nonlinear", cache_dir=tmp_path, progress=False, pose="all"
    )
    np.testing.assert_array_equal(both[0], np.concatenate([small[0], rot, eul]))
    # what the solve spent is kept beside the poses: the solver's own counts and residual
    _, stats = solver.solve(d[0])
    spent = ex.run_experiments(
        spec, d, kind="nonlinear", cache_dir=tmp_path, progress=False, pose="stats"
    )
    expected = [sum(stats.iterations), sum(stats.factorisations), stats.restarts, stats.residual]
    np.testing.assert_array_equal(spent[0], expected)
    assert spent.shape == (1, len(ex.SOLVE_STATS)) and spent[0, 0] >= 1 and spent[0, 1] >= 1
    assert len(list(tmp_path.glob("*.npy"))) == 1  # one solve, one cache entry
    with pytest.raises(ValueError, match="pose must be one of"):
        ex.run_experiments(spec, d, kind="linear", pose="rotvec", progress=False)


def test_a_quadrature_order_out_of_range_is_refused_by_name() -> None:
    with pytest.raises(ValueError, match=r"quad_order must be in \[2, 10\], got 11"):
        ModelSpec(SMALL, quad_order=11)
    with pytest.raises(TypeError, match="quad_order must be an integer"):
        ModelSpec(SMALL, quad_order=4.0)
    assert ModelSpec(SMALL, quad_order=10).quad_order == 10


def test_release_models_empties_the_model_and_solver_caches() -> None:
    spec = ModelSpec(SMALL, element="q2", mesh_size=1.0)
    from mechlib.campaign import solve

    ex.model_for(spec)
    ex.solver_for(spec)
    assert solve._model.cache_info().currsize >= 1
    assert solve.solver_for.cache_info().currsize >= 1
    ex.release_models()
    assert solve._model.cache_info().currsize == 0
    assert solve.solver_for.cache_info().currsize == 0


def test_a_docstring_only_package_does_not_enter_the_cache_key() -> None:
    from mechlib.campaign import taskcache

    assert not taskcache._defines_code(b'"""What the package holds."""\n')
    assert not taskcache._defines_code(b'"""Doc."""\n\nfrom __future__ import annotations\n')
    assert taskcache._defines_code(b'"""Doc."""\n\nSIZE = 2\n')
    assert taskcache._defines_code(b"from mechlib.hexflex.fe.model import HexFlexModel\n")


def test_the_models_size_is_cached_like_a_run(tmp_path, monkeypatch) -> None:
    from mechlib.campaign import solve

    want = ex.model_for(SPEC).n_dofs
    assert ex.model_size(SPEC, tmp_path) == want
    ex.release_models()

    def no_model(spec):
        raise AssertionError("a cached size builds no model")

    monkeypatch.setattr(solve, "model_for", no_model)
    assert ex.model_size(SPEC, tmp_path) == want
    with pytest.raises(ex.ExperimentError, match="builds no model"):  # no cache: built
        ex.model_size(SPEC, None)


def test_a_worker_with_other_fe_code_refuses_the_task(monkeypatch) -> None:
    """A task is solved only where the FE code is the code its key names (a Dask worker on
    another commit would otherwise cache its results under this code's keys)."""
    monkeypatch.setattr(ex, "_task", lambda *a: pytest.fail("solved by other code"))
    spec = ModelSpec(SMALL, element="q2", mesh_size=1.0)
    with pytest.raises(ex.CodeMismatchError, match=r"not the submitting process's \(0{16}\)"):
        ex.same_code_task("0" * 16, spec, "linear", np.zeros((1, 6)), 1)
    here = ex.model_code_fingerprint(spec.TASK_MODULES)
    monkeypatch.setattr(ex, "_task", lambda *a: np.ones((1, 6)))
    assert ex.same_code_task(here, spec, "linear", np.zeros((1, 6)), 1).shape == (1, 6)
