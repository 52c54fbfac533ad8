"""Dask workers of an FE campaign get glibc's memory reuse back and one BLAS thread."""

from __future__ import annotations

import sys

import pytest

from mechlib.campaign import daskworker


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="glibc's mallopt")
def test_restore_malloc_sets_glibc_thresholds_and_one_blas_thread() -> None:
    import subprocess

    code = (  # in a process of its own: the BLAS limit lasts for the life of the process
        "import numpy; from threadpoolctl import threadpool_info; "
        "from mechlib.campaign import daskworker as d; ok = d.restore_malloc(); "
        "print(ok, sorted({i['num_threads'] for i in threadpool_info() "
        "if i['user_api'] == 'blas'}))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["True", "[1]"]


def test_the_plugin_is_a_named_worker_plugin() -> None:
    from distributed.diagnostics.plugin import WorkerPlugin

    plugin = daskworker.CampaignWorker()
    assert isinstance(plugin, WorkerPlugin) and plugin.name == "mechlib-campaign-worker"


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="glibc's mallopt")
def test_a_task_thread_can_limit_blas_after_the_plugins_thread_did() -> None:
    import subprocess

    # as on a Dask worker: the plugin's setup runs in one thread (alive for the worker's life),
    # the tasks in others, the FE stack imported by the first task: BLAS is one thread there
    code = """
import threading
import numpy
from threadpoolctl import threadpool_info
from mechlib.campaign import daskworker as d
done, alive = threading.Event(), threading.Event()
def setup():  # stays alive, as a worker's event-loop thread does
    d.restore_malloc()
    done.set()
    alive.wait()
threading.Thread(target=setup).start()
done.wait()
import sfepy.discrete.fem  # the FE stack, loaded after the setup
from mechlib.blas import one_thread
out = []
def task():
    with one_thread():
        out.append(sorted({i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"}))
t = threading.Thread(target=task)
t.start()
t.join()
alive.set()
print(out[0])
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split("\n")[-2] == "[1]"  # the last line (SfePy prints its notices)
