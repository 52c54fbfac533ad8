"""papermill's command line as the build runs it: the kernel's own log at ERROR level.

``python -m mechlib.pipeline.papermillrun <papermill arguments>`` is papermill's own command
line (:func:`papermill.cli.papermill`) with one engine added, :data:`ENGINE`: papermill's
``nbclient`` engine that starts the kernel with :data:`KERNEL_ARGUMENTS`. At every start
ipykernel logs a WARNING that it is "running over TCP without encryption" on the loopback — a
warning nobody running the build can act on. The kernel's application log then shows errors
only; warnings raised by a notebook's code are not that log (they reach the cell's output, which
the book's checks read). IPC transport (``KernelManager.transport = "ipc"``), which avoids the
warning at its source, left the kernel unanswered for 60 s here, so it is not used.
:func:`mechlib.pipeline.execute.papermill_command` is the one command line that calls it.
"""

from __future__ import annotations

import sys
from typing import Any

from papermill.engines import NBClientEngine, papermill_engines

#: the engine's name (papermill's ``--engine``)
ENGINE = "mechlib-quiet"
#: the kernel's command-line arguments: its application log at ERROR level
KERNEL_ARGUMENTS = ["--IPKernelApp.log_level=ERROR"]


class QuietKernelEngine(NBClientEngine):
    """papermill's ``nbclient`` engine, its kernel started with :data:`KERNEL_ARGUMENTS`."""

    @classmethod
    def execute_managed_notebook(cls, nb_man: Any, kernel_name: str, **kwargs: Any) -> Any:
        """Execute as the ``nbclient`` engine does, with ``extra_arguments``
        :data:`KERNEL_ARGUMENTS`."""
        return super().execute_managed_notebook(
            nb_man, kernel_name, **{**kwargs, "extra_arguments": KERNEL_ARGUMENTS}
        )


def main(argv: list[str] | None = None) -> None:
    """papermill's command line (``argv``: its arguments), run with :data:`ENGINE`."""
    from papermill.cli import papermill

    papermill_engines.register(ENGINE, QuietKernelEngine)
    args = sys.argv[1:] if argv is None else list(argv)
    papermill.main(args=["--engine", ENGINE, *args], prog_name="papermill")


if __name__ == "__main__":
    main()
