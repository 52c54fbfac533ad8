"""Force → pose meta-models of the HexFlex: the thesis's own (:mod:`.linear`, S_T of Eq 7 and its
inverse, Eq 9; :mod:`.quadratic`, the second-order model of Eq 6; :mod:`.gaussian_process`, the
chapter's Gaussian process; :mod:`.metrics`, the validation errors of Eqs 10–11) and the fitted
families compared beyond it (:mod:`.families`, fit and predict a named family inside its validated
force range; :mod:`.scoring`, held-out errors, k-fold cross-validation, latency; :mod:`.designs`,
space-filling training designs; :mod:`.inverse`, forces for a desired pose by Newton;
:mod:`.study`, learning curves, error budgets and the inverse checked against the truth). Its
modules import only each other (in that order: linear, quadratic, gaussian_process, metrics,
families, scoring, inverse, study; designs imports none), :mod:`mechlib.params`,
:mod:`mechlib.blas` (one BLAS thread), :mod:`mechlib.memo` (a fit remembered), NumPy, SciPy,
scikit-learn, threadpoolctl and pandas; never the chapters' packages (``mechlib.hexflex``,
``mechlib.fivebar`` …), plotting or ``mechlib.pipeline``.
"""
