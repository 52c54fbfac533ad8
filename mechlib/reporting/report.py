"""Rows of the reproduction report: published value, ours, difference, verdict.

A row is built by :func:`compare_row` (numbers against the published ones), :func:`check_row`
(a statement that holds by construction or sets published values against each other, checked by a
computed test), :func:`computed_row` (a number the thesis does not publish) or
:func:`not_reproduced_row`. Notebooks describe a row without "ours" — :class:`Comparison`,
:class:`Check`, :class:`Computed`, :class:`NotReproduced` — and hand it to
:meth:`mechlib.reporting.records.Recorder.value`, which fills in the value it records: the number
in the report is then the number checked against the references. A claim the book judges has its
row from the claims registry (:mod:`mechlib.reporting.claims`), through
:meth:`~mechlib.reporting.records.Recorder.claim`.
The build wing (:mod:`mechlib.pipeline.bookbuild`) gathers the rows of every record into the book's
report page. A verdict is never typed: it follows from the numbers and tolerances given.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import partial
from typing import Any

import numpy as np

from mechlib.params import check_float, check_int
from mechlib.reporting import categories as cat

REPRODUCED = "reproduced"
WITHIN = "within tolerance"
DIVERGES = "diverges"
COMPUTED = "computed (no published value)"
#: the tolerance of a row whose values agree to the printed digits, and of an exact one
PRINTED_DIGIT = "half a unit of the last printed digit"
EXACT = "exact (floating-point round-off only)"


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
    basis: str = cat.BASIS_INDEPENDENT,
    source: str = cat.SOURCE_THESIS,
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
    basis : {"independent", "construction", "thesis-inconsistency"}
        What an agreement rests on. ``"construction"``: we fitted to the published value or
        computed ours from an input taken from it, so agreement is "consistent by
        construction", not a reproduction. ``"thesis-inconsistency"``: the comparison sets
        published values against each other, so a divergence is an "inconsistency inside the
        thesis" and an agreement is "consistent inside the thesis", never a reproduction
        (categories: :mod:`mechlib.reporting.categories`).
    source : {"thesis", "ours"}
        ``"ours"``: the row tests a hypothesis of ours ("our finding beyond the thesis", never
        counted with the thesis's values).

    Returns
    -------
    dict
        A row with the published and our values (listed, or summarised when long), the largest
        absolute and relative difference, the verdict (text), and the structured fields
        ``category``, ``basis``, ``source``, ``cause``, ``tolerance`` (the one the agreement
        met, in words), ``n_values``, ``n_agree`` (values within the tolerance),
        ``difference`` (max |ours − published| / max |published|), ``difference_text`` and
        ``tolerance_used`` (the largest difference over the allowed one).

    Raises
    ------
    ValueError
        For different shapes, negative tolerances, an unknown ``basis`` or ``source``, or
        diverging values without a ``cause``.
    """
    cat.check_kinds(basis, source)
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
    allowed = res + rtol * np.abs(pub) + abs_tol + slack
    agree = diff <= allowed
    tolerance = tolerance or f"{100 * rtol:g} %"
    if np.all(diff <= res + slack):
        verdict = REPRODUCED
        tolerance = PRINTED_DIGIT if np.any(res > 0) else EXACT
    elif np.all(agree):
        verdict = f"{WITHIN} ({tolerance})"
    else:
        if not cause:
            raise ValueError(f"{artefact} {quantity}: values diverge, a cause must be given")
        verdict = f"{DIVERGES}: {cause}"
    scale = float(np.abs(pub).max()) if pub.size else 0.0
    printed = res > 0
    res_ratio = float((diff[printed] / res[printed]).max()) if np.any(printed) else None
    return {
        "artefact": artefact,
        "quantity": quantity,
        "published": cat.summarise(pub),
        "ours": cat.summarise(our),
        "max_abs_diff": float(diff.max()),
        "max_rel_diff": float(rel.max()),
        "verdict": verdict,
        "category": cat.comparison_category(bool(np.all(agree)), basis, source),
        "basis": basis,
        "source": source,
        "cause": "" if np.all(agree) else cause,
        "tolerance": tolerance,
        "n_values": int(pub.size),
        "n_agree": int(agree.sum()),
        "difference": float(diff.max() / scale) if scale > 0 else None,
        "difference_text": cat.difference_text(float(diff.max()), scale, res_ratio),
        "tolerance_used": float((diff / allowed).max()),
    }


_NO_DIFFERENCE = {"max_abs_diff": None, "max_rel_diff": None, "difference": None}
#: what a check's row shows as its published value (its "ours" is evidence text, kept as written)
CHECK_PUBLISHED = "(check)"


