"""papermill's command line as the build runs it: the kernel on IPC transport.

``python -m mechlib.pipeline.papermillrun <papermill arguments>`` is papermill's own command
line (:func:`papermill.cli.papermill`) with one engine added, :data:`ENGINE`: papermill's
``nbclient`` engine whose kernel manager talks to the kernel through local IPC sockets
(jupyter_client's documented setting ``KernelManager.transport = "ipc"``) instead of TCP on the
loopback. The notebooks' kernels are local, so nothing is lost, and ipykernel no longer warns,
at every start, that it is "running over TCP without encryption" — a warning nobody running the
build could act on. :func:`mechlib.pipeline.execute.papermill_command` is the one command line
that calls it.
"""

from __future__ import annotations

import sys
from typing import Any

from papermill.engines import NBClientEngine, papermill_engines
from traitlets.config import Config

#: the engine's name (papermill's ``--engine``)
ENGINE = "mechlib-ipc"
#: the kernel manager's configuration: local IPC sockets, not TCP
KERNEL_CONFIG = Config({"KernelManager": {"transport": "ipc"}})


class IpcEngine(NBClientEngine):
    """papermill's ``nbclient`` engine, its kernel manager configured by
    :data:`KERNEL_CONFIG`."""

    @classmethod
    def execute_managed_notebook(cls, nb_man: Any, kernel_name: str, **kwargs: Any) -> Any:
        """Execute as the ``nbclient`` engine does, with ``config`` :data:`KERNEL_CONFIG`."""
        return super().execute_managed_notebook(
            nb_man, kernel_name, **{**kwargs, "config": KERNEL_CONFIG}
        )


def main(argv: list[str] | None = None) -> None:
    """papermill's command line (``argv``: its arguments), run with :data:`ENGINE`."""
    from papermill.cli import papermill

    papermill_engines.register(ENGINE, IpcEngine)
    args = sys.argv[1:] if argv is None else list(argv)
    papermill.main(args=["--engine", ENGINE, *args], prog_name="papermill")


if __name__ == "__main__":
    main()
