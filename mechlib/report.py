"""Rows of the reproduction report: published value, ours, difference, verdict.

A row is built by :func:`compare_row` (numbers against the published ones), :func:`claim_row`
(a statement checked by a computed test) or :func:`computed_row` (a number the thesis does not
publish). Notebooks describe a row without "ours" — :class:`Comparison`, :class:`Claim`,
:class:`Computed` — and hand it to :meth:`mechlib.records.Recorder.value`, which fills in the
value it records: the number in the report is then the number checked against the references.
The build wing (:mod:`mechlib.pipeline.bookbuild`) gathers the rows of every record into the book's
report page. A verdict is never typed: it follows from the numbers and tolerances given.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from typing import Any

import numpy as np

from mechlib.params import check_float, check_int

REPRODUCED = "reproduced"
WITHIN = "within tolerance"
DIVERGES = "diverges"
SUPPORTED = "claim supported"
NOT_SUPPORTED = "claim not supported"
COMPUTED = "computed (no published value)"


def _fmt(values: np.ndarray, digits: int = 6) -> str:
    flat = values.ravel()
    text = ", ".join(f"{v:.{digits}g}" for v in flat[:6])
    return text + (f", … ({flat.size} values)" if flat.size > 6 else "")


def compare_row(
    artefact: str,
    quantity: str,
    published: object,
    ours: object,
    *,
    resolution: object = 0.0,
    rtol: float = 0.0,
    atol: object = 0.0,
    tolerance: str = "",
    cause: str = "",
) -> dict[str, Any]:
    """Compare our value(s) with the published ones and classify the agreement.

    Parameters
    ----------
    artefact : str
        Thesis artefact, e.g. ``"Table 3"``.
    quantity : str
        What is compared, e.g. ``"|effects| (36 cells)"``.
    published, ours : array_like
        Same shape.
    resolution : array_like
        Half a unit of the last printed digit (see ``published.printed_resolution``): a
        difference within it is "reproduced".
    rtol : float
        Relative tolerance beyond printing for "within tolerance".
    atol : array_like
        Absolute tolerance added to ``rtol`` (e.g. a fraction of a row's scale, so that entries
        printed as exact zeros can be judged).
    tolerance : str
        How the tolerance reads in the verdict; default ``"<rtol> %"``.
    cause : str
        Why the values diverge, shown when they do. Required in that case.

    Returns
    -------
    dict
        A row with the published and our values (shortened), the largest absolute and relative
        difference and the verdict.
    """
    pub = np.asarray(published, dtype=float)
    our = np.asarray(ours, dtype=float)
    if pub.shape != our.shape:
        raise ValueError(f"published shape {pub.shape} differs from ours {our.shape}")
    rtol = check_float("rtol", rtol, low=0.0)
    res = np.broadcast_to(np.asarray(resolution, dtype=float), pub.shape)
    abs_tol = np.broadcast_to(np.asarray(atol, dtype=float), pub.shape)
    if np.any(abs_tol < 0) or np.any(res < 0):
        raise ValueError("atol and resolution must be >= 0")
    diff = np.abs(our - pub)
    rel = np.divide(diff, np.abs(pub), out=np.zeros_like(diff), where=pub != 0)
    # a tiny allowance for binary floating point on top of the printed half-digit
    slack = 1e-9 * np.maximum(np.abs(pub), 1.0)
    if np.all(diff <= res + slack):
        verdict = REPRODUCED
    elif np.all(diff <= res + rtol * np.abs(pub) + abs_tol + slack):
        verdict = f"{WITHIN} ({tolerance or f'{100 * rtol:g} %'})"
    else:
        if not cause:
            raise ValueError(f"{artefact} {quantity}: values diverge, a cause must be given")
        verdict = f"{DIVERGES}: {cause}"
    return {
        "artefact": artefact,
        "quantity": quantity,
        "published": _fmt(pub),
        "ours": _fmt(our),
        "max_abs_diff": float(diff.max()),
        "max_rel_diff": float(rel.max()),
        "verdict": verdict,
    }


def claim_row(artefact: str, claim: str, evidence: str, holds: bool) -> dict[str, Any]:
    """A row for a statement of the thesis checked by a computed test (``holds``)."""
    return {
        "artefact": artefact,
        "quantity": claim,
        "published": "(claim)",
        "ours": evidence,
        "max_abs_diff": None,
        "max_rel_diff": None,
        "verdict": SUPPORTED if bool(holds) else NOT_SUPPORTED,
    }


def computed_row(artefact: str, quantity: str, ours: object) -> dict[str, Any]:
    """A row for a number the thesis does not publish (ours only)."""
    return {
        "artefact": artefact,
        "quantity": quantity,
        "published": "—",
        "ours": _fmt(np.asarray(ours, dtype=float)),
        "max_abs_diff": None,
        "max_rel_diff": None,
        "verdict": COMPUTED,
    }


def float_format(digits: int, zero_below: float = 0.0) -> Callable[[float], str]:
    """A number format for tables (pandas' ``display.float_format``): ``digits`` significant
    digits, and ``"0"`` for magnitudes up to ``zero_below`` (round-off residue of exact zeros)."""
    digits = check_int("digits", digits, low=1, high=17)
    zero_below = check_float("zero_below", zero_below, low=0.0)
    return partial(_format_float, digits=digits, zero_below=zero_below)


def _format_float(value: float, *, digits: int, zero_below: float) -> str:
    return "0" if abs(value) <= zero_below else f"{value:.{digits}g}"


@dataclass(frozen=True)
class Comparison:
    """A :func:`compare_row` waiting for our value (the recorded one); fields as there.

    ``part`` selects the compared part of the recorded value (an index, e.g. ``2`` or
    ``(slice(None), 0)``); ``None`` compares all of it.
    """

    artefact: str
    quantity: str
    published: object
    resolution: object = 0.0
    rtol: float = 0.0
    atol: object = 0.0
    tolerance: str = ""
    cause: str = ""
    part: object = None

    def row(self, ours: object) -> dict[str, Any]:
        """The report row for our value ``ours`` (see :func:`compare_row`)."""
        ours = np.asarray(ours, dtype=float)
        return compare_row(
            self.artefact,
            self.quantity,
            self.published,
            ours if self.part is None else ours[self.part],
            resolution=self.resolution,
            rtol=self.rtol,
            atol=self.atol,
            tolerance=self.tolerance,
            cause=self.cause,
        )


@dataclass(frozen=True)
class Claim:
    """A :func:`claim_row` waiting for its test: the recorded value says whether it holds."""

    artefact: str
    claim: str
    evidence: str

    def row(self, holds: object) -> dict[str, Any]:
        """The row for ``holds``: a bool, or booleans that must all be true.

        Raises
        ------
        TypeError
            If ``holds`` is not boolean (a number must first be compared with a named
            threshold).
        """
        arr = np.asarray(holds)
        if arr.dtype != bool:
            raise TypeError(f"{self.artefact}: a claim holds or not, got {holds!r}")
        return claim_row(self.artefact, self.claim, self.evidence, bool(arr.all()))


@dataclass(frozen=True)
class Computed:
    """A :func:`computed_row` waiting for our value."""

    artefact: str
    quantity: str

    def row(self, ours: object) -> dict[str, Any]:
        """The row for our value ``ours``."""
        return computed_row(self.artefact, self.quantity, ours)


#: A report row waiting for the recorded value it reports on.
RowSpec = Comparison | Claim | Computed
