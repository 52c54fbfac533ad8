"""Force → pose meta-model families compared on designed runs (issue 28; thesis Eqs 6–9, Table 5).

Given training forces X (runs, 6) [N] and poses Y (runs, 6) [µm, µrad]:

- :mod:`~mechlib.surrogates.families` fits a named family (``linear`` S_T of Eq 7, ``quadratic``
  Eq 6, ``cubic``, ``gp``, ``pce``) and predicts inside the validated force range;
- :mod:`~mechlib.surrogates.scoring` scores it on held-out runs (Table 5's max |error| as % of
  each component's range, RMSE), by seeded k-fold cross-validation, and times it per pose;
- :mod:`~mechlib.surrogates.curves` builds space-filling training designs (LHS optimised on the
  centred discrepancy), learning curves and the force range that meets an error budget;
- :mod:`~mechlib.surrogates.inverse` gives the forces for a desired pose (Eq 9's analogue).

Libraries for GP and PCE (measured, see ``LIBRARY_CHOICE``): scikit-learn, already locked.
"""

from mechlib.surrogates.curves import learning_curve, range_within_budget, space_filling_design
from mechlib.surrogates.families import (
    FAMILIES,
    Surrogate,
    fit_surrogate,
    n_terms,
    predict,
)
from mechlib.surrogates.inverse import compare_with_truth, invert, jacobian, round_trip_error
from mechlib.surrogates.scoring import compare_families, cross_validate, latency_us, score

__all__ = [
    "FAMILIES",
    "Surrogate",
    "compare_families",
    "compare_with_truth",
    "cross_validate",
    "fit_surrogate",
    "invert",
    "jacobian",
    "latency_us",
    "learning_curve",
    "n_terms",
    "predict",
    "range_within_budget",
    "round_trip_error",
    "score",
    "space_filling_design",
]
