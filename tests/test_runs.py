"""``make run``'s helpers: the papermill command."""

from __future__ import annotations

from pathlib import Path

from mechlib import runs


def test_papermill_command_is_the_one_command_line() -> None:
    cmd = runs.papermill_command(
        Path("notebooks/a.ipynb"), Path("/out/a.ipynb"), ["-p", "seed", "1"], python="/env/bin/py"
    )
    assert cmd == [
        "/env/bin/papermill",
        "-k",
        "python3",
        "--cwd",
        "notebooks",
        "--no-progress-bar",
        "notebooks/a.ipynb",
        "/out/a.ipynb",
        "-p",
        "seed",
        "1",
    ]
