"""``python -m mechlib.bench``: run the benchmarks."""

from mechlib.bench.cli import main

raise SystemExit(main())
