"""The HexFlex: a six-axis compliant stage, its finite-element model and the studies built on it.

At the top: :mod:`.geometry` (the planform reconstructed from the thesis, its dimensions and
bounds), :mod:`.checks` (invariants of a compliance: three-fold symmetry, Eq 8's zero pattern,
reciprocity), :mod:`.frame_solver` and :mod:`.frame` (a millisecond 3-D beam model of the same
part) and :mod:`.identify` (free dimensions fitted so that the FE compliance meets Eq 8); they
import no subpackage. The subpackages (what each may import is held by ``tests/test_wings.py``):

- :mod:`.fe` — the finite-element model: mesh, SfePy problem, linear model, non-linear solver,
  stage pose from displacements; imports only :mod:`.geometry` (and :mod:`mechlib.params`);
- :mod:`.spec` — the FE model's specification for campaigns (:class:`~.spec.ModelSpec`, the
  :class:`mechlib.campaign.spec.Spec` of the HexFlex); imports :mod:`.fe` and the top;
- :mod:`.compliance` — an identification's compliances as cached campaign tasks; imports
  :mod:`.spec`, :mod:`.fe` and the top;
- :mod:`.rom` — the hyper-reduced reduced-order model and the full solutions it is trained on;
  imports :mod:`.fe`, :mod:`.spec`, :mod:`.compliance` and the top;
- :mod:`.studies` — what the chapters compute from these: mesh convergence, beam and elastica
  benchmarks, linear range, departure from linearity, the family of Eq 8 members; imports
  :mod:`.fe`, :mod:`.spec`, :mod:`.compliance` and the top, and nothing imports a study.

The campaigns themselves (runner, FE cache, results store, cold checks) are
:mod:`mechlib.campaign`, shared with the compliant layouts.

Nothing here imports the build wing (:mod:`mechlib.pipeline`).
"""
