"""The HexFlex: a six-axis compliant stage, its finite-element model and the studies built on it.

At the top: :mod:`.geometry` (the planform reconstructed from the thesis, its dimensions and
bounds), :mod:`.checks` (invariants of a compliance: three-fold symmetry, Eq 8's zero pattern,
reciprocity), :mod:`.frame_solver` and :mod:`.frame` (a millisecond 3-D beam model of the same
part) and :mod:`.identify` (free dimensions fitted so that the FE compliance meets Eq 8); they
import no subpackage. The subpackages (what each may import is held by ``tests/test_wings.py``):

- :mod:`.fe` — the finite-element model: mesh, SfePy problem, linear model, non-linear solver,
  stage pose from displacements; imports only :mod:`.geometry` (and :mod:`mechlib.params`);
- :mod:`.campaign` — running many FE tasks: executors (processes, Dask), the disk cache and its
  keys, the results store and its cold checks; imports :mod:`.fe` and the top;
- :mod:`.rom` — the hyper-reduced reduced-order model and the full solutions it is trained on;
  imports :mod:`.fe`, :mod:`.campaign` and the top;
- :mod:`.studies` — what the chapters compute from these: mesh convergence, beam and elastica
  benchmarks, linear range, departure from linearity, the family of Eq 8 members; imports
  :mod:`.fe`, :mod:`.campaign` and the top, and nothing imports a study.

Nothing here imports the build wing (:mod:`mechlib.pipeline`).
"""
