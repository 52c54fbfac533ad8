"""Verdict categories of the reproduction report, and the cells that describe a difference.

Every report row (:mod:`mechlib.reporting.report`) carries a ``category``: a structured field set
from the
numbers and from what the row declares — the ``basis`` of an agreement and the ``source`` of a
statement — never parsed back from the verdict text. The report's tallies and the landing page
count these categories; only :data:`CLAIM_CATEGORIES` are counted as claims of the thesis, and a
finding of ours (:data:`CAT_OURS`) is never counted with them.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

#: an independent computation agrees with the published value within the stated tolerance
CAT_REPRODUCED = "reproduced"
#: agreement that holds by construction: we fitted to the published value, or it follows from one
CAT_CONSTRUCTION = "consistent by construction"
#: our independent computation disagrees; the row names the cause
CAT_DIVERGES = "diverges"
#: the published values contradict each other (a copy error, two tables that cannot both hold)
CAT_INCONSISTENT = "inconsistency inside the thesis"
#: published values set against each other agree (no computation of ours is tested by it)
CAT_CONSISTENT_THESIS = "consistent inside the thesis"
#: a published value that none of our computations reaches; the row says what was tried
CAT_NOT_REPRODUCED = "not reproduced"
CAT_SUPPORTED = "thesis claim supported"
CAT_NOT_SUPPORTED = "thesis claim not supported"
#: a claim made of several parts, some of which hold
CAT_MIXED = "thesis claim mixed"
#: a claim of the thesis whose every part holds by construction or is arithmetic on published
#: values: shown, never counted as support (its own line in the counts)
CAT_CLAIM_CONSTRUCTION = "thesis claim consistent by construction"
#: a hypothesis or result of ours: never counted with the thesis's claims or values
CAT_OURS = "our finding beyond the thesis"
CAT_COMPUTED = "computed (no published value)"
#: a figure of the thesis's method redrawn from its text: nothing computed, nothing to compare
CAT_REDRAWN = "redrawn from the thesis's text (nothing to compare)"
#: every category, in the order the report and the landing page list them
CATEGORIES = (
    CAT_REPRODUCED,
    CAT_CONSTRUCTION,
    CAT_DIVERGES,
    CAT_INCONSISTENT,
    CAT_CONSISTENT_THESIS,
    CAT_NOT_REPRODUCED,
    CAT_SUPPORTED,
    CAT_NOT_SUPPORTED,
    CAT_MIXED,
    CAT_CLAIM_CONSTRUCTION,
    CAT_OURS,
    CAT_COMPUTED,
    CAT_REDRAWN,
)
#: the categories of a thesis claim that a test which could fail has judged
TESTED_CLAIM_CATEGORIES = (CAT_SUPPORTED, CAT_NOT_SUPPORTED, CAT_MIXED)
#: every category of a thesis claim's row (tested, or consistent by construction only)
CLAIM_CATEGORIES = (*TESTED_CLAIM_CATEGORIES, CAT_CLAIM_CONSTRUCTION)

#: what a comparison's agreement rests on: an independent computation (default), a fit to the
#: published value or an input taken from it, or two published values set against each other
#: (``BASIS_THESIS``: its agreement is "consistent inside the thesis", its divergence an
#: "inconsistency inside the thesis"; the value's name is kept from the records)
BASIS_INDEPENDENT = "independent"
BASIS_CONSTRUCTION = "construction"
BASIS_THESIS = "thesis-inconsistency"
BASES = (BASIS_INDEPENDENT, BASIS_CONSTRUCTION, BASIS_THESIS)
#: whose statement a row checks: the thesis's (default) or ours
SOURCE_THESIS = "thesis"
SOURCE_OURS = "ours"
SOURCES = (SOURCE_THESIS, SOURCE_OURS)

#: values listed in full in a Published/Ours cell; longer arrays are summarised (size, range)
LIST_MAX = 6
#: significant digits of listed values and of the difference measure
VALUE_DIGITS = 6
DIFF_DIGITS = 3
#: a difference within this share of the largest published value is floating-point round-off
ROUND_OFF = 1e-12
#: from this many times the largest published value on, a difference is said in orders of magnitude
ORDERS_FROM = 100.0
#: the ratio to half the last printed digit is shown up to this value (beyond it adds nothing)
RESOLUTION_SHOWN = 1000.0


def summarise(
    values: np.ndarray, digits: int = VALUE_DIGITS, labels: Sequence[str] | None = None
) -> str:
    """A Published/Ours cell: up to :data:`LIST_MAX` values listed, more summarised.

    Parameters
    ----------
    values : numpy.ndarray
        The values (any shape).
    digits : int
        Significant digits of listed values.

    labels : sequence of str, optional
        One name per value: the values are then listed by name, ``"GP: 0.0921; PCE: 1.56"``
        (semicolons, so that names may hold commas), however many.

    Returns
    -------
    str
        ``"1, 2.5"``, or ``"72 values (12 × 6) from -1 to 1, max |x| = 1"``: never a repr.

    Raises
    ------
    ValueError
        For labels that are not one per value.
    """
    flat = values.ravel()
    if labels is not None:
        if len(labels) != flat.size:
            raise ValueError(f"labels must name each of the {flat.size} values, got {len(labels)}")
        return "; ".join(f"{name}: {v:.{digits}g}" for name, v in zip(labels, flat, strict=True))
    if flat.size <= LIST_MAX:
        return ", ".join(f"{v:.{digits}g}" for v in flat)
    shape = " × ".join(str(n) for n in values.shape)
    dims = f" ({shape})" if values.ndim > 1 else ""
    return (
        f"{flat.size} values{dims} from {flat.min():.4g} to {flat.max():.4g}, "
        f"max |x| = {np.abs(flat).max():.4g}"
    )


def difference_text(
    max_abs_diff: float, published_scale: float, resolution_ratio: float | None = None
) -> str:
    """The Difference cell: the largest |ours − published| relative to the largest |published|.

    Parameters
    ----------
    max_abs_diff : float
        Largest absolute difference, in the published value's units.
    published_scale : float
        Largest |published value| of the row (0 when all are printed as 0).
    resolution_ratio : float, optional
        Largest difference in units of half the last printed digit, when the row gives one.

    Returns
    -------
    str
        ``"round-off (2e-16)"`` when the difference is floating-point round-off of the published
        value (:data:`ROUND_OFF`); else ``"0.0294 % of max |published|"``, ``"16.8 × max
        |published|"`` or, beyond :data:`ORDERS_FROM` times, ``"4 orders of magnitude
        (× 1.7e+04)"``;
        with the printed-resolution ratio appended while it is at most :data:`RESOLUTION_SHOWN`
        (beyond, the relative measure says it all). :data:`DIFF_DIGITS` significant digits.
    """
    if max_abs_diff < 0 or published_scale < 0:
        raise ValueError(
            f"max_abs_diff and published_scale must be >= 0, got {max_abs_diff}, {published_scale}"
        )
    d = DIFF_DIGITS
    if published_scale == 0:
        text = f"{max_abs_diff:.{d}g} (published values all 0)"
    elif max_abs_diff == 0:
        return "none (equal)"
    elif max_abs_diff <= ROUND_OFF * published_scale:
        return f"round-off ({max_abs_diff:.1g})"
    else:
        rel = max_abs_diff / published_scale
        if rel <= 1:
            text = f"{100 * rel:.{d}g} % of max |published|"
        elif rel < ORDERS_FROM:
            text = f"{rel:.{d}g} × max |published|"
        else:
            shown = float(f"{rel:.2g}")  # the orders of the factor as printed: 999.7 is × 1e+03
            text = f"{np.floor(np.log10(shown)):.0f} orders of magnitude (× {rel:.2g})"
    if resolution_ratio is not None and resolution_ratio <= RESOLUTION_SHOWN:
        text += f"; {resolution_ratio:.{d}g} × half the last printed digit"
    return text


def check_kinds(basis: str, source: str) -> None:
    """Raise ``ValueError`` naming ``basis`` or ``source`` when it is not one of the allowed."""
    if basis not in BASES:
        raise ValueError(f"basis must be one of {BASES}, got {basis!r}")
    if source not in SOURCES:
        raise ValueError(f"source must be one of {SOURCES}, got {source!r}")


def comparison_category(
    agree: bool, basis: str = BASIS_INDEPENDENT, source: str = SOURCE_THESIS
) -> str:
    """The category of a comparison from whether all values agree and what it declares.

    A hypothesis of ours is :data:`CAT_OURS` whatever the numbers; agreement is
    :data:`CAT_CONSTRUCTION` when it holds by construction, :data:`CAT_CONSISTENT_THESIS` when
    published values are set against each other, else :data:`CAT_REPRODUCED`; a divergence is
    :data:`CAT_INCONSISTENT` when published values are set against each other, else
    :data:`CAT_DIVERGES` (also when agreement by construction fails).
    """
    check_kinds(basis, source)
    if source == SOURCE_OURS:
        return CAT_OURS
    if agree:
        return {BASIS_CONSTRUCTION: CAT_CONSTRUCTION, BASIS_THESIS: CAT_CONSISTENT_THESIS}.get(
            basis, CAT_REPRODUCED
        )
    return CAT_INCONSISTENT if basis == BASIS_THESIS else CAT_DIVERGES
