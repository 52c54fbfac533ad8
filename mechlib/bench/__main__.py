"""``python -m mechlib.bench``: run the benchmarks."""

from mechlib.bench import main

raise SystemExit(main())