def check_row(
    artefact: str, statement: str, evidence: str, holds: object, *, basis: str
) -> dict[str, Any]:
    """A row for a statement checked by a computed test that is no claim to judge: it holds by
    construction on our model, or it sets published values against each other.

    A claim the book judges — the thesis's or ours — is registered in
    :mod:`mechlib.reporting.claimlist` and recorded with
    :meth:`mechlib.reporting.records.Recorder.claim`, never through this row.

    Parameters
    ----------
    artefact, statement, evidence : str
        The artefact, the statement and what the test found (shown as written).
    holds : bool or array of bool
        Whether the statement holds; several parts must all hold.
    basis : {"construction", "thesis-inconsistency"}
        ``"construction"``: it holds by construction (holding is "consistent by construction";
        failing is "diverges": our computation is at fault). ``"thesis-inconsistency"``: published
        values are set against each other (holding is "consistent inside the thesis", failing an
        "inconsistency inside the thesis").

    Raises
    ------
    ValueError
        For any other ``basis``.
    """
    if basis not in (cat.BASIS_CONSTRUCTION, cat.BASIS_THESIS):
        raise ValueError(
            f"{artefact}: a check's basis is {cat.BASIS_CONSTRUCTION!r} or {cat.BASIS_THESIS!r}, "
            f"got {basis!r} (a claim to judge is registered in mechlib.reporting.claimlist and "
            "recorded with Recorder.claim)"
        )
    parts = np.atleast_1d(np.asarray(holds, dtype=bool))
    n_hold = int(parts.sum())
    if n_hold == parts.size:
        category = (
            cat.CAT_CONSTRUCTION if basis == cat.BASIS_CONSTRUCTION else cat.CAT_CONSISTENT_THESIS
        )
        cause = ""
    elif basis == cat.BASIS_CONSTRUCTION:
        category, cause = cat.CAT_DIVERGES, "fails although it holds by construction"
    else:
        category, cause = cat.CAT_INCONSISTENT, "published values contradict each other"
    return {
        "artefact": artefact,
        "quantity": statement,
        "published": CHECK_PUBLISHED,
        "ours": evidence,
        **_NO_DIFFERENCE,
        "verdict": f"{category}: {cause}" if cause else category,
        "category": category,
        "source": cat.SOURCE_THESIS,
        "basis": basis,
        "cause": cause,
        "n_values": int(parts.size),
        "n_agree": n_hold,
        "difference_text": "—",
    }


def computed_row(
    artefact: str, quantity: str, ours: object, labels: Sequence[str] | None = None
) -> dict[str, Any]:
    """A row for a number the thesis does not publish (ours only), its values named by
    ``labels`` when given (see :func:`mechlib.reporting.categories.summarise`)."""
    return {
        "artefact": artefact,
        "quantity": quantity,
        "published": "—",
        "ours": cat.summarise(np.asarray(ours, dtype=float), labels=labels),
        **_NO_DIFFERENCE,
        "verdict": COMPUTED,
        "category": cat.CAT_COMPUTED,
        "source": cat.SOURCE_OURS,
        "difference_text": "—",
    }


def not_reproduced_row(
    artefact: str, quantity: str, published: object, ours: object, *, tried: str
) -> dict[str, Any]:
    """A row for a published value that none of our computations reaches.

    Parameters
    ----------
    artefact, quantity : str
        As in :func:`compare_row`.
    published, ours : array_like
        The published values and ours in each setting tried (any shapes: they are not
        compared entry by entry).
    tried : str
        What was computed and how far it is (required): e.g. "linear FE: 1e-8 %; non-linear
        FE: up to 1e3 %".

    Raises
    ------
    ValueError
        If ``tried`` is empty.
    """
    if not tried.strip():
        raise ValueError(f"{artefact} {quantity}: say what was tried (tried=...), got {tried!r}")
    return {
        "artefact": artefact,
        "quantity": quantity,
        "published": cat.summarise(np.asarray(published, dtype=float)),
        "ours": cat.summarise(np.asarray(ours, dtype=float)),
        **_NO_DIFFERENCE,
        # not "diverges": no computation of ours is at fault, the published value is out of reach
        "verdict": f"{cat.CAT_NOT_REPRODUCED} in any setting — {tried}",
        "category": cat.CAT_NOT_REPRODUCED,
        "source": cat.SOURCE_THESIS,
        "cause": tried,
        "n_values": int(np.size(published)),
        "n_agree": 0,
        "difference_text": "—",
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
    basis: str = cat.BASIS_INDEPENDENT
    source: str = cat.SOURCE_THESIS

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
            basis=self.basis,
            source=self.source,
        )


@dataclass(frozen=True)
class Check:
    """A :func:`check_row` waiting for its test: the recorded value says whether it holds."""

    artefact: str
    statement: str
    evidence: str
    basis: str

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
            raise TypeError(f"{self.artefact}: a check holds or not, got {holds!r}")
        return check_row(self.artefact, self.statement, self.evidence, arr, basis=self.basis)


@dataclass(frozen=True)
class Computed:
    """A :func:`computed_row` waiting for our value; ``labels`` names its values."""

    artefact: str
    quantity: str
    labels: tuple[str, ...] | None = None

    def row(self, ours: object) -> dict[str, Any]:
        """The row for our value ``ours``."""
        return computed_row(self.artefact, self.quantity, ours, self.labels)


@dataclass(frozen=True)
class NotReproduced:
    """A :func:`not_reproduced_row` waiting for our value(s) in the settings tried."""

    artefact: str
    quantity: str
    published: object
    tried: str

    def row(self, ours: object) -> dict[str, Any]:
        """The row for our value(s) ``ours``."""
        return not_reproduced_row(
            self.artefact, self.quantity, self.published, ours, tried=self.tried
        )


#: A report row waiting for the recorded value it reports on.
RowSpec = Comparison | Check | Computed | NotReproduced
