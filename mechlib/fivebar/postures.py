"""Observability indices and posture selection of the 5R chapter.

The implementation lives in the mechanism-independent core, :mod:`mechlib.calibration.selection`;
this module keeps the 5R chapter's names.
"""

from mechlib.calibration.selection import (
    IMPROVEMENT_TOL,
    START_REGULARISATION,
    observability_borm_menq,
    observability_o1,
    select_active,
    select_reference_svd,
)

__all__ = [
    "IMPROVEMENT_TOL",
    "START_REGULARISATION",
    "observability_borm_menq",
    "observability_o1",
    "select_active",
    "select_reference_svd",
]
