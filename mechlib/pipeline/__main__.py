"""``python -m mechlib.pipeline <command> …`` (see :mod:`mechlib.pipeline.cli`)."""

from mechlib.pipeline.cli import main

raise SystemExit(main())
