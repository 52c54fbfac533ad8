"""The HexFlex: a six-axis compliant stage, its finite-element model and the studies built on it.

At the top sit what every room below uses: :mod:`.geometry` (the planform reconstructed from the
thesis, its dimensions and bounds), :mod:`.checks` (invariants of a compliance: three-fold
symmetry, Eq 8's zero pattern, reciprocity), :mod:`.frame` (a millisecond beam model of the same
part) and :mod:`.identify` (free dimensions fitted so that the FE compliance meets Eq 8). The
subpackages, each importing only the ones listed before it and the top:

- :mod:`.fe` — the finite-element model: mesh, SfePy problem, linear model, non-linear solver,
  stage pose from displacements;
- :mod:`.campaign` — running many FE tasks: executors (processes, Dask), the disk cache and its
  keys, the results store and its cold checks;
- :mod:`.rom` — the hyper-reduced reduced-order model and the full solutions it is trained on;
- :mod:`.studies` — what the chapters compute from these: mesh convergence, beam and elastica
  benchmarks, linear range, departure from linearity, the family of Eq 8 members.

Nothing here imports the build wing (:mod:`mechlib.pipeline`).
"""
