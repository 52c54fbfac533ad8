"""Speed benchmarks (``make bench``): ratios measured in one run, never asserted in tests.

- Posture selection at 10⁴ candidates: the active-calibration search with determinant and
  Woodbury updates against the same search scoring every candidate by an SVD.
- HexFlex load cases: the factorise-once model (assembly and factorisation once, one
  back-substitution per case) against SfePy's plain ``Problem.solve()`` per case, for the 1042
  cases of Tables 2, 4 and 5 (12 + 30 + 1000). The plain path is timed on a few cases and its
  per-case time multiplied by 1042 (it is the same work every case); the fast path is timed on
  all 1042.
- SuperLU ordering on the same stiffness: the minimum-degree ordering of A + Aᵀ with symmetric
  pivoting that the model uses, against SciPy's default column ordering (COLAMD).
- The non-linear solve (issue 18's options, :mod:`mechlib.bench.nonlinear`), on the first
  validation runs of the DOE chapter's model: Newton with SfePy's tangent and SuperLU (the solver
  before issue 18), Newton with the batched-BLAS tangent (:mod:`mechlib.fe.svk_tangent`),
  modified Newton with SuperLU and modified Newton with CHOLMOD's Cholesky (the default,
  :mod:`mechlib.fe.factor`), each timed on the same runs, with the largest relative pose
  difference to the first; the cost of one tangent (SfePy's, batched), one factorisation (LU,
  Cholesky), one residual and one back-substitution; and the Newton–Krylov alternative: GMRES
  iterations, preconditioned by the factorised linear stiffness (a whole solve on the first run:
  Newton corrections, GMRES iterations, time).
- Reusing one factorised tangent across runs (:mod:`mechlib.bench.reuse`): chord iterations
  with the tangent of a neighbouring equilibrium, at growing distances in force space, and the
  nearest-neighbour distances of random designs.
- The hyper-reduced ROM of the non-linear HexFlex (:mod:`mechlib.bench.rom`): its online cost
  per pose against one full non-linear run, as a ratio measured in one run, and its pose error.
- The lean FE model against the default one (:mod:`mechlib.bench.lean`): both identified to
  Eq 8, the same seeded non-linear runs in one process; the speed-up at equal accuracy and the
  accuracy check (poses as % of full scale, the departure from linearity as % of itself).
- The DOE chapter (``virtual_experiments``) on the identified model, cold (no FE cache): the linear
  part (model, Tables 2 and 4, the 1000 validation runs) timed whole; the non-linear part timed
  per run in-process and on two-process pools (one BLAS thread per worker, and a plain one), and
  projected to the chapter's run count on two workers. The executed
  notebooks' own papermill durations are printed when a build holds them.
- A campaign on a Dask cluster against the local worker pool (:mod:`mechlib.bench.dask`): the
  same non-linear runs on the same number of single-threaded workers, on a cluster the
  benchmark starts itself; the ratio of the two times and whether the poses are bit-identical.
- The main job as a reader runs it (:mod:`mechlib.bench.book`, ``--only book``, not in the
  default run: it builds the whole book): ``make book`` on a fresh clone of HEAD, its wall time
  and each chapter's papermill duration.

The command line is :mod:`mechlib.bench.cli` (its ``SECTIONS``); the first three benchmarks
and the calibration cost are in :mod:`mechlib.bench.basics`.
"""
