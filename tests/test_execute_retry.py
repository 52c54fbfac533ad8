"""A notebook whose kernel dies before it starts is started again; a failing cell is not."""

from __future__ import annotations

import stat
import sys
from pathlib import Path

import pytest

from mechlib.pipeline import execute


def test_only_a_kernel_that_died_at_start_is_retried() -> None:
    assert execute.kernel_died_at_start("RuntimeError: Kernel died before replying to kernel_info")
    assert not execute.kernel_died_at_start("PapermillExecutionError: cell 3 raised ValueError")


def test_execute_starts_a_dead_kernel_again_and_gives_up_after_the_attempts(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # a stand-in papermill: fails with a dead kernel until its counter file reaches `ok_after`
    counter = tmp_path / "count"
    fake = tmp_path / "papermill"
    fake.write_text(
        f"#!{sys.executable}\nimport sys, pathlib\np = pathlib.Path({str(counter)!r})\n"
        "n = int(p.read_text()) + 1 if p.exists() else 1\np.write_text(str(n))\n"
        "ok_after = int(pathlib.Path(p.parent / 'ok_after').read_text())\n"
        "if n < ok_after:\n    sys.stderr.write('Kernel died before replying to kernel_info\\n')\n"
        "    sys.exit(1)\n"
    )
    fake.chmod(fake.stat().st_mode | stat.S_IEXEC)
    monkeypatch.setattr(execute, "papermill_command", lambda nb, out, args: [str(fake)])
    monkeypatch.setattr(execute, "input_arguments", lambda *a, **k: [])
    (tmp_path / "ok_after").write_text("2")
    assert execute.execute(tmp_path / "nb.ipynb", tmp_path / "out.ipynb", tmp_path) == 0
    assert counter.read_text() == "2"
    counter.unlink()
    (tmp_path / "ok_after").write_text("99")
    assert execute.execute(tmp_path / "nb.ipynb", tmp_path / "out.ipynb", tmp_path) == 1
    assert counter.read_text() == str(execute.KERNEL_START_ATTEMPTS)
