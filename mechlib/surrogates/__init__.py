"""Force → pose meta-model families compared on designed runs (issue 28; thesis Eqs 6–9, Table 5).

Given training forces X (runs, 6) [N] and poses Y (runs, 6) [µm, µrad]:

- :mod:`~mechlib.surrogates.families` fits a named family (``linear`` S_T of Eq 7, ``quadratic``
  Eq 6, ``cubic``, ``gp``, ``pce``) and predicts inside the validated force range;
- :mod:`~mechlib.surrogates.scoring` scores it on held-out runs (Table 5's max |error| as % of
  each component's range, RMSE), by seeded k-fold cross-validation, and times it per pose;
- :mod:`~mechlib.surrogates.curves` builds space-filling training designs (LHS optimised on the
  centred discrepancy), learning curves and the force range that meets an error budget;
- :mod:`~mechlib.surrogates.inverse` gives the forces for a desired pose (Eq 9's analogue).

Libraries for GP and PCE: scikit-learn (already locked), chosen by measurement against SMT 2.15,
OpenTURNS 1.27 and chaospy 4.3 (``benchmarks/surrogate_libraries.py``; Eq 8's S_T with 2 % on
every entry, plus ~3 % quadratic, ~1 % cubic and a 1 % sine term; LHS random-cd training of 30 /
100 / 300 runs, 1000 uniform validation runs; worst max |error| as % of range; times on a shared,
loaded 2-core machine, one BLAS thread, so compare them only as ratios):

=====================================  ====================  ==================  ===============
GP / Kriging                           error % (30/100/300)  fit s (30/100/300)  batch µs/pose
=====================================  ====================  ==================  ===============
sklearn GP on a linear trend (``gp``)  2.6 / 0.56 / 0.089    0.4 / 1.9 / 82      3 / 16 / 44
sklearn GP, constant mean              2.5 / 2.7 / 0.23      1.6 / 5.9 / 66      7 / 23 / 101
OpenTURNS GP, linear basis             3.1 / 0.69 / 0.11     1.3 / 3.5 / 27      41 / 156 / 137
SMT KRG, linear trend                  4.1 / 0.96 / —        19 / 29 / > 600     15 / 83 / —
SMT KRG, constant trend                5.0 / 3.1 / 0.37      46 / 42 / 538       88 / 84 / 515
=====================================  ====================  ==================  ===============

=========================================  ====================  ==================  =============
PCE, total degree 3                        error % (30/100/300)  fit s (30/100/300)  one pose µs
=========================================  ====================  ==================  =============
Legendre + sklearn LassoLarsCV (``pce``)   1.9 / 3.2 / 1.7       0.5 / 0.6 / 0.4     66 – 165
chaospy + sklearn LarsCV                   3.1 / 1.0 / 1.4       2.5 / 2.0 / 2.4     94k – 207k
OpenTURNS FunctionalChaos, LARS + LOO      4.4 / 4.3 / 1.7       4.9 / 0.5 / 6.8     380 – 3600
=========================================  ====================  ==================  =============

For reference: ``linear`` 2.8 / 3.0 / 2.7, ``quadratic`` 7.4 / 2.7 / 2.8, ``cubic`` — / 3.3 / 1.8
(84 terms). No other library was clearly better (OpenTURNS's GP is close to scikit-learn's,
slower to predict; chaospy's PCE is better at 100 runs, worse at 30, and a thousand times slower
per pose), so no dependency was added.
"""

from mechlib.surrogates.curves import (
    learning_curve,
    range_within_budget,
    sobol_design,
    space_filling_design,
)
from mechlib.surrogates.families import (
    FAMILIES,
    LABELS,
    PHYSICS,
    Surrogate,
    fit_surrogate,
    n_terms,
    predict,
    wrap_model,
)
from mechlib.surrogates.inverse import compare_with_truth, invert, jacobian, round_trip_error
from mechlib.surrogates.scoring import (
    compare_families,
    cross_validate,
    cv_folds,
    latency_us,
    score,
    summary_table,
)
from mechlib.surrogates.study import budget_ranges, inverse_round_trip

__all__ = [
    "FAMILIES",
    "LABELS",
    "PHYSICS",
    "Surrogate",
    "budget_ranges",
    "compare_families",
    "compare_with_truth",
    "cross_validate",
    "cv_folds",
    "fit_surrogate",
    "inverse_round_trip",
    "invert",
    "jacobian",
    "latency_us",
    "learning_curve",
    "n_terms",
    "predict",
    "range_within_budget",
    "round_trip_error",
    "score",
    "sobol_design",
    "space_filling_design",
    "summary_table",
    "wrap_model",
]
